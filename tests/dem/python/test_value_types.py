"""Yade's value types (talus.dem.base.linalg) against real minieigen: every expression below is
evaluated by Yade 2023 (``yade -n -x``, in a subprocess) and by Talus, and the results compared;
then what Talus does on purpose otherwise (numpy's meaning where minieigen has none), what
minieigen cannot be asked (its pruned, svd and polarDecomposition crash or are wrong in Yade
2023), and that the accessors hand out these types."""

import json
import math
import os
import shutil
import subprocess
import textwrap

import numpy as np
import pytest

from talus.dem import (Matrix3, Matrix6, NewtonIntegrator, Quaternion, Scene, Vector2, Vector2i, Vector3,
                       Vector3i, Vector6, Vector6i, bodyStressTensors, box, facet, fabricTensor, getStress,
                       getStressAndTangent, sphere)
from talus.dem.step.kinematic import RotationEngine

# The same names on both sides; helpers for what an expression cannot say (in-place operators).
SETUP = textwrap.dedent("""
    v = Vector3(1, 2, 3); w = Vector3(4, -5, 6); u = Vector3(0.3, -1.7, 2.2)
    m = Matrix3(1, 2, 3, 4, 5, 6, 7, 8, 10); s = Matrix3(4, 1, 0.5, 1, 3, -1, 0.5, -1, 2)
    q = Quaternion(Vector3(1, 2, 3), 0.7); p = Quaternion(Vector3(-1, 0.5, 2), 2.1)
    vi = Vector3i(1, 2, 3); wi = Vector3i(-2, 0, 5)
    v2 = Vector2(1.5, -2); v6 = Vector6(1, -2, 3, 0.5, 5, 6); m6 = Matrix6(m, s, s * 2, m + s)

    def iop(a, op, b):
        x = type(a)(a)
        if op == "+": x += b
        elif op == "-": x -= b
        elif op == "*": x *= b
        elif op == "/": x /= b
        return x

    def normalize(a):
        x = type(a)(a)
        x.normalize()
        return x

    def setitem(a, i, value):
        x = type(a)(a)
        x[i] = value
        return x

    VALUE_TYPES = ("Vector2", "Vector2i", "Vector3", "Vector3i", "Vector6", "Vector6i", "Matrix3", "Matrix6",
                   "Quaternion")

    def plain(x):
        # JSON of a result: value types by name and components (a matrix by rows), numbers as
        # floats, bools as bools.
        name = type(x).__name__
        if name in ("bool", "bool_"):
            return {"bool": bool(x)}
        if name in VALUE_TYPES:
            return {"type": name, "value": [plain(x[i]) for i in range(len(x))]}
        if isinstance(x, (tuple, list)):
            return [plain(i) for i in x]
        if isinstance(x, str):
            return x
        return float(x)

    def evaluate(expressions):
        out = []
        for e in expressions:
            try:
                out.append(plain(eval(e)))
            except Exception as error:
                out.append({"error": type(error).__name__ + ": " + str(error).splitlines()[0]})
        return out
""")

