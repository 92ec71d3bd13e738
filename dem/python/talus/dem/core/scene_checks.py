"""Checks of a scene's setup that no single setter can make: an engine list that would integrate
the bodies twice or never detect a contact, a time step far above what the particles allow."""

from __future__ import annotations

import math
import os
import sys
import warnings

from talus.dem.step.engines import InsertionSortCollider, InteractionLoop, NewtonIntegrator

# O.dt above this many P-wave steps of the stiffest moving sphere is refused: the critical step
# of one linear contact of that sphere is at most about 4 P-wave steps, so none of its contacts
# could be stable, and a falling sphere crosses a wall or floor between two steps.
DT_LIMIT = 10.0


_PACKAGE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def _warn(text: str) -> None:
    """A RuntimeWarning pointing at the script's line (the first caller outside Talus)."""
    frame, level = sys._getframe(1), 2
    while frame is not None and os.path.abspath(frame.f_code.co_filename).startswith(_PACKAGE):
        frame, level = frame.f_back, level + 1
    warnings.warn(text, RuntimeWarning, stacklevel=level)


def _warn_or_raise(scene, text: str) -> None:
    """An error in a Talus scene; a warning in a scene run as Yade's (O.overlapStops off), since
    Yade runs it without a word."""
    if scene._cpp.overlapStops:
        raise ValueError(text)
    _warn(text)


def _with_slaves(engines):
    """The engines and, in their place, those of ParallelEngines' slaves."""
    for e in engines:
        yield e
        for slave in getattr(e, "slaves", ()):
            yield from _with_slaves(slave if isinstance(slave, list) else [slave])


def check_engines(engines) -> None:
    """Refuse two NewtonIntegrators moving the same bodies (each step would integrate them twice);
    warn of an InteractionLoop without a collider (no contact would ever be detected)."""
    def live(kind):
        return [(k, e) for k, e in enumerate(engines) if isinstance(e, kind) and not getattr(e, "dead", False)]

    newtons = live(NewtonIntegrator)
    for a, (k, first) in enumerate(newtons):
        for m, second in newtons[a + 1:]:
            # mask <= 0 moves every body (Yade's); two positive masks share a body only through a bit
            if first.mask <= 0 or second.mask <= 0 or first.mask & second.mask:
                raise ValueError(f"O.engines has two NewtonIntegrators (engines {k} and {m}) moving the same bodies "
                                 f"(masks {first.mask} and {second.mask}): each step would integrate them twice; "
                                 "keep one, or give them masks without a common bit")
    loops = live(InteractionLoop)
    if loops and not any(isinstance(e, InsertionSortCollider) for e in _with_slaves(engines)):
        _warn(f"O.engines has an InteractionLoop (engine {loops[0][0]}) but no collider (InsertionSortCollider): "
              "no contact will be detected, only interactions created by hand (createInteraction) will act")


def check_time_step(scene) -> None:
    """Before a run: refuse an O.dt more than DT_LIMIT times the P-wave step of the stiffest
    moving sphere, contacts or not (in a sparse scene nothing else would notice), where contacts
    can form: an InteractionLoop and two bodies or more (a lone sphere settling in a fluid may
    take the fluid's step). Checked again only when O.dt, the bodies or the engines change; not
    while a time stepper sets O.dt."""
    cpp = scene._cpp
    engines = scene._running()
    key = (cpp.dt, cpp.bodiesVersion, cpp.materialCount())
    checked = scene.__dict__.get("_checkedTimeStep")
    if checked is not None and checked[0] == key and checked[1] is engines:
        return
    contacts = cpp.bodyCount() >= 2 and any(isinstance(e, InteractionLoop) and not getattr(e, "dead", False)
                                            for e in engines)
    stepper = scene._timeStepper()
    step, body = cpp.stiffestSphere() if contacts and (stepper is None or not stepper.active) else (math.inf, -1)
    if body >= 0 and cpp.dt > DT_LIMIT * step:
        _refuse_time_step(scene, step, body)
    scene.__dict__["_checkedTimeStep"] = (key, engines)    # refused, it is checked again at the next run


def _refuse_time_step(scene, step: float, body: int) -> None:
    cpp = scene._cpp
    b = scene.bodies[body]
    _warn_or_raise(scene, f"O.dt = {cpp.dt:.3g} is {cpp.dt / step:.3g} times the P-wave critical step {step:.3g} of "
                          f"sphere {body} (radius {b.shape.radius:.3g}, young {b.material.young:.3g} of material "
                          f"'{b.material.label}'): its contacts cannot be stable and a moving sphere can pass through "
                          f"a wall or another sphere in one step; the safe range is O.dt <= PWaveTimeStep() "
                          f"(usually 0.2 to 0.8 times it; refused above {DT_LIMIT:g} times)")

