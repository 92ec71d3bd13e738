"""VANS case: two-way coupled bedload against the experiments of Frey (2014), as in Maurin et al. (2015).

Run:      OMP_NUM_THREADS=1 build/bin/talus run cases/vans/vans_frey_experiments.py [--quick] [--results DIR]
Data:     Frey (2014) experiments 6, 14, 20 (time-averaged solid fraction and particle velocity
          profiles in a quasi-2D flume), as shipped with Debian's yade in
          examples/FluidCouplingVANS1D/twoWayCoupling/shapeVariation/data-exp/Frey2014_EXP*.py
          (z in grain diameters above the ground, phi, vx in m/s). The case skips an experiment
          whose data file is missing.
Set-up:   that folder's case-exp*/params.py and common/*.py (Maurin et al. 2015): 6 mm spheres,
          rho_p 2500 kg/m^3, visco-elastic contacts (restitution 0.5, friction tan 0.4, normal
          stiffness in the rigid limit 1e4 x the static bed pressure x d), channel 6.5 mm wide
          (two walls at +-w/2 in a periodic cell 4 w wide; a wall meets the spheres, not their
          periodic images), slope 0.1, periodic along the flow; rough bed of fixed spheres (one
          per d, heights random within +-d/2 around the ground); mobile sediment height
          hs = 7.08 / 7.37 / 7.30 d, fluid + sediment height 5.3 / 5.7 / 5.9 cm for exp 6 / 14 / 20;
          water rho 1000, nu 1e-6; Dallavalle drag with Richardson-Zaki exponent 3.1; 301 fluid
          layers over the flow depth; side-wall friction (channel width w); turbulent velocity
          fluctuations as in both of Yade's scripts for these experiments (validations/
          DEMCoupling/Maurinetal2015/validMaurin2015.py and shapeVariation's
          computeTurbulentFluctuations): Yade's turbulentFluctuation() redraws every grain's
          fluctuation at once every eddy turnover time (water depth above the bed / mean fluid
          velocity there), the bed being the first layer from the top above phi = 0.5, starting
          0.5 s after the fluid (--fluctuations zdep: per-grain lives 0.33 kappa z / u* instead,
          Yade's velFluct / turbulentFluctuationZDep). Yade's shapeVariation example uses
          turbulence model 3, which only exists in a modified Yade; Maurin et al. (2015) used the
          Li-Sawamoto mixing length with phiMax 0.51 (the bed's solid fraction in this quasi-2D
          channel), as here. Gravity deposition (damping 0.2, no fluid), a 1 s fluid resolution
          (shapeVariation's start-up), then DEM and fluid alternate every 1e-2 s (fluid step
          1e-5 s). The grains start from a jittered lattice with a seed. Not as in Yade's
          scripts: the channel is 20 d (quick) or 60 d (full) long instead of 1000 d, and the
          average is over 1.5 s (quick) or 10 s (full) instead of 30-100 s.
Checked:  per experiment, the profiles averaged over the second half of the transport against the
          data at the data's elevations: RMS error of the solid fraction and of the particle
          velocity (<phi vx>/<phi>, where the simulated phi > 0.01) divided by the range of the
          data, and the relative error of the transport rate integral phi vx dz (over the data's
          elevations). Tolerance 0.2: Maurin et al. (2015) reproduce these profiles to about
          10-20 % (their Fig. 6-8); the values are recorded, not tuned.
          Quick: experiment 6 only, 20 d long, 0.3 s deposition and 3 s of transport; full:
          the three experiments, 60 d long, 0.4 s and 20 s.
          --experiments 6 14 20, --transport SECONDS, --length D and --seed N override the mode's choice.
Produces: records vans.frey-experiments.exp<N>.phi, .vx, .transport; chart
          vans.frey-experiments.png (simulated and measured profiles, one column per experiment).
"""
import math
import os
import random
import time

import numpy as np

from talus import results
from talus.dem import PyRunner, Scene, ViscElMat, sphere, wall
from talus.flow import HydroForceEngine, VansCoupling

from vans_sediment_transport import engines, start_fluid   # the engines and the fluid's start as in Yade's example

