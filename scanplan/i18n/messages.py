"""The engine's sentences in English and Russian: one catalogue of coded messages.

Every sentence the engine writes — a constraint's reason, the explanation of the binding
constraint, a warning, the reason of a specification, a maximum flight height's reason,
the text of a formula — is a :class:`Message`: a stable ``code`` from :data:`MESSAGES`
and the ``params`` (numbers, names) that fill its template. A message *is* its English
text (``Message`` subclasses ``str``), so ``warning.message``, ``constraint.reason`` and
``scenario.explanation`` read, print and serialise exactly as plain English strings;
``message.text("ru")`` renders the same numbers in Russian for the reports.

Templates use :meth:`str.format` fields with these parameter kinds:

- numbers, with an ordinary format spec (``{x:g}``, ``{x:.1f}``, ``{n:d}``); a number of
  1,000 or more is grouped as the reports' tables group it (:class:`scanplan.i18n.
  numbers.Numbers`: ``2,093`` / ``2 093``, a no-break space in Russian, where the decimal
  point becomes a comma); ``{n:id}`` — an identifier (a photo's number) or a shutter speed's
  denominator (``1/1614 s``, as photographers write it), never grouped;
- ``{x:scale}`` — a scale denominator (:func:`scale_text`: ``1:25000`` in English,
  ``1:25 000`` in Russian, ``1:8000`` in both); ``{x:denominator}`` — the same
  denominator without ``1:`` (``8000``, ``25000``; Russian ``25 000``), for a
  computation with the scale number (``7 µm × 8000``); ``{x:um}`` — a pixel [µm] as the
  tables give it (one decimal; two significant digits below 1 µm, never ``0.0``);
- lists, each item formatted with the spec and joined by ``", "`` (English) or ``"; "``
  (Russian, where the comma is the decimal separator); a spec starting with ``;`` joins
  with ``"; "`` in both languages;
- ``{n:,d|маршрут|маршрута|маршрутов}`` — a count and its noun in the form the number
  takes (:func:`plural`: Russian one/few/many — 1, 21, 101, 1501 маршрут; 2, 22
  маршрута; 5, 11, 111 маршрутов; English singular/plural);
- ``{"en": ..., "ru": ...}`` — a name given in both languages (a constraint's name, a norm
  object's name, a shape);
- a nested :class:`Message`, rendered in the same language (``""`` or ``None`` for an
  optional part that is absent).

In a Russian template ``~`` is a no-break space, so a number stays on the line of its unit
(``{x:.1f}~мкм``), as Russian typesetting requires.

A project-file key is written ``⁅[uav] max_height_m⁆`` or ``⁅[uav] max_height_m|the altitude
ceiling⁆``: the terminal and the JSON show the key as it is typed (the user edits that
file), while the documents to sign (inside :func:`document_text`) show the words after
``|`` — or nothing, with the brackets around it dropped — since the customer and the crew
read what to do, not which key to type.

Plain data and :meth:`str.format`; no I/O (base module).
"""

from __future__ import annotations

import math
import numbers
import re
import string
from collections.abc import Iterator, Mapping
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass
from typing import Any

__all__ = ["LOCALES", "MAX_LISTED", "MESSAGES", "Message", "Names", "PlanWarning", "listing",
           "localize", "params_json", "placeholders", "render", "scale_text"]

LOCALES = ("en", "ru")

_NBSP = "\u00a0"
_TIE = "~"  # in a Russian template: a no-break space (a number stays with its unit)
_KEYREF = re.compile(r"⁅([^⁆|]*)(?:\|([^⁆]*))?⁆")  # ⁅project-file key|words for documents⁆
_MEDIUM: ContextVar[str] = ContextVar("scanplan_text_medium", default="terminal")
_M001 = "Михеева, Илюшенко, 2015"  # the paper, as the Russian reports cite it
_M001_EN = "Miheeva & Ilushenko 2015"  # the paper, as the English reports cite it
_TAIL_EN = (" They need R ≥ {need:.1f} lines/mm; the photo has {r:g}. Remedies: interpret them "
            "in the field, use photos with a higher resolving power, or fly a larger photo "
            "scale ({limit:scale} or larger, Mc/Mk ≤ {ratio:.1f}).")
_TAIL_RU = (" Для них нужна разрешающая способность R ≥ {need:.1f}~мм⁻¹, у снимков — {r:g}~"
            "мм⁻¹. Выход: дешифрировать эти объекты в поле, использовать снимки с более высокой "
            "разрешающей способностью или выполнить аэрофотосъёмку в более крупном масштабе "
            "({limit:scale} или крупнее, Mc/Mk ≤ {ratio:.1f}).")

