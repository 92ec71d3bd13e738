"""FEM x DEM case: shear band in drained biaxial compression, mesh refinement study.

Run:      build/bin/talus run cases/fem/fem_shear_band.py [--quick] [--results DIR]
Set-up:   a W x H = 1 x 2 plane-strain sample of bilinear quadrilaterals (2x2 Gauss points) on two
          unstructured meshes (gmsh, frontal-Delaunay recombined: no mesh line or element diagonal at
          one angle), element size h = 0.25 (43 cells) and 0.125 (152 cells) in both modes (the quick
          mode's RVEs are smaller). (Structured meshes of square cells, whose diagonals run at 45
          degrees, gave 39.7 to 42.6 degrees on 8 x 16 with one packing everywhere; docs/fem.md.)
          Every Gauss point outside the imperfection carries one of four dense planar RVEs, drawn at
          random (numpy generator seed 7): talus.fem.prepareRVE planar=True, a layer of disks of rMean
          0.03 compacted to -100 kPa with friction 0.1, then friction 0.5; quick: cell edge 0.5, 55 to
          63 disks, packing seeds 2 to 5; full: edge 0.7, seeds 3 to 6. Such small RVEs are
          anisotropic: under a biaxial strain they carry a shear stress (up to 15 % of the axial
          stress). One packing copied to every Gauss point (Yade's FEMxDEM biaxial example loads one
          0.yade.gz everywhere) makes the whole sample anisotropic, and its band followed the fabric:
          27 degrees on the coarse mesh, against 49.5 for the mix (docs/fem.md). The imperfection (one
          file per Gauss point, as the other branch of that example's initLoad): the Gauss points
          inside a square of side 0.25 at the centre of the sample (placed by position: 4 and 22
          points) get a looser, weaker RVE (the first seed, compacted with friction 0.5, then friction
          0.3). At the centre, a band at any inclination up to the sample's diagonal (63 degrees) can
          leave through both free sides. Smooth platens: bottom uy = 0 (and ux = 0 at the bottom-left
          corner), top lowered to 10 % axial strain in 20 (quick) or 50 load steps, left and right
          edges under a 100 kPa traction; 40 (quick) or 100 DEM steps per call; finite-difference
          consistent tangent; Newton tolerance 1e-3 (quick) or 1e-5, a step is cut after 6 iterations
          without progress (down to 1/16), a failing correction halved (backtracking); updated
          Lagrangian. A load step that still fails (small RVEs in the band lose their contacts or are
          crushed) ends that mesh's run with the solver's report; the records use the converged steps.
          When the fd tangent fails a step (near collapse it is nearly singular), the run goes on with
          the contact-stiffness tangent. Quick mode is sized for a shared 2-core machine (780 RVEs of
          55 to 63 disks); the full mode (780 RVEs of ~110 disks, 2.5 times the load steps and DEM
          steps per call) is hours on one core.
Measured: friction angle phi from the peak stress ratio, sin phi = (s1 - s3) / (s1 + s3); dilatancy
          angle psi from the volumetric curve, the largest dilatancy rate
          sin psi = -d eps_v / d(eps_1 - eps_3) (compression positive) between consecutive load
          steps from two steps before to two steps after the peak. The band: the cells'
          accumulated shear strain sqrt(2/3 e':e') from the peak to the end, fitted with a
          straight band (talus.fem.band.fitBand: a Radon scan for the line along which the excess
          strain integrates to the most, then a least-squares Gaussian band profile across it);
          its inclination to the horizontal (the minor principal stress), width and contrast.
Checked:  The rule: "a band forms" is checked on the finest mesh of the study (h = 0.125, the one
          whose cells are narrower than the band; a cell of 0.25 is about as wide as the band,
          which it can only smear); the refinement study is checked by the meshes agreeing before
          localisation and by the band not getting less sharp as the cells shrink (a local
          continuum's band narrows with the cells: the expected mesh dependence). The coarse
          mesh's localisation and inclination are measured the same way and written into the
          records (their metric text and fields coarse_*), not checked.
          fem.shear-band.localised-<finest>: max / mean post-peak shear strain over the cells of
          the finest mesh (>= 2.5: a band, not a homogeneous field, for which the ratio is ~1).
          fem.shear-band.inclination-<finest>: band inclination on the finest mesh against the
          Mohr-Coulomb angle 45 + phi/2 and the Roscoe angle 45 + psi/2: distance (degrees)
          outside the interval [Roscoe - 10, Mohr-Coulomb + 10] (= 0; the 10 degrees are the
          resolution of a few cells; the fit itself finds a synthetic band within 0.4 degrees,
          tests/fem/test_band.py).
          fem.shear-band.sharpening: max / mean of the finest mesh over that of the coarsest
          (>= 1: the localisation contrast does not decrease with refinement).
          fem.shear-band.peak: relative difference of the peak stress ratio of the refined mesh to
          the coarse mesh (<= 0.05: before localisation both meshes carry the same homogeneous
          response).
          fem.shear-band.converged: fraction of the load steps that converged on both meshes (= 1).
Produces: the records; chart fem.shear-band.png (stress ratio and volumetric strain against axial
          strain, both meshes); fem.shear-band.field.png (accumulated shear strain per cell over the
          whole test and after the peak, each mesh, with the band axis); shear_band_h<size>.xdmf
          (ParaView: displacement, stress, void ratio, shear strain of the last increment, every
          load step); fem.shear-band.fields.npz (the cells and post-peak fields, to re-measure).
"""
import tempfile
import time
from pathlib import Path

