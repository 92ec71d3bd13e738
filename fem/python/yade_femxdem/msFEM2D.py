"""Drop-in for Yade's FEMxDEM msFEM2D (plane strain), on Talus's Gauss-point RVEs.

Put this folder and Talus's python folder on PYTHONPATH instead of Yade's FEMxDEM folder:
    PYTHONPATH=<build>/python/yade_femxdem:<build>/python run-escript biaxialSmooth.py
``MultiScale`` is :class:`talus.fem.msfem.MultiScale`; docs/fem.md lists what differs from Yade.
"""
import _compat  # noqa: F401  (file = open for Yade's Python 2 examples)
from talus.fem.msfem import MultiScale  # noqa: F401
from simDEM import *  # noqa: F401,F403  (Yade's msFEM2D re-exports simDEM's names)

__all__ = ["MultiScale", "get_pool"]


def get_pool(mpi=False, threads=1):
    """Yade's process pool is not used: the RVE calls are batched in C++ (OpenMP, MPI ranks)."""
    raise RuntimeError("Talus's MultiScale runs its RVEs without a process pool (OMP_NUM_THREADS, mpirun)")
