"""What a script sees of a scene split over the processes (``mpirun -np N talus run``): every
body (``bodies``: ``for b in O.bodies``, the bodies owned elsewhere as snapshots) and every
contact (``contacts``: ``O.interactions``) of the whole scene, collectively on every process, and
a process's share of the per-body arrays (``shares``: the rows of the script's ids, sums over
the processes, what runs once). The split itself is talus.dem.distributed's."""