import numpy as np

from talus import results

P_CONF, W, H, STRAIN = 1e5, 1.0, 2.0, 0.10


def unstructured_mesh(h):
    """An unstructured quadrilateral mesh of the W x H sample, element size h: gmsh's
    frontal-Delaunay triangles recombined into quadrilaterals (Blossom), so that no mesh line or
    element diagonal runs through the sample at one angle."""
    from dolfinx.io import gmshio            # dolfinx before gmsh (the other order crashes here)
    from mpi4py import MPI
    import gmsh
    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        geo = gmsh.model.geo
        corners = [geo.addPoint(x, y, 0, h) for x, y in ((0, 0), (W, 0), (W, H), (0, H))]
        sides = [geo.addLine(corners[i], corners[(i + 1) % 4]) for i in range(4)]
        surface = geo.addPlaneSurface([geo.addCurveLoop(sides)])
        geo.synchronize()
        gmsh.model.addPhysicalGroup(2, [surface], 1)
        gmsh.option.setNumber("Mesh.Algorithm", 6)               # frontal-Delaunay
        gmsh.option.setNumber("Mesh.RecombinationAlgorithm", 1)  # Blossom: all quadrilaterals
        gmsh.option.setNumber("Mesh.RecombineAll", 1)
        gmsh.model.mesh.generate(2)
        msh, _, _ = gmshio.model_to_mesh(gmsh.model, MPI.COMM_SELF, 0, gdim=2)
    finally:
        gmsh.finalize()
    return msh


def run_mesh(label, h, strong, weak, region, steps, nSteps, tol, folder):
    """The biaxial test on the unstructured mesh of size h; returns its curves, cells and
    per-increment shear."""
    from dolfinx.io import XDMFFile

    from talus.fem import MultiscaleRVEs
    from talus.fem.fenicsx import (Dirichlet, MultiscaleSolver, NewtonDivergence, Traction, gaussPointCoordinates,
                                   shearStrain)

    msh = unstructured_mesh(h)
    (x0, y0), (x1, y1) = region
    p = gaussPointCoordinates(msh)
    inside = (p[:, 0] > x0) & (p[:, 0] < x1) & (p[:, 1] > y0) & (p[:, 1] < y1)
    # every point outside the weak square one of the strong packings, drawn at random
    pick = np.random.default_rng(7).integers(len(strong), size=len(inside))
    rves = MultiscaleRVEs([str(weak) if k else str(strong[q]) for k, q in zip(inside, pick)], nSteps=nSteps,
                          form="fd")
    # Prescribed nodes are those on the bottom and on the current top (the platens stay flat; the
    # nearest interior node is 0.8 h away); the traction sides are found among the boundary facets
    # by their side of x = h / 2 and W - h / 2 (the sides bulge by less).
    dx, flat = h / 2, 1e-6 * H
    solver = MultiscaleSolver(
        msh, rves, tol=tol, stall=6, minStepFraction=1 / 16,
        dirichlet=[Dirichlet(lambda x: x[1] < flat, 1), Dirichlet(lambda x: (x[1] < flat) & (x[0] < flat), 0),
                   Dirichlet(lambda x: x[1] > x[1].max() - flat, 1, lambda t: -STRAIN * H * t)],
        tractions=[Traction(lambda x: x[0] < dx, lambda t: (P_CONF, 0.0)),
                   Traction(lambda x: x[0] > W - dx, lambda t: (-P_CONF, 0.0))])
    rows, shear, converged, start = [], [], 0, time.perf_counter()
    with XDMFFile(msh.comm, str(folder / f"shear_band_{label}.xdmf"), "w") as xdmf:
        xdmf.write_mesh(msh)
        n, fallback = 1, None
        while n <= steps:
            done = len(solver.history)
            try:
                report = solver.step(n / steps)
            except NewtonDivergence as e:
                if rves.form != "fd":
                    print(f"{label} step {n}: {str(e)[:400]}", flush=True)
                    break
                # Near collapse the fd tangent is nearly singular and its corrections crush RVEs:
                # go on with the contact-stiffness tangent (an upper bound: slower, no overshoot).
                print(f"{label} step {n}: fd tangent failed, contact-stiffness tangent from here", flush=True)
                rves.form, solver.stall, solver.maxIter, fallback = "full", 10, 80, n
                continue
            converged += 1
            # the shear strain of this load step, summed over its increments (cut steps have several)
            shear.append(sum(shearStrain(r.gradients).reshape(-1, 4).mean(axis=1) for r in solver.history[done:]))
            # The sample may shear as a whole (smooth platens) and bulge: its volume is the mesh
            # area, the axial stress the top reaction over the top edge's length.
            x = msh.geometry.x
            height = H * (1 - solver.t * STRAIN)
            onTop = x[:, 1] > height - flat
            top = -solver.reactions(lambda y: y[1] > height - flat, 1) / np.ptp(x[onTop, 0])   # compressive, Pa
            rows.append((solver.t * STRAIN, top, 1 - area(msh) / (W * H)))
            print(f"{label} step {n}: axial strain {rows[-1][0]:.4f}, stress ratio "
                  f"{(top - P_CONF) / (top + P_CONF):.3f}, volumetric strain {rows[-1][2]:.5f}, Newton "
                  f"{report.iterations}{' (cut)' if report.cut else ''}, {time.perf_counter() - start:.0f} s",
                  flush=True)
            solver.write(xdmf, solver.t)
            n += 1
    return {"rows": np.array(rows), "shear": np.array(shear), "polygons": polygons(msh), "converged": converged,
            "weakPoints": int(inside.sum()), "newton": solver.newtonIterations, "wall": time.perf_counter() - start,
            "fallback": fallback}


