"""Time series of a run and their plots: Yade's ``plot`` module.

    from talus import plot
    plot.plots = {"i": ("unbalanced", None, "kinetic"), "t": ("sz",)}
    O.engines = O.engines + [PyRunner(command=lambda: plot.addData(i=O.iter, t=O.time,
                                      unbalanced=unbalancedForce(), kinetic=..., sz=...), iterPeriod=100)]
    O.run(10000)
    plot.saveDataTxt("run.txt")        # or run.csv, run.txt.bz2, run.txt.gz
    plot.saveDataHdf5("run.h5")
    plot.savePlot("run.png")          # or fig = plot.plot(noShow=True)

``data`` maps each name to its list of values, one entry per ``addData`` call: a name first
given late is padded with NaN in the rows before, a name missing from a call gets NaN in that
row, so every column has the same length (as in Yade).

``plots`` maps an x name to the y names plotted against it, one subplot per x name. Spaces
around an x name are ignored when looking up data, so the same x can have several subplots
(``"t"``, ``"t "``). In a y list, ``None`` moves the following names to a right-hand axis, a name
may come with a matplotlib format (``("unbalanced", "go")``), and a callable (``O.energy.keys``)
is called for a list of names.

Files are written atomically (temporary file, then rename): an interrupted save never leaves a
half-written file in place of a good one.
"""

from __future__ import annotations

import bz2
import functools
import gzip
import math
import numbers
import os
import sys
import types
from typing import Callable, Iterable

import numpy as np

from talus.atomic import write_atomically

__all__ = ["data", "plots", "labels", "addData", "addAutoData", "reset", "resetData", "plot", "savePlot",
           "saveDataTxt", "saveDataHdf5", "loadDataTxt", "saveGnuplot"]

data: dict[str, list[float]] = {}
plots: dict[str, Iterable] = {}
labels: dict[str, str] = {}  # axis and legend text of a name, when it should read otherwise

# Yade's settings of its live plot window. Talus draws on demand (plot, savePlot), so they are
# kept for scripts that set them and change nothing.
live = True
liveInterval = 1
autozoom = True


def _rows() -> int:
    return max((len(column) for column in data.values()), default=0)


def addData(*dicts: dict, **values) -> None:
    """Append one row: ``addData(i=O.iter, unbalanced=..., **O.energy)``. Positional arguments
    are dicts merged into the row (later ones win, keywords last). Numbers are kept as given
    (an int stays an int, as in Yade); a Vector2, Vector3 or Matrix3 gives one column per
    component, named with Yade's suffixes (``f=Vector3(...)``: ``f_x``, ``f_y``, ``f_z``;
    Matrix3: ``_xx``, ``_xy``, ...)."""
    row: dict[str, float] = {}
    for d in dicts:
        row.update(d)
    row.update(values)
    before = _rows()
    for name, value in _components(row).items():
        data.setdefault(name, [math.nan] * before).append(value)
    for column in data.values():
        if len(column) == before:
            column.append(math.nan)


def _components(row: dict) -> dict:
    """The row with each vector or matrix value split into its components' columns (Yade's
    componentSuffixes), each value checked to be a number."""
    from talus.dem.base.linalg import Matrix3, Vector2, Vector3
    suffixes = {Vector2: "xy", Vector3: "xyz"}
    out = {}
    for name, value in row.items():
        if type(value) in suffixes:
            out.update((f"{name}_{s}", value[k]) for k, s in enumerate(suffixes[type(value)]))
        elif type(value) is Matrix3:
            out.update((f"{name}_{'xyz'[i]}{'xyz'[j]}", value[i, j]) for i in range(3) for j in range(3))
        elif isinstance(value, numbers.Number) and not isinstance(value, complex):
            out[name] = value
        else:
            try:
                out[name] = float(value)   # numpy 0-d arrays and other numbers that convert
            except (TypeError, ValueError):
                raise TypeError(f"plot.addData: value of {name!r} is not a number, Vector2, Vector3 or Matrix3: "
                                f"{value!r}") from None
    return out


def addAutoData() -> None:
    """Append one row evaluated from ``plots`` (Yade's addAutoData): each x name and each y
    entry is an expression or ``"name=expression"`` evaluated in the script's namespace, or a
    mapping (``O.energy``) whose items are added; ``None`` (the axis switch) is skipped and a
    ``(entry, format)`` pair gives its entry. An expression that raises adds nothing and prints
    Yade's warning, as Yade does."""
    namespace = {**_script_names(), **vars(sys.modules["__main__"])}
    row = {}

    def evaluate(entry: str):
        name, expr = entry.split("=", 1) if "=" in entry else (entry, entry)
        try:
            row[name] = eval(expr, namespace)
        except Exception:
            print(f"WARN: ignoring exception raised while evaluating auto-column `{expr}'"
                  + ("" if name == expr else f" ({name})") + ".")

    for x, ys in plots.items():
        evaluate(x.strip())
        for y in ys if isinstance(ys, (tuple, list)) else (ys,):
            if isinstance(y, (tuple, list)):
                y = y[0]
            if y is None:
                continue
            if hasattr(y, "keys"):
                row.update(dict(y))
            else:
                evaluate(y)
    addData(row)


