"""HydroForceEngine (talus.flow): fluid forces on particles and solid-phase averaging, against
analytic values and side by side with Yade's HydroForceEngine on identical input."""
import json
import math
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from talus.dem import ForceResetter, NewtonIntegrator, Scene, sphere, wall
from talus.flow import HydroForceEngine

HERE = Path(__file__).parent
YADE = shutil.which("yade")


def run_json(cmd, env=None):
    done = subprocess.run(cmd, capture_output=True, text=True, timeout=300, env=env, cwd=HERE)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    line = next(l for l in done.stdout.splitlines() if l.startswith("RESULT "))
    return json.loads(line[len("RESULT "):])


@pytest.mark.skipif(YADE is None, reason="yade is not installed (apt-get install yade)")
def test_forces_and_average_match_yade(build_dir):
    env = {**os.environ, "PYTHONPATH": str(build_dir / "python")}
    ours = run_json([sys.executable, str(HERE / "hydro_forces.py")], env=env)
    theirs = run_json([YADE, "-n", "-j1", "-x", str(HERE / "hydro_forces.py")])
    for name in ("default", "rest", "lift", "one layer", "two layers"):
        a, b = np.array(ours[name]), np.array(theirs[name])
        pushed = np.linalg.norm(b, axis=1) > 0
        # the coarse grids end half-way (one layer) and a third of the way up the column (two)
        assert pushed.all() if name in ("default", "rest", "lift") else 5 < pushed.sum() < 35, name
        assert np.all(a[~pushed] == 0), name
        rel = np.linalg.norm(a[pushed] - b[pushed], axis=1) / np.linalg.norm(b[pushed], axis=1)
        assert rel.max() < 1e-10, (name, rel.max())
    # The option sets really differ (the comparison would not see a dropped term otherwise).
    assert np.abs(np.array(theirs["rest"]) - np.array(theirs["default"])).max() > 1e-4
    assert np.abs(np.array(theirs["lift"])[:, 2] - np.array(theirs["default"])[:, 2]).max() > 1e-6
    for q in ("phi", "vx", "vy", "vz", "drag"):
        a, b = np.array(ours["average"][q]), np.array(theirs["average"][q])
        assert np.abs(b).max() > 0
        assert np.abs(a - b).max() < 1e-10 * np.abs(b).max(), q
    # enableMultiClassAverage: the classes (the radii of the engine's ids, not the scene's other
    # three sizes) and each class's solid fraction and drag profiles
    assert ours["average"]["radiusParts"] == theirs["average"]["radiusParts"] == [1.5e-3, 2.5e-3]
    phi = np.array(theirs["average"]["multiPhi"])
    # A sphere tangent to a layer's boundary leaves a round-off volume there (1e-32 in Yade, 0 in
    # Talus): Yade then gives the layer that sphere's drag, Talus none. Compared where a class has
    # volume.
    holds = phi > 1e-12 * phi.max()
    for q in ("multiPhi", "multiDrag"):
        a, b = np.array(ours["average"][q]), np.array(theirs["average"][q])
        assert a.shape == b.shape == (2, 60) and np.abs(b).max(axis=1).min() > 0
        assert np.abs(a - b)[holds].max() < 1e-10 * np.abs(b).max(), q
    assert np.abs(np.array(ours["average"]["multiPhi"]) - phi).max() < 1e-10 * phi.max()


def test_class_profiles_add_up_to_the_total_and_need_known_radii():
    """enableMultiClassAverage: the classes' solid fractions add up to phiPart and their
    volume-weighted velocities to vPart; a sphere whose radius is not in radiusParts (added
    after initialization) stops averageProfile, naming the body; the classes are the radii of
    the engine's ids."""
    s = scene_with([((0, 0, 0.0035 + 0.0013 * k), (5e-4, 1e-3)[k % 2], (0.1 * k, 0.02 * k, -0.01 * k))
                    for k in range(7)])
    e = HydroForceEngine(deltaZ=1e-3, nCell=20, vCell=1e-6, enableMultiClassAverage=True, scene=s,
                         ids=range(7), dead=True)
    e.initialization()
    assert e.radiusParts == [5e-4, 1e-3]
    e.averageProfile()
    phi, vx = np.array(e.multiPhiPart), np.array(e.multiVxPart)
    assert phi.shape == (2, 20) and (phi > 0).sum(axis=1).min() >= 3
    assert np.allclose(phi.sum(axis=0), e.phiPart, rtol=1e-13, atol=0)
    for k, v in enumerate((vx, np.array(e.multiVyPart), np.array(e.multiVzPart))):
        assert np.allclose((phi * v).sum(axis=0), e.phiPart * e.vPart[:, k], rtol=1e-12, atol=1e-18)
    s.bodies.append(sphere((0, 0, 0.01), 7e-4))
    with pytest.raises(ValueError, match="body 7's radius 0.0007 is not in radiusParts"):
        e.averageProfile()
    e.computeRadiusParts()
    assert e.radiusParts == [5e-4, 1e-3]
    e.ids = range(8)
    e.computeRadiusParts()
    e.averageProfile()
    assert e.radiusParts == [5e-4, 1e-3, 7e-4] and len(e.multiPhiPart) == 3


