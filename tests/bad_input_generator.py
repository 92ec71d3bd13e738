"""Random bad parameters for the main constructors: each draw gives one or two parameters of a
material, a body, an engine, the pore-flow engine, the VANS fluid or the FEM x DEM RVEs a bad
value (NaN, inf, negative, zero, huge, wrong type, wrong length, empty string ...) and runs a
few steps with it. A draw may end in a clean Python exception or a valid run with finite
results; never in a crash (signal), a hang or non-finite results.

Draw i of seed s is a function of (s, i) only, so that a batch of draws runs in one subprocess
(`python bad_input_generator.py SEED FIRST LAST`, one JSON line per draw) and a crash or hang is
pinned to its draw by the parent (`run_draws`), which resumes with the next one in a new
subprocess. Used by tests/test_bad_input_random.py and cases/reliability_bad_inputs.py.
"""
from __future__ import annotations

import json
import math
import os
import queue
import random
import subprocess
import sys
import tempfile
import threading
from dataclasses import dataclass
from pathlib import Path

NAN, INF = math.nan, math.inf

# Bad values by the kind of parameter they replace.
SCALARS = [NAN, INF, -INF, -1.0, 0.0, 1e300, -1e300, 1e-300, "abc", "", None, [1.0, 2.0], True]
INTEGERS = [-1, 0, 10 ** 12, 2 ** 63, NAN, 1.5, "", "3", None]
VECTORS = [(NAN, 0.0, 0.0), (INF, INF, INF), (1e300, 0.0, 0.0), (1.0, 2.0), (1.0, 2.0, 3.0, 4.0), (), "abc",
           "", None, 5.0, ("a", "b", "c")]
FLAGS = [-1, 2, "abcdef", "", None, NAN, [1, 0]]
STRINGS = ["", "no such thing", None, 3, NAN]
LISTS6 = [[NAN] * 6, [INF] * 6, [1.0] * 5, [1.0] * 7, "abcdef", "", None, [1e300] * 6, [-1e300] * 6]
MATRICES = [[[NAN] * 3] * 3, [[INF] * 3] * 3, [[1e300] * 3] * 3, [[1.0] * 2] * 2, "abc", None, [[-10.0, 0, 0], [0, 0, 0], [0, 0, 0]]]

KINDS = {"scalar": SCALARS, "int": INTEGERS, "vector": VECTORS, "flag": FLAGS, "string": STRINGS,
         "list6": LISTS6, "matrix": MATRICES}


def _dem_scene(material=None, bodies=None, engines=None, dt=None, law="linear"):
    """Two spheres falling on a wall (and what ``bodies`` adds), ``law`` contacts, 20 steps."""
    from talus.dem import (ForceResetter, FrictMat, InsertionSortCollider, InteractionLoop,
                           Ig2_Sphere_Sphere_ScGeom, Ig2_Sphere_Sphere_ScGeom6D, Ig2_Wall_Sphere_ScGeom,
                           Ig2_Wall_Sphere_ScGeom6D, Ig2_Facet_Sphere_ScGeom, Ig2_Box_Sphere_ScGeom,
                           Ip2_CohFrictMat_CohFrictMat_CohFrictPhys, Ip2_FrictMat_FrictMat_FrictPhys,
                           Law2_ScGeom6D_CohFrictPhys_CohesionMoment, Law2_ScGeom_FrictPhys_CundallStrack,
                           NewtonIntegrator, PWaveTimeStep, Scene, sphere, wall)
    S = Scene()
    S.materials.append(material if material is not None else FrictMat(young=1e7, density=2600))
    S.bodies.append([sphere((0, 0, 0.025), 0.02), sphere((0.01, 0, 0.07), 0.02), wall(0, axis=2, sense=1)])
    if bodies:
        S.bodies.append(bodies)
    if law == "cohesive":
        geoms = [Ig2_Sphere_Sphere_ScGeom6D(), Ig2_Wall_Sphere_ScGeom6D()]
        phys, laws = [Ip2_CohFrictMat_CohFrictMat_CohFrictPhys()], [Law2_ScGeom6D_CohFrictPhys_CohesionMoment()]
    else:
        geoms = [Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom(), Ig2_Box_Sphere_ScGeom()]
        phys, laws = [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]
    S.engines = engines or [ForceResetter(), InsertionSortCollider(), InteractionLoop(geoms, phys, laws),
                            NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.2)]
    S.dt = dt if dt is not None else 0.5 * PWaveTimeStep(S)
    S.run(20, True)
    return [S.positions(), S.velocities(), S.forces()]


