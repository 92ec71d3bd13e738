"""The bad-input suite's case table, by component: each case does one bad thing and names the
exception and the words that must tell the user what is wrong (the parameter, body or file).
The tests (tests/<component>/test_bad_input_suite.py) and cases/reliability_bad_inputs.py (the
record reliability.bad-inputs: the fraction of these cases that end in such a clear error) both
read it. The inputs Yade runs silently, or that failed with a misleading message, have their own
tests (tests/dem/*/test_bad_input_*.py, tests/flow/pore/test_bad_input_flow.py); the random parameters
are drawn by bad_input_generator.py."""
from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

NAN, INF = math.nan, math.inf


@dataclass(frozen=True)
class Case:
    component: str
    name: str
    run: Callable[[Path], object]  # does the bad thing; gets a scratch folder
    error: type | tuple
    words: str                     # regular expression the message must match


def _scene(*bodies):
    from talus.dem import FrictMat, Scene
    S = Scene()
    S.materials.append(FrictMat())
    if bodies:
        S.bodies.append(list(bodies))
    return S


def _sphere_scene():
    from talus.dem import sphere
    return _scene(sphere((0, 0, 0), 1))


def _material_in_scene(**bad):
    from talus.dem import FrictMat, Scene
    Scene().materials.append(FrictMat(**bad))


def _run_engine(engine):
    from talus.dem import ForceResetter, NewtonIntegrator
    S = _sphere_scene()
    S.engines = [ForceResetter(), engine, NewtonIntegrator()]
    S.dt = 1e-6
    S.run(1, True)


def _nan_written_into_positions():
    from talus.dem import ForceResetter, InsertionSortCollider, NewtonIntegrator, sphere
    S = _scene(*[sphere((0, 0, 0.1 * i), 0.04) for i in range(3)])
    S.engines = [ForceResetter(), InsertionSortCollider(), NewtonIntegrator()]
    S.dt = 1e-5
    S.run(2, True)
    S.positions()[1] = (math.nan, 0, 0)
    S.run(2, True)


def _write(path: Path, text: str) -> str:
    path.write_text(text)
    return str(path)


def _rve(tmp: Path) -> str:
    from talus.fem import prepareRVE
    path = tmp / "rve.h5"
    if not path.exists():
        prepareRVE(path, size=1.0, rMean=0.1, rRelFuzz=0.3, seed=1, sigma=-1e5, young=1e8)
    return str(path)


def _lattice():
    import numpy as np
    g = np.arange(3) * 0.1
    return np.array([(a, b, c) for a in g for b in g for c in g]), np.full(27, 0.045)


