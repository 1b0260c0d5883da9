"""scanplan — photogrammetric scan and interpretation planner.

The Instruction GKINP (GNTA)-02-036-02 scan-pixel rules (with the corrected P_R
coefficient), seed 001's recognition model, and (for UAV cameras) the MTF ground
resolution of seed 000, combined into a plan for a mapping contract.
"""

from ._version import __version__
from .errors import InputError
from .norms import load_norm_set
from .project.api import scan

__all__ = ["InputError", "__version__", "load_norm_set", "scan"]
