"""A fluid engine's step as the callback of its C++ runner, without keeping the engine alive.

A bound method given to the runner made a reference cycle through C++, which Python's garbage
collector does not see: an engine the script dropped was never freed, nor its pore network and
CHOLMOD factor (hundreds of MB at tens of thousands of spheres). The scene's engine list keeps
an engine in use alive."""
import weakref
from typing import Callable


def step_of(engine, method: str) -> Callable[[], None]:
    """A callable running ``engine.<method>()`` while the engine exists (nothing after)."""
    ref = weakref.ref(engine)

    def step():
        alive = ref()
        if alive is not None:
            getattr(alive, method)()
    return step