def _material(cls, law="linear"):
    def build(p):
        import talus.dem as dem
        return _dem_scene(material=getattr(dem, cls)(**p), law=law)
    return build


def _body(factory):
    def build(p):
        import talus.dem as dem
        return _dem_scene(bodies=[getattr(dem, factory)(**p)])
    return build


def _newton(p):
    from talus.dem import (ForceResetter, InsertionSortCollider, InteractionLoop, Ig2_Sphere_Sphere_ScGeom,
                           Ig2_Wall_Sphere_ScGeom, Ip2_FrictMat_FrictMat_FrictPhys,
                           Law2_ScGeom_FrictPhys_CundallStrack, NewtonIntegrator)
    return _dem_scene(engines=[ForceResetter(), InsertionSortCollider(),
                               InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
                                               [Ip2_FrictMat_FrictMat_FrictPhys()],
                                               [Law2_ScGeom_FrictPhys_CundallStrack()]),
                               NewtonIntegrator(**p)])


def _collider(p):
    from talus.dem import (ForceResetter, InsertionSortCollider, InteractionLoop, Ig2_Sphere_Sphere_ScGeom,
                           Ig2_Wall_Sphere_ScGeom, Ip2_FrictMat_FrictMat_FrictPhys,
                           Law2_ScGeom_FrictPhys_CundallStrack, NewtonIntegrator)
    collider = InsertionSortCollider()
    for name, value in p.items():
        setattr(collider, name, value)
    return _dem_scene(engines=[ForceResetter(), collider,
                               InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
                                               [Ip2_FrictMat_FrictMat_FrictPhys()],
                                               [Law2_ScGeom_FrictPhys_CundallStrack()]),
                               NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.2)])


def _time_step(p):
    return _dem_scene(dt=p["dt"])


def _peri_triax(p):
    """A periodic cloud of 20 spheres compressed by a PeriTriaxController for 30 steps."""
    from talus.dem import (ForceResetter, FrictMat, InsertionSortCollider, InteractionLoop,
                           Ig2_Sphere_Sphere_ScGeom, Ip2_FrictMat_FrictMat_FrictPhys,
                           Law2_ScGeom_FrictPhys_CundallStrack, NewtonIntegrator, PeriTriaxController,
                           PWaveTimeStep, Scene)
    from talus.dem.packing import pack
    S = Scene()
    S.periodic = True
    S.cell.setBox(1, 1, 1)
    S.materials.append(FrictMat(young=1e7, density=2600))
    sp = pack.SpherePack()
    sp.makeCloud((0, 0, 0), (1, 1, 1), rMean=0.12, rRelFuzz=0.2, num=20, periodic=True, seed=1)
    sp.toSimulation(S)
    S.engines = [ForceResetter(), InsertionSortCollider(),
                 InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                                 [Law2_ScGeom_FrictPhys_CundallStrack()]),
                 PeriTriaxController(**p), NewtonIntegrator(damping=0.2)]
    S.dt = 0.5 * PWaveTimeStep(S)
    S.run(30, True)
    return [S.positions(), S.cell.hSize]


def _flow(p):
    """Pore flow through a 4 x 4 x 4 lattice of spheres, solved once."""
    import numpy as np
    from talus.flow import FlowEngine
    g = np.arange(4) * 0.1
    x = np.array([(a, b, c) for a in g for b in g for c in g]) + np.random.default_rng(1).uniform(-0.01, 0.01, (64, 3))
    flow = FlowEngine(**p)
    flow.triangulate(x, np.full(64, 0.045), np.arange(6, 70))
    flow.solve()
    return [flow.pressures]


