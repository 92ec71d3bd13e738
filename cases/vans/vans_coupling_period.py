"""VANS case: accuracy against cost of the two-way coupling, over the coupling period and the
fluid time step ("speed and accuracy together").

Run:      OMP_NUM_THREADS=1 build/bin/talus run cases/vans/vans_coupling_period.py [--quick] [--results DIR]
Set-up:   the sediment-transport scene of cases/vans/vans_sediment_transport.py, deposited for 0.3 s
          (deterministic: every run starts from the same state), the fluid initialised for 1 s,
          then a coupled window of W seconds (quick 0.3 s, full 1 s) with coupling period
          1e-3 ... 1e-1 s at fluid step 1e-5 s, and fluid steps 1e-4 and 2e-6 s at the 1e-2 s
          period (full mode only for 2e-6 s). The transport rate is measured every 1e-2 s with the
          standalone measurement (HydroForceEngine.measure, which does not touch the coupling),
          after a 0.1 s start-up (the fluid in the bed, free during the drag-free initial
          resolution as in Yade's example, is slowed by the drag over a few tens of ms; the
          couplings of the start-up are also exempt from the run-time check).
Checked:  the window-averaged transport rate against the finest coupling (period 1e-3 s, fluid
          step 1e-5 s): relative error of each configuration, with the wall time of the window;
          the run-time detection (VansCoupling's warning when the fluid velocity changes by more
          than 10 % between two couplings, after the start-up coupling) must fire for the longest
          period (1e-1 s) and not for the reference: record vans.coupling-period (1 if both hold).
          The error of the seed's default (1e-2 s, 1e-5 s) is recorded as an extra.
Produces: record vans.coupling-period; chart vans.coupling-period.png (transport-rate error
          against wall time, each point labelled with its period and fluid step; the
          configurations the run-time check flagged are marked).
"""
import time
import warnings

import numpy as np

from talus import results

import vans_sediment_transport as st

STARTUP = 0.1   # s of the coupled window left out (start-up of the coupling)


def run(period: float, dt_fluid: float, window: float) -> dict:
    s, hydro, newton, mobile = st.build()
    s.run(round(0.3 / s.dt))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)      # taufsi caps at start-up
        st.start_fluid(hydro, newton, dt_fluid)
    # The start-up (the fluid in the bed, free during the drag-free initial resolution, is slowed
    # over a few tens of milliseconds) is excluded from the check and from the measurement.
    warmup = max(1, round(STARTUP / period))
    coupling = st.VansCoupling(hydro, period, dt_fluid, densPart=st.RHO_P, diameterPart=st.D, changeLimit=0.1,
                               warmup=warmup)
    coupling.attach()
    chunk = round(1e-2 / s.dt)
    rates = []
    scale = (st.RHO_P / st.RHO_F - 1) * abs(st.GRAVITY[2]) * st.D ** 3
    start = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)      # counted in coupling.warned
        for k in range(round(window / 1e-2)):
            s.run(chunk)
            if (k + 1) * 1e-2 > STARTUP + 1e-9:
                p = hydro.measure()
                rates.append(float(np.sum(p["phiPart"] * p["vxPart"]) * hydro.deltaZ / np.sqrt(scale)))
    wall = time.perf_counter() - start
    return dict(period=period, dt_fluid=dt_fluid, qs=float(np.mean(rates)), wall=wall, warned=coupling.warned,
                max_change=float(max(coupling.series["fluidChange"][warmup:] or [0.0])))


def main():
    args = results.case_arguments(__doc__).parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    case = results.Case("vans.coupling-period", quick=args.quick, folder=args.results)
    window = 0.3 if args.quick else 1.0
    configs = [(1e-3, 1e-5), (1e-2, 1e-5), (1e-1, 1e-5), (1e-2, 1e-4)]
    if not args.quick:
        configs[2:2] = [(3e-3, 1e-5), (3e-2, 1e-5)]
        configs.append((1e-2, 2e-6))
    runs = []
    for period, dtf in configs:
        r = run(period, dtf, window)
        runs.append(r)
        print(f"period {period:g} s, fluid dt {dtf:g} s: qs* = {r['qs']:.5f}, wall {r['wall']:.1f} s, "
              f"max fluid change {r['max_change']:.3f}, warnings {r['warned']}")
    ref = runs[0]["qs"]
    for r in runs:
        r["error"] = abs(r["qs"] - ref) / abs(ref) if ref else float("nan")
    longest = next(r for r in runs if r["period"] == 1e-1)
    detected = longest["warned"] > 0 and runs[0]["warned"] == 0
    default = next(r for r in runs if r["period"] == 1e-2 and r["dt_fluid"] == 1e-5)
    case.record("run-time detection: warned at period 0.1 s and not at 1e-3 s (1 = yes)", float(detected),
                "VansCoupling fluid-change check, limit 10 %", 1.0, comparison=">=", runs=runs,
                window_s=window, default_error=default["error"])
    print(f"reference qs* {ref:.5f}; default (1e-2 s, 1e-5 s) error {default['error']:.3f}; "
          f"detection {'ok' if detected else 'FAILED'}")

    fig, ax = plt.subplots(figsize=(6, 4.5))
    for r in runs[1:]:
        marker = "s" if r["dt_fluid"] != 1e-5 else "o"
        color = "red" if r["warned"] else "blue"
        ax.loglog(r["wall"], max(r["error"], 1e-4), marker, color=color)
        ax.annotate(f"T={r['period']:g}, dt={r['dt_fluid']:g}", (r["wall"], max(r["error"], 1e-4)),
                    textcoords="offset points", xytext=(4, 2), fontsize=7)
    ax.axvline(runs[0]["wall"], color="gray", ls="--", lw=0.8, label="reference (T=1e-3 s) wall time")
    ax.set_xlabel(f"wall time of the {window:g} s coupled window (s)")
    ax.set_ylabel("relative error of the mean transport rate")
    ax.set_title("Coupling period / fluid step: error vs cost (red: run-time warning)")
    ax.legend(fontsize=7)
    case.save_chart(fig)


if __name__ == "__main__":
    main()