MESSAGES: dict[str, dict[str, str]] = {
    # --- what each film constraint protects, and its formula with the source ------------
    "protects.PS": {
        "en": "keeps the planimetric error of the model within V_s on the map after the "
              "processing loss k",
        "ru": "ограничивает ошибку положения точек модели в плане величиной V_s на карте с "
              "учётом потери точности при обработке~k",
    },
    "protects.PZ": {
        "en": "keeps the height error within V_z = fraction·h_c after the processing loss k",
        "ru": "ограничивает ошибку высот величиной V_z = доля·h_c с учётом потери точности "
              "при обработке~k",
    },
    "protects.PP": {
        "en": "keeps the resolution of a graphic photo-plan (70 µm on the plan)",
        "ru": "сохраняет разрешающую способность графического фотоплана (70~мкм на плане)",
    },
    "protects.PR": {
        "en": "keeps the photo's resolving power R in the digital image",
        "ru": "передаёт разрешающую способность снимка R в цифровое изображение",
    },
    "protects.PD": {
        "en": "lets the map's smallest objects be recognised with probability P",
        "ru": "обеспечивает распознавание наименьших объектов карты с вероятностью P",
    },
    "equation.PS": {
        "en": f"P_S = V_s·Mk/(k·Mc) — GKINP (GNTA)-02-036-02; {_M001_EN}, eq. (1)",
        "ru": f"P_S = V_s·Mk/(k·Mc) — ГКИНП (ГНТА)-02-036-02; {_M001}, ф. (1)",
    },
    "equation.PZ": {
        "en": "P_Z = V_z·f/(k·Mc·b) (Instruction) or V_z·b/(k·Mc·f) (parallax) — "
              f"{_M001_EN}, eq. (2)",
        "ru": "P_Z = V_z·f/(k·Mc·b) (по Инструкции) или V_z·b/(k·Mc·f) (параллактическая) — "
              f"{_M001}, ф. (2)",
    },
    "equation.PP": {
        "en": f"P_P = 0.070·Mk/Mc — GKINP (GNTA)-02-036-02; {_M001_EN}, eq. (3)",
        "ru": f"P_P = 0,070·Mk/Mc — ГКИНП (ГНТА)-02-036-02; {_M001}, ф. (3)",
    },
    "equation.PR": {
        "en": f"P_R = k_R/R, k_R = 0.5 (printed 0.4) — {_M001_EN}, eqs. (4)–(6)",
        "ru": f"P_R = k_R/R, k_R = 0,5 (в Инструкции напечатано 0,4) — {_M001}, ф. (4)–(6)",
    },
    "equation.PD": {
        "en": f"P_D = 2·k_R·L·sqrt(−ln P)/(B·Mc) — {_M001_EN}, eq. (16)",
        "ru": f"P_D = 2·k_R·L·sqrt(−ln P)/(B·Mc) — {_M001}, ф. (16)",
    },
    # --- why each film constraint is there, with the contract's numbers -----------------
    "reason.PS": {
        "en": "keeps planimetric error within {vs:g} mm at {map:scale} ({ground:g} m on the "
              "ground) after processing loss k = {k:g}",
        "ru": "ограничивает ошибку положения в плане величиной {vs:g}~мм в масштабе "
              "{map:scale} ({ground:g}~м на местности) с учётом потери точности при обработке "
              "k = {k:g}",
    },
    "reason.PZ": {
        "en": "keeps height error within {fraction:g}·h_c = {vz:g} m (relief interval {hc:g} m) "
              "after k = {k:g}, {formula} form",
        "ru": "ограничивает ошибку высот величиной {fraction:g}·h_c = {vz:g}~м (высота сечения "
              "рельефа {hc:g}~м) с учётом k = {k:g} ({formula})",
    },
    "reason.PP": {
        "en": "keeps the graphic photo-plan resolution of {resolution:g} µm at {map:scale}",
        "ru": "сохраняет разрешающую способность графического фотоплана {resolution:g}~мкм в "
              "масштабе {map:scale}",
    },
    "reason.PR": {
        "en": "keeps the photo's resolving power of {r:g} lines/mm (k_R = {kr:g})",
        "ru": "сохраняет разрешающую способность снимка {r:g}~мм⁻¹ (k_R = {kr:g})",
    },
    "reason.PD": {
        "en": "lets {object} ({size:g} m, {shape}, B = {b:g}) be recognised with probability "
              "{p:g}",
        "ru": "обеспечивает распознавание объектов «{object}» ({size:g}~м, {shape}, B = {b:g}) "
              "с вероятностью {p:g}",
    },
    "height_formula.instruction": {
        "en": "Instruction's (f/b)",
        "ru": "формула Инструкции",
    },
    "height_formula.parallax": {
        "en": "parallax (b/f)",
        "ru": "параллактическая формула",
    },
    # --- the binding constraint at one photo scale -------------------------------------
    "explanation": {
        "en": "{cid} ({name}) binds at {scale:scale}: {pixel:um} µm {reason}{next}.",
        "ru": "При масштабе {scale:scale} размер пикселя сканирования {pixel:um}~мкм "
              "определяет условие {cid} ({name}): такой пиксель {reason}{next}.",
    },
    "explanation.next": {
        "en": "; next is {cid} at {pixel:um} µm (+{margin:.0f} %)",
        "ru": "; следующее условие — {cid}, {pixel:um}~мкм (+{margin:.0f}~%)",
    },
    # --- film warnings (the conclusions of Miheeva & Ilushenko 2015) ------------------
    "at_scale": {
        "en": "at {scales:scale}",
        "ru": "При масштабе снимков {scales:scale}",
    },
    "at_scales": {
        "en": "at {scales:scale}",
        "ru": "При масштабах снимков {scales:scale}",
    },
    "not_interpretable": {
        "en": "{at} P_D ({pd:.1f} µm) < P_R ({pr:.1f} µm): {object} ({size:g} m, {shape}) cannot "
              "be interpreted even on the original photos, and scanning finer than P_R does "
              "not help — the photo does not carry that detail." + _TAIL_EN,
        "ru": "{at} P_D ({pd:.1f}~мкм) < P_R ({pr:.1f}~мкм): объекты «{object}» ({size:g}~м, "
              "{shape}) не дешифрируются даже по исходным снимкам, и сканирование с пикселем "
              "мельче P_R не поможет — на снимке нет таких деталей." + _TAIL_RU,
    },
    "above_interpretation_limit": {
        "en": "{scales:scale} is above the interpretation limit {limit:scale}: {object} "
              "({size:g} m, {shape}) cannot be interpreted even on the original photos (this "
              "norm set does not check interpretation)." + _TAIL_EN,
        "ru": "Снимки масштаба {scales:scale} мельче предела дешифрирования {limit:scale}: "
              "объекты «{object}» ({size:g}~м, {shape}) не дешифрируются даже по исходным "
              "снимкам (эти нормативы не проверяют условие дешифрирования)." + _TAIL_RU,
    },
    "pr_drives_volume": {
        "en": "at {scale:scale} P_R ({pr:.1f} µm) binds only to keep the photo's resolving "
              "power; accuracy and interpretation allow {coarsest:.1f} µm ({cid}), which is "
              f"{{ratio:.1f}}× less data per frame ({_M001_EN}, conclusion 3).",
        "ru": "При масштабе снимков {scale:scale} условие P_R ({pr:.1f}~мкм) определяет пиксель "
              "только ради сохранения разрешающей способности снимка; условия точности и "
              "дешифрирования допускают {coarsest:.1f}~мкм ({cid}), то есть в {ratio:.1f}~раза "
              f"меньший объём данных на снимок ({_M001}, вывод 3).",
    },
    "scanner_too_coarse": {
        "en": "{at} the scan pixel ({pixels:.1f} µm) is finer than the finest step of scanner "
              "'{scanner}' ({step:g} µm); choose a larger photo scale or another scanner",
        "ru": "{at} размер пикселя сканирования ({pixels:.1f}~мкм) меньше наименьшего шага "
              "сканера «{scanner}» ({step:g}~мкм); выберите более крупный масштаб снимков или "
              "другой сканер.",
    },
    "overlap_not_standard": {
        "en": "forward overlap {overlap:g} % is not the Instruction's {standard:g} %: the "
              "printed height formula V_z·f/(k·Mc·b) lets a larger overlap allow a coarser "
              "pixel. {detail}(The parallax form: ⁅[norms] height_formula = \"parallax\" in the "
              "project file|the norm set's parallax height formula⁆.)",
        "ru": "Перекрытие {overlap:g}~% отличается от принятого в Инструкции {standard:g}~%: по "
              "напечатанной в Инструкции формуле точности по высоте V_z·f/(k·Mc·b) большее "
              "перекрытие допускает более крупный пиксель. {detail}(Параллактическую форму "
              "задаёт ⁅ключ [norms] height_formula = \"parallax\" файла проекта|выбор "
              "формулы высоты в нормативах⁆.)",
    },
    "overlap_not_standard.detail": {
        "en": "The parallax form gives {pairs}. ",
        "ru": "Параллактическая форма даёт {pairs}. ",
    },
    "overlap_not_standard.pair": {
        "en": "{pixel:.1f} µm at {scale:scale}",
        "ru": "{pixel:.1f}~мкм при {scale:scale}",
    },
    # --- UAV: the constraints as limits on the ground, warnings -------------------------
    "limit.PS": {
        "en": "planimetric error ≤ {vs:g} mm at {map:scale} after k = {k:g}",
        "ru": "ошибка положения в плане ≤ {vs:g}~мм в масштабе {map:scale} с учётом k = {k:g}",
    },
    "limit.PZ": {
        "en": "height error ≤ {vz:g} m (relief interval {hc:g} m) after k = {k:g}, {formula} "
              "form",
        "ru": "ошибка высот ≤ {vz:g}~м (высота сечения рельефа {hc:g}~м) с учётом k = {k:g} "
              "({formula})",
    },
    "limit.PP": {
        "en": "photo-plan resolution {resolution:g} µm at {map:scale}",
        "ru": "разрешающая способность фотоплана {resolution:g}~мкм в масштабе {map:scale}",
    },
    "limit.PD": {
        "en": "{object} ({size:g} m, {shape}) recognised with probability {p:g} on the real "
              "ground resolution L",
        "ru": "распознавание объектов «{object}» ({size:g}~м, {shape}) с вероятностью {p:g} "
              "по реальному линейному разрешению на местности L",
    },
    "motion_blur": {
        "en": "motion blur {blur:g} px at {height:g} m exceeds {limit:g} px: use an exposure ≤ "
              "1/{denominator:id} s or a speed ≤ {speed:.1f} m/s",
        "ru": "Смаз {blur:g}~пикс. на высоте {height:g}~м больше допустимого {limit:g}~пикс.: "
              "нужна выдержка не длиннее 1/{denominator:id}~с или скорость не выше {speed:.1f}~"
              "м/с.",
    },
    "haze_default_height": {
        "en": "the haze contrast coefficient {c:g} assumed for clear air below {valid:g} m is "
              "applied at {height:g} m, where haze lowers contrast more: give the expected "
              "value for the flight (⁅{key}⁆)",
        "ru": "Коэффициент снижения контраста дымкой {c:g}, принятый для чистого воздуха ниже "
              "{valid:g}~м, применён на высоте {height:g}~м, где дымка снижает контраст "
              "сильнее: задайте ожидаемое значение (⁅{key}⁆).",
    },
    "trigger_interval": {
        "en": "photo interval {interval:.2f} s is shorter than the camera's minimum "
              "{minimum:g} s: fly ≤ {speed:.1f} m/s or lower the forward overlap",
        "ru": "Интервал фотографирования {interval:.2f}~с короче наименьшего интервала "
              "срабатывания затвора камеры {minimum:g}~с: снизьте скорость до {speed:.1f}~м/с "
              "или уменьшите продольное перекрытие.",
    },
    "not_resolvable": {
        "en": "object contrast K = {contrast:.3f} is below the sensor's threshold contrast "
              "{threshold:g}: nothing is resolved, so the ground resolution L has no value",
        "ru": "Контраст объекта K = {contrast:.3f} ниже порогового контраста {threshold:g}: "
              "детали не разрешаются, и линейное разрешение на местности L не определено.",
    },
    "height_above_max": {
        "en": "planned height {height:g} m is above the maximum planned height {max:.0f} m set "
              "by {cid} ({name}){tolerance}",
        "ru": "Плановая высота полёта {height:g}~м выше максимальной плановой {max:.0f}~м по "
              "условию {cid} ({name}){tolerance}.",
    },
    "height_not_feasible": {
        "en": "no flight height is feasible: {cid} ({name}) allows at most {max:.2g} m"
              "{tolerance}, below the lowest flight height of {lowest:g} m; the planned "
              "{height:g} m cannot meet it",
        "ru": "Ни одна высота полёта не выполнима: условие {cid} ({name}) допускает не более "
              "{max:.2g}~м{tolerance}, что ниже наименьшей высоты полёта {lowest:g}~м; "
              "плановая высота {height:g}~м ему не удовлетворяет.",
    },
    "height_never_feasible": {
        "en": "no flight height is feasible: {cid} ({name}) cannot be met at any height"
              "{tolerance}; the planned {height:g} m does not meet it",
        "ru": "Ни одна высота полёта не выполнима: условие {cid} ({name}) не выполняется ни "
              "на какой высоте{tolerance}; плановая высота {height:g}~м ему не "
              "удовлетворяет.",
    },
    "height_above_max.tolerance": {
        "en": " with a {tolerance:g} % height tolerance",
        "ru": " с учётом допуска высоты {tolerance:g}~%",
    },
    # --- where the object to interpret comes from --------------------------------------
    "object_source.norm": {
        "en": "norm table of the smallest objects, {map:scale} ({source})",
        "ru": "таблица наименьших объектов нормативов, {map:scale} ({source})",
    },
    "object_source.user": {
        "en": "size given in the project file (⁅[norms] object_size_m⁆)",
        "ru": "размер задан в файле проекта (⁅[norms] object_size_m⁆)",
    },
    # --- the specification (scanplan plan) ----------------------------------------------
    "spec.film": {
        "en": "{scale:scale} is the smallest candidate photo scale (fewest frames) that meets "
              "every constraint: {explanation}",
        "ru": "{scale:scale} — самый мелкий из рассмотренных масштабов снимков (наименьшее "
              "число снимков), при котором выполняются все условия. {explanation}",
    },
    "no_feasible_photo_scale": {
        "en": "no candidate photo scale meets every constraint ({why:;}); add a larger photo "
              "scale to ⁅[film] photo_scales|the candidates⁆",
        "ru": "Ни один из рассмотренных масштабов снимков не удовлетворяет всем условиям "
              "({why:;}); добавьте более крупный масштаб снимков ⁅в [film] photo_scales|в число "
              "рассматриваемых⁆.",
    },
    "no_feasible_photo_scale.objects": {
        "en": "the map's objects need photo scales up to {limit:scale}",
        "ru": "для дешифрирования объектов карты масштаб снимков должен быть не мельче "
              "{limit:scale}",
    },
    "no_feasible_photo_scale.scanner": {
        "en": "scanner {scanner} must reach the scan pixel",
        "ru": "наименьший шаг сканера {scanner} должен быть не больше размера пикселя "
              "сканирования",
    },
    "no_feasible_photo_scale.pixel": {
        "en": "a scan pixel under {finest:g} µm is beyond any scanner and the film itself",
        "ru": "пиксель сканирования меньше {finest:g}~мкм недостижим ни для сканера, ни для "
              "самой плёнки",
    },
    "no_feasible_photo_scale.relief": {
        "en": "over the relief the frames of {scales:scale} reach {locals:scale}",
        "ru": "с учётом рельефа снимки масштаба {scales:scale} доходят до {locals:scale}",
    },
    "layout.too_many_strips": {
        "en": "the area needs {n:,d} strips at a line spacing of {spacing:g} m; at most "
              "{most:,d} are planned",
        "ru": "Для участка нужно {n:,d|маршрут|маршрута|маршрутов} при расстоянии между "
              "ними {spacing:g}~м; планируется не более {most:,d}.",
    },
    "layout.sortie_too_short": {
        "en": "a sortie of {limit:g} min does not fly even one photo base ({base:,.1f} m at "
              "{speed:g} m/s); give ⁅[uav] max_flight_time_min|the sortie time⁆ for the aircraft's "
              "endurance",
        "ru": "За полёт продолжительностью {limit:g}~мин не пролетается даже один базис "
              "фотографирования ({base:,.1f}~м при {speed:g}~м/с); задайте ⁅[uav] "
              "max_flight_time_min|продолжительность вылета⁆ по продолжительности полёта носителя.",
    },
    "layout.too_many_sorties": {
        "en": "more than {most:,d} sorties of {limit:g} min: the block cannot be flown with "
              "this aircraft",
        "ru": "Более {most:,d} полётов по {limit:g}~мин: участок не может быть снят этим "
              "носителем.",
    },
    "layout.sortie_cannot_reach": {
        "en": "a sortie of {limit:g} min ({have:,.0f} m) cannot fly from the take-off point "
              "to the block, photograph one exposure and return ({need:,.0f} m); move "
              "[flight] takeoff closer or give a longer [uav] max_flight_time_min",
        "ru": "За полёт продолжительностью {limit:g}~мин ({have:,.0f}~м) нельзя долететь от "
              "точки взлёта до участка, сделать хотя бы один снимок и вернуться "
              "({need:,.0f}~м); перенесите [flight] takeoff ближе или увеличьте [uav] "
              "max_flight_time_min.",
    },
    "layout.single_strip": {
        "en": "the line spacing {spacing:,.1f} m is larger than the area ({width:,.1f} m "
              "across the flight lines): one strip covers it and no block with side overlap "
              "can be formed; fly a single strip or lower the height",
        "ru": "Расстояние между маршрутами {spacing:,.1f}~м больше ширины участка "
              "({width:,.1f}~м поперёк маршрутов): его покрывает один маршрут, блок с "
              "поперечным перекрытием не образуется; снимайте одним маршрутом или ниже.",
    },
    "area_scale_distortion": {
        "en": "the planning projection {crs} stretches the ground by up to {pct:.2f} % over "
              "the area (longitude {west:.4f} … {east:.4f}°), where a 6° UTM zone stays within "
              "0.1 %: strip spacing, photo base and ground pixel on the map differ from the "
              "ground by as much; check the area's coordinates, split the block by zones or "
              "plan in a projection for the area's middle (⁅[area] plan_crs⁆)",
        "ru": "Проекция планирования {crs} растягивает местность до {pct:.2f}~% на участке "
              "(долгота {west:.4f} … {east:.4f}°), тогда как в 6-градусной зоне UTM искажение "
              "не более 0,1~%: расстояния между маршрутами, базис фотографирования и размер "
              "пикселя на местности отличаются на столько же; проверьте координаты участка, "
              "разделите блок по зонам или задайте проекцию для середины участка "
              "(⁅[area] plan_crs⁆).",
    },
    "crosshatch": {
        "en": "crosshatch: the area is flown twice — the first pass at {direction:.1f}° "
              "({first} strips), then the second at {cross:.1f}° ({second} strips), with a "
              "pass transit of {transit:,.0f} m between them; every plan compared is flown "
              "so, as ⁅[uav] crosshatch⁆ asks",
        "ru": "Двойная сетка: участок облетается дважды — первый проход под {direction:.1f}° "
              "(маршрутов: {first}), затем второй под {cross:.1f}° (маршрутов: {second}), "
              "переход между проходами {transit:,.0f}~м; так облетаются все сравниваемые "
              "планы, как задано ⁅[uav] crosshatch⁆.",
    },
    "flight_not_feasible": {
        "en": "the flight plan over the area is not feasible: {why}",
        "ru": "План полёта над участком невыполним: {why}",
    },
    "spec.uav_none": {
        "en": "no flight height meets every constraint with this camera",
        "ru": "Ни одна высота полёта не удовлетворяет всем условиям с этой камерой.",
    },
    "spec.uav_rounded": {
        "en": "the maximum planned height {max:.0f} m ({cid} binds) rounded down to a "
              "multiple of {step:g} m",
        "ru": "Рекомендуемая высота полёта — максимальная плановая {max:.0f}~м (определяющее "
              "условие "
              "{cid}), округлённая в меньшую сторону с шагом {step:g}~м.",
    },
    "height_lowered": {
        "en": "the flight height given in the project, {planned:g} m, is above the maximum "
              "planned height {max:.0f} m ({cid} binds); lowered to {recommended:g} m",
        "ru": "Высота полёта, заданная в проекте, {planned:g}~м, выше максимальной плановой "
              "{max:.0f}~м (определяющее условие {cid}); высота понижена до "
              "{recommended:g}~м.",
    },
    "spec.uav_within": {
        "en": "the planned height is within the maximum planned height {max:.0f} m",
        "ru": "Плановая высота полёта не превышает максимальную плановую {max:.0f}~м.",
    },
}
"""Message code → template per locale (same codes and the same fields in every locale)."""