def scene_with(spheres, periodic_box=None):
    """A scene holding spheres given as (centre, radius, velocity)."""
    s = Scene()
    if periodic_box is not None:
        s.periodic = True
        s.cell.setBox(*periodic_box)
    for centre, radius, vel in spheres:
        i = s.bodies.append(sphere(centre, radius))
        s.bodies[i].state.vel = vel
    s.dt = 1e-6
    return s


def engine(s, **kw):
    args = dict(nCell=20, deltaZ=1e-3, zRef=0.0, ids=list(range(len(s.bodies))), scene=s)
    args.update(kw)
    return HydroForceEngine(**args)


def cap(r, h):
    """Volume of a spherical cap of height h (0 <= h <= 2r)."""
    h = min(max(h, 0.0), 2 * r)
    return math.pi * h * h * (3 * r - h) / 3


def test_drag_and_buoyancy_analytic():
    r, rho, mu, expo = 1e-3, 1000.0, 1e-3, 2.7
    s = scene_with([((0, 0, 0.0123), r, (0.1, -0.05, 0.02))])
    e = engine(s, densFluid=rho, viscoDyn=mu, expoRZ=expo, gravity=(0.5, 0.0, -9.8), steadyFlow=False)
    vx = np.linspace(0, 1, 21)
    phi = np.full(20, 0.3)
    e.vxFluid, e.phiPart = vx, phi
    layer = 12
    ur = np.array([vx[layer + 1] - 0.1, 0.05, -0.02])
    u = np.linalg.norm(ur)
    drag = 0.5 * rho * math.pi * r * r * (0.44 * u + 24.4 * mu / (rho * 2 * r)) * 0.7 ** -expo * ur
    buoy = -4 / 3 * math.pi * r ** 3 * rho * np.array([0.5, 0.0, -9.8])
    assert np.allclose(e.force(0), drag + buoy, rtol=1e-14, atol=0)
    e.steadyFlow = True        # steady flow: no streamwise buoyancy
    buoy[0] = 0.0
    assert np.allclose(e.force(0), drag + buoy, rtol=1e-14, atol=0)
    # As an engine: the same force ends up in the step's force array.
    s.engines = [ForceResetter(), e]
    s.step()
    assert np.allclose(s.forces()[0], drag + buoy, rtol=1e-14, atol=0)


def test_only_chosen_ids_get_forces():
    s = scene_with([((0, 0, 0.005), 1e-3, (0, 0, 0)), ((0.01, 0, 0.005), 1e-3, (0, 0, 0))])
    e = engine(s, ids=[1])
    s.engines = [ForceResetter(), e]
    s.step()
    assert np.all(s.forces()[0] == 0) and s.forces()[1][2] > 0


def test_slice_volumes_are_exact():
    r, dz = 2.5e-3, 1e-3
    z = 0.0071       # crosses layers 4 .. 9
    s = scene_with([((0, 0, z), r, (0.3, 0.1, -0.2))])
    e = engine(s, deltaZ=dz, vCell=1.0)
    profile = e.averageProfile()
    expected = [cap(r, (k + 1) * dz - (z - r)) - cap(r, k * dz - (z - r)) for k in range(20)]
    assert np.allclose(profile["phiPart"], expected, rtol=1e-12, atol=1e-22)
    assert math.isclose(sum(profile["phiPart"]), 4 / 3 * math.pi * r ** 3, rel_tol=1e-13)
    # The sphere spans 4.6 .. 9.6 mm: a 0.6 mm cap in layer 9, a 0.4 mm one in layer 4 (Yade
    # 2023.02a swaps them: it mirrors the slices about the sphere's centre).
    assert profile["phiPart"][9] > 1.5 * profile["phiPart"][4]
    occupied = profile["phiPart"] > 0
    assert np.allclose(profile["vxPart"][occupied], 0.3) and np.allclose(profile["vzPart"][occupied], -0.2)
    assert np.all(profile["vxPart"][~occupied] == 0)


