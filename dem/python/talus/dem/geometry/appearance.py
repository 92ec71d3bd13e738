"""How bodies look in ParaView: Yade's ``shape.color``, ``shape.highlight``, ``shape.wire``.

Kept per body id by the scene, written to VTK (talus.dem.files.export: the "color" array) and to
checkpoints, and never read by the physics."""

from __future__ import annotations

import json

import numpy as np

DEFAULT_COLOR = (0.5, 0.5, 0.5)


class Appearance:
    """Colour (RGB in [0, 1]), highlight and wire flags of every body, indexed by id."""

    def __init__(self):
        self.color = np.empty((0, 3))
        self.highlight = np.zeros(0, dtype=bool)
        self.wire = np.zeros(0, dtype=bool)

    def ensure(self, count: int):
        """Room for bodies 0 .. count - 1 (new ones get the default look)."""
        missing = count - len(self.highlight)
        if missing > 0:
            self.color = np.vstack([self.color, np.tile(DEFAULT_COLOR, (missing, 1))])
            self.highlight = np.concatenate([self.highlight, np.zeros(missing, dtype=bool)])
            self.wire = np.concatenate([self.wire, np.zeros(missing, dtype=bool)])


    def of(self, ids: np.ndarray, count: int) -> np.ndarray:
        """The colours of bodies ``ids`` of a scene of ``count`` bodies, for VTK output."""
        self.ensure(count)
        return self.color[ids]

    def to_json(self) -> str | None:
        """The appearance for a checkpoint; None when every body has the default look."""
        if (self.color == DEFAULT_COLOR).all() and not self.highlight.any() and not self.wire.any():
            return None
        return json.dumps({"color": self.color.tolist(), "highlight": np.flatnonzero(self.highlight).tolist(),
                           "wire": np.flatnonzero(self.wire).tolist()})

    @classmethod
    def from_json(cls, text: str | None) -> "Appearance":
        """The appearance a checkpoint kept (:meth:`to_json`); the default look when it kept none."""
        look = cls()
        if text:
            data = json.loads(text)
            look.ensure(len(data["color"]))
            look.color[:] = np.asarray(data["color"], dtype=float).reshape(-1, 3)
            look.highlight[data["highlight"]] = True
            look.wire[data["wire"]] = True
        return look


def check_color(value) -> tuple[float, float, float]:
    rgb = np.asarray(value, dtype=float).reshape(-1)
    if rgb.shape != (3,) or not np.all(np.isfinite(rgb)):
        raise ValueError(f"color must be 3 finite numbers (red, green, blue in [0, 1]), got {value!r}")
    return tuple(float(c) for c in rgb)