from .messages_archive import ARCHIVE as _ARCHIVE  # noqa: E402  (archive photos)

MESSAGES.update(_ARCHIVE)
from .messages_terrain import TERRAIN as _TERRAIN  # noqa: E402  (the terrain)

MESSAGES.update(_TERRAIN)
from .messages_outputs import OUTPUTS as _OUTPUTS  # noqa: E402  (files not written)

MESSAGES.update(_OUTPUTS)
from .messages_uav import UAV as _UAV  # noqa: E402  (height accuracy, ceiling, airspace)

MESSAGES.update(_UAV)
from .messages_site import SITE as _SITE  # noqa: E402  (where the area is: swap, site)

MESSAGES.update(_SITE)
from .messages_flight import FLIGHT as _FLIGHT  # noqa: E402  (the aircraft, the sorties)

MESSAGES.update(_FLIGHT)
from .messages_control import CONTROL as _CONTROL  # noqa: E402  (ground control)

MESSAGES.update(_CONTROL)
from .messages_plans import PLANS as _PLANS  # noqa: E402  (the plans compared, the choice)

MESSAGES.update(_PLANS)


@contextmanager
def document_text() -> Iterator[None]:
    """Render messages for a document to sign while the block runs: project-file keys
    (``⁅[uav] max_height_m|…⁆``) give way to words (see the module docstring)."""
    token = _MEDIUM.set("document")
    try:
        yield
    finally:
        _MEDIUM.reset(token)


