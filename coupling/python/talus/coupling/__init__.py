"""CFD-DEM coupling with OpenFOAM over MPI: ``FoamCoupling`` spawns the OpenFOAM
coupling solver (foam-solvers/talusPointForceFoam) and exchanges particles and forces with it
every fluid step. See docs/coupling.md."""

from talus.coupling.foam import FoamCoupling, find_solver, initMPI

__all__ = ["FoamCoupling", "find_solver", "initMPI"]
