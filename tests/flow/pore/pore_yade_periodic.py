# Yade side of the periodic pore-flow comparison (tests/flow/pore/test_pore_periodic.py,
# cases/pore/flow_permeability.py): run with
#   cd tests/flow/pore && yade -n -x pore_yade_periodic.py packing.txt out.json Lx Ly Lz gx gy gz threshold
# Reads a sphere list (x y z r per line), puts it in the periodic cell [0, L), runs Yade's
# PeriodicFlowEngine once (CHOLMOD, macroscopic gradient g, no boundary) and writes as JSON: the
# cell count, the average velocity (the permeability is -mu v.g/|g|^2), every cell's centre and
# pressure, and the fluid force on every sphere.
import json
import sys

def _number(a):
    try:
        float(a)
        return True
    except ValueError:
        return False


args = [a for a in sys.argv[1:] if not a.startswith("-") or _number(a)]  # keep negative numbers
packing, out = args[0], args[1]
L = [float(v) for v in args[2:5]]
g = [float(v) for v in args[5:8]]
threshold = float(args[8])
O.periodic = True
O.cell.hSize = Matrix3(L[0], 0, 0, 0, L[1], 0, 0, 0, L[2])
for line in open(packing):
    if line.strip() and not line.startswith("#"):
        x, y, z, r = map(float, line.split()[:4])
        O.bodies.append(sphere((x, y, z), r, fixed=True))
flow = PeriodicFlowEngine(useSolver=3, duplicateThreshold=threshold, gradP=Vector3(*g), permeabilityFactor=1.0,
                          viscosity=1.0)
O.engines = [flow]
O.dt = 1e-6
O.step()
n = flow.nCells()
res = {
    "nCells": n,
    "averageVelocity": list(flow.averageVelocity()),
    "centers": [list(flow.getCellCenter(i)) for i in range(n)],
    "pressures": [flow.getCellPressure(i) for i in range(n)],
    "fluidForce": [list(flow.fluidForce(b.id)) for b in O.bodies],
}
json.dump(res, open(out, "w"))
print("nCells", n, "averageVelocity", res["averageVelocity"])
