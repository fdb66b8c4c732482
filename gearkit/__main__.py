"""``python -m gearkit``: the same command line as ``gearkit``."""
import sys

from gearkit.cli import main

sys.exit(main())
