"""DEM case: the seed's periodic simple shear tutorial (04), with the tutorial's random cloud.

Run:      build/bin/talus run cases/dem/dem_periodic_simple_shear.py [--quick] [--results DIR]
Set-up:   a periodic cell 2 x 2 x 2 m filled by makeCloud (rMean 0.1, rRelFuzz 0.6, periodic, seed 1;
          quick: rMean 0.12), FrictMat with young 1e8 (the default 1e7 overlaps the small spheres by more
          than half their radius at 500 kPa, which Talus rejects) and the friction set to 0 for a
          dense packing, damping 0.4, dt 0.5 P-wave. Isotropic compression at a strain rate of -0.1/s (O.cell.velGrad) until
          the mean stress is below -500 kPa; then friction 0.5 rad for materials and existing contacts
          (setContactFriction) and simple shear velGrad[0, 2] = 0.1/s until trsf[0, 2] = 0.5 (quick:
          0.3).
Checked:  dem.periodic-simple-shear.kinematics: |increase of trsf[0, 2] - 0.1 trsf[2, 2] t_shear| at
          the end: the cell shears as (I + L dt) trsf with the imposed L (<= 1e-9).
          dem.periodic-simple-shear.isotropy: largest relative difference between the diagonal
          stresses at the end of the compression (<= 0.15: a frictionless random packing of a few
          hundred spheres compressed isotropically).
          dem.periodic-simple-shear.friction: mobilised friction |sxz / szz| averaged over the last
          40 % of the shear (steady state), within 0.25 ... 0.6 (recorded as its distance to the
          band centre over the half-width, <= 1): dense frictional spheres with a contact friction of
          tan(0.5) = 0.55 flow at a macroscopic friction of about 0.3-0.5.
          dem.periodic-simple-shear.symmetry: |sxz - szx| / |sxz| in the steady state (<= 0.05).
Produces: the records and chart dem.periodic-simple-shear.png (stresses and mobilised friction
          against the shear strain).
"""
import numpy as np

from talus import results
from talus.dem import *  # noqa: F401,F403


def main():
    args = results.case_arguments(__doc__).parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    case = results.Case("dem.periodic-simple-shear", quick=args.quick, folder=args.results)
    r_mean, gamma_end = (.12, .3) if args.quick else (.1, .5)

    scene = Scene()
    scene.periodic = True
    scene.cell.hSize = Matrix3(2, 0, 0, 0, 2, 0, 0, 0, 2)
    sp = pack.SpherePack()
    sp.makeCloud((0, 0, 0), (2, 2, 2), rMean=r_mean, rRelFuzz=.6, periodic=True, seed=1)
    scene.materials.append(FrictMat(young=1e8, frictionAngle=0))
    sp.toSimulation(scene)
    scene.engines = [
        ForceResetter(),
        InsertionSortCollider([Bo1_Sphere_Aabb()]),
        InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                        [Law2_ScGeom_FrictPhys_CundallStrack()]),
        NewtonIntegrator(damping=.4),
    ]
    scene.dt = .5 * PWaveTimeStep(scene)
    scene.cell.velGrad = Matrix3(-.1, 0, 0, 0, -.1, 0, 0, 0, -.1)
    while True:
        scene.run(100)
        stress = getStress(scene=scene)
        if stress.trace() / 3 < -5e5:
            break
    diag = np.diag(stress)
    isotropy = float((diag.max() - diag.min()) / abs(diag.mean()))
    print(f"{len(sp)} spheres compressed to {diag} Pa at step {scene.iter}, porosity {porosity(scene=scene):.3f}")

    scene.cell.velGrad = Matrix3(0, 0, .1, 0, 0, 0, 0, 0, 0)
    setContactFriction(.5, scene=scene)
    start_time, start_shear = scene.time, scene.cell.trsf[0, 2]
    gamma, sxz, szx, szz = [], [], [], []
    while abs(scene.cell.trsf[0, 2]) < gamma_end:
        scene.run(100)
        s = getStress(scene=scene)
        gamma.append(float(scene.cell.trsf[0, 2]))
        sxz.append(float(s[0, 2]))
        szx.append(float(s[2, 0]))
        szz.append(float(s[2, 2]))
    gamma, sxz, szx, szz = map(np.array, (gamma, sxz, szx, szz))
    kinematics = abs(scene.cell.trsf[0, 2] - start_shear - .1 * scene.cell.trsf[2, 2] * (scene.time - start_time))
    steady = gamma > .6 * gamma_end
    mu = float(np.mean(np.abs(sxz[steady] / szz[steady])))
    symmetry = float(np.mean(np.abs(sxz[steady] - szx[steady])) / np.mean(np.abs(sxz[steady])))
    print(f"shear to {gamma[-1]:.3f}: steady mobilised friction {mu:.3f}, asymmetry {symmetry:.4f}")

    case.record("|trsf[0,2] - imposed shear rate x time| at the end of the shear", kinematics,
                "velGrad[0,2] = 0.1/s applied to trsf over the shear time", 1e-9, suffix="kinematics")
    case.record("largest relative difference of the diagonal stresses after isotropic compression", isotropy,
                "isotropic compression of a frictionless random packing", 0.15, suffix="isotropy",
                stresses=diag.tolist(), spheres=len(sp))
    case.record("steady mobilised friction |sxz/szz|: distance to the centre of 0.25...0.6 over the half-width",
                abs(mu - .425) / .175, "dense frictional spheres (contact friction 0.55): macroscopic 0.3-0.5", 1.0,
                suffix="friction", mobilised_friction=mu)
    case.record("relative asymmetry |sxz - szx| / |sxz| of the stress in the steady state", symmetry,
                "quasi-static equilibrium (symmetric Love-Weber stress)", 0.05, suffix="symmetry")

    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    axes[0].plot(gamma, -szz / 1e3, label="-szz")
    axes[0].plot(gamma, -sxz / 1e3, label="-sxz")
    axes[0].set_xlabel("shear strain trsf[0, 2]")
    axes[0].set_ylabel("stress (kPa)")
    axes[0].set_title("periodic simple shear at constant volume")
    axes[0].legend()
    axes[1].plot(gamma, np.abs(sxz / szz))
    axes[1].axhline(mu, color="gray", ls="--", lw=.8, label=f"steady {mu:.2f}")
    axes[1].set_xlabel("shear strain trsf[0, 2]")
    axes[1].set_ylabel("|sxz / szz|")
    axes[1].set_title("mobilised friction")
    axes[1].legend()
    fig.tight_layout()
    case.save_chart(fig)


if __name__ == "__main__":
    main()
