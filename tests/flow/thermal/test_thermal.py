"""ThermalEngine, conduction between particles: the rod of Yade's conductionVerification.py
(thermal_rod.py, the same script under Yade and Talus) against Yade 2023.02a's numbers, against
Fourier's series with the chain's diffusivity, and against its own heat balance; checkpoints and
ParaView output of the temperatures."""
import json
import os
from pathlib import Path

import numpy as np
import pytest

HERE = Path(__file__).resolve().parent
YADE = json.loads((HERE.parent / "data" / "thermal_rod_yade.json").read_text())
T0, RADIUS, DENSITY, CP = 400.0, 0.003, 2600.0, 710.0


def run_rod(talus_cmd, tmp_path, **settings):
    env = {**os.environ, **{f"ROD_{k.upper()}": str(v) for k, v in settings.items()}}
    out = tmp_path / "rod.json"
    talus_cmd("run", "-j", "1", HERE / "thermal_rod.py", out, cwd=tmp_path, env=env)
    return json.loads(out.read_text())


def test_rod_matches_yade(talus_cmd, tmp_path):
    """Same input, same numbers: temperatures after 2000 steps and the boundary heat rates every
    100 steps, to round-off (the end spheres are the boundary's: the same triangulation)."""
    rod = run_rod(talus_cmd, tmp_path)
    assert rod["ids"] == YADE["ids"] and rod["contacts"] == YADE["contacts"]
    np.testing.assert_allclose(rod["temp"], YADE["temp"], rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(rod["fluxes"], YADE["fluxes"], rtol=1e-12)
    assert rod["temp"][0] == rod["temp"][-1] == 0.0 and min(rod["temp"][1:-1]) > 20


def fourier(x, t, length, diffusivity):
    """Rod at T0 with both ends held at 0 from t = 0 (x from one end)."""
    n = np.arange(1, 2000)
    modes = 2 * T0 * (1 - np.cos(n * np.pi)) / (n * np.pi)
    return (modes * np.sin(np.outer(x, n) * np.pi / length) * np.exp(-diffusivity * (n * np.pi / length) ** 2 * t)).sum(1)


def test_rod_fourier_and_heat_balance(talus_cmd, tmp_path):
    """particleK 200: the thermal step (0.8 x the stable 0.087 s) is below O.dt = 1 s, so each
    step conducts in sub-steps. The temperatures follow Fourier's series with the chain's
    diffusivity G D² / C (G = 4 k r² / D between neighbours D apart, C = rho 4/3 pi r³ Cp): a
    conductance or a heat capacity 5 % off moves the middle of the rod by about 5 %. The heat the
    two boundaries received is what the spheres lost, C (T0 - T) with C computed here: a heat
    capacity scaled together with the conductance (same temperatures) fails this one."""
    rod = run_rod(talus_cmd, tmp_path, k=200, tsf=0.8, steps=500)
    x, temp = np.array(rod["x"]), np.array(rod["temp"])
    spacing = x[1] - x[0]
    capacity = DENSITY * 4 / 3 * np.pi * RADIUS ** 3 * CP
    diffusivity = 4 * 200 * RADIUS ** 2 / spacing * spacing ** 2 / capacity
    exact = fourier(x - x[0], rod["time"], x[-1] - x[0], diffusivity)
    middle = len(x) // 2
    assert 150 < exact[middle] < 200
    assert abs(temp[middle] - exact[middle]) < 1e-3 * exact[middle]
    assert np.abs(temp - exact).max() < 2e-4 * T0
    lost = capacity * (T0 - temp[1:-1]).sum()
    assert sum(rod["heat"]) == pytest.approx(lost, rel=1e-10)
    assert rod["heat"][0] == pytest.approx(rod["heat"][1], rel=1e-9) and rod["heat"][2:] == [0.0] * 4


def test_rod_kern_method(talus_cmd, tmp_path):
    """useKernMethod: the area of the intersection circle, tiny for the rod's 1e-8 m overlaps
    (rc² ~ r x overlap): after 200 steps the second sphere lost 0.015 K, as in Yade 2023.02a
    (399.98467326275517 with ROD_KERN=1 ROD_STEPS=200), where the default cools it by half."""
    rod = run_rod(talus_cmd, tmp_path, kern=1, steps=200)
    assert T0 - rod["temp"][1] == pytest.approx(T0 - 399.98467326275517, rel=1e-9)


def test_checkpoint_and_vtk(talus_cmd, tmp_path):
    """O.save half-way, run on, O.load and run the second half again: the same temperatures to
    the bit; the thermal recorder writes them in the sphere file."""
    rod = run_rod(talus_cmd, tmp_path, k=200, tsf=0.8, steps=200, save=tmp_path / "half.h5", vtk=tmp_path / "vtk" / "rod-")
    assert rod["temp"] == rod["tempBeforeReload"]
    assert max(rod["temp"]) < T0 - 1
    vtu = (tmp_path / "vtk" / "rod-spheres.100.vtu").read_text()
    assert 'Name="temp"' in vtu and 'Name="Cp"' in vtu
