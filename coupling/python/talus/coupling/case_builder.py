"""A complete OpenFOAM case for Talus's coupling solvers, from a box or an existing mesh.

::

    from talus.coupling.case_builder import cfd_case, Inlet, Outlet
    case = cfd_case("bed", solver="volumeaveraged", box=((0, 0, 0), (0.01, 0.01, 0.05)), cell_size=1e-3,
                    rho=1000, nu=1e-6, boundaries={"z0": Inlet((0, 0, 0.01)), "z1": Outlet(),
                                                   "x0": "periodic", "y0": "periodic"},
                    coupling_interval=1e-4, procs=2)
    coupling = case.coupling(O)          # FoamCoupling with the case's fluid, gravity and ranks
    coupling.start()

:func:`cfd_case` writes 0/ (U, p and, for the volume-averaged solver, alphaf), constant/
(transportProperties, g, couplingProperties when given), system/ (blockMeshDict for a box,
controlDict, fvSchemes with the solver's own scheme names, fvSolution with a pressure solver
chosen for the mesh's size and shape and ``pRefCell`` when no boundary fixes the pressure,
decomposeParDict) and an empty ``case.foam`` for ParaView's reader; then meshes it (blockMesh)
and decomposes it (decomposePar) for ``procs > 1``. ``talus case cfd`` does the same from the command line.

Boundary conditions, per patch (a box's patches are its faces x0, x1, y0, y1, z0, z1; an
existing mesh's are read from its constant/polyMesh/boundary):

- ``Wall(velocity=(0, 0, 0))`` or ``"wall"``: no slip (a moving wall with a velocity);
- ``"slip"``: free slip;
- ``Inlet(velocity, ramp=0)``: fixed velocity (reached linearly over ``ramp`` seconds); for the
  volume-averaged solver the fluid fraction is fixed to 1 there, so the velocity is the
  superficial one;
- ``Outlet(pressure=0)``: fixed (kinematic) pressure, zero-gradient velocity;
- ``"periodic"``: cyclic, given on either face of a box's axis (both become periodic); an
  existing mesh's cyclic patches are periodic already.
"""

from __future__ import annotations

import math
import re
import shutil
import subprocess
from dataclasses import dataclass, field
from pathlib import Path
from typing import Mapping, Sequence

import numpy as np

__all__ = ["SOLVERS", "Wall", "Inlet", "Outlet", "SLIP", "PERIODIC", "FoamCase", "cfd_case", "boundary_condition"]

# Short names (the CLI's --solver) -> the solvers' executables.
SOLVERS = {"pointforce": "talusPointForceFoam", "volumeaveraged": "talusVolumeAveragedFoam"}
# The momentum equation's convection term, as each solver names it (fvSchemes divSchemes).
_CONVECTION = {"talusPointForceFoam": "div(phi,U)", "talusVolumeAveragedFoam": "div(alphaPhi,U)"}
# The pressure-velocity algorithm's dictionary in fvSolution.
_ALGORITHM = {"talusPointForceFoam": "PISO", "talusVolumeAveragedFoam": "PIMPLE"}
# The pressure goes to GAMG from this many cells, or from this many cells along the mesh's
# longest side: a Krylov solver's iterations grow with the mesh's extent in cells (PCG with
# DIC: about 0.6 per cell of the longest side per fluid step, both correctors), multigrid's do
# not (25 to 30); docs/coupling.md has the measurements behind both thresholds.
GAMG_FROM_CELLS = 20000
GAMG_FROM_SPAN = 200
_FACES = ("x0", "x1", "y0", "y1", "z0", "z1")


@dataclass(frozen=True)
class Wall:
    """A no-slip wall; moving at ``velocity`` [m/s] (tangential) if given."""
    velocity: tuple = (0.0, 0.0, 0.0)


@dataclass(frozen=True)
class Inlet:
    """A fixed inflow velocity [m/s], reached linearly from rest over ``ramp`` seconds."""
    velocity: tuple
    ramp: float = 0.0


@dataclass(frozen=True)
class Outlet:
    """A fixed kinematic pressure p/rho [m2/s2] (without its hydrostatic part)."""
    pressure: float = 0.0


SLIP = "slip"
PERIODIC = "periodic"