def polygons(msh):
    """The cells of a quadrilateral mesh as polygons (cells, 4, 2), counter-clockwise."""
    x = msh.geometry.x[:, :2]
    cells = msh.topology.index_map(2).size_local
    # dolfinx quadrilaterals list their vertices in tensor-product order: 0 1 3 2 goes around.
    return np.array([x[msh.geometry.dofmap.links(c)[[0, 1, 3, 2]]] for c in range(cells)])


def area(msh):
    """The area of the mesh in its current configuration (shoelace formula per cell)."""
    p = polygons(msh)
    q = np.roll(p, -1, axis=1)
    return 0.5 * np.abs(np.sum(p[..., 0] * q[..., 1] - q[..., 0] * p[..., 1], axis=1)).sum()


def angles(rows):
    """Friction and dilatancy angles (degrees) and the index of the peak, from the global curves."""
    strain, axial, ev = rows[:, 0], rows[:, 1], rows[:, 2]
    ratio = (axial - P_CONF) / (axial + P_CONF)
    peak = int(np.argmax(ratio))
    phi = np.degrees(np.arcsin(ratio[peak]))
    gamma = 2 * strain - ev                     # eps_1 - eps_3 with eps_3 = eps_v - eps_1
    window = slice(max(peak - 2, 0), min(peak + 3, len(rows)))
    rates = -np.diff(ev[window]) / np.diff(gamma[window])
    sinpsi = rates.max() if len(rates) else 0.0
    return phi, float(np.degrees(np.arcsin(np.clip(sinpsi, -1, 1)))), peak


