"""``python -m rancf``: the command line."""

import sys

from rancf.cli import main

sys.exit(main())
