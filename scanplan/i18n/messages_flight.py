"""The sentences about the aircraft and its sorties: an unknown sortie time, a speed above
the aircraft's, a plan that needs more flying days than the crew has, the take-off point
assumed (:mod:`scanplan.project.aircraftplan`). Part of the message catalogue:
:data:`scanplan.i18n.messages.MESSAGES` merges them (same template rules, see
:mod:`scanplan.i18n.messages`). Plain data; no I/O (base module)."""

from __future__ import annotations

FLIGHT: dict[str, dict[str, str]] = {
    "sortie_time_unknown": {
        "en": "the sortie time is unknown: the {hours:,.1f} h of flight are not split into "
              "sorties, and the number of sorties and batteries is not counted. Give "
              "⁅[uav] aircraft|the aircraft⁆ or ⁅[uav] max_flight_time_min|the flight time "
              "of one sortie⁆",
        "ru": "Продолжительность вылета неизвестна: {hours:,.1f}~ч полёта не разделены на "
              "вылеты, число вылетов и аккумуляторов не подсчитано. Укажите ⁅[uav] "
              "aircraft|носитель⁆ или ⁅[uav] max_flight_time_min|продолжительность "
              "вылета⁆.",
    },
    "aircraft_sortie": {
        "en": "sorties of {minutes:.0f} min: the {name}'s published flight time of "
              "{published:g} min ({conditions}) less the {reserve:g} % battery reserve",
        "ru": "Вылеты по {minutes:.0f}~мин: опубликованная продолжительность полёта "
              "{name} {published:g}~мин ({conditions}) за вычетом резерва аккумулятора "
              "{reserve:g}~%.",
    },
    "flight_time.no_payload_windless_to_empty": {
        "en": "without payload, in still air, until the battery is empty",
        "ru": "без полезной нагрузки, в безветрие, до полного разряда аккумулятора",
    },
    "flight_time.approximate": {"en": "an approximate figure",
                                "ru": "приблизительное значение"},
    "aircraft_camera_unlisted": {
        "en": "the catalogue does not list the camera {camera} on the {name} (it lists "
              "{cameras}); check that the aircraft carries it",
        "ru": "В каталоге камера {camera} не указана для {name} (указаны: {cameras}); "
              "проверьте, что носитель её несёт.",
    },
    "aircraft_speed_above_max": {
        "en": "the ground speed {speed:g} m/s is above the {name}'s maximum of {max:g} m/s",
        "ru": "Путевая скорость {speed:g}~м/с больше наибольшей скорости {name} "
              "{max:g}~м/с.",
    },
    "takeoff_assumed": {
        "en": "no take-off point is given: each sortie is taken to take off from the "
              "area's boundary point nearest its first strip and to return there; the "
              "transit there and back ({km:,.1f} km in all) is in the sorties' time. Give "
              "⁅[flight] takeoff|the take-off point⁆ where the crew launches",
        "ru": "Точка взлёта не задана: принято, что каждый вылет начинается в ближайшей к "
              "его первому маршруту точке границы участка и возвращается туда же; перелёт "
              "туда и обратно ({km:,.1f}~км всего) учтён во времени вылетов. Укажите "
              "⁅[flight] takeoff|точку взлёта⁆, откуда взлетает экипаж.",
    },
    "flying_days_exceeded": {
        "en": "the flight needs {needed}, more than the {most:,} the crew has (⁅[flight] "
              "max_flying_days|the most flying days⁆): split the area, fly higher or bring "
              "more aircraft",
        "ru": "Для полёта нужно {needed} — больше, чем {most:,}, которые есть у экипажа "
              "(⁅[flight] max_flying_days|наибольшее число лётных дней⁆): разделите "
              "участок, поднимите высоту или привлеките больше носителей.",
    },
    "flying_days.at_least": {
        "en": "at least {days:,} days of flying around the clock",
        "ru": "не менее {days:,}~суток круглосуточных полётов",
    },
    "flying_days.by_schedule": {
        "en": "{days:,} flying days in the schedule's sun windows",
        "ru": "{days:,}~лётных дней в окнах съёмки по Солнцу",
    },
}
