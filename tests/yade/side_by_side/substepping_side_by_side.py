"""Yade's sub-stepping, engines set during a step and a step interrupted by a PyRunner error,
written so that the same file runs in Yade (`yade -n -x`) and in Talus: prints a trace of
O.iter, O.subStep, the engine lists and a falling sphere's position (one RESULT line;
tests/yade/test_substepping.py)."""
import json

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403

trace = []


def note(what):
    trace.append([what, O.iter, O.subStep, len(O.engines), len(O._currEngines), len(O._nextEngines),
                  [float(x) for x in O.bodies[0].state.pos]])


O.bodies.append(sphere((0, 0, 0), 1))
O.dt = 0.1
O.engines = [ForceResetter(), PyRunner(command='note("runner")', iterPeriod=1), NewtonIntegrator(gravity=(0, 0, -10))]
note("start")
O.subStepping = True
for k in range(5):
    O.step()
    note("sub-step")
O.subStepping = False
O.step()
note("finished")
# engines set by a PyRunner take over at the next step
O.engines = [ForceResetter(), NewtonIntegrator(gravity=(0, 0, -10)),
             PyRunner(command='O.engines = [ForceResetter(), PyRunner(command=\'note("new")\', iterPeriod=1), '
                      'NewtonIntegrator(gravity=(0, 0, -10), damping=0.3)]; note("set")', iterPeriod=1)]
O.step()
note("after set")
O.step()
note("new engines")
# a PyRunner error: the run stops there; the next one finishes the step and goes on
O.engines = [ForceResetter(), PyRunner(command='note("before")', iterPeriod=1),
             PyRunner(command='missingFunction()', iterPeriod=2), NewtonIntegrator(gravity=(0, 0, -10))]
errors = []
for k in range(3):
    try:
        O.run(4, True)
    except RuntimeError as e:
        errors.append(str(e).splitlines()[0])
    note("after run")
print("RESULT " + json.dumps({"trace": trace, "errors": errors}))
