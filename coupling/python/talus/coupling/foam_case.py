"""Reading what the DEM side needs from an OpenFOAM case folder, and preparing the case folders
of Yade's examples (examples/openfoam, written for OpenFOAM 6) for Debian's OpenFOAM v1912.

Yade's ``FoamCoupling`` is given no case, fluid density or viscosity: the fluid ranks are started
in the case folder and read them there. Talus's engine, used with Yade's interface, reads them
from the same folder (the working directory) with :func:`case_settings`.

:func:`prepare_case` (also ``python3 -m talus.coupling.foam_case prepare CASE``) meshes and
decomposes such a case: ``blockMesh``, then ``decomposePar`` with the case's
``system/decomposeParDict`` bridged to v1912 where it has to be (see :func:`v1912_decompose_dict`).
"""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

__all__ = ["read_dict", "case_settings", "prepare_case", "v1912_decompose_dict", "find_solver", "YADE_SOLVERS"]

# Yade's solver names (controlDict `application` of its examples) -> Talus's solvers.
YADE_SOLVERS = {"icoFoamYade": "talusPointForceFoam", "pimpleFoamYade": "talusVolumeAveragedFoam"}

_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"


def find_solver(name: str) -> str:
    """Path of an OpenFOAM coupling solver: a path as given, else TALUS_FOAM_BIN/<name>, the
    build tree's or installation's bin/ folder, then PATH."""
    if os.sep in name:
        return name
    candidates = []
    if os.environ.get("TALUS_FOAM_BIN"):
        candidates.append(Path(os.environ["TALUS_FOAM_BIN"]) / name)
    import talus
    root = Path(talus.__file__).resolve().parents[1]
    candidates += [root.parent / "bin" / name, root / "bin" / name]
    for c in candidates:
        if c.is_file():
            return str(c)
    found = shutil.which(name)
    if found is None:
        raise FileNotFoundError(f"FoamCoupling: solver {name!r} not found (looked in "
                                f"{', '.join(map(str, candidates))} and PATH); build Talus with foam-solvers")
    return found


def _strip_comments(text: str) -> str:
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    return re.sub(r"//[^\n]*", " ", text)


def read_dict(path) -> dict[str, str]:
    """The top-level entries ``key value;`` of an OpenFOAM dictionary file (values as written,
    without the semicolon); sub-dictionaries are skipped (FoamFile's included)."""
    text = _strip_comments(Path(path).read_text(errors="replace"))
    entries, depth, start = {}, 0, 0
    statement = []
    for k, ch in enumerate(text):
        if ch == "{":
            if depth == 0:
                statement = []
            depth += 1
        elif ch == "}":
            depth -= 1
            start = k + 1
        elif depth == 0 and ch == ";":
            words = text[start:k].split(None, 1)
            if len(words) == 2:
                entries[words[0]] = words[1].strip()
            start = k + 1
    return entries


def _scalar(value: str, what: str) -> float:
    """The value of a scalar entry, with or without its dimensions ([1 -3 0 0 0 0 0] 1000)."""
    value = re.sub(r"\[[^\]]*\]", " ", value)
    numbers = re.findall(_NUMBER, value)
    if not numbers:
        raise ValueError(f"FoamCoupling: {what}: no number in {value!r}")
    return float(numbers[-1])


def _vector(value: str, what: str) -> tuple[float, float, float]:
    match = re.search(r"\(([^()]*)\)", value)
    numbers = re.findall(_NUMBER, match.group(1)) if match else []
    if len(numbers) != 3:
        raise ValueError(f"FoamCoupling: {what}: not a vector: {value!r}")
    return tuple(float(x) for x in numbers)


def case_settings(case) -> dict:
    """What the DEM side needs of a coupling case: ``rhoFluid`` and ``nu`` (transportProperties:
    ``rho``, Yade's ``fluidDensity`` or ``rho.<continuousPhaseName>``), ``gravity``
    (constant/g), ``application``, ``deltaT``, ``startTime`` and ``endTime`` (controlDict),
    ``nProcs`` (the decomposeParDict's numberOfSubdomains when the case is decomposed, else 1)."""
    case = Path(case)
    transport = read_dict(case / "constant" / "transportProperties")
    phase = transport.get("continuousPhaseName")
    for key in ("rho", "fluidDensity", f"rho.{phase}" if phase else None):
        if key and key in transport:
            rho = _scalar(transport[key], f"transportProperties {key}")
            break
    else:
        raise ValueError(f"FoamCoupling: {case}/constant/transportProperties has no fluid density "
                         "(rho, fluidDensity or rho.<continuousPhaseName>)")
    if "nu" not in transport:
        raise ValueError(f"FoamCoupling: {case}/constant/transportProperties has no nu")
    g = read_dict(case / "constant" / "g")
    control = read_dict(case / "system" / "controlDict")
    settings = dict(rhoFluid=rho, nu=_scalar(transport["nu"], "transportProperties nu"),
                    gravity=_vector(g.get("value", ""), "constant/g value"),
                    application=control.get("application", ""),
                    deltaT=_scalar(control.get("deltaT", "0"), "controlDict deltaT"),
                    startTime=_scalar(control.get("startTime", "0"), "controlDict startTime"),
                    endTime=_scalar(control["endTime"], "controlDict endTime") if "endTime" in control else None,
                    nProcs=1)
    if (case / "processor0").is_dir() and (case / "system" / "decomposeParDict").is_file():
        decompose = read_dict(case / "system" / "decomposeParDict")
        settings["nProcs"] = int(_scalar(decompose.get("numberOfSubdomains", "1"), "numberOfSubdomains"))
    return settings


