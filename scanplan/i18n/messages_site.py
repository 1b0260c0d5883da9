"""The sentences about where the area is: coordinates that look swapped, a site of the sun
window far from the area (:mod:`scanplan.project.site`). Part of the message catalogue:
:data:`scanplan.i18n.messages.MESSAGES` merges them (same template rules, see
:mod:`scanplan.i18n.messages`). Plain data; no I/O (base module)."""

from __future__ import annotations

SITE: dict[str, dict[str, str]] = {
    "area_latlon_swapped": {
        "en": "the area lies at longitude {lon:.4f}°, latitude {lat:.4f}°; with latitude and "
              "longitude swapped it would lie at longitude {slon:.4f}°, latitude "
              "{slat:.4f}°, and {why}: latitude and longitude look swapped. Check the "
              "coordinate order of the area: a GeoJSON or KML file and the inline polygon "
              "give the longitude first, [lon, lat]",
        "ru": "Участок находится на долготе {lon:.4f}°, широте {lat:.4f}°; если поменять "
              "широту и долготу местами, он окажется на долготе {slon:.4f}°, широте "
              "{slat:.4f}°, и {why}: похоже, широта и долгота перепутаны. Проверьте порядок "
              "координат участка: в файле границы участка и в полигоне, заданном в проекте, "
              "первой идёт долгота — [долгота, широта].",
    },
    "area_swap.site": {
        "en": "the site given for the sun window is {swapped:,.0f} km from there, but "
              "{given:,.0f} km from the area as given",
        "ru": "место, заданное для расчёта окна съёмки по Солнцу, — в {swapped:,.0f}~км "
              "оттуда, но в {given:,.0f}~км от участка в заданных координатах",
    },
    "area_swap.crs": {
        "en": "there it lies within the area of use of {crs}, where the given coordinates "
              "do not",
        "ru": "там он лежит в области применения системы координат {crs}, а в заданных "
              "координатах — нет",
    },
    "site_far_from_area": {
        "en": "the site of the sun window (latitude {lat:.4f}°, longitude {lon:.4f}°, "
              "⁅[site] lat_deg, lon_deg|as given in the project⁆) is {km:,.0f} km from the "
              "centre of the area (latitude {alat:.4f}°, longitude {alon:.4f}°), farther "
              "than {limit:g} km: the sun's elevation there differs from the area's by up to "
              "{deg:.1f}°, so the sun window and the flying days are another place's. Give "
              "the site of the area, or leave the site out: the sun window is then computed "
              "at the area's centre (up to {limit:g} km the elevation differs by less than "
              "0.5°)",
        "ru": "Место расчёта окна съёмки по Солнцу (широта {lat:.4f}°, долгота {lon:.4f}°, "
              "⁅[site] lat_deg, lon_deg|как задано в проекте⁆) находится в {km:,.0f}~км от "
              "центра участка (широта {alat:.4f}°, долгота {alon:.4f}°), дальше {limit:g}~км: "
              "высота Солнца там отличается от высоты над участком до {deg:.1f}°, и окно "
              "съёмки и число лётных дней рассчитаны для другого места. Задайте место "
              "участка или не задавайте место вовсе: тогда окно рассчитывается для центра "
              "участка (в пределах {limit:g}~км высота Солнца отличается менее чем на "
              "0,5°).",
    },
}
"""Message code → template per locale."""