def _dem_cases():
    import talus.dem as d
    from talus.dem import CheckpointError
    from talus.dem.packing import pack
    C = lambda name, run, error, words: Case("dem", name, run, error, words)  # noqa: E731
    return [
        # materials
        C("material young negative", lambda t: _material_in_scene(young=-1), ValueError, r"young must be finite and >= 0"),
        C("material density NaN", lambda t: _material_in_scene(density=NAN), ValueError, r"density must be finite"),
        C("material poisson negative", lambda t: _material_in_scene(poisson=-1), ValueError, r"poisson .* must be >= 0"),
        C("material friction angle 2", lambda t: _material_in_scene(frictionAngle=2), ValueError, r"frictionAngle must be in \[0, pi/2\)"),
        C("material unknown parameter", lambda t: d.FrictMat(yung=1), TypeError, r"FrictMat has no parameter 'yung'"),
        C("body with unknown material label", lambda t: _scene(d.sphere((0, 0, 0), 1, material="nope")), ValueError, r"no material labelled 'nope'"),
        C("body with material index out of range", lambda t: _scene(d.sphere((0, 0, 0), 1, material=42)), ValueError, r"unknown material index 42"),
        # bodies
        C("sphere radius 0", lambda t: _scene(d.sphere((0, 0, 0), 0)), ValueError, r"sphere #0: radius must be positive"),
        C("sphere radius NaN", lambda t: _scene(d.sphere((0, 0, 0), NAN)), ValueError, r"radius must be positive and finite"),
        C("sphere centre infinite", lambda t: _scene(d.sphere((INF, 0, 0), 1)), ValueError, r"sphere #0: centre is not finite"),
        C("sphere mask too big", lambda t: d.sphere((0, 0, 0), 1, mask=2 ** 40), OverflowError, r"mask of sphere: .* does not fit"),
        C("facet collinear vertices", lambda t: _scene(d.facet([(0, 0, 0), (1, 0, 0), (2, 0, 0)])), ValueError, r"facet #0: the three vertices are \(nearly\) collinear"),
        C("facet two vertices", lambda t: d.facet([(0, 0, 0), (1, 0, 0)]), ValueError, r"facet: needs three 3D vertices"),
        C("wall axis 5", lambda t: d.wall(0, axis=5), ValueError, r"wall: axis must be 0, 1 or 2, got 5"),
        C("wall position NaN", lambda t: _scene(d.wall(NAN, axis=2)), ValueError, r"wall #0: position is not finite"),
        C("box negative extents", lambda t: _scene(d.box((0, 0, 0), (-1, 1, 1))), ValueError, r"box #0: extents \(half-sizes\) must be finite and >= 0"),
        C("box two extents", lambda t: d.box((0, 0, 0), (1, 1)), ValueError, r"box: center and extents must be 3 numbers"),
        C("empty clump", lambda t: _scene().bodies.appendClumped([]), ValueError, r"clump #0: needs at least one member"),
        C("body id out of range", lambda t: _sphere_scene().bodies[999], IndexError, r"no body with id 999"),
        C("erase a missing body", lambda t: _sphere_scene().bodies.erase(12345), IndexError, r"no body with id 12345"),
        C("blockedDOFs unknown letter", lambda t: setattr(_sphere_scene().bodies[0].state, "blockedDOFs", "xq"), ValueError, r"blockedDOFs: unknown letters 'q'"),
        C("negative mass", lambda t: setattr(_sphere_scene().bodies[0].state, "mass", -1), ValueError, r"body 0: mass must be finite and >= 0"),
        C("NaN velocity", lambda t: setattr(_sphere_scene().bodies[0].state, "vel", (NAN, 0, 0)), ValueError, r"body 0: vel must be 3 finite numbers"),
        # engines
        C("NewtonIntegrator unknown parameter", lambda t: d.NewtonIntegrator(dampin=0.1), TypeError, r"unexpected keyword argument 'dampin'"),
        C("gravity of two numbers", lambda t: d.GravityEngine(gravity=(0, 0)), ValueError, r"gravity must be 3 finite numbers"),
        C("ForceEngine on a missing body", lambda t: _run_engine(d.ForceEngine(ids=[7], force=(0, 0, 1))), IndexError, r"ForceEngine: no body with id 7"),
        C("TranslationEngine on a missing body", lambda t: _run_engine(d.TranslationEngine(ids=[3], translationAxis=(1, 0, 0), velocity=1)), IndexError, r"TranslationEngine: no body with id 3"),
        C("translation axis zero", lambda t: d.TranslationEngine(ids=[0], translationAxis=(0, 0, 0), velocity=1), ValueError, r"translationAxis must not be zero"),
        C("PyRunner negative period", lambda t: d.PyRunner("pass", iterPeriod=-1), ValueError, r"PyRunner: iterPeriod, realPeriod and virtPeriod must be >= 0"),
        C("time stepper safety negative", lambda t: d.GlobalStiffnessTimeStepper(timestepSafetyCoefficient=-1), ValueError, r"timestepSafetyCoefficient must be positive"),
        C("collider skin NaN", lambda t: d.InsertionSortCollider(verletDist=NAN), ValueError, r"InsertionSortCollider.verletDist must be a number"),
        C("engine list of numbers", lambda t: setattr(_scene(), "engines", [5]), TypeError, r"O.engines takes engines, got 5"),
        C("bounding boxes enlarged", lambda t: d.Bo1_Sphere_Aabb(aabbEnlargeFactor=1.5), ValueError, r"Bo1_Sphere_Aabb.aabbEnlargeFactor = 1.5: enlarging the bounding boxes .* not implemented"),
        C("contacts detected at a distance", lambda t: d.Ig2_Sphere_Sphere_ScGeom6D(interactionDetectionFactor=1.2), ValueError, r"Ig2_Sphere_Sphere_ScGeom6D.interactionDetectionFactor = 1.2: detecting contacts at a distance"),
        C("stressMask beyond the three axes", lambda t: d.PeriTriaxController(stressMask=9), ValueError, r"stressMask takes bits 1, 2, 4 \(x, y, z\): an integer from 0 to 7, got 9"),
        C("NaN written into positions()", lambda t: _nan_written_into_positions(), RuntimeError, r"body 1 has a non-finite position \(nan, 0, 0\) .* or a position set so from Python"),
        C("engine list not a list", lambda t: setattr(_scene(), "engines", 5), TypeError, r"O.engines takes a list of engines, got 5"),
        # run control and the periodic cell
        C("O.run negative steps", lambda t: _scene().run(-5, True), ValueError, r"O.run: nSteps must be >= 0"),
        C("O.dt NaN", lambda t: setattr(_scene(), "dt", NAN), ValueError, r"O.dt must be zero or positive and finite"),
        C("O.dt a string", lambda t: setattr(_scene(), "dt", "abc"), TypeError, r"O.dt is a number of seconds, got 'abc'"),
        C("cell of zero volume", lambda t: _scene().cell.setBox(0, 1, 1), Exception, r"cell: hSize must be finite with a positive volume"),
        C("cell box negative", lambda t: _scene().cell.setBox(-1, 1, 1), Exception, r"cell: hSize must be finite with a positive volume"),
        # packings
        C("regularHexa negative radius", lambda t: pack.regularHexa(pack.inAlignedBox((0, 0, 0), (1, 1, 1)), radius=-1, gap=0), ValueError, r"regular packing: radius must be positive"),
        # files
        C("load a missing checkpoint", lambda t: _scene().load(str(t / "missing.h5")), CheckpointError, r"checkpoint '.*missing.h5': no such file"),
        C("load a text file", lambda t: _scene().load(_write(t / "x.h5", "hello")), CheckpointError, r"not an HDF5 file"),
        C("save into a missing folder", lambda t: _scene().save(str(t / "no" / "x.h5")), CheckpointError, r"the folder '.*no' does not exist"),
    ]


