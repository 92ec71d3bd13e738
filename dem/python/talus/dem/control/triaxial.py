"""Yade's triaxial test engines, built on :class:`TriaxialStressController` (six walls):

* ``TriaxialCompressionEngine``: the state machine of a whole test (isotropic compaction to
  ``sigmaIsoCompaction``, optional unloading to ``sigmaLateralConfinement``, then loading of top
  and bottom at ``strainRate`` under that lateral stress), with Yade's autosaved files;
* ``ThreeDTriaxialEngine``: each axis in stress (``stressControl_i``, ``goal_i``) or at a
  strain rate (``strainRate_i``);
* ``TriaxialStateRecorder``: Yade's stress-strain record (``WallStresses`` files).

Use them as Yade does::

    walls = aabbWalls(material='frictionless'); wallIds = O.bodies.append(walls)
    triax = TriaxialCompressionEngine(internalCompaction=False, sigmaIsoCompaction=-50e3,
                                      sigmaLateralConfinement=-50e3, strainRate=0.01, max_vel=10)
    O.engines = [..., InteractionLoop(...), GlobalStiffnessTimeStepper(), triax,
                 TriaxialStateRecorder(iterPeriod=20, file='WallStresses'), NewtonIntegrator(damping=.4)]
"""

from __future__ import annotations

import inspect
import math
import weakref

import numpy as np

from talus import _dem
from talus.dem.control.controllers import TriaxialStressController, cpp_attribute, setContactFriction
from talus.dem.step.engines import PyRunner
from talus.dem.files.io import owner_scene
from talus.dem.base.linalg import Vector3
from talus.dem.analysis.measure import kineticEnergy, unbalancedForce

_CONTROLLER_PARAMS = tuple(inspect.signature(TriaxialStressController).parameters)


def _write_spheres(scene, path: str):
    """Yade's Shop::saveSpheresToFile: 'x y z r' of each dynamic sphere, 6 significant digits."""
    with open(path, "w") as f:
        for b in scene.bodies:
            if b is not None and b.dynamic and type(b.shape).__name__ == "Sphere":
                x, y, z = b.state.pos
                f.write(f"{x:g} {y:g} {z:g} {b.shape.radius:g}\n")


class _Driven(TriaxialStressController):
    """A controller subclass whose own parameters (``_OWN``) are saved with the controller's by
    O.save, and whose run-time state (``_STATE``) is restored by O.load."""

    _OWN: tuple[str, ...] = ()
    _STATE: tuple[str, ...] = ()

    def _io_params(self):
        return {name: self._plain(getattr(self, name)) for name in _CONTROLLER_PARAMS + self._OWN}

    @staticmethod
    def _plain(value):
        return tuple(float(x) for x in value) if isinstance(value, (np.ndarray, Vector3)) else value

    def _io_state(self):
        state = super()._io_state()
        state.update({name: self._plain(getattr(self._cpp, name)) for name in self._STATE})
        return state

    def _io_restore(self, state):
        own = {k: state.pop(k) for k in self._STATE if k in state}
        super()._io_restore(state)
        for k, v in own.items():
            setattr(self._cpp, k, np.asarray(v) if isinstance(v, tuple) else v)

    def setContactProperties(self, frictionDegree: float):
        """Give the dynamic bodies' materials and the current contacts this friction angle, in
        degrees (Yade's setContactProperties)."""
        setContactFriction(math.radians(frictionDegree), scene=owner_scene(self))


