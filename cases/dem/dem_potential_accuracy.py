"""DEM case: accuracy of the Potential Block and Potential Particle contact solvers against an
exact polyhedral overlap, and their cost, over the solvers' tolerance `accuracyTol`.

Run:      build/bin/talus run cases/dem/dem_potential_accuracy.py [--quick] [--results DIR]
Set-up:   two cubes of half-size 0.5 m in the configurations where contact solvers go wrong and
          in random ones: faces twisted 30 deg, a vertex into a face, crossed edges, an edge into
          a face, nearly parallel faces (tilted 1e-3 rad), and random orientations (quick 4,
          full 12); body 2 is moved along z (with a lateral offset) until the reference overlap
          is 1e-4, 1e-3 or 1e-2 m.
          Potential Blocks: d = 0.48, r = 0.02 (faces at d + r = 0.5). accuracyTol is the
          analytic centre's stopping Newton decrement (default 1e-10).
          Potential Particles: d = 0.48, r = 0.02, k = 1e-7 (a vanishing sphere term).
          accuracyTol is the tolerance on |f1 - f2| at the contact point (default 1e-8).
Reference (exact): the penetration depth delta* of the two shapes (the shortest translation of
          body 2 that separates them) and its direction n*:
          - Potential Blocks, the polyhedra P = {n_i . x <= d_i + r}: the distance from the origin
            to the surface of the Minkowski difference P2 - P1 (the convex hull of the vertex
            differences, scipy's Qhull), exact for convex polyhedra;
          - Potential Particles as k -> 0: {sum <n_i . x - d_i>^2 <= r^2}, for a cube (orthogonal
            planes) the inner cube {n_i . x <= d_i} dilated by a ball of radius r, whose overlap
            is the inner cubes' penetration depth + 2 r (2 r - their distance when apart): the
            rounded polyhedron, which tends to the polyhedron as r -> 0. The sphere term moves the
            surface by at most k r / 2 = 1e-9 m.
          Potential Blocks are run twice: as the seed defines their overlap (the default: the
          chord of the overlap region through its analytic centre along the normal, Yade's
          bracketed bisection), against that definition computed independently (the analytic
          centre of both cubes' half-spaces by Newton steps in numpy from scipy's HiGHS linear
          program, the chord along the solver's normal clipped against every plane); and with
          Ig2_PB_PB_ScGeom(exactDepth=True), against delta* and n*.
Measured: for each tolerance, the worst and median relative overlap error |delta - delta*| /
          delta*, the worst angle between the normal and n* (where n* is unique), the median
          solver time per contact (`seconds`: a new contact; `secondsWarm`: starting from the
          previous contact point) over `repeats` calls. Times are wall times on a shared machine.
Checked:  dem.potential-accuracy.blocks: worst relative error of the seed's chord at the
          default tolerance <= 1e-6 (the record also keeps how far that chord is from delta*:
          about half of it for edge-edge contacts and for the wedge between nearly parallel
          faces, and the angle of the seed's normal from n*);
          dem.potential-accuracy.blocks-depth and .blocks-normal: the exact-depth option's
          overlap error <= 1e-6 and normal angle <= 1e-6 rad;
          dem.potential-accuracy.particles: the same for particles <= 1e-4 (ten times the most
          the sphere term moves the surface, k r / 2, relative to the smallest overlap) and
          .particles-normal <= 1e-6 rad.
Produces: the records and chart dem.potential-accuracy.png.
"""
import math

import numpy as np
from scipy.optimize import linprog
from scipy.spatial import ConvexHull

from talus import results
from talus.dem import (FrictMat, Ig2_PB_PB_ScGeom, InteractionLoop, Ip2_FrictMat_FrictMat_KnKsPBPhys,
                       Law2_SCG_KnKsPBPhys_KnKsPBLaw, PotentialBlock, PotentialParticle, Quaternion, Scene,
                       blockContact, particleContact, potentialBlock, potentialParticle)
from talus import _dem

HALF, ROUND, K_SPHERE = 0.5, 0.02, 1e-7
OVERLAPS = (1e-4, 1e-3, 1e-2)
BLOCK_TOLERANCES = (1e-1, 1e-2, 1e-3, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12)
PARTICLE_TOLERANCES = (1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-8, 1e-10, 1e-13)
DEFAULT_BLOCK_TOL, DEFAULT_PARTICLE_TOL = 1e-10, 1e-8
CORNERS = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)], float)


