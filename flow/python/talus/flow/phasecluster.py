"""Yade's ``PhaseCluster``: one cluster of pores of a TwoPhaseFlowEngine with
``isCellLabelActivated`` (``getClusters()[k]``; label 0 the non-wetting pores, 1 the wetting
reservoir, 2... other wetting clusters) and its interfaces, the throats from one of its pores to a
non-wetting pore. A dynamic injection (Yade's ``TwoPhaseFlowInjection.py``) moves the menisci of
the interfaces (their volumes, ``updateCapVolList``) with the fluxes of the cluster's pressure
field (``solvePressure``) and lets the pores they fill join the cluster
(``TwoPhaseFlowEngine.clusterOutvadePore``). Interfaces are addressed by their rank in
``getInterfaces()``, which a pore joining the cluster changes (see docs/twophase.md).
"""

from __future__ import annotations

import math
import numbers


class PhaseCluster:
    """A view of cluster ``index`` of a TwoPhaseFlowEngine: it follows the cluster as it grows or
    merges (as Yade's shared object), until the engine's next ``initialization()``."""

    def __init__(self, engine, index: int):
        self._engine = engine
        self._index = index

    def _tp(self):
        engine = self._engine
        # the engine's check, inlined: scripts call these once per interface and step
        return engine._tp if engine._current else engine._state()

    def _number(self, numf) -> int:
        """The interface rank ``numf`` checked (an integer, numpy's too; the range is checked in C++)."""
        if type(numf) is int:
            return numf
        if isinstance(numf, bool) or not isinstance(numf, numbers.Integral):
            raise TypeError(f"PhaseCluster: interface index (numf) must be an integer, got {numf!r}")
        return int(numf)

    def _summary(self) -> dict:
        return self._tp().cluster(self._index)

    @property
    def label(self) -> int:
        return self._summary()["label"]

    @property
    def volume(self) -> float:
        """Pore-body volume of the cluster's pores."""
        return self._summary()["volume"]

    @property
    def entryRadius(self) -> float:
        """Largest entry radius of the throats of its interfaces."""
        return self._summary()["entryRadius"]

    @property
    def entryPore(self) -> int:
        return self._summary()["entryPore"]

    @property
    def interfacialArea(self) -> float:
        return self._summary()["interfacialArea"]

    def getPores(self) -> list[int]:
        return list(self._summary()["pores"])

    def getInterfaces(self, cellId: int = -1, **kwargs) -> list[tuple]:
        """The interfaces as (inner pore, outer pore, fluid area, rank); with ``cellId`` >= 0 only
        those of that inner pore. Yade 2023.02a's binding spells the argument ``CellId`` (so its
        own TwoPhaseFlowInjection.py, which passes ``cellId``, stops there): both are accepted."""
        if kwargs:
            if set(kwargs) != {"CellId"}:
                raise TypeError(f"PhaseCluster.getInterfaces() got unexpected arguments {sorted(kwargs)}")
            cellId = kwargs["CellId"]
        return self._tp().interfaces(self._index, self._number(cellId))

    def _interface(self, numf):
        return self._tp().interface(self._index, self._number(numf))

    def getFlux(self, interface: int) -> float:
        """Flux through the interface out of the cluster: conductance (p_inner + capillary
        pressure - p_outer) (the velocity of the meniscus times the throat's area)."""
        return self._tp().interfaceFlux(self._index, self._number(interface))

    def getConductivity(self, numf: int) -> float:
        return self._tp().interfaceConductance(self._index, self._number(numf))

    def setCapPressure(self, numf: int, pCap: float):
        """Capillary pressure jump across the interface (added to the inner pore's pressure)."""
        self._interface(numf).capillaryPressure = _finite("pCap", pCap)

    def getCapPressure(self, numf: int) -> float:
        return self._interface(numf).capillaryPressure

    def setCapVol(self, numf: int, vCap: float):
        """Volume that crossed the interface (the meniscus position)."""
        self._tp().setInterfaceVolume(self._index, self._number(numf), _finite("vCap", vCap))

    def getCapVol(self, numf: int) -> float:
        # the checks inlined: scripts call it once per interface and step
        engine = self._engine
        return (engine._tp if engine._current else engine._state()).interfaceVolume(
            self._index, numf if type(numf) is int else self._number(numf))

    def updateCapVol(self, numf: int, dt: float) -> float:
        """Add flux * dt to the interface's volume; returns it."""
        interface = self._interface(numf)
        interface.volume += _finite("dt", dt) * self.getFlux(numf)
        return interface.volume

    def updateCapVolList(self, dt: float):
        """Add flux * dt to the volume of every interface."""
        self._tp().updateInterfaceVolumes(self._index, _finite("dt", dt))

    def solvePressure(self):
        """The pressures of the cluster's pores (those not on a pressure boundary): Darcy flow in
        the cluster with the non-wetting and imposed pressures around it, plus the interfaces'
        capillary pressures."""
        self._tp().solveClusterPressure(self._index)

    def __repr__(self):
        return f"<PhaseCluster label={self.label} pores={len(self.getPores())}>"


def _finite(name: str, value) -> float:
    number = float(value)
    if not math.isfinite(number):
        raise ValueError(f"PhaseCluster: {name} must be finite, got {value!r}")
    return number
