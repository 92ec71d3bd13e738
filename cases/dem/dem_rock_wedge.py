"""DEM case: the seed's rock-slope wedge (Yade's examples/PotentialBlocks/WedgeYADE.py with
joints/jointC.csv): blocks generated from 73 joint planes, a vertical cut, and the stability of
the blocks it frees, against the limit equilibrium of those blocks (Hoek & Bray's wedge).

Run:      build/bin/talus run cases/dem/dem_rock_wedge.py [--quick] [--results DIR]
Set-up:   as WedgeYADE.py (x north, y east, z down, gravity (0, 0, 9.81) m/s^2):
          - rock mass x, y in [-20, 20] m, z in [0, 40] m (BlockGen's boundarySize*), cut by the
            joints of jointC.csv in file order (readJoints, generateBlocks) with Yade's pruning
            minSize = 7 m (no block thinner: a joint that would cut a piece with an inscribed
            ball below 7 m across stops there) and maxRatio = 1e4, rounding r = 0.2 m; the
            joints are persistent (traces 10 km); the file's cohesion and tension are not used,
            as in the script (BlockGen's useFaceProperties off: frictional joints);
          - density 2700 kg/m^3, Knormal 2e8 N/m^3, Kshear 1e7 N/m^3, rock friction 50 deg;
            five fixed boundary plates 8 m thick (bottom, the four sides), frictionless
            material, kn_i 2e9, ks_i 1e8 N/m^3; verletDist 0.1 minSize;
          - the script's stages: 500 steps with Cundall damping 0.8 and no dashpot, then
            viscousDamping 0.5 and no Cundall damping; the time step 0.15 sqrt(m / kn), the
            smallest over the contacts (the script's calTimeStep, every 2000 steps); at step
            2000 the velocities are zeroed and the excavation removes every block whose
            centroid lies south-east of the joint 90/315 through the origin (the script's
            NorthWall(pos) < 0.001) and the east and south plates: a vertical face 40 m high
            facing 135 deg; then 20000 steps (quick: 6000);
          - limit equilibrium's setting for the friction search: the same blocks, the excavated
            ones left out, every block fixed but the freed ones (below), gravity ramped up over
            2 s (full: 6 s) with Cundall damping 0.3, then 1 s (full: 2 s) with the dashpot only, at rock
            friction 3 deg below and above each freed block's limit phi_c (full mode also
            50 deg); and a bisection (4 steps, full 7) on the friction below which the most
            critical block moves more than 5 cm (the strength reduction tan phi = tan 50 / F).
          Reference: for every block left, its contact faces (all but the top z = 0 and the cut
          face; those on the plates frictionless) and its weight give Goodman & Shi's sliding
          mode with Hoek & Bray's limit equilibrium (talus.dem.analysis.analytic.block_sliding_mode,
          friction only): lift-off, sliding on one face, or on two (a wedge, along their
          intersection line), and the friction phi_c at which it is at the limit; "freed" blocks
          are those with a mode. The slope's factor of safety at the script's 50 deg is
          tan 50 deg / tan(max phi_c). Yade's side cannot be run: Debian's Yade 2023.02a has no
          POTENTIAL_BLOCKS (no PotentialBlock, BlockGen), and its source tarball
          (yade_2023.02a.orig.tar.bz2) is not downloadable from this machine.
Checked:  dem.rock-wedge.partition: relative difference between the blocks' total volume and
          the intact volume (64000 m^3) <= 1e-9;
          dem.rock-wedge.script-run: number of blocks that limit equilibrium says fail at 50 deg
          (phi_c > 50 deg) and did not move 0.1 m in the script's run, = 0;
          dem.rock-wedge.stability: number of freed blocks, over the friction angles run, that
          did not slide (> 0.1 m after the loading) below their limit or did not hold (< 0.03 m,
          about their elastic shear W / (Kshear A)) above it, = 0;
          dem.rock-wedge.factor-of-safety: relative difference between tan 50 / tan phi* (phi*
          the bisected onset) and tan 50 / tan phi_c of the most critical block, <= 0.05.
Produces: the four records, the chart dem.rock-wedge.png (displacement histories of the
          script's run; the freed blocks' displacement against friction with their limits) and
          dem.rock-wedge.vtu in the results folder (the true block shapes at the end of the
          script's run, for ParaView).
"""
import math
import os

import numpy as np

