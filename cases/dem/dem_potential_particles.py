"""DEM case: Potential Particles (Yade's PotentialParticle) against analytic contact geometry and
forces, friction, and side by side with Yade (Debian's yade has PotentialParticle).

Run:      build/bin/talus run cases/dem/dem_potential_particles.py [--quick] [--results DIR]
Set-up:   cube particles with Yade's cubePPscaled.py planes (half-size 0.5 m: d = 0.5 - r,
          r = 0.05 m, k = 0.2, R = sqrt(3) 0.5 m), density 1000 kg/m^3, the KnKs law (Knormal
          1e8 N/m^3, Kshear 1e7 N/m^3):
          1. pressing: two fixed cubes face to face, overlaps 1e-5 ... 1e-2 m, aligned and
             twisted 45 deg about the normal; one step; again in 2D mode
             (Ig2_PP_PP_ScGeom(twoDimension=True, unitWidth2D=0.5), twoDdir y);
          2. resting: a cube dropped 0.1 mm onto a wall under gravity (viscous damping 0.5,
             Cundall damping 0.3), 1 s;
          3. incline: a flat block (half-sizes 0.5, 0.5, 0.25 m, friction angle 30 deg) resting
             on a wall, gravity turned to theta over 0.25 s with Cundall damping, then 0.5 s
             (quick) or 1 s undamped, theta = 25 ... 35 deg (displacements from the ramp's end);
          4. Yade side by side (cases/yade/potential_particles.py, same input in both): the
             pressing and resting set-ups with a boundary plate instead of the wall (Yade's PP
             has no wall contact), and a packing of 8 (quick) or 27 cubes settled in a box of
             five boundary plates (cubePPscaled.py made small): porosity, coordination, and the
             cost of a step per contact with every body fixed (contact geometry only).
Checked:  dem.potential-particles.pressing: worst relative error of the overlap against
          2 s - D (s the face centre's distance, root of the potential on the axis) <= 1e-8,
          and of the normal force against Knormal A u_n with A the section of the overlap by
          the mid-plane integrated independently (numpy, 720 rays) <= 2e-3;
          dem.potential-particles.pressing-2d: the same in 2D mode against Knormal L w u_n, L the
          overlap's chord along x through the contact point (numpy bisection), <= 1e-6;
          dem.potential-particles.resting: relative error of the contact force against m g <= 1e-6;
          dem.potential-particles.incline-slip: worst relative error of the sliding acceleration
          above the friction angle against g (sin theta - cos theta tan phi) <= 1e-2;
          dem.potential-particles.incline-stick: largest displacement below it after the ramp
          <= 5 mm (the undamped oscillation of the shear spring, Kshear A ~ 1.4e6 N/m);
          dem.potential-particles.yade-pressing / yade-resting: relative difference of overlap
          and force from Yade's (reported; tolerance 5 %, Yade's area is a heuristic);
          dem.potential-particles.yade-pressing-2d: relative difference of the 2D area from
          Yade's (<= 1e-6);
          dem.potential-particles.yade-packing: porosity difference (absolute, <= 0.05) and
          coordination difference (relative, reported);
          dem.potential-particles.yade-cost: Yade's step time per contact over Talus's (>= 3).
Produces: the records and chart dem.potential-particles.png.
"""
import math
from pathlib import Path

import numpy as np

from talus import results
from talus.dem import (ForceResetter, FrictMat, Ig2_PP_PP_ScGeom, InsertionSortCollider, InteractionLoop,
                       Ip2_FrictMat_FrictMat_KnKsPhys, Law2_SCG_KnKsPhys_KnKsLaw, NewtonIntegrator,
                       PotentialParticle, PotentialParticle2AABB, Scene, potentialParticle, wall)
from talus import twin
from talus import _dem
from talus.dem.analysis.sliding import fittedAcceleration, inclineSweep, plotInclineSweep, rampGravity, restingForce, slide, tilted

