"""yade.plot's data handling, written so that the same file runs in Yade (`yade -n -x`) and in
Talus: addData keeping ints, splitting Vector3 and Matrix3 into component columns, padding with
NaN; addAutoData from plot.plots ("name=expression" entries, an expression that raises);
saveDataTxt's text. Prints one RESULT line (tests/yade/test_plot_yade.py)."""
import json
import os
import tempfile

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403
from yade import plot

plot.resetData()
plot.addData(a=1, b=2.5)
plot.addData(c=Vector3(5, 6, 7), d=Matrix3(8, 9, 10, 11, 12, 13, 14, 15, 16))
plot.addData({"a": 3}, b=True)
added = {k: [repr(v) for v in column] for k, column in plot.data.items()}

plot.resetData()
O.reset()
plot.plots = {"i=O.iter": ("O.time", None, "n=len(O.bodies)", "broken=1/0")}
plot.addAutoData()
O.bodies.append(sphere((0, 0, 0), 1))
O.dt = 0.5
O.engines = [ForceResetter(), NewtonIntegrator()]
O.step()
plot.addAutoData()
auto = {k: [repr(v) for v in column] for k, column in plot.data.items()}

path = os.path.join(tempfile.mkdtemp(), "data.txt")
plot.saveDataTxt(path, vars=("i", "n", "O.time"))
text = open(path).read()
print("RESULT " + json.dumps({"added": added, "auto": auto, "text": text}))
