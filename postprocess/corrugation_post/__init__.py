"""Post-processing of corrugation run files: wear maps, loads, traction snapshots, comparisons.

Command line: ``python -m corrugation_post {figures,compare,check} ...``
(see ``python -m corrugation_post --help``).
"""

from .io import Run, RunFileError, open_group

__all__ = ["Run", "RunFileError", "open_group"]
__version__ = "0.1.0"
