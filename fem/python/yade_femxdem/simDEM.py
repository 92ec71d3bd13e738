"""Drop-in for Yade's FEMxDEM simDEM: the per-RVE functions, on Talus RVE checkpoints.

Yade's simDEM passes pickled Yade scenes between processes; Talus keeps the RVEs in C++
(talus.fem.MultiscaleRVEs), so these functions take an RVE checkpoint path (or a talus.dem
Scene) and answer as Yade's do: ``initLoad(ID)`` (the file a Gauss point loads),
``getStressAndTangent2D/3D``, ``getVoidRatio2D/3D``, ``getEquivalentPorosity``,
``getFabric2D/3D``, ``avgRotation2D/3D``, ``numOfParticles``."""
import _compat  # noqa: F401
import os

import numpy

from talus.fem.rves import MultiscaleRVEs, tangentToTensor

__all__ = ["initLoad", "numOfParticles", "getStressAndTangent2D", "getStressAndTangent3D", "getStressAndTangent",
           "getVoidRatio2D", "getVoidRatio3D", "getVoidRatio", "getEquivalentPorosity", "getFabric2D", "getFabric3D",
           "getFabric", "avgRotation2D", "avgRotation3D", "avgRotation", "numpy"]


def initLoad(ID=0, random=False):
    """The RVE file of Gauss point ID: 0.yade.gz (uniform sample) or <ID>.yade.gz (random)."""
    return os.path.abspath(f"{ID}.yade.gz" if random else "0.yade.gz")


def _rve(scene, dim):
    return MultiscaleRVEs(scene, numPoints=1, dim=dim, form="yade")


def numOfParticles(scene):
    from talus.dem import Scene
    if isinstance(scene, (str, os.PathLike)):
        S = Scene()
        S.load(os.fspath(scene), engines="current")
        scene = S
    return len(scene.sphere_ids())


def _stressAndTangent(scene, dim):
    s, t = _rve(scene, dim).getStressAndTangent()
    s = 0.5 * (s[0] + s[0].T)
    return s.tolist(), tangentToTensor(t[0]).tolist()


def getStressAndTangent2D(scene):
    return _stressAndTangent(scene, 2)


def getStressAndTangent3D(scene):
    return _stressAndTangent(scene, 3)


getStressAndTangent = getStressAndTangent3D


def getVoidRatio3D(scene):
    return float(_rve(scene, 3).getVoidRatio()[0])


getVoidRatio = getVoidRatio3D


def getVoidRatio2D(scene):
    """Void ratio by area in the cell's plane (Yade's voidratio2D)."""
    from talus.dem import Scene
    S = Scene()
    if isinstance(scene, (str, os.PathLike)):
        S.load(os.fspath(scene), engines="current")
    else:
        S = scene
    r = numpy.asarray(S.radii())[S.sphere_ids()]
    h = numpy.array(S.cell.hSize)
    area = abs(numpy.linalg.det(h)) / h[2, 2]
    solid = numpy.pi * (r ** 2).sum()
    return float((area - solid) / solid)


def getEquivalentPorosity(scene):
    e = getVoidRatio2D(scene)
    return e / (1. + e)


def getFabric2D(scene):
    return _rve(scene, 2).getFabric()[0][:2, :2].tolist()


def getFabric3D(scene):
    return _rve(scene, 3).getFabric()[0].tolist()


getFabric = getFabric3D


def avgRotation2D(scene):
    return float(_rve(scene, 2).getRotation()[0][2])


def avgRotation3D(scene):
    return _rve(scene, 3).getRotation()[0].tolist()


avgRotation = avgRotation3D
