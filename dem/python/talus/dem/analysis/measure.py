"""Measurements with Yade's names: unbalancedForce, getStress, avgNumInteractions,
fabricTensor, bodyStressTensors, porosity, getStressAndTangent. Tensors come as Yade's
Matrix3 (the tangent as a Matrix6).

Under ``mpirun -np N talus run`` they give the whole scene's value on every process (each body
and contact counted by one process, the shares summed over the processes, within round-off of
the serial run's): every process calls them, as a PyRunner does."""

from __future__ import annotations

import numpy as np

from talus import _dem
from talus.dem import distributed
from talus.dem.base.linalg import Matrix3, Matrix6, Vector3
from talus.dem.core.scenes import default_scene


def _scene(scene):
    if scene is None:
        O = default_scene()
        return O
    return scene


def _gravity(scene) -> np.ndarray:
    from talus.dem.step.engines import NewtonIntegrator
    for e in scene.engines:
        if isinstance(e, NewtonIntegrator):
            return np.asarray(e.gravity, dtype=float)
    return np.zeros(3)


def unbalancedForce(useMaxForce: bool = False, scene=None) -> float:
    """Mean (or largest) total force on dynamic bodies, gravity included, over the mean
    contact force: tends to 0 at equilibrium."""
    scene = _scene(scene)
    return _dem.unbalancedForce(scene._cpp, _gravity(scene), useMaxForce)     # under mpirun: the whole scene's


def getStress(volume: float = -1, scene=None) -> Matrix3:
    """Love-Weber stress -(1/V) sum f (x) l (compression negative, as Yade); `volume` defaults
    to the periodic cell's."""
    scene = _scene(scene)
    return Matrix3(_dem.loveWeberStress(scene._cpp, float(volume)))


def getStressAndTangent(volume: float = -1, symmetry: bool = True, form: str = "full",
                        scene=None) -> tuple[Matrix3, Matrix6]:
    """Love-Weber stress (as getStress) and the 6x6 contact-stiffness tangent operator in Voigt
    order xx, yy, zz, yz, xz, xy with engineering shear strains: d(stress) ~ tangent @ d(strain)
    for an affine strain increment without sliding (docs/dem.md gives the formula).
    ``form="yade"`` gives Yade's getStressAndTangent operator instead (shear stiffness only along
    the current shear force), to reproduce Yade's numbers."""
    if not symmetry:
        raise ValueError("getStressAndTangent: only the symmetric (Voigt) tangent is provided; use symmetry=True")
    if form not in ("full", "yade"):
        raise ValueError(f"getStressAndTangent: form must be 'full' or 'yade', got {form!r}")
    scene = _scene(scene)
    return (Matrix3(_dem.loveWeberStress(scene._cpp, float(volume))),
            Matrix6(_dem.contactStiffnessTangent(scene._cpp, float(volume), form == "yade")))


def avgNumInteractions(skipFree: bool = False, scene=None) -> float:
    """Mean coordination number 2 Nc / N of the spheres."""
    return _dem.coordinationNumber(_scene(scene)._cpp, skipFree)


def fabricTensor(scene=None) -> Matrix3:
    """(1/Nc) sum of n (x) n over sphere-sphere contacts."""
    return Matrix3(_dem.fabricTensor(_scene(scene)._cpp))


def bodyStressTensors(revertSign: bool = False, scene=None) -> list[Matrix3]:
    """Per body id, the mean stress in the solid sphere from its contact forces,
    (1/V) sum of force (x) arm over its contacts (Yade's bodyStressTensors: compression negative,
    the opposite with ``revertSign``); zero for bodies that are not spheres."""
    sign = -1.0 if revertSign else 1.0
    scene = _scene(scene)
    if (split := distributed.domain(scene)) is not None:     # under mpirun: every body's, by id
        return [sign * Matrix3(s) for s in split.bodyStressTensors(scene._cpp)]
    return [sign * Matrix3(s) for s in _dem.bodyStressTensors(scene._cpp)]