def test_average_weights_velocity_and_drag_by_slice_volume():
    r, dz = 1e-3, 1e-3
    # Two spheres sharing layer 5 (one centred in it, one below it).
    s = scene_with([((0, 0, 0.0055), r, (1.0, 0, 0)), ((0.01, 0, 0.0045), r, (3.0, 0, 0))])
    e = engine(s, vCell=1e-6)
    e.vxFluid = np.full(21, 2.0)
    # The drag averaged is the one applied with the solid fraction before this average.
    f1, f2 = e.force(0)[0], e.force(1)[0]          # no streamwise buoyancy: drag only
    p = e.averageProfile()
    v1 = cap(r, 1.5e-3) - cap(r, 0.5e-3)            # sphere 1 centred in layer 5: its middle 1 mm
    v2 = cap(r, 2e-3) - cap(r, 1.5e-3)             # sphere 2: the top 0.5 mm of it
    assert math.isclose(p["phiPart"][5] * 1e-6, v1 + v2, rel_tol=1e-12)
    assert math.isclose(p["vxPart"][5], (v1 * 1.0 + v2 * 3.0) / (v1 + v2), rel_tol=1e-12)
    assert math.isclose(p["averageDrag"][5], (v1 * f1 + v2 * f2) / (v1 + v2), rel_tol=1e-12)


def test_periodic_cell_wraps_elevations_and_sets_layer_volume():
    box = (0.02, 0.03, 0.05)
    r = 2e-3
    inside = scene_with([((0.001, 0.002, 0.0103), r, (0.2, 0, 0))], periodic_box=box)
    shifted = scene_with([((0.001, 0.002, 0.0103), r, (0.2, 0, 0))], periodic_box=box)
    # Positions are not wrapped during a run: the particle may sit several periods away.
    shifted.bodies[0].state.pos = (0.001 + 0.02, 0.002 - 0.03, 0.0103 + 2 * 0.05)
    p1 = engine(inside).averageProfile()
    p2 = engine(shifted).averageProfile()
    assert np.allclose(p1["phiPart"], p2["phiPart"], rtol=1e-9, atol=0)
    total = np.sum(p1["phiPart"]) * 0.02 * 0.03 * 1e-3
    assert math.isclose(total, 4 / 3 * math.pi * r ** 3, rel_tol=1e-12)   # vCell = area x deltaZ
    assert np.allclose(engine(inside).force(0), engine(shifted).force(0), rtol=1e-12)


def test_fluctuations_are_reproducible_and_have_the_reynolds_stress():
    n = 4000
    spheres = [((0, 0, 0.0105), 1e-3, (0, 0, 0))] * n
    stress = 0.4          # Pa: u* = 0.02 m/s

    def draw(seed):
        s = scene_with(spheres)
        e = engine(s, velFluct=True, seed=seed)
        e.ReynoldStresses = np.full(20, stress)
        e.turbulentFluctuation()
        return e
    a, b, c = draw(3), draw(3), draw(4)
    assert np.array_equal(a.vFluct, b.vFluct) and not np.array_equal(a.vFluct, c.vFluct)
    u = a.vFluct
    ustar2 = stress / 1000.0
    assert abs(np.mean(u[:, 0] * u[:, 2]) / ustar2 + 1) < 0.1       # <u'w'> = -u*^2
    assert abs(np.mean(u[:, 2] ** 2) / ustar2 - 1) < 0.1
    assert abs(np.mean(u[:, 0] ** 2) / ustar2 - 2) < 0.15           # streamwise twice the normal
    life = a._core.fluctuationLife()
    assert np.allclose(life, 0.33 * 0.41 * 0.0105 / math.sqrt(ustar2))
    # The drag sees the fluctuation: with a still fluid the particle is dragged along it.
    assert np.allclose(a.force(0)[:2] / np.abs(a.force(0)[:2]), np.sign(u[0, :2]))


