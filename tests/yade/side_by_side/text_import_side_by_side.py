"""ymport.textExt and ymport.text, written so that the same file runs in Yade (`yade -n -x`) and
in Talus: one file in each format (a '#format' line overriding the format argument, comment
lines, extra columns), read with scale, shift and sphere keywords. Prints one RESULT line
(tests/yade/test_text_import.py)."""
import json
import os
import tempfile

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403
from yade import ymport

folder = tempfile.mkdtemp()
O.materials.append(FrictMat(young=1e6, label="soft"))
O.materials.append(FrictMat(young=1e7, label="hard"))
files = {
    # format given by the argument only; a column after the radius is ignored
    "plain": "# a comment\n0.1 0.2 0.3 0.05\n1.5\t-2.5\t3e-1\t2.5e-1 7\n",
    "matId": "#format x_y_z_r_matId\n#x y z r m\n0 0 0 1 1\n2 0 0 0.5 0\n",
    "idMatId": "#format id_x_y_z_r_matId\n5 1 2 3 0.4 1\n9 4 5 6 0.6 0\n",
    "attrs": "#format x_y_z_r_attrs\n# x y z r t v\n1 1 1 0.1 300.5 abc\n2 2 2 0.2 301 def\n",
}
calls = {
    "plain": lambda path, attrs: ymport.textExt(path, "x_y_z_r", shift=Vector3(1, -1, 0.5), scale=2.0,
                                                material="hard", color=(0.1, 0.1, 0.9)),
    "matId": lambda path, attrs: ymport.textExt(path, scale=0.5),
    "idMatId": lambda path, attrs: ymport.textExt(path, "x_y_z_r"),
    "attrs": lambda path, attrs: ymport.textExt(path, attrs=attrs, fixed=True),
}
result = {}
for name, content in files.items():
    path = os.path.join(folder, name + ".spheres")
    with open(path, "w") as f:
        f.write(content)
    attrs = []
    ids = O.bodies.append(calls[name](path, attrs))
    result[name] = {
        "pos": [list(O.bodies[i].state.pos) for i in ids],
        "radius": [O.bodies[i].shape.radius for i in ids],
        "material": [O.bodies[i].material.label for i in ids],
        "dynamic": [O.bodies[i].dynamic for i in ids],
        "attrs": attrs,
    }
path = os.path.join(folder, "text.spheres")
with open(path, "w") as f:
    f.write("0 1 2 0.3\n")
ids = O.bodies.append(ymport.text(path, shift=Vector3(1, 1, 1), scale=3))
result["text"] = {"pos": [list(O.bodies[i].state.pos) for i in ids], "radius": [O.bodies[i].shape.radius for i in ids]}
print("RESULT " + json.dumps(result))