def for_medium(text: str, medium: str | None = None) -> str:
    """``text`` with its project-file keys as the medium shows them.

    Parameters
    ----------
    text : str
        A rendered message, possibly holding ``⁅key⁆`` or ``⁅key|words⁆``.
    medium : {"terminal", "document"}, optional
        Default: the medium in force (``"document"`` inside :func:`document_text`).

    Returns
    -------
    str

    Examples
    --------
    >>> t = "raise the ceiling (⁅[uav] max_height_m⁆) or fly ⁅[terrain] altitude_mode|lower⁆."
    >>> for_medium(t, "terminal")
    'raise the ceiling ([uav] max_height_m) or fly [terrain] altitude_mode.'
    >>> for_medium(t, "document")
    'raise the ceiling or fly lower.'
    """
    if "⁅" not in text:
        return text
    if (medium or _MEDIUM.get()) != "document":
        return _KEYREF.sub(lambda m: m.group(1), text)
    text = _KEYREF.sub(lambda m: m.group(2) or "", text)
    text = re.sub(r"[ \u00a0]*\([ \u00a0,;]*\)", "", text)  # brackets left empty
    text = re.sub(r"(?<=\S)[ \u00a0]+(?=[.,;:)])", "", text)  # space before punctuation
    return re.sub(r"(?<=\S)  +", " ", text)


