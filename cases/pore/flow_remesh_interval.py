"""Pore-scale flow case: what the remeshing interval costs in accuracy and saves in time, on the
consolidating oedometer of flow_terzaghi.py.

Run:      build/bin/talus run cases/pore/flow_remesh_interval.py [--quick] [--results DIR]
Set-up:   the compacted 400-sphere oedometer of cases/pore/flow_terzaghi.py (quick and full alike), the
          same 1 kPa load step with the incompressible pore flow, run with meshUpdateInterval
          1 (the reference: remeshing every step), 5, 20, 100, 400 (quick: 1, 10, 100, 400) and
          defTolerance off, from the same saved state, over 1.5 consolidation times; and once
          with background remeshing (multithread, interval 5 with backgroundSteps 5; full:
          interval 10 with backgroundSteps 10): a new mesh every 10 (20) steps like the
          synchronous interval 10 (20), each arriving 5 (10) steps after its positions.
Checked:  the mean excess pore pressure and the settlement against the every-step reference:
          worst relative difference (of the load, resp. of the final settlement) over the run;
          record flow.remesh-interval: the pressure difference at interval 100 (bound 0.05 —
          Yade's default interval is 1000 steps, the packing barely moves between remeshes
          here), with all intervals, errors and wall times in the record.
Produces: flow.remesh-interval.png (error against wall time, one point per interval).
"""
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import flow_terzaghi as terzaghi  # noqa: E402  (the oedometer set-up)

from talus import results  # noqa: E402
from talus.dem import O, GlobalStiffnessTimeStepper  # noqa: E402
from talus.flow import FlowEngine  # noqa: E402


def name(run):
    lag = "" if run["background"] is None else f", background {run['background']} steps"
    return f"interval {run['interval']:4d}{lag}"


def main():
    args = results.case_arguments(__doc__).parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    case = results.Case("flow.remesh-interval", quick=args.quick, folder=args.results)
    # (meshUpdateInterval, backgroundSteps or None for synchronous remeshing)
    configs = ([(1, None), (10, None), (100, None), (400, None), (5, 5)] if args.quick
               else [(1, None), (5, None), (20, None), (100, None), (400, None), (10, 10)])
    tc = 0.6
    terzaghi.compacted_sample(400, seed=1)
    O.engines = [e for e in O.engines if not isinstance(e, GlobalStiffnessTimeStepper)]
    height = terzaghi.top() - terzaghi.bottom()
    O.saveTmp("oedometer")
    k = terzaghi.permeability()
    mu = k * tc / (height ** 2 * 2.5e-6)   # m_v of the packing (E_oed ~ 4e5 Pa, flow_terzaghi.py)
    steps = int(round(1.5 * tc / O.dt))
    runs = []
    for interval, lag in configs:
        O.loadTmp("oedometer", engines="current")
        flow = FlowEngine(bndCondIsPressure=[0, 0, 0, 1, 0, 0], bndCondValue=[0] * 6, boundaryUseMaxMin=[0] * 6,
                          wallIds=terzaghi.WALLS, viscosity=mu, meshUpdateInterval=interval, defTolerance=0,
                          multithread=lag is not None, backgroundSteps=lag or 0)
        # loadTmp(engines="current") keeps the engine list: drop the previous run's flow engine
        engines = [e for e in O.engines if not isinstance(e, FlowEngine)]
        engines.insert(3, flow)
        O.engines = engines
        start = time.perf_counter()
        series = terzaghi.load_step(steps, 10, flow)
        wall = time.perf_counter() - start
        runs.append(dict(interval=interval, background=lag, wall_s=wall, p=series["p"], s=series["s"],
                         remeshes=flow.remeshCount()[0]))
        print(f"{name(runs[-1])}: {wall:6.1f} s, {runs[-1]['remeshes']} remeshes")
    ref = runs[0]
    for r in runs:
        r["p_err"] = float(np.max(np.abs(r["p"] - ref["p"])) / abs(terzaghi.DSIGMA))
        r["s_err"] = float(np.max(np.abs(r["s"] - ref["s"])) / abs(ref["s"][-1]))
        print(f"{name(r)}: pressure difference {r['p_err']:.2e} of the load, "
              f"settlement difference {r['s_err']:.2e} of the final settlement")
    at100 = next(r for r in runs if r["interval"] == 100 and r["background"] is None)
    table = [{k: v for k, v in r.items() if k not in ("p", "s")} for r in runs]
    case.record("worst difference of the mean excess pore pressure from remeshing every step, interval 100 "
                "(fraction of the load)", at100["p_err"], "the same run remeshing every step", 0.05,
                intervals=table, steps=steps)

    fig, ax = plt.subplots(figsize=(5.5, 4))
    synchronous = [r for r in runs[1:] if r["background"] is None]
    background = [r for r in runs if r["background"] is not None]
    for key, label, color in (("p_err", "mean pore pressure / load", "C0"),
                              ("s_err", "settlement / final settlement", "C1")):
        ax.loglog([r["wall_s"] for r in synchronous], [max(r[key], 1e-16) for r in synchronous], "o-", color=color,
                  label=label)
        ax.loglog([r["wall_s"] for r in background], [max(r[key], 1e-16) for r in background], "s", color=color,
                  mfc="none", label=label + ", background remeshing")
    for r in runs[1:]:
        ax.annotate(str(r["interval"]) + ("" if r["background"] is None else f"+{r['background']}"),
                    (r["wall_s"], max(r["p_err"], 1e-16)), fontsize=8)
    ax.axvline(ref["wall_s"], color="gray", ls=":", label="remeshing every step")
    ax.set_xlabel("wall time of the coupled run (s)")
    ax.set_ylabel("worst difference from remeshing every step")
    ax.set_title("Remeshing interval: error against cost")
    ax.legend(fontsize=8)
    case.save_chart(fig)


if __name__ == "__main__":
    main()
