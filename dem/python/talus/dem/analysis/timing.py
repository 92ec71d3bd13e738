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
"""

from __future__ import annotations

from talus.dem.core.scenes import default_scene

__all__ = ["rows", "stats", "reset"]


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
    text = "\n".join(lines)
    print(text, file=file)
    return text


def reset(scene=None) -> None:
    """Zero every engine's time, count and stages."""
    for engine in _scene(scene).engines:
        engine.execTime = 0
        engine.execCount = 0
        engine.timingDeltas.reset()
