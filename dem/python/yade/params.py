"""``yade.params``: the parameters of a batch job (``from yade.params.table import *``), read by
``readParamsFromTable`` (talus.batch)."""

import sys

import talus.batch

sys.modules[__name__] = talus.batch.params
