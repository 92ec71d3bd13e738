"""Thermal case: ThermalEngine with the pore fluid in Talus and in Yade 2023.02a on the same
packing and parameters (the set-ups of Yade's examples/ThermalEngine/noFlowScenario.py and
flowScenario.py), and the speed of a coupled step.

Run:      build/bin/talus run cases/pore/thm_vs_yade.py [--quick] [--results DIR]
Set-up:   cases/yade/thermal_scenario.py, the same text run by both programs (talus.twin, one
          thread each): the examples' 210 spheres of 4 mm in a 5 cm box, mechanically static,
          each centre moved by up to 2 um at random (seeded, the same file for both). The
          examples' packing is a regular lattice: its spheres are cospherical by fours, so its
          regular triangulation is not unique and Talus's and Yade's differ, which changes the
          pore network the fluid is advected on (not the sums over a sphere's pores, so the
          no-flow scenario agrees on the lattice too).
          noflow: spheres at 333.15 K in still water at 343.15 K, O.dt 1e-5 s;
          flow: water at 343.15 K entering through xmin (10 Pa against 0 at xmax) into a packing
          and water at 333.15 K, O.dt 1e-4 s.
          2000 steps (quick) or 10000 (full) each; uniformReynolds 10, tsSafetyFactor 0.
Checked:  the sphere temperatures and the pore temperatures at 24 inner probe points against
          Yade's, the largest difference relative to the largest change of Yade's field from its
          initial temperature (<= 1 %, records thm.vs-yade.noflow, thm.vs-yade.flow); the heat
          flux carried across x = 10 mm, rho Cp Q (mean probe temperature there - 333.15), Q the
          volume flux through xmax (getBoundaryFlux), against Yade's (<= 1 %, record
          thm.vs-yade.heat-flux: the hot front does not reach the outlet within the steps run);
          the CPU time of the coupled steps (FlowEngine, ThermalEngine
          and the DEM step), Yade's over Talus's (>= 3, record thm.bench.coupled).
Produces: the records above; chart thm.vs-yade.png (Talus's temperatures against Yade's).
"""
from pathlib import Path

import numpy as np

import tempfile

from talus import results
from talus import twin

SCRIPT = Path(__file__).resolve().parents[1] / "yade" / "thermal_scenario.py"
PACKING = Path("/usr/share/doc/yade/examples/ThermalEngine/5cmEdge_1mm.spheres")
RHO_CP = 997 * 4181.7
T0 = 333.15


def field_error(talus, yade, initial):
    """Largest |Talus - Yade| over the field relative to the largest change of Yade's field."""
    talus, yade = np.asarray(talus), np.asarray(yade)
    return float(np.max(np.abs(talus - yade)) / np.max(np.abs(yade - initial)))


def heat_flux(run):
    """rho Cp Q (T_plane - T0) across the probes' plane x = 10 mm nearest to the inlet (the front
    reaches no further in the steps run), Q the volume flux through the packing."""
    probes, temps = np.array(run["probes"]), np.array(run["poreTemp"])
    plane = probes[:, 0] == probes[:, 0].min()
    return RHO_CP * abs(run["outflux"]) * float(np.mean(temps[plane]) - T0)


def main():
    parser = results.case_arguments(__doc__)
    args = parser.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    case = results.Case("thm.vs-yade", quick=args.quick, folder=args.results)
    if not (twin.yade_available() and PACKING.exists()):
        print("yade or its ThermalEngine examples are not installed: no record")
        return
    steps = 2000 if args.quick else 10000
    rows = np.array([[float(v) for v in line.split()] for line in PACKING.read_text().splitlines()
                     if line.strip() and not line.startswith("#")])
    rows[:, :3] += np.random.default_rng(1).uniform(-2e-6, 2e-6, (len(rows), 3))
    packing = Path(tempfile.mkdtemp(prefix="talus_thm_")) / "jittered.spheres"
    np.savetxt(packing, rows, fmt="%.9e")
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    cpu = {"talus": 0.0, "yade": 0.0}
    for mode, ax in zip(("noflow", "flow"), axes):
        runs = {program: twin.run(SCRIPT, {"mode": mode, "steps": steps, "packing": str(packing)}, program)
                for program in ("talus", "yade")}
        t, y = runs["talus"], runs["yade"]
        if t["ids"] != y["ids"] or t["contacts"] != y["contacts"]:
            raise RuntimeError(f"{mode}: the two programs do not have the same spheres and contacts")
        fluid0 = 343.15 if mode == "noflow" else T0
        spheres = field_error(t["temp"], y["temp"], T0)
        pores = field_error(t["poreTemp"], y["poreTemp"], fluid0)
        for program in cpu:
            cpu[program] += runs[program]["cpu"]
        print(f"{mode}: spheres {spheres:.2e}, pores {pores:.2e} of Yade's largest change; CPU Talus "
              f"{t['cpu']:.2f} s, Yade {y['cpu']:.2f} s; cells {t['cells']} / {y['cells']}")
        case.record(f"{mode} scenario, {steps} steps: largest |T_Talus - T_Yade| over the sphere temperatures and the "
                    "pore temperatures at 24 probes, relative to the largest change of Yade's field",
                    max(spheres, pores), "Yade 2023.02a ThermalEngine, same script (cases/yade/thermal_scenario.py)",
                    0.01, suffix=mode, spheres=spheres, pores=pores, cells=[t["cells"], y["cells"]])
        if mode == "flow":
            heat_t, heat_y = heat_flux(t), heat_flux(y)
            difference = abs(heat_t / heat_y - 1)
            print(f"heat flux at x = 10 mm: Talus {heat_t:.5e} W, Yade {heat_y:.5e} W ({difference:.2e}); volume flux "
                  f"{t['outflux']:.6e} / {y['outflux']:.6e} m3/s")
            case.record(f"flow scenario, {steps} steps: relative difference of the heat flux carried across x = 10 mm, "
                        "rho Cp Q (T_plane - T0) (Q the volume flux through xmax, T_plane the mean pore temperature of "
                        "the 6 probes at x = 10 mm), from Yade's", difference, "Yade 2023.02a, same script", 0.01,
                        suffix="heat-flux", talus=heat_t, yade=heat_y, fluxes=[t["outflux"], y["outflux"]])
        ax.plot(y["temp"], t["temp"], "o", ms=2, label="spheres")
        ax.plot(y["poreTemp"], t["poreTemp"], "s", ms=3, label="pores (probes)")
        low = min(min(y["temp"]), min(y["poreTemp"]))
        high = max(max(y["temp"]), max(y["poreTemp"]))
        ax.plot([low, high], [low, high], "k-", lw=0.6)
        ax.set_xlabel("Yade temperature (K)")
        ax.set_ylabel("Talus temperature (K)")
        ax.set_title(f"{mode}, {steps} steps")
        ax.legend()
    case.save_chart(fig)
    bench = results.Case("thm.bench.coupled", quick=args.quick, folder=args.results)
    ratio = cpu["yade"] / cpu["talus"]
    print(f"coupled steps: Yade {cpu['yade']:.2f} s, Talus {cpu['talus']:.2f} s CPU: {ratio:.2f}x")
    bench.record("Yade CPU time / Talus CPU time over the coupled steps of both scenarios (FlowEngine, ThermalEngine, "
                 "DEM step; one thread each)", ratio, "Yade 2023.02a, same script and steps", 3, comparison=">=",
                 talusCpu=cpu["talus"], yadeCpu=cpu["yade"])


if __name__ == "__main__":
    main()
