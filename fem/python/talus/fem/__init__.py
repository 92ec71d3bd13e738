"""FEM x DEM hierarchical multiscale (the seed's FEMxDEM with Yade and escript, chapter 13).

A periodic DEM packing (an RVE) sits at every Gauss point of a finite element mesh. Given the
displacement gradients of all Gauss points, :class:`MultiscaleRVEs` deforms every RVE through its
periodic cell and returns the homogenised Cauchy stress and the contact-stiffness tangent, in one
C++ call over all points (OpenMP), optionally spread over MPI ranks::

    from talus.fem import MultiscaleRVEs, prepareRVE
    prepareRVE("0.h5", sigma=-1e5)                  # a consolidated periodic packing
    rves = MultiscaleRVEs("0.h5", numPoints=4, nSteps=50)
    rves.run(grads)                                 # (4, 2, 2) or (4, 3, 3): trial state
    stress, tangent = rves.getStressAndTangent()
    rves.commit()                                   # or rves.rollback()

The FEniCSx driver is :mod:`talus.fem.fenicsx`, the escript client :mod:`talus.fem.escript`, Yade's
FEMxDEM ``MultiScale`` :mod:`talus.fem.msfem` (drop-in modules: ``yade_femxdem/``).
"""

from talus.fem.prepare import exportRVE, prepareRVE, rveFromJSON
from talus.fem.rves import MultiscaleRVEs, isPlanarRVE, tangentToTensor

__all__ = ["MultiscaleRVEs", "exportRVE", "isPlanarRVE", "prepareRVE", "rveFromJSON", "tangentToTensor"]