KN, KS, RHO, G, PHI = 1e8, 1e7, 1000.0, 9.81, math.radians(30)
HALF, R_ROUND, K_SPH = 0.5, 0.05, 0.2
CUBE = PotentialParticle.cuboid((HALF, HALF, HALF), r=R_ROUND, k=K_SPH)
SCENARIO = Path(__file__).resolve().parents[1] / "yade" / "potential_particles.py"


def face_centre(shape, axis=2):
    """Distance of the face centre along `axis` (the root s > d of the potential on the axis)."""
    d, r, k, R = shape.d[2 * axis], shape.r, shape.k, shape.R
    A = (1 - k) / r**2 + k / R**2
    B = -2 * d * (1 - k) / r**2
    C = (1 - k) * d * d / r**2 - 1
    return (-B + math.sqrt(B * B - 4 * A * C)) / (2 * A)


def potential(shape, p, rot=np.eye(3)):
    """f of `shape` (at the origin, turned by `rot`) at points p (n x 3), in numpy."""
    N = np.stack([shape.a, shape.b, shape.c], axis=1) @ rot.T
    g = np.maximum(p @ N.T - np.asarray(shape.d), 0)
    return (1 - shape.k) * ((g * g).sum(-1) / shape.r**2 - 1) + shape.k * ((p * p).sum(-1) / shape.R**2 - 1)


def ray_lengths(f, z, u):
    """Distances from (0, 0, z) (inside the convex f <= 0) to f = 0 along the unit rows of u, by
    bisection."""
    lo, hi = np.zeros(len(u)), np.full(len(u), 3.0)
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        inside = f(np.array([0, 0, z]) + mid[:, None] * u) <= 0
        lo, hi = np.where(inside, mid, lo), np.where(inside, hi, mid)
    return lo


def section_area(f, z, n=720):
    """Area of {(x, y) : f(x, y, z) <= 0} (f convex, (0, 0, z) inside) by polar bisection."""
    th = 2 * np.pi * np.arange(n) / n
    rho = ray_lengths(f, z, np.stack([np.cos(th), np.sin(th), np.zeros(n)], axis=1))
    return 0.5 * np.sum(rho**2) * 2 * np.pi / n


def section_chord(f, z):
    """Length of {x : f(x, 0, z) <= 0}: the 2D mode's joint length for twoDdir y."""
    return float(ray_lengths(f, z, np.array([[1.0, 0, 0], [-1.0, 0, 0]])).sum())


def make_scene(friction=PHI, damping=0.0, viscous=0.0, gravity=(0, 0, -G), **geometry):
    S = Scene()
    m = S.materials.append(FrictMat(density=RHO, frictionAngle=friction))
    S.engines = [ForceResetter(), InsertionSortCollider([PotentialParticle2AABB()], verletDist=0.01),
                 InteractionLoop([Ig2_PP_PP_ScGeom(calContactArea=True, **geometry)],
                                 [Ip2_FrictMat_FrictMat_KnKsPhys(Knormal=KN, Kshear=KS, viscousDamping=viscous)],
                                 [Law2_SCG_KnKsPhys_KnKsLaw()]),
                 NewtonIntegrator(gravity=gravity, damping=damping)]
    S.dt = 2e-4
    return S, m


