"""Post-processing of corrugation run files: wear maps, loads, traction snapshots, comparisons.

Command line: ``corrugation-post {figures,compare,check,...} ...`` (or ``python -m corrugation_post``)
(see ``corrugation-post --help``).
"""

from .io import Run, RunFileError, open_group

__all__ = ["Run", "RunFileError", "open_group"]
__version__ = "0.1.0"
