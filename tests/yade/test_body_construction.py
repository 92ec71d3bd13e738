"""Body(), Sphere(...), Box(...), Interaction() as Yade 2023.02a's, and what Talus refuses."""
from pathlib import Path

import numpy as np
import pytest

from talus.dem import Body, Facet, Scene, Sphere, sphere
from talus import twin

HERE = Path(__file__).parent


@pytest.mark.skipif(not twin.yade_available(), reason="yade is not installed")
def test_bodies_made_the_long_way_as_yade():
    ours, theirs = (twin.run(HERE / "side_by_side" / "body_construction_side_by_side.py", {}, who) for who in ("talus", "yade"))
    assert theirs["appended"][3:6] == [0.5, [1.0, 0.0, 0.0], True]
    positions = [ours.pop("positions"), theirs.pop("positions")]
    assert str(theirs["shapes"][:2]) == "[nan, [1.0, 1.0, 1.0]]"     # Yade's Sphere()
    assert str(ours) == str(theirs)
    assert np.allclose(*positions, rtol=0, atol=1e-13)
    assert positions[1][0][2] < 2.96                      # it fell


def test_what_talus_refuses():
    scene = Scene()
    b = Body()
    with pytest.raises(ValueError, match="without a shape Talus can add"):
        scene.bodies.append(b)
    with pytest.raises(ValueError, match="Body\\(\\) takes a Sphere, Box or Wall"):
        b.shape = Facet(vertices=[(0, 0, 0), (1, 0, 0), (0, 1, 0)])
    with pytest.raises(AttributeError, match="b.state = ... is not supported"):
        b.state = None
    with pytest.raises(AttributeError, match="Body has no attribute 'colour'"):
        Body(colour=1)
    b.shape = Sphere(radius=1)
    scene.bodies.append(b)
    with pytest.raises(AttributeError, match="radius of body 0 cannot be changed"):
        b.shape.radius = 2
    with pytest.raises(AttributeError, match="its shape cannot be replaced"):
        b.shape = Sphere(radius=2)


def test_a_body_made_without_mass_is_refused_at_the_step():
    scene = Scene()
    b = Body(shape=Sphere(radius=1))
    scene.bodies.append([b, sphere((5, 0, 0), 1)])
    assert scene.bodies[0].state.mass == 0 and scene.bodies[1].state.mass > 0
    from talus.dem import ForceResetter, NewtonIntegrator
    scene.engines = [ForceResetter(), NewtonIntegrator()]
    with pytest.raises(ValueError, match="body 0 is dynamic but its mass is 0.*b.state.mass"):
        scene.step()