from talus import _dem, results
from talus.dem import (ForceResetter, FrictMat, Ig2_PB_PB_ScGeom, InsertionSortCollider, InteractionLoop,
                       Ip2_FrictMat_FrictMat_KnKsPBPhys, Law2_SCG_KnKsPBPhys_KnKsPBLaw, NewtonIntegrator,
                       PotentialBlock, PotentialBlock2AABB, Scene, blockShape, generateBlocks, potentialBlock,
                       readJoints, write_blocks)
from talus.dem.analysis.analytic import block_sliding_mode
from talus.dem.geometry.blockgen import dipNormal
from talus.dem.analysis.sliding import rampGravity

JOINTS = "/usr/share/doc/yade/examples/PotentialBlocks/joints/jointC.csv"
HALF, DEPTH, R = 20.0, 40.0, 0.2            # boundarySizeX/Y 20 m each way, Z 0 ... 40 m; rForPP
MIN_SIZE, MAX_RATIO = 7.0, 1e4
RHO, KN, KS, KN_I, KS_I = 2700.0, 2e8, 1e7, 2e9, 1e8
PHI = 50.0                                  # BlockGen frictionDeg
G = 9.81
THICK = 0.1 * DEPTH                         # the plates' thickness (0.1 boundarySizeZmax)
CUT = dipNormal(90, 315)                    # the excavation plane; its normal points to the removed side
# Displacement (m) after the loading that counts as sliding, as holding (the elastic shear
# of a block under its weight, W / (Kshear A), is 1 ... 4 cm), and as the onset of sliding.
SLID, HELD, ONSET = 0.1, 0.03, 0.05


def rock_mass():
    """The intact rock (planes in world coordinates) cut by the joints of jointC.csv."""
    if not os.path.exists(JOINTS):
        raise SystemExit(f"dem_rock_wedge: {JOINTS} not found (Yade's examples, Debian package yade)")
    intact = PotentialBlock(a=[1, -1, 0, 0, 0, 0], b=[0, 0, 1, -1, 0, 0], c=[0, 0, 0, 0, 1, -1],
                            d=[HALF - R, HALF - R, HALF - R, HALF - R, DEPTH - R, -R], r=R)
    return generateBlocks(intact, readJoints(JOINTS), minSize=MIN_SIZE, maxRatio=MAX_RATIO)


def plates(m):
    """The five fixed boundary plates of the script, keyed by side."""
    size = {"bottom": (HALF, HALF, THICK), "east": (HALF, THICK, DEPTH / 2), "west": (HALF, THICK, DEPTH / 2),
            "south": (THICK, HALF, DEPTH / 2), "north": (THICK, HALF, DEPTH / 2)}
    centre = {"bottom": (0, 0, DEPTH + THICK), "east": (0, HALF + THICK, DEPTH / 2),
              "west": (0, -HALF - THICK, DEPTH / 2), "south": (-HALF - THICK, 0, DEPTH / 2),
              "north": (HALF + THICK, 0, DEPTH / 2)}
    return {side: potentialBlock(PotentialBlock.cuboid(size[side], r=R, isBoundary=True), pos=centre[side],
                                 material=m, fixed=True) for side in size}


def time_step(S, dynamic):
    """The script's calTimeStep: 0.15 sqrt(m / kn), smallest over the contacts (m of a moving
    body of the pair)."""
    mass = S._cpp.mass()
    dts = [0.15 * math.sqrt(mass[i] / c["kn"]) for c in S._cpp.contacts() for i in (c["id1"], c["id2"])
           if i in dynamic and c["kn"] > 0]
    return min(dts) if dts else S.dt


def scene(blocks, phi_deg, sides, viscous, damping, gravity):
    """The blocks (body id = index in ``blocks``; None: left out), the plates of ``sides`` and
    the script's engines. Returns the scene, the Ip2 and the integrator."""
    S = Scene()
    rock = S.materials.append(FrictMat(density=RHO, frictionAngle=math.radians(phi_deg)))
    smooth = S.materials.append(FrictMat(density=RHO, frictionAngle=0.0))
    for k, b in enumerate(blocks):
        assert S.bodies.append(potentialBlock(b, material=rock)) == k
    for side, b in plates(smooth).items():
        if side in sides:
            S.bodies.append(b)
    phys = Ip2_FrictMat_FrictMat_KnKsPBPhys(Knormal=KN, Kshear=KS, kn_i=KN_I, ks_i=KS_I, viscousDamping=viscous)
    newton = NewtonIntegrator(gravity=gravity, damping=damping)
    S.engines = [ForceResetter(), InsertionSortCollider([PotentialBlock2AABB()], verletDist=0.1 * MIN_SIZE),
                 InteractionLoop([Ig2_PB_PB_ScGeom(calContactArea=True)], [phys],
                                 [Law2_SCG_KnKsPBPhys_KnKsPBLaw(allowViscousAttraction=True, allowBreakage=False)]),
                 newton]
    return S, phys, newton


