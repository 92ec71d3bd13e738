"""DEM case: Potential Blocks (Yade's PotentialBlock) against analytic contact forces and friction.

Run:      build/bin/talus run cases/dem/dem_potential_blocks.py [--quick] [--results DIR]
Set-up:   unit cubes (edge 1 m, r = 0.02 m, density 1000 kg/m^3) with the KnKsPB law
          (Knormal 1e8 N/m^3, Kshear 1e7 N/m^3; kn_i, ks_i the same for the boundary plate):
          1. pressing: two fixed cubes face to face, overlaps 1e-5 ... 1e-2 m, lateral offsets
             (0, 0), (0.2, 0.1), (0.4, 0.3) m and a 45-degree twist about the normal; one step;
          2. resting: a cube dropped 1 mm onto a fixed boundary plate under gravity (viscous
             damping 0.5, Cundall damping 0.3), 2 s (quick 1 s);
          3. incline: the resting cube (friction angle 30 deg) under gravity turned from the
             plate's normal to theta (an inclined plane) over 0.25 s with Cundall damping 0.3,
             then T = 1 s (quick 0.5 s) undamped, for theta = 20 ... 40 deg;
          2b. resting in 2D (Ig2_PB_PB_ScGeom twoDimension=True, unitWidth2D = 0.5): a prism
             1 m wide (x) and 6 m long along twoDdir = y, dropped 1 mm onto the plate;
          4. plane failure: a 4 x 2 x 2 m block cut by one persistent joint dipping 35 deg
             (generateBlocks), the lower piece fixed, friction angle phi = 31 ... 39 deg, Knormal
             1e9 N/m^3, Kshear 1e8 N/m^3; gravity
             ramped up over 0.25 s with Cundall damping, then 0.5 s undamped;
          5. rock bridge: the same block and joint dip, phi = 30 deg, but the joint's trace
             (half-length 0.872 m along its dip line from the block's centre) covers half of the
             section (6.97 m^2): the rest is a rock bridge of cohesion c (generateBlocks'
             rockCohesion), bonded by Ip2_FrictMat_FrictMat_KnKsPBPhys(useFaceProperties=True)
             with allowBreakage; c = 0.8 and 1.25 times the hand-computed critical cohesion
             c* = W (sin psi - cos psi tan phi) / A_bridge (W the upper piece's weight).
          Yade's Debian build has no PotentialBlock (its ENABLE_POTENTIAL_BLOCKS is off), so no
          side-by-side run: references are analytic.
Checked:  dem.potential-blocks.pressing: worst relative error of the normal force against
          Knormal A u_n (A the exact overlap area: offset rectangle, or the octagon 2(sqrt 2 - 1)
          of the twisted squares) <= 1e-8, and of the overlap against u_n (in the record);
          dem.potential-blocks.resting: relative error of the contact force against m g <= 1e-6;
          dem.potential-blocks.resting-2d: relative error of the prism's overlap against
          m g / (Knormal L w), the seed's 2D area being the joint length L = 1 m times
          unitWidth2D w (in 3D the section would be 6 m^2), <= 1e-4;
          dem.potential-blocks.incline-slip: worst relative error of the sliding acceleration
          (quadratic fit of the undamped phase) against g (sin theta - cos theta tan phi) above
          the friction angle <= 1e-2; dem.potential-blocks.incline-stick: largest displacement
          along the slope below it (elastic shear only, ~0.5 mm) <= 1 mm;
          dem.potential-blocks.plane-failure: worst relative error of the upper piece's
          acceleration for FS = tan phi / tan psi < 1, plus the number of wrong slide/stick
          outcomes (displacement > 1 mm), <= 1e-2;
          dem.potential-blocks.rock-bridge: the same measure for the bridged joint (holds at
          1.25 c*, breaks and slides by friction at 0.8 c*, acceleration against
          g (sin psi - cos psi tan phi)), <= 1e-2.
Produces: the seven records and chart dem.potential-blocks.png (force against analytic, the
          resting cube's contact force over time, sliding acceleration against theta and against
          the factor of safety of the plane failure).
"""
import math

