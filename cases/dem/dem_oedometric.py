"""DEM case: the seed's oedometric test tutorial (03), and oedometric loading to a stress with
TriaxialStressController.

Run:      build/bin/talus run cases/dem/dem_oedometric.py [--quick] [--results DIR]
Set-up:   1. The tutorial: a seeded cloud (makeCloud, rMean 0.05, rRelFuzz 0.3; quick: rMean 0.07)
             deposited under gravity in an open facet box (damping 0.5), until the unbalanced force is
             below 0.1 (after 5000 steps). FrictMat with young 1e8 instead of the default 1e7: at 1 MPa
             the default material overlaps by more than half a radius, which Talus rejects
             (O.maxOverlapRatio). A wall is put on top of the packing and
             driven down at 0.1 m/s until its force exceeds maxLoad = 1 MN, then back up until the
             force falls below minLoad = 10 kN.
          2. Oedometric loading to a stress: spheres compacted between six plane walls to -10 kPa
             (TriaxialStressController, internalCompaction), then the lateral walls are fixed
             (wall_*_activated = False) and the top and bottom walls are servo-controlled to -100 kPa
             (stressMask 2).
Checked:  dem.oedometric.load: largest plate force over maxLoad (>= 1: the load was reached).
          dem.oedometric.irreversible: residual plate displacement after unloading over the largest
          displacement (>= 0.2: a granular packing compacts irreversibly; an elastic solid gives 0).
          dem.oedometric.servo: relative gap of the vertical stress to -100 kPa at the end (<= 1 %).
          dem.oedometric.lateral-fixed: largest displacement of a lateral wall during part 2 (== 0).
          dem.oedometric.k0: earth pressure coefficient at rest K0 = s_h / s_v (recorded; physically
          between 0 and 1: <= 1).
Produces: the records and chart dem.oedometric.png (plate force against displacement; stresses of
          part 2 against iterations).
"""
import numpy as np

from talus import results
from talus.dem import *  # noqa: F401,F403


def tutorial(r_mean: float):
    scene = Scene()
    scene.materials.append(FrictMat(young=1e8))
    scene.bodies.append(geom.facetBox((.5, .5, .5), (.5, .5, .5), wallMask=31))
    sp = pack.SpherePack()
    sp.makeCloud((0, 0, 0), (1, 1, 1), rMean=r_mean, rRelFuzz=.3, seed=1)
    ids = sp.toSimulation(scene)
    scene.engines = [
        ForceResetter(),
        InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb(), Bo1_Wall_Aabb()]),
        InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
                        [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
        NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.5),
    ]
    scene.dt = .5 * PWaveTimeStep(scene)
    while scene.iter < 5000 or unbalancedForce(scene=scene) > .1:
        scene.run(500)
    r, z = scene.radii()[ids], scene.positions()[ids][:, 2]
    top = float(np.max(z + r))
    plate = scene.bodies.append(wall(top, axis=2, sense=-1))
    scene.bodies[plate].state.vel = (0, 0, -.1)
    w, f = [], []
    stage = "loading"
    while stage != "done":
        scene.run(100)
        fz = float(scene.forces()[plate][2])
        w.append(float(scene.positions()[plate][2] - top))
        f.append(fz)
        if stage == "loading" and abs(fz) > 1e6:
            scene.bodies[plate].state.vel = (0, 0, .1)
            stage = "unloading"
        elif stage == "unloading" and abs(fz) < 1e4:
            stage = "done"
    return np.array(w), np.array(f), len(ids)