class TriaxialCompressionEngine(_Driven):
    """Yade's TriaxialCompressionEngine: a triaxial test as a state machine on six walls.

    ``currentState``: 1 isotropic compaction to ``sigmaIsoCompaction`` (by the walls, or by
    growing the spheres with ``internalCompaction``); 2 unloading to ``sigmaLateralConfinement``
    (if ``autoUnload`` and the two differ); 3 deviatoric loading: the lateral walls keep
    ``sigmaLateralConfinement`` while top and bottom approach each other at a strain rate
    relaxing towards ``strainRate`` (positive compresses) until |strain[1]| = ``epsilonMax``
    (if ``autoCompressionActivation``); 4 compaction at a fixed rate (``fixedPoroCompaction``);
    5 limbo (``autoStopSimulation`` pauses there). A phase ends once ``unbalancedForce`` <=
    ``StabilityCriterion`` with the mean stress within 0.5 % of its goal, tested every
    ``testEquilibriumInterval`` steps. Entering the loading, the strains restart from zero
    and, with ``frictionAngleDegree`` > 0, the contacts take that friction.

    Unless ``noFiles``, the state at the end of the isotropic phase is saved, as Yade does, to
    ``./<Key>_<Compacted|Unloaded>_<iter>_<state>.xml`` (a Talus checkpoint under Yade's name:
    ``O.reload()`` comes back to it) and its spheres to the same name in ``.spheres``.
    All of TriaxialStressController's parameters and read-outs apply."""

    _cpp_type = _dem.TriaxialCompressionEngine
    _OWN = ("strainRate", "currentStrainRate", "StabilityCriterion", "translationAxis", "autoCompressionActivation",
            "autoUnload", "autoStopSimulation", "testEquilibriumInterval", "currentState", "previousState",
            "sigmaIsoCompaction", "previousSigmaIso", "sigmaLateralConfinement", "Key", "noFiles",
            "frictionAngleDegree", "epsilonMax", "uniaxialEpsilonCurr", "fixedPoroCompaction", "fixedPorosity",
            "maxStress", "sigma_iso", "isAxisymetric", "UnbalancedForce", "warn")
    _STATE = ()

    def __init__(self, strainRate: float = 0, currentStrainRate: float = 0, StabilityCriterion: float = 0.001,
                 translationAxis=(0, 1, 0), autoCompressionActivation: bool = True, autoUnload: bool = True,
                 autoStopSimulation: bool = False, testEquilibriumInterval: int = 20, currentState: int = 0,
                 previousState: int = 0, sigmaIsoCompaction: float = 1, previousSigmaIso: float = 0,
                 sigmaLateralConfinement: float = 1, Key: str = "", noFiles: bool = False,
                 frictionAngleDegree: float = -1, epsilonMax: float = 0.5, uniaxialEpsilonCurr: float = 1,
                 fixedPoroCompaction: bool = False, fixedPorosity: float = 0, maxStress: float = 0,
                 sigma_iso: float = 0, isAxisymetric: bool = True, UnbalancedForce: float = 1, warn: int = 0,
                 **controller):
        super().__init__(**controller)
        values = locals()
        for name in self._OWN:
            setattr(self, name, values[name])
        me = weakref.ref(self)
        self._cpp.saveHook = lambda stem: me()._save(stem)

    strainRate = cpp_attribute("strainRate", kind=float)
    currentStrainRate = cpp_attribute("currentStrainRate", kind=float)
    StabilityCriterion = cpp_attribute("StabilityCriterion", kind=float)
    translationAxis = cpp_attribute("translationAxis", kind=lambda v: np.asarray(v, dtype=float).reshape(3))
    autoCompressionActivation = cpp_attribute("autoCompressionActivation", kind=bool)
    autoUnload = cpp_attribute("autoUnload", kind=bool)
    autoStopSimulation = cpp_attribute("autoStopSimulation", kind=bool)
    testEquilibriumInterval = cpp_attribute("testEquilibriumInterval", kind=int)
    currentState = cpp_attribute("currentState", "1 isotropic compaction, 2 unloading, 3 loading, 4 fixed-porosity "
                            "compaction, 5 limbo (0 before the first step)", kind=int)
    previousState = cpp_attribute("previousState", kind=int)
    sigmaIsoCompaction = cpp_attribute("sigmaIsoCompaction", kind=float)
    previousSigmaIso = cpp_attribute("previousSigmaIso", kind=float)
    sigmaLateralConfinement = cpp_attribute("sigmaLateralConfinement", kind=float)
    Key = cpp_attribute("Key", kind=str)
    noFiles = cpp_attribute("noFiles", kind=bool)
    frictionAngleDegree = cpp_attribute("frictionAngleDegree", kind=float)
    epsilonMax = cpp_attribute("epsilonMax", kind=float)
    uniaxialEpsilonCurr = cpp_attribute("uniaxialEpsilonCurr", kind=float)
    fixedPoroCompaction = cpp_attribute("fixedPoroCompaction", kind=bool)
    fixedPorosity = cpp_attribute("fixedPorosity", kind=float)
    maxStress = cpp_attribute("maxStress", kind=float)
    sigma_iso = cpp_attribute("sigma_iso", kind=float)
    isAxisymetric = cpp_attribute("isAxisymetric", kind=bool)
    UnbalancedForce = cpp_attribute("UnbalancedForce", kind=float)

    def _save(self, stem: str):
        scene = owner_scene(self)
        scene.save(stem + ".xml")
        _write_spheres(scene, stem + ".spheres")


def _axis_flag(name: str, axis: int, kind):
    def get(self):
        return getattr(self._cpp, name)[axis]

    def set(self, value):
        values = list(getattr(self._cpp, name))
        values[axis] = kind(value)
        setattr(self._cpp, name, values)
    return property(get, set)