import numpy as np

from talus import _dem, results
from talus.dem import (ForceResetter, FrictMat, Ig2_PB_PB_ScGeom, InsertionSortCollider, InteractionLoop,
                       Ip2_FrictMat_FrictMat_KnKsPBPhys, Joint, Law2_SCG_KnKsPBPhys_KnKsPBLaw, NewtonIntegrator,
                       PotentialBlock, PotentialBlock2AABB, Scene, generateBlocks, potentialBlock)
from talus.dem.geometry.blockgen import dipNormal
from talus.dem.analysis.sliding import (coulombAcceleration, fittedAcceleration, inclineSweep, plotInclineSweep, rampGravity,
                               restingForce, slide, tilted)

KN, KS, RHO, G, PHI = 1e8, 1e7, 1000.0, 9.81, math.radians(30)
CUBE = PotentialBlock.cuboid((0.5, 0.5, 0.5), r=0.02)
MASS = RHO * 1.0


def make_scene(friction=PHI, damping=0.0, viscous=0.0, gravity=(0, 0, -G), kn=KN, ks=KS, bonds=False, **geometry):
    """A scene with the KnKsPB law; `bonds`: intact-rock faces are bonded (useFaceProperties)
    by the contacts made until the Ip2's cohesionBroken is set back to True, and break."""
    S = Scene()
    m = S.materials.append(FrictMat(density=RHO, frictionAngle=friction))
    bond = dict(useFaceProperties=True, cohesionBroken=False, tensionBroken=False) if bonds else {}
    S.engines = [ForceResetter(), InsertionSortCollider([PotentialBlock2AABB()], verletDist=0.01),
                 InteractionLoop([Ig2_PB_PB_ScGeom(calContactArea=True, **geometry)],
                                 [Ip2_FrictMat_FrictMat_KnKsPBPhys(Knormal=kn, Kshear=ks, kn_i=kn, ks_i=ks,
                                                                   viscousDamping=viscous, **bond)],
                                 [Law2_SCG_KnKsPBPhys_KnKsPBLaw(allowBreakage=bonds)]),
                 NewtonIntegrator(gravity=gravity, damping=damping)]
    S.dt = 5e-4
    return S, m


def quat_z(angle):
    return (math.cos(angle / 2), 0.0, 0.0, math.sin(angle / 2))


def pressing():
    """Rows (overlap, area, force, analytic force, overlap found)."""
    rows = []
    for ox, oy, twist, area in [(0, 0, 0, 1.0), (0.2, 0.1, 0, 0.8 * 0.9), (0.4, 0.3, 0, 0.6 * 0.7),
                                (0, 0, math.pi / 4, 2 * (math.sqrt(2) - 1))]:
        for u in np.logspace(-5, -2, 7):
            S, m = make_scene(gravity=(0, 0, 0))
            S.bodies.append(potentialBlock(CUBE, pos=(0, 0, 0), material=m, fixed=True))
            S.bodies.append(potentialBlock(CUBE, pos=(ox, oy, 1 - u), orientation=quat_z(twist), material=m, fixed=True))
            S.run(1, True)
            c = S._cpp.contacts()[0]
            rows.append((u, area, float(c["normalForce"][2]), KN * area * u, float(c["penetrationDepth"])))
    return rows


def plate(m):
    """The fixed boundary plate, top face at z = 0."""
    return potentialBlock(PotentialBlock.cuboid((3, 4, 0.25), r=0.02, isBoundary=True), pos=(0, 0, -0.25), material=m,
                          fixed=True)


def resting(seconds):
    S, m = make_scene(damping=0.3, viscous=0.5)
    S.bodies.append(plate(m))
    S.bodies.append(potentialBlock(CUBE, pos=(0, 0, 0.501), material=m))
    return (S, *restingForce(S, seconds))


