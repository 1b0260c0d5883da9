"""``scanplan serve``: a local web page where a plan is made on a map.

The page (``static/``) holds no engine: it sends the project, as the tables of a project
file, to the JSON API (:mod:`scanplan.web.app`), which plans it exactly as
``scanplan plan`` plans the same project file (:mod:`scanplan.web.jobs`) in a worker
process with a time limit (:mod:`scanplan.web.worker`). Uploaded area and DEM files are
kept in a temporary store (:mod:`scanplan.web.uploads`) and read by the same readers, with
the same guards, as the command line's. The project downloads as a TOML project file
(:mod:`scanplan.web.tomlfile`) that ``scanplan plan`` runs.

Nothing here is imported by ``import scanplan``; the web framework is imported only by
``scanplan serve`` and :func:`scanplan.web.app.create_app`.
"""
