"""Which network interfaces a coupled run's Open MPI traffic uses.

Open MPI's TCP transports (``btl tcp`` between the DEM process and the fluid ranks, ``oob tcp``
of its daemon) use every interface but the loopback by default: a coupled run on one host would
send its messages through the host's network address. FoamCoupling keeps them on the loopback
unless told otherwise (``interfaces``). The settings are environment variables that Open MPI
reads when MPI starts: in the DEM process before it starts MPI (a script run without mpirun),
inherited by Open MPI's daemon and the fluid ranks it spawns.
"""

from __future__ import annotations

import os
import warnings

# Open MPI's TCP components and their interface selections (mutually exclusive per component).
_COMPONENTS = ("btl_tcp", "oob_tcp")

LOOPBACK = "lo"


def under_mpirun(environ=os.environ) -> bool:
    """Whether this process was started by mpirun (MPI's transports are then already chosen)."""
    return "OMPI_COMM_WORLD_SIZE" in environ


def network_settings(interfaces: str | None, environ=os.environ) -> dict[str, str]:
    """The environment variables that restrict Open MPI's TCP traffic to ``interfaces`` (Open
    MPI's ``if_include`` syntax: interface names or CIDR networks, comma-separated), for each
    component whose interfaces the environment does not choose already (the user's own
    ``OMPI_MCA_<component>_if_include`` or ``_if_exclude`` win). ``None``: nothing (Open MPI's
    default: every interface but the loopback)."""
    if interfaces is None:
        return {}
    if not isinstance(interfaces, str) or not interfaces.strip():
        raise ValueError(f"FoamCoupling: interfaces must be Open MPI interface names or CIDR networks, "
                         f"comma-separated (e.g. 'lo' or 'eth0,192.168.0.0/16'), or None; got {interfaces!r}")
    settings = {}
    for component in _COMPONENTS:
        chosen = any(f"OMPI_MCA_{component}_if_{kind}" in environ for kind in ("include", "exclude"))
        if not chosen:
            settings[f"OMPI_MCA_{component}_if_include"] = interfaces
    return settings


def apply_network_settings(interfaces: str | None, environ=os.environ) -> dict[str, str]:
    """Put :func:`network_settings` in the environment before MPI starts; under mpirun (too late
    for this process) warn when mpirun was not given them. Returns the variables set."""
    settings = network_settings(interfaces, environ)
    if under_mpirun(environ):
        if settings:
            options = " ".join(f"--mca {name[len('OMPI_MCA_'):]} {value}" for name, value in settings.items())
            warnings.warn(f"FoamCoupling: under mpirun Open MPI's network is chosen by mpirun: add {options} to "
                          f"the mpirun command to keep the coupled run on interfaces={interfaces!r} (or give "
                          f"FoamCoupling interfaces=None for Open MPI's default)", RuntimeWarning, stacklevel=4)
        return {}
    environ.update(settings)
    return settings