_script_namespaces: list[Callable[[], dict]] = []


def add_script_names(namespace: Callable[[], dict]) -> None:
    """Let addAutoData's expressions see the names ``namespace()`` returns (asked once, at the
    first addAutoData), under the script's own globals. The ``yade`` package registers Yade's
    script namespace, which Yade's plot module evaluates in; this module imports no scripting
    layer itself, so that the DEM can import it."""
    if not callable(namespace):
        raise TypeError(f"plot.add_script_names: namespace must be a function returning a dict, got {namespace!r}")
    _script_namespaces.append(functools.cache(namespace))


def _script_names() -> dict:
    names = {}
    for namespace in _script_namespaces:
        names.update(namespace())
    return names


def resetData() -> None:
    """Forget the recorded rows (keep ``plots``)."""
    data.clear()


def reset() -> None:
    """Forget the recorded rows and the plot layout."""
    data.clear()
    plots.clear()


def _recorded(name: str) -> list:
    key = name.strip()
    if key not in data:
        known = ", ".join(sorted(data)) or "none yet"
        raise KeyError(f"plot: no data named {key!r} (recorded: {known})")
    return data[key]


def _column(name: str) -> np.ndarray:
    return np.asarray(_recorded(name), dtype=float)


def _text(value) -> str:
    """A value as saveDataTxt writes it: an int as an int (Yade's str), any other number as a float."""
    return str(value) if isinstance(value, numbers.Integral) else str(float(value))


def _y_entries(spec) -> list[tuple[str | None, str]]:
    """Expand a y list into (name or None for the axis switch, format)."""
    if isinstance(spec, str) or callable(spec):
        spec = (spec,)
    entries: list[tuple[str | None, str]] = []
    for item in spec:
        if item is None:
            entries.append((None, ""))
        elif callable(item):
            entries.extend((str(name), "") for name in item())
        elif isinstance(item, str):
            entries.append((item, ""))
        elif isinstance(item, (tuple, list)) and len(item) == 2 and isinstance(item[0], str):
            entries.append((item[0], str(item[1])))
        else:
            raise TypeError(f"plot.plots: cannot plot {item!r}; give a name, (name, format), None or a callable")
    return entries


def plot(noShow: bool = False, subPlots: bool = True):
    """Draw ``plots`` from ``data`` and return the matplotlib figure; shown on screen unless
    ``noShow`` or there is no display. ``subPlots=False`` gives one figure per x name (the list
    of figures is returned)."""
    import matplotlib
    if noShow or not os.environ.get("DISPLAY") or not _writes():    # (under mpirun: process 0 shows it)
        noShow = True
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    if not plots:
        raise ValueError("plot.plot: plot.plots is empty; set e.g. plot.plots = {'i': ('unbalanced',)}")
    # Yade's scripts open the (live) plot before the run: with no rows yet the axes come out
    # empty, and the names are checked once there is data.
    empty = _rows() == 0
    n = len(plots)
    figures = []
    if subPlots:
        figure, axes = plt.subplots(n, 1, figsize=(7, 3.2 * n), squeeze=False)
        axes_list = [row[0] for row in axes]
        figures.append(figure)
    else:
        axes_list = []
        for _ in range(n):
            figure, ax = plt.subplots(figsize=(7, 3.6))
            figures.append(figure)
            axes_list.append(ax)
    for ax, (x_name, y_spec) in zip(axes_list, plots.items()):
        x = None if empty else _column(x_name)
        target, lines = ax, []
        for name, fmt in _y_entries(y_spec):
            if name is None:
                target = ax.twinx()
                continue
            if not empty:
                lines += target.plot(x, _column(name), fmt or "-", label=labels.get(name.strip(), name.strip()))
        ax.set_xlabel(labels.get(x_name.strip(), x_name.strip()))
        ax.grid(True, alpha=0.3)
        if lines:
            ax.legend(lines, [line.get_label() for line in lines], loc="best", fontsize="small")
    for figure in figures:
        figure.tight_layout()
    if not noShow:
        plt.show()
    return figures[0] if subPlots else figures


def _writes() -> bool:
    """Whether this process writes the files: under ``mpirun -np N talus run`` every process runs
    the script (and adds the same rows: the measurements give the whole scene's value on every
    process), process 0 writes them; any process of a run of its own."""
    from talus.dem import distributed
    return not distributed.ACTIVE or distributed.rank() == 0


def savePlot(path: str | os.PathLike, dpi: int = 120) -> None:
    """Draw ``plots`` (all subplots in one figure) and write it as an image (PNG by suffix);
    under mpirun, process 0 writes it."""
    import matplotlib.pyplot as plt
    if not _writes():
        return
    figure = plot(noShow=True)
    write_atomically(path, lambda tmp: figure.savefig(tmp, dpi=dpi, format=os.path.splitext(str(path))[1][1:] or "png"))
    plt.close(figure)