def plural(n: int, forms: tuple[str, ...] | list[str], locale: str = "en") -> str:
    """The form of a noun that goes with the count ``n``.

    Parameters
    ----------
    n : int
        The count.
    forms : sequence of str
        Russian: the forms for one, few and many (``("снимок", "снимка", "снимков")``);
        English: singular and plural.
    locale : {"en", "ru"}

    Returns
    -------
    str

    Examples
    --------
    >>> [plural(n, ("снимок", "снимка", "снимков"), "ru") for n in (1, 2, 5, 11, 21, 1501)]
    ['снимок', 'снимка', 'снимков', 'снимков', 'снимок', 'снимок']
    >>> plural(1, ("strip", "strips")), plural(3, ("strip", "strips"))
    ('strip', 'strips')
    """
    n = abs(int(n))
    if locale == "ru" and len(forms) == 3:
        if n % 10 == 1 and n % 100 != 11:
            return forms[0]
        if 2 <= n % 10 <= 4 and not 12 <= n % 100 <= 14:
            return forms[1]
        return forms[2]
    return forms[0] if n == 1 else forms[-1]


def placeholders(template: str) -> set[str]:
    """The field names a template uses (``{x:g}`` → ``"x"``)."""
    return {name for _, name, _, _ in string.Formatter().parse(template) if name}


