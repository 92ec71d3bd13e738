"""Two-way DEM x 1D VANS coupling (seed chapter 15.4): the DEM runs with the fluid forces of a
frozen fluid velocity profile for one coupling period; then the solid phase is averaged and the
fluid resolved over that period with the averaged profiles frozen; and so on::

    coupling = VansCoupling(hydro, period=1e-2, dtFluid=1e-5, densPart=2500, diameterPart=6e-3)
    coupling.attach()            # a PyRunner right after the HydroForceEngine in O.engines
    O.run(10000)
    coupling.series["transportRate"], coupling.series["shieldsNumber"]

The coupling period must stay short compared with the grains' response (the seed warns that a
drastic change of the fluid profile between two couplings is not compensated by the drag it
transmits): when the fluid velocity profile changes by more than ``changeLimit`` (relative L2
norm) between two couplings, a RuntimeWarning suggests a shorter period.
"""

from __future__ import annotations

import warnings

import numpy as np

from talus.dem.step.engines import PyRunner
from talus.flow.hydro import HydroForceEngine

__all__ = ["VansCoupling"]


class VansCoupling:
    """Alternate DEM and fluid resolution every ``period`` seconds of simulated time.

    Args:
        hydro: the HydroForceEngine (its ``fluid`` is resolved, its forces use the result).
        period: coupling period [s] (Yade's fluidResolPeriod); rounded to whole DEM steps.
        dtFluid: fluid time step [s].
        densPart, diameterPart: grain density and diameter, for the transport rate and the
            Shields number recorded at each coupling.
        changeLimit: relative change of the fluid velocity between two couplings above which a
            RuntimeWarning suggests a shorter period (0 disables it).
        warmup: couplings exempt from the warning: the first one follows a fluid resolution
            from solid profiles without drag (Yade's start-up), whatever the period.
    """

    def __init__(self, hydro: HydroForceEngine, period: float, dtFluid: float, *, densPart: float,
                 diameterPart: float, changeLimit: float = 0.1, warmup: int = 1):
        if not period > 0 or not dtFluid > 0:
            raise ValueError(f"VansCoupling: period and dtFluid must be positive, got {period}, {dtFluid}")
        if not densPart > hydro.densFluid or not diameterPart > 0:
            raise ValueError("VansCoupling: densPart must exceed the fluid density and diameterPart be positive")
        self.hydro, self.period, self.dtFluid = hydro, float(period), float(dtFluid)
        self.densPart, self.diameterPart, self.changeLimit = float(densPart), float(diameterPart), changeLimit
        self.series: dict[str, list[float]] = {"time": [], "transportRate": [], "shieldsNumber": [],
                                               "fluidChange": []}
        self.warmup = int(warmup)
        self.warned = 0
        self.runner: PyRunner | None = None

    @property
    def scene(self):
        return self.hydro.scene

    def attach(self) -> PyRunner:
        """Insert the coupling PyRunner right after the HydroForceEngine in the scene's engines,
        every round(period / O.dt) steps; returns it."""
        scene = self.scene
        engines = list(scene.engines)
        if not any(e is self.hydro for e in engines):
            raise ValueError("VansCoupling.attach: the HydroForceEngine is not in the scene's engines")
        steps = max(1, round(self.period / scene.dt))
        self.runner = PyRunner(self.couple, iterPeriod=steps)
        self.runner._cpp.resumable = False   # a failed exchange leaves the step without its forces
        engines.insert(next(k for k, e in enumerate(engines) if e is self.hydro) + 1, self.runner)
        scene.engines = engines
        return self.runner

    def couple(self) -> None:
        """One coupling: average the solid phase, resolve the fluid over the period (the actual
        period in DEM steps), record the transport rate, Shields number and fluid change."""
        h = self.hydro
        steps = self.runner.iterPeriod if self.runner is not None else max(1, round(self.period / self.scene.dt))
        before = h.vxFluid
        h.averageProfile()
        h.fluidResolution(steps * self.scene.dt, self.dtFluid)
        after = h.vxFluid
        # Relative L2 change of the profile: one layer at the bed surface, where a single grain
        # makes the solid fraction jump, does not dominate it as a maximum would.
        scale = np.linalg.norm(after)
        change = float(np.linalg.norm(after - before) / scale) if scale > 0 and np.any(before) else 0.0
        s = self.series
        s["time"].append(self.scene.time)
        s["transportRate"].append(h.transportRate(self.densPart, self.diameterPart))
        s["shieldsNumber"].append(h.shieldsNumber(self.densPart, self.diameterPart))
        s["fluidChange"].append(change)
        if self.changeLimit and change > self.changeLimit and len(s["time"]) > self.warmup:
            self.warned += 1
            if self.warned == 1:
                suggested = steps * self.scene.dt * self.changeLimit / change
                warnings.warn(f"VansCoupling: the fluid velocity profile changed by {change:.0%} (relative L2 norm) between two "
                              f"couplings (limit {self.changeLimit:.0%}) at t = {self.scene.time:g} s: the coupling "
                              f"period {steps * self.scene.dt:g} s is too long for the grains' response; use about "
                              f"{suggested:.2g} s or less", RuntimeWarning, stacklevel=2)