def main():
    args = results.case_arguments(__doc__).parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection

    from talus.fem import prepareRVE
    from talus.fem.band import fitBand

    case = results.Case("fem.shear-band", quick=args.quick, folder=args.results)
    # unstructured quadrilaterals of size h, coarsest first, finest last (the checks use both ends)
    meshes = [("h0.25", 0.25), ("h0.125", 0.125)]
    steps, nSteps, tol, size, seeds = (20, 40, 1e-3, 0.5, (2, 3, 4, 5)) if args.quick else (50, 100, 1e-5, 0.7,
                                                                                             (3, 4, 5, 6))
    folder = Path(case.folder)
    folder.mkdir(parents=True, exist_ok=True)
    work = Path(tempfile.mkdtemp(prefix="fem_shear_band_"))
    # A sample of one small packing copied everywhere has that packing's anisotropy everywhere
    # (its shear stress under a biaxial strain): the band then follows the fabric (27 degrees on
    # the coarse mesh). Four packings mixed at random are a statistically isotropic sample.
    strong, weak = [work / f"strong{seed}.h5" for seed in seeds], work / "weak.h5"
    infos = {f"strong (seed {seed})": prepareRVE(path, size=size, rMean=0.03, seed=seed, sigma=-P_CONF, young=1e8,
                                                 planar=True, friction=0.5, compactionFriction=0.1)
             for seed, path in zip(seeds, strong)}
    infos["weak"] = prepareRVE(weak, size=size, rMean=0.03, seed=seeds[0], sigma=-P_CONF, young=1e8, planar=True,
                               friction=0.3, compactionFriction=0.5)
    for name, info in infos.items():
        print(f"{name} RVE: {info['spheres']} disks, porosity {info['porosity']:.3f}, "
              f"coordination {info['coordination']:.2f}", flush=True)
    # The imperfection: a square of the coarse cell's size at the centre of the sample, the Gauss
    # points inside it weak (the same area on both meshes). At the centre, a band at any inclination
    # up to the sample's diagonal (63 degrees) leaves through the two free sides and splits the
    # sample into two blocks; a band through a point higher up (it was at (0.375, 1.125)) that
    # is steeper than about 50 degrees runs into the top platen instead, and the flatter band wins.
    side = meshes[0][1]
    region = ((W / 2 - side / 2, H / 2 - side / 2), (W / 2 + side / 2, H / 2 + side / 2))
    runs = {}
    for label, h in meshes:
        runs[label] = run_mesh(label, h, strong, weak, region, steps, nSteps, tol, folder)
    np.savez(folder / "fem.shear-band.fields.npz",
             **{f"{key}_{label}": r[key] for label, r in runs.items() for key in ("polygons", "shear", "rows")})

    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    fieldFig, fieldAxes = plt.subplots(2, len(meshes), figsize=(4 * len(meshes), 10))
    peaks, measured = [], {}
    for k, ((label, h), r) in enumerate(zip(meshes, runs.values())):
        rows = r["rows"]
        ratio = (rows[:, 1] - P_CONF) / (rows[:, 1] + P_CONF)
        axes[0].plot(100 * rows[:, 0], ratio, "o-", ms=3, label=f"{label} ({4 * len(r['polygons'])} RVEs)")
        axes[1].plot(100 * rows[:, 0], 100 * rows[:, 2], "o-", ms=3, label=label)
        phi, psi, peak = angles(rows)
        peaks.append(ratio[peak])
        post = r["shear"][peak + 1:].sum(axis=0) if peak + 1 < len(r["shear"]) else r["shear"][-1]
        loc = float(post.max() / post.mean())
        fitted = fitBand(r["polygons"], post)
        incl = fitted.inclination
        mc, roscoe = 45 + phi / 2, 45 + psi / 2
        lo, hi = min(roscoe, mc) - 10, max(roscoe, mc) + 10
        outside = max(lo - incl, incl - hi, 0.0)
        print(f"{label}: peak ratio {ratio[peak]:.3f} at {100 * rows[peak, 0]:.1f} %, phi {phi:.1f}, psi {psi:.1f}, "
              f"band max/mean {loc:.2f}, inclination {incl:.1f} (Roscoe {roscoe:.1f}, Mohr-Coulomb {mc:.1f}), "
              f"width {fitted.width:.3f}, contrast {fitted.contrast:.2f}, Newton iterations {r['newton']}, "
              f"contact tangent from step {r['fallback']}, {r['wall']:.0f} s", flush=True)
        measured[label] = dict(
            label=label, localisation=loc, outside=outside, inclination=incl, phi=phi, psi=psi, roscoe=roscoe,
            mohr_coulomb=mc, band_width=fitted.width, band_contrast=fitted.contrast, cell_width=h,
            peak_strain=float(rows[peak, 0]), cells=len(r["polygons"]), gauss_points=4 * len(r["polygons"]),
            steps=steps, nSteps=nSteps,
            weak_gauss_points=r["weakPoints"], wall_mesh_s=r["wall"], final_strain=float(rows[-1, 0]),
            contact_tangent_from_step=r["fallback"])
        # the fields: accumulated shear strain of the whole test and after the peak, per cell
        for row, (field, what) in enumerate(((r["shear"].sum(axis=0), "whole test"), (post, "after the peak"))):
            ax = fieldAxes[row, k]
            patches = PolyCollection(r["polygons"], array=field, cmap="viridis", edgecolor="face")
            ax.add_collection(patches)
            ax.add_patch(plt.Rectangle(region[0], side, side, fill=False, edgecolor="w", lw=0.8, ls=":"))
            ax.plot(*np.array([fitted.point - 1.2 * fitted.direction, fitted.point + 1.2 * fitted.direction]).T,
                    "r--", lw=1.2)
            ax.set_xlim(r["polygons"][..., 0].min() - 0.05, r["polygons"][..., 0].max() + 0.05)
            ax.set_ylim(r["polygons"][..., 1].min() - 0.05, r["polygons"][..., 1].max() + 0.05)
            ax.set_aspect("equal")
            ax.set_title(f"{label}, {what} (to {100 * rows[-1, 0]:.1f} %)\nband {incl:.0f}° (Mohr-Coulomb {mc:.0f}°, "
                         f"Roscoe {roscoe:.0f}°), max/mean {loc:.1f}" if row else f"{label}, {what} (to "
                         f"{100 * rows[-1, 0]:.1f} %)", fontsize=9)
            fieldFig.colorbar(patches, ax=ax, shrink=0.8)
    # "A band forms" on the finest mesh; the coarsest mesh's figures ride along (coarse_*), unchecked.
    fine, coarse = measured[meshes[-1][0]], measured[meshes[0][0]]
    label = fine["label"]
    given = lambda m: {k: v for k, v in m.items() if k != "label"}            # noqa: E731
    aside = {f"coarse_{k}": v for k, v in given(coarse).items()}
    case.record(f"max / mean post-peak shear strain over the cells, finest mesh {label} (coarsest "
                f"{coarse['label']}: {coarse['localisation']:.2f}, not checked: cells as wide as the band)",
                fine["localisation"], "a homogeneous field gives ~1", 2.5, comparison=">=",
                suffix=f"localised-{label}", coarse_mesh=coarse["label"], **given(fine), **aside)
    case.record(f"band inclination (degrees from horizontal) outside [Roscoe - 10, Mohr-Coulomb + 10], finest "
                f"mesh {label} ({fine['inclination']:.1f} in [{min(fine['roscoe'], fine['mohr_coulomb']) - 10:.1f}, "
                f"{max(fine['roscoe'], fine['mohr_coulomb']) + 10:.1f}]; coarsest {coarse['label']}: "
                f"{coarse['inclination']:.1f} in [{min(coarse['roscoe'], coarse['mohr_coulomb']) - 10:.1f}, "
                f"{max(coarse['roscoe'], coarse['mohr_coulomb']) + 10:.1f}], {coarse['outside']:.1f} outside, "
                f"not checked)", fine["outside"],
                "45 + psi/2 and 45 + phi/2 from the measured peak friction and dilatancy angles", 0.0,
                suffix=f"inclination-{label}", coarse_mesh=coarse["label"], **given(fine), **aside)
    case.record(f"localisation contrast (max / mean post-peak shear strain) of the finest mesh {label} over the "
                f"coarsest {coarse['label']} ({fine['localisation']:.2f} / {coarse['localisation']:.2f})",
                fine["localisation"] / coarse["localisation"],
                "the band sharpens or stays as sharp as the cells shrink (mesh dependence of a local continuum)",
                1.0, comparison=">=", suffix="sharpening", fine=fine["localisation"], coarse=coarse["localisation"],
                fine_mesh=label, coarse_mesh=coarse["label"])
    gap = abs(peaks[-1] - peaks[0]) / peaks[0]
    case.record("relative difference of the peak stress ratio, refined mesh against coarse mesh", gap,
                "the coarse mesh (same RVEs and imperfection)", 0.05, suffix="peak", coarse=peaks[0], refined=peaks[1])
    converged = min(r["converged"] for r in runs.values()) / steps
    case.record("fraction of the load steps that converged (worse mesh)", converged, "all steps", 1.0,
                comparison=">=", suffix="converged")
    axes[0].set_xlabel("axial strain (%)")
    axes[0].set_ylabel("(s1 - s3) / (s1 + s3)")
    axes[0].legend()
    axes[1].set_xlabel("axial strain (%)")
    axes[1].set_ylabel("volumetric strain (%, compression +)")
    axes[1].legend()
    fig.suptitle(f"FEM x DEM drained biaxial, 100 kPa, planar RVEs of "
                 f"{', '.join(str(i['spheres']) for i in infos.values())} disks (the last: weak)")
    case.save_chart(fig)
    fieldFig.suptitle("accumulated shear strain per cell (dotted: the weak region, initial position; dashed: "
                      "band axis)", fontsize=9)
    case.save_chart(fieldFig, "field")


if __name__ == "__main__":
    main()
