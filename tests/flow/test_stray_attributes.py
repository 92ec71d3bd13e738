"""An attribute an engine does not have (Yade's flowScenario.py sets flow.minKdivmean, a misspelt
minKdivKmean): Talus refuses it naming the closest attribute; a Yade script under `talus run`
gets Yade 2023.02a's behaviour (the value kept as a plain attribute that nothing reads) with one
warning naming the attribute and the likely intended one. Constructor keywords are refused in
both, as Yade refuses them."""
import pytest

from talus.flow import FlowEngine, PeriodicFlowEngine, ThermalEngine

SCRIPT = """
flow = FlowEngine(label="flow")
flow.minKdivmean = 0.0001
flow.minKdivmean = 0.0002
thermal = ThermalEngine(label="thermal")
thermal.particleKK = 3
print("kept", flow.minKdivmean, thermal.particleKK, "default", flow.minKdivKmean, thermal.particleK)
for make in (lambda: FlowEngine(viscosityy=1), lambda: PeriodicFlowEngine(gradPP=(1, 0, 0)),
             lambda: ThermalEngine(particleKK=2)):
    try:
        make()
        print("constructor accepted")
    except AttributeError as e:
        print("constructor refused:", e)
"""


def test_talus_api_refuses_naming_the_closest():
    with pytest.raises(AttributeError, match=r"FlowEngine has no attribute 'minKdivmean' \(did you mean "
                                             r"'minKdivKmean'\?\)"):
        FlowEngine().minKdivmean = 1e-4
    with pytest.raises(AttributeError, match=r"ThermalEngine has no attribute 'particleKK' \(did you mean "
                                             r"'particleK'\?\)"):
        ThermalEngine().particleKK = 3
    with pytest.raises(AttributeError, match=r"FlowEngine has no attribute 'gradPP'"):
        PeriodicFlowEngine().gradPP = (1, 0, 0)


def test_yade_script_keeps_them_with_one_warning(talus_cmd, tmp_path):
    script = tmp_path / "stray.py"
    script.write_text(SCRIPT)
    done = talus_cmd("run", script, cwd=tmp_path)
    assert "kept 0.0002 3 default 0.0001 3.0" in done.stdout
    warnings = [line for line in done.stderr.splitlines() if "has no attribute" in line]
    assert len(warnings) == 2, done.stderr          # once per engine type and name
    assert "FlowEngine has no attribute 'minKdivmean' (did you mean 'minKdivKmean'?)" in warnings[0]
    assert "nothing reads" in warnings[0] and "ThermalEngine has no attribute 'particleKK'" in warnings[1]
    refused = [line for line in done.stdout.splitlines() if line.startswith("constructor")]
    assert refused == ["constructor refused: FlowEngine has no attribute 'viscosityy' (did you mean 'viscosity'?)",
                       "constructor refused: FlowEngine has no attribute 'gradPP'",
                       "constructor refused: ThermalEngine has no attribute 'particleKK' (did you mean "
                       "'particleK'?)"]
