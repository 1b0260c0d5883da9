"""Everything scanplan writes in words, in English and Russian: the base-layer catalogues.

Nothing here imports a layer above the base (``tests/test_layers.py``): the engines
(``rules``, ``geo``, ``project``), the reports and the command line all take their words
and number formats from this package.

Modules
-------
messages
    The engine's sentences as coded messages (:class:`~scanplan.i18n.messages.Message`,
    :data:`~scanplan.i18n.messages.MESSAGES`), their template rules (numbers, plurals,
    scales, lists), :func:`~scanplan.i18n.messages.scale_text` and
    :func:`~scanplan.i18n.messages.plural`. The sentences of one subject live in a part
    of their own, merged into ``MESSAGES``: ``messages_archive`` (archive photos),
    ``messages_terrain`` (the terrain), ``messages_outputs`` (files not written),
    ``messages_uav`` (a digital block's height accuracy, the altitude ceiling, airspace)
    and ``messages_site`` (where the area is).
labels
    The report labels, one key per concept (:data:`~scanplan.i18n.labels.LABELS`,
    :func:`~scanplan.i18n.labels.t`), with the wording of a manned aerial survey
    (:data:`~scanplan.i18n.labels.AIRCRAFT_LABELS`). Its parts, merged into ``LABELS``:
    ``labels_more`` (documents fit to sign, the terminal summary, the survey design
    sheet, terrain) and ``labels_geo`` (the map page, strips, exported files).
labels_cli
    The templates of the ``scan``/``uav`` terminal reports and of the catalogue
    listings (:data:`~scanplan.i18n.labels_cli.CLI`,
    :func:`~scanplan.i18n.labels_cli.cli_text`).
numbers
    :class:`~scanplan.i18n.numbers.Numbers`: every number a document prints, in one
    locale's convention (decimal comma and no-break-space thousands in Russian).

Notes
-----
To add a language string:

- an engine sentence: a code in ``MESSAGES`` (or the part of its subject) with an
  ``"en"`` and a ``"ru"`` template of the same fields; the engine returns
  ``Message(code, **params)``;
- a report label: a key in both ``"en"`` and ``"ru"`` of the catalogue of its concept
  (``labels``, ``labels_more``, ``labels_geo``), named by what it means, not by the
  renderer that prints it (``ground_speed``, not ``xlsx_ground_speed``): before adding
  one, look for a key that already holds the same words and use it — two keys with the
  same English and Russian text fail ``tests/test_i18n.py``; writers call
  ``t(key, locale)``;
- a terminal-report or listing template: a key in both languages of ``CLI``.

Both languages must hold the same keys and fields (``tests/test_messages.py``,
``tests/test_labels_one_word.py``); an English label has one Russian translation.
"""

from typing import Any


def catalogues() -> dict[str, dict[str, dict[str, Any]]]:
    """Every word catalogue, by name: each ``{locale: {key: text}}`` (one shape), keyed by
    concept — the documents' labels (``labels``, with the carrier-specific
    ``aircraft`` wording), the terminal's templates and words (``terminal``), the page of
    ``scanplan serve`` (``page``) and the comments of the project file ``scanplan init``
    writes (``init``).

    Returns
    -------
    dict
        Name → catalogue.
    """
    from .labels import AIRCRAFT_LABELS, LABELS
    from .labels_cli import CLI
    from .labels_init import INIT
    from .labels_page import PAGE

    return {"labels": LABELS, "aircraft": AIRCRAFT_LABELS, "terminal": CLI, "page": PAGE,
            "init": INIT}
