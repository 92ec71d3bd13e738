"""FEM x DEM against Yade: the Gauss-point stress and tangent on the same packing.

Run:      build/bin/talus run cases/fem/fem_vs_yade.py [--quick] [--results DIR]
Set-up:   two RVEs prepared by talus.fem.prepareRVE at -100 kPa: a 3D cube of spheres (rMean 0.1,
          edge 1.2 quick, 1.6 full) and a planar (2D-like) layer of disks (rMean 0.03, edge 0.5
          quick, 0.7 full, as cases/fem/fem_shear_band.py). Each is exported (talus.fem.exportRVE) and
          built identically in both programs by cases/yade/fem_rve_tangent.py: every sphere gets
          the same deterministic velocity and the scene runs one step (fresh contacts get a first
          shear increment, so the shear terms are exercised); Yade then prints its
          getStressAndTangent(volume, symmetry=True), Talus hands the scene to
          talus.fem.MultiscaleRVEs and prints the Gauss-point getStressAndTangent with form="yade".
          Yade 2023.02a (Debian package `yade`).
Checked:  fem.vs-yade.<rve>: the largest relative difference of the stress (and, in the record's
          fields, of the 6 x 6 tangent), max |ours - Yade's| / max |Yade's|, for <rve> = 3d and
          planar; the record's value is the larger of the two (<= 1e-6).
Produces: the records and chart fem.vs-yade.png (every tangent entry, Talus against Yade, both RVEs).
"""
import tempfile
from pathlib import Path

import numpy as np

from talus import results
from talus import twin

SCENARIO = Path(__file__).resolve().parents[1] / "yade" / "fem_rve_tangent.py"


def main():
    args = results.case_arguments(__doc__).parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from talus.fem import exportRVE, prepareRVE, rve_scene
    case = results.Case("fem.vs-yade", quick=args.quick, folder=args.results)
    if not twin.yade_available():
        raise SystemExit("fem_vs_yade: yade is not installed (./setup.sh installs the Debian package)")
    work = Path(tempfile.mkdtemp(prefix="fem_vs_yade_"))
    rves = {"3d": dict(size=1.2 if args.quick else 1.6, rMean=0.1),
            "planar": dict(size=0.5 if args.quick else 0.7, rMean=0.03, planar=True)}
    fig, axes = plt.subplots(1, len(rves), figsize=(5 * len(rves), 4.2))
    for ax, (name, options) in zip(axes, rves.items()):
        info = prepareRVE(work / f"{name}.h5", sigma=-1e5, young=1e8, **options)
        exportRVE(work / f"{name}.h5", work / f"{name}.json")
        params = {"packing": str(work / f"{name}.json"), "rveSceneDir": rve_scene.FOLDER}
        ours, yade = (twin.run(SCENARIO, params, program, timeout=600) for program in ("talus", "yade"))
        s, sy = np.array(ours["stress"]), np.array(yade["stress"])
        c, cy = np.array(ours["tangent"]), np.array(yade["tangent"])
        stress = float(np.abs(s - sy).max() / np.abs(sy).max())
        tangent = float(np.abs(c - cy).max() / np.abs(cy).max())
        print(f"{name} RVE ({info['spheres']} spheres, {ours['shearing']} contacts shearing): stress {stress:.2e}, "
              f"tangent {tangent:.2e} relative to Yade's", flush=True)
        case.record(f"largest relative difference of the Gauss-point stress and tangent from Yade's "
                    f"getStressAndTangent, {name} RVE (stress {stress:.1e}, tangent {tangent:.1e})",
                    max(stress, tangent),
                    "Yade 2023.02a getStressAndTangent(volume, symmetry=True) on the same packing", 1e-6, suffix=name, peer="yade 2023.02a", stress=stress, tangent=tangent, spheres=info["spheres"],
                    shearing_contacts=ours["shearing"], yade_stress_max=float(np.abs(sy).max()))
        ax.plot(cy.ravel(), c.ravel(), "o", ms=4, label="tangent entries (Pa)")
        ax.plot(sy.ravel(), s.ravel(), "s", ms=4, mfc="none", label="stress entries (Pa)")
        span = [min(cy.min(), sy.min()), max(cy.max(), sy.max())]
        ax.plot(span, span, "k:", lw=0.8, label="equal")
        ax.set_xlabel("Yade getStressAndTangent")
        ax.set_ylabel('Talus MultiscaleRVEs (form="yade")')
        ax.set_xscale("symlog", linthresh=1e2)
        ax.set_yscale("symlog", linthresh=1e2)
        ax.set_title(f"{name} RVE, {info['spheres']} spheres: stress {stress:.1e}, tangent {tangent:.1e}", fontsize=9)
        ax.legend(fontsize=8)
    case.save_chart(fig)


if __name__ == "__main__":
    main()
