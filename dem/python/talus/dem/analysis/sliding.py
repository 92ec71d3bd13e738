"""Sliding-block experiments as the block and particle cases run them: load a body nearly
statically by ramping gravity up (or turning it), let it go, and fit its acceleration; a sweep
of slope angles against Coulomb's g (sin theta - cos theta tan phi); the contact force of a body
settling on its support."""

from __future__ import annotations

import math
from typing import Callable, Sequence

import numpy as np


def rampGravity(scene, newton, gravity: Callable[[float], Sequence[float]], seconds: float, stages: int = 20):
    """Set ``newton``'s gravity to ``gravity(k / stages)`` for k = 1 ... stages, each held for
    ``seconds / stages``. With damping on the contact springs load nearly statically: a sudden
    load overshoots, and can slip a block past a Coulomb limit that holds it under a static one."""
    for k in range(1, stages + 1):
        newton.gravity = tuple(gravity(k / stages))
        scene.run(int(round(seconds / stages / scene.dt)), True)


def tilted(g: float, theta: float) -> tuple[float, float, float]:
    """Gravity of magnitude g on a slope of angle theta whose downhill direction is +x."""
    return (g * math.sin(theta), 0.0, -g * math.cos(theta))


def slide(scene, body: int, seconds: float, direction=(1.0, 0.0, 0.0), every: int = 20):
    """Run ``seconds`` in runs of ``every`` steps; returns the times and the body's displacements
    along the unit ``direction`` since the call."""
    start = np.array(scene.bodies[body].state.pos)
    along = np.asarray(direction, dtype=float)
    times, moved = [], []
    for _ in range(int(round(seconds / scene.dt / every))):
        scene.run(every, True)
        times.append(scene.time)
        moved.append(float((np.array(scene.bodies[body].state.pos) - start) @ along))
    return np.array(times), np.array(moved)


def restingForce(scene, seconds: float, every: int = 20):
    """Run ``seconds`` in runs of ``every`` steps; returns the times and, after each run, the
    vertical normal force of the scene's first contact (0 while there is none)."""
    times, forces = [], []
    for _ in range(int(seconds / scene.dt / every)):
        scene.run(every, True)
        c = scene._cpp.contacts()
        times.append(scene.time)
        forces.append(float(c[0]["normalForce"][2]) if c else 0.0)
    return times, forces


def fittedAcceleration(times, moved) -> float:
    """Acceleration of the parabola fitted to the displacements (least squares)."""
    return 2.0 * float(np.polyfit(times, moved, 2)[0])


def coulombAcceleration(g: float, theta: float, phi: float) -> float:
    """A block's acceleration down a slope theta with friction angle phi: g (sin theta -
    cos theta tan phi), 0 where friction holds it."""
    return max(g * (math.sin(theta) - math.cos(theta) * math.tan(phi)), 0.0)


def inclineSweep(incline: Callable[[float, float], tuple[float, float]], thetas_deg: Sequence[float],
                 seconds: float, g: float, phi: float) -> dict:
    """Run ``incline(theta, seconds)`` -> (displacement, acceleration) at each angle. Returns the
    displacements, accelerations and Coulomb's accelerations, the worst relative error of the
    sliding ones (``slip``) and the largest displacement of those friction holds (``stick``)."""
    moved, accelerations, analytic = [], [], []
    for deg in thetas_deg:
        theta = math.radians(deg)
        s, a = incline(theta, seconds)
        moved.append(s)
        accelerations.append(a)
        analytic.append(coulombAcceleration(g, theta, phi))
        print(f"incline {deg:4.1f} deg: moved {s:.6f} m, acceleration {a:.5f} m/s^2, analytic {analytic[-1]:.5f}")
    return {"moved": moved, "accelerations": accelerations, "analytic": analytic,
            "slip": max(abs(a - ref) / ref for a, ref in zip(accelerations, analytic) if ref > 0),
            "stick": max(abs(s) for s, ref in zip(moved, analytic) if ref == 0)}


def plotInclineSweep(ax, thetas_deg: Sequence[float], sweep: dict, g: float, phi: float, label: str, title: str):
    """The sweep's accelerations against the slope angle, over Coulomb's curve (a matplotlib axis)."""
    fine = np.linspace(min(thetas_deg), max(thetas_deg), 200)
    ax.plot(fine, [coulombAcceleration(g, math.radians(t), phi) for t in fine], "k-", lw=0.8,
            label="g (sin theta - cos theta tan phi)")
    ax.plot(thetas_deg, sweep["accelerations"], "bo", label=label)
    ax.axvline(math.degrees(phi), color="r", ls=":", label="friction angle")
    ax.set_xlabel("slope angle theta (deg)")
    ax.set_ylabel("sliding acceleration (m/s^2)")
    ax.set_title(title)
    ax.legend(fontsize=8)
