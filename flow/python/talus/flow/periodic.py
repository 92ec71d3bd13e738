"""Pore-scale flow in a periodic cell (Yade's ``PeriodicFlowEngine``).

The spheres are wrapped into the orthorhombic cell [0, L) and the images of those closer than
radius + ``duplicateThreshold`` to a cell face enter the triangulation, so that every pore of the
cell is complete; the pores are then grouped by periodic translation, one pressure unknown per
periodic pore. The pressure is periodic plus the macroscopic gradient: a pore's image shifted by
n cells has the pressure p + ``gradP`` · (n ∘ L). Boundaries exist only where ``wallIds[k] >= 0``
(as Yade's: default none, all three axes periodic); an axis with a boundary is neither wrapped
nor duplicated (the injection tutorial's bottom and top walls). With nothing imposed (no pressure
boundary, no imposed point, incompressible fluid) the pressure is known up to a constant: Talus
reports the field whose periodic part p − gradP · x has zero volume-weighted mean.

    from talus.flow import PeriodicFlowEngine
    flow = PeriodicFlowEngine(gradP=(0, 1, 0), duplicateThreshold=0.2)
    flow.triangulate(positions, radii, cellSize=(1, 1, 1))   # or flow.triangulateScene(O)
    flow.solve()
    K = flow.samplePermeability()           # -mu <v> . g / |g|^2

In ``O.engines`` it reads the periodic cell (``O.cell.hSize``, diagonal) every step. Same
attributes and queries as ``FlowEngine`` (``docs/flow.md``), plus ``gradP``,
``duplicateThreshold`` and ``cellSize``.
"""

from __future__ import annotations

from typing import Sequence

import numpy as np

from talus.flow.pore import FlowEngine
from talus.dem.geometry.shapes import Sphere


class PeriodicFlowEngine(FlowEngine):
    """Yade's PeriodicFlowEngine (see the module docstring); defaults ``duplicateThreshold`` 0.06
    (a length, as Yade's), ``gradP`` (0, 0, 0), ``wallIds`` [-1]*6 (no boundary: fully periodic)."""

    def __init__(self, scene=None, **attrs):
        super().__init__(scene)
        self._constructed = False   # its own keywords follow: an unknown one is an error, as in Yade
        params = self._flow.params
        params.periodic = True
        params.hasBoundary = [False] * 6
        self._flow.params = params
        for name, value in attrs.items():
            setattr(self, name, value)
        self._constructed = True

    def __setattr__(self, name, value):
        if name in ("gradP", "cellSize"):
            vector = [float(v) for v in value]
            if len(vector) != 3:
                raise ValueError(f"PeriodicFlowEngine.{name} needs 3 values")
            if name == "cellSize" and not min(vector) > 0:
                raise ValueError("PeriodicFlowEngine.cellSize must be positive")
            params = self._flow.params
            setattr(params, name, np.array(vector))
            self._flow.params = params
            return
        if name == "duplicateThreshold":
            if not float(value) >= 0:
                raise ValueError("PeriodicFlowEngine.duplicateThreshold must be >= 0")
            params = self._flow.params
            params.duplicateThreshold = float(value)
            self._flow.params = params
            return
        super().__setattr__(name, value)
        if name == "wallIds":
            params = self._flow.params
            params.hasBoundary = [i >= 0 for i in self._wallIds]
            self._flow.params = params

    def __getattr__(self, name):
        if name in ("gradP", "cellSize"):
            return tuple(float(v) for v in getattr(self._flow.params, name))
        if name == "duplicateThreshold":
            return self._flow.params.duplicateThreshold
        return super().__getattr__(name)

    def triangulate(self, positions, radii, ids: Sequence[int] | None = None, cellSize=None):
        """Build the periodic pore network of spheres (any positions: they are wrapped into the
        cell) in the cell [0, cellSize) (default: the ``cellSize`` attribute). Raises
        RuntimeError when duplicateThreshold is too small for the packing (a pore of the cell
        with no periodic counterpart for a neighbour)."""
        if cellSize is not None:
            self.cellSize = cellSize
        super().triangulate(positions, radii, ids)

    def triangulateScene(self, scene):
        """Build the network of the live spheres of a periodic talus.dem scene (its cell)."""
        if not scene.periodic:
            raise ValueError("PeriodicFlowEngine: the scene is not periodic")
        h = np.asarray(scene.cell.hSize, dtype=float)
        if np.any(h - np.diag(np.diag(h))):
            raise ValueError("PeriodicFlowEngine: only orthorhombic cells (diagonal hSize) are supported")
        ids = [b.id for b in scene.bodies if isinstance(b.shape, Sphere)]
        pos = np.asarray(scene.positions())[ids]
        rad = np.asarray(scene.radii())[ids]
        self.triangulate(pos, rad, ids, cellSize=np.diag(h))

    def samplePermeability(self, lo: int | None = None, hi: int | None = None) -> float:
        """Without arguments: the permeability along ``gradP``, K = −μ ⟨v⟩ · g / |g|² (⟨v⟩ the
        volume-averaged Darcy velocity); with two opposite pressure boundaries, as FlowEngine's."""
        if lo is None and hi is None:
            return self._flow.periodicPermeability()
        return super().samplePermeability(lo, hi)

    def nImages(self) -> int:
        """Periodic images of spheres in the triangulation (Talus addition)."""
        return self._flow.nImages()

    @property
    def throatPeriods(self) -> np.ndarray:
        """(nThroats, 3): how many cells each throat's second pore is shifted from the first."""
        return self._flow.throatPeriods()
