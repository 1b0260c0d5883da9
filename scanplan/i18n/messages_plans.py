"""The engine's sentences about the plans compared for a UAV block and the one chosen
(:mod:`scanplan.project.alternatives`): what a plan misses, how it is flown, why it was
chosen, what a choice of the project costs. Part of the message catalogue:
:data:`scanplan.i18n.messages.MESSAGES` merges them (same template rules, see
:mod:`scanplan.i18n.messages`). Plain data; no I/O (base module)."""

from __future__ import annotations

PLANS: dict[str, dict[str, str]] = {
    # --- what a plan misses (the "why rejected" column) ---------------------------------
    "plan_choice.not_feasible": {
        "en": "cannot be flown: {why}",
        "ru": "не может быть выполнен: {why}",
    },
    "plan_choice.limit": {
        "en": "the worst photo misses {cid} (at most {max:.0f} m over this ground)",
        "ru": "наихудший снимок не удовлетворяет условию {cid} (не выше {max:.0f}~м над этим "
              "рельефом)",
    },
    "plan_choice.overlap.forward": {
        "en": "forward overlap down to {value:.1f} % (planned {planned:g} %)",
        "ru": "продольное перекрытие до {value:.1f}~% (планировалось {planned:g}~%)",
    },
    "plan_choice.overlap.side": {
        "en": "side overlap down to {value:.1f} % (planned {planned:g} %)",
        "ru": "поперечное перекрытие до {value:.1f}~% (планировалось {planned:g}~%)",
    },
    "plan_choice.block": {
        "en": "one-height rule: ground range {range:.0f} m is {pct:.0f} % of the height, "
              "{limit:g} % allowed",
        "ru": "правило одной высоты: перепад {range:.0f}~м составляет {pct:.0f}~% высоты, "
              "допустимо {limit:g}~%",
    },
    "plan_choice.needs_dem.follow": {
        "en": "an estimate: following the terrain needs the ground under every photo "
              "(⁅[terrain] dem⁆)",
        "ru": "оценка: для полёта с огибанием рельефа нужны отметки под каждым снимком "
              "(⁅[terrain] dem⁆)",
    },
    "plan_choice.needs_parts": {
        "en": "an estimate: the {n:d} parts by ground height are not laid out here (their "
              "outlines follow the relief; each part adds its own edge strips)",
        "ru": "оценка: {n:d|часть|части|частей} по высоте местности здесь не размечены (их "
              "границы следуют рельефу; каждая часть добавляет свои краевые маршруты)",
    },
    "plan_choice.within": {
        "en": "{what}, within the {slack:g}-point allowance",
        "ru": "{what}, в пределах допуска в {slack:g|процентный пункт|процентных пункта|"
              "процентных пунктов}",
    },
    # --- how a plan is flown --------------------------------------------------------------
    "plan_choice.mode.flat": {"en": "flat ground", "ru": "без рельефа"},
    "plan_choice.mode.constant": {"en": "one altitude", "ru": "постоянная высота"},
    "plan_choice.mode.strip": {"en": "one altitude per strip", "ru": "высота по маршрутам"},
    "plan_choice.mode.follow": {"en": "following the terrain", "ru": "огибание рельефа"},
    "plan_choice.mode.parts": {
        "en": "{n:d} parts by ground height",
        "ru": "{n:d|часть|части|частей} по высоте местности",
    },
    "plan_choice.what": {
        "en": "{mode}, lines at {direction:.1f}°, {height:g} m",
        "ru": "{mode}, маршруты под {direction:.1f}°, {height:g}~м",
    },
    "plan_choice.figures": {
        "en": "{photos:,d} photos, {time:,.0f} min, {sorties:d} sorties",
        "ru": "{photos:,d} снимков, {time:,.0f}~мин, вылетов: {sorties:d}",
    },
    # --- why this plan ---------------------------------------------------------------------
    "plan_choice.chosen": {
        "en": "Of {n:d} plans compared it is the one with the least flying time that meets "
              "every constraint: {what} ({figures})",
        "ru": "Из сравнённых вариантов ({n:d}) это вариант с наименьшим временем полёта, "
              "удовлетворяющий всем условиям: {what} ({figures}).",
    },
    "plan_choice.chosen_allowed": {
        "en": "Of {n:d} plans compared it is the one with the least flying time that meets "
              "every constraint among those the project's choices allow: {what} ({figures})",
        "ru": "Из сравнённых вариантов ({n:d}) это вариант с наименьшим временем полёта, "
              "удовлетворяющий всем условиям, среди допускаемых выбором проекта: {what} "
              "({figures}).",
    },
    "plan_choice.chosen_none": {
        "en": "None of the {n:d} plans compared meets every constraint with what the project "
              "gives; this is the one laid out with the least flying time the project allows: "
              "{what} ({figures})",
        "ru": "Ни один из сравнённых вариантов ({n:d}) не удовлетворяет всем условиям при "
              "данных проекта; это размеченный вариант с наименьшим временем полёта из "
              "допускаемых проектом: {what} ({figures}).",
    },
    # --- warnings -------------------------------------------------------------------------
    "plan_choice_costs": {
        "en": "the project's choice ({keys}) costs {pct:.0f} % of its flying time more than "
              "needed: {what} needs {figures}, while {better} meets every constraint with "
              "{better_figures}; leave the choice to scanplan (remove the keys) to fly that",
        "ru": "Выбор проекта ({keys}) увеличивает время полёта: {what} требует {figures}, "
              "тогда как вариант «{better}» удовлетворяет всем условиям при {better_figures} "
              "(экономия {pct:.0f}~% времени полёта); чтобы лететь так, оставьте выбор "
              "программе (удалите эти ключи).",
    },
    "plan_choice_needs": {
        "en": "no plan laid out here meets every constraint; {better} would, with about "
              "{figures} ({pct:.0f} % less flying time): {needs}",
        "ru": "Ни один размеченный вариант не удовлетворяет всем условиям; вариант "
              "«{better}» удовлетворил бы им примерно при {figures} (на {pct:.0f}~% меньше "
              "времени полёта): {needs}.",
    },
}
