"""The sentences of a digital block's height accuracy, the altitude ceiling and the
airspace rules, and the target GSD (:mod:`scanplan.rules.uav`). Part of the message
catalogue: :data:`scanplan.i18n.messages.MESSAGES` merges them (same template rules, see
:mod:`scanplan.i18n.messages`). Plain data; no I/O (base module)."""

from __future__ import annotations

UAV: dict[str, dict[str, str]] = {
    # --- digital height accuracy, altitude ceiling, target GSD (scanplan.rules.uav) -------------
    "limit.PZ.normal_case": {
        "en": "idealised stereo precision σ_Z = (H/B)·(H/f)·σ_px ≤ V_z = {vz:g} m RMS (relief "
              "interval {hc:g} m) with a parallax error σ_px = {sigma:g} px (an assumption) and "
              "the base of a stereo pair with {overlap:g} % overlap at the highest flown "
              "height and the mission's trigger distance (B = {steps:.2f} × the photo step, "
              "B/H = {bh:.3f}){multi}",
        "ru": "идеализированная точность стереоизмерений σ_Z = (H/B)·(H/f)·σ_px ≤ V_z = "
              "{vz:g}~м (СКО; высота сечения рельефа {hc:g}~м) при ошибке измерения "
              "параллакса σ_px = {sigma:g}~пикс. (допущение) и базисе стереопары с "
              "перекрытием {overlap:g}~% на наибольшей фактической высоте при шаге "
              "фотографирования задания (B = {steps:.2f}~× шаг, B/H = {bh:.3f}){multi}",
    },
    "equation.PZ.normal_case": {
        "en": "σ_Z = (H/B)·(H/f)·σ_px ≤ V_z, B the base of a pair with the standard overlap "
              "(a bound of the multi-ray intersection) — idealised stereo precision of the "
              "normal case, Kraus (2007), Luhmann et al. (2014); ground control, camera "
              "calibration and the surface are not in it",
        "ru": "σ_Z = (H/B)·(H/f)·σ_px ≤ V_z, B — базис стереопары со стандартным продольным "
              "перекрытием (оценка сверху для многолучевой засечки) — идеализированная "
              "точность стереоизмерений нормального случая, Краус (2007), Луман и др. (2014); "
              "опорные точки, калибровка камеры и поверхность в ней не учтены",
    },
    "limit.PZ.multi": {
        "en": ", σ_Z multiplied by {f:.2f} for the rays of every photo of the strip",
        "ru": ", σ_Z с множителем {f:.2f} за счёт лучей всех снимков маршрута",
    },
    "protects.GL": {
        "en": "keeps the GSD of the photos within the largest one today's standard recommends "
              "for the plan scale",
        "ru": "удерживает размер пикселя на местности в пределах, рекомендуемых действующим "
              "стандартом для масштаба плана",
    },
    "equation.GL": {
        "en": "GSD = p·H/f ≤ GSD_max(Mk) — GOST R 59562-2021, Appendix B, Table B.1",
        "ru": "GSD = p·H/f ≤ GSD_max(Mk) — ГОСТ Р 59562-2021, прил. Б, табл. Б.1",
    },
    "limit.GL": {
        "en": "GSD at the highest flown height ≤ {gsd:g} cm for {map:scale} ({area})",
        "ru": "Размер пикселя на местности на наибольшей фактической высоте ≤ {gsd:g}~см "
              "для масштаба {map:scale} "
              "({area})",
    },
    "gsd_area.general": {
        "en": "general",
        "ru": "общий случай",
    },
    "gsd_area.dense_urban": {
        "en": "towns with dense multi-storey buildings",
        "ru": "городские населённые пункты с многоэтажной и плотной застройкой",
    },
    "gsd_limit_film": {
        "en": "the scanned ground pixel of {scale:scale} photos, {pixel:g} µm × "
              "{scale:denominator} = {ground:.1f} cm, is {verdict} the {limit:g} cm that GOST R "
              "59562-2021, Table B.1, recommends for digital photos for {map:scale} ({area}); "
              "for information: the table is written for digital cameras",
        "ru": "Размер пикселя скана на местности для снимков {scale:scale}: {pixel:g}~мкм × "
              "{scale:denominator} = {ground:.1f}~см — {verdict} {limit:g}~см, рекомендуемых "
              "ГОСТ Р 59562-2021, табл. Б.1, для цифровых снимков к масштабу {map:scale} ({area}); "
              "для сведения: таблица написана для цифровых камер.",
    },
    "gsd_limit.within": {"en": "within", "ru": "не больше"},
    "gsd_limit.over": {"en": "coarser than", "ru": "больше"},
    "block_split": {
        "en": "the ground height range in the block, {range:.0f} m, is {pct:.1f} % of the flight "
              "height {h:g} m, over the {limit:g} % allowed for {relief} (GOST R 59328-2021 "
              "§6.2.1, second draft): split the block into {n:d} parts by ground height "
              "({bands:;}) and fly each at its own height, or fly following the terrain",
        "ru": "Перепад высот в пределах съёмочного участка {range:.0f}~м составляет {pct:.1f}~% "
              "высоты фотографирования {h:g}~м — больше допустимых {limit:g}~% для местности "
              "категории «{relief}» (ГОСТ Р 59328-2021, п. 6.2.1, проект 2-й редакции): "
              "разделите участок "
              "на {n:d|часть|части|частей} по высоте местности ({bands:;}) с отдельной высотой "
              "фотографирования для каждой или выполняйте съёмку с огибанием рельефа.",
    },
    "block_height_waived": {
        "en": "the one-height rule of GOST R 59328-2021 §6.2.1 (second draft: {limit:g} % for "
              "{relief}) is waived: the flight follows the relief (⁅[terrain] altitude_mode = "
              "\"follow\"⁆), so the photographing height is kept over the ground and not one "
              "height for the block (the ground range, {range:.0f} m, is {pct:.1f} % of the "
              "flight height {h:g} m)",
        "ru": "Требование одной высоты фотографирования на участок (ГОСТ Р 59328-2021, "
              "п. 6.2.1, проект 2-й редакции: {limit:g}~% для местности категории «{relief}») "
              "не применяется: полёт "
              "выполняется с огибанием рельефа (⁅режим [terrain] altitude_mode⁆), высота "
              "фотографирования выдерживается над местностью (перепад высот {range:.0f}~м — "
              "{pct:.1f}~% высоты фотографирования {h:g}~м).",
    },
    "recommendation_set_aside": {
        "en": "{what} is set aside by the project: {reason}",
        "ru": "{what} не применяется по решению проекта: {reason}",
    },
    "set_aside.gsd_limits": {
        "en": "the largest GSD per plan scale of GOST R 59562-2021 Table B.1 (a recommended "
              "appendix; the GSD is {gsd:.1f} cm against the recommended {limit:g} cm)",
        "ru": "Рекомендация ГОСТ Р 59562-2021 (рекомендуемое приложение Б, табл. Б.1) о "
              "предельном размере пикселя на местности (размер пикселя {gsd:.1f}~см при "
              "рекомендуемом {limit:g}~см)",
    },
    "set_aside.block_relief": {
        "en": "the one-height rule of a block (GOST R 59328-2021 §6.2.1, a requirement of the "
              "standard's body with an exception, in the second draft's wording: {limit:g} % "
              "of the flight height; the ground height range is {pct:.1f} %)",
        "ru": "Требование одной высоты фотографирования на участок (ГОСТ Р 59328-2021, "
              "п. 6.2.1 — требование основной части стандарта с исключением, в редакции "
              "проекта 2-й редакции: {limit:g}~% высоты фотографирования; перепад высот "
              "{pct:.1f}~%)",
    },
    "block.band": {
        "en": "ground {lo:.0f}–{hi:.0f} m",
        "ru": "местность {lo:.0f}–{hi:.0f}~м",
    },
    "relief.flat": {"en": "flat terrain", "ru": "равнинная"},
    "relief.hilly": {"en": "hilly terrain", "ru": "всхолмлённая"},
    "relief.mountainous": {"en": "mountainous terrain", "ru": "горная"},
    "sun_no_window": {
        "en": "the sun does not reach {elev:g}° at the site from {start} to {end} (at most "
              "{top:.1f}°): no photography window on these dates; change the dates "
              "(⁅[schedule] start_date, end_date⁆)",
        "ru": "Солнце не поднимается на {elev:g}° над горизонтом в районе работ с {start} по "
              "{end} (наибольшая высота {top:.1f}°): в эти даты аэрофотосъёмка невозможна; "
              "измените сроки (⁅[schedule] start_date, end_date⁆).",
    },
    "sun_dates_short": {
        "en": "the {n:d} sorties do not fit into the sun windows from {start} to {end} (only "
              "{flown:d} do): extend the end date (⁅[schedule] end_date⁆)",
        "ru": "Вылеты ({n:d}) не умещаются в периоды достаточной высоты Солнца с {start} по "
              "{end} (умещается {flown:d}): продлите срок работ (⁅[schedule] end_date⁆).",
    },
    "protects.GSD": {
        "en": "gives the ground sample distance the customer asked for",
        "ru": "обеспечивает заданный заказчиком размер пикселя на местности",
    },
    "equation.GSD": {
        "en": "GSD = p·H/f ≤ the target GSD",
        "ru": "GSD = p·H/f ≤ заданного значения",
    },
    "protects.HC": {
        "en": "keeps the highest flown height within the legal or airframe altitude ceiling",
        "ru": "удерживает наибольшую фактическую высоту полёта в пределах допустимой высоты",
    },
    "equation.HC": {
        "en": "H·(1 + height tolerance) ≤ ceiling; without an airspace-use permission below "
              "it — Federal Rules for the Use of the Airspace",
        "ru": "H·(1 + допуск высоты) ≤ предельной высоты; без разрешения на использование "
              "воздушного пространства — менее неё — Федеральные правила использования "
              "воздушного пространства",
    },
    "limit.GSD": {
        "en": "GSD at the highest flown height ≤ the target {gsd:g} cm",
        "ru": "Размер пикселя на местности на наибольшей фактической высоте ≤ заданного "
              "{gsd:g}~см",
    },
    "limit.HC": {
        "en": "highest flown height ≤ the altitude ceiling {ceiling:g} m ({source})",
        "ru": "наибольшая фактическая высота ≤ предельной высоты полёта {ceiling:g}~м ({source})",
    },
    "limit.HC.below": {
        "en": "highest flown height below {ceiling:g} m ({source})",
        "ru": "наибольшая фактическая высота менее {ceiling:g}~м ({source})",
    },
    "airspace_conditions": {
        "en": "conditions of this plan without an airspace-use permission (Federal Rules for "
              "the Use of the Airspace, as amended by Decree No. 1016 of 21.06.2023; the "
              "wording in force from {date}, as secondary sources describe it): "
              "{conditions}. Check the rules in force on the flying date",
        "ru": "Условия плана без разрешения на использование воздушного пространства "
              "(Федеральные правила использования воздушного пространства в ред. "
              "постановления от 21~июня 2023~г. №~1016; редакция, действующая с {date}, "
              "в изложении вторичных источников): {conditions}. Проверьте правила, "
              "действующие на дату полётов.",
    },
    "airspace_not_below": {
        "en": "the highest flown height {flown:g} m (planned {planned:g} m) is not below the "
              "{ceiling:g} m up to which no airspace-use permission is needed (the rule reads "
              "\"below {ceiling:g} m\"): plan lower, or obtain the permission and raise "
              "the ceiling (⁅{key}⁆)",
        "ru": "Наибольшая фактическая высота {flown:g}~м (плановая {planned:g}~м) не менее "
              "{ceiling:g}~м, ниже которых разрешение на использование воздушного "
              "пространства не требуется (в правилах: «менее {ceiling:g}~м»): снизьте высоту "
              "или получите разрешение и увеличьте предельную высоту (⁅{key}⁆).",
    },
    "ceiling.project": {
        "en": "set in the project",
        "ru": "задана в проекте",
    },
    "ceiling.norms": {
        "en": "the norm set's ceiling for flights without an airspace-use permission",
        "ru": "предельная высота по нормативам для полётов без разрешения на использование "
              "воздушного пространства",
    },
    "ceiling_binds": {
        "en": "the altitude ceiling of {ceiling:g} m binds: {tolerance}the plan may be at most "
              "{max:.0f} m, while the other constraints "
              "would allow planning up to {allow:.0f} m ({cid} binds there). Flying higher "
              "needs an airspace-use permission; then raise the ceiling (⁅[uav] max_height_m⁆)",
        "ru": "Определяет предельная высота полёта {ceiling:g}~м: {tolerance}плановая высота "
              "не более {max:.0f}~м, тогда как остальные "
              "условия допускают плановую высоту до {allow:.0f}~м (там определяет условие "
              "{cid}). Полёт выше требует разрешения на использование воздушного пространства; "
              "тогда увеличьте предельную высоту (⁅[uav] max_height_m⁆).",
    },
    "ceiling_binds.tolerance": {
        "en": "with the +{tolerance:g} % height tolerance ",
        "ru": "с допуском высоты +{tolerance:g}~% ",
    },
}

RU_MONTHS_GENITIVE = ("января", "февраля", "марта", "апреля", "мая", "июня", "июля",
                      "августа", "сентября", "октября", "ноября", "декабря")
"""Russian month names in the genitive (a date in words: «1 марта 2024 г.»)."""


def date_words(iso: str) -> dict[str, str]:
    """An ISO date as a message parameter in both languages: ``01.03.2024`` and
    «1 марта 2024 г.», no-break spaces (a Russian sentence writes the date in words, so no
    digit-dot-digit reads as a decimal).

    >>> date_words("2024-03-01")["ru"]
    '1\\xa0марта 2024\\xa0г.'
    """
    y, m, d = (int(x) for x in iso.split("-"))
    return {"en": f"{d:02d}.{m:02d}.{y}",
            "ru": f"{d}\u00a0{RU_MONTHS_GENITIVE[m - 1]} {y}\u00a0г."}