def boundary_condition(spec):
    """A boundary condition from its object or its text: ``wall``, ``wall:UX,UY,UZ``, ``slip``,
    ``periodic``, ``inlet:UX,UY,UZ[:RAMP]``, ``outlet[:P]`` (the CLI's form)."""
    if isinstance(spec, (Wall, Inlet, Outlet)) or spec in (SLIP, PERIODIC):
        return spec
    if not isinstance(spec, str):
        raise ValueError(f"boundary condition {spec!r}: give Wall(...), Inlet(...), Outlet(...), 'slip' or 'periodic'")
    kind, _, rest = spec.partition(":")
    try:
        if kind == "wall":
            return Wall(_vector(rest)) if rest else Wall()
        if kind == "inlet" and rest:
            velocity, _, ramp = rest.partition(":")
            return Inlet(_vector(velocity), float(ramp) if ramp else 0.0)
        if kind == "outlet":
            return Outlet(float(rest) if rest else 0.0)
    except ValueError as e:
        raise ValueError(f"boundary condition {spec!r}: {e}") from None
    raise ValueError(f"boundary condition {spec!r}: use wall[:UX,UY,UZ], slip, periodic, inlet:UX,UY,UZ[:RAMP] "
                     "or outlet[:P]")


def _vector(text) -> tuple:
    values = tuple(float(v) for v in (text.split(",") if isinstance(text, str) else text))
    if len(values) != 3:
        raise ValueError(f"{text!r} is not a vector of 3 numbers")
    return values


@dataclass
class FoamCase:
    """A written (and meshed) case: what :class:`~talus.coupling.FoamCoupling` needs from it."""
    path: Path
    solver: str
    rho: float
    nu: float
    gravity: tuple
    procs: int
    deltaT: float
    cells: int
    patches: dict = field(default_factory=dict)

    def coupling(self, scene, **options):
        """The coupling engine for this case (not started): fluid, gravity, solver and ranks
        from the case; ``options`` go to FoamCoupling (ids, implicitDrag, timeout, ...)."""
        from talus.coupling.foam import FoamCoupling
        return FoamCoupling(scene, self.path, rhoFluid=self.rho, nu=self.nu, gravity=self.gravity,
                            nProcs=self.procs, solver=self.solver, **options)


def _header(cls: str, location: str, name: str) -> str:
    return ("FoamFile\n{\n    version     2.0;\n    format      ascii;\n"
            f"    class       {cls};\n    location    \"{location}\";\n    object      {name};\n}}\n"
            "// Written by talus.coupling.case_builder.\n\n")


def _foam_vector(v) -> str:
    return "(" + " ".join(f"{float(x):.12g}" for x in v) + ")"


def _box_geometry(box, cells, cell_size):
    low, high = (np.asarray(_vector(c)) for c in box)
    if np.any(high <= low):
        raise ValueError(f"cfd_case: box {box}: every upper corner coordinate must exceed the lower one")
    if (cells is None) == (cell_size is None):
        raise ValueError("cfd_case: give the box's cells (nx, ny, nz) or its cell_size, not both")
    if cells is None:
        if cell_size <= 0:
            raise ValueError(f"cfd_case: cell_size must be positive, got {cell_size}")
        cells = tuple(max(1, round(s / cell_size)) for s in high - low)
    cells = tuple(int(n) for n in cells)
    if len(cells) != 3 or min(cells) < 1:
        raise ValueError(f"cfd_case: cells {cells}: three counts of at least 1")
    return low, high, cells


def _read_boundary(poly_mesh: Path) -> dict[str, str]:
    """Patch name -> type of an existing mesh's constant/polyMesh/boundary."""
    text = re.sub(r"/\*.*?\*/|//[^\n]*", " ", (poly_mesh / "boundary").read_text(), flags=re.S)
    body = text[text.index("(", text.index("}")) + 1:]
    return {m.group(1): m.group(2) for m in re.finditer(r"([\w.:-]+)\s*\{[^{}]*?\btype\s+(\w+)\s*;", body)}


def _conditions(patches: Sequence[str], cyclic: set, boundaries: Mapping, default) -> dict:
    unknown = sorted(set(boundaries) - set(patches))
    if unknown:
        raise ValueError(f"cfd_case: boundaries: no patch named {', '.join(unknown)} (the mesh's patches: "
                         f"{', '.join(patches)})")
    chosen = {name: boundary_condition(boundaries.get(name, default)) for name in patches}
    for name in cyclic:
        chosen[name] = PERIODIC
    return chosen


