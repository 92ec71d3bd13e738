# Yade side of the transient pore-flow comparison (tests/flow/pore/test_pore.py): run with
#   cd tests/flow/pore && yade -n -x pore_yade_transient.py packing.txt out.json bulkModulus [bulkModulus ...]
# The 400 spheres of packing.txt in the walls of their bounding box (boundaryUseMaxMin), each
# moving at a constant velocity towards the box centre (blockedDOFs keep it: x1 = x0 + v dt),
# pressure 1 at ymin, 0 at ymax. Step 1 meshes and solves at x0; step 2 moves the spheres to x1,
# updates the pore volumes (the volume-change source) and solves again, compressible when
# bulkModulus > 0; once per bulk modulus given. Writes, keyed by the modulus as given, each
# cell's vertex ids and its pressure after steps 1 and 2, and the positions step 2 sees.
import json
import sys

args = [a for a in sys.argv[1:] if not a.startswith("-")]
packing, out = args[0], args[1]
DT, RATE = 1e-3, 0.5   # homothetic strain rate towards the centre: 5e-4 of the size per step
spheres = [tuple(map(float, l.split())) for l in open(packing) if l.strip() and not l.startswith("#")]
lo = [min(s[k] - s[3] for s in spheres) for k in range(3)]
hi = [max(s[k] + s[3] for s in spheres) for k in range(3)]
centre = Vector3(*[(a + b) / 2 for a, b in zip(lo, hi)])
everything = {}
for name in args[2:]:
    bulk = float(name)
    O.reset()
    O.bodies.append(aabbWalls([Vector3(*lo), Vector3(*hi)], thickness=0))
    for x, y, z, r in spheres:
        b = sphere((x, y, z), r)
        b.state.blockedDOFs = "xyzXYZ"
        b.state.vel = -RATE * (Vector3(x, y, z) - centre)
        O.bodies.append(b)
    flow = FlowEngine(useSolver=3, permeabilityFactor=1.0, viscosity=1.0, fluidBulkModulus=bulk)
    flow.bndCondIsPressure = [0, 0, 1, 1, 0, 0]
    flow.bndCondValue = [0, 0, 1, 0, 0, 0]
    flow.boundaryUseMaxMin = [1, 1, 1, 1, 1, 1]
    flow.meshUpdateInterval = 1000000
    O.engines = [ForceResetter(), flow, NewtonIntegrator(damping=0, gravity=(0, 0, 0))]
    O.dt = DT
    res = {}
    for step in (1, 2):
        O.step()
        res[f"step{step}"] = [{"vertices": [int(v) for v in flow.getVertices(i)], "pressure": flow.getCellPressure(i)}
                              for i in range(flow.nCells())]
        if step == 1:   # the positions step 2's flow sees (moved by step 1's NewtonIntegrator)
            res["positions"] = [list(O.bodies[i].state.pos) for i in range(6, len(O.bodies))]
    everything[name] = res
json.dump(everything, open(out, "w"))
