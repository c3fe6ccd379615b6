"""python -m arcus.cli: the arcus command."""
import sys

from . import main

sys.exit(main())
