"""One concept, one key: no two report labels hold the same words.

A label is keyed by what it means (``ground_speed``), not by the renderer that prints it
(``xlsx_…``, ``pdf_…``, ``term_…``): two keys with the same English and the same Russian
text — and the same wording for a manned aircraft, if any — are one concept under two
names, and fail here. (That one English label has one Russian translation is
``tests/test_labels_one_word.py``.)
"""

from __future__ import annotations

from collections import defaultdict

from scanplan.i18n.labels import AIRCRAFT_LABELS, LABELS
from scanplan.i18n.labels_cli import CLI

# Duplicates not merged yet (none: every label key is written out where it is used, a
# field's label through an explicit mapping, never built at run time). Only ever shrinks.
KNOWN: set[tuple[str, ...]] = set()


def duplicate_keys(catalogue: dict[str, dict[str, str]],
                   aircraft: dict[str, dict[str, str]] | None = None) -> set[tuple[str, ...]]:
    """The groups of keys of ``catalogue`` that hold the same English and Russian text (and
    the same ``aircraft`` wording), each sorted."""
    aircraft = aircraft or {"en": {}, "ru": {}}
    keys: dict[tuple, list[str]] = defaultdict(list)
    for key, en in catalogue["en"].items():
        words = (en, catalogue["ru"][key], aircraft["en"].get(key), aircraft["ru"].get(key))
        keys[words].append(key)
    return {tuple(sorted(group)) for group in keys.values() if len(group) > 1}


def test_one_concept_one_key():
    found = duplicate_keys(LABELS, AIRCRAFT_LABELS) | duplicate_keys(CLI)
    assert found - KNOWN == set(), "merge these keys into one concept key"
    assert KNOWN - found == set(), "merged: drop them from KNOWN"


def test_a_duplicate_is_found():
    labels = {loc: dict(words) for loc, words in LABELS.items()}
    labels["en"]["xlsx_copy_of_map_scale"] = labels["en"]["map_scale"]
    labels["ru"]["xlsx_copy_of_map_scale"] = labels["ru"]["map_scale"]
    assert ("map_scale", "xlsx_copy_of_map_scale") in duplicate_keys(labels, AIRCRAFT_LABELS)
    labels["ru"]["xlsx_copy_of_map_scale"] += " (другой)"  # other Russian words: two concepts
    assert not any("xlsx_copy_of_map_scale" in g for g in duplicate_keys(labels))


def test_the_aircraft_wording_tells_keys_apart():
    # "UAV" on the sheet tab and in the comparison's header are worded apart for an aircraft
    labels = {"en": {"a": "UAV", "b": "UAV"}, "ru": {"a": "БПЛА", "b": "БПЛА"}}
    assert duplicate_keys(labels) == {("a", "b")}
    assert duplicate_keys(labels, {"en": {"a": "Aerial survey"}, "ru": {}}) == set()


def test_a_crs_name_reads_the_same_in_the_terminal_and_the_documents():
    """Bug: the Russian terminal said ``WGS 84 / UTM, зона 37N`` and the PDF and the page
    ``WGS 84 / UTM зона 37 с. ш.`` for the same system (two translators). One function
    says a name in Russian; a name it cannot say leaves the EPSG code alone."""
    from types import SimpleNamespace

    from scanplan.i18n.labels_geo import crs_name
    from scanplan.reports.mapview import area_crs_text
    from scanplan.reports.text import format_area

    assert crs_name("WGS 84 / UTM zone 37N", "ru") == "WGS 84 / UTM зона 37\u00a0с.\u00a0ш."
    assert crs_name("WGS 84 / UTM zone 19S", "ru") == "WGS 84 / UTM зона 19\u00a0ю.\u00a0ш."
    assert crs_name("Pulkovo 1942 / Gauss-Kruger zone 7", "ru") == (
        "Пулково 1942 / Гаусса — Крюгера зона 7")
    assert crs_name("NAD83 / New York Long Island (ftUS)", "ru") == ""
    assert crs_name("WGS 84 / UTM zone 37N", "en") == "WGS 84 / UTM zone 37N"
    for name, code in (("WGS 84 / UTM zone 37N", "EPSG:32637"),
                       ("NAD83 / New York Long Island (ftUS)", "EPSG:2263")):
        area = SimpleNamespace(
            plan_crs=code, plan_crs_name=name, georeferenced=True, source_file="a.kml",
            source_feature="A", source_layer="", source="a.kml", area_km2=1.0,
            perimeter_km=4.0)
        document = area_crs_text(area, "ru")
        line = format_area(area, "ru").replace("\n", " ")
        said = crs_name(name, "ru") or code
        assert document.endswith(said) and line.endswith(f", {said}"), (document, line)
