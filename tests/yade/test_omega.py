"""The rest of Yade's Omega: O.labeledEngine, O.runEngine, O.dynDtAvailable, O.filename,
O.thisScene, and a clear error for Yade's Omega attributes Talus lacks. Expected values are what
Yade 2023.02a prints for the same script."""

SCRIPT = """
O.bodies.append(sphere((0, 0, 0), 1))
O.bodies[0].state.vel = (1, 0, 0)
O.dt = 0.1
n = NewtonIntegrator(damping=0, label='nw')
O.engines = [ForceResetter(), n]
O.runEngine(n)
print('RE', O.bodies[0].state.pos[0], O.iter, O.time, O.dynDtAvailable, O.labeledEngine('nw') is n, O.thisScene)
try:
    O.labeledEngine('zz')
except ValueError as e:
    print('ERR', e)
O.engines = O.engines + [GlobalStiffnessTimeStepper()]
print('DA', O.dynDtAvailable, O.filename)
O.save('saved.h5')
print('FN', O.filename)
try:
    O.miscParams = []
except AttributeError as e:
    print('MISSING', e)
"""


def test_omega_queries_follow_yade(talus_cmd, tmp_path):
    script = tmp_path / "omega.py"
    script.write_text(SCRIPT)
    out = talus_cmd("run", script, cwd=tmp_path).stdout
    assert "RE 0.1 0 0.0 False True 0" in out
    assert "ERR No engine labeled `zz'" in out
    assert "DA True None" in out and "FN saved.h5" in out
    assert "MISSING O.miscParams is an attribute of Yade 2023.02a's Omega that Talus does not implement" in out
