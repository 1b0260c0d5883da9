"""The numeric core: pure numpy, no files, no norms, no reports.

- :mod:`~scanplan.core.formulas` — the Instruction's scan-pixel formulas and the recognition
  model, each citing its seed equation;
- :mod:`~scanplan.core.stereo` — height accuracy of a digital block (the stereo normal case);
- :mod:`~scanplan.core.domains` — the allowed range of every input;
- :mod:`~scanplan.core.checks` — the array checks every formula makes of its inputs (finite,
  positive, non-negative, in a range), raising an error that names the input;
- :mod:`~scanplan.core.flight` — block geometry: bases, strips, photos, overlaps, flight time;
- :mod:`~scanplan.core.orientation` — image orientation (landscape/portrait) of a UAV frame;
- :mod:`~scanplan.core.mtf` — the camera's MTF chain and its ground resolution.

Layers above (rules, norms, project, geo, reports, cli) import from here; nothing here imports
from them (tests/test_layers.py).
"""
