"""PWaveTimeStep as Yade's Shop::PWaveTimeStep: the density of each sphere from its mass."""
import math

from talus.dem import FrictMat, PWaveTimeStep, Scene, sphere


def test_a_lightened_sphere_shortens_the_step():
    S = Scene()
    S.materials.append(FrictMat(young=1e7, density=1000))
    S.bodies.append([sphere((0, 0, 0), 0.01), sphere((1, 0, 0), 0.002)])
    assert math.isclose(PWaveTimeStep(S), 0.002 / math.sqrt(1e7 / 1000), rel_tol=1e-14)
    S.bodies[0].state.mass *= 1e-4        # as Yade's timeStepperUsage.py does to one body
    density = S.bodies[0].state.mass / (4 / 3 * math.pi * 0.01 ** 3)
    assert math.isclose(PWaveTimeStep(S), 0.01 / math.sqrt(1e7 / density), rel_tol=1e-14)
