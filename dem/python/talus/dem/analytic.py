"""Reference solutions of contact models, for validation (tests and cases)."""

from __future__ import annotations

import math

import numpy as np


def thornton_damping_ratio(e: float) -> float:
    """Damping ratio (fraction of the critical 2 sqrt(m kn)) that Yade's
    Ip2_FrictMat_FrictMat_MindlinPhys gives for restitution ``e`` (Thornton et al. 2013, B6-B7)."""
    if e == 1:
        return 0.0
    h = [-6.918798, -16.41105, 146.8049, -796.4559, 2928.711, -7206.864, 11494.29, -11342.18, 6276.757, -1489.915]
    alpha = e * np.polynomial.polynomial.polyval(e, h)
    return math.sqrt(1 / (1 - (1 + e) ** 2 * math.exp(alpha)) - 1)


def hertz_restitution(mass: float, kno: float, beta: float, v0: float) -> float:
    """Restitution of the damped Hertz contact m u'' = -max(0, kno u^1.5 + 2 beta sqrt(m 3/2 kno
    u^0.5) u') from u = 0, u' = v0 until u = 0 again, integrated to 1e-12 (scipy's DOP853)."""
    from scipy.integrate import solve_ivp

    def rhs(_, y):
        u, v = max(y[0], 0.0), y[1]
        f = kno * u ** 1.5 + 2 * beta * math.sqrt(mass * 1.5 * kno * math.sqrt(u)) * v
        return [v, -max(f, 0.0) / mass]

    def leaves(_, y):
        return y[0]
    leaves.terminal, leaves.direction = True, -1
    t0 = 1e-9 * (mass ** 2 / (kno ** 2 * v0)) ** 0.2   # start just inside: no event at t = 0
    sol = solve_ivp(rhs, (0, 1.0), [v0 * t0, v0], method="DOP853", rtol=1e-12, atol=1e-20, events=leaves)
    return -sol.y_events[0][0][1] / v0


def hertz_contact_time(mass: float, kno: float, v0: float) -> float:
    """Duration of an elastic Hertz impact at speed v0: 2.87 (m^2 / (kno^2 v0))^(1/5)."""
    return 2.87 * (mass ** 2 / (kno ** 2 * v0)) ** 0.2