class ThreeDTriaxialEngine(_Driven):
    """Yade's ThreeDTriaxialEngine: each axis i = 1, 2, 3 (x, y, z) in stress
    (``stressControl_i``: its walls keep ``goal_i``) or in strain (its two walls approach each
    other at a rate relaxing towards ``strainRate_i``, positive compresses, by
    (1 - ``strainDamping``) per step). ``internalCompaction`` grows the spheres as the
    controller does. At the first step the walls of the strain-controlled axes are switched off
    for the stress control (``wall_*_activated``) and, with ``updateFrictionAngle``, the friction
    becomes ``frictionAngleDegree``. ``strainDamping`` is this engine's own (default 0.9997), as
    in Yade, where it hides the controller's."""

    _cpp_type = _dem.ThreeDTriaxialEngine
    _OWN = ("strainRate1", "strainRate2", "strainRate3", "currentStrainRate1", "currentStrainRate2",
            "currentStrainRate3", "stressControl_1", "stressControl_2", "stressControl_3", "frictionAngleDegree",
            "updateFrictionAngle", "UnbalancedForce", "Key")
    _STATE = ("firstRun",)

    def __init__(self, strainRate1: float = 0, strainRate2: float = 0, strainRate3: float = 0,
                 currentStrainRate1: float = 0, currentStrainRate2: float = 0, currentStrainRate3: float = 0,
                 stressControl_1: bool = True, stressControl_2: bool = True, stressControl_3: bool = True,
                 strainDamping: float = 0.9997, frictionAngleDegree: float = -1, updateFrictionAngle: bool = False,
                 UnbalancedForce: float = 1, Key: str = "", **controller):
        super().__init__(**controller)
        values = locals()
        for name in self._OWN + ("strainDamping",):
            setattr(self, name, values[name])

    strainRate1, strainRate2, strainRate3 = (_axis_flag("strainRate", k, float) for k in range(3))
    currentStrainRate1, currentStrainRate2, currentStrainRate3 = (_axis_flag("currentStrainRate", k, float)
                                                                  for k in range(3))
    stressControl_1, stressControl_2, stressControl_3 = (_axis_flag("stressControl", k, bool) for k in range(3))
    strainDamping = cpp_attribute("strainRateDamping", "relaxation of the strain rates (this engine's, not the "
                             "controller's)", kind=float)
    frictionAngleDegree = cpp_attribute("frictionAngleDegree", kind=float)
    updateFrictionAngle = cpp_attribute("updateFrictionAngle", kind=bool)
    UnbalancedForce = cpp_attribute("UnbalancedForce", kind=float)
    Key = cpp_attribute("Key", kind=str)


class TriaxialStateRecorder(PyRunner):
    """Yade's TriaxialStateRecorder: every ``iterPeriod`` steps (and at the first, ``initRun``)
    appends to ``file`` (emptied first with ``truncate``; ``-<iter>`` added to its name with
    ``addIterNum``) the line ``iteration s11 s22 s33 e11 e22 e33 unb_force porosity kineticE``
    (the header when the file is empty) of the last TriaxialStressController, TriaxialCompressionEngine or
    ThreeDTriaxialEngine in O.engines: stresses on the right, top and front walls, strains,
    unbalancedForce, porosity of the box between the walls and kinetic energy, numbers as Yade
    writes them (17 significant digits)."""

    HEADER = "iteration s11 s22 s33 e11 e22 e33 unb_force porosity kineticE\n"

    def __init__(self, file: str = "", iterPeriod: int = 0, realPeriod: float = 0, initRun: bool = True,
                 truncate: bool = False, addIterNum: bool = False, label: str = ""):
        super().__init__(command=self._record, iterPeriod=iterPeriod, realPeriod=realPeriod, initRun=initRun,
                         label=label)
        self.file, self.truncate, self.addIterNum = str(file), bool(truncate), bool(addIterNum)
        self.porosity = 1.0
        self._path = None

    def _open(self, scene) -> str:
        path = self.file + (f"-{scene.iter}" if self.addIterNum else "")
        if not path:
            raise ValueError("TriaxialStateRecorder: file is empty")
        with open(path, "w" if self.truncate else "a"):
            pass
        return path

    def _controller(self, scene) -> TriaxialStressController:
        found = [e for e in scene.engines if isinstance(e, TriaxialStressController)]
        if not found:
            raise RuntimeError("TriaxialStateRecorder: O.engines has no TriaxialStressController, "
                               "TriaxialCompressionEngine or ThreeDTriaxialEngine")
        return found[-1]

    def _record(self):
        scene = owner_scene(self)
        if self._path is None:
            self._path = self._open(scene)
        triax = self._controller(scene)
        if scene.iter % triax.computeStressStrainInterval != 0:
            triax._cpp.computeStressStrain(scene._cpp)
        cpp = scene._cpp
        r = np.asarray(cpp.radius())
        solid = np.asarray(cpp.alive(), dtype=bool) & np.asarray(cpp.dynamic(), dtype=bool) & (r > 0)
        # Yade's constant, 1.3333333 for 4/3, so that the column is Yade's to the last digit
        volume = float(np.sum(1.3333333 * math.pi * r[solid] ** 3))
        box = triax.height * triax.width * triax.depth
        self.porosity = (box - volume) / box
        s, e = triax._cpp.stressVectors, triax._cpp.strain
        values = [s[1][0], s[3][1], s[5][2], e[0], e[1], e[2], unbalancedForce(scene=scene), self.porosity,
                  kineticEnergy(scene=scene)]
        with open(self._path, "a") as f:
            if f.tell() == 0:
                f.write(self.HEADER)
            f.write(f"{scene.iter} " + " ".join(f"{v:.17g}" for v in values) + "\n")


__all__ = ["TriaxialCompressionEngine", "ThreeDTriaxialEngine", "TriaxialStateRecorder"]
