"""O.bodies[i] and b.state's vectors as scripts read them body by body (Yade 2023.02a's behaviour):
one Body per body (``O.bodies[i] is O.bodies[i]``, as Yade's), None once erased, ids counted from
the end when negative; ``id`` and ``state`` not replaceable; ``pos`` a copy of the body's row,
``vel`` and ``angVel`` references into the body; the values the core's arrays hold, bit for bit."""
import numpy as np
import pytest

from talus.dem import NewtonIntegrator, Scene, sphere
from talus.dem.base.linalg import Vector3


def two_spheres():
    S = Scene()
    S.bodies.append([sphere((0.1, 0.2, 0.3), 1), sphere((3, 0, 0), 1)])
    return S


def test_one_body_per_id_none_once_erased():
    S = two_spheres()
    b = S.bodies[1]
    assert S.bodies[1] is b and S.bodies[-1] is b and S.bodies[np.int64(1)] is b
    assert [x.id for x in S.bodies] == [0, 1] and list(S.bodies)[1] is b
    S.bodies.erase(1)
    assert S.bodies[1] is None and [x.id for x in S.bodies] == [0]


def test_bad_ids_are_refused_by_name():
    S = two_spheres()
    with pytest.raises(IndexError, match="no body with id 2 .ids run from 0 to 1"):
        S.bodies[2]
    with pytest.raises(IndexError, match="no body with id -3"):
        S.bodies[-3]
    with pytest.raises(TypeError, match="body ids are integers, got 1.0"):
        S.bodies[1.0]


def test_id_and_state_cannot_be_replaced():
    S = two_spheres()
    b = S.bodies[0]
    with pytest.raises(AttributeError, match="Body.id cannot be set"):
        b.id = 1
    with pytest.raises(AttributeError, match="Body.state cannot be replaced"):
        b.state = S.bodies[1].state
    assert S.bodies[0].id == 0 and S.bodies[0].state is b.state
    b.dynamic = False                   # the other attributes are still set as before
    assert not S.bodies[0].dynamic


def test_vectors_are_the_rows_pos_a_copy_vel_a_reference():
    S = two_spheres()
    S.engines = [NewtonIntegrator(gravity=(0, 0, -9.81))]
    S.dt = 1e-3
    S.bodies[0].state.angVel = (0.5, 0, 0)
    S.run(7, True)
    state = S.bodies[0].state
    for name, rows in (("pos", S._cpp.pos()), ("vel", S._cpp.vel()), ("angVel", S._cpp.angVel())):
        value = getattr(state, name)
        assert isinstance(value, Vector3) and value.shape == (3,), name
        assert value.tobytes() == np.array(rows[0]).tobytes(), name
    assert type(state.pos) is Vector3 and isinstance(state.pos[2], float)
    pos = state.pos
    pos[0] = 9                          # a copy: the body stays
    assert S._cpp.pos()[0][0] != 9
    vel = state.vel
    vel[0] = 9                          # a reference: the body's velocity changes
    assert S._cpp.vel()[0][0] == 9


def test_a_view_follows_its_row_after_clear():
    S = two_spheres()
    b = S.bodies[0]
    S.bodies.clear()
    with pytest.raises(IndexError):
        b.state.pos
    S.bodies.append(sphere((4, 5, 6), 1))
    assert list(S.bodies[0].state.pos) == [4, 5, 6]