def _open_text(path: str, mode: str):
    if path.endswith(".bz2"):
        return bz2.open(path, mode + "t")
    if path.endswith(".gz"):
        return gzip.open(path, mode + "t")
    return open(path, mode, encoding="utf-8")


def saveDataTxt(fileName: str | os.PathLike, vars: Iterable[str] | None = None, headers=None) -> None:
    """Write ``data`` as text columns in Yade's format::

        # radius=<TAB>0.1          one line per entry of ``headers`` (a dict, or a module such as
                                   yade.params.table), if given
        # i<TAB><TAB>z             the names (all, sorted, or ``vars`` in their order)
        0.0<TAB>0.5                one row per addData

    comma-separated with a plain header when the name ends in ``.csv``; compressed when it ends
    in ``.bz2`` or ``.gz``. Under mpirun, process 0 writes it."""
    if not _writes():
        return
    names = list(vars) if vars is not None else sorted(data)
    columns = [_recorded(name) for name in names]
    if isinstance(headers, types.ModuleType):
        headers = {k: getattr(headers, k) for k in getattr(headers, "__all__", ())}
    name = os.fspath(fileName)
    csv = name.removesuffix(".bz2").removesuffix(".gz").endswith(".csv")

    def write(tmp: str):
        # The compression is chosen from the real name, not the temporary one.
        opener = bz2.open if name.endswith(".bz2") else gzip.open if name.endswith(".gz") else None
        with (opener(tmp, "wt") if opener else open(tmp, "w", encoding="utf-8")) as out:
            for key, value in (headers or {}).items():
                out.write(f"# {key}=\t{value}\n")
            out.write((",".join(names) if csv else "# " + "\t\t".join(names)) + "\n")
            for row in zip(*columns):
                out.write((",".join if csv else "\t".join)(_text(v) for v in row) + "\n")

    write_atomically(name, write)


def loadDataTxt(fileName: str | os.PathLike) -> dict[str, list[float]]:
    """Read a file written by ``saveDataTxt`` into ``data`` (replacing it) and return it; the
    header lines (``# name=<TAB>value``) are skipped."""
    name = os.fspath(fileName)
    with _open_text(name, "r") as source:
        header = source.readline()
        while header.startswith("#") and "=" in header:
            header = source.readline()
        csv = not header.startswith("#")
        names = header.lstrip("#").strip().split("," if csv else None)
        rows = [line.split("," if csv else None) for line in source if line.strip()]
    for number, row in enumerate(rows, start=2):
        if len(row) != len(names):
            raise ValueError(f"{name}, line {number}: {len(row)} values for {len(names)} columns")
    data.clear()
    for k, column in enumerate(names):
        data[column] = [float(row[k]) for row in rows]
    return data


def saveDataHdf5(fileName: str | os.PathLike) -> None:
    """Write ``data`` to an HDF5 file, one float64 dataset per name (needs h5py); under mpirun,
    process 0 writes it."""
    import h5py
    if not _writes():
        return

    def write(tmp: str):
        with h5py.File(tmp, "w") as out:
            for column in sorted(data):
                out.create_dataset(column, data=_column(column))

    write_atomically(fileName, write)


def saveGnuplot(baseName: str, term: str = "wxt", extension: str | None = None, timestamp: bool = False,
                comment: str | None = None, title: str | None = None, varData: bool = False) -> str:
    """Yade's saveGnuplot: ``data`` to ``baseName.data.bz2`` and a gnuplot script
    ``baseName.gnuplot`` drawing ``plots`` (one plot per x name; ``None`` in a y list puts the
    names after it on the right-hand axis). ``term`` and ``extension`` choose gnuplot's terminal
    and, for a file terminal, the images' suffix. Returns the script's name."""
    import time as _time
    base = baseName + (_time.strftime("_%Y%m%d_%H%M") if timestamp else "")
    data_file = base + ".data.bz2"
    saveDataTxt(data_file)
    names = sorted(data)
    lines = [f"# gnuplot script written by Talus for {base}" + (f": {comment}" if comment else ""),
             f"set term {term}", "set grid", "set datafile missing 'nan'"]
    for k, (x_name, y_spec) in enumerate(plots.items()):
        x = x_name.strip()
        _column(x)   # an unknown name is an error naming it
        if extension:
            lines.append(f"set output '{base}.{x}.{k}.{extension}'")
        if title:
            lines.append(f"set title '{title}'")
        lines += ["set xlabel '" + labels.get(x, x) + "'", "set y2tics", "set ytics nomirror"]
        curves, axis = [], "x1y1"
        for name, _fmt in _y_entries(y_spec):
            if name is None:
                axis = "x1y2"
                continue
            _column(name)
            curves.append(f"'< bzcat {data_file}' using {names.index(x) + 1}:{names.index(name.strip()) + 1} "
                          f"title '{labels.get(name.strip(), name.strip())}' with lines axes {axis}")
        lines.append("plot " + ", ".join(curves))
        if not extension:
            lines.append("pause -1")
    script = base + ".gnuplot"

    def write(tmp: str):
        with open(tmp, "w", encoding="utf-8") as out:
            out.write("\n".join(lines) + "\n")

    if _writes():
        write_atomically(script, write)
    return script
