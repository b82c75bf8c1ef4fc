"""`python -m sweeplib`: the bench/sweep command line (cli.py)."""
import sys

from .cli import main

sys.exit(main())