def _vans(p):
    from talus.flow import VansFluid
    fluid = VansFluid(**p)
    fluid.fluidResolution(0.05, 1e-3)
    return [fluid.vxFluid]


_RVE = None


def _rve_file() -> str:
    global _RVE
    if _RVE is None:
        from talus.fem import prepareRVE
        _RVE = str(Path(tempfile.mkdtemp(prefix="talus-bad-rve-")) / "rve.h5")
        prepareRVE(_RVE, size=1.0, rMean=0.1, rRelFuzz=0.3, seed=1, sigma=-1e5, young=1e8)
    return _RVE


def _rves(p):
    import numpy as np
    from talus.fem import MultiscaleRVEs
    grads = p.pop("dispGrads")
    rves = MultiscaleRVEs(_rve_file(), **p)
    rves.run(np.array([grads] * rves.numPoints) if not isinstance(grads, (str, type(None))) else grads)
    return list(rves.getStressAndTangent())


@dataclass
class Target:
    name: str
    run: object                  # callable(params) -> list of arrays that must be finite
    good: dict                   # parameters of a valid run
    kinds: dict                  # parameter -> kind of bad values (KINDS)


TARGETS = [
    Target("FrictMat", _material("FrictMat"), dict(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600),
           dict(young="scalar", poisson="scalar", frictionAngle="scalar", density="scalar")),
    Target("CohFrictMat", _material("CohFrictMat", "cohesive"),
           dict(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600, normalCohesion=1e4, shearCohesion=1e4,
                isCohesive=True),
           dict(young="scalar", poisson="scalar", frictionAngle="scalar", density="scalar",
                normalCohesion="scalar", shearCohesion="scalar", isCohesive="flag")),
    Target("sphere", _body("sphere"), dict(center=(0.2, 0, 0.03), radius=0.02, mask=1),
           dict(center="vector", radius="scalar", mask="int")),
    Target("facet", _body("facet"), dict(vertices=[(-1, -1, 0.001), (1, -1, 0.001), (0, 1, 0.001)]),
           dict(vertices="vector")),
    Target("wall", _body("wall"), dict(position=-0.01, axis=2, sense=1),
           dict(position="scalar", axis="int", sense="int")),
    Target("box", _body("box"), dict(center=(0.3, 0, 0.02), extents=(0.05, 0.05, 0.02), fixed=True),
           dict(center="vector", extents="vector", orientation="vector")),
    Target("NewtonIntegrator", _newton, dict(gravity=(0, 0, -9.81), damping=0.2),
           dict(gravity="vector", damping="scalar")),
    Target("InsertionSortCollider", _collider, dict(verletDist=-0.5), dict(verletDist="scalar")),
    Target("O.dt", _time_step, dict(dt=1e-5), dict(dt="scalar")),
    Target("PeriTriaxController", _peri_triax,
           dict(goal=(-1e4, -1e4, -1e4), stressMask=7, maxUnbalanced=0.01, maxStrainRate=(1, 1, 1), dynCell=True,
                mass=1.0),
           dict(goal="vector", stressMask="int", maxUnbalanced="scalar", maxStrainRate="vector", mass="scalar")),
    Target("FlowEngine", _flow,
           dict(bndCondIsPressure=[0, 0, 1, 1, 0, 0], bndCondValue=[0, 0, 1, 0, 0, 0], viscosity=1.0,
                permeabilityFactor=1.0),
           dict(bndCondIsPressure="list6", bndCondValue="list6", viscosity="scalar", permeabilityFactor="scalar",
                useSolver="int", minKdivKmean="scalar")),
    Target("VansFluid", _vans,
           dict(nCell=20, deltaZ=0.005, densFluid=1000.0, viscoDyn=1e-3, gravity=(9.81 * 0.05, 0, -9.81), kappa=0.41,
                phiMax=0.64),
           dict(nCell="int", deltaZ="scalar", densFluid="scalar", viscoDyn="scalar", gravity="vector",
                dpdx="scalar", kappa="scalar", phiMax="scalar", iturbu="int", ilm="int", irheolf="int",
                iusl="int", uTop="scalar")),
    Target("MultiscaleRVEs", _rves,
           dict(numPoints=2, nSteps=10, damping=0.2, fdStep=1e-5, dispGrads=[[1e-4, 0, 0], [0, 0, 0], [0, 0, 0]]),
           dict(numPoints="int", nSteps="int", damping="scalar", fdStep="scalar", law="string", form="string",
                dispGrads="matrix")),
]


