"""`python -m mechkit`: the command line."""

import sys

from mechkit.cli import main

sys.exit(main())
