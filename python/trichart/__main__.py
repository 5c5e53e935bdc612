"""python3 -m trichart: the TriChart command line."""
import sys

from .cli import main

sys.exit(main())
