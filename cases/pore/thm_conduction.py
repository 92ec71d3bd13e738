"""Thermal case: a rod of spheres cooling from both ends (the set-up of Yade's
examples/ThermalEngine/conductionVerification.py) against Fourier's series, with the error against
the time step and the particle count, and the explicit scheme's stability limit.

Run:      build/bin/talus run cases/pore/thm_conduction.py [--quick] [--results DIR]
Set-up:   a chain of spheres (pack.regularOrtho in a 1 m box one sphere wide, gap -1e-8) at
          T0 = 400, the spheres that share a pore with the xmin and xmax boundaries of the
          FlowEngine's triangulation held at 0 (bndCondIsTemperature), particleK = 2,
          particleCp = 710, particleDensity = 2600, Yade's default conductance
          G = 2 (k1 + k2) r1 r2 / d = 2 k r between touching spheres. The chain is a discrete
          heat equation with diffusivity D = G d^2 / C = 6 k / (pi rho Cp) for spacing d = 2r and
          heat capacity C = rho 4/3 pi r^3 Cp, the same for every radius.
          Radii 24, 12, 6, 3 mm (20 to 166 spheres), time steps 0.5 to 8 s (the stable step C / 2G
          is 8.7 s for every radius); tsSafetyFactor 0: the thermal step is O.dt.
Checked:  the largest difference between the free spheres' temperatures at t = 30 000 s
          (D t / L^2 = 0.062) and Fourier's series T0 sum_n odd 4 / (n pi) sin(n pi x / L)
          exp(-n^2 pi^2 D t / L^2) over the held spheres' span L, relative to T0: <= 1e-3 for
          166 spheres and O.dt = 1 s (record thm.conduction); the error's order in the time
          step (slope of log error against log dt over the sweep at 166 spheres: 1 for explicit
          Euler, the error taken against the chain's exact solution in time (its modes), record
          thm.conduction.dt-order, >= 0.8) and in the particle spacing (slope of the error
          against Fourier's series against log(1 / N) at the smallest dt: 2 for the discrete
          Laplacian, 1.66 measured over 20-83 spheres, record thm.conduction.n-order, >= 1.5); a run with O.dt = 10 s above the stable step stops at its first step with an
          error naming the stable step and tsSafetyFactor (record thm.conduction.stability, 1).
Produces: records thm.conduction, thm.conduction.dt-order, thm.conduction.n-order,
          thm.conduction.stability; chart thm.conduction.png (temperature profile against
          Fourier's series, error against dt and N).
"""
import math

import numpy as np

from talus import results
from talus.dem import (O, Bo1_Box_Aabb, Bo1_Sphere_Aabb, ForceResetter, FrictMat, Ig2_Box_Sphere_ScGeom,
                       Ig2_Sphere_Sphere_ScGeom, InsertionSortCollider, InteractionLoop,
                       Ip2_FrictMat_FrictMat_FrictPhys, Law2_ScGeom_FrictPhys_CundallStrack, NewtonIntegrator,
                       aabbWalls)
from talus.dem.packing import pack
from talus.flow import FlowEngine, ThermalEngine

T0, K, CP, RHO = 400.0, 2.0, 710.0, 2600.0
T_END = 30000.0
DIFFUSIVITY = 6 * K / (math.pi * RHO * CP)


def fourier(x, t, length):
    x = np.asarray(x, dtype=float)
    out = np.zeros_like(x)
    for n in range(1, 400, 2):
        out += 4 / (n * math.pi) * np.sin(n * math.pi * x / length) * math.exp(-(n * math.pi) ** 2 * DIFFUSIVITY * t / length ** 2)
    return T0 * out


def chain_exact(n: int, t: float):
    """Temperatures of the n free spheres of a uniform chain between two held at 0, exact in time
    (the chain's modes: C dT_j/dt = G (T_j-1 - 2 T_j + T_j+1) with G / C = D / d^2): what the
    explicit scheme converges to as O.dt -> 0."""
    j = np.arange(1, n + 1)
    out = np.zeros(n)
    rate = DIFFUSIVITY / (1.0 / (n + 1)) ** 2      # G / C for the spacing d = L / (n + 1), L = 1
    for k in range(1, n + 1):
        mode = np.sin(j * k * math.pi / (n + 1))
        amplitude = 2 / (n + 1) * T0 * mode.sum()
        out += amplitude * mode * math.exp(-4 * rate * math.sin(k * math.pi / (2 * (n + 1))) ** 2 * t)
    return out


def rod(radius: float, dt: float):
    """The chain of spheres of `radius` along a 1 m box, its engines; returns the ThermalEngine."""
    O.reset()
    width = 8 / 3 * radius
    O.materials.append(FrictMat(young=1e6, poisson=0.5, frictionAngle=math.radians(3), density=RHO, label="spheres"))
    O.materials.append(FrictMat(young=1e6, poisson=0.5, frictionAngle=0, density=0, label="walls"))
    lo, hi = (0, 0, 0), (1.0, width, width)
    O.bodies.append(aabbWalls([lo, hi], thickness=0, material="walls"))
    O.bodies.append(pack.regularOrtho(pack.inAlignedBox(lo, hi), radius=radius, gap=-1e-8, material="spheres"))
    for b in O.bodies:
        b.dynamic = False
    flow = FlowEngine(label="flow")
    thermal = ThermalEngine(label="thermal", advection=False, fluidConduction=False, thermoMech=False,
                            solidThermoMech=False, fluidThermoMech=False, bndCondIsTemperature=[1, 1, 0, 0, 0, 0],
                            thermalBndCondValue=[0] * 6, tsSafetyFactor=0, particleDensity=RHO, particleT0=T0,
                            particleCp=CP, particleK=K)
    O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Box_Aabb()]),
                 InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Box_Sphere_ScGeom()],
                                 [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
                 flow, thermal, NewtonIntegrator(damping=0.2)]
    O.dt = dt
    flow.updateTriangulation = True
    flow.emulateAction()   # the triangulation only: it finds the spheres next to each boundary
    flow.dead = True
    return thermal