def _box_mesh_dict(low, high, cells, grading, conditions) -> str:
    x0, y0, z0 = low
    x1, y1, z1 = high
    corners = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
               (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    faces = {"x0": "(0 4 7 3)", "x1": "(1 2 6 5)", "y0": "(0 1 5 4)", "y1": "(2 3 7 6)",
             "z0": "(0 3 2 1)", "z1": "(4 5 6 7)"}
    lines = []
    for name in _FACES:
        condition = conditions[name]
        if condition == PERIODIC:
            other = name[0] + ("1" if name[1] == "0" else "0")
            lines.append(f"    {name} {{ type cyclic; neighbourPatch {other}; faces ({faces[name]}); }}")
        else:
            kind = "wall" if isinstance(condition, Wall) else "patch"
            lines.append(f"    {name} {{ type {kind}; faces ({faces[name]}); }}")
    return (_header("dictionary", "system", "blockMeshDict")
            + "vertices\n(\n" + "".join(f"    {_foam_vector(c)}\n" for c in corners) + ");\n\n"
            + f"blocks\n(\n    hex (0 1 2 3 4 5 6 7) ({cells[0]} {cells[1]} {cells[2]}) "
              f"simpleGrading ({' '.join(f'{g:.12g}' for g in grading)})\n);\n\n"
            + "boundary\n(\n" + "\n".join(lines) + "\n);\n")


def _patch_entries(conditions: dict, field: str) -> str:
    """The boundaryField entries of U, p or alphaf."""
    out = []
    for name, c in conditions.items():
        if c == PERIODIC:
            entry = "type cyclic;"
        elif field == "U":
            if isinstance(c, Wall):
                entry = ("type noSlip;" if not any(c.velocity)
                         else f"type fixedValue; value uniform {_foam_vector(c.velocity)};")
            elif isinstance(c, Inlet):
                entry = (f"type fixedValue; value uniform {_foam_vector(c.velocity)};" if c.ramp <= 0 else
                         "type uniformFixedValue; uniformValue table "
                         f"((0 (0 0 0)) ({c.ramp:.12g} {_foam_vector(c.velocity)}) "
                         f"({1e9:.12g} {_foam_vector(c.velocity)}));")
            elif isinstance(c, Outlet):
                entry = "type zeroGradient;"
            else:
                entry = "type slip;"
        elif field == "p":
            entry = (f"type fixedValue; value uniform {c.pressure:.12g};" if isinstance(c, Outlet)
                     else "type zeroGradient;")
        else:  # alphaf: pure fluid enters through an inlet
            entry = "type fixedValue; value uniform 1;" if isinstance(c, Inlet) else "type zeroGradient;"
        out.append(f"    {name} {{ {entry} }}")
    return "boundaryField\n{\n" + "\n".join(out) + "\n}\n"


def _internal_velocity(initial_velocity, box_cells) -> str:
    if initial_velocity is None:
        return "uniform (0 0 0)"
    if not callable(initial_velocity):
        return f"uniform {_foam_vector(_vector(initial_velocity))}"
    if box_cells is None:
        raise ValueError("cfd_case: initial_velocity as a function of the cell centres needs a box mesh "
                         "(give a uniform vector for an existing mesh)")
    low, high, cells = box_cells
    size = (high - low) / np.array(cells)
    # blockMesh numbers a single block's cells x fastest, then y, then z.
    k, j, i = np.meshgrid(*(np.arange(n) for n in cells[::-1]), indexing="ij")
    centres = low + (np.stack([i.ravel(), j.ravel(), k.ravel()], axis=1) + 0.5) * size
    u = np.asarray(initial_velocity(centres), dtype=float)
    if u.shape != centres.shape:
        raise ValueError(f"cfd_case: initial_velocity returned shape {u.shape} for {len(centres)} cell centres, "
                         f"expected {centres.shape}")
    return f"nonuniform List<vector> {len(u)}\n(\n" + "\n".join(_foam_vector(v) for v in u) + "\n)"


def _span_in_cells(cells: int, low, high) -> int:
    """The mesh's longest side in mean cell sizes (the cube root of its bounding box's volume
    per cell), rounded: a box's largest cell count when its cells are cubes."""
    span = np.asarray(high, dtype=float) - np.asarray(low, dtype=float)
    return round(span.max() / (np.prod(span) / cells) ** (1 / 3))


def _pressure_solver(cells: int, span: int, tolerance: float, relative: float) -> str:
    if cells >= GAMG_FROM_CELLS or span >= GAMG_FROM_SPAN:
        p = f"solver GAMG; smoother GaussSeidel; tolerance {tolerance:g}; relTol {relative:g};"
    else:
        p = f"solver PCG; preconditioner DIC; tolerance {tolerance:g}; relTol {relative:g};"
    return (f"    p {{ {p} }}\n    pFinal {{ $p; relTol 0; }}\n"
            "    U { solver smoothSolver; smoother symGaussSeidel; tolerance 1e-12; relTol 0; }\n"
            "    UFinal { $U; }\n")


def _decomposition(procs: int, decomposition, conditions, low, high) -> tuple[int, int, int]:
    """Slabs across the longest axis without periodic patches (the volume-averaged solver's
    periodic envelope needs every rank to hold whole periods), unless given."""
    if decomposition is not None:
        counts = tuple(int(n) for n in decomposition)
        if len(counts) != 3 or math.prod(counts) != procs:
            raise ValueError(f"cfd_case: decomposition {decomposition} must be three counts whose product is "
                             f"procs = {procs}")
        return counts
    span = high - low
    periodic = {"xyz".index(name[0]) for name, c in conditions.items() if c == PERIODIC and name in _FACES}
    axes = [k for k in range(3) if k not in periodic] or [0, 1, 2]
    counts = [1, 1, 1]
    counts[max(axes, key=lambda k: span[k])] = procs
    return tuple(counts)


def cfd_case(out, *, solver: str = "pointforce", box=None, cells=None, cell_size: float | None = None,
             grading=(1.0, 1.0, 1.0), mesh=None, rho: float, nu: float, gravity=(0.0, 0.0, -9.81), boundaries: Mapping | None = None,
             default_boundary="wall", coupling_interval: float, procs: int = 1, decomposition=None,
             coupling_properties: Mapping | None = None, initial_velocity=None, write_every: int = 100,
             write_precision: int = 8, pressure_tolerance: float = 1e-8, pressure_relative_tolerance: float = 0.01,
             run_mesh: bool = True) -> FoamCase:
    """Write an OpenFOAM case for a coupled run in the folder ``out`` (created; an existing
    folder must be empty) and mesh it.

    Args:
        solver: ``pointforce`` (talusPointForceFoam, PISO) or ``volumeaveraged``
            (talusVolumeAveragedFoam, PIMPLE); the executables' names are accepted too.
        box: ((x0, y0, z0), (x1, y1, z1)) [m], meshed with ``cells`` (nx, ny, nz) or cubes of
            about ``cell_size``, graded by ``grading`` (blockMesh's simpleGrading: per axis the
            last cell's size over the first's); or ``mesh``: an existing case folder (its
            constant/polyMesh) or polyMesh folder, copied.
        rho, nu: fluid density [kg/m3] and kinematic viscosity [m2/s]; ``gravity`` [m/s2].
        boundaries: patch name -> condition (see the module's doc); ``default_boundary`` for
            the others.
        coupling_interval: the fluid step [s]: one exchange with the DEM per fluid step.
        procs: fluid ranks; ``decomposition`` (nx, ny, nz) slabs (default: across the longest
            axis without periodic patches).
        coupling_properties: entries of constant/couplingProperties (the volume-averaged
            solver's envelope, drag model, ...; see docs/coupling.md).
        initial_velocity: the fluid's initial velocity: a vector, or (box only) a function of
            the cell centres (n x 3 array) returning n x 3 velocities.
        write_every: the fluid fields are written every so many fluid steps (and at the end),
            with ``write_precision`` significant digits.
        pressure_tolerance, pressure_relative_tolerance: absolute and relative (relTol, 0 in the
            last corrector) tolerances of the pressure solver (a relative one of 0 in every
            corrector makes a decomposed fluid differ from a serial one by rounding only): GAMG from GAMG_FROM_CELLS cells or GAMG_FROM_SPAN cells along the
            longest side, PCG with DIC below.
        run_mesh: run blockMesh (box) and decomposePar (procs > 1) now.
    """
    solver = SOLVERS.get(solver, solver)
    if solver not in _CONVECTION:
        raise ValueError(f"cfd_case: solver {solver!r}: use {' or '.join(SOLVERS)} ({', '.join(_CONVECTION)})")
    if (box is None) == (mesh is None):
        raise ValueError("cfd_case: give the geometry as a box or as an existing mesh, one of them")
    for name, value in (("rho", rho), ("nu", nu), ("coupling_interval", coupling_interval)):
        if not value > 0:
            raise ValueError(f"cfd_case: {name} must be positive, got {value}")
    if int(procs) < 1 or int(write_every) < 1 or int(write_precision) < 1:
        raise ValueError(f"cfd_case: procs ({procs}), write_every ({write_every}) and write_precision "
                         f"({write_precision}) must be at least 1")
    procs = int(procs)
    out = Path(out)
    if out.exists() and any(out.iterdir()):
        raise FileExistsError(f"cfd_case: {out} exists and is not empty")
    boundaries = dict(boundaries or {})

    if box is not None:
        low, high, counts = _box_geometry(box, cells, cell_size)
        grading = _vector(grading)
        if not all(g > 0 for g in grading):
            raise ValueError(f"cfd_case: grading {grading}: three positive ratios (last cell over first)")
        if callable(initial_velocity) and grading != (1.0, 1.0, 1.0):
            raise ValueError("cfd_case: initial_velocity as a function of the cell centres needs an ungraded box "
                             "(grading (1, 1, 1))")
        # "periodic" on one face of an axis makes the pair periodic.
        for name, c in list(boundaries.items()):
            if name in _FACES and boundary_condition(c) == PERIODIC:
                boundaries[name[0] + ("1" if name[1] == "0" else "0")] = PERIODIC
        conditions = _conditions(_FACES, set(), boundaries, default_boundary)
        n_cells = math.prod(counts)
        box_cells = (low, high, counts)
    else:
        source = Path(mesh)
        poly = source if (source / "boundary").is_file() else source / "constant" / "polyMesh"
        if not (poly / "boundary").is_file():
            raise FileNotFoundError(f"cfd_case: mesh {mesh}: no constant/polyMesh/boundary in it")
        types = _read_boundary(poly)
        cyclic = {name for name, kind in types.items() if kind == "cyclic"}
        for name, c in boundaries.items():
            if boundary_condition(c) == PERIODIC and name not in cyclic:
                raise ValueError(f"cfd_case: boundaries: patch {name} of the mesh is not cyclic; a periodic "
                                 "pair must be made cyclic in the mesh itself")
        conditions = _conditions(list(types), cyclic, boundaries, default_boundary)
        box_cells = None

    (out / "0").mkdir(parents=True, exist_ok=True)
    (out / "constant").mkdir(exist_ok=True)
    (out / "system").mkdir(exist_ok=True)
    if box is not None:
        (out / "system" / "blockMeshDict").write_text(_box_mesh_dict(low, high, counts, grading, conditions))
    else:
        shutil.copytree(poly, out / "constant" / "polyMesh")
        n_cells = _count_cells(out / "constant" / "polyMesh")
        low, high = _mesh_bounds(out / "constant" / "polyMesh")

    velocity = _internal_velocity(initial_velocity, box_cells)
    (out / "0" / "U").write_text(_header("volVectorField", "0", "U") + "dimensions      [0 1 -1 0 0 0 0];\n"
                                 f"internalField   {velocity};\n" + _patch_entries(conditions, "U"))
    (out / "0" / "p").write_text(_header("volScalarField", "0", "p")
                                 + "// Kinematic pressure p/rho without its hydrostatic part.\n"
                                 "dimensions      [0 2 -2 0 0 0 0];\ninternalField   uniform 0;\n"
                                 + _patch_entries(conditions, "p"))
    if solver == "talusVolumeAveragedFoam":
        (out / "0" / "alphaf").write_text(_header("volScalarField", "0", "alphaf")
                                          + "// Fluid fraction: the solver replaces the internal field by the "
                                          "particles' each step.\n"
                                          "dimensions      [0 0 0 0 0 0 0];\ninternalField   uniform 1;\n"
                                          + _patch_entries(conditions, "alphaf"))
    (out / "constant" / "transportProperties").write_text(
        _header("dictionary", "constant", "transportProperties")
        + f"nu              {nu:.12g};\nrho             {rho:.12g};\n")
    (out / "constant" / "g").write_text(_header("uniformDimensionedVectorField", "constant", "g")
                                        + f"dimensions      [0 1 -2 0 0 0 0];\nvalue           "
                                          f"{_foam_vector(_vector(gravity))};\n")
    if coupling_properties:
        (out / "constant" / "couplingProperties").write_text(
            _header("dictionary", "constant", "couplingProperties")
            + "".join(f"{key:<20} {value};\n" for key, value in coupling_properties.items()))
    (out / "system" / "controlDict").write_text(
        _header("dictionary", "system", "controlDict")
        + "// The DEM process drives the time loop (one fluid step per exchange): endTime only lies\n"
          "// beyond any coupled run.\n"
        + f"application     {solver};\nstartFrom       startTime;\nstartTime       0;\nstopAt          endTime;\n"
          f"endTime         1e9;\ndeltaT          {coupling_interval:.12g};\nwriteControl    timeStep;\n"
          f"writeInterval   {int(write_every)};\npurgeWrite      0;\nwriteFormat     ascii;\n"
          f"writePrecision  {int(write_precision)};\n"
          "writeCompression off;\ntimeFormat      general;\ntimePrecision   8;\nrunTimeModifiable false;\n")
    orthogonal = box is not None
    laplacian = "Gauss linear orthogonal" if orthogonal else "Gauss linear corrected"
    (out / "system" / "fvSchemes").write_text(
        _header("dictionary", "system", "fvSchemes")
        + "ddtSchemes { default Euler; }\ngradSchemes { default Gauss linear; }\n"
        + f"divSchemes {{ default none; {_CONVECTION[solver]} Gauss linear; }}\n"
        + f"laplacianSchemes {{ default {laplacian}; }}\ninterpolationSchemes {{ default linear; }}\n"
        + f"snGradSchemes {{ default {'orthogonal' if orthogonal else 'corrected'}; }}\n")
    reference = not any(isinstance(c, Outlet) for c in conditions.values())
    algorithm = _ALGORITHM[solver]
    controls = ["nOuterCorrectors 1;"] if algorithm == "PIMPLE" else []
    controls += ["nCorrectors 2;", "nNonOrthogonalCorrectors 0;", "momentumPredictor yes;"]
    if reference:  # no boundary fixes the pressure: one cell does
        controls += ["pRefCell 0;", "pRefValue 0;"]
    (out / "system" / "fvSolution").write_text(
        _header("dictionary", "system", "fvSolution")
        + "solvers\n{\n" + _pressure_solver(n_cells, _span_in_cells(n_cells, low, high), pressure_tolerance,
                                            pressure_relative_tolerance)
        + "}\n\n"
        + f"{algorithm}\n{{\n" + "".join(f"    {c}\n" for c in controls) + "}\n")
    counts = _decomposition(procs, decomposition, conditions, low, high)
    (out / "system" / "decomposeParDict").write_text(
        _header("dictionary", "system", "decomposeParDict")
        + f"numberOfSubdomains {procs};\nmethod          simple;\n"
          f"coeffs {{ n ({counts[0]} {counts[1]} {counts[2]}); }}\n")
    (out / "case.foam").touch()   # ParaView's OpenFOAM reader opens this
    if run_mesh:
        mesh_and_decompose(out, blockmesh=box is not None, procs=procs)
    return FoamCase(out.resolve(), solver, float(rho), float(nu), _vector(gravity), procs, float(coupling_interval),
                    int(n_cells), conditions)


def _count_cells(poly: Path) -> int:
    owner = (poly / "owner").read_text(errors="replace")
    match = re.search(r"nCells:\s*(\d+)", owner)
    if match is None:
        raise ValueError(f"cfd_case: {poly}/owner has no nCells in its note (an ASCII polyMesh is needed)")
    return int(match.group(1))


def _mesh_bounds(poly: Path):
    number = r"([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)"
    text = (poly / "points").read_text(errors="replace")
    points = np.array(re.findall(rf"\(\s*{number}\s+{number}\s+{number}\s*\)", text), dtype=float)
    if len(points) == 0:
        raise ValueError(f"cfd_case: {poly}/points has no ASCII points (an ASCII polyMesh is needed)")
    return points.min(axis=0), points.max(axis=0)


def mesh_and_decompose(case, *, blockmesh: bool = True, procs: int = 1) -> None:
    """Run blockMesh and, for ``procs > 1``, decomposePar in ``case``; a failure raises with its
    log file (``case/log.<utility>``)."""
    from talus.coupling.cases import foam_environment
    case = Path(case)
    env = foam_environment()
    for command in ([["blockMesh"]] if blockmesh else []) + ([["decomposePar", "-force"]] if procs > 1 else []):
        log_path = case / f"log.{command[0]}"
        with open(log_path, "w") as log:
            done = subprocess.run(command + ["-case", str(case)], stdout=log, stderr=subprocess.STDOUT, env=env)
        if done.returncode != 0:
            raise RuntimeError(f"{command[0]} failed on the case {case} (see {log_path})")
