"""Yade's older spellings of the interaction loop, which Yade 2023 still runs:

* ``ElasticContactLaw()``: an engine applying Law2_ScGeom_FrictPhys_CundallStrack to every
  contact, after an ``IGeomDispatcher`` and an ``IPhysDispatcher`` in O.engines (the three
  stand for one InteractionLoop, see :func:`talus.dem.step.engines.collapseDispatchers`);
* ``InteractionGeometryDispatcher``, ``InteractionPhysicsDispatcher``,
  ``InteractionDispatchers``: Yade's deprecated names of ``IGeomDispatcher``,
  ``IPhysDispatcher`` and ``InteractionLoop``, with Yade's DeprecationWarning.
"""

from __future__ import annotations

import warnings

from talus.dem.step.engines import (IGeomDispatcher, InteractionLoop, IPhysDispatcher, LawDispatcher,
                               Law2_ScGeom_FrictPhys_CundallStrack)


class ElasticContactLaw(LawDispatcher):
    """Yade's ElasticContactLaw: Law2_ScGeom_FrictPhys_CundallStrack on every contact, as an
    engine of its own. In O.engines it completes the ``IGeomDispatcher``, ``IPhysDispatcher``
    before it into one InteractionLoop; engines between them (Yade's examples put
    RotationEngines there) then run after the contact forces instead of before: they set
    velocities, which the law does not read, so the forces are Yade's."""

    def __init__(self, neverErase: bool = False, label: str = ""):
        if neverErase:
            raise ValueError("ElasticContactLaw: neverErase=True (keeping separated contacts for another law) "
                             "is not implemented; Talus erases a contact once its spheres separate")
        super().__init__([Law2_ScGeom_FrictPhys_CundallStrack()], label=label)
        self.neverErase = False


def _renamed(old: str, new):
    def make(*args, **kwargs):
        warnings.warn(f"Class `{old}' was renamed to (or replaced by) `{new.__name__}', update your code!",
                      DeprecationWarning, stacklevel=2)
        return new(*args, **kwargs)
    make.__name__ = make.__qualname__ = old
    make.__doc__ = f"Yade's deprecated name of {new.__name__}."
    return make


InteractionGeometryDispatcher = _renamed("InteractionGeometryDispatcher", IGeomDispatcher)
InteractionPhysicsDispatcher = _renamed("InteractionPhysicsDispatcher", IPhysDispatcher)
InteractionDispatchers = _renamed("InteractionDispatchers", InteractionLoop)

__all__ = ["ElasticContactLaw", "InteractionGeometryDispatcher", "InteractionPhysicsDispatcher",
           "InteractionDispatchers"]
