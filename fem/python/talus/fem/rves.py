"""The Gauss-point calls: :class:`MultiscaleRVEs` (batched in C++, optionally over MPI ranks)."""

from __future__ import annotations

import os

import numpy as np

from talus import _fem

_FORMS = ("full", "yade", "fd")


def _source(rve, point: int):
    """What the C++ side takes for one Gauss point: a file name or the C++ scene of a talus.dem Scene."""
    if isinstance(rve, (str, os.PathLike)):
        return os.fspath(rve)
    cpp = getattr(rve, "_cpp", None)
    if cpp is None:
        raise TypeError(f"Gauss point {point}: an RVE is a checkpoint file name or a talus.dem Scene, got {rve!r}")
    return cpp


def _block(count: int, size: int, rank: int) -> tuple[int, int]:
    """The contiguous block [start, stop) of `count` points that `rank` of `size` owns."""
    base, extra = divmod(count, size)
    start = rank * base + min(rank, extra)
    return start, start + base + (1 if rank < extra else 0)


class MultiscaleRVEs:
    """The RVEs of all Gauss points and the seed's calls on them.

    ``rves``: one RVE (a checkpoint file written by ``O.save`` / :func:`prepareRVE`, or a
    periodic talus.dem Scene, copied) for every Gauss point, or a single one with ``numPoints``
    copies (a uniform sample). ``nSteps``: DEM steps over which each call applies its
    displacement gradient (each step's strain is the gradient / nSteps). ``law`` and
    ``damping``: the RVEs' contact law (Yade's Law2 name) and NewtonIntegrator damping.
    ``form``: the tangent operator, "full" (contact stiffness in every tangential direction),
    "yade" (Yade's getStressAndTangent) or "fd": the consistent tangent of the symmetric part
    of the stress (what the drivers balance) by finite differences, each column re-running
    every RVE from its committed state with the gradients of the pending trial plus ``fdStep``
    times a unit strain (relaxation, sliding and contact changes included; costs 3 (2D) or 6 (3D) more runs per call; without a pending trial, after commit
    or rollback, the contact-stiffness tangent is returned).

    ``comm`` (an mpi4py communicator): the calls are collective; every rank passes the
    gradients of all points (the same array), keeps the RVEs of its own block of points
    between calls, and gets the stress and tangent of all points back (only gradients, stress
    and tangent cross ranks; the RVE states never move).
    """

    def __init__(self, rves, numPoints: int | None = None, nSteps: int = 100,
                 law: str = "Law2_ScGeom_FrictPhys_CundallStrack", damping: float = 0.2, form: str = "full",
                 comm=None, fdStep: float = 1e-5, dim: int | None = None):
        single = isinstance(rves, (str, os.PathLike)) or hasattr(rves, "_cpp")
        if single:
            if numPoints is None or numPoints < 1:
                raise ValueError("MultiscaleRVEs: give numPoints >= 1 with a single RVE")
            rves = [rves] * numPoints
        elif numPoints is not None and numPoints != len(rves):
            raise ValueError(f"MultiscaleRVEs: {len(rves)} RVEs given for numPoints={numPoints}")
        if form not in _FORMS:
            raise ValueError(f"MultiscaleRVEs: form must be one of {_FORMS}, got {form!r}")
        if int(nSteps) < 1:
            raise ValueError(f"MultiscaleRVEs: nSteps must be >= 1, got {nSteps}")
        if not 0 <= float(damping) <= 1:
            raise ValueError(f"MultiscaleRVEs: damping (the RVEs' NewtonIntegrator damping) must be in [0, 1], "
                             f"got {damping!r}")
        if not 0 < float(fdStep) < 1:
            raise ValueError(f"MultiscaleRVEs: fdStep (the finite-difference strain of form='fd') must be in (0, 1), "
                             f"got {fdStep!r}")
        self.numPoints, self.nSteps, self.form, self.comm, self.fdStep = len(rves), int(nSteps), form, comm, fdStep
        self._grads = None
        size, rank = (comm.Get_size(), comm.Get_rank()) if comm is not None else (1, 0)
        self._start, self._stop = _block(self.numPoints, size, rank)
        self._blocks = [_block(self.numPoints, size, r) for r in range(size)]
        if self._stop <= self._start:
            raise ValueError(f"MultiscaleRVEs: {self.numPoints} Gauss points cannot be spread over {size} ranks")
        mine = [_source(r, p) for p, r in enumerate(rves)][self._start:self._stop]
        try:
            self._cpp = _fem.GaussPointRVEs(mine, law, float(damping))
        except ValueError as e:     # the C++ side numbers this rank's points from 0
            raise ValueError(self._renumber(str(e))) from None
        if dim not in (None, 2, 3):
            raise ValueError(f"MultiscaleRVEs: dim must be 2 (plane strain), 3 or None, got {dim!r}")
        # The dimension of the answers before the first run (afterwards that of the gradients):
        # given, or 2 when every RVE is planar (all its spheres blocked in z: prepareRVE(planar=True),
        # Yade's FEMxDEM prepareRVE.py), else 3.
        self.dim = dim if dim is not None else (2 if all(isPlanarRVE(r) for r in _distinct(rves)) else 3)

    @property
    def localPoints(self) -> range:
        """The Gauss points whose RVEs live on this rank."""
        return range(self._start, self._stop)

    def run(self, dispGrads, nSteps=None) -> None:
        """Deform every RVE from its committed state by its displacement gradient (shape
        (numPoints, d, d), d = 2 for plane strain or 3); the result is the trial state.
        ``nSteps``: the DEM steps of this call, one count or one per Gauss point (default: the
        constructor's; Yade's FEMxDEM takes max(1e5 max|G|, 2) per point)."""
        g = np.ascontiguousarray(dispGrads, dtype=float)
        if g.ndim != 3 or g.shape[0] != self.numPoints:
            raise ValueError(f"MultiscaleRVEs.run: expected displacement gradients of shape ({self.numPoints}, d, d), "
                             f"got {g.shape} (Gauss-point count mismatch)" if g.ndim == 3 else
                             f"MultiscaleRVEs.run: expected shape ({self.numPoints}, d, d), got {g.shape}")
        bad = np.flatnonzero(~np.isfinite(g).reshape(len(g), -1).all(axis=1))
        if len(bad):
            raise ValueError(f"MultiscaleRVEs.run: displacement gradient of Gauss point {bad[0]} is not finite")
        self.dim = g.shape[1]
        self._grads = g
        error = None
        try:
            self._cpp.deform(g[self._start:self._stop], self._steps(nSteps))
        except (RuntimeError, ValueError) as e:   # DEM failure or bad gradient: renumber the local points
            error = (type(e), self._renumber(str(e)))
        if self.comm is not None:     # every rank raises, so none is left waiting in a collective call
            errors = [e for e in self.comm.allgather(error) if e]
            error = (errors[0][0], "; ".join(m for _, m in errors)) if errors else None
        if error:
            raise error[0](error[1])

    def _steps(self, nSteps):
        if nSteps is None:
            return self.nSteps
        n = np.atleast_1d(np.asarray(nSteps, dtype=np.int64))
        if n.size == 1:
            return int(n[0])
        if n.size != self.numPoints:
            raise ValueError(f"MultiscaleRVEs.run: {n.size} step counts for {self.numPoints} Gauss points")
        return np.ascontiguousarray(n[self._start:self._stop], dtype=np.intc)

    def save(self, point: int, path) -> None:
        """Write the current state of the RVE of Gauss point ``point`` (one of this rank's
        :attr:`localPoints`) to a checkpoint (state only; its engines are those of this object)."""
        if point not in self.localPoints:
            raise ValueError(f"MultiscaleRVEs.save: Gauss point {point} does not live on this rank")
        self._cpp.save(point - self._start, os.fspath(path))

    def _renumber(self, message: str) -> str:
        import re
        return re.sub(r"Gauss point (\d+)", lambda m: f"Gauss point {int(m.group(1)) + self._start}", message)

    def getStressAndTangent(self):
        """Cauchy stress (numPoints, d, d; compression negative) and tangent (numPoints, v, v) in
        Voigt order (3D: xx, yy, zz, yz, xz, xy; 2D: xx, yy, xy) with engineering shear strains.
        d is that of the last run's gradients; before the first run, the constructor's ``dim``,
        or 2 if every RVE is planar (:func:`isPlanarRVE`), else 3."""
        dim = self.dim
        stress, tangent = self._cpp.getStressAndTangent(dim, self.form == "yade")
        stress, tangent = self._gather(stress), self._gather(tangent)
        if self.form == "fd" and self._grads is not None:
            tangent = self._finiteDifferenceTangent(stress)
        return stress, tangent

    def _finiteDifferenceTangent(self, stress):
        """d(sym stress)/d(strain) column by column (Voigt, engineering shear), from runs at the
        last gradients plus fdStep times each unit strain; the trial state at the last gradients
        is re-run at the end (the runs are deterministic, so it is the same state).

        The Love-Weber stress of an RVE is slightly asymmetric and the drivers
        (talus.fem.newton) balance its symmetric part, so the shear row is that of
        (s_ij + s_ji) / 2, not of s_ij: the tangent of exactly the stress Newton balances."""
        d, base = self.dim, self._grads
        pairs = [(0, 0), (1, 1), (0, 1)] if d == 2 else [(0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1)]
        voigt = lambda s: np.stack([0.5 * (s[:, i, j] + s[:, j, i]) for i, j in pairs], axis=1)   # noqa: E731
        s0, columns = voigt(stress), []
        for i, j in pairs:
            E = np.zeros((d, d))
            E[i, j] += self.fdStep / (1 if i == j else 2)
            E[j, i] += 0 if i == j else self.fdStep / 2
            self.run(base + E)
            s, _ = self._cpp.getStressAndTangent(d, False)
            columns.append((voigt(self._gather(s)) - s0) / self.fdStep)
        self.run(base)
        return np.stack(columns, axis=2)

    def _gather(self, local: np.ndarray) -> np.ndarray:
        if self.comm is None:
            return local
        out = np.empty((self.numPoints,) + local.shape[1:])
        per = int(np.prod(local.shape[1:]))
        counts = [(b - a) * per for a, b in self._blocks]
        self.comm.Allgatherv(np.ascontiguousarray(local), [out, counts, np.cumsum([0] + counts[:-1]), _mpi_double()])
        return out

    def _state(self, key: str) -> np.ndarray:
        return self._gather(self._cpp.states()[key])

    def getPorosity(self) -> np.ndarray:
        return self._state("porosity")

    def getVoidRatio(self) -> np.ndarray:
        return self._state("voidRatio")

    def getCoordination(self) -> np.ndarray:
        """Mean coordination number 2 Nc / N of every RVE."""
        return self._state("coordination")

    def getFabric(self) -> np.ndarray:
        """Fabric tensor (1/Nc) sum n n of every RVE, (numPoints, 3, 3)."""
        return self._state("fabric")

    def getRotation(self) -> np.ndarray:
        """Mean rotation vector of the particles of every RVE since it was loaded, (numPoints, 3)."""
        return self._state("rotation")

    def commit(self) -> None:
        """The trial states become the committed ones (the load step converged)."""
        self._cpp.commit()
        self._grads = None

    def rollback(self) -> None:
        """Every RVE returns to its last committed state."""
        self._cpp.rollback()
        self._grads = None


