"""CFD-DEM coupling with OpenFOAM (seed chapter "CFD-DEM coupled simulations with Yade and
OpenFOAM"; Yade's FoamCoupling): the DEM process spawns the OpenFOAM coupling solver ranks over
MPI, and every fluid step sends them the particles and gets back the hydrodynamic forces::

    coupling = FoamCoupling(O, case="my_case", rhoFluid=1000, nu=1e-3, gravity=(0, 0, -9.81))
    coupling.start()        # spawns talusPointForceFoam, checks the case, sets O.dt, adds a hook
    O.run(coupling.substeps * 100, True)
    coupling.stop()

The DEM sub-steps between fluid steps: ``substeps = ceil(fluid deltaT / O.dt)`` and ``O.dt`` is
lowered to ``deltaT / substeps`` so both clocks agree at every exchange. The hydrodynamic force
of the last exchange is held (as a persistent force) over the sub-steps.
"""

from __future__ import annotations

import atexit
import math
import os
import time
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from talus.coupling.decomposed import OwnedParticles, collective
from talus.coupling.foam_case import YADE_SOLVERS, case_settings, find_solver
from talus.dem import distributed
from talus.coupling.network import apply_network_settings, network_settings

__all__ = ["CouplingTimes", "FoamCoupling", "find_solver", "initMPI"]

_links = []  # every started link, stopped at interpreter exit so no fluid rank is orphaned


def _load_mpi_globally():
    # Open MPI's plugins resolve symbols of libmpi: load it with RTLD_GLOBAL before our module.
    import ctypes
    for name in ("libmpi.so.40", "libmpi.so"):
        try:
            ctypes.CDLL(name, mode=ctypes.RTLD_GLOBAL)
            return
        except OSError:
            continue


def _module():
    _load_mpi_globally()
    from talus import _coupling
    return _coupling


@atexit.register
def _shutdown():
    for link in _links:
        if link.running:
            link.stop()
    if _links:
        _module().finalize_mpi()


def initMPI():
    """Yade's ``initMPI()`` (yade.utils), which its OpenFOAM examples call before creating the
    engine. Talus starts MPI when the fluid ranks are started (the engine's first step), so
    there is nothing left to do here; kept so that those scripts run unchanged."""
    return None


@dataclass
class CouplingTimes:
    """Where a coupled run's wall time went, summed since ``start()`` [s] (``FoamCoupling.times``).

    ``dem`` is the DEM process's own coupling work: gathering the particles' state, sorting it
    into the fluid ranks' arrays, summing and applying the forces, and (``implicitDrag``) the
    drag's update at every sub-step; ``waiting`` the DEM's wait for the forces (the fluid's
    exchange plus whatever was left of its previous step). The fluid ranks report their
    exchanges (particles received, located, forces computed and sent) and fluid steps one
    exchange late: ``fluidExchange`` and ``fluidSteps`` sum ``fluidReports`` of them, each the
    slowest rank's. The ``...Cpu`` fields are the same as CPU time (``demCpu``: the DEM's main
    thread in the coupling's hooks, without its polling while it waits for the forces), which a
    busy machine does not stretch as it stretches wall times."""
    exchanges: int = 0
    dem: float = 0.0
    waiting: float = 0.0
    fluidReports: int = 0
    fluidExchange: float = 0.0
    fluidSteps: float = 0.0
    demCpu: float = 0.0
    fluidExchangeCpu: float = 0.0
    fluidStepsCpu: float = 0.0

    def since(self, earlier: "CouplingTimes") -> "CouplingTimes":
        """The times spent between the snapshot ``earlier`` (a ``copy()``) and this one."""
        return CouplingTimes(**{k: getattr(self, k) - getattr(earlier, k) for k in self.__dataclass_fields__})

    def copy(self) -> "CouplingTimes":
        return CouplingTimes(**vars(self))


from talus.dem.step.engines import Engine as _Engine  # noqa: E402


