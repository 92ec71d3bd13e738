"""Where the time of a run goes, engine by engine (Yade's ``yade.timing``)::

    O.timingEnabled = True
    O.run(1000, True)
    from talus.dem import timing
    timing.stats()   # table: engine, calls, time, share of the step; labelled stages indented
    timing.reset()

Only the time spent while ``O.timingEnabled`` is on is counted. Engines that label stages (the
collider: skin check and the stages of a re-detection — binning, sphere pairs, boundary pairs,
sort, merge with the previous contacts, per-body index; the interaction loop: geometry/physics/law, forces per body)
show them below their own line, as Yade's timingDeltas.

Under mpirun the table is this process's, followed by the load of every process (collective:
every process calls ``stats()``, as a script written for one process does): its spheres, ghosts,
contacts and compute seconds (CPU seconds not spent waiting in MPI calls, between re-detections),
the imbalance (the slowest process's compute seconds over the mean) and the rebalances it set off
(``talus.dem.distributed.rebalanceThreshold``).
"""

from __future__ import annotations

from talus.dem.core.scenes import default_scene

__all__ = ["rows", "stats", "runtime", "reset"]


def _scene(scene):
    return default_scene() if scene is None else scene


def rows(scene=None) -> list[dict]:
    """One dict per engine (name, label, count, nsec) with its stages (a list of dicts)."""
    out = []
    for engine in _scene(scene).engines:
        stages = [{"name": label, "count": count, "nsec": nsec} for label, nsec, count in engine.timingDeltas.data]
        out.append({"name": type(engine).__name__, "label": engine.label, "count": engine.execCount,
                    "nsec": engine.execTime, "stages": stages})
    return out


def stats(scene=None, file=None) -> str:
    """Print (and return) the table of time per engine and per labelled stage."""
    table = rows(scene)
    total = sum(r["nsec"] for r in table) or 1
    lines = [f"{'Name':<44}{'Count':>10}{'Time':>16}{'Rel. time':>12}", "-" * 82]
    for r in table:
        name = r["name"] + (f" ({r['label']})" if r["label"] else "")
        lines.append(f"{name:<44}{r['count']:>10}{r['nsec'] / 1000:>14.0f}us{100 * r['nsec'] / total:>11.2f}%")
        own = r["nsec"] or 1
        for s in r["stages"]:
            lines.append(f"  {s['name']:<42}{s['count']:>10}{s['nsec'] / 1000:>14.0f}us{100 * s['nsec'] / own:>11.2f}%")
    lines += ["-" * 82, f"{'TOTAL':<44}{'':>10}{total / 1000:>14.0f}us{100.0:>11.2f}%"]
    lines += _load_lines(_scene(scene))
    text = "\n".join(lines)
    print(text, file=file)
    return text


def _load_lines(scene) -> list[str]:
    """Under mpirun, every process's load and the rebalances (collective); nothing in one process."""
    from talus.dem import distributed
    b = distributed.balance(scene)
    if not b:
        return []
    lines = ["", f"{'Process':<10}{'spheres':>12}{'ghosts':>12}{'contacts':>12}{'compute time':>18}", "-" * 64]
    for rank, p in enumerate(b["processes"]):
        lines.append(f"{rank:<10}{p['spheres']:>12}{p['ghosts']:>12}{p['contacts']:>12}"
                     f"{p['compute_seconds'] * 1e6:>16.0f}us")
    threshold = "never" if b["threshold"] == float("inf") else f"above {b['threshold']:g}"
    lines.append(f"imbalance {b['imbalance']:.3f} (slowest process's compute time over the mean, over the "
                 f"{len(b['intervals'])} re-detections measured); rebalances: {b['rebalances']} ({threshold})")
    if b["rebalances"]:
        after = f"{b['imbalance_after']:.3f}" if b["imbalance_after"] else "not measured yet"
        lines.append(f"last rebalance: imbalance {b['imbalance_before']:.3f} before, {after} after")
    return lines


def runtime(scene=None) -> int:
    """The engines' total time in nanoseconds (the last line of stats(); Yade's timing.runtime)."""
    return sum(engine.execTime for engine in _scene(scene).engines)


def reset(scene=None) -> None:
    """Zero every engine's time, count and stages."""
    for engine in _scene(scene).engines:
        engine.execTime = 0
        engine.execCount = 0
        engine.timingDeltas.reset()
