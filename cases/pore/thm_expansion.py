"""Thermo-hydro-mechanical case: pore pressure from the thermal expansion of the pore fluid and of
the particles in a confined packing (ThermalEngine thermoMech, fluidThermoMech, solidThermoMech
on a FlowEngine network with a compressible fluid).

Run:      build/bin/talus run cases/pore/thm_expansion.py [--quick] [--results DIR]
Set-up:   the packing of Yade's examples/ThermalEngine (5cmEdge_1mm.spheres, 210 spheres of 4 mm in a
          5 cm box), mechanically static, saturated with water (fluidBulkModulus K_f = 2.2e9 Pa,
          fluidBeta = 2e-4 1/K), spheres and water at 293.15 K. The whole packing is heated
          uniformly (every pore's temperature and, by ThermalEngine.delT, every sphere's).
          1. Undrained (no boundary imposes a pressure): a step of dT = 1 K with particleAlpha = 0,
             then again with particleAlpha = 3e-5 1/K and solidThermoMech (the spheres grow and
             take void volume).
          2. Drained at xmin (pressure 0 there, no flux elsewhere): the same step dT, then the
             pressure decays by flow towards xmin. The hydraulic diffusivity of the rigid packing
             is c = k K_f / (mu n) (k its Darcy permeability, measured on the same network, n the
             network's void fraction); the viscosity sets the drainage time L^2 / c to 200 steps.
          3. The undrained-drained transition: heating at a constant rate to dT over a time t_h
             (T_h = c t_h / L^2 from 0.01 to 10), drained at xmin.
Checked:  1. the mean pore pressure (over the void volumes) against K_f fluidBeta dT (fluid alone,
             within 1e-6), and against K_f (fluidBeta dT V_f + dV_s) / V_f with the spheres'
             volume change dV_s = sum 4/3 pi ((r + alpha r dT)^3 - r^3) (within 1 %);
          2. the mean pressure after the step against the one-dimensional diffusion series with
             one drained face, p / p0 = sum 8 / ((2m+1)^2 pi^2) exp(-(2m+1)^2 pi^2 T / 4),
             T = c t / L^2: worst difference for T in [0.05, 1] (fraction of p0, <= 0.05);
          3. the mean pressure at the end of the heating against K_f fluidBeta dT (1 / T_h) sum
             2 / M^4 (1 - exp(-M^2 T_h)), M = (2m+1) pi / 2 (undrained for T_h -> 0, drained as
             1 / (3 T_h)): worst difference over the T_h (fraction of K_f fluidBeta dT, <= 0.05).
Produces: records thm.expansion.undrained, thm.expansion.undrained-solid, thm.expansion.drainage,
          thm.expansion.transition; chart thm.expansion.png (pressure decay and transition
          against the closed forms).
"""
import math
from pathlib import Path

import numpy as np

from talus import results
from talus.dem import (O, Bo1_Sphere_Aabb, Bo1_Wall_Aabb, ForceResetter, FrictMat, Ig2_Sphere_Sphere_ScGeom,
                       Ig2_Wall_Sphere_ScGeom, InsertionSortCollider, InteractionLoop, Ip2_FrictMat_FrictMat_FrictPhys,
                       Law2_ScGeom_FrictPhys_CundallStrack, NewtonIntegrator, aabbWalls, sphere)
from talus.dem.step.engines import PyRunner
from talus.flow import FlowEngine, ThermalEngine

PACKING = Path("/usr/share/doc/yade/examples/ThermalEngine/5cmEdge_1mm.spheres")
BOX = 0.05
T0, DT_HEAT = 293.15, 1.0
K_F, BETA, ALPHA = 2.2e9, 2e-4, 3e-5
STEP = 1e-5            # s
DRAINAGE_STEPS = 200   # L^2 / c in steps


def diffusion_mean(tv):
    """Mean excess pressure / initial one, one drained face (the Terzaghi series)."""
    tv = np.asarray(tv, dtype=float)
    out = np.zeros_like(tv)
    for m in range(200):
        big_m = math.pi * (2 * m + 1) / 2
        out += 2 / big_m ** 2 * np.exp(-big_m ** 2 * tv)
    return out


def ramp_mean(th):
    """Mean excess pressure at the end of a constant-rate heating over T_h, / (K_f beta dT)."""
    total = 0.0
    for m in range(200):
        big_m = math.pi * (2 * m + 1) / 2
        total += 2 / big_m ** 4 * (1 - math.exp(-big_m ** 2 * th))
    return total / th