def resting_2d(seconds, width):
    """The 2D prism at rest on the plate: (contact force, overlap, area, mass)."""
    S, m = make_scene(damping=0.3, viscous=0.5, twoDimension=True, unitWidth2D=width)
    S.bodies.append(plate(m))
    prism = S.bodies.append(potentialBlock(PotentialBlock.cuboid((0.5, 3.0, 0.5), r=0.02), pos=(0, 0, 0.501),
                                           material=m))
    S.run(int(seconds / S.dt), True)
    c = S._cpp.contacts()[0]
    return float(c["normalForce"][2]), float(c["penetrationDepth"]), _dem.contact_areas(S._cpp)[0], S._cpp.mass()[prism]


def incline(theta, seconds):
    """The resting cube under gravity turned from the plate's normal to theta over 0.25 s (with
    Cundall damping, so the shear spring loads quasi-statically), then `seconds` undamped.
    Returns (displacement along the slope since the start, acceleration fitted to the free
    phase)."""
    S, _, _ = resting(0.5)
    start = float(S.bodies[1].state.pos[0])
    newton = S.engines[-1]
    rampGravity(S, newton, lambda f: tilted(G, f * theta), 0.25)
    newton.damping = 0.0
    times, moved = slide(S, 1, seconds)
    return float(S.bodies[1].state.pos[0]) - start, fittedAcceleration(times, moved)


PSI = math.radians(35)   # dip of the joint of the plane-failure test


# The rock-bridge variant: the joint's trace, half-length BRIDGE_TRACE along its dip line from
# the block's centre, covers half of the section (2 m x 2 / sin psi), the rest is rock bridge.
SECTION = 2.0 * 2.0 / math.sin(PSI)
BRIDGE_TRACE = 0.5 / math.sin(PSI)
BRIDGE_AREA = 0.5 * SECTION


def plane_failure(phi_deg, seconds, trace=math.inf, rockCohesion=0.0):
    """A 4 x 2 x 2 m rock block cut by one joint dipping at PSI (generateBlocks; `trace`: its
    half-length along the dip line, the rest of the cut being a rock bridge of cohesion
    `rockCohesion`, bonded); the piece below is fixed, the one above rests on the joint. Gravity
    ramped up over 0.25 s with Cundall damping (the joint's shear spring loads quasi-statically),
    then `seconds` undamped.
    Returns (displacement down the dip since the ramp, acceleration fitted to its second half)."""
    joint = Joint(dipNormal(35, 0), np.zeros(3), traceY=trace)
    blocks = generateBlocks(PotentialBlock.cuboid((2, 1, 1), r=0.02), [joint], rockCohesion=rockCohesion)
    # Stiffer joint (1e9 N/m^3): the acceleration's error is first order in the contact's
    # compliance (1.8 %, 0.3 %, 0.09 % at Knormal 1e8, 1e9, 1e10 for phi = 33 deg).
    S, m = make_scene(friction=math.radians(phi_deg), damping=0.3, viscous=0.5, gravity=(0, 0, 0), kn=10 * KN,
                      ks=10 * KS, bonds=rockCohesion > 0)
    ids = S.bodies.append([potentialBlock(b, material=m) for b in blocks])
    low, up = sorted(ids, key=lambda i: S.bodies[i].state.pos[2])
    S.bodies[low].dynamic = False
    newton = S.engines[-1]
    rampGravity(S, newton, lambda f: (0.0, 0.0, -G * f), 0.25)
    phys = S.engines[2].physFunctors[0]
    phys.cohesionBroken = phys.tensionBroken = True   # only the cut is bonded; later contacts are frictional
    newton.damping = 0.0
    times, moved = slide(S, up, seconds, direction=(-math.cos(PSI), 0.0, -math.sin(PSI)))
    half = len(times) // 2   # after the release transient (the block slid during the ramp already)
    return float(moved[-1]), fittedAcceleration(times[half:], moved[half:])