def pressing(overlaps, width=None):
    """Rows (twist, overlap, overlap found, force, analytic force, area, reference area); with
    `width`, in 2D mode (unitWidth2D = width, twoDdir y): the reference area is width times
    the overlap's chord along x through the contact point."""
    geometry = {} if width is None else dict(twoDimension=True, unitWidth2D=width, twoDdir=(0, 1, 0))
    s = face_centre(CUBE)
    rows = []
    for twist in (0.0, math.pi / 4):
        c, sn = math.cos(twist), math.sin(twist)
        rot = np.array([[c, -sn, 0], [sn, c, 0], [0, 0, 1]])
        for u in overlaps:
            S, m = make_scene(gravity=(0, 0, 0), **geometry)
            S.bodies.append(potentialParticle(CUBE, pos=(0, 0, 0), material=m, fixed=True))
            S.bodies.append(potentialParticle(CUBE, pos=(0, 0, 2 * s - u), orientation=(math.cos(twist / 2), 0, 0,
                                                                                         math.sin(twist / 2)),
                                              material=m, fixed=True))
            S.run(1, True)
            c0 = S._cpp.contacts()[0]
            area = _dem.contact_areas(S._cpp)[0]
            zc = s - u / 2
            both = lambda p: np.maximum(potential(CUBE, p), potential(CUBE, p - np.array([0, 0, 2 * s - u]), rot))
            ref = section_area(both, zc) if width is None else width * section_chord(both, zc)
            rows.append((twist, u, float(c0["penetrationDepth"]), float(c0["normalForce"][2]), KN * ref * u, area, ref))
    return rows


def resting(seconds):
    S, m = make_scene(damping=0.3, viscous=0.5)
    S.bodies.append(wall(0, axis=2, sense=1, material=m))
    i = S.bodies.append(potentialParticle(CUBE, pos=(0, 0, face_centre(CUBE) + 1e-4), material=m))
    return (S, i, *restingForce(S, seconds))


def incline(theta, seconds):
    """A flat block resting on a wall, gravity turned to theta over 0.25 s with Cundall damping,
    then `seconds` undamped: (displacement along the slope, acceleration fitted to the free
    phase)."""
    block = PotentialParticle.cuboid((HALF, HALF, HALF / 2), r=R_ROUND, k=K_SPH)
    S, m = make_scene(damping=0.3, viscous=0.5)
    S.bodies.append(wall(0, axis=2, sense=1, material=m))
    i = S.bodies.append(potentialParticle(block, pos=(0, 0, face_centre(block) + 1e-4), material=m))
    S.run(2500, True)
    newton = S.engines[-1]
    rampGravity(S, newton, lambda f: tilted(G, f * theta), 0.25)
    newton.damping = 0.0
    # Displacement counted from the end of the ramp: the shear spring (and the small rocking of
    # the bulged face) loads during the ramp, a few mm at Kshear A ~ 1e6 N/m.
    times, moved = slide(S, i, seconds)
    return float(moved[-1]), fittedAcceleration(times, moved)


def shapes_for_yade(box, height):
    """Planes and Talus's volume and principal inertia (per density) of every shape the twin
    scenario uses."""
    t = 0.5
    out = {}
    for name, half, k in [("cube", (HALF, HALF, HALF), K_SPH), ("plate", (3.0, 3.0, 0.25), 0.1),
                          ("floor", (box / 2 + t, t / 2, box / 2 + t), 0.1), ("side_x", (t / 2, height / 2, box / 2 + t), 0.1),
                          ("side_z", (box / 2 + t, height / 2, t / 2), 0.1)]:
        r = R_ROUND if name == "cube" else 0.1 * t
        R = math.sqrt(sum(h * h for h in half)) if name == "cube" else 0.5 * max(half)
        shape = PotentialParticle.cuboid(half, r=r, k=k, R=R)
        p = shape.properties()
        out[name] = dict(d=shape.d, r=r, k=k, R=R, volume=p["volume"], inertia=list(map(float, p["inertiaPerDensity"])),
                         half=[face_centre(shape, a) for a in range(3)])
    return out