EXPRESSIONS = [
    # constructors and class attributes
    "Vector3()", "Vector3i()", "Vector3((1, 2, 3))", "Vector3([1, 2, 3])", "Vector2(1, 2)", "Vector2i(1, 2)",
    "Vector6(1, 2, 3, 4, 5, 6)", "Vector6(v, w)", "Vector6((1, 2, 3, 4, 5, 6))", "Vector6i(1, 2, 3, 4, 5, 6)",
    "Matrix3(1, 2, 3, 4, 5, 6, 7, 8, 9)", "Matrix3((1, 2, 3), (4, 5, 6), (7, 8, 9))", "Matrix3(v, w, u)",
    "Matrix3([[1, 2, 3], [4, 5, 6], [7, 8, 9]])", "Matrix3(q)", "Matrix3(v)", "Matrix3(m)", "Matrix6(m, s, s, m)",
    "Matrix6(*[Vector6(i, 1, 2, 3, 4, 5) for i in range(6)])",
    "Vector3.Zero", "Vector3.Ones", "Vector3.UnitX", "Vector3.UnitY", "Vector3.UnitZ", "Vector3.Unit(1)",
    "Vector3.Identity", "Vector3i.UnitZ", "Vector2.UnitY", "Vector2i.UnitX", "Vector6.Unit(4)", "Vector6i.Ones",
    "Vector6.Identity", "Matrix3.Identity", "Matrix3.Zero", "Matrix3.Ones", "Matrix6.Identity", "Matrix6.Zero",
    "Matrix6.Ones",
    # vector methods
    "v.norm()", "v.squaredNorm()", "v.normalized()", "normalize(v)", "v.dot(w)", "v.cross(w)", "v.outer(w)",
    "v.asDiagonal()", "w.maxCoeff()", "w.minCoeff()", "w.maxAbsCoeff()", "w.sum()", "w.prod()", "w.mean()",
    "v.rows()", "v.cols()", "v.xy()", "v.xz()", "v.yx()", "v.yz()", "v.zx()", "v.zy()", "vi.xy()", "v2.norm()",
    "v2.normalized()", "v2.dot(Vector2(3, 4))", "v6.norm()", "v6.head()", "v6.tail()", "v6.outer(v6)",
    "v6.asDiagonal()", "v6.dot(v6)", "vi.dot(wi)", "vi.cross(wi)", "vi.sum()", "vi.prod()", "vi.maxCoeff()",
    "wi.minCoeff()", "wi.maxAbsCoeff()",
    "v.isApprox(v * (1 + 1e-14))", "v.isApprox(v * (1 + 1e-3))", "v.isApprox(v * (1 + 1e-3), 1e-2)",
    # matrix methods
    "m.trace()", "m.inverse()", "m.transpose()", "m.determinant()", "m.diagonal()", "m.row(1)", "m.col(2)",
    "m.rows()", "m.cols()", "m.norm()", "m.squaredNorm()", "m.normalized()", "normalize(m)", "m.maxCoeff()",
    "m.minCoeff()", "(-m).maxAbsCoeff()", "m.sum()", "m.prod()", "m.mean()", "m.isApprox(m)",
    "m.isApprox(m * (1 + 1e-3))", "s.spectralDecomposition()[1]", "s.selfAdjointEigenDecomposition()[1]",
    # eigenvectors are defined up to their sign: compare a sign-free projection of each
    "[abs(s.spectralDecomposition()[0].col(i).dot(u)) for i in range(3)]",
    "m6.trace()", "m6.determinant()", "m6.inverse()", "m6.transpose()", "m6.diagonal()", "m6.row(4)",
    "m6.col(5)", "m6.ul()", "m6.ur()", "m6.ll()", "m6.lr()", "m6.norm()", "m6.rows()",
    # arithmetic
    "v + w", "v - w", "-v", "v * 2", "2 * v", "v / 2", "v * 0.5", "v + vi", "vi + wi", "vi - wi", "vi * 2",
    "2 * vi", "-vi", "v2 + v2", "v6 + v6", "v6 * 3", "m * v", "v * m", "m * m", "m * s", "m * 2", "2 * m", "m / 2",
    "m + s", "m - s", "-m", "m6 * v6", "v6 * m6", "m6 * m6", "m6 * 2", "abs(v)", "abs(m)", "abs(q)", "abs(v6)",
    "m * (1, 2, 3)", "v + (1, 1, 1)", "v - [1, 1, 1]",
    "iop(v, '+', w)", "iop(v, '-', w)", "iop(v, '*', 2)", "iop(v, '/', 2)", "iop(m, '*', s)", "iop(m, '*', 2)",
    "iop(m, '+', s)", "iop(vi, '+', wi)", "iop(vi, '*', 3)", "iop(q, '*', p)",
    # indexing and sequences
    "v[0]", "v[2]", "m[1]", "m[1][2]", "m[0, 1]", "m[2, 0]", "len(v)", "len(m)", "len(q)", "len(v6)", "len(m6)",
    "list(v)", "list(m)", "m6[3]", "setitem(v, 1, 7)", "setitem(m, (1, 2), 7)", "setitem(vi, 0, 9)",
    # equality
    "v == Vector3(1, 2, 3)", "v == vi", "v == w", "v != w", "v != Vector3(1, 2, 3)", "v == (1, 2, 3)",
    "v == [1, 2, 3]", "v == (1, 2)", "v == m", "m == Matrix3(m)", "m == s", "m != s", "vi == Vector3i(1, 2, 3)",
    "v6 == Vector6(v6)", "m6 == Matrix6(m6)", "q == Quaternion(q)", "q == p", "q != p",
    # quaternions
    "Quaternion(1, 2, 3, 4)", "Quaternion(v, 0.7)", "Quaternion(0.7, v)", "Quaternion((1, 2, 3), 0.7)",
    "Quaternion(q.toRotationMatrix())", "Quaternion(Matrix3(-1, 0, 0, 0, -1, 0, 0, 0, 1))",
    "Quaternion(Matrix3(1, 0, 0, 0, -1, 0, 0, 0, -1))", "Quaternion(Matrix3(-1, 0, 0, 0, 1, 0, 0, 0, -1))",
    "Quaternion(Matrix3(0, -1, 0, 0, 0, -1, 1, 0, 0))",
    "Quaternion(Vector3(1, 0, 0), Vector3(0, 1, 0))", "Quaternion(v, w)", "Quaternion(q)", "Quaternion.Identity",
    "Quaternion(Vector3(1, 0, 0), Vector3(-1, 0, 0)) * Vector3(1, 0, 0)",
    "q[0]", "q[1]", "q[2]", "q[3]", "list(q)", "Quaternion(1, 2, 3, 4)[3]", "Quaternion(1, 2, 3, 4)[0]",
    "setitem(q, 3, 0.5)", "setitem(q, 0, 0.5)",
    "q * v", "q * (1, 0, 0)", "q * p", "p * q", "q * q.conjugate()", "q.Rotate(v)",
    "q.toAxisAngle()", "q.toAngleAxis()", "Quaternion(-q[3], -q[0], -q[1], -q[2]).toAxisAngle()",
    "Quaternion.Identity.toAxisAngle()", "q.toRotationMatrix()", "q.toRotationVector()", "q.conjugate()",
    "q.inverse()", "Quaternion(1, 2, 3, 4).inverse()", "Quaternion(1, 2, 3, 4).norm()",
    "Quaternion(1, 2, 3, 4).normalized()", "normalize(Quaternion(1, 2, 3, 4))", "q.norm()",
    "q.angularDistance(p)", "q.angularDistance(q)", "q.slerp(0.3, p)", "q.slerp(0.3, Quaternion(-p[3], -p[0], -p[1], -p[2]))",
    "q.slerp(0.5, q)",
    # printing (exact values: Yade 2023 prints 19 digits where minieigen and Talus print the shortest)
    "repr(Vector3(1, 2, 3))", "str(Vector3(1, 2, 3))", "repr(Vector3i(1, 2, 3))", "repr(Vector2(1, -2))",
    "repr(Vector2i(1, -2))", "repr(Vector6(1, 2, 3, 4, 5, 6))", "repr(Vector6i(1, 2, 3, 4, 5, 6))",
    "repr(Matrix3(0.5, 0, 0, 0, 1, 0, 0, 0, -2))", "str(Matrix3.Zero)", "repr(Matrix6.Identity)",
    "repr(Quaternion.Identity)", "repr(Vector3(float('nan'), float('inf'), -0.0))", "repr(Vector3(1.5, -0.25, 1e+20))",
]