def configurations(n_random):
    """(name, orientation of body 1, of body 2, lateral offset of body 2)."""
    diag = np.array([1, 1, 1]) / math.sqrt(3)
    axis = np.cross(diag, [0, 0, -1])
    vertex_down = Quaternion(axis / np.linalg.norm(axis), math.acos(-diag[2]))   # a unit axis, as Yade's Quaternion wants
    out = [("faces twisted 30 deg", Quaternion((0, 0, 1), 0), Quaternion((0, 0, 1), math.pi / 6), (0.1, 0.05)),
           ("nearly parallel faces", Quaternion((0, 0, 1), 0), Quaternion((1, 0.3, 0), 1e-3), (0.1, 0.05)),
           ("vertex into a face", Quaternion((0, 0, 1), 0), vertex_down, (0.1, 0.05)),
           ("crossed edges", Quaternion((1, 0, 0), math.pi / 4), Quaternion((0, 1, 0), math.pi / 4), (0.02, 0.03)),
           ("edge into a face", Quaternion((0, 0, 1), 0), Quaternion((1, 0, 0), math.pi / 4), (0.1, 0.05))]
    rng = np.random.default_rng(11)
    for k in range(n_random):
        q1, q2 = rng.normal(size=4), rng.normal(size=4)
        out.append((f"random {k}", q1 / np.linalg.norm(q1), q2 / np.linalg.norm(q2), tuple(rng.uniform(-0.2, 0.2, 2))))
    return out


def point_triangle(p, a, b, c):
    """Closest point of triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5)."""
    ab, ac, ap = b - a, c - a, p - a
    d1, d2 = ab @ ap, ac @ ap
    if d1 <= 0 and d2 <= 0:
        return a
    bp = p - b
    d3, d4 = ab @ bp, ac @ bp
    if d3 >= 0 and d4 <= d3:
        return b
    vc = d1 * d4 - d3 * d2
    if vc <= 0 and d1 >= 0 and d3 <= 0:
        return a + d1 / (d1 - d3) * ab
    cp = p - c
    d5, d6 = ab @ cp, ac @ cp
    if d6 >= 0 and d5 <= d6:
        return c
    vb = d5 * d2 - d1 * d6
    if vb <= 0 and d2 >= 0 and d6 <= 0:
        return a + d2 / (d2 - d6) * ac
    va = d3 * d6 - d5 * d4
    if va <= 0 and d4 - d3 >= 0 and d5 - d6 >= 0:
        return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b)
    den = 1 / (va + vb + vc)
    return a + ab * vb * den + ac * vc * den


def penetration(half, q1, q2, pos2):
    """Penetration depth of cube 2 (centre pos2) into cube 1 (at the origin), both of half-size
    `half`, negative for their distance when apart, and the direction from 1 to 2 that
    separates them fastest (None when several facets of the Minkowski difference tie)."""
    v1 = half * CORNERS @ Quaternion(q1).toRotationMatrix().T
    v2 = half * CORNERS @ Quaternion(q2).toRotationMatrix().T + pos2
    hull = ConvexHull((v2[:, None, :] - v1[None, :, :]).reshape(-1, 3))
    normals, offsets = hull.equations[:, :3], hull.equations[:, 3]   # n . x + offset <= 0 inside
    if np.all(offsets < 0):
        depth = -offsets
        k = int(np.argmin(depth))
        # The reference direction is unique unless another facet's plane is as near with a
        # different normal.
        ties = (depth - depth[k] <= 1e-9 * half) & (normals @ normals[k] < 1 - 1e-12)
        return depth[k], (None if ties.any() else -normals[k])
    points = hull.points
    nearest = min((point_triangle(np.zeros(3), *points[s]) for s in hull.simplices), key=np.linalg.norm)
    return -np.linalg.norm(nearest), nearest / np.linalg.norm(nearest)


def seed_chord(q1, q2, pos2, normal):
    """The seed's overlap of the two cubes: the chord of their intersection through its analytic
    centre (minimum of -sum log(h - N x)) along `normal`."""
    R1, R2 = Quaternion(q1).toRotationMatrix(), Quaternion(q2).toRotationMatrix()
    axes = np.vstack([np.eye(3), -np.eye(3)])
    N = np.vstack([axes @ R1.T, axes @ R2.T])
    h = np.concatenate([np.full(6, HALF), HALF + axes @ R2.T @ pos2])
    deepest = linprog([0, 0, 0, -1], A_ub=np.hstack([N, np.ones((12, 1))]), b_ub=h,
                      bounds=[(-4 * HALF, 4 * HALF)] * 3 + [(None, None)], method="highs")
    x = deepest.x[:3]
    for _ in range(200):    # Newton steps with backtracking, to the rounding
        inv = 1 / (h - N @ x)
        g, H = N.T @ inv, (N.T * inv ** 2) @ N
        dx = -np.linalg.solve(H, g)
        t = 1.0
        while np.min(h - N @ (x + t * dx)) <= 0:
            t /= 2
        x = x + t * dx
        if np.linalg.norm(t * dx) < 1e-16:
            break
    a, slack = N @ normal, h - N @ x
    return np.min(slack[a > 1e-14] / a[a > 1e-14]) - np.max(slack[a < -1e-14] / a[a < -1e-14])


