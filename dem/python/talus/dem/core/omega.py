"""The rest of Yade's Omega (``O``) interface: small queries scripts use, and a clear error for
the attributes of Yade's Omega that Talus does not have (setting one would otherwise make a
plain Python attribute that changes nothing, as ``O.dynDt = False`` once did)."""

from __future__ import annotations

import sys

# dir(O) under Yade 2023.02a that Talus does not implement: Yade's multi-scene registry, its
# serialisation to strings, class-registry queries and speed meter.
_YADE_ONLY = frozenset("""addScene bufferFromIntrsct childClassesNonrecursive forceSyncCount intrsctToBytes
    isChildClassOf miscParams plugins sceneToString speed stringToScene switchScene switchToScene tmpToFile
    tmpToString""".split())


class OmegaMethods:
    """Yade's ``O.labeledEngine``, ``O.runEngine``, ``O.dynDtAvailable``, ``O.filename``,
    ``O.thisScene``, ``O.resetThisScene``/``resetCurrentScene``/``resetAllScenes``,
    ``O.exitNoBacktrace``, ``O.disableGdb``: a base class of ``Scene``."""

    def labeledEngine(self, label: str):
        """The engine of O.engines labelled ``label`` (Yade's ValueError if none)."""
        for e in self.engines:
            if getattr(e, "label", "") == label:
                return e
        raise ValueError(f"No engine labeled `{label}'")

    def runEngine(self, engine) -> None:
        """Run ``engine`` once outside a step; time and step count are not advanced (Yade's)."""
        self._cpp.runEngine(engine._cpp)

    @property
    def dynDtAvailable(self) -> bool:
        """Whether O.engines holds a time stepper that O.dynDt could switch on."""
        return any(type(e).__name__ == "GlobalStiffnessTimeStepper" for e in self.engines)

    @property
    def filename(self) -> str | None:
        """The file last saved or loaded (None if none), as Yade's O.filename."""
        from talus.dem.files.io import last_file
        return last_file(self)

    thisScene = 0   # Talus's O is one scene (Yade's index of the current one among its scenes)

    def resetThisScene(self):
        """Yade's name of O.reset() for its current scene."""
        self.reset()

    resetCurrentScene = resetAllScenes = resetThisScene

    @staticmethod
    def exitNoBacktrace(status: int = 0):
        """Leave Python with ``status`` (Yade's exit without a GDB backtrace)."""
        sys.stdout.flush()
        sys.exit(status)

    @staticmethod
    def disableGdb():
        """Yade's switch off its GDB crash handler: Talus has none (Python's own tracebacks)."""

    def __getattr__(self, name):
        if name in _YADE_ONLY:
            raise AttributeError(f"O.{name} is an attribute of Yade 2023.02a's Omega that Talus does not implement")
        raise AttributeError(f"{type(self).__name__!r} object has no attribute {name!r}")

    def __setattr__(self, name, value):
        if name in _YADE_ONLY:
            raise AttributeError(f"O.{name} is an attribute of Yade 2023.02a's Omega that Talus does not implement; "
                                 "setting it would change nothing")
        super().__setattr__(name, value)