# What the accessors hand out in Yade, to compare with Talus's (Talus has no refPos).
YADE_ACCESSORS = textwrap.dedent("""
    O.periodic = True
    O.cell.setBox(2, 2, 2)
    b = O.bodies[O.bodies.append(utils.sphere((1, 1, 1), 0.3))]
    accessors = {name: type(value).__name__ for name, value in [
        ("pos", b.state.pos), ("vel", b.state.vel), ("angVel", b.state.angVel), ("angMom", b.state.angMom),
        ("inertia", b.state.inertia), ("ori", b.state.ori), ("hSize", O.cell.hSize), ("velGrad", O.cell.velGrad),
        ("trsf", O.cell.trsf), ("size", O.cell.size), ("wrap", O.cell.wrap((3, 1, 1))),
        ("getStress", utils.getStress()), ("getStressAndTangent", utils.getStressAndTangent()[0]),
        ("tangent", utils.getStressAndTangent()[1]), ("bodyStressTensors", utils.bodyStressTensors()[0]),
        ("gravity", NewtonIntegrator(gravity=(0, 0, -9.81)).gravity),
        ("rotationAxis", RotationEngine(rotationAxis=(0, 0, 1)).rotationAxis)]}
""")



def _public_type(value) -> str:
    """The class a script sees: vel, angVel, inertia are a private Vector3 that writes through to
    the body (Yade's references), their public class Vector3."""
    return next(c.__name__ for c in type(value).__mro__ if not c.__name__.startswith("_"))

