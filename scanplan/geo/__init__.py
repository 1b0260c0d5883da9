"""The geography layer: the contract area, flight lines over it, terrain, and the files a
crew or a GIS opens (mission plan, KML, GeoJSON, photo-centre tables).

It sits above the numeric core, the rules and the norms and below the project layer
(tests/test_layers.py): it uses the field's libraries — shapely (geometry), pyproj (CRS),
pyogrio/GDAL (GIS files), rasterio (DEMs) — and never hand-written geometry, projections or
file parsers. Its results are the records of :mod:`scanplan.geo.layout`.
"""
