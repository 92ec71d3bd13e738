"""An exported RVE packing (:func:`talus.fem.exportRVE` JSON) built as a periodic scene, the same
way in Yade and in Talus, for the side-by-side scenarios (cases/yade/fem_rve_tangent.py,
cases/yade/fem_rve_call.py).

This file imports nothing from talus: the scenario passes its own namespace (Yade's builtins or
``talus.dem``'s, which share Yade's names), so Yade can load it by path without importing the
talus package: the scenario appends this folder to ``sys.path`` (the caller passes it as the
parameter ``rveSceneDir``, :data:`FOLDER`) and imports ``rve_scene``."""

import json
import os

FOLDER = os.path.dirname(os.path.abspath(__file__))


def buildRVEScene(ns: dict, packing, damping: float = 0.2, dt: float | None = None) -> dict:
    """Fill ``ns["O"]`` with the periodic packing ``packing`` (a path to the JSON or the dict):
    cell, one FrictMat, the spheres, Yade's sphere engine chain (ForceResetter, collider,
    ScGeom / FrictPhys / CundallStrack loop, NewtonIntegrator with ``damping``), time step
    ``dt`` (default: the exported one). Returns the packing data."""
    data = json.load(open(packing)) if not isinstance(packing, dict) else packing
    O, Matrix3 = ns["O"], ns["Matrix3"]
    O.periodic = True
    O.cell.hSize = Matrix3(*[x for row in data["hSize"] for x in row])
    O.materials.append(ns["FrictMat"](young=data["young"], poisson=data["poisson"],
                                      frictionAngle=data["frictionAngle"], density=data["density"]))
    O.bodies.append([ns["sphere"](tuple(c), r) for c, r in zip(data["pos"], data["radius"])])
    O.engines = [
        ns["ForceResetter"](),
        ns["InsertionSortCollider"]([ns["Bo1_Sphere_Aabb"]()]),
        ns["InteractionLoop"]([ns["Ig2_Sphere_Sphere_ScGeom"]()], [ns["Ip2_FrictMat_FrictMat_FrictPhys"]()],
                              [ns["Law2_ScGeom_FrictPhys_CundallStrack"]()]),
        ns["NewtonIntegrator"](damping=damping),
    ]
    O.dt = data["dt"] if dt is None else dt
    return data