def main():
    args = results.case_arguments(__doc__).parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    case = results.Case("dem.potential-particles", quick=args.quick, folder=args.results)

    overlaps = list(np.logspace(-5, -2, 4 if args.quick else 7))
    rows = pressing(overlaps)
    overlap_error = max(abs(found - u) / u for _, u, found, *_ in rows)
    force_error = max(abs(f - ref) / ref for *_, f, ref, _, _ in rows)
    print(f"pressing: worst overlap error {overlap_error:.2e}, worst force error {force_error:.2e}")
    case.record("worst relative error of the overlap of two cubes pressed face to face", overlap_error,
                "2 s - D, s the face centre's distance from the centre", 1e-8, suffix="pressing-overlap",
                overlaps=[r[1] for r in rows], found=[r[2] for r in rows])
    case.record("worst relative error of the normal force of two cubes pressed face to face", force_error,
                "Knormal A u_n, A the overlap's mid-plane section integrated in numpy (720 rays)", 2e-3,
                suffix="pressing", forces=[r[3] for r in rows], analytic=[r[4] for r in rows],
                areas=[r[5] for r in rows], reference_areas=[r[6] for r in rows], twists=[r[0] for r in rows])

    rows2d = pressing(overlaps, width=0.5)
    force_2d_error = max(abs(f - ref) / ref for *_, f, ref, _, _ in rows2d)
    print(f"pressing 2D: worst force error {force_2d_error:.2e} against Knormal L w u_n")
    case.record("worst relative error of the normal force of two cubes pressed face to face in 2D mode", force_2d_error,
                "Knormal L unitWidth2D u_n, L the overlap's chord along x through the contact point (numpy bisection)",
                1e-6, suffix="pressing-2d", forces=[r[3] for r in rows2d], analytic=[r[4] for r in rows2d],
                areas=[r[5] for r in rows2d], reference_areas=[r[6] for r in rows2d], unitWidth2D=0.5,
                twists=[r[0] for r in rows2d])

    S, i, times, forces = resting(1.0)
    weight = float(S._cpp.mass()[i]) * G
    rest_error = abs(forces[-1] - weight) / weight
    print(f"resting: contact force {forces[-1]:.6f} N, m g = {weight:.6f} N, error {rest_error:.2e}")
    case.record("relative error of the resting cube's contact force", rest_error, "the weight m g", 1e-6,
                suffix="resting", force=forces[-1], weight=weight)

    T = 0.5 if args.quick else 1.0
    thetas = [25, 29, 31, 35] if args.quick else [20, 25, 28, 29, 31, 32, 35, 40]
    sweep = inclineSweep(incline, thetas, T, G, PHI)
    case.record("worst relative error of the sliding acceleration above the friction angle (30 deg)", sweep["slip"],
                "g (sin theta - cos theta tan phi)", 1e-2, suffix="incline-slip", thetas_deg=thetas,
                accelerations=sweep["accelerations"], analytic=sweep["analytic"], moved=sweep["moved"], T=T)
    case.record("largest displacement (m) along the slope below the friction angle, after the ramp", sweep["stick"],
                "no sliding: the undamped elastic oscillation only (m g sin theta / (Kshear A) ~ 2.5 mm, "
                "A ~ 0.14 m^2 on the bulged face)", 5e-3, suffix="incline-stick", thetas_deg=thetas,
                moved=sweep["moved"])

    yade = None
    if twin.yade_available():
        yade = side_by_side(case, args.quick)
    else:
        print("yade is not installed: no side-by-side run")

    fig, axes = plt.subplots(1, 4, figsize=(20, 4.2))
    ax1, ax2, ax3, ax4 = axes
    for twist, style in [(0.0, "bo"), (math.pi / 4, "gs")]:
        sel = [r for r in rows if r[0] == twist]
        ax1.loglog([r[1] for r in sel], [r[3] for r in sel], style, label=f"Talus, twist {math.degrees(twist):.0f} deg")
        ax1.loglog([r[1] for r in sel], [r[4] for r in sel], "k-", lw=0.8)
    if yade:
        ax1.loglog(yade["overlaps"], yade["forces"], "rx", ms=9, label="Yade (same input)")
    ax1.set_xlabel("overlap (m)")
    ax1.set_ylabel("normal force (N)")
    ax1.set_title("two PP cubes pressed (line: Knormal A u_n)")
    ax1.legend(fontsize=8)
    ax2.plot(times, forces, "b-", label="Talus, cube on a wall")
    ax2.axhline(weight, color="k", lw=0.8, ls="--", label="m g")
    if yade:
        ax2.plot(yade["rest_times"], yade["rest_yade"], "r--", label="Yade, on a boundary plate")
        ax2.plot(yade["rest_times"], yade["rest_talus"], "c:", label="Talus, on a boundary plate")
    ax2.set_xlabel("time (s)")
    ax2.set_ylabel("normal force (N)")
    ax2.set_title("cube resting under gravity")
    ax2.legend(fontsize=8)
    plotInclineSweep(ax3, thetas, sweep, G, PHI, "Talus", "PP block on an inclined wall")
    if yade:
        labels = ["porosity", "coordination", "us per contact-step"]
        x = np.arange(3)
        ax4.bar(x - 0.2, yade["pack_talus"], 0.4, label="Talus")
        ax4.bar(x + 0.2, yade["pack_yade"], 0.4, label="Yade")
        ax4.set_xticks(x, labels)
        ax4.set_yscale("log")
        ax4.set_title("packing of PP cubes settled in a box")
        ax4.legend(fontsize=8)
    fig.tight_layout()
    case.save_chart(fig)


