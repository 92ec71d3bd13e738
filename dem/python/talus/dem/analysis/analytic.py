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


def spring_dashpot_restitution(mass: float, kn: float, cn: float) -> float:
    """Restitution of the linear spring-dashpot m u'' = -max(0, kn u + cn u'): the collision
    ends when the force would pull (Schwager and Poeschel 2007); under-, over- and critically
    damped. With beta = cn / 2m, omega0^2 = kn / m, below critical damping the force vanishes
    at omega t = pi - atan2(2 beta omega, omega^2 - beta^2)."""
    beta, omega0 = cn / (2 * mass), math.sqrt(kn / mass)
    if beta < omega0:
        omega = math.sqrt(omega0 ** 2 - beta ** 2)
        return math.exp(-beta / omega * (math.pi - math.atan2(2 * beta * omega, omega ** 2 - beta ** 2)))
    if beta > omega0:
        big = math.sqrt(beta ** 2 - omega0 ** 2)
        return math.exp(-beta / big * math.log((beta + big) / (beta - big)))
    return math.exp(-2.0)   # critical: the force vanishes at omega0 t = 2


def hertz_contact_time(mass: float, kno: float, v0: float) -> float:
    """Duration of an elastic Hertz impact at speed v0: 2.87 (m^2 / (kno^2 v0))^(1/5)."""
    return 2.87 * (mass ** 2 / (kno ** 2 * v0)) ** 0.2


def block_sliding_mode(weight, normals, tan_phi, tol: float = 1e-9) -> dict:
    """Limit equilibrium of a rigid block on fixed neighbours under a force ``weight`` (its
    weight), friction only (Goodman & Shi's block theory; for two faces the vector form of
    Hoek & Bray's wedge). ``normals``: the block's outward unit normals of its contact faces
    (pointing into what holds it), ``tan_phi``: each face's friction coefficient.

    The sliding mode is the one of lift-off (every face opens), sliding on one face (the others
    open or slide parallel) and sliding along the intersection line of two faces (both
    pressed, the others open) whose direction d no other face blocks (d . m <= 0). Returns
    ``mode`` ("lift", "plane", "wedge" or "none": no mode, the block is not removable),
    ``faces`` (indices), ``direction`` d, the normal reactions ``N`` per face of the mode,
    ``driving`` W . d and the factor of safety ``FS`` = sum(N tan phi) / (W . d) (0 for lift-off,
    inf for "none"). Of several admissible modes (only on degenerate geometry) the smallest FS."""
    W = np.asarray(weight, dtype=float)
    m = np.asarray(normals, dtype=float).reshape(-1, 3)
    mu = np.broadcast_to(np.asarray(tan_phi, dtype=float), (len(m),))
    scale = float(np.linalg.norm(W))
    w = W / scale

    def free(d, skip):
        return all(d @ m[k] <= tol for k in range(len(m)) if k not in skip)

    best = {"mode": "none", "faces": (), "direction": np.zeros(3), "N": [], "driving": 0.0, "FS": math.inf}

    def offer(mode, faces, d, N):
        driving = float(W @ d)
        FS = float(sum(n * mu[k] for n, k in zip(N, faces)) / driving) if faces else 0.0
        if FS < best["FS"]:
            best.update(mode=mode, faces=faces, direction=d, N=list(N), driving=driving, FS=FS)

    if free(w, ()):
        offer("lift", (), w, [])
    for i in range(len(m)):
        N = float(W @ m[i])
        tangential = w - (w @ m[i]) * m[i]
        if N > tol * scale and np.linalg.norm(tangential) > tol:
            d = tangential / np.linalg.norm(tangential)
            if free(d, (i,)):
                offer("plane", (i,), d, [N])
    for i in range(len(m)):
        for j in range(i + 1, len(m)):
            line = np.cross(m[i], m[j])
            if np.linalg.norm(line) < 1e-6:
                continue   # parallel faces: no intersection line
            d = line / np.linalg.norm(line)
            d = d if w @ d >= 0 else -d
            if w @ d <= tol or not free(d, (i, j)):
                continue
            # The reactions -N_i m_i - N_j m_j balance the weight's part normal to d.
            N = np.linalg.lstsq(np.column_stack([m[i], m[j]]), W - (W @ d) * d, rcond=None)[0]
            if N.min() > tol * scale:
                offer("wedge", (i, j), d, N)
    return best