def porosity(volume: float = -1, scene=None) -> float:
    """1 - (sphere volume) / volume; `volume` defaults to the periodic cell's, else to the
    bounding box of the spheres."""
    scene = _scene(scene)
    if volume <= 0:
        if scene.periodic:
            volume = scene.cell.volume
        else:
            lo, hi = _sphere_box(scene, False, "porosity")
            volume = float(np.prod(hi - lo))
    return 1.0 - _dem.sphereVolume(scene._cpp) / volume


def _counted(scene) -> np.ndarray:
    """Per row, whether this process counts the body in sums over bodies (under mpirun each body
    on one process: its own bodies, the walls on process 0; in one process all)."""
    split = distributed.domain(scene)
    if split is None:
        return np.ones(len(scene._cpp.alive()), dtype=bool)
    return np.asarray(split.counted(scene._cpp), dtype=bool)


def _whole(scene, values) -> np.ndarray:
    """``values``, this process's shares of sums, summed over the processes under mpirun
    (collective); as they are in one process."""
    values = np.asarray(values, dtype=float)
    split = distributed.domain(scene)
    if split is None:
        return values
    return np.asarray(split.sum(values.ravel().tolist()), dtype=float).reshape(values.shape)


def _moving(scene) -> np.ndarray:
    """Rows of the bodies that carry momentum: alive, dynamic, not clump members (their clump
    does), of those this process counts."""
    cpp = scene._cpp
    rows = np.flatnonzero(np.asarray(cpp.alive(), dtype=bool) & np.asarray(cpp.dynamic(), dtype=bool) & _counted(scene))
    return np.array([i for i in rows if _dem.clump_id(cpp, int(i)) < 0], dtype=int)


def kineticEnergy(findMaxId: bool = False, scene=None):
    """Total kinetic energy of the dynamic bodies, 1/2 m v^2 + 1/2 w.I w, summed in id order as
    Yade's utils.kineticEnergy; with ``findMaxId``, ``(energy, id of the body with the most)``.
    In a periodic cell with homoDeform, of the fluctuations only, as Yade's and as O.energy's
    kinetic term: the velocity less the cell's field L x at the position the last step started
    from (x - dt v), the angular velocity less the cell's spin (L: Cell.prevVelGrad)."""
    scene = _scene(scene)
    if (split := distributed.domain(scene)) is not None:     # under mpirun: the whole scene's
        if not findMaxId:
            return split.kineticEnergy(scene._cpp)
        # the largest over the processes, and the lowest id having it (the serial run's first)
        per_body = np.asarray(_dem.body_kinetic_energies(scene._cpp))     # 0 for bodies counted elsewhere
        rows = np.flatnonzero(per_body)
        largest = -split.min(-float(per_body[rows].max())) if len(rows) else -split.min(0.0)
        mine = [split.globalIds([int(r)])[0] for r in rows if per_body[r] == largest]
        first = split.min(float(min(mine)) if mine and largest > 0 else np.inf)
        return split.kineticEnergy(scene._cpp), (int(first) if np.isfinite(first) else -1)
    per_body = np.asarray(_dem.body_kinetic_energies(scene._cpp))
    ids = np.flatnonzero(per_body)
    per_body = per_body[ids]
    total = float(np.add.accumulate(per_body)[-1]) if len(per_body) else 0.0   # in order, as Yade
    if findMaxId:
        return total, (int(ids[np.argmax(per_body)]) if len(ids) else -1)
    return total


def momentum(scene=None) -> Vector3:
    """Total linear momentum of the dynamic bodies."""
    scene = _scene(scene)
    ids = _moving(scene)
    cpp = scene._cpp
    return Vector3(_whole(scene, (np.asarray(cpp.mass())[ids, None] * np.asarray(cpp.vel())[ids]).sum(axis=0)))


def angularMomentum(origin=(0.0, 0.0, 0.0), scene=None) -> Vector3:
    """Total angular momentum of the dynamic bodies about ``origin`` (spin with principal inertia
    and world-frame angular velocity: exact for spheres)."""
    scene = _scene(scene)
    ids = _moving(scene)
    cpp = scene._cpp
    r = np.asarray(cpp.pos())[ids] - np.asarray(origin, dtype=float)
    p = np.asarray(cpp.mass())[ids, None] * np.asarray(cpp.vel())[ids]
    spin = np.asarray(cpp.inertia())[ids] * np.asarray(cpp.angVel())[ids]
    return Vector3(_whole(scene, (np.cross(r, p) + spin).sum(axis=0)))