def _flow_cases():
    import numpy as np
    from talus.flow import FlowEngine, HydroForceEngine, TwoPhaseFlowEngine, VansCoupling, VansFluid
    C = lambda name, run, error, words: Case("flow", name, run, error, words)  # noqa: E731

    def solve(**bad):
        f = FlowEngine(bndCondIsPressure=[0, 0, 1, 1, 0, 0], bndCondValue=[0, 0, 1, 0, 0, 0], **bad)
        f.triangulate(*_lattice())
        f.solve()

    return [
        C("FlowEngine unknown attribute", lambda t: FlowEngine(viscosityy=1), AttributeError, r"FlowEngine has no attribute 'viscosityy'"),
        C("FlowEngine negative viscosity", lambda t: solve(viscosity=-1), ValueError, r"FlowEngine.viscosity must be positive"),
        C("FlowEngine infinite permeabilityFactor", lambda t: FlowEngine(permeabilityFactor=INF), ValueError, r"FlowEngine.permeabilityFactor must be a finite number"),
        C("FlowEngine solver 2", lambda t: FlowEngine(useSolver=2), ValueError, r"FlowEngine.useSolver must be 0 \(Gauss-Seidel\) or 3"),
        C("FlowEngine permeabilityMap True", lambda t: FlowEngine(permeabilityMap=True), ValueError, r"FlowEngine.permeabilityMap = True .* not implemented"),
        C("FlowEngine NaN boundary value", lambda t: FlowEngine(bndCondValue=[0, 0, NAN, 0, 0, 0]), ValueError, r"FlowEngine.bndCondValue must be 6 finite numbers"),
        C("FlowEngine 2 spheres", lambda t: FlowEngine().triangulate(np.zeros((2, 3)), np.ones(2)), ValueError, r"needs at least 4 spheres, got 2"),
        C("FlowEngine 2D positions", lambda t: FlowEngine().triangulate(np.zeros((5, 2)), np.ones(5)), ValueError, r"positions must be \(n, 3\)"),
        C("FlowEngine negative radius", lambda t: FlowEngine().triangulate(np.random.default_rng(1).random((10, 3)), -np.ones(10)), ValueError, r"body 0 has a non-positive radius"),
        C("FlowEngine solve before triangulate", lambda t: FlowEngine().solve(), RuntimeError, r"no pore network yet \(triangulate first\)"),
        C("TwoPhaseFlowEngine entry pressure method 4", lambda t: TwoPhaseFlowEngine(entryPressureMethod=4), ValueError, r"TwoPhaseFlowEngine.entryPressureMethod must be 1 \(MS-P"),
        C("TwoPhaseFlowEngine negative surfaceTension", lambda t: TwoPhaseFlowEngine(surfaceTension=-0.07), ValueError, r"TwoPhaseFlowEngine.surfaceTension must be a finite number >= 0"),
        C("TwoPhaseFlowEngine 5 boundary values", lambda t: TwoPhaseFlowEngine(bndCondValue=[0, 0, 1, 0, 0]), ValueError, r"TwoPhaseFlowEngine.bndCondValue needs a list of 6 values"),
        C("VansFluid one cell", lambda t: VansFluid(nCell=1, deltaZ=0.01).fluidResolution(0.1, 1e-3), ValueError, r"nCell must be at least 2"),
        C("VansFluid negative deltaZ", lambda t: VansFluid(nCell=10, deltaZ=-1), ValueError, r"VansFluid: deltaZ must be positive"),
        C("VansFluid phiMax 2", lambda t: VansFluid(nCell=10, deltaZ=0.01, phiMax=2), ValueError, r"VansFluid: phiMax must be in \(0, 1\]"),
        C("VansFluid NaN density", lambda t: VansFluid(nCell=10, deltaZ=0.01, densFluid=NAN), ValueError, r"VansFluid: densFluid must be finite"),
        C("VansFluid negative dt", lambda t: VansFluid(nCell=10, deltaZ=0.01).fluidResolution(1, -1), ValueError, r"fluidResolution: dt must be finite and positive"),
        C("HydroForceEngine deltaZ 0", lambda t: HydroForceEngine(deltaZ=0, nCell=10), ValueError, r"deltaZ must be positive"),
        C("VansCoupling negative period", lambda t: VansCoupling(HydroForceEngine(deltaZ=0.01, nCell=10), period=-1, dtFluid=1e-3, densPart=2500, diameterPart=1e-3), ValueError, r"VansCoupling: period and dtFluid must be positive"),
    ]


