"""python -m hertz: the hertz command."""

import sys

from .cli import main

sys.exit(main())
