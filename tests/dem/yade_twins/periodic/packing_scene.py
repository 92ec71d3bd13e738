"""The dense packing of periodic_packing.json (150 spheres) as the side-by-side scripts of this
folder load it, importable by the same text under Yade and Talus (Yade's `-x` puts no script
folder on sys.path: a script first adds this folder)."""
import json
import os

from yade import (O, Bo1_Sphere_Aabb, ForceResetter, FrictMat, Ig2_Sphere_Sphere_ScGeom, InsertionSortCollider,
                  InteractionLoop, Ip2_FrictMat_FrictMat_FrictPhys, Law2_ScGeom_FrictPhys_CundallStrack,
                  NewtonIntegrator)
from yade.minieigenHP import Matrix3
from yade.utils import sphere


def load_packing(periodic=True):
    """FrictMat (young 1e7, poisson 0.3, friction 0.5, density 2600) and the spheres of
    periodic_packing.json, in the packing's sheared periodic cell if `periodic`; returns the
    file's data."""
    with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "periodic_packing.json")) as f:
        data = json.load(f)
    if periodic:
        O.periodic = True
        O.cell.hSize = Matrix3(*[x for row in data["hSize"] for x in row])
    O.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600))
    O.bodies.append([sphere(tuple(c), r) for c, r in zip(data["pos"], data["radius"])])
    return data


def linear_engines():
    """O.engines for a step of the packing: linear Cundall-Strack with Coulomb friction, no damping."""
    O.engines = [
        ForceResetter(),
        InsertionSortCollider([Bo1_Sphere_Aabb()]),
        InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                        [Law2_ScGeom_FrictPhys_CundallStrack()]),
        NewtonIntegrator(damping=0.0),
    ]
