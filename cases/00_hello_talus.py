"""Case 00: hello Talus — the toolchain check every newcomer runs first.

Run:    build/bin/talus run cases/00_hello_talus.py
Checks: the talus package imports from the build tree, its compiled core reports the same version
        as the Python layer, and the components this build has are listed with the reason for
        any that is off. Exits non-zero if the compiled core and the package disagree.
"""
import talus
from talus import _dem

# 1. The version of the Python layer and of the compiled core (they must agree).
print(f"Talus {talus.__version__} (compiled core {_dem.version()})")

# 2. What this build contains, as the configure step decided it.
info = talus.build_info()
for kind in ("components", "features"):
    print(f"{kind}:")
    for name, (on, note) in info[kind].items():
        print(f"  {name:<14}{'ON ' if on else 'OFF'}  {note}")

# 3. The C++ table and the Python table come from the same configure step.
cxx = {(kind + "s", name): on for kind, name, on, _note in _dem.build_config()}
py = {(kind, name): on for kind, table in info.items() for name, (on, _n) in table.items()}
if cxx != py:
    raise SystemExit(f"component tables disagree: C++ {cxx} vs Python {py}")
print("toolchain OK")
