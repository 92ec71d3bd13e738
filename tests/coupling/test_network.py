"""coupling: a coupled run on one host keeps Open MPI's TCP traffic on the loopback unless asked
(FoamCoupling interfaces, talus.coupling.network)."""
import re
import subprocess
import sys
import time
import warnings
from pathlib import Path

import pytest

from foam_case import DRIVER, ENV, meshed_box, needs_solver
from talus.coupling.network import apply_network_settings, network_settings

LOOPBACK = {"OMPI_MCA_btl_tcp_if_include": "lo", "OMPI_MCA_oob_tcp_if_include": "lo"}


def test_loopback_by_default_and_other_interfaces_on_request():
    assert network_settings("lo", {}) == LOOPBACK
    assert network_settings("eth0,10.0.0.0/8", {})["OMPI_MCA_btl_tcp_if_include"] == "eth0,10.0.0.0/8"
    assert network_settings(None, {}) == {}


def test_the_environment_of_the_user_wins():
    chosen = {"OMPI_MCA_btl_tcp_if_exclude": "docker0"}
    assert network_settings("lo", chosen) == {"OMPI_MCA_oob_tcp_if_include": "lo"}


@pytest.mark.parametrize("bad", ["", "  ", 3, ["lo"]])
def test_malformed_interfaces_are_refused(bad):
    with pytest.raises(ValueError, match="interfaces must be Open MPI interface names"):
        network_settings(bad, {})


def test_under_mpirun_it_is_too_late_and_says_how():
    environ = {"OMPI_COMM_WORLD_SIZE": "1"}
    with pytest.warns(RuntimeWarning, match="--mca btl_tcp_if_include lo --mca oob_tcp_if_include lo"):
        assert apply_network_settings("lo", environ) == {}
    assert "OMPI_MCA_btl_tcp_if_include" not in environ
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        apply_network_settings("lo", dict(environ, **LOOPBACK))  # mpirun was told: no warning


def connections(pid: int) -> list[tuple[str, str]]:
    """(local, peer) addresses of the established TCP connections of ``pid`` and its descendants."""
    tree = subprocess.run(["pstree", "-p", str(pid)], capture_output=True, text=True).stdout
    pids = set(re.findall(r"\((\d+)\)", tree))
    found = []
    for line in subprocess.run(["ss", "-tnpH", "state", "established"], capture_output=True, text=True).stdout.splitlines():
        owners = set(re.findall(r"pid=(\d+),", line))
        if owners & pids:
            fields = line.split()
            found.append((fields[2], fields[3]))
    return found


@needs_solver("talusPointForceFoam")
def test_a_coupled_run_talks_over_the_loopback_only(tmp_path):
    """Open MPI's default would connect the DEM process and the fluid rank through the host's
    network address; FoamCoupling's default keeps every connection of the run on 127.0.0.1."""
    work = meshed_box(tmp_path / "case")
    env = {k: v for k, v in ENV.items() if not k.startswith(("OMPI_MCA_btl_tcp", "OMPI_MCA_oob_tcp"))}
    run = subprocess.Popen([sys.executable, str(DRIVER), str(work), str(work / "out.json"), "--exchanges", "1000000"],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    try:
        seen = set()
        deadline = time.monotonic() + 5
        while time.monotonic() < deadline and run.poll() is None:
            seen.update(connections(run.pid))  # the daemon's, and the DEM-fluid one once they exchange
            time.sleep(0.2)
        assert run.poll() is None, run.communicate()
    finally:
        run.kill()
        run.communicate()
    assert len(seen) >= 6, seen  # both ends of the DEM-daemon, fluid-daemon and DEM-fluid ones
    for local, peer in seen:
        assert local.startswith(("127.", "[::1]")) and peer.startswith(("127.", "[::1]")), seen
