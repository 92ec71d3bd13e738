"""``talus case``: write a ready-to-run case folder.

    talus case cfd --solver pointforce|volumeaveraged (--box X0 Y0 Z0 X1 Y1 Z1 | --mesh CASE) ...
    talus case permeability --porosities 0.36 0.4 --out DIR
    talus case femxdem --cells 2 4 --out DIR

Each prints what it wrote and how to run it. The Python functions behind them:
talus.coupling.case_builder.cfd_case, talus.flow.case_builder.permeability_study,
talus.fem.case_builder.biaxial_study (docs/coupling.md, docs/flow.md, docs/fem.md).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path


def add_arguments(parser: argparse.ArgumentParser) -> None:
    kinds = parser.add_subparsers(dest="kind", required=True, metavar="KIND")

    cfd = kinds.add_parser("cfd", help="an OpenFOAM case for CFD-DEM coupling (meshed, decomposed)")
    cfd.add_argument("--solver", default="pointforce", help="pointforce (PISO) or volumeaveraged (PIMPLE)")
    geometry = cfd.add_mutually_exclusive_group(required=True)
    geometry.add_argument("--box", type=float, nargs=6, metavar=("X0", "Y0", "Z0", "X1", "Y1", "Z1"))
    geometry.add_argument("--mesh", type=Path, help="an existing case (its constant/polyMesh) to copy")
    size = cfd.add_mutually_exclusive_group()
    size.add_argument("--cells", type=int, nargs=3, metavar=("NX", "NY", "NZ"))
    size.add_argument("--cell-size", type=float, help="[m] cubes of about this size")
    cfd.add_argument("--rho", type=float, required=True, help="fluid density [kg/m3]")
    cfd.add_argument("--nu", type=float, required=True, help="kinematic viscosity [m2/s]")
    cfd.add_argument("--gravity", type=float, nargs=3, default=(0.0, 0.0, -9.81), metavar=("GX", "GY", "GZ"))
    cfd.add_argument("--boundary", action="append", default=[], metavar="PATCH=COND",
                     help="e.g. z0=inlet:0,0,0.01  z1=outlet  x0=periodic  y1=wall:0.05,0,0  x1=slip (repeat)")
    cfd.add_argument("--default-boundary", default="wall", help="for the patches not named (default wall)")
    cfd.add_argument("--dt", type=float, required=True, help="the coupling interval = fluid step [s]")
    cfd.add_argument("--procs", type=int, default=1, help="fluid ranks")
    cfd.add_argument("--decomposition", type=int, nargs=3, metavar=("NX", "NY", "NZ"))
    cfd.add_argument("--coupling", action="append", default=[], metavar="KEY=VALUE",
                     help="an entry of constant/couplingProperties, e.g. envelopeWidth=0.003 (repeat)")
    cfd.add_argument("--write-every", type=int, default=100, help="fluid steps between written fields")
    cfd.add_argument("--no-mesh", action="store_true", help="write the files only (no blockMesh/decomposePar)")
    cfd.add_argument("--out", type=Path, required=True)
    cfd.set_defaults(func=run, handler=_cfd)

    perm = kinds.add_parser("permeability", help="a pore-flow permeability study (script + inputs)")
    perm.add_argument("--porosities", type=float, nargs="+", default=[0.36, 0.40, 0.44])
    perm.add_argument("--spheres", type=int, default=400)
    perm.add_argument("--rrelfuzz", type=float, default=0.3)
    perm.add_argument("--axis", type=int, default=1)
    perm.add_argument("--viscosity", type=float, default=1.0)
    perm.add_argument("--seed", type=int, default=1)
    perm.add_argument("--out", type=Path, required=True)
    perm.set_defaults(func=run, handler=_permeability)

    fem = kinds.add_parser("femxdem", help="an FEM x DEM biaxial test (script + inputs)")
    fem.add_argument("--cells", type=int, nargs=2, default=[2, 4], metavar=("NX", "NY"))
    fem.add_argument("--size", type=float, nargs=2, default=[1.0, 2.0], metavar=("WIDTH", "HEIGHT"))
    fem.add_argument("--confinement", type=float, default=1e5, help="[Pa]")
    fem.add_argument("--axial-strain", type=float, default=0.015)
    fem.add_argument("--steps", type=int, default=6, help="load steps")
    fem.add_argument("--dem-steps", type=int, default=40, help="DEM steps per Gauss-point call")
    fem.add_argument("--rmean", type=float, default=0.1)
    fem.add_argument("--friction", type=float, default=0.5)
    fem.add_argument("--out", type=Path, required=True)
    fem.set_defaults(func=run, handler=_femxdem)


def _pairs(items: list[str], what: str) -> dict[str, str]:
    pairs = {}
    for item in items:
        key, sep, value = item.partition("=")
        if not sep or not key or not value:
            raise ValueError(f"{what} {item!r}: write NAME=VALUE")
        pairs[key] = value
    return pairs


def _cfd(args) -> int:
    from talus.coupling.case_builder import cfd_case
    case = cfd_case(args.out, solver=args.solver, box=(args.box[:3], args.box[3:]) if args.box else None,
                    mesh=args.mesh, cells=args.cells, cell_size=args.cell_size, rho=args.rho, nu=args.nu,
                    gravity=args.gravity, boundaries=_pairs(args.boundary, "--boundary"),
                    default_boundary=args.default_boundary, coupling_interval=args.dt, procs=args.procs,
                    decomposition=args.decomposition, coupling_properties=_pairs(args.coupling, "--coupling"),
                    write_every=args.write_every, run_mesh=not args.no_mesh)
    print(f"talus case cfd: wrote {case.path} ({case.solver}, {case.cells} cells, {case.procs} fluid rank(s), "
          f"fluid step {case.deltaT:g} s)")
    print("  patches: " + ", ".join(f"{name} {condition}" for name, condition in case.patches.items()))
    print(f"  couple it from a script: FoamCoupling(O, {str(case.path)!r}, rhoFluid={case.rho:g}, nu={case.nu:g}, "
          f"gravity={case.gravity}, nProcs={case.procs}, solver={case.solver!r}).start()")
    return 0


def _permeability(args) -> int:
    from talus.flow.case_builder import permeability_study
    script = permeability_study(args.out, porosities=args.porosities, spheres=args.spheres, rRelFuzz=args.rrelfuzz,
                                axis=args.axis, viscosity=args.viscosity, seed=args.seed)
    print(f"talus case permeability: wrote {script} and its inputs {script.with_name('study.json')}")
    print(f"  run it: talus run {script}")
    return 0


def _femxdem(args) -> int:
    from talus.fem.case_builder import biaxial_study
    script = biaxial_study(args.out, cells=args.cells, size=args.size, confinement=args.confinement,
                           axialStrain=args.axial_strain, steps=args.steps, demSteps=args.dem_steps,
                           rMean=args.rmean, friction=args.friction)
    print(f"talus case femxdem: wrote {script} and its inputs {script.with_name('study.json')}")
    print(f"  run it: talus run {script}")
    return 0


def run(args) -> int:
    try:
        return args.handler(args)
    except (ValueError, FileExistsError, FileNotFoundError, RuntimeError) as e:
        print(f"talus case {args.kind}: {e}", file=sys.stderr)
        return 2