def side_by_side(case, quick):
    out = {}
    box, height = 4.0, 8.0
    shapes = shapes_for_yade(box, height)
    s = face_centre(CUBE)
    overlaps = [1e-4, 1e-3, 1e-2]
    diffs_u, diffs_f, forces = [], [], []
    for u in overlaps:
        params = dict(mode="pressing", D=2 * s - u, shapes=shapes, Knormal=KN, Kshear=KS)
        ours, theirs = twin.run(SCENARIO, params, "talus"), twin.run(SCENARIO, params, "yade")
        a, b = ours["contacts"][0], theirs["contacts"][0]
        diffs_u.append(abs(a["penetrationDepth"] - b["penetrationDepth"]) / b["penetrationDepth"])
        diffs_f.append(abs(a["normalForce"][2] - b["normalForce"][2]) / abs(b["normalForce"][2]))
        forces.append(abs(b["normalForce"][2]))
        print(f"Yade pressing u={u:.0e}: overlap Talus {a['penetrationDepth']:.6e} Yade {b['penetrationDepth']:.6e}; "
              f"area {a['contactArea']:.5e} / {b['contactArea']:.5e}; force {a['normalForce'][2]:.5e} / "
              f"{b['normalForce'][2]:.5e}")
    out["overlaps"], out["forces"] = overlaps, forces
    case.record("largest relative difference of the contact force of two pressed cubes from Yade's", max(diffs_f),
                "Yade's Ig2_PP_PP_ScGeom + KnKsLaw on the same input", 0.05, suffix="yade-pressing",
                overlap_differences=diffs_u, force_differences=diffs_f, overlaps=overlaps)

    # 2D mode: both programs' contact area is the joint length times unitWidth2D.
    diffs_a = []
    for u in overlaps:
        params = dict(mode="pressing", D=2 * s - u, shapes=shapes, Knormal=KN, Kshear=KS, twoDimension=True,
                      unitWidth2D=0.5)
        a, b = twin.run(SCENARIO, params, "talus")["contacts"][0], twin.run(SCENARIO, params, "yade")["contacts"][0]
        diffs_a.append(abs(a["contactArea"] - b["contactArea"]) / b["contactArea"])
        print(f"Yade pressing 2D u={u:.0e}: area (joint length x 0.5) Talus {a['contactArea']:.12e} "
              f"Yade {b['contactArea']:.12e}")
    case.record("largest relative difference of the 2D contact area (joint length x unitWidth2D) of two pressed "
                "cubes from Yade's", max(diffs_a), "Yade's Ig2_PP_PP_ScGeom(twoDimension=True) on the same input",
                1e-6, suffix="yade-pressing-2d", area_differences=diffs_a, overlaps=overlaps, unitWidth2D=0.5)

    steps = 5000 if quick else 10000
    params = dict(mode="resting", shapes=shapes, steps=steps, dt=2e-4, Knormal=KN, Kshear=KS)
    ours, theirs = twin.run(SCENARIO, params, "talus"), twin.run(SCENARIO, params, "yade")
    a, b = ours["contacts"][0], theirs["contacts"][0]
    du = abs(a["penetrationDepth"] - b["penetrationDepth"]) / b["penetrationDepth"]
    df = abs(a["normalForce"][2] - b["normalForce"][2]) / abs(b["normalForce"][2])
    print(f"Yade resting: force Talus {a['normalForce'][2]:.6f} Yade {b['normalForce'][2]:.6f}; overlap Talus "
          f"{a['penetrationDepth']:.6e} Yade {b['penetrationDepth']:.6e}; area {a['contactArea']:.5e} / {b['contactArea']:.5e}")
    case.record("relative difference of the resting cube's overlap from Yade's", du,
                "Yade on the same input (cube on a boundary PP plate)", 0.05, suffix="yade-resting",
                force_difference=df, talus=a, yade=b)
    out["rest_times"] = [0.02 * (k + 1) for k in range(len(ours["history"]))]
    out["rest_talus"], out["rest_yade"] = ours["history"], theirs["history"]

    # Yade's particle contact costs tens to hundreds of times Talus's (docs/blocks.md, "Cost"):
    # a small packing, so that Yade's side stays short; 100 timed steps, so that Talus's side
    # lasts longer than a time slice.
    n, per_row = (8, 2) if quick else (27, 3)
    params = dict(mode="packing", shapes=shapes, n=n, perRow=per_row, spacing=1.3, box=box, height=height,
                  dt=5e-4, steps=2500 if quick else 4000, timedSteps=100, seed=7, Knormal=KN, Kshear=KS)
    ours, theirs = twin.run(SCENARIO, params, "talus"), twin.run(SCENARIO, params, "yade")
    V = shapes["cube"]["volume"]

    def porosity(r):
        top = max(p[1] for p in r["positions"]) + s
        return 1 - n * V / (box * box * top)

    def coordination(r):
        return (2 * r["particleContacts"] + r["wallContacts"]) / n

    pt, py = porosity(ours), porosity(theirs)
    ct, cy = coordination(ours), coordination(theirs)
    cost_t = ours["stepSeconds"] / max(ours["realAfter"], 1)
    cost_y = theirs["stepSeconds"] / max(theirs["realAfter"], 1)
    print(f"Yade packing: porosity Talus {pt:.4f} Yade {py:.4f}; coordination Talus {ct:.3f} Yade {cy:.3f}; "
          f"contacts {ours['realAfter']} / {theirs['realAfter']}; step per contact {cost_t * 1e6:.2f} us / "
          f"{cost_y * 1e6:.2f} us (ratio {cost_y / cost_t:.1f})")
    case.record("absolute difference of the settled packing's porosity from Yade's", abs(pt - py),
                "Yade's run of the same packing (cubePPscaled.py style)", 0.05, suffix="yade-packing",
                porosity_talus=pt, porosity_yade=py, coordination_talus=ct, coordination_yade=cy, n=n)
    case.record("Yade's step time per contact over Talus's (contact geometry of a fixed packing)", cost_y / cost_t,
                "Yade 2023.02a, one thread, same packing and engines", 3.0, comparison=">=", suffix="yade-cost",
                talus_seconds_per_contact=cost_t, yade_seconds_per_contact=cost_y,
                contacts_talus=ours["realAfter"], contacts_yade=theirs["realAfter"])
    out["pack_talus"] = [pt, ct, cost_t * 1e6]
    out["pack_yade"] = [py, cy, cost_y * 1e6]
    return out


if __name__ == "__main__":
    main()
