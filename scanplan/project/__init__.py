"""The project layer: what a user gives scanplan and what one run of it computes.

- :mod:`~scanplan.project.file` — project files (TOML), their keys and validation;
- :mod:`~scanplan.project.spec` — a project turned into a specification (rules + norms);
- :mod:`~scanplan.project.api` — the Python functions behind the CLI (``scan``, ``uav``);
- :mod:`~scanplan.project.archive` — archive (already flown) photos;
- :mod:`~scanplan.project.cameras` — the camera catalogue and its import.
"""
