"""The sentences about files ``plan --out`` does not write, and why. Part of the message
catalogue: :data:`scanplan.i18n.messages.MESSAGES` merges them (same template rules, see
:mod:`scanplan.i18n.messages`). Plain data; no I/O (base module)."""

from __future__ import annotations

OUTPUTS: dict[str, dict[str, str]] = {
    "export.no_mission": {
        "en": "no mission file written: {why}",
        "ru": "Файл полётного задания не записан: {why}.",
    },
    "export.no_photos": {
        "en": "no {name} written: the {n:,d} photo centres are more than the {most:,d} "
              "scanplan lists",
        "ru": "Файл {name} не записан: центров снимков {n:,d} — больше, чем {most:,d}, "
              "которые перечисляет программа.",
    },
    "export.why_not_feasible": {
        "en": "the flight plan over the area is not feasible ({why})",
        "ru": "план полёта над участком невыполним ({why})",
    },
    "export.why_not_listed": {
        "en": "the {n:,d} photo centres are more than the {most:,d} scanplan lists, so the "
              "trigger points are not known",
        "ru": "центров снимков {n:,d} — больше, чем {most:,d}, которые перечисляет "
              "программа, и точки съёмки неизвестны",
    },
    "export.why_no_speed": {
        "en": "the flight has no ground speed",
        "ru": "не задана путевая скорость",
    },
    "export.why_aircraft": {
        "en": "the camera is carried by a manned aircraft, not a UAV",
        "ru": "камера установлена на пилотируемом самолёте, а не на БВС",
    },
}