class FoamCoupling(_Engine):
    """DEM side of the CFD-DEM coupling (point-force or volume-averaged solver).

    Two interfaces. Talus's: ``FoamCoupling(O, case, rhoFluid=..., nu=...)`` then ``start()``
    (below). Yade's (its examples/openfoam scripts run unchanged): ``FoamCoupling()`` without
    arguments, ``setNumParticles``, ``setIdList``, ``isGaussianInterp``, ``getRank()``, the
    engine put in ``O.engines`` after the time stepper, ``killMPI()`` at the end; see
    :meth:`setIdList` and the section "Running Yade's OpenFOAM examples" of docs/coupling.md.

    A periodic scene (``O.periodic``) is coupled with a mesh whose cyclic patches span the cell:
    the particles' positions are sent wrapped into the cell (origin 0).

    Args:
        scene: the DEM scene (O).
        case: OpenFOAM case folder (0/, constant/ with transportProperties and g, system/);
            decomposed into ``nProcs`` folders when ``nProcs > 1``.
        rhoFluid, nu: fluid density [kg/m3] and kinematic viscosity [m2/s]; the solver refuses
            values different from its transportProperties.
        gravity: must equal the case's constant/g and the NewtonIntegrator's gravity.
        ids: bodies coupled (default: every sphere).
        solver: solver name or path: talusPointForceFoam (default; point forces, Stokes drag
            unless the case's constant/couplingProperties sets dragModel, e.g. SchillerNaumann)
            or talusVolumeAveragedFoam (fluid fraction, Gaussian envelope, Schiller-Naumann drag).
        nProcs: fluid ranks (MPI_Comm_spawn, ``-parallel`` when > 1).
        couplingInterval: [s] the fluid deltaT may not exceed it (None: no limit).
        timeout: longest wait [s] of either side for the other: the DEM for the fluid's forces,
            the fluid for the DEM's next exchange (a DEM stuck in a step, a hook or a PyRunner, or
            stopped, for longer); then both sides stop, each saying why, and every process of
            the run ends.
        interfaces: the network interfaces Open MPI's TCP traffic may use (Open MPI's
            ``if_include`` syntax: names or CIDR networks, comma-separated). Default ``"lo"``,
            the loopback: a run on one host stays off the network. ``None``: Open MPI's default
            (every interface but the loopback), or e.g. ``"eth0"`` for fluid ranks on other
            hosts; ``OMPI_MCA_{btl,oob}_tcp_if_{include,exclude}`` in the environment win
            (talus.coupling.network).
        reynoldsLimit: a RuntimeWarning when the particle Reynolds number exceeds it (default:
            the limit of the solver's drag law, told at the handshake: 0.5 for Stokes drag, 2e5
            for Schiller-Naumann, 1e4 for Di Felice).
        implicitDrag: re-evaluate the drag beta (u_f - v) at every DEM sub-step with the particle's
            current velocity (beta and u_f from the last exchange) instead of holding the drag of
            the exchange over the fluid step. Needed when the particles' velocities change within
            a fluid step (contacts in a dense bed), stable for DEM steps below the relaxation time.
        checkpoint: DEM checkpoint file written (atomically, O.save) every
            ``checkpointInterval`` fluid steps at the end of a DEM step; if the coupled run fails
            (a particle leaves the mesh, a fluid rank dies) the last one written is intact.
    """

    def __init__(self, scene=None, case=None, *, rhoFluid: float | None = None, nu: float | None = None,
                 gravity=(0.0, 0.0, -9.81), ids=None,
                 solver: str = "talusPointForceFoam", nProcs: int = 1, couplingInterval: float | None = None,
                 timeout: float = 60.0, reynoldsLimit: float | None = None, checkpoint=None,
                 checkpointInterval: int = 100, implicitDrag: bool = False, interfaces: str | None = "lo",
                 label: str = ""):
        # The engine Yade's scripts put in O.engines (a callback every step, see _engine_step).
        from talus.dem.step.engines import PyRunner
        import weakref
        me = weakref.ref(self)  # no cycle through the C++ engine's callback

        def step():
            coupling = me()
            if coupling is not None:
                coupling._engine_step()
        self._runner = PyRunner(step, iterPeriod=1)
        self._runner._cpp.resumable = False   # a failed exchange leaves the step without the fluid's forces
        self._cpp = self._runner._cpp
        self.label = label
        self._yade = scene is None and case is None  # Yade's interface: FoamCoupling()
        if scene is None:
            from talus.dem import O as scene
        if not self._yade and (case is None or rhoFluid is None or nu is None):
            raise TypeError("FoamCoupling(scene, case, rhoFluid=..., nu=...): give the case and the fluid's "
                            "properties, or no argument at all (Yade's interface: the case is the working "
                            "directory, see docs/coupling.md)")
        self.scene = scene
        self.case = str(Path(case if case is not None else os.getcwd()).resolve())
        self.rhoFluid = None if rhoFluid is None else float(rhoFluid)
        self.nu = None if nu is None else float(nu)
        self.gravity = tuple(float(g) for g in gravity)
        self.ids = None if ids is None else np.asarray(ids, dtype=np.int64)
        self.solver, self.nProcs = solver, int(nProcs)
        self.couplingInterval, self.timeout = couplingInterval, float(timeout)
        if not self.timeout > 0:
            raise ValueError(f"FoamCoupling: timeout must be a positive number of seconds, got {timeout!r}")
        network_settings(interfaces)  # refuses a malformed value before anything starts
        self.interfaces = interfaces
        self.reynoldsLimit = None if reynoldsLimit is None else float(reynoldsLimit)  # None: the solver's (start)
        if checkpoint is not None and int(checkpointInterval) < 1:
            raise ValueError(f"FoamCoupling: checkpointInterval must be >= 1 fluid steps, got {checkpointInterval}")
        self.checkpoint = None if checkpoint is None else str(checkpoint)
        self.checkpointInterval = int(checkpointInterval)
        self._checkpoint_hook = None
        self.implicitDrag = bool(implicitDrag)
        self._drag_hook = None
        self._beta = self._fluid_velocity = self._sent_velocity = None
        self.link = None
        self.substeps = 0
        self.hook = None
        self.maxReynolds = 0.0
        self.exchanges = 0
        self.times = CouplingTimes()
        self._applied = None
        self._owned = None   # under mpirun: this process's particles (talus.coupling.decomposed)
        # Yade's interface (FoamCoupling()): see _engine_step.
        self.isGaussianInterp = False
        self.couplingModeParallel = False
        self.numParticles = 1            # Yade's default
        self.fluidDensity = 1.0          # Yade's attributes; the case's values are used
        self.particleDensity = 1.0
        self.dataExchangeInterval = 0
        self.foamDeltaT = 0.0
        self.fluidSteps = None           # fluid steps before the case's endTime (Yade's solver stops there)
        self._id_list = None
        self._since_exchange = 0
        self._force = None
        self._finished = False

    # -- Yade's interface ----------------------------------------------------------------------
    def getRank(self):
        """Yade: initialises the coupling's MPI communicator. Talus starts MPI with the fluid
        ranks at the engine's first step; returns None as Yade's."""
        return None

    def setNumParticles(self, numparticles: int):
        """Yade: the number of coupled particles (must equal the length of :meth:`setIdList`'s)."""
        self.numParticles = int(numparticles)

    def setIdList(self, bodyIdList):
        """Yade: the bodies (spheres) coupled with the fluid."""
        self._id_list = [int(i) for i in bodyIdList]

    def getIdList(self) -> list[int]:
        """Yade: the ids of the coupled bodies."""
        if self._id_list is None:
            return [int(i) for i in (self.ids if self.ids is not None else self.scene.sphere_ids())]
        return list(self._id_list)

    def getNumBodies(self) -> int:
        """Yade: the number of coupled bodies."""
        return len(self.getIdList())

    def insertBodyId(self, newId: int):
        """Yade: couple one more body (before the first step: the fluid ranks are told the
        particle count at the handshake)."""
        self._before_start("insertBodyId")
        self._id_list = self.getIdList() + [int(newId)]
        self.numParticles = len(self._id_list)

    def eraseId(self, idToErase: int):
        """Yade: stop coupling a body (before the first step, as insertBodyId)."""
        self._before_start("eraseId")
        ids = self.getIdList()
        if int(idToErase) not in ids:
            raise ValueError(f"FoamCoupling.eraseId: body {idToErase} is not coupled")
        ids.remove(int(idToErase))
        self._id_list = ids
        self.numParticles = len(ids)

    def getFluidDomainBbox(self):
        """Yade: the fluid ranks' sub-mesh boxes (known after the handshake): one
        ((xmin, ymin, zmin), (xmax, ymax, zmax)) per fluid rank."""
        if self.link is None:
            return []
        boxes = np.array(self.link.boxes).reshape(-1, 7)
        return [(tuple(b[:3]), tuple(b[3:6])) for b in boxes]

    def killMPI(self):
        """Yade: end of the coupled run: the fluid ranks write their fields and exit."""
        self.stop()

    @property
    def fluidDomains(self):
        return []

    def _before_start(self, what: str):
        if self.link is not None:
            raise RuntimeError(f"FoamCoupling.{what}: the coupling has started (the fluid ranks were told "
                               f"{self.link.nParticles} particles); change the coupled bodies before O.run")

    def _engine_step(self):
        """The engine's work each DEM step (Yade's interface: the engine in O.engines, after the
        time stepper, before the NewtonIntegrator). First step: start the fluid ranks in the
        working directory (solver from controlDict's application: icoFoamYade = point force,
        pimpleFoamYade = volume averaged; ranks from the decomposition), as Yade's run.sh does
        with mpiexec. Then, as Yade: an exchange every dataExchangeInterval = foamDeltaT / O.dt
        steps (recomputed at each exchange with the current O.dt, which a time stepper changes),
        the last exchange's hydrodynamic forces added to the coupled bodies at every step. When
        the fluid reaches the case's endTime (where Yade's solvers leave their time loop) the
        fluid ranks stop and the DEM run is paused."""
        if not self._yade or self._finished:
            return
        if self.link is None:
            self._yade_start()
            self._since_exchange = self.dataExchangeInterval  # exchange at once
        if self._since_exchange >= self.dataExchangeInterval:
            if self.fluidSteps is not None and self.exchanges >= self.fluidSteps:
                self._finish()
                return
            self.exchange_yade()
            self.dataExchangeInterval = max(1, int(self.foamDeltaT / self.scene.dt * (1 + 1e-9)))
            self._since_exchange = 0
        self.scene.forces()[self._rows] += self._force
        self._since_exchange += 1

    def _yade_start(self):
        if self.couplingModeParallel:
            raise NotImplementedError("FoamCoupling.couplingModeParallel (Yade-MPI's parallel DEM) is not "
                                      "supported: Talus decomposes the DEM under mpirun -np N talus run, with "
                                      "FoamCoupling(O, case, rhoFluid=..., nu=...).start() (docs/coupling.md)")
        case = case_settings(self.case)
        application = case["application"]
        if application in YADE_SOLVERS or application in YADE_SOLVERS.values():
            self.solver = application
        else:
            self.solver = "pimpleFoamYade" if self.isGaussianInterp else "icoFoamYade"
        talus_solver = YADE_SOLVERS.get(self.solver, self.solver)
        if self.isGaussianInterp != (talus_solver == "talusVolumeAveragedFoam"):
            warnings.warn(f"FoamCoupling: isGaussianInterp={self.isGaussianInterp} but the case's solver is "
                          f"{self.solver}: the solver decides (Gaussian envelope with pimpleFoamYade only)",
                          RuntimeWarning, stacklevel=3)
        self.rhoFluid, self.nu, self.nProcs = case["rhoFluid"], case["nu"], case["nProcs"]
        self.gravity = tuple(case["gravity"])
        from talus.dem.step.engines import NewtonIntegrator
        for e in self.scene.engines:
            if isinstance(e, NewtonIntegrator) and not np.allclose(e.gravity, self.gravity, rtol=1e-12, atol=0):
                warnings.warn(f"FoamCoupling: the NewtonIntegrator's gravity {tuple(e.gravity)} differs from the "
                              f"case's constant/g {self.gravity} (the fluid's buoyancy uses constant/g)",
                              RuntimeWarning, stacklevel=3)
        if self._id_list is not None:
            if self.numParticles != len(self._id_list):
                raise ValueError(f"FoamCoupling: setNumParticles({self.numParticles}) but setIdList got "
                                 f"{len(self._id_list)} ids")
            self.ids = np.asarray(self._id_list, dtype=np.int64)
        ids = self._coupled_ids()
        if len(ids) == 0:
            raise ValueError("FoamCoupling: no sphere to couple")
        self.ids = np.ascontiguousarray(ids, dtype=np.int64)
        contiguous = np.array_equal(ids, np.arange(ids[0], ids[0] + len(ids)))
        self._rows = slice(int(ids[0]), int(ids[0]) + len(ids)) if contiguous else self.ids
        self._start_link(self.ids)
        self.foamDeltaT = self.link.fluidDt
        if case["endTime"] is not None and self.foamDeltaT > 0:
            self.fluidSteps = max(0, int(round((case["endTime"] - case["startTime"]) / self.foamDeltaT)))
        if not self.scene.dt > 0:
            raise ValueError("FoamCoupling: O.dt must be positive at the first step")
        self.dataExchangeInterval = max(1, int(self.foamDeltaT / self.scene.dt * (1 + 1e-9)))
        self.substeps = self.dataExchangeInterval
        self._warn_relaxation(self.foamDeltaT, self.ids)
        self._force = np.zeros((len(self.ids), 3))
        print(f"FoamCoupling: {self.link.fluidProcs} rank(s) of {Path(find_solver(self.solver)).name} "
              f"({talus_solver}) on {self.case}, {len(self.ids)} particles, fluid deltaT {self.foamDeltaT:g} s, "
              f"exchange every {self.dataExchangeInterval} DEM steps"
              + (f", {self.fluidSteps} fluid steps to endTime" if self.fluidSteps is not None else ""), flush=True)

    def exchange_yade(self):
        """One fluid step with Yade's interface: the forces are kept and added every step."""
        start, start_cpu = time.perf_counter(), time.thread_time()
        rows = self._rows
        forces, re, self._beta, self._fluid_velocity = self.link.exchange(
            self._positions(rows), self.scene.velocities()[rows], self.scene.radii()[rows])
        if not np.all(np.isfinite(forces)):
            raise FloatingPointError("FoamCoupling: the fluid returned non-finite forces")
        self._force = forces
        self._received(forces, re)
        self._count_times(time.perf_counter() - start, time.thread_time() - start_cpu)

    def _write_summary(self, path):
        """A JSON summary of the coupled run (Yade's interface; written at stop() when
        TALUS_FOAM_SUMMARY names a file): what cases/cfd/cfd_yade_openfoam_examples.py checks."""
        import json
        rows = self._rows
        r = np.array(self.scene.radii()[rows])
        beta = np.zeros(len(r)) if self._beta is None else np.asarray(self._beta)
        stokes = 3 * math.pi * self.rhoFluid * self.nu * 2 * r
        forces = np.asarray(self._force if self._force is not None else np.zeros((len(r), 3)))
        summary = dict(solver=self.solver, fluidProcs=self.link.fluidProcs, nCells=self.link.nCells,
                       particles=len(r), exchanges=self.exchanges, fluidSteps=self.fluidSteps,
                       foamDeltaT=self.foamDeltaT, dataExchangeInterval=self.dataExchangeInterval,
                       iter=self.scene.iter, time=self.scene.time, maxReynolds=self.maxReynolds,
                       rhoFluid=self.rhoFluid, nu=self.nu,
                       beta_over_stokes=(beta / stokes).tolist(),
                       finite=bool(np.all(np.isfinite(forces)) and np.all(np.isfinite(self.scene.velocities()[rows]))),
                       positions=self._positions(rows).tolist(),
                       velocities=np.asarray(self.scene.velocities()[rows]).tolist(),
                       forces=forces.tolist(),
                       fluid_velocities=np.asarray(self._fluid_velocity if self._fluid_velocity is not None
                                                   else np.zeros((len(r), 3))).tolist())
        Path(path).write_text(json.dumps(summary))

    def _finish(self):
        """The fluid reached the case's endTime: stop it and pause the DEM run."""
        self._finished = True
        print(f"FoamCoupling: the fluid reached endTime after {self.exchanges} fluid steps; "
              f"fluid stopped, DEM run paused at iteration {self.scene.iter}", flush=True)
        self.stop()
        self.scene.pause()

    # -- start ---------------------------------------------------------------------------------
    def _coupled_ids(self) -> np.ndarray:
        if self.ids is not None:
            self._check_ids(self.ids)
            return self.ids
        return self.scene.sphere_ids()

    def _check_ids(self, ids: np.ndarray):
        """Before any process starts: every id a live sphere of the scene, none twice (a negative
        id would otherwise wrap around to another body in the per-body arrays)."""
        count = len(self.scene.bodies)
        outside = ids[(ids < 0) | (ids >= count)]
        if len(outside):
            raise ValueError(f"FoamCoupling: ids: {int(outside[0])} is not a body id of the scene "
                             f"(0 ... {count - 1})")
        unique, seen = np.unique(ids, return_counts=True)
        if np.any(seen > 1):
            raise ValueError(f"FoamCoupling: ids: body {int(unique[seen > 1][0])} is listed twice")
        others = ids[~np.isin(ids, self.scene.sphere_ids())]
        if len(others):
            i = int(others[0])
            try:
                what = f"a {type(self.scene.bodies[i].shape).__name__}"
            except IndexError:
                what = "erased"
            raise ValueError(f"FoamCoupling: ids: body {i} is {what}, not a sphere")

    def _check_gravity(self):
        from talus.dem.step.engines import NewtonIntegrator
        for e in self.scene.engines:
            if isinstance(e, NewtonIntegrator) and not np.allclose(e.gravity, self.gravity, rtol=1e-12, atol=0):
                raise ValueError(f"FoamCoupling: gravity {self.gravity} differs from the NewtonIntegrator's "
                                 f"{tuple(e.gravity)}")

    def start(self):
        """Spawn the solver, check the case and the time steps, set O.dt and add the hook."""
        if self._yade:
            raise RuntimeError("FoamCoupling.start: with Yade's interface (FoamCoupling() without arguments) "
                               "the engine starts the fluid at its first step in O.engines")
        if self.link is not None:
            raise RuntimeError("FoamCoupling.start: already started")
        self._check_gravity()
        if distributed.ACTIVE:
            return self._start_decomposed()
        ids = self._coupled_ids()
        if len(ids) == 0:
            raise ValueError("FoamCoupling: no sphere to couple")
        self.ids = np.ascontiguousarray(ids, dtype=np.int64)  # as add_force_change takes them
        # The rows of the coupled bodies in the per-body arrays: a slice when they are one run of
        # ids (every sphere of a scene that has its walls first, say), so that the per-exchange
        # gathers and updates are views instead of copies (index arrays copy every row at every
        # exchange: docs/coupling.md, "Measurements behind the code").
        contiguous = np.array_equal(ids, np.arange(ids[0], ids[0] + len(ids)))
        self._rows = slice(int(ids[0]), int(ids[0]) + len(ids)) if contiguous else ids
        self._start_link(ids)
        self._applied = np.zeros((len(ids), 3))
        return self._add_hooks(ids)

    def _start_decomposed(self):
        """start() under mpirun (the DEM split over the processes, talus.dem.distributed): every
        process starts the fluid ranks with the others and exchanges the particles it owns
        (talus.coupling.decomposed). Collective."""
        if self.checkpoint is not None:
            distributed.refuse("FoamCoupling's checkpoints")
        if self.ids is not None and distributed.domain(self.scene) is None:
            self._check_ids(self.ids)
        self._owned = OwnedParticles(self.scene, self.ids, _module())
        self._owned.refresh()
        count = int(self._owned.total([len(self._owned.ids)])[0])
        if count == 0:
            raise ValueError("FoamCoupling: no sphere to couple")
        self._start_link(self._owned.rows, count, self._owned.ids)
        return self._add_hooks(self._owned.rows)

    def _add_hooks(self, rows):
        """Sub-steps and O.dt from the fluid's step, the hooks (after the link has started)."""
        m = _module()
        dt_fluid = self.link.fluidDt
        if not self.scene.dt > 0:
            raise ValueError("FoamCoupling: set O.dt (the DEM time step) before start()")
        self.substeps = max(1, math.ceil(dt_fluid / self.scene.dt * (1 - 1e-12)))
        self.scene.dt = dt_fluid / self.substeps
        self._warn_relaxation(dt_fluid, rows)
        self._add_force_change = m.add_force_change
        self.hook = self.scene.add_hook("before_forces", self.exchange, self.substeps)
        if self.implicitDrag:
            self._drag_hook = self.scene.add_hook("after_forces", self._update_drag, 1)
        if self.checkpoint is not None:
            self.save_checkpoint()
            self._checkpoint_hook = self.scene.add_hook("after_step", self.save_checkpoint,
                                                        self.substeps * self.checkpointInterval)
        return self

    def _start_link(self, rows, count=None, names=None):
        """Start the fluid ranks (handshake), refuse particles outside the mesh. ``rows``: the
        particles' rows here; ``count``: of the whole DEM (default: the rows'); ``names``: their
        ids in messages (default: the rows)."""
        os.environ.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")  # OpenFOAM's etc/ files
        # The DEM process plus the fluid ranks usually outnumber the cores; Open MPI refuses to
        # spawn more processes than slots unless told (read when MPI starts, below).
        os.environ.setdefault("OMPI_MCA_rmaps_base_oversubscribe", "1")
        apply_network_settings(self.interfaces)
        m = _module()
        s = m.FoamSettings()
        s.solver, s.caseDir, s.nProcs = find_solver(self.solver), self.case, self.nProcs
        s.rhoFluid, s.nu, s.gravity = self.rhoFluid, self.nu, self.gravity
        s.couplingInterval, s.timeout = float(self.couplingInterval or 0.0), self.timeout
        s.demAcrossProcesses = distributed.ACTIVE
        if distributed.ACTIVE:   # the solver ranks get mpirun's environment, not this process's
            s.environment = [f"WM_PROJECT_DIR={os.environ['WM_PROJECT_DIR']}"]
        try:
            self.link = m.FoamLink(s, len(rows) if count is None else count)
        except RuntimeError as e:   # every DEM process has the same reason
            raise (collective(e) if distributed.ACTIVE else e) from None
        _links.append(self.link)
        if self.reynoldsLimit is None:
            self.reynoldsLimit = self.link.dragReynoldsLimit
        self._check_inside_mesh(rows, rows if names is None else names)

    def _check_inside_mesh(self, rows, names):
        """Refuse (before the first step) a particle outside the bounding box of the fluid mesh,
        the union of the ranks' sub-mesh boxes; one inside the box but outside a non-convex
        mesh is found by the fluid ranks at the first exchange. Under mpirun every process
        checks its own particles and all raise the same error."""
        boxes = np.array(self.link.boxes).reshape(-1, 7)[:, :6]
        boxes = boxes[np.all(boxes[:, :3] <= boxes[:, 3:], axis=1)]  # ranks without cells send an empty box
        low, high = boxes[:, :3].min(axis=0), boxes[:, 3:].max(axis=0)
        tolerance = 1e-9 * np.linalg.norm(high - low)
        x = self._positions(rows)
        outside = np.flatnonzero(np.any((x < low - tolerance) | (x > high + tolerance), axis=1))
        reduce = self._owned if self._owned is not None else None
        total = len(outside) if reduce is None else int(reduce.total([len(outside)])[0])
        if total:
            # the lowest id outside, and its position from its process
            first = float(names[outside[0]]) if len(outside) else math.inf
            first = first if reduce is None else reduce.smallest(first)
            where = np.zeros(3)
            if len(outside) and names[outside[0]] == first:
                where = x[outside[0]]
            where = where if reduce is None else np.array(reduce.total(where))
            self.link.stop()
            error = ValueError(f"FoamCoupling: particle {int(first)} at ({where[0]:g}, {where[1]:g}, {where[2]:g}) is "
                               f"outside the fluid mesh of case '{self.case}' (its bounding box is "
                               f"({low[0]:g}, {low[1]:g}, {low[2]:g}) - ({high[0]:g}, {high[1]:g}, {high[2]:g})); "
                               f"{total} particle(s) outside, nothing was run")
            raise collective(error) if reduce is not None else error

    def save_checkpoint(self):
        """Write the DEM checkpoint (O.save, atomic; the engines are not stored: the coupling's
        hooks cannot be)."""
        self.scene.save(self.checkpoint, engines=False)

    def _warn_relaxation(self, dt_fluid, rows):
        r = self.scene.radii()[rows]
        m = self.scene.masses()[rows]
        rho_p = m / (4 / 3 * math.pi * r ** 3)
        tau = float(np.min(rho_p * (2 * r) ** 2 / (18 * self.rhoFluid * self.nu), initial=math.inf))
        if self._owned is not None:
            tau = self._owned.smallest(tau)
        self.relaxationTime = tau
        if dt_fluid > tau:
            warnings.warn(f"FoamCoupling: the fluid step {dt_fluid:g} s exceeds the particle relaxation time "
                          f"{tau:g} s: the explicit drag held over a fluid step is inaccurate or unstable; "
                          f"lower deltaT in system/controlDict", RuntimeWarning, stacklevel=3)

    def _warn_drag_relaxation(self, ids, names=None):
        """The relaxation time m / beta with the drag the fluid actually applies (with the
        volume-averaged solver: Schiller-Naumann and the hindrance factor, up to ~20 times shorter
        than the Stokes estimate of start() in a dense bed)."""
        beta = self._beta
        if not np.any(beta > 0):
            return
        tau = np.where(beta > 0, self.scene.masses()[ids] / np.where(beta > 0, beta, 1.0), np.inf)
        k = int(np.argmin(tau))
        if self.implicitDrag:
            step, what, fix = self.scene.dt, "DEM step", "lower O.dt"
        else:
            step, what, fix = self.link.fluidDt, "fluid step", "lower deltaT in system/controlDict or use implicitDrag=True"
            if step > self.relaxationTime:
                return  # start() has warned already
        if step > tau[k]:
            warnings.warn(f"FoamCoupling: the {what} {step:g} s exceeds the relaxation time m/beta = {tau[k]:g} s of "
                          f"body {int((ids if names is None else names)[k])} with the drag of the first exchange (hindrance included): the drag "
                          f"is inaccurate or unstable; {fix}", RuntimeWarning, stacklevel=3)

    # -- exchange ------------------------------------------------------------------------------
    def exchange(self):
        """One fluid step: send the particles, replace last step's forces by the new ones."""
        if self._owned is not None:
            return self._exchange_decomposed()
        start, start_cpu = time.perf_counter(), time.thread_time()
        ids, rows = self.ids, self._rows
        velocities = self.scene.velocities()[rows]  # a view when rows is a slice: no copy sent
        forces, re, self._beta, self._fluid_velocity = self.link.exchange(self._positions(rows), velocities,
                                                                          self.scene.radii()[rows])
        if self.implicitDrag:
            self._sent_velocity = np.array(velocities)  # a copy: the sub-steps change the view
        if self.exchanges == 0:
            self._warn_drag_relaxation(ids)
        # The persistent forces carry the force over the sub-steps; this step's accumulator was
        # already filled from them by the ForceResetter, so it gets the change too.
        self._add_force_change(forces, self._applied, ids, self.scene.persistent_forces(), self.scene.forces())
        self._applied = forces
        self._received(forces, re)
        self._count_times(time.perf_counter() - start, time.thread_time() - start_cpu)

    def _exchange_decomposed(self):
        """exchange() under mpirun: this process's particles (collective)."""
        start, start_cpu = time.perf_counter(), time.thread_time()
        owned = self._owned
        owned.refresh()
        rows = owned.rows
        velocities = self.scene.velocities()[rows]
        try:
            forces, re, beta, self._fluid_velocity = self.link.exchange(self._positions(rows), velocities,
                                                                        self.scene.radii()[rows], owned.ids)
        except RuntimeError as e:
            if "outside the fluid mesh" in str(e):  # found by every process together
                raise collective(e) from None
            raise
        # The same sums as in one process: the change from the force applied at the last exchange.
        self._add_force_change(forces, owned.applied, rows, self.scene.persistent_forces(), self.scene.forces())
        owned.store(forces, beta, velocities)
        self._beta = beta
        if self.exchanges == 0:
            self._warn_drag_relaxation(rows, owned.ids)
        self._received(forces, re)
        self._count_times(time.perf_counter() - start, time.thread_time() - start_cpu)

    def _received(self, forces, re: float):
        """Book one exchange's forces and largest particle Reynolds number (warned once past
        the solver's drag law's limit)."""
        self.lastForces = forces
        self.exchanges += 1
        if re > self.reynoldsLimit and self.maxReynolds <= self.reynoldsLimit:
            warnings.warn(f"FoamCoupling: particle Reynolds number {re:.3g} exceeds {self.reynoldsLimit:g}: the drag "
                          f"law of {Path(self.solver).name} is no longer accurate; dragModel in the case's "
                          f"constant/couplingProperties selects it (docs/coupling.md lists the drag laws and their "
                          f"ranges: SchillerNaumann for finite Re_p)", RuntimeWarning, stacklevel=3)
        self.maxReynolds = max(self.maxReynolds, re)

    def _count_times(self, hook_seconds: float, hook_cpu: float):
        link, times = self.link, self.times
        times.exchanges += 1
        times.waiting += link.lastWaitSeconds
        times.dem += hook_seconds - link.lastWaitSeconds
        times.demCpu += hook_cpu - link.lastWaitCpuSeconds
        if self.exchanges > 1:  # the first reply has nothing to report yet
            times.fluidReports += 1
            times.fluidExchange += link.lastFluidExchangeSeconds
            times.fluidSteps += link.lastFluidStepSeconds
            times.fluidExchangeCpu += link.lastFluidExchangeCpuSeconds
            times.fluidStepsCpu += link.lastFluidStepCpuSeconds

    def _positions(self, rows) -> np.ndarray:
        """The particles' positions; in a periodic scene moved into the cell by whole periods (the
        DEM keeps positions unwrapped; the mesh's cyclic patches span the cell)."""
        x = self.scene.positions()[rows]
        if not self.scene.periodic:
            return x
        h = self.scene.cell.hSize
        frac = np.linalg.solve(h, x.T)
        return (h @ (frac - np.floor(frac))).T

    def _update_drag(self):
        """This sub-step's drag minus the exchange's: beta (v_exchange - v) (implicitDrag)."""
        if self._beta is None:
            return
        start, start_cpu = time.perf_counter(), time.thread_time()
        if self._owned is not None:   # under mpirun: after a migration, the particles' new rows (collective)
            self._owned.refresh()
            rows, beta, sent = self._owned.rows, self._owned.beta, self._owned.sent_velocity
        else:
            rows, beta, sent = self._rows, self._beta, self._sent_velocity
        self.scene.forces()[rows] += beta[:, None] * (sent - self.scene.velocities()[rows])
        self.times.dem += time.perf_counter() - start
        self.times.demCpu += time.thread_time() - start_cpu

    def stop(self):
        """Let the fluid write its last fields and exit; remove the hooks."""
        if self._yade and self.link is not None:
            self._finished = True  # the engine does nothing more (Yade's killMPI)
            if os.environ.get("TALUS_FOAM_SUMMARY") and self.link.running:
                self._write_summary(os.environ["TALUS_FOAM_SUMMARY"])
        for hook in (self.hook, self._checkpoint_hook, self._drag_hook):
            if hook is not None:
                hook.dead = True
        if self.link is not None and self.link.running:
            self.link.stop()
