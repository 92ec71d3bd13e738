"""FEM x DEM case: shear band in drained biaxial compression, mesh refinement study (issue #7).

Run:      build/bin/talus run cases/fem_shear_band.py [--quick] [--results DIR]
Set-up:   a W x H = 1 x 2 plane-strain sample of bilinear quadrilaterals (2x2 Gauss points) on two
          meshes, coarse 4 x 8 and refined 8 x 16 (both modes; the quick mode's RVEs are smaller). Every
          Gauss point carries a copy of one dense planar RVE (talus.fem.prepareRVE planar=True, a
          layer of disks of rMean 0.03 compacted to -100 kPa with friction 0.1, then friction 0.5;
          quick: cell edge 0.5, 63 disks, seed 2; full: edge 0.7, 111 disks, seed 3). Such small
          RVEs are anisotropic: under a biaxial strain they carry a shear stress, which shears the
          whole sample between its smooth platens; the seeds are those of the least anisotropic of
          three packings (|s_xy / s_yy| < 0.03 against up to 0.15). The imperfection (Yade's FEMxDEM
          biaxial example loads 0.yade.gz everywhere, or one file per Gauss point from initLoad's
          other branch; here a weak region): the Gauss points inside one square of the coarse cell size,
          left of the centre (the same region on both meshes), get a looser, weaker RVE (compacted
          with friction 0.5, then friction 0.3). Smooth platens: bottom uy = 0 (and ux = 0 at the
          bottom-left corner), top lowered to 10 % axial strain in 20 (quick) or 50 load steps, left
          and right edges under a 100 kPa traction; 40 (quick) or 100 DEM steps per call;
          finite-difference consistent tangent; Newton tolerance 1e-3 (quick) or 1e-5, a step is cut
          after 6 iterations without progress (down to 1/16), a failing correction halved
          (backtracking); updated Lagrangian. A load step that still fails (small RVEs in the band
          lose their contacts or are crushed) ends that mesh's run with the solver's report; the
          records use the converged steps. When the fd tangent fails a step (near collapse it is
          nearly singular), the run goes on with the contact-stiffness tangent. Quick mode is
          sized for a shared 2-core machine (640 RVEs of 63 disks); the full mode (640 RVEs of 111
          disks, 2.5 times the load steps and DEM steps per call) is hours on one core. A 3 x 6
          coarse mesh (cells a third of the sample wide, as wide as the band) did not localise.
Measured: friction angle phi from the peak stress ratio, sin phi = (s1 - s3) / (s1 + s3); dilatancy
          angle psi from the volumetric curve, the largest dilatancy rate
          sin psi = -d eps_v / d(eps_1 - eps_3) (compression positive) between consecutive load
          steps from two steps before to two steps after the peak. The band: the cells'
          accumulated shear strain sqrt(2/3 e':e') from the peak to the end, fitted with a
          straight band (talus.fem.band.fitBand: a Radon scan for the line along which the excess
          strain integrates to the most, then a least-squares Gaussian band profile across it);
          its inclination to the horizontal (the minor principal stress), width and contrast.
Checked:  The rule: "a band forms" is checked on the finest mesh of the study (8 x 16, the one
          whose cells are narrower than the band; a 4 x 8 cell is about as wide as the band, which
          it can only smear); the refinement study is checked by the meshes agreeing before
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
          whole test and after the peak, each mesh, with the band axis); shear_band_<nx>x<ny>.xdmf
          (ParaView: displacement, stress, void ratio, shear strain of the last increment, every
          load step); fem.shear-band.fields.npz (the cells and post-peak fields, to re-measure).
"""
import tempfile
import time
from pathlib import Path

import numpy as np

from talus import results

P_CONF, W, H, STRAIN = 1e5, 1.0, 2.0, 0.10