def _yade_reference(tmp_path_factory):
    if shutil.which("yade") is None:
        pytest.skip("yade is not installed (./setup.sh installs it): minieigen's reference values come from it")
    folder = tmp_path_factory.mktemp("minieigen")
    script, out = folder / "reference.py", folder / "reference.json"
    script.write_text("from yade.minieigenHP import *\n" + SETUP + YADE_ACCESSORS + textwrap.dedent(f"""
        import json
        with open({str(out)!r}, "w") as f:
            json.dump({{"results": evaluate({EXPRESSIONS!r}), "accessors": accessors}}, f)
        import os
        os._exit(0)
    """))
    done = subprocess.run(["yade", "-n", "-x", str(script)], capture_output=True, text=True, timeout=300,
                          cwd=folder, env={**os.environ, "OMP_NUM_THREADS": "1"})
    if not out.exists():
        raise AssertionError(f"yade did not write the reference values (exit {done.returncode}):\n"
                             f"{done.stdout[-3000:]}\n{done.stderr[-3000:]}")
    return json.loads(out.read_text())


@pytest.fixture(scope="module")
def yade_reference(tmp_path_factory):
    return _yade_reference(tmp_path_factory)


def _talus_results():
    names = dict(Vector2=Vector2, Vector2i=Vector2i, Vector3=Vector3, Vector3i=Vector3i, Vector6=Vector6,
                 Vector6i=Vector6i, Matrix3=Matrix3, Matrix6=Matrix6, Quaternion=Quaternion)
    exec(SETUP, names)
    return names["evaluate"](EXPRESSIONS)


def _same(a, b, tol=1e-12) -> bool:
    if isinstance(a, float) and isinstance(b, float):
        return a == b or (math.isnan(a) and math.isnan(b)) or abs(a - b) <= tol * max(1.0, abs(a), abs(b))
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(_same(x, y, tol) for x, y in zip(a, b))
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k], tol) for k in a)
    return a == b


def test_methods_and_operators_give_minieigens_results(yade_reference):
    talus = _talus_results()
    wrong = [f"{e}:\n    yade  {y}\n    talus {t}" for e, y, t in zip(EXPRESSIONS, yade_reference["results"], talus)
             if not _same(y, t)]
    assert not wrong, f"{len(wrong)} of {len(EXPRESSIONS)} differ from minieigen:\n" + "\n".join(wrong)


def test_every_expression_is_answered_by_minieigen(yade_reference):
    # The comparison above is only worth something if minieigen answered (no error on both sides).
    errors = [e for e, y in zip(EXPRESSIONS, yade_reference["results"]) if isinstance(y, dict) and "error" in y]
    assert not errors, f"minieigen refused: {errors}"


def test_accessors_return_the_types_yade_returns(yade_reference):
    S = Scene()
    S.periodic = True
    S.cell.setBox(2, 2, 2)
    b = S.bodies[S.bodies.append(sphere((1, 1, 1), 0.3))]
    talus = {name: _public_type(value) for name, value in [
        ("pos", b.state.pos), ("vel", b.state.vel), ("angVel", b.state.angVel), ("angMom", b.state.angMom),
        ("inertia", b.state.inertia), ("ori", b.state.ori), ("hSize", S.cell.hSize), ("velGrad", S.cell.velGrad),
        ("trsf", S.cell.trsf), ("size", S.cell.size), ("wrap", S.cell.wrap((3, 1, 1))),
        ("getStress", getStress(scene=S)), ("getStressAndTangent", getStressAndTangent(scene=S)[0]),
        ("tangent", getStressAndTangent(scene=S)[1]), ("bodyStressTensors", bodyStressTensors(scene=S)[0]),
        ("gravity", NewtonIntegrator(gravity=(0, 0, -9.81)).gravity),
        ("rotationAxis", RotationEngine(rotationAxis=(0, 0, 1)).rotationAxis)]}
    assert talus == yade_reference["accessors"]


# -- Talus's own choices, where minieigen has no answer or numpy's is kept ------------------------

def test_numpy_meaning_where_minieigen_has_none():
    v, w = Vector3(1, 2, 3), Vector3(4, -5, 6)
    assert v * w == Vector3(4, -10, 18)                    # minieigen: TypeError
    assert v + 1 == Vector3(2, 3, 4)                       # minieigen: TypeError
    assert v[-1] == 3.0                                    # minieigen: IndexError
    assert Vector3i(1, 2, 3) / 2 == Vector3(0.5, 1, 1.5)   # minieigen: TypeError; the float type
    assert Matrix3() == Matrix3.Zero and Vector6() == Vector6.Zero   # minieigen: uninitialised
    assert Quaternion() == Quaternion.Identity
    np.testing.assert_array_equal(v == 2, [False, True, False])      # element-wise against a number
    np.testing.assert_array_equal(v == np.array([1, 0, 3]), [True, False, True])   # and a numpy array, as minieigen
    assert np.abs(-v) == v and (-v).abs() == v and abs(-v) == pytest.approx(math.sqrt(14))
    assert v @ w == 12 and np.dot(v, w) == 12


