"""DEM case: the seed's bouncing-sphere tutorial, in Talus and in Yade on identical input.

Run:      build/bin/talus run cases/dem/dem_bouncing_sphere.py [--quick] [--results DIR]
Set-up:   cases/yade/bouncing_sphere.py, run unchanged by both programs: a sphere (r 0.5) dropped from
          z = 2 onto a fixed one (FrictMat defaults), gravity 9.81, Cundall damping 0.1, dt 5e-5;
          quick: 20 001 steps (the first rebound to its apex), full: 30 001 steps.
Checked:  dem.bouncing-sphere.free-fall: largest difference of the height, before the first
          contact, from the leap-frog closed form z_n = 2 - a dt^2 n (n + 1) / 2 with the damped
          gravity a = 0.9 g (Cundall damping acts on gravity too, as in Yade; <= 1e-9 m).
          dem.bouncing-sphere.yade: largest height difference from Yade 2023.02a over the whole run
          (<= 1e-6 m; skipped if Yade is not installed).
          dem.bouncing-sphere.rebound: relative difference of the first rebound height from
          (0.9 / 1.1)^2 of the drop: damping scales the falling and the compressing accelerations
          by 1 - 0.1 and the rising and the decompressing ones by 1 + 0.1, so the spring gives back
          (1 - 0.1) / (1 + 0.1) of the energy and the flight loses the same ratio again (gravity
          during the contact is neglected: <= 1 %; measured 2.5e-4).
Produces: the records and chart dem.bouncing-sphere.png (height against time, both programs).
"""
from pathlib import Path

import numpy as np

from talus import results
from talus import twin

SCENARIO = Path(__file__).resolve().parents[1] / "yade" / "bouncing_sphere.py"
CONTACT = 1.0          # height at which the spheres touch (sum of the radii)
DAMPING, G = 0.1, 9.81


def main():
    args = results.case_arguments(__doc__).parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    case = results.Case("dem.bouncing-sphere", quick=args.quick, folder=args.results)
    params = {"steps": 20001 if args.quick else 30001}
    ours = twin.run(SCENARIO, params, "talus")
    theirs = twin.run(SCENARIO, params, "yade") if twin.yade_available() else None
    dt, z = ours["dt"], np.array(ours["z"])
    # integrations done when each height was taken: the PyRunner first runs at iteration 100, after
    # that step's integration (Yade's iterPeriod)
    steps = 100 * (np.arange(len(z)) + 1) + 1
    falling = np.flatnonzero(z > CONTACT)[: np.argmax(z <= CONTACT)]
    closed_form = 2 - (1 - DAMPING) * G * dt ** 2 * steps * (steps + 1) / 2
    case.record("largest height difference from the leap-frog free fall before contact (m)",
                float(np.max(np.abs(z[falling] - closed_form[falling]))),
                "z_n = 2 - a dt^2 n (n + 1) / 2, a = (1 - damping) g", 1e-9, suffix="free-fall",
                samples=int(len(falling)))
    first_contact = int(np.argmax(z <= CONTACT))
    apex = float(np.max(z[first_contact:]))
    expected = ((1 - DAMPING) / (1 + DAMPING)) ** 2 * (2 - CONTACT)
    case.record("relative difference of the first rebound height from the damped linear-spring estimate",
                abs((apex - CONTACT) / expected - 1), "(0.9 / 1.1)^2 of the drop height", 0.01, suffix="rebound",
                rebound=apex - CONTACT, expected=expected)
    print(f"free fall: {len(falling)} samples; rebound {apex - CONTACT:.5f} m, estimate {expected:.5f} m")
    fig, ax = plt.subplots(figsize=(7, 3.8))
    ax.plot(steps * dt, z, label="Talus")
    if theirs is not None:
        zy = np.array(theirs["z"])
        gap = float(np.max(np.abs(z - zy)))
        case.record("largest height difference from Yade over the run (m)", gap,
                    "yade 2023.02a on the same scenario file", 1e-6, suffix="yade", samples=int(len(z)))
        print(f"largest difference from Yade: {gap:.3g} m")
        ax.plot(steps * dt, zy, "--", label="Yade")
    ax.axhline(CONTACT, color="grey", lw=.8)
    ax.set_xlabel("time (s)")
    ax.set_ylabel("height of the falling sphere (m)")
    ax.set_title("bouncing sphere (tutorial 01)")
    ax.legend()
    fig.tight_layout()
    case.save_chart(fig)


if __name__ == "__main__":
    main()
