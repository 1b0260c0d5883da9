"""The sentences about files ``plan --out`` does not write, and why, and about a map
background the documents print without (tiles that did not come). Part of the message
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
    "map_tiles_unreachable": {
        "en": "no background tile came from {host} (offline, or the server has none here): "
              "the map is printed without its background; plan again when {host} answers "
              "— the tiles fetched are kept on disk for later plans, also offline",
        "ru": "Тайлы подложки с {host} не получены (нет сети или у сервера нет тайлов этого "
              "места): карта напечатана без подложки; повторите расчёт, когда {host} "
              "доступен, — полученные тайлы сохраняются на диске и используются и без сети.",
    },
    "map_tiles_missing": {
        "en": "{missing:,d} of the {asked:,d} background tiles did not come from {host}: "
              "the map shows blank squares where they belong; plan again when {host} "
              "answers",
        "ru": "С {host} не получено {missing:,d} из {asked:,d} тайлов подложки: на их месте "
              "на карте пустые квадраты; повторите расчёт, когда {host} доступен.",
    },
}