def test_results_of_another_shape_are_plain_numpy():
    v, m = Vector3(1, 2, 3), Matrix3(1, 2, 3, 4, 5, 6, 7, 8, 10)
    for result in [v[0:2], v[:, None], v.reshape(3, 1), np.outer(v, v), np.stack([v, v]), np.concatenate([v, v]),
                   m.sum(axis=0), m.reshape(9), m.ravel(), m[:, 0:2], np.ones((4, 3)) + v, v > 1, np.isnan(v),
                   m @ v]:
        assert type(result) is np.ndarray, repr(result)
    assert type(v.sum()) is np.float64 and type(m[1, 2]) is np.float64
    assert type(m[0]) is Vector3 and type(m.T) is Matrix3 and type(v + v) is Vector3
    assert type(v.astype(np.int64)) is Vector3i and type(v.astype(bool)) is np.ndarray
    row = m[0]
    row[0] = 9      # a row is a view, as numpy's
    assert m[0, 0] == 9


def test_constants_are_fresh_copies():
    z = Vector3.Zero
    z += 1
    i = Quaternion.Identity
    i.normalize()
    i[0] = 5
    assert Vector3.Zero == Vector3(0, 0, 0) and Quaternion.Identity == Quaternion(1, 0, 0, 0)


def test_constructors_refuse_what_they_cannot_read():
    for make in [lambda: Vector3(1, 2), lambda: Matrix3(1, 2, 3), lambda: Vector3i(1.5, 2, 3),
                 lambda: Vector3("abc"), lambda: Quaternion((1, 0, 0, 0)), lambda: Matrix6(1, 2)]:
        with pytest.raises(TypeError):
            make()
    with pytest.raises(ValueError, match="axis must be non-zero"):
        Quaternion((0, 0, 0), 1.0)
    with pytest.raises(IndexError):
        Vector3.Unit(3)


def test_pruned_svd_and_polar_decomposition():
    # Not compared with Yade 2023's minieigen: its Matrix3.pruned zeroes everything, its
    # Vector3.pruned, svd and polarDecomposition abort on an Eigen assertion.
    assert Matrix3(1, 1e-7, -1e-7, 0, -0.0, 2e-6, 1, 1, 1).pruned() == Matrix3(1, 0, 0, 0, 0, 2e-6, 1, 1, 1)
    assert Vector3(1, 1e-5, 3).pruned(1e-4) == Vector3(1, 0, 3)
    m = Matrix3(1, 2, 3, 4, 5, 6, 7, 8, 10)
    U, S, V = m.svd()
    assert (U * S * V.transpose()).isApprox(m) and S == S.diagonal().asDiagonal() and S[0, 0] >= S[1, 1] >= S[2, 2]
    R, P = m.polarDecomposition()
    assert (R * P).isApprox(m) and (R * R.transpose()).isApprox(Matrix3.Identity) and P == P.transpose()
    assert np.all(np.linalg.eigvalsh(P) >= 0)


def test_random_stays_in_eigens_range():
    r = Vector6.Random()
    assert type(r) is Vector6 and np.all(np.abs(r) <= 1) and Matrix3.Random().shape == (3, 3)


def test_pickle_and_copy_keep_the_types():
    import copy
    import pickle
    for value in [Vector3(1, 2, 3), Vector3i(1, 2, 3), Matrix3.Identity, Matrix6.Ones, Quaternion((1, 2, 3), 0.4)]:
        for again in [pickle.loads(pickle.dumps(value)), copy.deepcopy(value)]:
            assert type(again) is type(value) and again == value


# -- the accessors ------------------------------------------------------------------------------