def draw(seed: int, index: int):
    """The target and its parameters of draw ``index``: one or two parameters made bad."""
    rng = random.Random(seed * 1_000_003 + index)
    target = TARGETS[rng.randrange(len(TARGETS))]
    params = dict(target.good)
    names = rng.sample(sorted(target.kinds), k=min(len(target.kinds), rng.choice((1, 1, 2))))
    for name in names:
        params[name] = rng.choice(KINDS[target.kinds[name]])
    return target, names, params


def _finite(results) -> bool:
    import numpy as np
    for r in results:
        a = np.asarray(r, dtype=float)
        if not np.all(np.isfinite(a)):
            return False
    return True


def run_one(seed: int, index: int) -> dict:
    """Draw ``index`` in this process: 'error' (with the exception), 'ok' or 'nonfinite'."""
    import warnings
    target, names, params = draw(seed, index)
    out = dict(index=index, target=target.name, bad=names, values=[repr(params[n]) for n in names])
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            results = target.run(dict(params))
    except Exception as e:  # a clean exception is a pass; which one is recorded
        text = str(e)
        out.update(outcome="error", error=type(e).__name__, message=text[:300],
                   named=any(n in text for n in names))
        return out
    out["outcome"] = "ok" if _finite(results) else "nonfinite"
    return out


def run_draws(seed: int, count: int, batch: int = 200, hang_seconds: float = 30.0) -> list[dict]:
    """Draws 0 .. count-1, ``batch`` per subprocess; a draw that kills its process (signal or
    abnormal exit) is 'crash', one that takes longer than ``hang_seconds`` is 'hang'."""
    results, first = [], 0
    import talus
    env = dict(os.environ, OMP_NUM_THREADS="1",
               PYTHONPATH=os.pathsep.join(filter(None, [str(Path(talus.__file__).parents[1]), os.environ.get("PYTHONPATH")])))
    while first < count:
        last = min(count, first + batch)
        proc = subprocess.Popen([sys.executable, __file__, str(seed), str(first), str(last)],
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
        lines = queue.Queue()  # a reader thread: a select() on the pipe misses lines already buffered
        threading.Thread(target=lambda: [lines.put(line) for line in proc.stdout] + [lines.put("")],
                         daemon=True).start()
        started, wait = first, hang_seconds + 10  # the first draw also waits for the imports
        while True:
            try:
                line = lines.get(timeout=wait)
            except queue.Empty:
                proc.kill()
                proc.communicate()
                results.append(dict(index=started, outcome="hang", **_describe(seed, started)))
                first = started + 1
                break
            if not line:  # the process ended
                code = proc.wait()
                err = proc.stderr.read()
                if started < last:
                    results.append(dict(index=started, outcome="crash", returncode=code, stderr=err[-500:],
                                        **_describe(seed, started)))
                first = started + 1 if started < last else last
                break
            record = json.loads(line)
            results.append(record)
            started, wait = record["index"] + 1, hang_seconds
    return results


def _describe(seed: int, index: int) -> dict:
    target, names, params = draw(seed, index)
    return dict(target=target.name, bad=names, values=[repr(params[n]) for n in names])


def main(argv):
    seed, first, last = (int(a) for a in argv[1:4])
    for i in range(first, last):
        print(json.dumps(run_one(seed, i)), flush=True)


if __name__ == "__main__":
    main(sys.argv)
