"""Yade's FEMxDEM interface (msFEM2D / msFEM3D / msFEMup ``MultiScale``) on Talus's Gauss-point
RVEs, for Yade's escript scripts run unchanged with ``run-escript`` (the drop-in modules in
``yade_femxdem/``, docs/fem.md "Running Yade's FEMxDEM scripts").

The procedure is Yade's (seed chapter 13): per load step, one linear solve with the committed
stress and tangent and the prescribed displacement increment, then Newton corrections with the
trial stress and tangent of the RVEs deformed by grad(u) from their committed state, the
equilibrium of a correction taken on the domain moved by u, until |du| / |u| (L2 norms) < rtol;
the RVEs are then committed and the domain moved by u. Each RVE call runs
max(1e5 max|G_ij|, 2) DEM steps for the gradient G of its own point (Yade's shear2D/shear3D).

Talus replaces the pickled scenes and the process pool by :class:`talus.fem.MultiscaleRVEs`
(one C++ call over all points, OpenMP threads, MPI ranks with mpi4py).
"""

from __future__ import annotations

import os

import numpy as np

from talus.fem.escript import fromData, toData
from talus.fem.rves import MultiscaleRVEs, isPlanarRVE, tangentToTensor

__all__ = ["MultiScale", "rveSettings", "yadeSteps"]


def yadeSteps(grads, perStrain: float = 1e5, minimum: int = 2) -> np.ndarray:
    """Yade's DEM step count of each Gauss point's call: int(max(perStrain * max|G_ij|, minimum))."""
    g = np.abs(np.asarray(grads, dtype=float)).reshape(len(grads), -1).max(axis=1)
    return np.maximum(perStrain * g, minimum).astype(np.int64)


def _checkRVEFile(path: str, point: int) -> None:
    if not os.path.exists(path):
        raise FileNotFoundError(
            f"Gauss point {point}: RVE file '{path}' not found in {os.getcwd()}. Prepare it with Yade's "
            f"prepareRVE.py under `talus run` (it saves {path!r} as a Talus checkpoint) or with "
            f"talus.fem.prepareRVE('{path}', planar=True, ...)")
    with open(path, "rb") as f:
        head = f.read(8)
    if head[:2] == b"\x1f\x8b":
        raise ValueError(
            f"Gauss point {point}: '{path}' is a Yade file (gzip), not a Talus checkpoint: Talus cannot read "
            f"Yade's serialised scenes. Re-create it with Yade's prepareRVE.py under `talus run` (O.save "
            f"writes a Talus checkpoint whatever the name) or talus.fem.prepareRVE, or export the packing from "
            f"Yade (positions, radii, cell: talus.fem.exportRVE's JSON) and build it with talus.fem.rveFromJSON")
    if head[:8] != b"\x89HDF\r\n\x1a\n":
        raise ValueError(f"Gauss point {point}: '{path}' is not a Talus checkpoint (HDF5)")


def rveSettings(path) -> dict:
    """What a Talus RVE checkpoint says about how to step it: the Law2 of its InteractionLoop
    and its NewtonIntegrator's damping (from the engine list ``O.save`` stored), and whether it
    is planar. When the file has no engine list (or one that cannot be rebuilt): CundallStrack
    and damping None (MultiScale then takes 0.2 and warns)."""
    import warnings

    from talus.dem import Scene
    S = Scene()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        S.load(os.fspath(path))
    law, damping = "Law2_ScGeom_FrictPhys_CundallStrack", None
    for e in S.engines:
        name = type(e).__name__
        if name == "NewtonIntegrator":
            damping = float(e.damping)
        elif name == "InteractionLoop":
            laws = getattr(e, "lawDispatcher", None) or getattr(e, "laws", None) or []
            try:
                laws = list(laws)
            except TypeError:
                laws = []
            if laws:
                law = type(laws[0]).__name__
    return {"law": law, "damping": damping, "planar": isPlanarRVE(S)}


ENVIRONMENT = "TALUS_MSFEM"
_KEYWORDS = ("dim", "rve", "form", "stepsPerStrain", "minSteps", "damping", "law")


def _environmentOptions() -> dict:
    """Talus-only keywords for scripts run unchanged: a JSON object in $TALUS_MSFEM, e.g.
    TALUS_MSFEM='{"damping": 0.1, "form": "fd"}' (they override the script's)."""
    import json
    text = os.environ.get(ENVIRONMENT, "").strip()
    if not text:
        return {}
    try:
        options = json.loads(text)
    except ValueError as e:
        raise ValueError(f"${ENVIRONMENT} is not a JSON object: {e}") from None
    bad = set(options) - set(_KEYWORDS) if isinstance(options, dict) else {"(not an object)"}
    if bad:
        raise ValueError(f"${ENVIRONMENT}: unknown keys {sorted(bad)}; known: {list(_KEYWORDS)}")
    return options


