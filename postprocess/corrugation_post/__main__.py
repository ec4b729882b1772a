"""Entry point for ``python -m corrugation_post``."""

import sys

from .cli import main

sys.exit(main())