def _distinct(rves):
    seen, out = set(), []
    for r in rves:
        key = os.fspath(r) if isinstance(r, (str, os.PathLike)) else id(r)
        if key not in seen:
            seen.add(key)
            out.append(r)
    return out


def isPlanarRVE(rve) -> bool:
    """True if every sphere of the RVE (a checkpoint file or a talus.dem Scene) is blocked in z:
    a one-layer packing for plane-strain Gauss points (prepareRVE(planar=True), Yade's
    FEMxDEM prepareRVE.py with blockedDOFs 'zXY')."""
    from talus.dem import Scene
    if isinstance(rve, (str, os.PathLike)):
        scene = Scene()
        try:
            scene.load(os.fspath(rve), engines="current")
        except Exception:   # not loadable here: the C++ side names the file and the point
            return False
    else:
        scene = rve
    ids = scene.sphere_ids()
    return len(ids) > 0 and all("z" in scene.bodies[int(i)].state.blockedDOFs for i in ids)


def _mpi_double():
    from mpi4py import MPI
    return MPI.DOUBLE


def tangentToTensor(tangent: np.ndarray) -> np.ndarray:
    """Voigt tangents (..., v, v) with engineering shear strains to the fourth-order tensors
    D_ijkl (..., d, d, d, d) with d sigma_ij = D_ijkl d eps_kl (what escript's LinearPDE A takes)."""
    tangent = np.asarray(tangent)
    v = tangent.shape[-1]
    pairs = {6: [(0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1)], 3: [(0, 0), (1, 1), (0, 1)]}[v]
    d = 3 if v == 6 else 2
    index = np.zeros((d, d), dtype=int)
    for a, (i, j) in enumerate(pairs):
        index[i, j] = index[j, i] = a
    return tangent[..., index[:, :, None, None], index[None, None, :, :]]
