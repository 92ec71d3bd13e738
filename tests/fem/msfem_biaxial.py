"""Run by tests/fem/test_msfem.py under run-escript, in a folder holding 0.yade.gz (a planar
Talus RVE), with the drop-in folder yade_femxdem on PYTHONPATH: a one-element biaxial test
written as Yade's FEMxDEM examples are (msFEM2D.MultiScale, saveGauss2D). Writes out.json: the
Gauss-point strain increment of every load step and the stress after it."""
import json
import sys

from esys.escript import Function, FunctionOnBoundary, Vector, Solution, whereZero
from esys.finley import Rectangle
from msFEM2D import MultiScale
from saveGauss import saveGauss2D

from talus.fem.escript import fromData

steps, vel, confining = int(sys.argv[1]), float(sys.argv[2]), float(sys.argv[3])
domain = Rectangle(l0=1.0, l1=1.0, n0=1, n1=1, order=2, integrationOrder=2)
numg = Function(domain).getX().getNumberOfDataPoints()
prob = MultiScale(domain=domain, ng=numg, np=2, random=False, rtol=1e-2, usePert=False, pert=-2.e-5, verbose=True)
out = {"numg": numg, "initialShape": list(prob.getCurrentStress().getShape()),
       "initialTangentShape": list(prob.getCurrentTangent().getShape()), "increments": [], "stress": []}
x, bx = domain.getX(), FunctionOnBoundary(domain).getX()
Dbc = whereZero(x[1]) * [0, 1] + whereZero(x[1] - 1.0) * [0, 1] + whereZero(x[1]) * whereZero(x[0]) * [1, 1]
Vbc = whereZero(x[1] - 1.0) * [0, vel]
Nbc = whereZero(bx[0]) * [-confining, 0] + whereZero(bx[0] - 1.0) * [confining, 0]
before = fromData(prob.getCurrentStrain())
for t in range(steps):
    prob.initialize(f=Nbc, specified_u_mask=Dbc, specified_u_val=Vbc)
    prob.solve(iter_max=100)
    strain = fromData(prob.getCurrentStrain())
    out["increments"].append((strain - before).tolist())
    before = strain
    out["stress"].append(fromData(prob.getCurrentStress()).tolist())
    saveGauss2D(name=f"gauss_{t + 1}.dat", strain=prob.getCurrentStrain(), stress=prob.getCurrentStress(),
                fabric=prob.getLocalFabric())
out["voidRatio"] = fromData(prob.getLocalVoidRatio()).tolist()
json.dump(out, open("out.json", "w"))
prob.exitSimulation()