def test_fluctuations_refresh_after_their_eddy_life():
    s = scene_with([((0, 0, 0.0105), 1e-3, (0, 0, 0))])
    e = engine(s, velFluct=True, seed=1)
    e.ReynoldStresses = np.full(20, 0.4)
    s.engines = [ForceResetter(), e]
    s.dt = 1e-3
    s.step()
    first = e.vFluct[0].copy()
    life = 0.33 * 0.41 * 0.0105 / 0.02          # 0.071 s
    s.run(int(life / s.dt) - 2)
    assert np.array_equal(e.vFluct[0], first)
    s.run(3)
    assert not np.array_equal(e.vFluct[0], first)


def test_bad_input_is_refused_with_a_clear_error():
    s = scene_with([((0, 0, 0.5), 1e-3, (0, 0, 0))])
    e = engine(s)
    s.engines = [ForceResetter(), e]
    s.saveTmp("start")
    with pytest.raises(ValueError, match="body 0 at z = 0.5 is outside the fluid grid"):
        s.step()
    e.ignoreOutside = True
    s.loadTmp("start", engines="current")     # a failed step is not repeated on its half-updated state
    s.step()
    assert np.all(s.forces()[0] == 0)
    with pytest.raises(ValueError, match="vxFluid has 5 values, expected 21"):
        e.vxFluid = np.zeros(5)
    with pytest.raises(ValueError, match="phiPart"):
        e.phiPart = np.full(20, 1.2)
    with pytest.raises(ValueError, match="viscoDyn"):
        e.viscoDyn = -1.0
    with pytest.raises(ValueError, match="densFluid"):
        engine(s, densFluid=-5.0)
    with pytest.raises(ValueError, match="id 7 is not a body"):
        engine(s, ids=[7]).action()
    s.bodies.append(wall(0.0, axis=2))
    with pytest.raises(ValueError, match="body 1 is not a sphere"):
        engine(s, ids=[1]).action()
    with pytest.raises(ValueError, match="vCell"):
        engine(s).averageProfile()
    with pytest.raises(TypeError, match="unknown parameter"):
        engine(s, expoRz=3.0)


@pytest.mark.parametrize("z, where", [(0.0201, "above its top"), (-1e-4, "below zRef")])
def test_particles_out_of_the_grid_are_refused_not_clipped(z, where):
    # 20 layers of 1 mm: the grid ends at 20 mm (Yade's grid).
    for ignore in (False, True):
        s = scene_with([((0, 0, z), 3e-4, (0, 0, 0)), ((0, 0, 0.0195), 3e-4, (0, 0, 0))])
        s.engines = [ForceResetter(), engine(s, ignoreOutside=ignore)]
        if not ignore:
            with pytest.raises(ValueError, match=f"body 0 at z = {z:g} .*{where}"):
                s.step()
            continue
        s.step()
        assert np.all(s.forces()[0] == 0)
        assert s.forces()[1][2] > 0                     # the one in the top layer has its buoyancy


def test_top_layer_sees_the_surface_velocity_and_one_layer_is_a_grid():
    """Yade's grid: nCell layers from zRef; the fluid resolution's column ends at (nCell - 1)
    deltaZ, so a particle in the top layer is driven by the surface node vxFluid[nCell]."""
    r, rho = 3e-4, 1000.0
    s = scene_with([((0, 0, 0.0195), r, (0, 0, 0))])
    e = engine(s, densFluid=rho, expoRZ=0.0)
    e.vxFluid = np.linspace(0, 1, 21) ** 2
    s.engines = [ForceResetter(), e]
    s.step()
    ur = 1.0                                                  # vxFluid[20]
    drag = 0.5 * rho * math.pi * r * r * (0.44 * ur + 24.4 * 1e-3 / (rho * 2 * r)) * ur
    assert s.forces()[0][0] == pytest.approx(drag, rel=1e-14)
    # One layer (buoyantParticles.py, simpleBallRebound.py): buoyancy inside, nothing above.
    s = scene_with([((0, 0, 0.05), r, (0, 0, 0)), ((0, 0, 0.15), r, (0, 0, 0))])
    e = engine(s, nCell=1, deltaZ=0.1, steadyFlow=False, ignoreOutside=True)
    s.engines = [ForceResetter(), e]
    s.step()
    assert s.forces()[0] == pytest.approx([0, 0, 4 / 3 * math.pi * r ** 3 * 1000 * 9.81], rel=1e-14)
    assert np.all(s.forces()[1] == 0)
    with pytest.raises(ValueError, match="fluidResolution: nCell must be at least 2"):
        e.fluidResolution(1e-3, 1e-4)
    with pytest.raises(ValueError, match="nCell must be at least 1"):
        engine(s, nCell=0)


