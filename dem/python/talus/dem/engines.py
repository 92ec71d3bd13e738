"""Engines of a time step, with Yade's names and parameters.

A Yade engine list ports as it is::

    O.engines = [
        ForceResetter(),
        InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
        InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
                        [Ip2_FrictMat_FrictMat_FrictPhys()],
                        [Law2_ScGeom_FrictPhys_CundallStrack()]),
        NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.2),
        PyRunner(command="checkUnbalanced()", iterPeriod=100),
    ]

Bounding-volume (Bo1) and geometry (Ig2) functors are accepted for compatibility: Talus picks
the geometry from the shapes. Physics (Ip2) and law (Law2) functors choose the contact model;
each Law2 needs its Ip2 in the list, as in Yade.
"""

from __future__ import annotations

import __main__
from typing import Callable, Sequence

from talus import _dem


class Functor:
    """A Yade functor named in an engine's functor list."""

    def __init__(self, label: str = ""):
        self.label = label

    def __repr__(self):
        return f"{type(self).__name__}()"


def _functor(name: str, doc: str) -> type:
    return type(name, (Functor,), {"__doc__": doc})


Bo1_Sphere_Aabb = _functor("Bo1_Sphere_Aabb", "Bounding box of spheres (accepted; Talus bounds shapes itself).")
Bo1_Wall_Aabb = _functor("Bo1_Wall_Aabb", "Bounding box of walls (accepted; Talus bounds shapes itself).")
Bo1_Facet_Aabb = _functor("Bo1_Facet_Aabb", "Bounding box of facets (accepted; Talus bounds shapes itself).")
Bo1_Box_Aabb = _functor("Bo1_Box_Aabb", "Bounding box of boxes (accepted; Talus bounds shapes itself).")
Ig2_Box_Sphere_ScGeom = _functor("Ig2_Box_Sphere_ScGeom", "Box-sphere contact geometry (face, edge, corner).")
Ig2_Sphere_Sphere_ScGeom = _functor("Ig2_Sphere_Sphere_ScGeom", "Sphere-sphere contact geometry.")
Ig2_Facet_Sphere_ScGeom = _functor("Ig2_Facet_Sphere_ScGeom", "Facet-sphere contact geometry (face, edge, vertex).")
Ig2_Wall_Sphere_ScGeom = _functor("Ig2_Wall_Sphere_ScGeom", "Wall-sphere contact geometry.")
Ip2_FrictMat_FrictMat_FrictPhys = _functor(
    "Ip2_FrictMat_FrictMat_FrictPhys", "Stiffness and friction of linear contacts from FrictMat parameters.")
Ip2_ViscElMat_ViscElMat_ViscElPhys = _functor(
    "Ip2_ViscElMat_ViscElMat_ViscElPhys", "Spring-dashpot parameters from ViscElMat (tc, en, et or kn, cn, ks, cs).")


class _Law(Functor):
    _cpp_name = ""

    def __init__(self, label: str = ""):
        super().__init__(label)
        self._cpp = _dem.make_contact_law(self._cpp_name)


class Law2_ScGeom_FrictPhys_CundallStrack(_Law):
    """Linear elastic normal force and incremental shear force with Coulomb friction."""
    _cpp_name = "Law2_ScGeom_FrictPhys_CundallStrack"


class Law2_ScGeom_ViscElPhys_Basic(_Law):
    """Linear spring-dashpot normal and shear forces with Coulomb friction."""
    _cpp_name = "Law2_ScGeom_ViscElPhys_Basic"


class Engine:
    """Base of the engines: holds the C++ engine and forwards its parameters."""

    _cpp: object

    @property
    def label(self) -> str:
        return self._cpp.label

    @label.setter
    def label(self, value: str):
        self._cpp.label = value

    @property
    def dead(self) -> bool:
        return self._cpp.dead

    @dead.setter
    def dead(self, value: bool):
        self._cpp.dead = value

    def __repr__(self):
        return f"{type(self).__name__}(label={self.label!r})"


class ForceResetter(Engine):
    """Sets every body's force and torque to its persistent external force and torque."""

    def __init__(self, label: str = ""):
        self._cpp = _dem.ForceResetter()
        self.label = label


