"""The UAV rules engine under its former name: :mod:`scanplan.rules.uav` (this module *is*
that module, so imports and attributes of ``scanplan.uav`` keep working)."""

import sys

from .rules import uav as _uav

sys.modules[__name__] = _uav
