"""Measurements with Yade's names: unbalancedForce, getStress, avgNumInteractions,
fabricTensor, bodyStressTensors, porosity, getStressAndTangent."""

from __future__ import annotations

import numpy as np

from talus import _dem


def _scene(scene):
    if scene is None:
        from talus.dem import O
        return O
    return scene


def _gravity(scene) -> np.ndarray:
    from talus.dem.engines import NewtonIntegrator
    for e in scene.engines:
        if isinstance(e, NewtonIntegrator):
            return np.asarray(e.gravity, dtype=float)
    return np.zeros(3)


def unbalancedForce(useMaxForce: bool = False, scene=None) -> float:
    """Mean (or largest) total force on dynamic bodies, gravity included, over the mean
    contact force: tends to 0 at equilibrium."""
    scene = _scene(scene)
    return _dem.unbalancedForce(scene._cpp, _gravity(scene), useMaxForce)


def getStress(volume: float = -1, scene=None) -> np.ndarray:
    """Love-Weber stress -(1/V) sum f (x) l (compression negative, as Yade); `volume` defaults
    to the periodic cell's."""
    scene = _scene(scene)
    return np.array(_dem.loveWeberStress(scene._cpp, float(volume)))


def getStressAndTangent(volume: float = -1, symmetry: bool = True, form: str = "full",
                        scene=None) -> tuple[np.ndarray, np.ndarray]:
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
    return (np.array(_dem.loveWeberStress(scene._cpp, float(volume))),
            np.array(_dem.contactStiffnessTangent(scene._cpp, float(volume), form == "yade")))


def avgNumInteractions(skipFree: bool = False, scene=None) -> float:
    """Mean coordination number 2 Nc / N of the spheres."""
    return _dem.coordinationNumber(_scene(scene)._cpp, skipFree)


def fabricTensor(scene=None) -> np.ndarray:
    """(1/Nc) sum of n (x) n over sphere-sphere contacts."""
    return np.array(_dem.fabricTensor(_scene(scene)._cpp))


def bodyStressTensors(revertSign: bool = False, scene=None) -> list[np.ndarray]:
    """Per body id, the mean stress in the solid sphere from its contact forces,
    (1/V) sum of force (x) arm over its contacts (Yade's bodyStressTensors: compression negative,
    the opposite with ``revertSign``); zero for bodies that are not spheres."""
    sign = -1.0 if revertSign else 1.0
    return [sign * np.array(s) for s in _dem.bodyStressTensors(_scene(scene)._cpp)]


def porosity(volume: float = -1, scene=None) -> float:
    """1 - (sphere volume) / volume; `volume` defaults to the periodic cell's, else to the
    bounding box of the spheres."""
    scene = _scene(scene)
    if volume <= 0:
        if scene.periodic:
            volume = scene.cell.volume
        else:
            alive = np.asarray(scene._cpp.alive(), dtype=bool)
            r = scene.radii()
            spheres = alive & (r > 0)
            if not spheres.any():
                raise ValueError("porosity: the scene has no spheres")
            pos = scene.positions()[spheres]
            lo, hi = (pos - r[spheres, None]).min(axis=0), (pos + r[spheres, None]).max(axis=0)
            volume = float(np.prod(hi - lo))
    return 1.0 - _dem.sphereVolume(scene._cpp) / volume