def _foam_env() -> dict:
    env = dict(os.environ)
    env.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")
    return env


def _scotch_available() -> bool:
    """Debian's OpenFOAM v1912 ships scotchDecomp as its dummy stub (the real library, the one
    decomposePar needs for `method scotch`, is not in the package); ptscotch is real."""
    lib = Path("/usr/lib/libscotchDecomp.so")
    dummy = Path("/usr/lib/dummy/libscotchDecomp.so")
    if not lib.exists():
        return False
    return not (dummy.exists() and dummy.read_bytes() == lib.read_bytes())


def _case_info(case: Path) -> dict:
    out = subprocess.run([find_solver("talusCaseInfo"), "-case", str(case)], capture_output=True, text=True,
                         env=_foam_env(), timeout=120, check=True)
    return json.loads(out.stdout)


def v1912_decompose_dict(case) -> str | None:
    """The case's decomposeParDict as Debian's v1912 decomposePar reads it, or None if it reads
    it as it is. Two differences of Yade's examples are bridged:

    - ``strategies { optional }`` (a Scotch strategy string written as a keyword without value,
      which OpenFOAM 6 ignored): v1912 refuses the dictionary, so the entry is dropped;
    - ``method scotch`` with Debian's dummy scotchDecomp: replaced by ``method simple`` cutting
      the mesh into numberOfSubdomains slabs across the longest axis that has no cyclic patch
      (the coupling's periodic envelope needs every rank to hold whole periods)."""
    case = Path(case)
    path = case / "system" / "decomposeParDict"
    text = path.read_text()
    bridged = re.sub(r"\n[ \t]*strategies\s*\{[^{}]*\}", "\n", text)
    method = re.search(r"^\s*method\s+(\w+)\s*;", _strip_comments(bridged), flags=re.M)
    if method and method.group(1) == "scotch" and not _scotch_available():
        entries = read_dict(path)
        n = int(_scalar(entries.get("numberOfSubdomains", "1"), "numberOfSubdomains"))
        info = _case_info(case)
        low, high = info["bounds"]
        span = [h - l for l, h in zip(low, high)]
        periodic = set()
        for patch in info["patches"]:
            if patch["type"] == "cyclic" and "normal" in patch:
                periodic.add(max(range(3), key=lambda k: abs(patch["normal"][k])))
        axes = [k for k in range(3) if k not in periodic] or [0, 1, 2]
        axis = max(axes, key=lambda k: span[k])
        counts = ["1", "1", "1"]
        counts[axis] = str(n)
        bridged = re.sub(r"^(\s*method\s+)scotch(\s*;)", r"\1simple\2", bridged, flags=re.M)
        bridged += (f"\n// Talus: scotch is a dummy in Debian's OpenFOAM v1912: {n} slabs across axis {'xyz'[axis]}\n"
                    f"simpleCoeffs\n{{\n    n ({' '.join(counts)});\n    delta 0.001;\n}}\n")
    return None if bridged == text else bridged


def prepare_case(case, *, decompose: bool = True, log=None) -> Path:
    """Mesh (blockMesh) and decompose (decomposePar, if the case has a decomposeParDict and
    ``decompose``) a case folder in place, bridging its decomposeParDict to v1912 when needed
    (the bridged copy is written as ``system/decomposeParDict.v1912`` and passed with
    ``-decomposeParDict``; the case's own file is left as it is). Returns the case path."""
    case = Path(case).resolve()
    env = _foam_env()

    def run(command):
        done = subprocess.run(command, cwd=case, capture_output=True, text=True, env=env, timeout=600)
        name = Path(command[0]).name
        (case / f"log.{name}").write_text(done.stdout + done.stderr)
        if log:
            log(f"{' '.join(command)}: exit {done.returncode}")
        if done.returncode != 0:
            raise RuntimeError(f"{' '.join(command)} failed in {case} (see log.{name}):\n"
                               f"{(done.stdout + done.stderr)[-2000:]}")

    run(["blockMesh"])
    if decompose and (case / "system" / "decomposeParDict").is_file():
        for old in case.glob("processor*"):
            shutil.rmtree(old)
        bridged = v1912_decompose_dict(case)
        if bridged is None:
            run(["decomposePar"])
        else:
            (case / "system" / "decomposeParDict.v1912").write_text(bridged)
            run(["decomposePar", "-decomposeParDict", "system/decomposeParDict.v1912"])
    return case


def _main(argv: list[str]) -> int:
    if len(argv) != 2 or argv[0] != "prepare":
        print("usage: python3 -m talus.coupling.foam_case prepare CASE   (blockMesh + decomposePar, "
              "bridged to OpenFOAM v1912)", file=sys.stderr)
        return 2
    prepare_case(argv[1], log=print)
    return 0


if __name__ == "__main__":
    sys.exit(_main(sys.argv[1:]))