class MultiScale:
    """Yade's ``MultiScale`` (msFEM2D / msFEM3D): ``MultiScale(domain, ng, useMPI, np, random,
    rtol, usePert, pert, verbose)`` and the calls of Yade's examples.

    RVEs: ``0.yade.gz`` in the working directory for every Gauss point (``random=False``, Yade's
    default branch), or ``<point>.yade.gz`` per point (``random=True``: Yade's commented-out
    branch for an inherently heterogeneous sample); ``rve`` overrides (a path or a list). The
    files are Talus checkpoints (Yade's prepareRVE.py run by ``talus run``, or
    :func:`talus.fem.prepareRVE`); their saved engines give the contact law and damping.

    Talus-only keywords: ``dim`` (default the domain's), ``rve``, ``form`` (tangent: "yade",
    Yade's getStressAndTangent, the default; "full"; "fd", which ``usePert=True`` selects with
    step |pert|), ``stepsPerStrain`` and ``minSteps`` (Yade's 1e5 and 2), ``damping`` and
    ``law`` (default from the file). ``np`` is accepted and ignored: the RVE calls run on the
    OpenMP threads (OMP_NUM_THREADS); ``useMPI=True`` spreads the RVEs over the ranks of
    mpi4py's COMM_WORLD when there are several (every rank runs the script). For scripts run
    unchanged, the Talus-only keywords can be given in $TALUS_MSFEM as a JSON object.
    """

    def __init__(self, domain, ng=1, useMPI=False, np=1, random=False, rtol=1.e-2, usePert=False, pert=-2.e-6,
                 verbose=False, *, dim=None, rve=None, form="yade", stepsPerStrain=1e5, minSteps=2, damping=None,
                 law=None):
        from esys.escript import Function
        from esys.escript.linearPDEs import LinearPDE, SolverOptions
        options = _environmentOptions()
        dim, rve, form = options.get("dim", dim), options.get("rve", rve), options.get("form", form)
        stepsPerStrain, minSteps = options.get("stepsPerStrain", stepsPerStrain), options.get("minSteps", minSteps)
        damping, law = options.get("damping", damping), options.get("law", law)
        self._domain = domain
        self.dim = domain.getDim() if dim is None else int(dim)
        n = Function(domain).getX().getNumberOfDataPoints()
        if ng != n:
            raise ValueError(f"MultiScale: ng={ng}, but the domain has {n} Gauss points (data points of "
                             f"Function(domain)); Yade would run with a wrong count, Talus stops")
        self._ng, self._rtol, self._verbose = ng, rtol, verbose
        self._stepsPerStrain, self._minSteps = stepsPerStrain, minSteps
        if rve is None:
            rve = [f"{p}.yade.gz" for p in range(ng)] if random else "0.yade.gz"
        files = [rve] * ng if isinstance(rve, (str, os.PathLike)) else list(rve)
        if len(files) != ng:
            raise ValueError(f"MultiScale: {len(files)} RVE files for {ng} Gauss points")
        for p, f in enumerate(files):
            if p == 0 or f != files[p - 1]:
                _checkRVEFile(os.fspath(f), p)
        self._files = [os.fspath(f) for f in files]
        settings = rveSettings(files[0])
        comm = None
        if useMPI:
            try:
                from mpi4py import MPI
                comm = MPI.COMM_WORLD if MPI.COMM_WORLD.Get_size() > 1 else None
            except ImportError:
                comm = None
        if usePert:
            form = "fd"
        if damping is None:
            damping = settings["damping"]
        if damping is None:
            import warnings
            warnings.warn(f"MultiScale: '{self._files[0]}' stores no NewtonIntegrator damping; using 0.2 "
                          f"(set it with ${ENVIRONMENT}='{{\"damping\": ...}}')", RuntimeWarning, stacklevel=2)
            damping = 0.2
        self.rves = MultiscaleRVEs([os.fspath(f) for f in files], nSteps=minSteps,
                                   law=law or settings["law"],
                                   damping=damping, form=form,
                                   comm=comm, fdStep=abs(pert) if usePert else 1e-5, dim=self.dim)
        self._pde = LinearPDE(domain, numEquations=self.dim, numSolutions=self.dim)
        try:
            self._pde.getSolverOptions().setSolverMethod(SolverOptions.DIRECT)
        except Exception:
            pass
        self._pde.setSymmetryOn()
        self._strain = self._zeros((self.dim, self.dim))
        self._stress, self._S = self._answers()
        self._steps = 0

    # -- helpers ----------------------------------------------------------------------------
    def _zeros(self, shape):
        from esys.escript import Data, Function
        return Data(0, shape, Function(self._domain), True)

    def _answers(self):
        """The current stress (symmetric part) and tangent (D_ijkl) of the RVEs as escript Data."""
        s, t = self.rves.getStressAndTangent()
        s = 0.5 * (s + np.swapaxes(s, 1, 2))
        d = self.dim
        return toData(s, self._domain, (d, d)), toData(tangentToTensor(t), self._domain, (d,) * 4)

    def _trial(self, D):
        """Every RVE deformed by its gradient of D (escript Tensor on Function) from its committed
        state, over Yade's step count; the trial stress and tangent."""
        g = fromData(D)
        self.rves.run(g, nSteps=yadeSteps(g, self._stepsPerStrain, self._minSteps))
        return self._answers()

    # -- Yade's calls -----------------------------------------------------------------------
    def initialize(self, b=None, f=None, specified_u_mask=None, specified_u_val=None):
        """Body force b, boundary traction f (FunctionOnBoundary), prescribed mask and increment."""
        from esys.escript import Data
        self._pde.setValue(Y=Data() if b is None else b, y=Data() if f is None else f,
                           q=Data() if specified_u_mask is None else specified_u_mask,
                           r=Data() if specified_u_val is None else specified_u_val)

    def getDomain(self):
        return self._domain

    def getRelTolerance(self):
        return self._rtol

    def getCurrentStress(self):
        """Symmetric part of the RVE stresses (Tensor on Function; compression negative)."""
        return self._stress

    def getCurrentTangent(self):
        return self._S

    def getCurrentStrain(self):
        """Sum of the converged displacement gradients (Tensor on Function), as Yade's."""
        return self._strain

    def _states(self, key):
        return {"voidRatio": self.rves.getVoidRatio, "porosity": self.rves.getPorosity,
                "fabric": self.rves.getFabric, "rotation": self.rves.getRotation}[key]()

    def getLocalVoidRatio(self):
        """Void ratio per Gauss point: in 2D by area (Yade's voidratio2D: the disks' cross-sections
        in the cell's plane), in 3D by volume."""
        e = self._states("voidRatio")
        if self.dim == 2:
            e = self._areaVoidRatio(e)
        return toData(e, self._domain, ())

    def _areaVoidRatio(self, volumeVoidRatio):
        if not hasattr(self, "_disks"):
            self._disks = self._diskAreas()
        vs, area, zlen = self._disks
        cellVolume = vs * (1 + volumeVoidRatio)
        return (cellVolume / zlen - area) / area

    def _diskAreas(self):
        """Per point: total sphere volume, total disk area and cell thickness (constant in plane
        strain), from the RVE files."""
        from talus.dem import Scene
        cache, out = {}, []
        for f in self._files:
            if f not in cache:
                S = Scene()
                S.load(f, engines="current")
                r = np.asarray(S.radii())[S.sphere_ids()]
                cache[f] = (4 / 3 * np.pi * (r ** 3).sum(), np.pi * (r ** 2).sum(), float(np.array(S.cell.hSize)[2, 2]))
            out.append(cache[f])
        return tuple(np.array(c) for c in zip(*out))

    def getEquivalentPorosity(self):
        e = fromData(self.getLocalVoidRatio())
        return toData(e / (1 + e), self._domain, ())

    def getLocalFabric(self):
        """Contact-normal fabric (1/Nc) sum n n, in-plane block in 2D."""
        f = self._states("fabric")[:, :self.dim, :self.dim]
        return toData(f, self._domain, (self.dim, self.dim))

    def getLocalAvgRotation(self):
        """Mean particle rotation since loading: about z in 2D (Scalar), a Vector in 3D."""
        r = self._states("rotation")
        if self.dim == 2:
            return toData(r[:, 2], self._domain, ())
        return toData(r, self._domain, (3,))

    def getCurrentPacking(self, pos=(), time=0, prefix=""):
        """Save the RVEs of the points ``pos`` (all if empty) as Talus checkpoints named as Yade's
        ``<prefix>packing_<point>_<time>.yade.gz``."""
        points = range(self._ng) if len(pos) == 0 else pos
        for p in points:
            if p in self.rves.localPoints:
                self.rves.save(p, f"{prefix}packing_{p}_{time}.yade.gz")

    def exitSimulation(self):
        """Nothing to close (no process pool)."""

    def solve(self, iter_max=100):
        """One load step by Yade's Newton scheme (module docstring); returns the nodal
        displacement increment u."""
        from esys.escript import Data, grad
        from esys.escript.util import L2
        rtol = self._rtol
        x0 = self._domain.getX()
        self._pde.setValue(A=self._S, X=-self._stress)
        u = self._pde.getSolution()
        D = grad(u)
        stress, S = self._trial(D)
        err, iterate = 1.0, 0
        while err >= rtol and iterate < iter_max:
            if self._verbose:
                print("Not converged after %d iteration(s)! Relative error: %e" % (iterate, err))
            iterate += 1
            self._domain.setX(x0 + u)
            self._pde.setValue(A=S, X=-stress, r=Data())
            du = self._pde.getSolution()
            u += du
            err = L2(du) / L2(u)
            if err > rtol * 1e-3:       # Yade updates the RVEs unless the correction is negligible
                self._domain.setX(x0)
                D = grad(u)
                stress, S = self._trial(D)
        self._domain.setX(x0 + u)
        self.rves.commit()
        self._stress, self._S = stress, S
        self._strain = self._strain + D
        self._steps += 1
        self.iterations = iterate
        if self._verbose:
            print("Convergence reached after %d iteration(s)! Relative error: %e" % (iterate, err))
        return u
