"""Time stepper and stress/strain controllers, with Yade's names, parameters and read-outs:
``GlobalStiffnessTimeStepper``, ``PeriTriaxController`` (periodic cell), ``TriaxialStressController``
(six walls), and ``RayleighWaveTimeStep``, ``growParticles``.

Place the controllers after the InteractionLoop and before the NewtonIntegrator, as in Yade::

    O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
                 InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                                 [Law2_ScGeom_FrictPhys_CundallStrack()]),
                 PeriTriaxController(goal=(-1e5, -1e5, -1e5), stressMask=7, dynCell=True,
                                     maxUnbalanced=.1, relStressTol=1e-3, doneHook="done()", label="triax"),
                 NewtonIntegrator(damping=.2)]
"""

from __future__ import annotations

from typing import Callable

import numpy as np

from talus import _dem
from talus.dem import distributed
from talus.dem.step.engines import Engine, asCallback
from talus.dem.base.linalg import Vector3, as_value
from talus.dem.core.scenes import default_scene


def cpp_attribute(name: str, doc: str = "", kind=None):
    """A property reading and writing the C++ engine's attribute ``name`` (``kind`` converts);
    vectors and matrices are read as Yade's value types (a copy)."""
    def get(self):
        value = getattr(self._cpp, name)
        return as_value(value) if isinstance(value, np.ndarray) else value

    def set(self, value):
        setattr(self._cpp, name, kind(value) if kind else value)
    return property(get, set, doc=doc)


