"""coupling: talusVolumeAveragedFoam's envelopeMethod convolution (latticeConvolution.H) against an
independent numpy evaluation of its kernel, against 2 fluid ranks and against the pairwise
Gaussian, on cfd_settling_sphere.py's box meshed 10 x 10 x 20 (cells 4.5 mm, the exchange-cost
mesh; written by the case builder) with 3000 spheres at random positions and velocities (tests/coupling/foam_cloud_driver.py),
fluid at rest, first exchange.

Checked:
- the fluid fraction the solver writes equals the numpy kernel's, sum_n T_n(x_i) G'(x_c - x_n)
  with the trilinear weights T, sigma'^2 = sigma^2 - h^2/6 and F_c, to 1e-12 (also with every
  sphere within a cell of a wall), and so does the fluid fraction interpolated to each sphere
  (read back from its drag's hindrance factor): the normalisation W_i cut by the walls;
- a uniform particle field (one sphere at each cell centre) gives a uniform fluid fraction up to
  the walls, to 1e-12;
- 2 fluid ranks give the serial forces to 1e-12 of the largest;
- against pairwise: the forces and the fluid fraction differ by little (bounds below from the
  measured values) but do differ (the kernels are not the same);
- a graded mesh falls back to pairwise and says so in the log; an unknown envelopeMethod stops
  the run before the first step with the reason."""
import json
import math
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from foam_case import ENV, needs_solver

pytestmark = needs_solver("talusVolumeAveragedFoam")

DRIVER = Path(__file__).with_name("foam_cloud_driver.py")
CELLS = (10, 10, 20)
LOW = np.array([-0.0225, -0.0225, 0.0])
H = np.array([0.0045, 0.0045, 0.0045])
DELTA = 3 * 0.0045                                   # the default width: 3 mean cell sizes
SIGMA = DELTA / (2 * math.sqrt(2 * math.log(2)))
CUTOFF = 3 * SIGMA                                   # the default cut-off (3 sigma)
RHO, NU = 1000.0, 1e-3


def case(tmp_path: Path, method: str, procs: int = 1, grading=(1, 1, 1)) -> Path:
    """The closed box, meshed (and decomposed along z), its fields written with every digit."""
    from talus.coupling.case_builder import cfd_case
    work = tmp_path / f"case_{method}_{procs}_{'_'.join(map(str, grading))}"
    cfd_case(work, solver="volumeaveraged", box=(LOW, LOW + H * CELLS), cells=CELLS, grading=grading, rho=RHO, nu=NU,
             coupling_interval=2e-5, procs=procs, write_precision=17, coupling_properties={"envelopeMethod": method})
    return work


def drive(work: Path, *extra: str):
    out = work / "out.json"
    run = subprocess.run([sys.executable, str(DRIVER), str(work), str(out), *extra], capture_output=True, text=True,
                         env=ENV, timeout=300)
    assert run.returncode == 0, run.stdout + run.stderr
    return json.loads(out.read_text())


def written_alpha(work: Path) -> np.ndarray:
    """The internal field of alphaf at the last time the solver wrote (x fastest: blockMesh's order)."""
    times = sorted((d for d in work.iterdir() if re.fullmatch(r"[0-9.e+-]+", d.name) and d.name != "0"),
                   key=lambda d: float(d.name))
    text = (times[-1] / "alphaf").read_text()
    body = text.split("internalField", 1)[1]
    uniform = re.match(r"\s*uniform\s+([^;\s]+);", body)   # OpenFOAM's form when every value is equal
    if uniform:
        return np.full(CELLS, float(uniform.group(1)))
    n = int(re.search(r"List<scalar>\s*(\d+)", body).group(1))
    values = body.split("(", 1)[1].split(")", 1)[0].split()
    assert len(values) == n
    return np.array(values, dtype=float).reshape(CELLS[::-1]).transpose(2, 1, 0)   # [ix, iy, iz]


def kernel_1d(x: np.ndarray, k: int) -> np.ndarray:
    """Per particle the convolution's kernel along axis k at the cells' centres, [n, cells]."""
    h = H[k]
    sigma2 = SIGMA ** 2 - h ** 2 / 6
    reach = math.ceil(CUTOFF / h) - 1
    u = (x[:, k] - (LOW[k] + h / 2)) / h
    below = np.floor(u)
    t = u - below
    cells = np.arange(CELLS[k])
    out = np.zeros((len(x), CELLS[k]))
    for node, weight in ((below, 1 - t), (below + 1, t)):
        # Between a wall and the outermost centre: on the outermost node (the hat reflected).
        d = cells[None, :] - np.clip(node, 0, CELLS[k] - 1)[:, None]
        out += weight[:, None] * np.where(np.abs(d) <= reach, np.exp(-(d * h) ** 2 / (2 * sigma2)), 0.0)
    return out


def reference(x: np.ndarray, volumes: np.ndarray):
    """The convolution method's fluid fraction per cell [ix, iy, iz] and the fluid fraction it
    interpolates to each particle."""
    kx, ky, kz = (kernel_1d(x, k) for k in range(3))
    # F_c = sum_c' G'(x_c - x_c') V_c' (uniform cells): per axis the kernels of particles at the
    # centres, summed over those particles.
    fill = []
    for k in range(3):
        at_centres = np.zeros((CELLS[k], 3))
        at_centres[:, k] = LOW[k] + H[k] * (np.arange(CELLS[k]) + 0.5)
        fill.append(kernel_1d(at_centres, k).sum(0))
    v_cell = np.prod(H)
    f = v_cell * np.einsum("a,b,c->abc", *fill)
    solid = np.einsum("i,ia,ib,ic->abc", volumes, kx, ky, kz) / f
    alpha = 1 - solid
    w = np.einsum("ia,ib,ic->i", kx, ky, kz)
    interpolated = np.einsum("ia,ib,ic,abc->i", kx, ky, kz, alpha) / w
    return alpha, interpolated