def test_body_state_accessors_hand_out_value_types():
    S = Scene()
    q = Quaternion((0, 0, 1), 0.5)
    s = S.bodies.append(sphere((0, 0, 1), 0.1))
    bx = S.bodies.append(box((1, 0, 0), (0.1, 0.2, 0.3), orientation=q))
    f = S.bodies.append(facet([(0, 0, 0), (1, 0, 0), (0, 1, 0)]))
    state = S.bodies[bx].state
    for value in [state.pos, state.vel, state.angVel, state.angMom, state.inertia]:
        assert _public_type(value) == "Vector3"
    # the orientation given is the orientation read, its (w, x, y, z) the core's
    assert type(state.ori) is Quaternion and state.ori.angularDistance(q) == pytest.approx(0, abs=1e-15)
    assert (state.ori.w, state.ori.x, state.ori.y, state.ori.z) == pytest.approx(S._cpp.ori(bx))
    assert list(state.ori) == pytest.approx([q.x, q.y, q.z, q.w])
    assert type(S.bodies[bx].shape.extents) is Vector3 and S.bodies[bx].shape.extents == Vector3(0.1, 0.2, 0.3)
    assert all(type(v) is Vector3 for v in S.bodies[f].shape.vertices) and type(S.bodies[f].shape.normal) is Vector3
    # setting takes the value types (and anything of 3 numbers), reading gives a copy
    S.bodies[s].state.pos = Vector3(1, 2, 3)
    S.bodies[s].state.vel = (0, 0, -1)
    S.bodies[s].state.angVel = Vector3.UnitZ
    pos = S.bodies[s].state.pos
    pos[0] = 99
    assert S.bodies[s].state.pos == Vector3(1, 2, 3) and S.bodies[s].state.vel == Vector3(0, 0, -1)
    assert S.bodies[s].state.angVel == Vector3(0, 0, 1)
    # the bulk views stay plain numpy arrays
    assert type(S.positions()) is np.ndarray and type(S.positions()[s]) is np.ndarray


def test_cell_and_measures_hand_out_value_types():
    S = Scene()
    S.periodic = True
    S.cell.setBox(2, 3, 4)
    S.bodies.append([sphere((0.5, 0.5, 0.5), 0.3), sphere((1, 0.5, 0.5), 0.3)])
    assert S.cell.hSize == Matrix3(2, 0, 0, 0, 3, 0, 0, 0, 4) and type(S.cell.hSize) is Matrix3
    assert S.cell.size == Vector3(2, 3, 4) and type(S.cell.size) is Vector3
    assert type(S.cell.velGrad) is Matrix3 and type(S.cell.trsf) is Matrix3
    assert S.cell.wrap((2.5, 0, 0)) == pytest.approx([0.5, 0, 0]) and type(S.cell.wrap((2.5, 0, 0))) is Vector3
    S.cell.velGrad = Matrix3(0, 0.1, 0, 0, 0, 0, 0, 0, 0)
    assert S.cell.velGrad[0, 1] == 0.1
    S.cell.hSize = Matrix3.Identity * 3
    assert S.cell.size == Vector3(3, 3, 3)
    stress, tangent = getStressAndTangent(scene=S)
    assert type(getStress(scene=S)) is Matrix3 and type(stress) is Matrix3 and type(tangent) is Matrix6
    assert type(fabricTensor(scene=S)) is Matrix3 and all(type(t) is Matrix3 for t in bodyStressTensors(scene=S))


def test_engine_vectors_are_vector3():
    newton = NewtonIntegrator(gravity=(0, 0, -9.81))
    assert type(newton.gravity) is Vector3 and newton.gravity == (0, 0, -9.81)
    newton.gravity = Vector3(0, -1, 0)
    assert newton.gravity == Vector3(0, -1, 0)
    engine = RotationEngine(rotationAxis=(0, 0, 1), zeroPoint=(1, 2, 3))
    assert type(engine.rotationAxis) is Vector3 and engine.zeroPoint == Vector3(1, 2, 3)


def test_norms_are_numpys_sums_bit_for_bit():
    """norm() and squaredNorm() add the squares in numpy's order (a quick path below eight
    components): the same bits as numpy's sum, for every size."""
    rng = np.random.default_rng(4)
    for cls, size in ((Vector2, 2), (Vector3, 3), (Vector6, 6), (Matrix3, 9)):
        for _ in range(2000):
            values = rng.standard_normal(size) * 10.0 ** rng.uniform(-8, 8, size)
            v = cls(*values)
            assert v.squaredNorm() == float(np.sum(values ** 2)), cls.__name__
            assert v.norm() == float(np.sqrt(np.sum(values ** 2))), cls.__name__
    assert Vector3(3, 4, 0).norm() == 5.0 and type(Vector3(1, 2, 3).norm()) is float