# -- two-way coupling ------------------------------------------------------------------------------

def film_with_bed(period, **kw):
    """A 4 mm laminar film on a 0.05 rad slope, its fluid at steady state without grains; then a
    bed of fixed grains appears at the bottom and the coupling starts."""
    from talus.flow import VansCoupling
    s = Scene()
    s.dt = 1e-4
    e = HydroForceEngine(nCell=41, deltaZ=1e-4, zRef=0.0, gravity=(0.49, 0.0, -9.8), iturbu=0, ids=[], scene=s,
                         vCell=1.6e-5 * 1e-4, radiusPart=2e-4)
    e.fluidResolution(50.0, 1e-2)                      # steady film, no grains yet
    for x in range(10):
        for y in range(10):
            s.bodies.append(sphere((x * 4e-4, y * 4e-4, 3e-4), 2e-4, fixed=True))
    s.engines = [ForceResetter(), e, NewtonIntegrator(gravity=(0.49, 0.0, -9.8))]
    c = VansCoupling(e, period, 1e-5, densPart=2500.0, diameterPart=4e-4, **kw)
    c.attach()
    return s, e, c


def test_coupling_alternates_and_records_series():
    s, e, c = film_with_bed(1e-3, changeLimit=0.5)
    with warnings_as_list() as caught:
        s.run(41)                                               # couplings at steps 10, 20, 30, 40
    assert len(c.series["time"]) == 4 and c.series["time"][0] == pytest.approx(1e-3)
    assert np.max(e.phiPart) > 0.3 and e.taufsi.max() > 0     # the bed entered the fluid resolution
    assert not [w for w in caught if "VansCoupling" in str(w.message)]
    assert 0.01 < max(c.series["fluidChange"]) < 0.5            # the film slows down in the bed
    assert c.series["fluidChange"][-1] < 0.02                   # and settles
    assert c.series["shieldsNumber"] == [0.0] * 4               # laminar: no Reynolds stress
    assert c.series["transportRate"] == [0.0] * 4               # fixed grains


def test_coupling_warns_when_the_fluid_jumps_between_couplings():
    s, e, c = film_with_bed(1e-3, changeLimit=0.02, warmup=0)
    with warnings_as_list() as caught:
        s.run(41)
    changes = np.array(c.series["fluidChange"])
    assert c.warned == np.sum(changes > 0.02) >= 1
    messages = [str(w.message) for w in caught if "VansCoupling" in str(w.message)]
    assert len(messages) == 1                                   # once, then counted in `warned`
    first = changes[np.argmax(changes > 0.02)]
    assert f"changed by {first:.0%}" in messages[0]
    assert f"use about {1e-3 * 0.02 / first:.2g} s or less" in messages[0]


def warnings_as_list():
    import warnings
    manager = warnings.catch_warnings(record=True)
    class _Ctx:
        def __enter__(self):
            caught = manager.__enter__()
            warnings.simplefilter("always", RuntimeWarning)
            return caught
        def __exit__(self, *exc):
            return manager.__exit__(*exc)
    return _Ctx()


def test_settling_case_quick_mode(talus_cmd, repo_dir, tmp_path):
    talus_cmd("run", repo_dir / "cases" / "vans" / "vans_settling.py", "--quick", "--results", tmp_path)
    record = json.loads((tmp_path / "vans.settling.json").read_text())
    assert record["pass"] and record["value"] < 1e-6, record
    assert (tmp_path / "vans.settling.png").exists()


def test_standalone_measurement_leaves_the_engine_alone():
    from talus.flow import averageProfile
    s = scene_with([((0, 0, 0.0071), 2.5e-3, (0.3, 0, 0))], periodic_box=(0.02, 0.02, 0.05))
    e = engine(s)
    measured = e.measure()
    assert np.all(e.phiPart == 0)                           # not stored
    alone = averageProfile(nCell=20, deltaZ=1e-3, scene=s)
    assert np.array_equal(alone["phiPart"], measured["phiPart"])
    assert math.isclose(np.sum(alone["phiPart"]) * 0.02 * 0.02 * 1e-3, 4 / 3 * math.pi * 2.5e-3 ** 3, rel_tol=1e-12)


