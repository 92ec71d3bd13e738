"""Shared by the drop-in modules: Yade's FEMxDEM examples are Python 2 scripts that open their
output with ``file(...)``; Python 3 has no such builtin, so the examples stop at their first
output (under Yade too). The drop-ins give ``file`` = ``open`` to the scripts that import them."""
import builtins

if not hasattr(builtins, "file"):
    builtins.file = open