def reference(kind, q1, q2, pos2):
    """Exact overlap and direction for the shapes of this case (see the docstring)."""
    if kind.startswith("block"):
        return penetration(HALF, q1, q2, pos2)
    inner, n = penetration(HALF - ROUND, q1, q2, pos2)
    return inner + 2 * ROUND, n


def place(kind, q1, q2, lateral, overlap):
    """Position of body 2 (lateral offset, height by bisection) whose reference overlap is
    `overlap`: the overlap decreases with the height (both shapes are centrally symmetric, so
    the depth in their Minkowski difference is largest at the centre)."""
    lo, hi = 0.0, 4 * HALF
    for _ in range(70):
        mid = 0.5 * (lo + hi)
        if reference(kind, q1, q2, np.array([*lateral, mid]))[0] > overlap:
            lo = mid
        else:
            hi = mid
    return np.array([*lateral, 0.5 * (lo + hi)])


def solve(kind, q1, q2, pos2, tolerances, repeats):
    """Rows (tolerance, overlap, normal, cold seconds, warm seconds) of one placement."""
    S = Scene()
    m = S.materials.append(FrictMat(density=1000))
    if kind.startswith("block"):
        shape = PotentialBlock.cuboid((HALF, HALF, HALF), r=ROUND)
        a = S.bodies.append(potentialBlock(shape, pos=(0, 0, 0), orientation=tuple(q1), material=m))
        b = S.bodies.append(potentialBlock(shape, pos=tuple(pos2), orientation=tuple(q2), material=m))
        S.engines = [InteractionLoop([Ig2_PB_PB_ScGeom(exactDepth=kind == "block-depth")],
                                     [Ip2_FrictMat_FrictMat_KnKsPBPhys()], [Law2_SCG_KnKsPBPhys_KnKsPBLaw()])]
        probe = blockContact
    else:
        shape = PotentialParticle.cuboid((HALF, HALF, HALF), r=ROUND, k=K_SPHERE)
        a = S.bodies.append(potentialParticle(shape, pos=(0, 0, 0), orientation=tuple(q1), material=m))
        b = S.bodies.append(potentialParticle(shape, pos=tuple(pos2), orientation=tuple(q2), material=m))
        probe = particleContact
    rows = []
    for tol in tolerances:
        g = probe(S, a, b, repeats, accuracyTol=tol)
        if not g["touching"]:
            rows.append((tol, 0.0, None, g["seconds"], g["seconds"]))
            continue
        rows.append((tol, float(g["penetrationDepth"]), np.asarray(g["normal"], float), g["seconds"], g["secondsWarm"]))
    return rows


def sweep(kind, configs, tolerances, repeats):
    """Per tolerance: worst and median relative overlap error, worst normal angle, median cold
    and warm time; and the worst case's name at the default tolerance. For the seed's chord
    ("block"), the error is against the chord computed independently, and the chord's distance
    from the exact depth and the normal's angle from n* are kept as `depth_*`."""
    errors, angles, cold, warm, depth_errors = ({t: [] for t in tolerances} for _ in range(5))
    cases = []
    for name, q1, q2, lateral in configs:
        for overlap in OVERLAPS:
            pos2 = place(kind, q1, q2, lateral, overlap)
            exact, direction = reference(kind, q1, q2, pos2)
            for tol, found, normal, seconds, seconds_warm in solve(kind, q1, q2, pos2, tolerances, repeats):
                target = seed_chord(q1, q2, pos2, normal) if kind == "block" and normal is not None else exact
                errors[tol].append(abs(found - target) / target)
                depth_errors[tol].append(abs(found - exact) / exact)
                if normal is not None and direction is not None:
                    angles[tol].append(math.acos(min(1.0, float(normal @ direction))))
                cold[tol].append(seconds)
                warm[tol].append(seconds_warm)
                cases.append((tol, name, overlap, abs(found - target) / target))
    summary = [dict(tol=t, worst=max(errors[t]), median=float(np.median(errors[t])),
                    worst_angle=max(angles[t]) if angles[t] else 0.0, cold_s=float(np.median(cold[t])),
                    warm_s=float(np.median(warm[t])), depth_worst=max(depth_errors[t]),
                    depth_median=float(np.median(depth_errors[t]))) for t in tolerances]
    return summary, cases