def _fem_cases():
    import numpy as np
    from talus.fem import MultiscaleRVEs, prepareRVE
    C = lambda name, run, error, words: Case("fem", name, run, error, words)  # noqa: E731
    return [
        C("RVE file missing", lambda t: MultiscaleRVEs(str(t / "none.h5"), numPoints=2), ValueError, r"RVE file '.*none.h5' does not exist"),
        C("no Gauss point", lambda t: MultiscaleRVEs(_rve(t), numPoints=0), ValueError, r"give numPoints >= 1"),
        C("RVE damping 2", lambda t: MultiscaleRVEs(_rve(t), numPoints=1, damping=2), ValueError, r"damping .* must be in \[0, 1\]"),
        C("RVE fdStep negative", lambda t: MultiscaleRVEs(_rve(t), numPoints=1, fdStep=-1), ValueError, r"fdStep .* must be in \(0, 1\)"),
        C("RVE unknown law", lambda t: MultiscaleRVEs(_rve(t), numPoints=1, law="Nope"), ValueError, r"unknown contact law 'Nope'"),
        C("RVE unknown form", lambda t: MultiscaleRVEs(_rve(t), numPoints=1, form="nope"), ValueError, r"form must be one of"),
        C("RVE NaN gradient", lambda t: MultiscaleRVEs(_rve(t), numPoints=1, nSteps=5).run(np.full((1, 3, 3), NAN)), ValueError, r"displacement gradient of Gauss point 0 is not finite"),
        C("RVE gradients of the wrong shape", lambda t: MultiscaleRVEs(_rve(t), numPoints=2, nSteps=5).run(np.zeros(1)), ValueError, r"expected shape \(2, d, d\)"),
        C("prepareRVE negative radius", lambda t: prepareRVE(t / "r.h5", rMean=-1), ValueError, r"prepareRVE: rMean must be positive"),
        C("prepareRVE NaN stress", lambda t: prepareRVE(t / "r.h5", sigma=NAN), ValueError, r"prepareRVE: sigma .* must be negative"),
    ]


def _coupling_cases():
    from talus.coupling import FoamCoupling

    def coupling(**bad):
        from talus.dem import Scene
        return FoamCoupling(Scene(), "case", **{"rhoFluid": 1000.0, "nu": 1e-6, **bad})

    C = lambda name, run, error, words: Case("coupling", name, run, error, words)  # noqa: E731
    return [
        C("FoamCoupling without fluid properties", lambda t: FoamCoupling(_scene(), "case"), TypeError, r"give the case and the fluid's properties"),
        C("FoamCoupling timeout 0", lambda t: coupling(timeout=0), ValueError, r"timeout must be a positive number of seconds"),
        C("FoamCoupling timeout NaN", lambda t: coupling(timeout=NAN), ValueError, r"timeout must be a positive number of seconds"),
        C("FoamCoupling empty interfaces", lambda t: coupling(interfaces=""), ValueError, r"interfaces must be Open MPI interface names"),
        C("FoamCoupling checkpointInterval 0", lambda t: coupling(checkpoint="x.h5", checkpointInterval=0), ValueError, r"checkpointInterval must be >= 1"),
        C("FoamCoupling without spheres", lambda t: coupling().start(), ValueError, r"FoamCoupling: no sphere to couple"),
    ]


_BUILDERS = {"dem": _dem_cases, "flow": _flow_cases, "fem": _fem_cases, "coupling": _coupling_cases}


def cases(component: str) -> list[Case]:
    return _BUILDERS[component]()


def outcome(case: Case, scratch: Path) -> str:
    """'clear' (the expected exception, naming the problem), 'unclear' (another exception or
    message: with it), or 'accepted' (no error)."""
    try:
        case.run(scratch)
    except case.error as e:
        return "clear" if re.search(case.words, str(e)) else f"unclear: {type(e).__name__}: {e}"
    except Exception as e:
        return f"unclear: {type(e).__name__}: {e}"
    return "accepted"


def assert_clear(case: Case, scratch: Path):
    """The test of one case: the exception type and the words that name the problem."""
    import pytest
    with pytest.raises(case.error, match=case.words):
        case.run(scratch)
