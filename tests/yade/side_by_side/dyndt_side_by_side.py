"""O.dynDt and a negative O.dt hand the time step to the time stepper or take it back, as in
Yade 2023.02a; the same file runs in Yade (`yade -n -x`) and in Talus and prints one RESULT line
(tests/yade/test_dyndt.py)."""
import json

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403

O.bodies.append([sphere((0, 0, 0), 1, fixed=True), sphere((0, 0, 1.999), 1)])
stepper = GlobalStiffnessTimeStepper(timeStepUpdateInterval=5, timestepSafetyCoefficient=0.8)
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                             [Law2_ScGeom_FrictPhys_CundallStrack()]),
             stepper, NewtonIntegrator(gravity=(0, 0, -10), damping=0.9)]
trace = []


def note(what):
    trace.append([what, O.dt, O.dynDt, stepper.active, O.interactions.countReal()])


def attempt(what, action):
    try:
        action()
        trace.append([what, "ok", O.dynDt])
    except RuntimeError as e:
        trace.append([what, str(e)])


O.dt = 1e-6
note("start")
O.run(20, True)
note("the stepper acts")
O.dt = 1e-6
note("set by hand")
O.run(20, True)
note("overridden while active")
O.dt = 1e-6
O.dynDt = False
note("stepper off")
O.run(20, True)
note("kept")
O.dt = -1
note("negative dt")
O.run(20, True)
note("stepper on again")
O.engines = [ForceResetter(), NewtonIntegrator()]
attempt("off without a stepper", lambda: setattr(O, "dynDt", False))
attempt("on without a stepper", lambda: setattr(O, "dynDt", True))
attempt("negative dt without a stepper", lambda: setattr(O, "dt", -1))
print("RESULT " + json.dumps({"trace": trace}))