def scene(drained: bool, alpha: float, viscosity: float = 1e-3):
    """The static packing with its FlowEngine (compressible water) and ThermalEngine."""
    O.reset()
    O.materials.append(FrictMat(young=1e9, poisson=0.5, frictionAngle=math.radians(3), density=2600, label="spheres"))
    O.materials.append(FrictMat(young=1e9, poisson=0.5, frictionAngle=0, density=0, label="walls"))
    O.bodies.append(aabbWalls([(0, 0, 0), (BOX, BOX, BOX)], thickness=0, material="walls"))
    rows = [[float(v) for v in line.split()] for line in PACKING.read_text().splitlines()
            if line.strip() and not line.startswith("#")]
    O.bodies.append([sphere((x, y, z), r, material="spheres", fixed=True) for x, y, z, r in rows])
    flow = FlowEngine(label="flow", viscosity=viscosity, fluidBulkModulus=K_F, tZero=T0, meshUpdateInterval=10 ** 9,
                      bndCondIsPressure=[1 if drained else 0, 0, 0, 0, 0, 0], bndCondValue=[0] * 6)
    thermal = ThermalEngine(label="thermal", advection=True, fluidConduction=True, uniformReynolds=10,
                            thermoMech=True, fluidThermoMech=True, solidThermoMech=True, fluidBeta=BETA,
                            particleAlpha=alpha, particleT0=T0, particleDensity=2600, particleK=2, particleCp=710,
                            fluidK=0.6, tsSafetyFactor=0)
    heater = PyRunner(command="heat()", iterPeriod=1)   # placed before the flow: heats, then the flow solves
    O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
                 InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
                                 [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
                 heater, flow, thermal, NewtonIntegrator(damping=0)]
    O.dt = STEP
    return flow, thermal


class Heating:
    """Adds `rate` K per step to every pore and sphere over `steps` steps from the next one,
    before the flow and thermal engines run (spheres and fluid together: no exchange between them)."""

    def __init__(self, flow):
        self.flow, self.rate, self.left = flow, 0.0, 0
        self.spheres = [b for b in O.bodies if type(b.shape).__name__ == "Sphere"]

    def start(self, total: float, steps: int):
        self.rate, self.left = total / steps, steps

    def __call__(self):
        if self.left <= 0 or self.flow._poreHeat is None:
            return
        heat = self.flow._poreHeat
        t = heat.temperatures()
        for i in range(len(t)):
            heat.setTemperature(i, t[i] + self.rate)
        for b in self.spheres:
            b.state.temp += self.rate
        self.left -= 1


def mean_pressure(flow) -> float:
    """Mean over the void volumes of the pores that store fluid (not those of a pressure boundary)."""
    v = np.maximum(flow.cellVoidVolumes, 0)
    drained = [k for k in range(6) if flow.bndCondIsPressure[k]]
    v[np.isin(flow._flow.poreVertexIds(), drained).any(axis=1)] = 0
    return float(np.sum(flow.pressures * v) / np.sum(v))


def run_heating(drained: bool, alpha: float, total: float, heat_steps: int, after: int, viscosity: float = 1e-3):
    """Heat by `total` over `heat_steps` steps, go on `after` steps; series of (steps since the
    heating started, mean pressure), the flow and the spheres' volume change."""
    import builtins
    flow, thermal = scene(drained, alpha, viscosity)
    heating = Heating(flow)
    builtins.heat = heating       # the PyRunner's command
    O.run(2, True)                # network, pore temperatures and the expansion's reference
    radii0 = np.array([b.shape.radius for b in O.bodies if type(b.shape).__name__ == "Sphere"])
    heating.start(total, heat_steps)
    series = [(0, mean_pressure(flow))]
    # the expansion of step n enters the flow's solve of step n + 1
    for k in range(heat_steps + after + 1):
        O.run(1, True)
        series.append((k + 1, mean_pressure(flow)))
    radii = np.array([b.shape.radius for b in O.bodies if type(b.shape).__name__ == "Sphere"])
    solid = float(np.sum(4 / 3 * math.pi * (radii ** 3 - radii0 ** 3)))
    return np.array(series), flow, solid


def permeability(flow) -> float:
    """Darcy permeability along x of the scene's packing (unit viscosity)."""
    probe = FlowEngine(bndCondIsPressure=[1, 1, 0, 0, 0, 0], bndCondValue=[1, 0, 0, 0, 0, 0], viscosity=1.0)
    probe.triangulateScene(O)
    probe.solve()
    return probe.samplePermeability(0, 1)