DATA = "/usr/share/doc/yade/examples/FluidCouplingVANS1D/twoWayCoupling/shapeVariation/data-exp"
D, RHO_P, EN, FRICTION = 6e-3, 2500.0, 0.5, math.atan(0.4)
PHI_MAX = 0.51
RHO_F, NU, SLOPE = 1000.0, 1e-6, 0.1
DT_FLUID, PERIOD, N_CELL = 1e-5, 1e-2, 301
W = 6.5 / 6 * D                      # channel width
CELL_WIDTH = 4 * W
GRAVITY = (9.81 * math.sin(SLOPE), 0.0, -9.81 * math.cos(SLOPE))
# experiment: (mobile sediment height / d, fluid + sediment height [m])
EXPERIMENTS = {6: (7.08, 5.3e-2), 14: (7.37, 5.7e-2), 20: (7.30, 5.9e-2)}
TOLERANCE = 0.2


def load_data(exp: int) -> dict | None:
    path = os.path.join(DATA, f"Frey2014_EXP{exp}.py")
    if not os.path.exists(path):
        return None
    data = {}
    with open(path) as f:
        exec(compile(f.read(), path, "exec"), {"data": data})   # the file fills the dict `data`
    return {k: np.asarray(data[k], dtype=float) for k in ("z", "phi", "vx")}


def material(hs: float) -> ViscElMat:
    """Yade's set-up: contact kn in the rigid limit from the static pressure at the bottom of the
    sediment; per-material spring and dashpot whose series (two equal grains) give that kn and
    the restitution EN."""
    layers = hs / D * math.pi * D / (6 * PHI_MAX * W)   # Yade's n_l for one grain per d along x
    max_pressure = (RHO_P - RHO_F) * PHI_MAX * layers * D * abs(GRAVITY[2])
    kn_contact = max_pressure * D * 1e4 / 2
    mass = RHO_P * math.pi / 6 * D ** 3
    ln = math.log(EN)
    cn_contact = -2 * math.sqrt(kn_contact * mass / 2) * ln / math.sqrt(math.pi ** 2 + ln ** 2)
    return ViscElMat(kn=2 * kn_contact, cn=2 * cn_contact, ks=kn_contact, cs=0.0, density=RHO_P,
                     frictionAngle=FRICTION)


class TurnoverFluctuations:
    """Maurin et al. (2015)'s fluctuations, as Yade's validMaurin2015.py (and shapeVariation's
    computeTurbulentFluctuations): every grain's fluctuation is redrawn at once
    (HydroForceEngine.turbulentFluctuation, Yade's discrete random walk) every eddy turnover time,
    the water depth above the bed over the mean fluid velocity there, and kept in between. The
    bed is the first layer from the top whose solid fraction exceeds 0.5 and still rises
    downwards; grains below it get no fluctuation. Starts `delay` after the fluid (0.5 s in
    Yade's script, for stability)."""

    def __init__(self, hydro, scene, delay: float = 0.5):
        self.hydro, self.scene = hydro, scene
        self.next = scene.time + delay
        self.refreshes = 0

    def __call__(self):
        if self.scene.time < self.next:
            return
        phi = self.hydro.phiPart
        bed = next((k for k in range(len(phi) - 1, 0, -1) if phi[k] < phi[k - 1] and phi[k] > 0.5), None)
        velocity = float(np.mean(self.hydro.vxFluid[bed:])) if bed is not None else 0.0
        if bed is None or not velocity > 0:
            self.next = self.scene.time + PERIOD       # no bed found yet: look again at the next coupling
            return
        self.hydro.bedElevation = bed * self.hydro.deltaZ
        self.hydro.turbulentFluctuation()
        self.refreshes += 1
        self.next = self.scene.time + (len(phi) - 1 - bed) * self.hydro.deltaZ / velocity


