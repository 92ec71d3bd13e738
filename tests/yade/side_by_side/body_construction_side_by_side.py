"""Bodies made the long way, as Yade scripts make them (``b = Body(); b.shape = Sphere(...);
b.state.pos = ...; b.state.mass = ...; b.mat = m; O.bodies.append(b)``), and Yade's shape and
interaction constructors, written so that the same file runs in Yade (`yade -n -x`) and in
Talus: prints what the objects read and the bodies' positions after a fall (one RESULT line;
tests/yade/test_body_construction.py)."""
import json

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403

out = {}
mat = FrictMat(density=2000, young=1e7, label="grains")
O.materials.append(mat)
b = Body()
out["blank"] = [b.id, b.mat is None, b.dynamic, b.state.mass, b.isClump, b.bounded]
s = Sphere(radius=0.5, color=(1, 0, 0))
b.shape = s
b.state.pos = (1, 2, 3)
b.state.vel = (0.5, 0, 0)
b.state.mass = 2.0
b.state.inertia = (0.2, 0.2, 0.2)
b.mat = mat
s.wire = True                      # the shape is shared with the body
box = Body(shape=Box(extents=(0.2, 0.3, 0.4)), material=mat)
box.state.pos = (4, 0, 0)
box.state.mass, box.state.inertia = 1.5, (0.1, 0.1, 0.1)
ids = O.bodies.append([b, box])
out["appended"] = [ids, b.id, box.id, b.shape.radius, list(b.shape.color), b.shape.wire,
                   list(O.bodies[ids[1]].shape.extents), O.bodies[ids[0]].mat.label, O.bodies[ids[0]].state.mass]
O.engines = [ForceResetter(), NewtonIntegrator(gravity=(0, 0, -10), damping=0)]
O.dt = 0.01
O.run(10, True)
out["positions"] = [[float(x) for x in O.bodies[i].state.pos] for i in ids]
shapes = [Sphere(), Shape(wire=True), Box(extents=(1, 2, 3)), Wall(axis=1, sense=-1),
          Facet(vertices=[(0, 0, 0), (1, 0, 0), (0, 1, 0)])]
out["shapes"] = [shapes[0].radius, list(shapes[0].color), shapes[0].wire, shapes[1].wire, list(shapes[2].extents),
                 [shapes[3].axis, shapes[3].sense], [list(v) for v in shapes[4].vertices], list(shapes[4].normal)]
try:
    Sphere(attributeThatDoesntExist=42)
    out["unknown"] = None
except AttributeError:
    out["unknown"] = "AttributeError"
i = Interaction()
out["interaction"] = [i.isReal, hasattr(i, "iterLastSeen")]
print("RESULT " + json.dumps(out))
