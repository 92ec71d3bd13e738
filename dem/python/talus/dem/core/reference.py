"""Yade's reference configuration of each body: ``state.refPos`` and ``state.refOri``.

Yade gives a body its position and orientation at creation as reference (a clump gets the
origin and no rotation) and never changes them afterwards: scripts set them (``refPos = pos``
once a specimen is ready) and read displacements as ``pos - refPos``. Talus keeps them per body
id beside the scene, as data the physics never reads, and in checkpoints.
"""

from __future__ import annotations

import base64
import json

import numpy as np

_IDENTITY = (1.0, 0.0, 0.0, 0.0)     # (w, x, y, z)


class ReferenceStates:
    """``refPos`` (n, 3) and ``refOri`` (n, 4, as w x y z) of bodies 0 .. n - 1."""

    def __init__(self):
        self.pos = np.zeros((0, 3))
        self.ori = np.zeros((0, 4))

    def ensure(self, count: int):
        """Room for bodies 0 .. count - 1 (new ones: origin, no rotation, as a Yade clump's)."""
        missing = count - len(self.pos)
        if missing > 0:
            self.pos = np.vstack([self.pos, np.zeros((missing, 3))])
            self.ori = np.vstack([self.ori, np.tile(_IDENTITY, (missing, 1))])

    def to_json(self) -> str | None:
        """For a checkpoint (the float64 bytes in base64: exact and compact); None without bodies."""
        if not len(self.pos):
            return None
        return json.dumps({name: base64.b64encode(np.ascontiguousarray(a, dtype="<f8").tobytes()).decode("ascii")
                           for name, a in (("pos", self.pos), ("ori", self.ori))})

    @classmethod
    def from_json(cls, text: str | None) -> "ReferenceStates":
        """What :meth:`to_json` wrote; none kept (a checkpoint of an older Talus): empty."""
        states = cls()
        if text:
            data = json.loads(text)
            states.pos = np.frombuffer(base64.b64decode(data["pos"]), dtype="<f8").reshape(-1, 3).copy()
            states.ori = np.frombuffer(base64.b64decode(data["ori"]), dtype="<f8").reshape(-1, 4).copy()
        return states
