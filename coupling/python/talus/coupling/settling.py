"""What one sphere settling from rest in a fluid at rest should do, the reference of the coupled
settling cases (cases/cfd/cfd_settling_sphere_va.py, cases/cfd/cfd_settling_sphere_pf.py): the
Schiller-Naumann drag with Newton's C_d = 0.44 from Re = 1000 (the solvers' `SchillerNaumann`,
foam-solvers/talusCouplingCommon/dragClosure.H), its terminal velocity, and the equation of
motion integrated in time."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["SettlingSphere", "schiller_naumann_correction", "settling_row"]


def schiller_naumann_correction(re: float) -> float:
    """The drag over Stokes drag, C_d Re / 24: 1 + 0.15 Re^0.687 below Re = 1000, 0.44 Re / 24 above."""
    return 1 + 0.15 * re ** 0.687 if re < 1000 else 0.44 * re / 24


@dataclass(frozen=True)
class SettlingSphere:
    """A sphere of ``diameter`` [m] and ``density`` [kg/m3] in a fluid of density ``rhoFluid``
    and kinematic viscosity ``nu`` under gravity ``gravity`` [m/s2]; ``addedMassCoefficient``
    C_m adds C_m rho V to the inertia (0: none, as with the point-force solver)."""
    diameter: float
    density: float
    rhoFluid: float
    nu: float
    gravity: float = 9.81
    addedMassCoefficient: float = 0.0

    @property
    def volume(self) -> float:
        return math.pi * self.diameter ** 3 / 6

    @property
    def relaxation_time(self) -> float:
        """The Stokes relaxation time rho_p d^2 / (18 mu) [s]."""
        return self.density * self.diameter ** 2 / (18 * self.rhoFluid * self.nu)

    def reynolds(self, v: float) -> float:
        return abs(v) * self.diameter / self.nu

    def drag(self, v: float) -> float:
        """The Schiller-Naumann drag [N] at settling velocity v [m/s]."""
        return 3 * math.pi * self.rhoFluid * self.nu * self.diameter * v * schiller_naumann_correction(self.reynolds(v))

    def terminal_velocity(self) -> float:
        """Where the drag balances the buoyant weight (bisection to round-off)."""
        weight = (self.density - self.rhoFluid) * self.volume * self.gravity
        lo, hi = 0.0, 1.0
        while self.drag(hi) < weight:
            hi *= 2
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if self.drag(mid) < weight else (lo, mid)
        return 0.5 * (lo + hi)

    def velocity_history(self, t_end: float, dt: float) -> tuple[np.ndarray, np.ndarray]:
        """Times and settling velocities from rest to ``t_end``: (m + C_m rho V) dv/dt =
        (m - rho V) g - drag(v), integrated with RK4 steps of ``dt``."""
        inertia = (self.density + self.addedMassCoefficient * self.rhoFluid) * self.volume
        weight = (self.density - self.rhoFluid) * self.volume * self.gravity
        accel = lambda v: (weight - self.drag(v)) / inertia
        t, v, ts, vs = 0.0, 0.0, [0.0], [0.0]
        while t < t_end:
            k1 = accel(v); k2 = accel(v + dt / 2 * k1); k3 = accel(v + dt / 2 * k2); k4 = accel(v + dt * k3)
            v += dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
            t += dt
            ts.append(t); vs.append(v)
        return np.array(ts), np.array(vs)


def settling_row(t, v, terminal: float, reference: tuple, coupling, elapsed: float, diameter: float, dx: float,
                 fluid_steps: int, procs: int, ax=None) -> dict:
    """One coupled settling run against the `terminal` velocity and the equation of motion
    `reference` (times, velocities): its row for the case's table (final error, largest
    deviation during the fall, both over the terminal velocity), printed, and its curve drawn on
    `ax`."""
    t_ref, v_ref = reference
    transient = float(np.max(np.abs(v - np.interp(t, t_ref, v_ref)))) / terminal
    row = dict(d_over_dx=diameter / dx, dx=dx, v_end=float(v[-1]), t_end=float(t[-1]),
               rel_error_end=(v[-1] - terminal) / terminal, max_transient_error=transient, wall_time_s=elapsed,
               max_Re_p=coupling.maxReynolds, fluid_cells=coupling.link.nCells)
    print(f"  d/dx {diameter / dx:.3f}: v({t[-1]:.3g} s) {v[-1]:.6e} m/s ({row['rel_error_end']:+.3%} vs terminal), "
          f"largest deviation from the equation of motion {transient:.3%} of w, Re_p {coupling.maxReynolds:.2f}; "
          f"{fluid_steps} fluid steps in {elapsed:.1f} s on {procs} fluid rank(s)")
    if ax is not None:
        ax.plot(t, v * 100, "-", lw=1.2, label=f"d/dx = {diameter / dx:.2f}")
    return row