def scale_text(x: float, locale: str = "en") -> str:
    """A scale ``1:x`` as every document writes it: English never groups the denominator
    (``1:2000``, ``1:25000``); Russian groups it from five digits with a no-break space
    (``1:2000``, ``1:25 000``; four-digit numbers stay whole, the rule of Russian
    typesetting), with a decimal comma in a fractional one.

    Parameters
    ----------
    x : float
        The scale denominator.
    locale : {"en", "ru"}

    Returns
    -------
    str

    Examples
    --------
    >>> scale_text(2000), scale_text(25000), scale_text(25000, "ru"), scale_text(2000, "ru")
    ('1:2000', '1:25000', '1:25\xa0000', '1:2000')
    """
    if float(x).is_integer():
        whole = int(x)
        if locale == "ru" and abs(whole) >= 10000:
            return "1:" + f"{whole:,d}".replace(",", _NBSP)
        return f"1:{whole:d}"
    return "1:" + (f"{float(x):g}".replace(".", ",") if locale == "ru" else f"{float(x):g}")


_SPEC = re.compile(r"^(?P<head>[^.,a-zA-Z%]*)(?P<group>,?)(?P<tail>(\.\d+)?[a-zA-Z%]?)$")


def _grouped(spec: str, x: float) -> str:
    """``spec`` with thousands grouped when ``|x|`` ≥ 1000 (the one rule of
    :class:`scanplan.i18n.numbers.Numbers`: prose groups as tables do)."""
    m = _SPEC.match(spec)
    if m is None or abs(x) < 1000:
        return spec
    if m["tail"] in ("", "g") and float(x).is_integer():
        return m["head"] + ",.0f"  # a whole number: no exponent, grouped
    return m["head"] + "," + m["tail"]


