"""Case 00: hello Talus -- the toolchain check, the same as `build/bin/talus info`.

Run:    build/bin/talus run cases/00_hello_talus.py
Checks: the talus package imports from the build tree, its compiled core reports the same version
        as the Python layer and the same component table, and the components this build has are
        listed with the reason for any that is off. Exits non-zero if the compiled core and the
        package disagree.
"""
from talus.cli import main

raise SystemExit(main(["info"]))
