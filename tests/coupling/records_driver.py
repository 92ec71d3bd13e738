"""Run under `mpirun -np 2`: coupling records handed between two processes as their particles
change process (test_foam_mpi.py). Process 0 starts with particles 0, 1, 2 and process 1
with 3, 4 (each record: the id times 10, 100, ...); then 2 and 4 change sides, 5 is new. Writes
the records each process holds afterwards to <folder>/records-<rank>.json (argument: the folder)."""
import json
import sys
from pathlib import Path

import numpy as np

from talus.coupling.foam import _module

m = _module()
from talus import _distributed  # noqa: E402  (MPI set up as talus run does)

rank, _ = _distributed.init()
records = m.ParticleRecords(2)
mine = [0, 1, 2] if rank == 0 else [3, 4]
records.store(np.array(mine), np.array([[10.0 * i, 100.0 * i] for i in mine]))
now = [0, 1, 4] if rank == 0 else [2, 3, 5]
records.hand_over(np.array(now))
(Path(sys.argv[1]) / f"records-{rank}.json").write_text(
    json.dumps({"values": records.values.tolist(), "sent": records.lastSent}))
_distributed.finalize()