def test_frey_case_redraws_fluctuations_every_eddy_turnover_time(repo_dir, monkeypatch):
    # The Frey-experiment case's fluctuation scheme (Yade's validMaurin2015.py): the bed is the
    # first layer from the top above phi = 0.5 that still rises downwards; all fluctuations are
    # redrawn at once, then kept for (water depth above the bed) / (mean fluid velocity there).
    monkeypatch.syspath_prepend(str(repo_dir / "cases" / "vans"))
    from vans_frey_experiments import TurnoverFluctuations
    s = scene_with([((0, 0, 0.0035), 5e-4, (0, 0, 0)), ((0, 0, 0.0155), 5e-4, (0, 0, 0))])
    e = engine(s)
    phi = np.zeros(20)
    phi[:7] = [0.6, 0.55, 0.58, 0.6, 0.52, 0.3, 0.1]     # layers 0..6: bed top at layer 4
    e.phiPart = phi
    e.vxFluid = np.linspace(0.0, 1.0, 21)
    e.ReynoldStresses = np.full(20, 1.0)
    refresh = TurnoverFluctuations(e, s, delay=0.0)
    refresh()
    assert refresh.refreshes == 1
    assert e.bedElevation == pytest.approx(4e-3)
    assert np.all(e.vFluct[0] == 0) and np.any(e.vFluct[1] != 0)    # below / above the bed
    assert refresh.next == pytest.approx(15 * 1e-3 / np.mean(e.vxFluid[4:]))
    drawn = e.vFluct.copy()
    refresh()                                            # before the turnover time: kept
    assert refresh.refreshes == 1 and np.array_equal(e.vFluct, drawn)


def test_an_imposed_profile_of_ncell_values_has_a_zero_top_node():
    """Yade's scripts impose vxFluid with one value per layer (nCell). Yade 2023.02a then reads
    0 past the end for the top layer (checked: 18.5 m/s imposed on 20 layers, a sphere at rest
    in layer 10 gets drag, one in layer 19 none) and its fluid resolution starts from a zero top
    node. Talus appends that 0 and says so."""
    s = scene_with([((0, 0, 0.0105), 3e-4, (0, 0, 0)), ((0, 0, 0.0195), 3e-4, (0, 0, 0))])
    e = engine(s, expoRZ=0.0)
    with pytest.warns(RuntimeWarning, match="vxFluid has nCell = 20 values; its top node"):
        e.vxFluid = np.full(20, 18.5)
    assert len(e.vxFluid) == 21 and e.vxFluid[20] == 0
    s.engines = [ForceResetter(), e]
    s.step()
    assert s.forces()[0][0] == pytest.approx(0.02139551831597118897, rel=1e-14)   # Yade's number
    assert s.forces()[1][0] == 0
    e.radiusPart = 3e-4
    e.fluidResolution(1e-3, 1e-4)
    assert len(e.vxFluid) == 21 and e.vxFluid[20] > 18


def test_a_yade_attribute_it_lacks_is_refused_and_an_unknown_one_is_kept_with_a_warning():
    s = scene_with([((0, 0, 0.0105), 3e-4, (0, 0, 0))])
    e = engine(s)
    with pytest.raises(AttributeError, match="twoSize: a Yade 2023.02a attribute that Talus does not implement"):
        e.twoSize = True
    with pytest.warns(RuntimeWarning, match="expoRz is not an attribute of HydroForceEngine"):
        e.expoRz = 3.0           # Yade too keeps it as a plain attribute
    assert e.expoRz == 3.0 and e.expoRZ == 3.1
    e.expoRZ, e.label, e.dead = 2.0, "h", True
    assert (e.expoRZ, e.label, e.dead) == (2.0, "h", True)


def test_scripts_run_as_yades_leave_particles_outside_the_grid_without_force(monkeypatch):
    from talus.flow import hydro, stray_attributes
    from yade import _components
    monkeypatch.setattr(hydro, "OUTSIDE_IS_ERROR", True)      # restored after the test
    monkeypatch.setattr(stray_attributes, "_accepted", False)  # run_defaults sets it too
    s = scene_with([((0, 0, 0.5), 1e-3, (0, 0, 0))])
    assert not engine(s).ignoreOutside
    _components.run_defaults()                                 # what yade.yade_run_defaults calls
    assert engine(s).ignoreOutside and not engine(s, ignoreOutside=False).ignoreOutside