def totalForceInVolume(scene=None) -> tuple[Vector3, float]:
    """Yade's totalForceInVolume: the sum over real contacts of the absolute components of each
    contact's force (normal + shear), and the contacts' mean isotropic stiffness kn/3 + 2 ks/3
    (-1 without contacts)."""
    total, stiffness = _dem.totalForceInVolume(_scene(scene)._cpp)
    return Vector3(total), float(stiffness)


def sumForces(ids, direction, scene=None) -> float:
    """Sum over ``ids`` of the force on each body projected on ``direction`` (under mpirun a
    body's force on the process owning it, a wall's summed over the processes)."""
    scene = _scene(scene)
    rows = np.asarray(list(ids), dtype=int)
    if (split := distributed.domain(scene)) is not None:
        rows = np.array([r for r in map(split.rowOf, map(int, rows)) if split.owns(r)], dtype=int)
    f = np.asarray(scene._cpp.force())[rows]
    return float(_whole(scene, (f @ np.asarray(direction, dtype=float)).sum()))


def aabbExtrema(cutoff: float = 0.0, centers: bool = False, scene=None) -> tuple[Vector3, Vector3]:
    """Corners of the box enclosing the spheres (their centres only with ``centers``), shrunk
    by the fraction ``cutoff`` of its size on each side, as Yade's utils.aabbExtrema."""
    lo, hi = _sphere_box(_scene(scene), centers, "aabbExtrema")
    shrink = cutoff * (hi - lo)
    return Vector3(lo + shrink), Vector3(hi - shrink)


def _sphere_box(scene, centers: bool, caller: str) -> tuple[np.ndarray, np.ndarray]:
    """Lower and upper corners of the box enclosing the live spheres (their centres only with
    ``centers``); under mpirun the whole scene's (the extrema over the processes: a ghost is a
    copy of a sphere, inside the box its owner finds)."""
    ids = scene.sphere_ids()
    pos = np.asarray(scene._cpp.pos())[ids]
    r = np.zeros(len(ids)) if centers else np.asarray(scene._cpp.radius())[ids]
    lo = (pos - r[:, None]).min(axis=0) if len(ids) else np.full(3, np.inf)
    hi = (pos + r[:, None]).max(axis=0) if len(ids) else np.full(3, -np.inf)
    if (split := distributed.domain(scene)) is not None:
        extrema = np.asarray(split.minima([*lo, *(-hi)]))
        lo, hi = extrema[:3], -extrema[3:]
    if not np.isfinite(lo).all():
        raise ValueError(f"{caller}: the scene has no spheres")
    return lo, hi


def aabbDim(cutoff: float = 0.0, centers: bool = False, scene=None) -> Vector3:
    """Size of the box of ``aabbExtrema``."""
    lo, hi = aabbExtrema(cutoff, centers, scene)
    return Vector3(hi - lo)


def _spheres(mask: int, scene) -> tuple:
    """The scene and its spheres (clump members included) that ``mask`` selects: with mask > 0
    those whose mask shares a bit with it, otherwise all (Yade's); of those this process counts."""
    scene = _scene(scene)
    ids = scene.sphere_ids()
    ids = ids[_counted(scene)[ids]]
    if mask > 0:
        ids = np.array([i for i in ids if _dem.group_mask(scene._cpp, int(i)) & mask], dtype=int)
    return scene, ids


def getSpheresVolume(mask: int = -1, scene=None) -> float:
    """Total volume of the spheres ``mask`` selects, as Yade's."""
    scene, ids = _spheres(mask, scene)
    return float(_whole(scene, sum(4.0 / 3.0 * np.pi * r ** 3 for r in scene._cpp.radius()[ids])))


def getSpheresMass(mask: int = -1, scene=None) -> float:
    """Total mass of the spheres ``mask`` selects, as Yade's."""
    scene, ids = _spheres(mask, scene)
    return float(_whole(scene, sum(scene._cpp.mass()[ids])))      # in id order, as Yade adds them
