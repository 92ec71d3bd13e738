"""``yade.plot``: time series and their charts (talus.plot). ``from yade import plot`` gives
the very module ``talus.plot``, so ``plot.data``, ``plot.plots`` and ``plot.labels`` are shared
with every other user of it."""

import sys

import talus.plot

sys.modules[__name__] = talus.plot