def servo(num: int):
    scene = Scene()
    scene.materials.append(FrictMat(young=5e6, poisson=.5, frictionAngle=.5, density=2600, label="spheres"))
    scene.materials.append(FrictMat(young=5e6, poisson=.5, frictionAngle=0, density=2600, label="walls"))
    scene.bodies.append(aabbWalls(((0, 0, 0), (1, 1, 1)), material="walls"))
    sp = pack.SpherePack()
    sp.makeCloud((0, 0, 0), (1, 1, 1), -1, .3, num, False, .9, seed=1)
    sp.toSimulation(scene, material="spheres")
    triax = TriaxialStressController(thickness=0, stressMask=7, internalCompaction=True, goal1=-1e4, goal2=-1e4,
                                     goal3=-1e4)
    scene.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
                     InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
                                     [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
                     GlobalStiffnessTimeStepper(timeStepUpdateInterval=10), triax, NewtonIntegrator(damping=.2)]
    while not (abs(triax.meanStress + 1e4) < 1e-3 * 1e4 and unbalancedForce(scene=scene) < .01):
        scene.run(500)
    # oedometric: x and z walls stay, y walls carry the vertical stress
    triax.internalCompaction = False
    for side in ("left", "right", "back", "front"):
        setattr(triax, f"wall_{side}_activated", False)
    triax.stressMask, triax.goal2 = 2, -1e5
    lateral0 = scene.positions()[[0, 1, 4, 5]].copy()
    history = {"i": [], "sv": [], "sh": []}
    moved = 0.0
    for _ in range(120):
        scene.run(200)
        moved = max(moved, float(np.max(np.abs(scene.positions()[[0, 1, 4, 5]] - lateral0))))
        history["i"].append(scene.iter)
        history["sv"].append(float(-(triax.stress(2)[1] + triax.stress(3)[1]) / 2))
        history["sh"].append(float(-(triax.stress(0)[0] + triax.stress(1)[0] + triax.stress(4)[2]
                                      + triax.stress(5)[2]) / 4))
        if abs(history["sv"][-1] - 1e5) < 1e-3 * 1e5 and unbalancedForce(scene=scene) < .01:
            break
    return history, moved


def main():
    args = results.case_arguments(__doc__).parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    case = results.Case("dem.oedometric", quick=args.quick, folder=args.results)

    w, f, n = tutorial(.07 if args.quick else .05)
    k = int(np.argmax(np.abs(f)))
    print(f"tutorial: {n} spheres, largest force {abs(f[k]):.3e} N at w = {w[k]:.4f} m, residual w = {w[-1]:.4f} m")
    case.record("largest plate force over maxLoad", float(abs(f[k]) / 1e6), "maxLoad = 1 MN (the tutorial's)", 1.0,
                comparison=">=", suffix="load", spheres=n)
    case.record("residual plate displacement after unloading over the largest displacement",
                float(w[-1] / w[k]), "irreversible compaction of a granular packing (elastic: 0)", 0.2,
                comparison=">=", suffix="irreversible")

    history, moved = servo(300 if args.quick else 1000)
    sv, sh = history["sv"][-1], history["sh"][-1]
    print(f"servo: vertical {sv:.1f} Pa, horizontal {sh:.1f} Pa, K0 = {sh / sv:.3f}, lateral walls moved {moved}")
    case.record("relative gap of the vertical stress to the goal at the end", abs(sv / 1e5 - 1),
                "goal2 = -100 kPa (stressMask 2)", 0.01, suffix="servo")
    case.record("largest displacement of a lateral wall while loading", moved,
                "lateral walls deactivated (wall_*_activated = False)", 0.0, suffix="lateral-fixed")
    case.record("earth pressure coefficient at rest K0 = s_h / s_v", sh / sv,
                "a granular packing at rest: 0 < K0 < 1", 1.0, suffix="k0")

    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    axes[0].plot(-w * 1e3, -f / 1e6, "-")
    axes[0].set_xlabel("plate displacement (mm, downwards)")
    axes[0].set_ylabel("plate force (MN)")
    axes[0].set_title("oedometric tutorial: loading and unloading")
    axes[1].plot(history["i"], np.array(history["sv"]) / 1e3, label="vertical (servo)")
    axes[1].plot(history["i"], np.array(history["sh"]) / 1e3, label="horizontal (fixed walls)")
    axes[1].set_xlabel("iteration")
    axes[1].set_ylabel("stress (kPa, compression)")
    axes[1].set_title(f"oedometric servo: K0 = {sh / sv:.2f}")
    axes[1].legend()
    fig.tight_layout()
    case.save_chart(fig)


if __name__ == "__main__":
    main()
