"""growParticles with nothing to grow (Yade's: the multiplier is not looked at), as a
TriaxialStressController compacting fixed spheres towards a stress goal of 0 asks for."""
import pytest

from talus.dem import Scene, growParticles, sphere


def test_a_bad_multiplier_is_refused_only_when_a_body_would_grow():
    S = Scene()
    ids = S.bodies.append([sphere((0, 0, 0), 1.0, fixed=True), sphere((3, 0, 0), 1.0, fixed=True)])
    growParticles(float("-inf"), scene=S)                 # no dynamic sphere: nothing grows (Yade's)
    assert [S.bodies[i].shape.radius for i in ids] == [1.0, 1.0]
    with pytest.raises(ValueError, match="multiplier must be positive and finite, got -inf"):
        growParticles(float("-inf"), dynamicOnly=False, scene=S)
    S.bodies[ids[1]].dynamic = True
    with pytest.raises(ValueError, match="multiplier must be positive and finite, got -1"):
        growParticles(-1.0, scene=S)
    growParticles(1.5, scene=S)
    assert [S.bodies[i].shape.radius for i in ids] == [1.0, 1.5]