def build(length_d: int, hs_d: float, depth: float, seed: int = 1, fluctuations: str = "turnover"):
    rnd = random.Random(seed)
    length = length_d * D
    height = 5 * depth
    ground = height / 2
    yc = CELL_WIDTH / 2
    s = Scene()
    s.periodic = True
    s.cell.setBox(length, CELL_WIDTH, height)
    s.materials.append(material(hs_d * D))
    s.bodies.append(wall(yc - W / 2, axis=1))
    s.bodies.append(wall(yc + W / 2, axis=1))
    for i in range(length_d):                           # the rough bed: fixed grains
        s.bodies.append(sphere(((i + 0.5) * D, yc - W / 2 + D / 2, ground + (-0.5 + rnd.random()) * D), D / 2,
                               fixed=True))
    count = round(length_d * hs_d)                      # Yade: n = l/d * hs/d
    per_row = int(length / (1.05 * D))
    step = length / per_row
    mobile = []
    for k in range(count):
        layer, i = divmod(k, per_row)
        centre = ((i + 0.5) * step + 0.2e-3 * (rnd.random() - 0.5), yc + 0.4e-3 * (rnd.random() - 0.5),
                  ground + 1.5 * D + 1.1 * D * layer)
        mobile.append(s.bodies.append(sphere(centre, D / 2)))
    dz = depth / (N_CELL - 1)
    hydro = HydroForceEngine(densFluid=RHO_F, viscoDyn=NU * RHO_F, zRef=ground, gravity=GRAVITY, deltaZ=dz,
                             expoRZ=3.1, lift=False, nCell=N_CELL, vCell=length * W * dz, radiusPart=D / 2,
                             phiMax=PHI_MAX, ilm=2, fluidWallFriction=True, channelWidth=W,
                             velFluct=fluctuations == "zdep", bedElevation=hs_d * D, seed=seed, ignoreOutside=True,
                             ids=mobile, scene=s,
                             dead=True)   # a grain leaping out of the water gets no fluid force, as in Yade
    return s, hydro, engines(s, hydro, GRAVITY), mobile


def run_experiment(exp: int, length_d: int, deposition: float, transport: float, seed: int,
                   fluctuations: str = "turnover") -> dict:
    hs_d, depth = EXPERIMENTS[exp]
    s, hydro, newton, mobile = build(length_d, hs_d, depth, seed, fluctuations)
    start = time.perf_counter()
    s.run(round(deposition / s.dt))
    start_fluid(hydro, newton, DT_FLUID)
    coupling = VansCoupling(hydro, PERIOD, DT_FLUID, densPart=RHO_P, diameterPart=D)
    coupling.attach()
    refresh = None
    if fluctuations == "turnover":
        refresh = TurnoverFluctuations(hydro, s)
        s.engines = list(s.engines) + [PyRunner(refresh, iterPeriod=max(1, round(1e-3 / s.dt)))]
    chunk = round(PERIOD / s.dt)
    t0 = s.time
    phi, phivx = [], []
    while s.time < t0 + transport - 0.5 * s.dt:
        s.run(chunk)
        if s.time - t0 > transport / 2:
            phi.append(hydro.phiPart)
            phivx.append(hydro.vxPart * hydro.phiPart)
    wall_s = time.perf_counter() - start
    phi_mean = np.mean(phi, axis=0)
    phivx_mean = np.mean(phivx, axis=0)
    zc = (np.arange(N_CELL) + 0.5) * hydro.deltaZ / D
    t = np.array(coupling.series["time"]) - t0
    qs = np.array(coupling.series["transportRate"])
    return {"z": zc, "phi": phi_mean, "phivx": phivx_mean, "wall_s": wall_s, "grains": len(mobile),
            "qs_star": float(np.mean(qs[t > transport / 2])),
            "shields": float(np.mean(np.array(coupling.series["shieldsNumber"])[t > transport / 2])),
            "refreshes": refresh.refreshes if refresh else None}


def compare(sim: dict, data: dict) -> dict:
    z = data["z"]
    phi = np.interp(z, sim["z"], sim["phi"])
    phivx = np.interp(z, sim["z"], sim["phivx"])
    phi_err = float(np.sqrt(np.mean((phi - data["phi"]) ** 2)) / np.ptp(data["phi"]))
    ok = phi > 0.01
    vx = np.where(ok, phivx / np.maximum(phi, 1e-12), np.nan)
    vx_err = float(np.sqrt(np.mean((vx[ok] - data["vx"][ok]) ** 2)) / np.ptp(data["vx"]))
    q_sim = float(np.trapz(phivx, z * D))
    q_exp = float(np.trapz(data["phi"] * data["vx"], z * D))
    return {"phi_err": phi_err, "vx_err": vx_err, "q_sim": q_sim, "q_exp": q_exp,
            "q_err": abs(q_sim - q_exp) / q_exp, "vx_points": int(ok.sum()), "points": len(z)}