def cool(radius: float, dt: float):
    """Cool the rod to T_END; (x of the free spheres from the first held one, their temperatures,
    L, largest error against Fourier's series / T0, against the chain's exact solution / T0)."""
    rod(radius, dt)
    O.run(int(round(T_END / dt)), True)
    spheres = [b for b in O.bodies if type(b.shape).__name__ == "Sphere"]
    held = [b.state.pos[0] for b in spheres if b.state.Tcondition]
    start, length = min(held), max(held) - min(held)
    free = sorted((b for b in spheres if not b.state.Tcondition), key=lambda b: b.state.pos[0])
    x = np.array([b.state.pos[0] - start for b in free])
    t = np.array([b.state.temp for b in free])
    error = float(np.max(np.abs(t - fourier(x, O.time, length)))) / T0
    in_time = float(np.max(np.abs(t - chain_exact(len(free), O.time * length ** -2)))) / T0
    return x, t, length, error, in_time


def slope(x, y):
    return float(np.polyfit(np.log(x), np.log(y), 1)[0])


def main():
    parser = results.case_arguments(__doc__)
    args = parser.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    case = results.Case("thm.conduction", quick=args.quick, folder=args.results)
    steps = [1.0, 2.0, 4.0, 8.0] if args.quick else [0.5, 1.0, 2.0, 4.0, 8.0]
    radii = [0.024, 0.012, 0.006] if args.quick else [0.024, 0.012, 0.006, 0.003]
    dt_errors = []
    for dt in steps:
        x, t, length, error, in_time = cool(0.003, dt)
        dt_errors.append(in_time)
        print(f"r = 3 mm, dt = {dt:4.1f} s: largest error {error:.3e} T0 (Fourier), {in_time:.3e} T0 (exact in time)")
        if dt == 1.0:
            reference = (x, t, length, error)
    n_spheres, n_errors = [], []
    for r in radii:
        x, t, length, error, _ = cool(r, steps[0])
        n_spheres.append(len(x) + 2)
        n_errors.append(error)
        print(f"r = {r * 1e3:4.1f} mm ({n_spheres[-1]} spheres), dt = {steps[0]} s: largest error {error:.3e} T0")
    x, t, length, error = reference
    case.record("largest |T - T_Fourier| / T0 over the free spheres at t = 30000 s (166 spheres, O.dt = 1 s)", error,
                "Fourier's series with the chain's diffusivity D = G d^2 / C", 1e-3, maxTimeStep=C_over_2g())
    dt_order = slope(steps, dt_errors)
    case.record("order of the error in the time step (slope of log max |T - T_exact in time| against log O.dt, "
                "166 spheres; T_exact: the chain's modes)", dt_order,
                "explicit Euler: 1", 0.8, comparison=">=", steps=steps, errors=dt_errors, suffix="dt-order")
    n_order = slope(1 / np.array(n_spheres, dtype=float), n_errors)
    case.record(f"order of the error in the particle spacing (slope of log error against log 1/N, O.dt = {steps[0]} s)",
                n_order, "discrete Laplacian: 2", 1.5, comparison=">=", spheres=n_spheres, errors=n_errors,
                suffix="n-order")
    # past the stability limit: the run must stop, naming the limit and tsSafetyFactor
    rod(0.003, 10.0)
    message = ""
    try:
        O.run(1, True)
    except Exception as e:   # the step's own error, whatever its type
        message = str(e)
    stopped = float("stable" in message and "tsSafetyFactor" in message and O.iter == 0)
    print(f"O.dt = 10 s (stable step {C_over_2g():.3f} s): {message[:200]}")
    case.record("a run with O.dt = 10 s above the stable conduction step (tsSafetyFactor 0) stops at its first step "
                "with an error naming the stable step and tsSafetyFactor (1: yes)", stopped,
                "the explicit scheme's limit C / sum G", 1, comparison=">=", message=message, suffix="stability")

    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4))
    fine = np.linspace(0, length, 300)
    a.plot(fine, fourier(fine, T_END, length), "k-", lw=1, label="Fourier's series")
    a.plot(x, t, "o", ms=2, label="Talus, 166 spheres, dt = 1 s")
    a.set_xlabel("x from the held sphere (m)")
    a.set_ylabel("temperature")
    a.set_title(f"t = {T_END:.0f} s")
    a.legend()
    b.loglog(steps, dt_errors, "o-", label="against O.dt (166 spheres)")
    b2 = b.twiny()
    b2.loglog(n_spheres, n_errors, "s-", color="C1", label=f"against N (dt = {steps[0]} s)")
    b.set_xlabel("O.dt (s)")
    b2.set_xlabel("spheres N")
    b.set_ylabel("largest |T - T_Fourier| / T0")
    b.legend(loc="upper left")
    b2.legend(loc="lower right")
    case.save_chart(fig)


def C_over_2g() -> float:
    """The stable step C / (2G) of a free sphere with two contacts (any radius)."""
    r = 0.003
    return RHO * 4 / 3 * math.pi * r ** 3 * CP / (2 * 2 * K * r)


if __name__ == "__main__":
    main()
