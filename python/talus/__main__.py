"""``python -m talus`` is the ``talus`` command."""
import sys

from talus.cli import main

sys.exit(main())