def main():
    parser = results.case_arguments(__doc__)
    parser.add_argument("--experiments", type=int, nargs="+", choices=sorted(EXPERIMENTS),
                        help="experiments to run (default: 6 in quick mode, all in full mode)")
    parser.add_argument("--transport", type=float, help="seconds of coupled transport (overrides the mode's)")
    parser.add_argument("--length", type=int, help="periodic length in grain diameters (overrides the mode's)")
    parser.add_argument("--seed", type=int, default=1, help="seed of the rough bed and the initial lattice")
    parser.add_argument("--fluctuations", choices=("turnover", "zdep"), default="turnover",
                        help="turbulent fluctuations: redrawn for all grains every eddy turnover time (Maurin et "
                             "al. 2015, Yade's validMaurin2015.py; default) or per grain on its z-dependent eddy "
                             "life (Yade's turbulentFluctuationZDep, velFluct=True)")
    args = parser.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    case = results.Case("vans.frey-experiments", quick=args.quick, folder=args.results)
    if args.quick:
        experiments, length_d, deposition, transport = (6,), 20, 0.3, 3.0
    else:
        experiments, length_d, deposition, transport = (6, 14, 20), 60, 0.4, 20.0
    experiments = args.experiments or experiments
    transport = args.transport or transport
    length_d = args.length or length_d
    available = {exp: load_data(exp) for exp in experiments}
    available = {exp: data for exp, data in available.items() if data is not None}
    if not available:
        print(f"no Frey (2014) data under {DATA} (Debian's yade package): nothing to compare")
        return
    fig, axes = plt.subplots(2, len(available), figsize=(3.2 * len(available) + 0.5, 7), squeeze=False)
    for col, (exp, data) in enumerate(sorted(available.items())):
        sim = run_experiment(exp, length_d, deposition, transport, args.seed, args.fluctuations)
        c = compare(sim, data)
        print(f"exp {exp}: {sim['grains']} grains, {sim['wall_s']:.0f} s wall; RMS error / data range: "
              f"phi {c['phi_err']:.3f}, vx {c['vx_err']:.3f} ({c['vx_points']} of {c['points']} points); "
              f"transport rate {c['q_sim']:.3e} vs {c['q_exp']:.3e} m^2/s ({c['q_err']:.1%}); "
              f"qs* {sim['qs_star']:.4f}, Shields {sim['shields']:.3f}; fluctuations {args.fluctuations}"
              + (f" ({sim['refreshes']} turnover refreshes)" if sim["refreshes"] is not None else ""))
        common = dict(experiment=exp, seed=args.seed, length_d=length_d, transport_s=transport, deposition_s=deposition,
                      grains=sim["grains"], wall_run_s=sim["wall_s"], shields_mean=sim["shields"],
                      qs_star_mean=sim["qs_star"], phi_max=PHI_MAX, fluctuations=args.fluctuations, averaged="second half of the transport")
        ref = "Frey (2014) data; Maurin et al. (2015) reach about 10-20 %"
        case.record("RMS error of the solid fraction profile / data range", c["phi_err"], ref, TOLERANCE,
                    suffix=f"exp{exp}.phi", points=c["points"], **common)
        case.record("RMS error of the particle velocity profile / data range", c["vx_err"], ref, TOLERANCE,
                    suffix=f"exp{exp}.vx", points=c["vx_points"], **common)
        case.record("relative error of the transport rate (integral of phi vx dz over the data's range)",
                    c["q_err"], ref, TOLERANCE, suffix=f"exp{exp}.transport", q_sim_m2_s=c["q_sim"],
                    q_exp_m2_s=c["q_exp"], **common)
        a1, a2 = axes[0][col], axes[1][col]
        top = data["z"].max() + 1.5
        keep = sim["z"] < top
        a1.plot(data["phi"], data["z"], "ko", ms=3, label="Frey (2014)")
        a1.plot(sim["phi"][keep], sim["z"][keep], "b-", label="Talus")
        a1.set_xlabel("solid fraction")
        a1.set_title(f"exp {exp}: error {c['phi_err']:.0%} of range")
        occupied = keep & (sim["phi"] > 0.01)
        a2.plot(data["vx"], data["z"], "ko", ms=3, label="Frey (2014)")
        a2.plot(sim["phivx"][occupied] / sim["phi"][occupied], sim["z"][occupied], "r-", label="Talus")
        a2.set_xlabel("particle velocity (m/s)")
        a2.set_title(f"vx {c['vx_err']:.0%}, q {c['q_sim'] / c['q_exp']:.2f}x data", fontsize=9)
        if col == 0:
            a1.set_ylabel("z / d above the ground")
            a2.set_ylabel("z / d above the ground")
            a1.legend(fontsize=8)
    fig.suptitle(f"Frey (2014) experiments: {length_d} d periodic, {transport:g} s transport "
                 f"(second half averaged)")
    fig.tight_layout()
    case.save_chart(fig)


if __name__ == "__main__":
    main()