def main():
    args = results.case_arguments(__doc__).parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    case = results.Case("dem.potential-blocks", quick=args.quick, folder=args.results)

    rows = pressing()
    force_error = max(abs(f - ref) / ref for _, _, f, ref, _ in rows)
    overlap_error = max(abs(found - u) / u for u, _, _, _, found in rows)
    print(f"pressing: worst force error {force_error:.2e}, worst overlap error {overlap_error:.2e}")
    case.record("worst relative error of the normal force of two cubes pressed face to face", force_error,
                "Knormal A u_n with the exact overlap area A (rectangle, or octagon for the 45-degree twist)", 1e-8,
                suffix="pressing", overlap_relative_error=overlap_error, overlaps=[r[0] for r in rows],
                areas=[r[1] for r in rows], forces=[r[2] for r in rows])

    seconds = 1.0 if args.quick else 2.0
    _, times, forces = resting(seconds)
    rest_error = abs(forces[-1] - MASS * G) / (MASS * G)
    print(f"resting: contact force {forces[-1]:.6f} N, m g = {MASS * G:.6f} N, error {rest_error:.2e}")
    case.record("relative error of the resting cube's contact force", rest_error, "the weight m g", 1e-6,
                suffix="resting", force=forces[-1], weight=MASS * G)

    width = 0.5
    force, overlap, area, mass = resting_2d(seconds, width)
    expected = mass * G / (KN * 1.0 * width)
    overlap_2d_error = abs(overlap - expected) / expected
    print(f"resting 2D: overlap {overlap:.6e} m, m g / (Knormal L w) = {expected:.6e} m, error {overlap_2d_error:.2e}; "
          f"area {area:.6f} m^2 (L w = {width}), force error {abs(force - mass * G) / (mass * G):.2e}")
    case.record("relative error of the 2D prism's overlap at rest (contact area = joint length x unitWidth2D)",
                overlap_2d_error, "m g / (Knormal L unitWidth2D), L = 1 m the joint", 1e-4, suffix="resting-2d",
                overlap=overlap, area=area, force=force, weight=mass * G, unitWidth2D=width)

    T = 0.5 if args.quick else 1.0
    thetas = [20, 25, 28, 29, 31, 32, 35, 40] if not args.quick else [25, 29, 31, 35]
    sweep = inclineSweep(incline, thetas, T, G, PHI)
    case.record(f"worst relative error of the sliding acceleration above the friction angle ({math.degrees(PHI):.0f} deg)",
                sweep["slip"], "g (sin theta - cos theta tan phi)", 1e-2, suffix="incline-slip",
                thetas_deg=thetas, accelerations=sweep["accelerations"], analytic=sweep["analytic"],
                moved=sweep["moved"], T=T)
    case.record("largest displacement (m) along the slope below the friction angle", sweep["stick"],
                "no sliding: elastic shear only, m g sin theta / (Kshear A) ~ 5e-4 m", 1e-3, suffix="incline-stick",
                thetas_deg=thetas, moved=sweep["moved"])

    phis = [31, 33, 34, 36, 37, 39] if not args.quick else [33, 34, 36, 37]
    fs, pf_moved, pf_acc, pf_ref = [], [], [], []
    for deg in phis:
        # 0.5 s in both modes: the error grows with the distance slid (about 1 % after 0.48 m in
        # 1 s at phi = 31 deg): the single contact point at the overlap's centre lets the block
        # tilt as its support shifts, and the normal averaged between the faces tilts with it.
        s, a = plane_failure(deg, 0.5)
        fs.append(math.tan(math.radians(deg)) / math.tan(PSI))
        pf_moved.append(s)
        pf_acc.append(a)
        pf_ref.append(coulombAcceleration(G, PSI, math.radians(deg)))
        print(f"plane failure, joint dip 35 deg, phi {deg} deg (FS {fs[-1]:.3f}): moved {s:.6f} m, "
              f"acceleration {a:.5f} m/s^2, analytic {pf_ref[-1]:.5f}")
    wrong = sum((ref > 0) != (abs(s) > 1e-3) for s, ref in zip(pf_moved, pf_ref))
    pf_error = max(abs(a - ref) / ref for a, ref in zip(pf_acc, pf_ref) if ref > 0)
    case.record("worst relative error of the sliding acceleration of a block generated by a joint (FS < 1) "
                "plus the number of wrong slide/stick outcomes", pf_error + wrong,
                "g (sin psi - cos psi tan phi), psi = 35 deg; FS = tan phi / tan psi", 1e-2, suffix="plane-failure",
                phis_deg=phis, factor_of_safety=fs, moved=pf_moved, accelerations=pf_acc, analytic=pf_ref,
                wrong_outcomes=wrong)

    bridge_phi = math.radians(30)
    weight = RHO * 8.0 * G   # the upper half of the 4 x 2 x 2 m block
    slide = G * (math.sin(PSI) - math.cos(PSI) * math.tan(bridge_phi))
    c_critical = weight * (math.sin(PSI) - math.cos(PSI) * math.tan(bridge_phi)) / BRIDGE_AREA
    bridge_factors, bridge_moved, bridge_acc = [0.8, 1.25], [], []
    for factor in bridge_factors:
        s, a = plane_failure(30, 0.5, trace=BRIDGE_TRACE, rockCohesion=factor * c_critical)
        bridge_moved.append(s)
        bridge_acc.append(a)
        print(f"rock bridge, cohesion {factor} c* = {factor * c_critical:.1f} Pa: moved {s:.6f} m, acceleration "
              f"{a:.5f} m/s^2 (sliding by friction: {slide:.5f})")
    bridge_wrong = sum((f < 1) != (abs(s) > 1e-3) for f, s in zip(bridge_factors, bridge_moved))
    bridge_error = abs(bridge_acc[0] - slide) / slide
    case.record("relative error of the sliding acceleration once a rock bridge below its strength broke, plus the "
                "number of wrong hold/break outcomes", bridge_error + bridge_wrong,
                "c* = W (sin psi - cos psi tan phi) / A_bridge (hand-computed); after breaking "
                "g (sin psi - cos psi tan phi), psi = 35 deg, phi = 30 deg", 1e-2, suffix="rock-bridge",
                critical_cohesion=c_critical, bridge_area=BRIDGE_AREA, section_area=SECTION, weight=weight,
                cohesion_factors=bridge_factors, moved=bridge_moved, accelerations=bridge_acc, analytic=slide,
                wrong_outcomes=bridge_wrong)

    fig, (ax1, ax2, ax3, ax4) = plt.subplots(1, 4, figsize=(20, 4.2))
    ref = np.array([r[3] for r in rows])
    ax1.loglog(ref, [r[2] for r in rows], "bo", label="Talus")
    ax1.loglog(ref, ref, "k-", lw=0.8, label="Knormal A u_n")
    ax1.set_xlabel("analytic normal force (N)")
    ax1.set_ylabel("contact normal force (N)")
    ax1.set_title(f"two cubes pressed (worst error {force_error:.1e})")
    ax1.legend(fontsize=8)
    ax2.plot(times, forces, "b-", label="contact force")
    ax2.axhline(MASS * G, color="k", lw=0.8, ls="--", label="m g")
    ax2.set_xlabel("time (s)")
    ax2.set_ylabel("normal force (N)")
    ax2.set_title("cube resting on a boundary plate")
    ax2.legend(fontsize=8)
    plotInclineSweep(ax3, thetas, sweep, G, PHI, "Talus (fit of the free phase)", "block on an inclined plane")
    ax4.plot(fs, pf_ref, "k-", lw=0.8, label="g (sin psi - cos psi tan phi)")
    ax4.plot(fs, pf_acc, "bo", label="Talus")
    ax4.axvline(1.0, color="r", ls=":", label="FS = 1")
    ax4.set_xlabel("factor of safety tan phi / tan psi")
    ax4.set_ylabel("sliding acceleration (m/s^2)")
    ax4.set_title("plane failure on a generated joint (psi = 35 deg)")
    ax4.legend(fontsize=8)
    fig.tight_layout()
    case.save_chart(fig)


if __name__ == "__main__":
    main()