def displacements(S, ids, start):
    return np.linalg.norm(np.array([S.bodies[i].state.pos for i in ids]) - start, axis=1)


def run_script(blocks, steps_after, record_every=200):
    """WedgeYADE.py's stages at its rock friction (50 deg). Returns the scene, the ids of the
    blocks left after the excavation, their displacement histories from the excavation on
    (rows: records) and the record times."""
    S, phys, newton = scene(blocks, PHI, ("bottom", "east", "west", "south", "north"), viscous=0.0, damping=0.8,
                            gravity=(0, 0, G))
    ids = list(range(len(blocks)))
    S.dt = 1e-4
    S.run(3, True)
    S.dt = time_step(S, set(ids))
    S.run(497, True)
    phys.viscousDamping = 0.5        # the script's removeDamping() after 500 steps
    newton.damping = 0.0
    S.run(1500, True)
    S.dt = time_step(S, set(ids))
    for i in ids:                    # goToNextStage2 at step 2000: rest, then excavate
        S.bodies[i].state.vel = (0, 0, 0)
        S.bodies[i].state.angVel = (0, 0, 0)
    left = [i for i in ids if CUT @ np.asarray(S.bodies[i].state.pos) < 0.001]
    for i in set(ids) - set(left):
        S.bodies.erase(i)
    for side in ("east", "south"):   # the plates of the script's bA, bC
        S.bodies.erase(len(blocks) + ("bottom", "east", "west", "south", "north").index(side))
    start = np.array([S.bodies[i].state.pos for i in left])
    times, moved = [0.0], [np.zeros(len(left))]
    t0 = S.time
    for k in range(steps_after // record_every):
        S.run(record_every, True)
        if (k + 1) * record_every % 2000 == 0:
            S.dt = time_step(S, set(left))
        times.append(S.time - t0)
        moved.append(displacements(S, left, start))
    return S, left, np.array(moved), np.array(times)


def run_key_blocks(blocks, phi_deg, free, seconds, ramp_seconds):
    """Limit equilibrium's setting: the rock mass already excavated, every block but those of
    ``free`` fixed; gravity ramped up over ``ramp_seconds`` with Cundall damping 0.3, then
    ``seconds`` with the script's dashpot (0.5) only. A faster load makes the shear springs
    overshoot and slip a block past a Coulomb limit it keeps under a static load (block 0,
    phi_c 70 deg: at 71.9 deg it slides 5 cm after a 0.5 s ramp, 5e-5 m after a 2 s ramp).
    Returns the free blocks' displacements during the ramp and after it."""
    cut = [b if CUT @ np.mean(_corners(b), axis=0) < 0 else None for b in blocks]
    kept = [k for k, b in enumerate(cut) if b is not None]
    S, _, newton = scene([b for b in cut if b is not None], phi_deg, ("bottom", "west", "north"), viscous=0.5,
                         damping=0.3, gravity=(0, 0, 0))
    ids = [kept.index(k) for k in free]
    for j, k in enumerate(kept):
        S.bodies[j].dynamic = k in free
    start = np.array([S.bodies[i].state.pos for i in ids])
    S.dt = 1e-4
    newton.gravity = (0, 0, G / 20)
    S.run(3, True)
    S.dt = time_step(S, set(ids))
    rampGravity(S, newton, lambda f: (0, 0, G * f), ramp_seconds)
    newton.damping = 0.0
    loaded = np.array([S.bodies[i].state.pos for i in ids])
    ramp = displacements(S, ids, start)
    S.run(int(round(seconds / S.dt)), True)
    return ramp, displacements(S, ids, loaded)


def _corners(b):
    g = _dem.potential_block_geometry(list(b.a), list(b.b), list(b.c), list(b.d), b.r, "block")
    return np.asarray(g["vertices"])


def limit_equilibrium(blocks, volumes, keep):
    """Per generated block index in ``keep``: its sliding mode on fixed neighbours (faces other
    than the top and the cut; faces on the rock mass' outer planes rest on frictionless plates)
    and the rock friction angle phi_c (deg) at which it is at the limit (0: stable whatever the
    friction, 90: falls or slides whatever the friction)."""
    outer = [(np.array([1.0, 0, 0]), HALF), (np.array([0, -1.0, 0]), HALF), (np.array([0, 0, 1.0]), DEPTH)]
    free = [(np.array([0, 0, -1.0]), 0.0), (CUT, 0.0)]

    def on(n, h, planes):
        return any(np.allclose(n, m, atol=1e-9) and abs(h - o) < 1e-6 for m, o in planes)

    out = {}
    for k in keep:
        b = blocks[k]
        faces = [(n, h) for n, h in zip(np.column_stack([b.a, b.b, b.c]), np.asarray(b.d) + b.r)
                 if not on(n, h, free)]
        weight = np.array([0, 0, RHO * volumes[k] * G])
        # FS per unit tan(phi): rock faces tan phi = 1, plates 0.
        unit = block_sliding_mode(weight, [n for n, _ in faces], [0.0 if on(n, h, outer) else 1.0 for n, h in faces])
        fs = unit["FS"]
        phi_c = 90.0 if fs == 0 else (0.0 if math.isinf(fs) else math.degrees(math.atan(1 / fs)))
        out[k] = dict(mode=unit["mode"], phi_c=phi_c, volume=volumes[k],
                      direction=[float(x) for x in unit["direction"]])
    return out


def main():
    args = results.case_arguments(__doc__).parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    case = results.Case("dem.rock-wedge", quick=args.quick, folder=args.results)

    blocks = rock_mass()
    S = Scene()
    m = S.materials.append(FrictMat())
    volumes = [blockShape(S, i)["volume"] for i in S.bodies.append([potentialBlock(b, material=m) for b in blocks])]
    intact = (2 * HALF) ** 2 * DEPTH
    partition = abs(sum(volumes) - intact) / intact
    print(f"{len(blocks)} blocks from {len(readJoints(JOINTS))} joints (minSize {MIN_SIZE} m); volumes sum to "
          f"{sum(volumes):.6f} m^3 (intact {intact:.0f}), smallest {min(volumes):.1f} m^3, largest {max(volumes):.1f}")
    case.record("relative difference between the generated blocks' total volume and the intact rock's", partition,
                "the intact volume 40 x 40 x 40 m", 1e-9, suffix="partition", blocks=len(blocks),
                joints=len(readJoints(JOINTS)), min_volume=min(volumes), max_volume=max(volumes))

    steps = 6000 if args.quick else 20000
    S, left, moved, times = run_script(blocks, steps)
    limits = limit_equilibrium(blocks, volumes, left)
    free = sorted(k for k in left if limits[k]["phi_c"] > 0)
    for k in free:
        print(f"block {k}: {limits[k]['mode']} mode, phi_c {limits[k]['phi_c']:.2f} deg, volume "
              f"{limits[k]['volume']:.0f} m^3, moved {moved[-1][left.index(k)]:.3f} m at {PHI:.0f} deg")
    os.makedirs(case.folder, exist_ok=True)
    write_blocks(S, str(case.folder / "dem.rock-wedge.vtu"))
    must_fail = [k for k in free if limits[k]["phi_c"] > PHI]
    not_failed = [k for k in must_fail if moved[-1][left.index(k)] < SLID]
    failed = int(np.sum(moved[-1] > SLID))
    print(f"script's run: {len(left)} blocks left after the excavation, {failed} moved more than {SLID} m in "
          f"{times[-1]:.2f} s; of the {len(must_fail)} that limit equilibrium says fail, {len(not_failed)} did not")
    case.record(f"number of blocks that limit equilibrium says fail at phi = {PHI:.0f} deg and that did not slide "
                f"(> {SLID} m) in the script's run", len(not_failed),
                "Goodman & Shi / Hoek & Bray limit equilibrium of each freed block on fixed neighbours", 0,
                suffix="script-run", blocks_left=len(left), moved_more_than_slid=failed, must_fail=must_fail,
                seconds=float(times[-1]), moved_end={str(k): float(moved[-1][n]) for n, k in enumerate(left)})

    # Limit equilibrium's setting, friction 3 deg below and above each block's limit (and the
    # script's 50 deg in full mode): blocks below their limit slide, the others hold.
    seconds = 1.0 if args.quick else 2.0
    ramp_seconds = 2.0 if args.quick else 6.0   # the slower, the closer to the static limit
    limits_c = sorted({round(limits[k]["phi_c"], 2) for k in free})
    phis = sorted({round(c + sign * 3.0, 2) for c in limits_c for sign in (-1, 1)}
                  | ({PHI} if not args.quick else set()))
    ends, wrong = {}, []
    for phi in phis:
        ramp, after = run_key_blocks(blocks, phi, free, seconds, ramp_seconds)
        ends[phi] = after
        for n, k in enumerate(free):
            slides = limits[k]["phi_c"] > phi
            if (slides and after[n] < SLID) or (not slides and after[n] > HELD):
                wrong.append((phi, k, float(after[n]), limits[k]["phi_c"]))
        print(f"phi {phi} deg: "
              + ", ".join(f"block {k} {after[n]:.4f} m (ramp {ramp[n]:.4f})" for n, k in enumerate(free)))
    print(f"outcomes against limit equilibrium: {len(wrong)} wrong {wrong}")
    case.record(f"number of freed blocks whose outcome {seconds:.0f} s after the loading (slid > {SLID} m below "
                f"its limit, held < {HELD} m above) contradicts limit equilibrium, friction 3 deg off each limit",
                len(wrong),
                "Goodman & Shi sliding mode, Hoek & Bray limit equilibrium (friction only) of each block on fixed "
                "neighbours", 0, suffix="stability", phis_deg=phis, free_blocks=free, wrong=wrong,
                phi_c={str(k): limits[k]["phi_c"] for k in free}, modes={str(k): limits[k]["mode"] for k in free},
                moved={str(p): [float(x) for x in e] for p, e in ends.items()}, seconds=seconds,
                ramp_seconds=ramp_seconds)

    # Friction reduction: bisection on the friction at which the most critical block starts to
    # slide (moves more than ONSET after the loading), from [50, 85] deg.
    worst = max(free, key=lambda k: limits[k]["phi_c"])
    critical = limits[worst]["phi_c"]
    low, high = PHI, 85.0
    for _ in range(4 if args.quick else 7):
        mid = 0.5 * (low + high)
        moved_mid = run_key_blocks(blocks, mid, [worst], seconds, ramp_seconds)[1][0]
        print(f"bisection: phi {mid:.3f} deg, block {worst} moved {moved_mid:.4f} m")
        low, high = (mid, high) if moved_mid > ONSET else (low, mid)
    phi_star = 0.5 * (low + high)
    fs_dem = math.tan(math.radians(PHI)) / math.tan(math.radians(phi_star))
    fs_analytic = math.tan(math.radians(PHI)) / math.tan(math.radians(critical))
    fs_error = abs(fs_dem - fs_analytic) / fs_analytic
    print(f"factor of safety at {PHI:.0f} deg: DEM {fs_dem:.4f} (block {worst} slides below {phi_star:.2f} deg, "
          f"bracket {low:.2f} ... {high:.2f}), limit equilibrium {fs_analytic:.4f} (phi_c {critical:.2f} deg), "
          f"difference {fs_error:.2%}")
    case.record(f"relative difference of the slope's factor of safety at phi = {PHI:.0f} deg (friction reduction: "
                "tan 50 / tan phi*, phi* bisected)", fs_error,
                "tan(phi) / tan(phi_c) of limit equilibrium for the most critical block", 0.05,
                suffix="factor-of-safety", fs_dem=fs_dem, fs_analytic=fs_analytic, phi_star=phi_star,
                bracket=[low, high], phi_c=critical, block=worst, mode=limits[worst]["mode"],
                ramp_seconds=ramp_seconds)

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 4.5))
    for n, k in enumerate(left):
        if k in free:
            ax1.plot(times, moved[:, n], label=f"block {k}: {limits[k]['mode']}, phi_c {limits[k]['phi_c']:.1f} deg")
        else:
            ax1.plot(times, moved[:, n], color="0.7", lw=0.6)
    ax1.set_xlabel("time since the excavation (s)")
    ax1.set_ylabel("displacement (m)")
    ax1.set_title(f"WedgeYADE.py's run at {PHI:.0f} deg (grey: not free on fixed neighbours)", fontsize=10)
    ax1.legend(fontsize=7)
    for n, k in enumerate(free):
        ax2.semilogy(phis, [max(ends[p][n], 1e-6) for p in phis], "o-", label=f"block {k}")
        ax2.axvline(limits[k]["phi_c"], color="r", ls=":", lw=0.8)
    ax2.axhline(SLID, color="k", lw=0.6, ls="--")
    ax2.set_xlabel("rock friction angle (deg); dotted: limit-equilibrium phi_c")
    ax2.set_ylabel(f"displacement after the loading, {seconds:.0f} s (m)")
    ax2.set_title(f"friction reduction: FS at 50 deg DEM {fs_dem:.3f}, limit equilibrium {fs_analytic:.3f}",
                  fontsize=10)
    ax2.legend(fontsize=8)
    fig.tight_layout()
    case.save_chart(fig)


if __name__ == "__main__":
    main()