def hindered_alpha(record: dict, velocities: np.ndarray) -> np.ndarray:
    """The fluid fraction each sphere's drag was computed with: fluid at rest, so the force is
    -V_p K v - rho V_p g with K = 18 rho nu / d^2 (1 + 0.15 Re^0.687) alpha^-2.65."""
    r = record["radius"]
    d, vp = 2 * r, 4 / 3 * math.pi * r ** 3
    drag = np.array(record["forces"][0]) - np.array([0, 0, RHO * vp * 9.81])
    speed = np.linalg.norm(velocities, axis=1)
    k = -np.einsum("ij,ij->i", drag, velocities) / (vp * speed ** 2)
    stokes = 18 * RHO * NU / d ** 2 * (1 + 0.15 * (speed * d / NU) ** 0.687)
    return (k / stokes) ** (-1 / 2.65)


def cloud_velocities(n: int, wall: bool) -> np.ndarray:
    """The driver's random velocities (same generator calls)."""
    rng = np.random.default_rng(1)
    low, high = np.array([-0.022, -0.022, 0.001]), np.array([0.022, 0.022, 0.089])
    if wall:
        high[0] = -0.018
    rng.uniform(low, high, size=(n, 3))
    return rng.uniform(-0.02, 0.02, size=(n, 3))


@pytest.mark.parametrize("wall", [False, True])
def test_convolution_equals_its_kernel_evaluated_independently(tmp_path, wall):
    n = 3000 if not wall else 600
    work = case(tmp_path, "convolution")
    record = drive(work, "--n", str(n), *(["--wall"] if wall else []))
    x = np.array(record["positions"])
    volumes = np.full(len(x), 4 / 3 * math.pi * record["radius"] ** 3)
    alpha, interpolated = reference(x, volumes)
    np.testing.assert_allclose(written_alpha(work), alpha, rtol=0, atol=1e-12)
    # The solid part of the interpolated fraction (alpha is 0.99x: comparing it would hide errors).
    np.testing.assert_allclose(1 - hindered_alpha(record, cloud_velocities(n, wall)), 1 - interpolated, rtol=1e-9)
    assert "Gaussian envelope by convolution" in (work / "log.talusVolumeAveragedFoam").read_text()


@pytest.mark.parametrize("method", ["convolution", "pairwise"])
def test_uniform_particle_field_gives_uniform_fraction_up_to_the_walls(tmp_path, method):
    work = case(tmp_path, method)
    record = drive(work, "--centres")
    solid = 4 / 3 * math.pi * record["radius"] ** 3 / np.prod(H)
    np.testing.assert_allclose(written_alpha(work), 1 - solid, rtol=0, atol=1e-12)


def test_convolution_two_fluid_ranks_equal_serial(tmp_path):
    serial = drive(case(tmp_path, "convolution"))
    parallel = drive(case(tmp_path, "convolution", procs=2), "--procs", "2")
    assert parallel["fluidProcs"] == 2
    f1, f2 = np.array(serial["forces"][0]), np.array(parallel["forces"][0])
    np.testing.assert_allclose(f2, f1, rtol=0, atol=1e-12 * np.abs(f1).max())


def test_convolution_close_to_pairwise(tmp_path):
    conv_work, pair_work = case(tmp_path, "convolution"), case(tmp_path, "pairwise")
    conv, pair = drive(conv_work), drive(pair_work)
    f_conv, f_pair = np.array(conv["forces"][0]), np.array(pair["forces"][0])
    # Without buoyancy (the same -rho V_p g in both): the drag.
    weight = np.array([0, 0, RHO * 4 / 3 * math.pi * conv["radius"] ** 3 * 9.81])
    d_conv, d_pair = f_conv - weight, f_pair - weight
    l2 = np.linalg.norm(d_conv - d_pair) / np.linalg.norm(d_pair)
    largest = np.abs(d_conv - d_pair).max() / np.abs(d_pair).max()
    a_conv, a_pair = written_alpha(conv_work), written_alpha(pair_work)
    solid_l2 = np.linalg.norm(a_conv - a_pair) / np.linalg.norm(1 - a_pair)
    solid_max = np.abs(a_conv - a_pair).max() / np.abs(1 - a_pair).max()
    print(f"convolution against pairwise: drag relative L2 {l2:.3e}, max {largest:.3e}; solid fraction relative "
          f"L2 {solid_l2:.3e}, max {solid_max:.3e}")
    # Measured: drag 3.7e-5 L2, 1.6e-4 largest; solid fraction 0.77 % L2, 2.4 % of the largest.
    assert 0 < l2 < 1e-4 and largest < 5e-4
    assert 1e-4 < solid_l2 < 0.02 and solid_max < 0.05


def test_graded_mesh_falls_back_to_pairwise(tmp_path):
    work = case(tmp_path, "convolution", grading=(1, 1, 2))
    drive(work, "--n", "200")
    log = (work / "log.talusVolumeAveragedFoam").read_text()
    assert "envelopeMethod convolution: the cell centres are not equally spaced along z" in log
    assert "falling back to the pairwise Gaussian envelope" in log


def test_unknown_envelope_method_stops_before_the_first_step(tmp_path):
    work = case(tmp_path, "fft")
    out = work / "out.json"
    run = subprocess.run([sys.executable, str(DRIVER), str(work), str(out), "--n", "10"], capture_output=True,
                         text=True, env=ENV, timeout=120)
    assert run.returncode != 0 and not out.exists()
    assert "envelopeMethod fft unknown: use pairwise or convolution" in run.stdout + run.stderr
