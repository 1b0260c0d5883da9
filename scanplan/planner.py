"""The film rules engine under its former name: :mod:`scanplan.rules.film` (this module *is*
that module, so imports and attributes of ``scanplan.planner`` keep working)."""

import sys

from .rules import film as _film

sys.modules[__name__] = _film
