"""The project layer: what a user gives scanplan and what one run of it computes.

- :mod:`~scanplan.project.inputs` — the input registry: every key, option and keyword;
- :mod:`~scanplan.project.keys` — the keys of a project file and the checks of a value's type;
- :mod:`~scanplan.project.file` — project files (TOML), read and checked;
- :mod:`~scanplan.project.model` — a project file parsed once into typed sections, every
  value in its registry domain (what the specification and the reports read);
- :mod:`~scanplan.project.spec` — a project turned into a specification (rules + norms),
  whose records are in :mod:`~scanplan.project.results`;
- :mod:`~scanplan.project.jobs` — the Python functions behind the CLI (``scan``, ``uav``);
- :mod:`~scanplan.project.archive` — archive (already flown) photos;
- :mod:`~scanplan.project.cameras` — the camera catalogue and its import.
"""