def main():
    args = results.case_arguments(__doc__).parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    case = results.Case("dem.potential-accuracy", quick=args.quick, folder=args.results)
    configs = configurations(4 if args.quick else 12)
    repeats = 20 if args.quick else 100
    out = {}
    for kind, label, tolerances, default, bound, angle_bound in [
            ("block", "blocks", BLOCK_TOLERANCES, DEFAULT_BLOCK_TOL, 1e-6, None),
            ("block-depth", "blocks-depth", BLOCK_TOLERANCES, DEFAULT_BLOCK_TOL, 1e-6, 1e-6),
            ("particle", "particles", PARTICLE_TOLERANCES, DEFAULT_PARTICLE_TOL, 1e-4, 1e-6)]:
        if kind.startswith("block") and not _dem.have_potential_blocks:
            print("built without CLP: no Potential Blocks")
            continue
        summary, cases = sweep(kind, configs, tolerances, repeats)
        out[kind] = summary
        for row in summary:
            print(f"{label} accuracyTol {row['tol']:.0e}: overlap error worst {row['worst']:.2e} median "
                  f"{row['median']:.2e} (against the depth: worst {row['depth_worst']:.2e} median "
                  f"{row['depth_median']:.2e}), normal angle worst {row['worst_angle']:.2e} rad, time per contact "
                  f"cold {row['cold_s'] * 1e6:.1f} us warm {row['warm_s'] * 1e6:.1f} us")
        at_default = next(r for r in summary if r["tol"] == default)
        worst = max((c for c in cases if c[0] == default), key=lambda c: c[3])
        print(f"{label}: worst case at the default tolerance: {worst[1]}, overlap {worst[2]:.0e} m, error {worst[3]:.2e}")
        common = dict(accuracyTol=default, worst_configuration=worst[1], worst_overlap=worst[2], sweep=summary,
                      configurations=[c[0] for c in configs], overlaps=list(OVERLAPS))
        if kind == "block":
            case.record("worst relative error of the Potential Blocks' overlap (the seed's chord, the default) at "
                        "its default tolerance", at_default["worst"],
                        "the chord through the exact analytic centre of the overlap region along the normal", bound,
                        suffix=label, chord_against_depth_worst=at_default["depth_worst"],
                        chord_against_depth_median=at_default["depth_median"],
                        seed_normal_worst_angle=at_default["worst_angle"], **common)
            continue
        case.record(f"worst relative overlap error of the {label}' contact solver at its default tolerance",
                    at_default["worst"], "exact penetration depth of the (rounded) polyhedra, Minkowski difference",
                    bound, suffix=label, **common)
        case.record(f"worst angle (rad) of the {label}' contact normal from the exact separating direction",
                    at_default["worst_angle"], "direction of the exact penetration depth (where unique)", angle_bound,
                    suffix="blocks-normal" if kind == "block-depth" else f"{label}-normal", accuracyTol=default)

    fig, axes = plt.subplots(1, 3, figsize=(16, 4.6))
    styles = {"block": ("tab:blue", "Potential Blocks (seed's chord vs its exact value)"),
              "block-depth": ("tab:green", "Potential Blocks, exactDepth"), "particle": ("tab:red", "Potential Particles")}
    for kind, summary in out.items():
        colour, label = styles[kind]
        tol = [r["tol"] for r in summary]
        axes[0].loglog(tol, [max(r["worst"], 1e-17) for r in summary], "o-", color=colour, label=f"{label}: worst")
        axes[0].loglog(tol, [max(r["median"], 1e-17) for r in summary], "s--", color=colour, label=f"{label}: median")
        axes[1].loglog([r["warm_s"] * 1e6 for r in summary], [max(r["worst"], 1e-17) for r in summary], "o-",
                       color=colour, label=f"{label}: warm start")
        axes[1].loglog([r["cold_s"] * 1e6 for r in summary], [max(r["worst"], 1e-17) for r in summary], "^:",
                       color=colour, label=f"{label}: new contact")
        for r in summary:
            axes[1].annotate(f"{r['tol']:.0e}", (r["warm_s"] * 1e6, max(r["worst"], 1e-17)), fontsize=6)
        axes[2].loglog(tol, [max(r["worst_angle"], 1e-17) for r in summary], "o-", color=colour, label=label)
    axes[0].set_xlabel("accuracyTol")
    axes[0].set_ylabel("relative overlap error |delta - delta*| / delta*")
    axes[0].set_title("overlap error against the exact reference")
    axes[1].set_xlabel("median solver time per contact (us, shared machine)")
    axes[1].set_ylabel("worst relative overlap error")
    axes[1].set_title("accuracy versus cost (labels: accuracyTol)")
    axes[2].set_xlabel("accuracyTol")
    axes[2].set_ylabel("worst normal angle (rad)")
    axes[2].set_title("normal against the exact separating direction\n(blocks: the seed's averaged normal)")
    for ax in axes:
        ax.legend(fontsize=7)
    fig.tight_layout()
    case.save_chart(fig)


if __name__ == "__main__":
    main()