def main():
    parser = results.case_arguments(__doc__)
    args = parser.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    case = results.Case("thm.expansion", quick=args.quick, folder=args.results)
    p_fluid = K_F * BETA * DT_HEAT
    # 1. undrained, fluid alone then with the spheres' growth
    series, flow, _ = run_heating(False, 0.0, DT_HEAT, 1, 3)
    p = series[-1, 1]
    error = abs(p / p_fluid - 1)
    print(f"undrained, fluid: mean pressure {p:.6e} Pa against K_f beta dT = {p_fluid:.6e} Pa ({error:.2e})")
    case.record("relative difference of the mean pore pressure after a uniform 1 K step (undrained, rigid "
                "particles) from the closed form", error, "K_f fluidBeta dT", 1e-5, suffix="undrained",
                pressure=p, closedForm=p_fluid)
    series, flow, solid = run_heating(False, ALPHA, DT_HEAT, 1, 3)
    voids = float(np.sum(np.maximum(flow.cellVoidVolumes, 0)))
    p_solid = K_F * (BETA * DT_HEAT * voids + solid) / voids
    p = series[-1, 1]
    error = abs(p / p_solid - 1)
    print(f"undrained, fluid and spheres: {p:.6e} Pa against {p_solid:.6e} Pa ({error:.2e}); spheres alone "
          f"{K_F * solid / voids:.4e} Pa")
    case.record("relative difference of the mean pore pressure after a uniform 1 K step (undrained, spheres "
                "growing by particleAlpha = 3e-5) from the closed form", error,
                "K_f (fluidBeta dT V_f + dV_s) / V_f, dV_s the spheres' volume change", 0.01, suffix="undrained-solid",
                pressure=p, closedForm=p_solid, solidVolumeChange=solid, voidVolume=voids)

    # 2. drainage through xmin after a step
    flow, _ = scene(True, 0.0)
    flow.emulateAction()
    k = permeability(flow)
    # the network's porosity: its pores cover 75 % of the box (those of the box's edges and
    # corners are cut by two or three boundaries), and it is their void fraction that stores
    porosity = voids / float(np.sum(np.abs(flow.cellVolumes)))
    viscosity = k * K_F * DRAINAGE_STEPS * STEP / (porosity * BOX ** 2)   # L^2 / c = DRAINAGE_STEPS steps
    after = DRAINAGE_STEPS + (0 if args.quick else DRAINAGE_STEPS)
    series, flow, _ = run_heating(True, 0.0, DT_HEAT, 1, after, viscosity)
    tv = (series[1:, 0] - 1) / DRAINAGE_STEPS       # the pressure rises at the solve after the heating step
    ratio = series[1:, 1] / p_fluid
    window = (tv >= 0.05) & (tv <= 1)
    drainage_error = float(np.max(np.abs(ratio[window] - diffusion_mean(tv[window]))))
    late = (tv >= 0.4) & (ratio > 0)
    decay = float(-np.polyfit(tv[late], np.log(ratio[late]), 1)[0] / (math.pi ** 2 / 4)) if late.sum() > 2 else math.nan
    print(f"drainage: k = {k:.4e} m2, n = {porosity:.4f}, mu = {viscosity:.4e} Pa s; worst |p/p0 - series| "
          f"{drainage_error:.4f}; late decay rate / the series' {decay:.3f}")
    case.record("worst |mean pore pressure / (K_f fluidBeta dT) - diffusion series| for T = c t / L^2 in [0.05, 1] "
                "after a uniform 1 K step, drained at xmin", drainage_error,
                "one-dimensional diffusion with one drained face, c = k K_f / (mu n) (k, n measured on the packing)",
                0.05, suffix="drainage", permeability=k, porosity=porosity, viscosity=viscosity, decayRateRatio=decay)

    # 3. the transition: constant-rate heating over T_h
    durations = [0.01, 0.1, 1.0] if args.quick else [0.01, 0.03, 0.1, 0.3, 1.0, 3.0, 10.0]
    peaks = []
    for th in durations:
        steps = max(1, round(th * DRAINAGE_STEPS))
        run, _, _ = run_heating(True, 0.0, DT_HEAT, steps, 0, viscosity)
        # the pressure of the last heating step appears at the solve that follows it
        peaks.append(run[-1, 1] / p_fluid)
        print(f"T_h = {th:5.2f}: mean pressure {peaks[-1]:.4f} of K_f beta dT, closed form {ramp_mean(th):.4f}")
    transition_error = float(max(abs(p - ramp_mean(th)) for p, th in zip(peaks, durations)))
    case.record("worst |mean pore pressure at the end of a constant-rate heating / (K_f fluidBeta dT) - closed "
                "form| over heating times T_h = c t_h / L^2 from 0.01 to " + f"{durations[-1]:g}, drained at xmin",
                transition_error, "diffusion with a uniform source: (1 / T_h) sum 2 / M^4 (1 - exp(-M^2 T_h))", 0.05,
                suffix="transition", durations=durations, peaks=peaks)

    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4))
    fine = np.linspace(0.001, tv.max(), 400)
    a.plot(fine, diffusion_mean(fine), "k-", lw=1, label="diffusion series")
    a.plot(tv, ratio, "o", ms=2, label="Talus, mean pore pressure")
    a.set_xlabel("T = c t / L²")
    a.set_ylabel("p / (K_f β ΔT)")
    a.set_title("after a 1 K step, drained at xmin")
    a.legend()
    th_fine = np.logspace(-2.3, math.log10(max(durations)) + 0.2, 100)
    b.semilogx(th_fine, [ramp_mean(t) for t in th_fine], "k-", lw=1, label="closed form")
    b.semilogx(durations, peaks, "o", label="Talus")
    b.set_xlabel("heating time T_h = c t_h / L²")
    b.set_ylabel("p at the end of heating / (K_f β ΔT)")
    b.set_title("undrained (left) to drained (right)")
    b.legend()
    case.save_chart(fig)


if __name__ == "__main__":
    main()