def _axis_mask(value) -> int:
    """A stressMask of the three axes (bits 1, 2, 4): higher bits would be ignored, so a mask
    beyond 7 is a mistake said at once."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not 0 <= value <= 7:
        raise ValueError(f"stressMask takes bits 1, 2, 4 (x, y, z): an integer from 0 to 7, got {value!r}")
    return int(value)


def done_hook_attribute():
    """Yade's doneHook of a controller: a command string or a callable, run when it reaches its
    goal (kept as given; the C++ engine gets the callable)."""
    def get(self):
        return self._doneHook

    def set(self, command):
        self._doneHook = command
        self._cpp.doneHook = asCallback(command, "doneHook")
    return property(get, set, doc="command run when the goal is reached (a string or a callable)")


def _vector(value) -> np.ndarray:
    v = np.asarray(value, dtype=float).reshape(-1)
    if v.shape != (3,) or not np.all(np.isfinite(v)):
        raise ValueError(f"expected 3 finite numbers, got {value!r}")
    return v


class GlobalStiffnessTimeStepper(Engine):
    """Sets ``O.dt`` to ``timestepSafetyCoefficient`` times the smallest critical step of the
    bodies on their contact stiffnesses (translational kn, ks and rotational ks r^2), every
    ``timeStepUpdateInterval`` steps; ``defaultDt`` (default: timestepSafetyCoefficient x P-wave)
    before any contact; at most 5 % growth per update; ``maxDt`` caps it. Put it after the
    InteractionLoop. As in Yade 2023, it overrides a step set by hand while ``active``.
    ``viscEl``: also bound the step by the contacts' dashpots (cn, cs), Yade's
    2 timestepSafetyCoefficient m / c per body (its option for ViscElPhys contacts).
    ``parallelMode`` (Yade's switch for its mpy module) changes nothing: under mpirun the step is
    always the smallest over every process."""

    def __init__(self, active: bool = True, timestepSafetyCoefficient: float = 0.8, defaultDt: float = -1,
                 maxDt: float = 1.7976931348623157e308, timeStepUpdateInterval: int = 1, viscEl: bool = False,
                 parallelMode: bool = False, label: str = ""):
        if not 0 < timestepSafetyCoefficient:
            raise ValueError(f"GlobalStiffnessTimeStepper: timestepSafetyCoefficient must be positive, got "
                             f"{timestepSafetyCoefficient}")
        if timeStepUpdateInterval < 1:
            raise ValueError(f"GlobalStiffnessTimeStepper: timeStepUpdateInterval must be >= 1, got {timeStepUpdateInterval}")
        self._cpp = _dem.GlobalStiffnessTimeStepper()
        self.active, self.timestepSafetyCoefficient, self.defaultDt = active, timestepSafetyCoefficient, defaultDt
        self.maxDt, self.timeStepUpdateInterval, self.viscEl, self.label = maxDt, timeStepUpdateInterval, viscEl, label
        self.parallelMode = bool(parallelMode)

    active = cpp_attribute("active", kind=bool)
    viscEl = cpp_attribute("viscEl", kind=bool)
    timestepSafetyCoefficient = cpp_attribute("timestepSafetyCoefficient", kind=float)
    defaultDt = cpp_attribute("defaultDt", kind=float)
    maxDt = cpp_attribute("maxDt", kind=float)
    timeStepUpdateInterval = cpp_attribute("timeStepUpdateInterval", kind=int)
    previousDt = cpp_attribute("previousDt", "last step set", kind=float)

    def stiffnessTimeStep(self, scene=None) -> float:
        """The step the current contacts allow (safety coefficient included), inf without contacts."""
        O = default_scene()
        return self._cpp.stiffnessTimeStep((scene or O)._cpp)

    def _io_state(self):
        return {"previousDt": self._cpp.previousDt, "computedOnce": self._cpp.computedOnce}

    def _io_restore(self, state):
        self._cpp.previousDt, self._cpp.computedOnce = float(state["previousDt"]), bool(state["computedOnce"])


class PeriTriaxController(Engine):
    """Stress or strain control of the periodic cell (Yade's PeriTriaxController). ``goal``:
    per axis a stress (bit i of ``stressMask`` set; compression negative) or a logarithmic
    strain log(trsf_ii). ``dynCell``: the cell accelerates as a mass (``mass``, default the total
    mass of the bodies) under the stress gap; otherwise the strain increment is the stress gap
    over the mean contact stiffness. ``maxStrainRate`` caps the rates. Once every goal is met
    (``relStressTol``, ``absStressTol``) with ``unbalancedForce()`` below ``maxUnbalanced``,
    ``doneHook`` (a command string run in the script's namespace, or a callable) is called.

    Read-outs: ``stress`` (diagonal), ``stressTensor``, ``strain`` (log of the diagonal of
    ``O.cell.trsf``, as Yade 2023: not trsf - 1), ``strainRate``, ``stiff``, ``currUnbalanced``."""

    def __init__(self, goal=(0, 0, 0), stressMask: int = 0, maxStrainRate=(1, 1, 1), maxUnbalanced: float = 1e-4,
                 absStressTol: float = 1e3, relStressTol: float = 3e-5, growDamping: float = .25, globUpdate: int = 5,
                 dynCell: bool = False, mass: float = float("nan"), doneHook: str | Callable[[], None] = "",
                 label: str = ""):
        self._cpp = _dem.PeriTriaxController()
        self.goal, self.stressMask, self.maxStrainRate = goal, stressMask, maxStrainRate
        self.maxUnbalanced, self.absStressTol, self.relStressTol = maxUnbalanced, absStressTol, relStressTol
        self.growDamping, self.globUpdate, self.dynCell, self.mass = growDamping, globUpdate, dynCell, mass
        self.doneHook, self.label = doneHook, label

    goal = cpp_attribute("goal", kind=_vector)
    stressMask = cpp_attribute("stressMask", kind=_axis_mask)
    maxStrainRate = cpp_attribute("maxStrainRate", kind=_vector)
    maxUnbalanced = cpp_attribute("maxUnbalanced", kind=float)
    absStressTol = cpp_attribute("absStressTol", kind=float)
    relStressTol = cpp_attribute("relStressTol", kind=float)
    growDamping = cpp_attribute("growDamping", kind=float)
    globUpdate = cpp_attribute("globUpdate", kind=int)
    dynCell = cpp_attribute("dynCell", kind=bool)
    mass = cpp_attribute("mass", kind=float)
    stress = cpp_attribute("stress")
    strain = cpp_attribute("strain")
    strainRate = cpp_attribute("strainRate")
    stiff = cpp_attribute("stiff")
    stressTensor = cpp_attribute("stressTensor")
    currUnbalanced = cpp_attribute("currUnbalanced")
    externalWork = cpp_attribute("externalWork")

    doneHook = done_hook_attribute()

    def _io_state(self):
        c = self._cpp
        return {"prevGrow": np.array(c.prevGrow), "stiff": np.array(c.stiff), "stress": np.array(c.stress),
                "maxBodySpan": np.array(c.maxBodySpan), "currUnbalanced": c.currUnbalanced,
                "externalWork": c.externalWork, "mass": c.mass}

    def _io_restore(self, state):
        for k, v in state.items():
            setattr(self._cpp, k, v)


class PeriIsoCompressor(Engine):
    """Compression of the periodic cell to ``stresses`` in turn (Yade's PeriIsoCompressor, which
    randomDensePack and randomPeriPack use): the stress is Yade's own measure, the sum of the
    contact forces' components over the cell's face area (larger than the mean stress); the
    cell grows by 1e-4 (goal - stress) area / stiffness per step, at most ``maxDisplPerStep``
    (default 1e-2 ``charLen``). Once the last stress is reached (0.5 %) with the unbalanced force
    below ``maxUnbalanced``, ``doneHook`` runs. ``keepProportions``: homothetic. Read-outs:
    ``state`` (index of the stress being reached), ``sigma``, ``avgStiffness``, ``currUnbalanced``."""

    def __init__(self, stresses=(), charLen: float = -1, maxSpan: float = -1, maxUnbalanced: float = 1e-4,
                 globalUpdateInt: int = 20, maxDisplPerStep: float = -1, keepProportions: bool = True,
                 doneHook: str | Callable[[], None] = "", label: str = ""):
        self._cpp = _dem.PeriIsoCompressor()
        self.stresses, self.charLen, self.maxSpan = stresses, charLen, maxSpan
        self.maxUnbalanced, self.globalUpdateInt, self.maxDisplPerStep = maxUnbalanced, globalUpdateInt, maxDisplPerStep
        self.keepProportions, self.doneHook, self.label = keepProportions, doneHook, label

    @property
    def stresses(self) -> list:
        return list(self._cpp.stresses)

    @stresses.setter
    def stresses(self, values):
        values = [float(s) for s in values]
        if not all(s < 0 for s in values):
            raise ValueError(f"PeriIsoCompressor: stresses must be negative (compression), got {values}")
        self._cpp.stresses = values

    charLen = cpp_attribute("charLen", kind=float)
    maxSpan = cpp_attribute("maxSpan", kind=float)
    maxUnbalanced = cpp_attribute("maxUnbalanced", kind=float)
    globalUpdateInt = cpp_attribute("globalUpdateInt", kind=int)
    maxDisplPerStep = cpp_attribute("maxDisplPerStep", kind=float)
    keepProportions = cpp_attribute("keepProportions", kind=bool)
    state = cpp_attribute("state", kind=int)
    sigma = cpp_attribute("sigma")
    avgStiffness = cpp_attribute("avgStiffness")
    currUnbalanced = cpp_attribute("currUnbalanced")

    doneHook = done_hook_attribute()


_WALLS = ("left", "right", "bottom", "top", "back", "front")


def _wall_id(k: int):
    def get(self):
        return self._cpp.wallIds[k]

    def set(self, value):
        ids = list(self._cpp.wallIds)
        ids[k] = int(value)
        self._cpp.wallIds = ids
    return property(get, set, doc=f"body id of the {_WALLS[k]} wall")


def _wall_active(k: int):
    def get(self):
        return self._cpp.wallActivated[k]

    def set(self, value):
        flags = list(self._cpp.wallActivated)
        flags[k] = bool(value)
        self._cpp.wallActivated = flags
    return property(get, set, doc=f"the {_WALLS[k]} wall moves as its goal says (else it stays)")


class TriaxialStressController(Engine):
    """Six walls around a packing, each axis servo-controlled to a stress or a strain rate (Yade's
    TriaxialStressController). ``stressMask`` bits 1, 2, 4 (x, y, z) say which of ``goal1``,
    ``goal2``, ``goal3`` are stresses (tension positive) rather than strain rates. Walls are
    planes given by id (``wall_left_id`` ... ``wall_front_id``; Yade's order left, right, bottom,
    top, back, front = ids 0..5 by default, as :func:`aabbWalls` appends them).
    ``internalCompaction`` (Yade's default True) grows the spheres instead of moving walls.

    Read-outs: ``stress(i)`` (mean stress vector on wall i = 0..5), ``strain`` (log of size over
    initial size), ``volumetricStrain``, ``meanStress``, ``porosity``, ``width``/``height``/``depth``,
    ``strainRate``, ``externalWork``."""

    _cpp_type = _dem.TriaxialStressController   # subclasses (talus.dem.control.triaxial) drive their own

    _PARAMS = ("goal1", "goal2", "goal3", "stressMask", "internalCompaction", "maxMultiplier", "finalMaxMultiplier",
               "max_vel", "stressDamping", "strainDamping", "thickness", "stiffnessUpdateInterval",
               "radiusControlInterval", "computeStressStrainInterval")

    def __init__(self, goal1: float = 0, goal2: float = 0, goal3: float = 0, stressMask: int = 7,
                 internalCompaction: bool = True, maxMultiplier: float = 1.001, finalMaxMultiplier: float = 1.00001,
                 max_vel: float = 1, stressDamping: float = .25, strainDamping: float = .99, thickness: float = -1,
                 stiffnessUpdateInterval: int = 10, radiusControlInterval: int = 10,
                 computeStressStrainInterval: int = 10, wall_left_id: int = 0, wall_right_id: int = 1,
                 wall_bottom_id: int = 2, wall_top_id: int = 3, wall_back_id: int = 4, wall_front_id: int = 5,
                 wall_left_activated: bool = True, wall_right_activated: bool = True,
                 wall_bottom_activated: bool = True, wall_top_activated: bool = True,
                 wall_back_activated: bool = True, wall_front_activated: bool = True, label: str = ""):
        self._cpp = self._cpp_type()
        values = locals()
        for name in self._PARAMS:
            setattr(self, name, values[name])
        for w in _WALLS:
            setattr(self, f"wall_{w}_id", values[f"wall_{w}_id"])
            setattr(self, f"wall_{w}_activated", values[f"wall_{w}_activated"])
        self.label = label

    goal1 = cpp_attribute("goal1", kind=float)
    goal2 = cpp_attribute("goal2", kind=float)
    goal3 = cpp_attribute("goal3", kind=float)
    stressMask = cpp_attribute("stressMask", kind=_axis_mask)
    internalCompaction = cpp_attribute("internalCompaction", kind=bool)
    maxMultiplier = cpp_attribute("maxMultiplier", kind=float)
    finalMaxMultiplier = cpp_attribute("finalMaxMultiplier", kind=float)
    max_vel = cpp_attribute("max_vel", kind=float)
    stressDamping = cpp_attribute("stressDamping", kind=float)
    strainDamping = cpp_attribute("strainDamping", kind=float)
    thickness = cpp_attribute("thickness", kind=float)
    stiffnessUpdateInterval = cpp_attribute("stiffnessUpdateInterval", kind=int)
    radiusControlInterval = cpp_attribute("radiusControlInterval", kind=int)
    computeStressStrainInterval = cpp_attribute("computeStressStrainInterval", kind=int)
    updatePorosity = cpp_attribute("updatePorosity", kind=bool)
    width0 = cpp_attribute("width0", kind=float)
    height0 = cpp_attribute("height0", kind=float)
    depth0 = cpp_attribute("depth0", kind=float)
    strain = cpp_attribute("strain")
    volumetricStrain = cpp_attribute("volumetricStrain")
    meanStress = cpp_attribute("meanStress")
    porosity = cpp_attribute("porosity")
    boxVolume = cpp_attribute("boxVolume")
    particlesVolume = cpp_attribute("particlesVolume")
    spheresVolume = particlesVolume
    width = cpp_attribute("width")
    height = cpp_attribute("height")
    depth = cpp_attribute("depth")
    externalWork = cpp_attribute("externalWork")
    previousMultiplier = cpp_attribute("previousMultiplier")

    wall_left_id, wall_right_id, wall_bottom_id = _wall_id(0), _wall_id(1), _wall_id(2)
    wall_top_id, wall_back_id, wall_front_id = _wall_id(3), _wall_id(4), _wall_id(5)
    wall_left_activated, wall_right_activated = _wall_active(0), _wall_active(1)
    wall_bottom_activated, wall_top_activated = _wall_active(2), _wall_active(3)
    wall_back_activated, wall_front_activated = _wall_active(4), _wall_active(5)

    def stress(self, id: int) -> Vector3:
        """Mean stress vector on wall ``id`` = 0..5 (left, right, bottom, top, back, front; Yade's
        internal numbering), tension positive."""
        if not 0 <= id <= 5:
            raise ValueError(f"TriaxialStressController.stress: wall index must be 0..5, got {id}")
        return Vector3(self._cpp.stressVectors[id])

    def force(self, id: int) -> Vector3:
        """Force of the spheres on wall ``id`` = 0..5 at the last stress update."""
        return Vector3(self._cpp.force[id])

    @property
    def strainRate(self) -> Vector3:
        """d/dt of (exx, eyy, ezz) from the walls' velocities."""
        from talus.dem.files.io import owner_scene
        v = owner_scene(self).velocities()
        ids = self._cpp.wallIds
        return Vector3([(v[ids[1]][0] - v[ids[0]][0]) / self.width, (v[ids[3]][1] - v[ids[2]][1]) / self.height,
                         (v[ids[5]][2] - v[ids[4]][2]) / self.depth])

    def _io_state(self):
        c = self._cpp
        return {k: getattr(c, k) for k in ("previousTranslation", "stiffness", "stressVectors", "force", "strain",
                                          "meanStress", "porosity", "particlesVolume", "width0", "height0", "depth0",
                                          "externalWork", "previousStress", "previousMultiplier", "first",
                                          "maxMultiplier")}

    def _io_restore(self, state):
        for k, v in state.items():
            setattr(self._cpp, k, [np.asarray(x) for x in v] if k in ("previousTranslation", "stressVectors", "force")
                    else v)


def RayleighWaveTimeStep(scene=None) -> float:
    """Yade's Rayleigh-wave critical step: min over spheres of pi r / (0.1631 nu + 0.876605)
    sqrt(rho / G), G = E / (2 (1 + nu)) (under mpirun, the whole scene's: collective)."""
    scene = scene or default_scene()
    value = distributed.smallest(_dem.rayleighWaveTimeStep(scene._cpp), scene)
    if value == float("inf"):
        raise ValueError("RayleighWaveTimeStep: the scene has no spheres")
    return value


def growParticles(multiplier: float, updateMass: bool = True, dynamicOnly: bool = True, scene=None):
    """Multiply the spheres' radii by ``multiplier`` (Yade's growParticles): masses and inertias
    follow (``updateMass``), current contacts keep their overlap history with scaled stiffness;
    a clump grows about its centroid (members' offsets and radii, mass and moments)."""
    O = default_scene()
    _dem.growParticles((scene or O)._cpp, float(multiplier), bool(updateMass), bool(dynamicOnly))


def setContactFriction(angleRad: float, scene=None):
    """Set the friction angle of the dynamic bodies' materials and of the existing contacts
    (Yade's setContactFriction): e.g. compact frictionless, then shear with friction."""
    O = default_scene()
    scene = scene or O
    _dem.setContactFriction(scene._cpp, float(angleRad))


__all__ = ["GlobalStiffnessTimeStepper", "PeriTriaxController", "PeriIsoCompressor", "TriaxialStressController",
           "RayleighWaveTimeStep",
           "growParticles", "setContactFriction"]