def pixel_text(x: float, locale: str) -> str:
    """A pixel [µm] as every document prints it: one decimal (thousands grouped), or two
    significant digits below 1 µm written out (``0.55``, ``0.000011``; never ``0.0``)."""
    text = format(x, ",.1f") if x >= 0.95 or x <= 0 else f"{x:.2g}"
    if "e" in text:  # two significant digits written out: 0.000011, not 1.1e-05
        text = f"{float(text):.{1 - math.floor(math.log10(float(text)))}f}"
    if locale != "ru":
        return text
    return text.replace(",", _NBSP).replace(".", ",")


def _number(x: float, spec: str, locale: str) -> str:
    if spec == "scale":
        return scale_text(x, locale)
    if spec == "denominator":
        return scale_text(x, locale)[2:]
    if spec == "um":  # a pixel as the tables give it: 12.5, 0.55, 0.000011 (never 0.0)
        return pixel_text(x, locale)
    if spec == "id":  # an identifier (a photo's, a strip's number): never grouped
        return str(int(x))
    if spec.endswith("d") and float(x).is_integer():
        x = int(x)
    spec = _grouped(spec, x)
    if locale != "ru":
        return format(x, spec)
    return format(x, spec).replace(",", _NBSP).replace(".", ",")


class Names(Mapping[str, str]):
    """A name given in both languages, read as ``{"en": …, "ru": …}`` (a message
    parameter: a constraint's, a norm object's, a shape's name; a registered component's
    label). A message shows a Russian name left empty as the English one.

    >>> n = Names("circle", "круг")
    >>> n["ru"], dict(n), render("explanation.next", {"cid": Names("PS", ""), "pixel": 2,
    ...                                               "margin": 5}, "ru")[:24]
    ('круг', {'en': 'circle', 'ru': 'круг'}, '; следующее условие — PS')
    """

    __slots__ = ("_names",)

    def __init__(self, en: str, ru: str = "") -> None:
        self._names = (("en", en), ("ru", ru))

    def __getitem__(self, locale: str) -> str:
        for loc, name in self._names:
            if loc == locale:
                return name
        raise KeyError(locale)

    def __iter__(self) -> Iterator[str]:
        return iter(loc for loc, _ in self._names)

    def __len__(self) -> int:
        return len(self._names)

    def __repr__(self) -> str:
        return f"Names({self['en']!r}, {self['ru']!r})"

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Mapping) and dict(self) == dict(other)

    def __hash__(self) -> int:
        return hash(self._names)

    def __reduce__(self) -> tuple[Any, ...]:
        return (Names, (self["en"], self["ru"]))


