"""Yade's energy tracker: ``O.trackEnergy = True``, then ``O.energy`` (a read-only mapping).

Keys, as in Yade: ``kinetic`` (translational and rotational, computed when read; with
``NewtonIntegrator(kinSplit=True)`` the two parts ``kinTrans`` and ``kinRot`` instead),
``elastPotential`` (stored in the contacts' springs, computed when read), ``gravWork`` (minus the
work of gravity), ``nonviscDamp`` (dissipated by NewtonIntegrator's damping), ``plastDissip``
(friction sliding and plastic moments), ``viscDamp`` (contact dashpots), ``velGradWork`` (minus the
work of the periodic cell's deformation, Yade's PeriTriaxController key, booked for any deforming
cell) and ``kinematicWork`` (minus the work of imposed motions: non-dynamic bodies moved by their
velocity, as the walls of TriaxialStressController or the bodies of kinematic engines, and blocked
DOFs; not in Yade, which does not book it) and ``growthWork`` (minus the energy put in by
``growParticles``, which changes the radii at fixed positions: the contacts' compressions and
stiffnesses and the masses at fixed velocities; not in Yade either). Dissipations are positive; ``O.energy.total()`` is
conserved (it starts at the initial kinetic plus elastic energy). The accumulated terms count from when tracking was switched on (or from
``O.energy.clear()``); they are deterministic and independent of the number of threads.

Under ``mpirun -np N talus run``, every value is the whole scene's on every process (each body and
each contact counted by one process, the processes' shares summed): reading ``O.energy`` is
collective (every process reads it, as a PyRunner does), and the values equal the serial run's
within round-off (the shares are added in another order).
"""

from __future__ import annotations

from collections.abc import Mapping

from talus import _dem

KEYS = ("kinetic", "elastPotential", "gravWork", "nonviscDamp", "plastDissip", "viscDamp", "velGradWork",
        "kinematicWork", "growthWork")
# With NewtonIntegrator(kinSplit=True), as in Yade: the translational and rotational parts instead.
SPLIT_KEYS = ("kinTrans", "kinRot", *KEYS[1:])


class EnergyTracker(Mapping):
    """``O.energy``: ``O.energy['kinetic']``, ``keys()``, ``items()``, ``total()``, ``clear()``;
    ``plot.addData(**O.energy)`` works as in Yade."""

    def __init__(self, scene):
        self._scene = scene

    def _keys(self) -> tuple[str, ...]:
        return SPLIT_KEYS if any(getattr(e, "kinSplit", False) for e in self._scene.engines) else KEYS

    def _values(self) -> dict:
        return _dem.energy(self._scene._cpp, self._keys() is SPLIT_KEYS)

    def __getitem__(self, key: str) -> float:
        values = self._values()
        if key not in values:
            raise KeyError(f"no energy {key!r}; the energies are {', '.join(self._keys())}")
        return values[key]

    def __iter__(self):
        return iter(self._keys())

    def __len__(self) -> int:
        return len(self._keys())

    def keys(self):
        return list(self._keys())

    def items(self):
        values = self._values()
        return [(k, values[k]) for k in self._keys()]

    def total(self) -> float:
        """Sum of every energy (kinetic + elastic + the works + dissipations)."""
        return sum(self._values().values())

    def clear(self):
        """Set the accumulated energies (the works and the dissipations) to zero."""
        _dem.clear_energy(self._scene._cpp)

    def __repr__(self):
        return "EnergyTracker(" + ", ".join(f"{k}={v:.6g}" for k, v in self.items()) + ")"
