"""Yade's State.refPos and refOri, written so that the same file runs in Yade (`yade -n -x`)
and in Talus: what a sphere, a facet, a clump and its members get when made, that a run leaves
them, that they are settable and kept by saveTmp/loadTmp; and which state vectors are references
into the body. Prints one RESULT line (tests/yade/test_state_reference.py)."""
import json

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403


def ref(b):
    return [list(b.state.refPos), list(b.state.refOri)]     # minieigen's order: x, y, z, w


out = {}
b = sphere((1, 2, 3), 1)
out["spec"] = ref(b)
O.bodies.append(b)
b.state.vel = (1, 0, 0)
O.engines = [ForceResetter(), NewtonIntegrator()]
O.dt = 0.1
O.run(3, True)
out["after run"] = ref(b) + [list(b.state.pos)]
f = facet([(0, 0, 0), (1, 0, 0), (0, 1, 0)])
O.bodies.append(f)
out["facet"] = ref(f)
clump, members = O.bodies.appendClumped([sphere((0, 0, 10), 1), sphere((1, 0, 10), 1)])
out["clump"] = ref(O.bodies[clump]) + ref(O.bodies[members[1]])
b.state.refPos = b.state.pos
b.state.refOri = Quaternion((0, 0, 1), 0.5)
out["set"] = ref(b)
O.saveTmp()
b.state.refPos = (7, 7, 7)
O.loadTmp()
out["loaded"] = ref(O.bodies[0])
# Yade hands vel, angVel, inertia and refPos as references into the body, pos as a copy.
s = O.bodies[0].state
s.vel[0] = 5
angVel = s.angVel
angVel[1] = 3
s.inertia[2] = 0.25
s.refPos[1] = -1
s.pos[2] = 70
doubled = s.vel * 2
doubled[2] = 9          # a result of arithmetic is a value of its own
out["references"] = [list(s.vel), list(s.angVel), list(s.inertia), list(s.refPos), list(s.pos)]
print("RESULT " + json.dumps(out))