class InsertionSortCollider(Engine):
    """Contact detection with a Verlet skin ``verletDist`` (negative: a fraction of the smallest
    radius, Yade's default -0.5). Implemented with linked cells; Yade's name is kept."""

    def __init__(self, boundDispatcher: Sequence[Functor] = (), verletDist: float = -0.5, label: str = ""):
        self._cpp = _dem.Collider()
        self._cpp.verletDist = verletDist
        self.label = label

    verletDist = property(lambda self: self._cpp.verletDist,
                          lambda self, v: setattr(self._cpp, "verletDist", v))
    rebuilds = property(lambda self: self._cpp.rebuilds, doc="number of re-detections so far")


class InteractionLoop(Engine):
    """Contact geometry, physics and forces of every contact."""

    def __init__(self, geomFunctors: Sequence[Functor] = (), physFunctors: Sequence[Functor] = (),
                 lawFunctors: Sequence[Functor] = (), label: str = ""):
        laws = [f for f in lawFunctors if isinstance(f, _Law)]
        unknown = [f for f in lawFunctors if not isinstance(f, _Law)]
        if unknown:
            raise TypeError(f"InteractionLoop: not contact laws: {unknown}")
        if not laws:
            raise ValueError("InteractionLoop needs at least one Law2 functor, e.g. "
                             "Law2_ScGeom_FrictPhys_CundallStrack()")
        phys = {type(f).__name__ for f in physFunctors}
        for law in laws:
            if law._cpp.physicsName not in phys:
                raise ValueError(f"InteractionLoop: {type(law).__name__} needs "
                                 f"{law._cpp.physicsName}() in the physics functors")
        self._cpp = _dem.InteractionLoop()
        self._cpp.laws = [law._cpp for law in laws]
        self.geomFunctors, self.physFunctors, self.lawFunctors = list(geomFunctors), list(physFunctors), laws
        self.label = label


class NewtonIntegrator(Engine):
    """Leap-frog integration with ``gravity`` and Cundall's non-viscous ``damping``."""

    def __init__(self, gravity=(0.0, 0.0, 0.0), damping: float = 0.2, label: str = ""):
        self._cpp = _dem.NewtonIntegrator()
        self.gravity = gravity
        self.damping = damping
        self.label = label

    gravity = property(lambda self: tuple(self._cpp.gravity),
                       lambda self, g: setattr(self._cpp, "gravity", [float(x) for x in g]))
    damping = property(lambda self: self._cpp.damping, lambda self, d: setattr(self._cpp, "damping", float(d)))


class PyRunner(Engine):
    """Runs ``command`` every ``iterPeriod`` steps and/or every ``realPeriod`` seconds of wall
    time: a string executed in the script's namespace (as in Yade) or a Python callable."""

    def __init__(self, command: str | Callable[[], None] = "", iterPeriod: int = 0, realPeriod: float = 0,
                 initRun: bool = False, label: str = ""):
        if iterPeriod < 0 or realPeriod < 0 or (iterPeriod == 0 and realPeriod == 0):
            if iterPeriod == 0 and realPeriod == 0:
                iterPeriod = 1          # Yade's default: every step
            else:
                raise ValueError(f"PyRunner: iterPeriod and realPeriod must be >= 0, got {iterPeriod}, {realPeriod}")
        self._cpp = _dem.CallbackEngine()
        self._cpp.iterPeriod = iterPeriod
        self._cpp.realPeriod = float(realPeriod)
        self._cpp.initRun = initRun
        self.command = command
        self.label = label

    @property
    def command(self):
        return self._command

    @command.setter
    def command(self, command):
        self._command = command
        if callable(command):
            self._cpp.callback = command
        else:
            code = compile(command, f"<PyRunner {command!r}>", "exec")
            self._cpp.callback = lambda: exec(code, vars(__main__))

    iterPeriod = property(lambda self: self._cpp.iterPeriod, lambda self, v: setattr(self._cpp, "iterPeriod", v))
    nDone = property(lambda self: self._cpp.nDone)


__all__ = [
    "Functor", "Engine", "ForceResetter", "InsertionSortCollider", "InteractionLoop", "NewtonIntegrator",
    "PyRunner", "Bo1_Sphere_Aabb", "Bo1_Wall_Aabb", "Bo1_Facet_Aabb", "Bo1_Box_Aabb", "Ig2_Sphere_Sphere_ScGeom",
    "Ig2_Box_Sphere_ScGeom",
    "Ig2_Wall_Sphere_ScGeom", "Ig2_Facet_Sphere_ScGeom",
    "Ip2_FrictMat_FrictMat_FrictPhys", "Ip2_ViscElMat_ViscElMat_ViscElPhys",
    "Law2_ScGeom_FrictPhys_CundallStrack", "Law2_ScGeom_ViscElPhys_Basic",
]
