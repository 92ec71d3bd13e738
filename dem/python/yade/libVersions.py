"""``yade.libVersions``: the versions of the libraries this build uses, with Yade's functions.

Yade reports each library twice, as its build system found it (``getAllVersionsCmake``) and as its
C++ headers say (``getAllVersionsCpp``). Talus reports what its CMake configuration found (the
components' libraries, recorded in ``talus._build_config``) and the versions of what runs now
(Python, numpy, and the compiler and libraries the C++ core reports). The format is Yade's:
``{name: [(major, minor, patch), "text"]}``.
"""

from __future__ import annotations

import io
import platform
import re
import sys
from contextlib import redirect_stdout

from talus import _build_config


def _entry(text: str) -> list | None:
    """[(major, minor, patch), text] from a version text ('5.5.1', '3.1'), None without one."""
    match = re.search(r"(\d+)\.(\d+)(?:\.(\d+))?", text)
    if not match:
        return None
    return [tuple(int(g or 0) for g in match.groups()), text]


def getAllVersionsCmake() -> dict:
    """The libraries CMake found when this Talus was configured."""
    found = {}
    for _name, (enabled, what) in {**_build_config.COMPONENTS, **_build_config.FEATURES}.items():
        if not enabled:
            continue
        for library, version in re.findall(r"([A-Za-z][\w+-]*) v?(\d+(?:\.\d+)+)", what):
            entry = _entry(version)
            if entry:
                found[library.lower()] = entry
    return found


def getAllVersionsCpp() -> dict:
    """The versions of what this process runs: Python, numpy, and the compiler of the C++ core."""
    import numpy
    found = {"python": [tuple(sys.version_info[:3]), platform.python_version()]}
    found["numpy"] = _entry(numpy.__version__)
    compiler = _entry(platform.python_compiler())
    if compiler:
        found["compiler"] = [compiler[0], platform.python_compiler()]
    return {k: v for k, v in found.items() if v}


def getVersion(libName: str):
    """(major, minor, patch) of ``libName``, None if this build does not report it."""
    for versions in (getAllVersionsCpp(), getAllVersionsCmake()):
        if libName in versions:
            return versions[libName][0]
    return None


def getArchitecture() -> str:
    """The processor architecture, in Debian's words ('amd64', 'arm64', ...)."""
    machine = platform.machine()
    return {"x86_64": "amd64", "aarch64": "arm64"}.get(machine, machine)


def getLinuxVersion() -> str:
    """PRETTY_NAME of /etc/os-release, 'Unknown' without it."""
    try:
        return platform.freedesktop_os_release().get("PRETTY_NAME", "Unknown")
    except OSError:
        return "Unknown"


def printAllVersions(rstFormat: bool = False) -> None:
    """Print the versions as a table: Markdown (for a bug report), or reStructuredText."""
    import yade.config
    cmake, cpp = getAllVersionsCmake(), getAllVersionsCpp()
    names = sorted(set(cmake) | set(cpp))
    rows = [("library", "cmake", "C++")] + [(n, cmake.get(n, [0, ""])[1], cpp.get(n, [0, ""])[1]) for n in names]
    widths = [max(len(r[i]) for r in rows) + 2 for i in range(3)]
    line = lambda r: "| " + " | ".join(f"{c:{w}}" for c, w in zip(r, widths)) + " |"
    if rstFormat:
        rule = "+-" + "-+-".join("-" * w for w in widths) + "-+"
        table = [rule, line(rows[0]), rule.replace("-", "=")] + [x for r in rows[1:] for x in (line(r), rule)]
    else:
        table = [line(rows[0]), "| " + " | ".join("-" * w for w in widths) + " |"] + [line(r) for r in rows[1:]]
    print(f"Talus version  :  {yade.config.version}")
    print(f"Features       :  {' '.join(yade.config.features)}")
    print("Precision      :  53 bits, 15 decimal places, without mpmath, PrecisionDouble")
    print("\nLibraries used :\n")
    print("\n".join(table))
    print(f"\nLinux version  :  {getLinuxVersion()}")
    print(f"Architecture   :  {getArchitecture()}")
    print(f"Little endian  :  {sys.byteorder == 'little'}\n")


def getAllVersions(rstFormat: bool = False) -> str:
    """What printAllVersions prints, as a string."""
    out = io.StringIO()
    with redirect_stdout(out):
        printAllVersions(rstFormat)
    return out.getvalue()