def run_mesh(nx, ny, strong, weak, region, steps, nSteps, tol, folder):
    """The biaxial test on an nx x ny mesh; returns its curves, cells and per-increment shear."""
    from dolfinx import mesh as dmesh
    from dolfinx.io import XDMFFile
    from mpi4py import MPI

    from talus.fem import MultiscaleRVEs
    from talus.fem.fenicsx import Dirichlet, MultiscaleSolver, NewtonDivergence, Traction, shearStrain

    msh = dmesh.create_rectangle(MPI.COMM_SELF, [np.zeros(2), np.array([W, H])], [nx, ny],
                                 dmesh.CellType.quadrilateral)
    centres = dmesh.compute_midpoints(msh, 2, np.arange(nx * ny, dtype=np.int32))[:, :2]
    (x0, y0), (x1, y1) = region
    inside = (centres[:, 0] > x0) & (centres[:, 0] < x1) & (centres[:, 1] > y0) & (centres[:, 1] < y1)
    rves = MultiscaleRVEs([str(weak) if inside[c] else str(strong) for c in range(nx * ny) for _ in range(4)],
                          nSteps=nSteps, form="fd")
    dx, dy = W / nx / 2, H / ny / 2            # edges are found by their side of these lines
    solver = MultiscaleSolver(
        msh, rves, tol=tol, stall=6, minStepFraction=1 / 16,
        dirichlet=[Dirichlet(lambda x: x[1] < dy, 1), Dirichlet(lambda x: (x[1] < dy) & (x[0] < dx), 0),
                   # the top platen: the nodes near the current top (its height drops by 10 %)
                   Dirichlet(lambda x: x[1] > x[1].max() - dy, 1, lambda t: -STRAIN * H * t)],
        tractions=[Traction(lambda x: x[0] < dx, lambda t: (P_CONF, 0.0)),
                   Traction(lambda x: x[0] > W - dx, lambda t: (-P_CONF, 0.0))])
    rows, shear, converged, start = [], [], 0, time.perf_counter()
    with XDMFFile(msh.comm, str(folder / f"shear_band_{nx}x{ny}.xdmf"), "w") as xdmf:
        xdmf.write_mesh(msh)
        n, fallback = 1, None
        while n <= steps:
            done = len(solver.history)
            try:
                report = solver.step(n / steps)
            except NewtonDivergence as e:
                if rves.form != "fd":
                    print(f"{nx}x{ny} step {n}: {str(e)[:400]}", flush=True)
                    break
                # Near collapse the fd tangent is nearly singular and its corrections crush RVEs:
                # go on with the contact-stiffness tangent (an upper bound: slower, no overshoot).
                print(f"{nx}x{ny} step {n}: fd tangent failed, contact-stiffness tangent from here", flush=True)
                rves.form, solver.stall, solver.maxIter, fallback = "full", 10, 80, n
                continue
            converged += 1
            # the shear strain of this load step, summed over its increments (cut steps have several)
            shear.append(sum(shearStrain(r.gradients).reshape(-1, 4).mean(axis=1) for r in solver.history[done:]))
            # The sample may shear as a whole (smooth platens) and bulge: its volume is the mesh
            # area, the axial stress the top reaction over the top edge's length.
            x = msh.geometry.x
            height = H * (1 - solver.t * STRAIN)
            onTop = x[:, 1] > height - dy
            top = -solver.reactions(lambda y: y[1] > height - dy, 1) / np.ptp(x[onTop, 0])   # compressive, Pa
            rows.append((solver.t * STRAIN, top, 1 - area(msh) / (W * H)))
            print(f"{nx}x{ny} step {n}: axial strain {rows[-1][0]:.4f}, stress ratio "
                  f"{(top - P_CONF) / (top + P_CONF):.3f}, volumetric strain {rows[-1][2]:.5f}, Newton "
                  f"{report.iterations}{' (cut)' if report.cut else ''}, {time.perf_counter() - start:.0f} s",
                  flush=True)
            solver.write(xdmf, solver.t)
            n += 1
    return {"rows": np.array(rows), "shear": np.array(shear), "polygons": polygons(msh), "converged": converged,
            "inside": inside, "newton": solver.newtonIterations, "wall": time.perf_counter() - start,
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
    meshes = [(4, 8), (8, 16)]                  # coarsest first, finest last (the checks use both ends)
    steps, nSteps, tol, size, seed = (20, 40, 1e-3, 0.5, 2) if args.quick else (50, 100, 1e-5, 0.7, 3)
    folder = Path(case.folder)
    folder.mkdir(parents=True, exist_ok=True)
    work = Path(tempfile.mkdtemp(prefix="fem_shear_band_"))
    strong, weak = work / "strong.h5", work / "weak.h5"
    infos = {name: prepareRVE(path, size=size, rMean=0.03, seed=seed, sigma=-P_CONF, young=1e8, planar=True,
                              friction=phi, compactionFriction=phi0)
             for name, path, phi, phi0 in (("strong", strong, 0.5, 0.1), ("weak", weak, 0.3, 0.5))}
    for name, info in infos.items():
        print(f"{name} RVE: {info['spheres']} disks, porosity {info['porosity']:.3f}, "
              f"coordination {info['coordination']:.2f}", flush=True)
    side = W / meshes[0][0]                     # the imperfection: one coarse cell, left of the centre
    cx, cy = side * (int(0.3 * W / side) + 0.5), side * (int(0.5 * H / side) + 0.5)
    region = ((cx - side / 2, cy - side / 2), (cx + side / 2, cy + side / 2))
    runs = {}
    for nx, ny in meshes:
        runs[(nx, ny)] = run_mesh(nx, ny, strong, weak, region, steps, nSteps, tol, folder)
    np.savez(folder / "fem.shear-band.fields.npz",
             **{f"{key}_{nx}x{ny}": r[key] for (nx, ny), r in runs.items() for key in ("polygons", "shear", "rows")})

    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    fieldFig, fieldAxes = plt.subplots(2, len(meshes), figsize=(4 * len(meshes), 10))
    peaks, measured = [], {}
    for k, ((nx, ny), r) in enumerate(runs.items()):
        label = f"{nx}x{ny}"
        rows = r["rows"]
        ratio = (rows[:, 1] - P_CONF) / (rows[:, 1] + P_CONF)
        axes[0].plot(100 * rows[:, 0], ratio, "o-", ms=3, label=f"{label} ({4 * nx * ny} RVEs)")
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
        measured[(nx, ny)] = dict(
            label=label, localisation=loc, outside=outside, inclination=incl, phi=phi, psi=psi, roscoe=roscoe,
            mohr_coulomb=mc, band_width=fitted.width, band_contrast=fitted.contrast, cell_width=W / nx,
            peak_strain=float(rows[peak, 0]), cells=nx * ny, gauss_points=4 * nx * ny, steps=steps, nSteps=nSteps,
            wall_mesh_s=r["wall"], final_strain=float(rows[-1, 0]), contact_tangent_from_step=r["fallback"])
        # the fields: accumulated shear strain of the whole test and after the peak, per cell
        for row, (field, what) in enumerate(((r["shear"].sum(axis=0), "whole test"), (post, "after the peak"))):
            ax = fieldAxes[row, k]
            patches = PolyCollection(r["polygons"], array=field, cmap="viridis", edgecolor="face")
            ax.add_collection(patches)
            for poly in r["polygons"][r["inside"]]:
                ax.add_patch(plt.Polygon(poly, fill=False, edgecolor="w", lw=0.8, ls=":"))
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
    fine, coarse = measured[meshes[-1]], measured[meshes[0]]
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
    fig.suptitle(f"FEM x DEM drained biaxial, 100 kPa, planar RVEs of {infos['strong']['spheres']} disks "
                 f"(weak: {infos['weak']['spheres']})")
    case.save_chart(fig)
    fieldFig.suptitle("accumulated shear strain per cell (dotted: the weak RVEs; dashed: band axis)", fontsize=9)
    case.save_chart(fieldFig, "field")


if __name__ == "__main__":
    main()