class _Param:
    """A parameter value formatted for one locale (see the module docstring)."""

    __slots__ = ("locale", "value")

    def __init__(self, value: Any, locale: str) -> None:
        self.value = value
        self.locale = locale

    def __format__(self, spec: str) -> str:
        v, loc = self.value, self.locale
        if v is None:
            return ""
        if isinstance(v, Message):
            return format(v.text(loc), spec)
        if isinstance(v, Mapping):
            return format(str(v.get(loc) or v.get("en", "")), spec)
        if isinstance(v, list | tuple):
            if spec.startswith(";"):
                sep, spec = "; ", spec[1:]
            else:
                sep = "; " if loc == "ru" else ", "
            return sep.join(format(_Param(x, loc), spec) for x in v)
        if isinstance(v, numbers.Real) and not isinstance(v, bool):
            if "|" in spec:  # a count and its noun: {n:d|маршрут|маршрута|маршрутов}
                spec, *forms = spec.split("|")
                space = _NBSP if loc == "ru" else " "
                return f"{_number(v, spec, loc)}{space}{plural(v, forms, loc)}"
            return _number(v, spec, loc)
        return format(str(v), spec)


def render(code: str, params: Mapping[str, Any] | None = None, locale: str = "en") -> str:
    """The message ``code`` with ``params`` in ``locale`` (unknown locale → English).

    Parameters
    ----------
    code : str
        A key of :data:`MESSAGES`.
    params : mapping, optional
        The values of the template's fields.
    locale : {"en", "ru"}
        Language.

    Returns
    -------
    str

    Raises
    ------
    KeyError
        For an unknown code or a missing parameter.
    """
    templates = MESSAGES[code]
    template = templates.get(locale) or templates["en"]
    if locale == "ru":
        template = template.replace(_TIE, _NBSP)
    values = {k: _Param(v, locale) for k, v in (params or {}).items()}
    return for_medium(template.format_map(values))


class Message(str):
    """A coded engine sentence: its English text, plus ``code`` and ``params``.

    ``Message("reason.PR", r=40, kr=0.5)`` equals the English text (it is a ``str``), so
    it can stand wherever the engine used to put a plain English sentence;
    :meth:`text` gives it in another locale with the same numbers.
    """

    code: str
    params: dict[str, Any]

    def __new__(cls, code: str, params: Mapping[str, Any] | None = None, /,
                **kw: Any) -> Message:
        values = {**(params or {}), **kw}
        token = _MEDIUM.set("terminal")  # the str value is the terminal's English text
        try:
            english = render(code, values, "en")
        finally:
            _MEDIUM.reset(token)
        self = super().__new__(cls, english)
        self.code = code
        self.params = values
        return self

    def __getnewargs__(self) -> tuple[Any, ...]:  # type: ignore[override]
        return (self.code, self.params)

    def text(self, locale: str = "en") -> str:
        """The sentence in ``locale`` (``"en"`` or ``"ru"``)."""
        return render(self.code, self.params, locale)


def localize(value: Any, locale: str = "en") -> str:
    """``value`` in ``locale`` if it is a :class:`Message`, else the value as text."""
    if isinstance(value, Message):
        return value.text(locale)
    return "" if value is None else str(value)


def params_json(value: Any) -> Any:
    """Message parameters as plain JSON data (a nested message → ``{code, params}``)."""
    if isinstance(value, Message):
        return {"code": value.code, "params": params_json(value.params)}
    if isinstance(value, Mapping):
        return {str(k): params_json(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [params_json(v) for v in value]
    if isinstance(value, numbers.Integral) and not isinstance(value, bool):
        return int(value)
    if isinstance(value, numbers.Real) and not isinstance(value, bool):
        return float(value)
    return value


@dataclass(frozen=True)
class PlanWarning:
    """A warning or note of a plan (``severity`` is ``"warning"`` or ``"info"``).

    ``message`` is a :class:`Message` (its English text) whose code is ``code``;
    :meth:`text` renders it in another locale. Base-level, so that the ground and geometry
    layer (``geo/``) and the rules (``rules/``) state their findings the same way.
    """

    code: str
    message: str
    photo_scales: tuple[float, ...] = ()
    severity: str = "warning"

    def text(self, locale: str = "en") -> str:
        """The message in ``locale`` (``"en"`` or ``"ru"``)."""
        return localize(self.message, locale)


MAX_LISTED = 6
"""Photos or strips named in one warning; the rest are counted."""


def listing(numbers: Any) -> str:
    """``3, 4, 7`` or ``3, 4, 7, 9, 12, 15 (+40)``: the first :data:`MAX_LISTED` numbers of
    an integer array and how many more."""
    shown = ", ".join(str(int(v)) for v in numbers[:MAX_LISTED])
    more = len(numbers) - MAX_LISTED
    return shown + (f" (+{more})" if more > 0 else "")
