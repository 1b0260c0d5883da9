"""The engine's sentences about archive photos: the photo scale is given, not
chosen. Part of the message catalogue: :data:`scanplan.i18n.messages.MESSAGES` merges them (same
template rules, see :mod:`scanplan.i18n.messages`). Plain data; no I/O (base module)."""

from __future__ import annotations

ARCHIVE: dict[str, dict[str, str]] = {
    "spec.film_archive": {
        "en": "the photos exist at {scale:scale} (archive photos; the scale is given, not "
              "chosen): scan them at {pixel:.1f} µm. {explanation}",
        "ru": "Снимки уже получены в масштабе {scale:scale} (архивные снимки; масштаб задан, "
              "а не выбирается): сканировать их с пикселем {pixel:.1f}~мкм. {explanation}",
    },
    "spec.film_archive_uninterpretable": {
        "en": "the photos exist at {scale:scale} (archive photos; the scale is given, not "
              "chosen): scan them at {pixel:.1f} µm, where {cid} ({name}) binds. The "
              "interpretation pixel P_D ({pd:.1f} µm) is finer than P_R and is not used: a "
              "finer scan adds no detail the photos do not carry. The map's objects "
              "({objects}) cannot be interpreted on these photos (see the warnings).",
        "ru": "Снимки уже получены в масштабе {scale:scale} (архивные снимки; масштаб задан, "
              "а не выбирается): сканировать их с пикселем {pixel:.1f}~мкм, который определяет "
              "условие {cid} ({name}). Пиксель дешифрирования P_D ({pd:.1f}~мкм) мельче P_R и "
              "не применяется: более мелкий пиксель не добавит деталей, которых нет на "
              "снимках. Объекты «{objects}» по этим снимкам не дешифрируются (см. "
              "предупреждения).",
    },
    "archive_not_interpretable": {
        "en": "on the {scale:scale} photos {object} ({size:g} m, {shape}) cannot be "
              "interpreted: that needs photos of {limit:scale} or larger (Mc/Mk ≤ "
              "{ratio:.1f}), or a resolving power R ≥ {need:.1f} lines/mm (the photos have "
              "{r:g}). What follows: interpret these objects in the field (a field "
              "interpretation survey of the block), or take them from other sources — "
              "existing plans of a larger scale, utility and cadastral records, newer "
              "imagery of a larger scale.",
        "ru": "На снимках масштаба {scale:scale} объекты «{object}» ({size:g}~м, {shape}) не "
              "дешифрируются: для этого нужны снимки масштаба {limit:scale} или крупнее "
              "(Mc/Mk ≤ {ratio:.1f}) либо разрешающая способность R ≥ {need:.1f}~мм⁻¹ (у "
              "снимков — {r:g}~мм⁻¹). Что из этого следует: эти объекты дешифрировать в поле "
              "(полевое дешифрирование участка) или взять из других источников — "
              "существующих планов более крупного масштаба, материалов инвентаризации "
              "коммуникаций и кадастра, более новых снимков более крупного масштаба.",
    },
    "archive_scanner_too_coarse": {
        "en": "the scan pixel of the {scale:scale} photos ({pixel:.1f} µm) is finer than the "
              "finest step of scanner '{scanner}' ({step:g} µm): scan them on a scanner with "
              "a step of {pixel:.1f} µm or finer",
        "ru": "Пиксель сканирования снимков масштаба {scale:scale} ({pixel:.1f}~мкм) меньше "
              "наименьшего шага сканера «{scanner}» ({step:g}~мкм): сканировать их на сканере "
              "с шагом {pixel:.1f}~мкм или мельче.",
    },
}
