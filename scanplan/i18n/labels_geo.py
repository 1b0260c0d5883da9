"""Report labels of the flight over the area, merged into
:data:`scanplan.i18n.labels.LABELS`: the map page, the strips table, the Strips and Photos
sheets and the names written inside the exported mission and GIS files."""

from __future__ import annotations

import re

# Russian for the words of common projected-CRS names (pyproj's names are English)
_RU_CRS_WORDS = [(r"\bzone\b", "зона"), (r"\bPulkovo\b", "Пулково"),
                 (r"\bGauss-Kruger\b", "Гаусса — Крюгера"), (r"\bCM\b", "осевой меридиан"),
                 (r"\bN\b", "с.\u00a0ш."), (r"\bS\b", "ю.\u00a0ш.")]
_LATIN_WORD = re.compile(r"[A-Za-z][A-Za-z'-]*[A-Za-z]")
_RU_KEPT = {"EPSG", "UTM", "WGS", "GSK", "ETRS", "CS"}  # abbreviations kept in Russian


def crs_name(name: str, locale: str) -> str:
    """A coordinate system's name as pyproj gives it (``WGS 84 / UTM zone 37N``), its words
    in ``locale``: Russian ``WGS 84 / UTM зона 37 с. ш.`` (zone, Pulkovo, Gauss–Kruger, the
    hemisphere; no-break spaces keep ``37 с. ш.`` on one line). A Russian name that would
    keep other English words is ``""``: the EPSG code alone names the system then.
    """
    if locale != "ru" or not name:
        return name
    for letter, hemisphere in (("S", "ю.\u00a0ш."), ("N", "с.\u00a0ш.")):
        name = re.sub(rf"(\d){letter}\b", f"\\1\u00a0{hemisphere}", name)
    for pattern, word in _RU_CRS_WORDS:
        name = re.sub(pattern, word, name)
    return "" if any(w not in _RU_KEPT for w in _LATIN_WORD.findall(name)) else name


GEO: dict[str, dict[str, str]] = {
    "en": {
        "warn_area_scale_distortion": "The planning projection distorts the area",
        "warn_crosshatch": "Crosshatch (double grid)",
        "geo_crosshatch": "crosshatch (two passes at {first}° and {second}°)",
        "warn_area_latlon_swapped": "Latitude and longitude of the area look swapped",
        "warn_site_far_from_area": "The site of the sun window is far from the area",
        "warn_map_tiles_unreachable": "The map's background did not come",
        "warn_map_tiles_missing": "Part of the map's background did not come",
        "geo_export_title": "Flight plan",
        "area": "Area",
        "strips": "Strips",
        "photo_centres": "Photo centres",
        "frame_centres": "Frame centres",
        "geo_strip_n": "Strip {n}",
        "geo_sortie_n": "sortie {n}",
        "map_title": "Flight map",
        "map_title_film": "Flight scheme of the aerial survey",
        "map_ground_unknown": "Only a range of ground elevations is given, not a DEM: the "
                              "ground under each photo is not known, so the photo centres "
                              "are not coloured by their height above ground.",
        "map_north": "N",
        "map_easting_km": "Easting, km",
        "map_northing_km": "Northing, km",
        "km": "km",
        "map_legend_strips": "Strips (flight direction)",
        "map_legend_sorties": "Sortie starts (numbers)",
        "takeoff_point": "Take-off point",
        "map_legend_transit": "Transit",
        "geo_transit_km": "of which transit from and to the take-off point, km",
        "sorties": "Sorties",
        "map_local": "local frame (the block is not georeferenced)",
        "geo_summary": "Flight lines over the area",
        "area_km2": "Area, km²",
        "geo_perimeter_km": "Perimeter, km",
        "geo_direction_deg": "Strip direction (from grid north, clockwise), °",
        "geo_spacing_m": "Strip spacing, m",
        "geo_base_m": "Photo base (trigger distance), m",
        "geo_n_photos": "Number of photos",
        "geo_n_frames": "Number of frames",
        "geo_n_sorties": "Number of sorties",
        "geo_flight_km": "Flight length (strips, turns, run-in and run-out, transit), km",
        "geo_flight_min": "Flight time, min",
        "sortie": "Sortie",
        "strip_photos": "No. of photos",
        "strip_frames": "No. of frames",
        "strip_length_m": "Length, m",
        "strip_parts": "Photographed parts",
        "strip_start": "Start",
        "strip_end": "End",
        "strip_lat_lon": "latitude, longitude, °",
        "strip_xy": "easting, northing, m",
        "strips_more": "The first {shown} of {total} strips; all of them are in the workbook.",
        "strips_continued": "Battery changes in mid-strip (the next sortie continues the "
                            "strip from where the previous one ended): {list}.",
        "strip_continued_item": "strip {strip}, sortie {sortie} from photo {photo}",
        "geo_not_georeferenced": "The block is an abstract rectangle (width × length): it has "
                                 "no place on the map, so no map, mission or GIS files are "
                                 "written. Give the area as a polygon (a boundary file or a "
                                 "list of vertices) to get them.",
        "geo_not_feasible": "The flight plan cannot be flown: {reason}",
        "geo_photos_elsewhere": "{n} photo centres are too many for the workbook; they are in "
                                "the photo-centre table written beside this report.",
        "geo_photos_too_many": "{n} photo centres are too many for the workbook; the "
                               "photo-centre table is written with the mission files when "
                               "the project is planned into a folder.",
        "geo_files_note": "Files for the crew and a GIS (written beside the reports when "
                          "the project is planned into a folder): {items}.",
        "geo_file_mission": "the mission for the ground station (one per sortie)",
        "geo_file_flight": "the flight for Google Earth and for a GIS",
        "geo_file_photos": "the table of photo centres",
        "geo_file_frames": "the table of frame centres",
        "map_one_in": "1 in {k} shown",
        "map_background": "Background: {source}",
        "map_background_none": "Background: none — no tile came from {host} (see the "
                               "warnings on page 1)",
        "sheet_photos": "Photos",
        "sheet_strips_film": "Survey strips",
        "sheet_frames": "Frames",
        "photo_photo": "Photo",
        "photo_index": "No. in strip",
        "photo_x_m": "Easting, m",
        "photo_y_m": "Northing, m",
        "photo_lon_deg": "Longitude, °",
        "photo_lat_deg": "Latitude, °",
        "photo_gsd_cm": "GSD, cm",
        "photo_resolution_cm": "Ground resolution L, cm",
    },
    "ru": {
        "warn_area_scale_distortion": "Проекция планирования искажает участок",
        "warn_crosshatch": "Двойная сетка",
        "geo_crosshatch": "двойная сетка (два прохода: {first}° и {second}°)",
        "warn_area_latlon_swapped": "Широта и долгота участка, похоже, перепутаны",
        "warn_site_far_from_area": "Место расчёта окна съёмки по Солнцу далеко от участка",
        "warn_map_tiles_unreachable": "Подложка карты не получена",
        "warn_map_tiles_missing": "Подложка карты получена не полностью",
        "geo_export_title": "План полёта",
        "area": "Участок",
        "strips": "Маршруты",
        "photo_centres": "Центры снимков",
        "frame_centres": "Центры кадров",
        "geo_strip_n": "Маршрут {n}",
        "geo_sortie_n": "вылет {n}",
        "map_title": "Схема маршрутов",
        "map_title_film": "Схема маршрутов аэрофотосъёмки",
        "map_ground_unknown": "Задан только диапазон отметок местности, а не ЦМР: отметка под "
                              "каждым снимком неизвестна, поэтому центры снимков не окрашены "
                              "по высоте фотографирования над рельефом.",
        "map_north": "С",
        "map_easting_km": "Y (на восток), км",
        "map_northing_km": "X (на север), км",
        "km": "км",
        "map_legend_strips": "Маршруты (направление полёта)",
        "map_legend_sorties": "Начала вылетов (номера)",
        "takeoff_point": "Точка взлёта",
        "map_legend_transit": "Перелёт",
        "geo_transit_km": "в т. ч. перелёт от точки взлёта и обратно, км",
        "sorties": "Вылеты",
        "map_local": "местная система (участок не привязан к карте)",
        "geo_summary": "Маршруты над участком",
        "area_km2": "Площадь, км²",
        "geo_perimeter_km": "Периметр, км",
        "geo_direction_deg": "Направление маршрутов (от северного направления сетки, по "
                             "часовой стрелке), °",
        "geo_spacing_m": "Расстояние между маршрутами, м",
        "geo_base_m": "Базис фотографирования (шаг срабатывания камеры), м",
        "geo_n_photos": "Число снимков",
        "geo_n_frames": "Число кадров",
        "geo_n_sorties": "Число вылетов",
        "geo_flight_km": "Длина полёта (маршруты, развороты, заходы, перелёт), км",
        "geo_flight_min": "Время полёта, мин",
        "sortie": "Вылет",
        "strip_photos": "Снимков",
        "strip_frames": "Кадров",
        "strip_length_m": "Длина, м",
        "strip_parts": "Частей съёмки",
        "strip_start": "Начало",
        "strip_end": "Конец",
        "strip_lat_lon": "широта, долгота, °",
        "strip_xy": "координаты X (на север), Y (на восток), м",
        "strips_more": "Первые {shown} из {total} маршрутов; все — в рабочей книге.",
        "strips_continued": "Смена аккумулятора в середине маршрута (следующий вылет "
                            "продолжает маршрут с места окончания предыдущего): {list}.",
        "strip_continued_item": "маршрут {strip}, вылет {sortie} со снимка {photo}",
        "geo_not_georeferenced": "Участок задан условным прямоугольником (ширина × длина): "
                                 "он не привязан к карте, поэтому схема, полётное задание и "
                                 "файлы для ГИС не создаются. Чтобы их получить, задайте "
                                 "участок контуром (файлом границы или списком вершин).",
        "geo_not_feasible": "План полёта невыполним: {reason}",
        "geo_photos_elsewhere": "Центров снимков {n} — слишком много для рабочей книги; они "
                                "в таблице центров снимков, записанной рядом с отчётом.",
        "geo_photos_too_many": "Центров снимков {n} — слишком много для рабочей книги; "
                               "таблица центров снимков записывается вместе с полётным "
                               "заданием при расчёте проекта в папку.",
        "geo_files_note": "Файлы для экипажа и ГИС (записываются рядом с отчётами при "
                          "расчёте проекта в папку): {items}.",
        "geo_file_mission": "полётное задание для наземной станции (по одному на вылет)",
        "geo_file_flight": "маршруты для просмотра на глобусе и в ГИС",
        "geo_file_photos": "таблица центров снимков",
        "geo_file_frames": "таблица центров кадров",
        "map_one_in": "показан 1 из {k}",
        "map_background": "Подложка: {source}",
        "map_background_none": "Подложка: нет — тайлы с {host} не получены (см. "
                               "предупреждения на листе 1)",
        "sheet_photos": "Снимки",
        "sheet_strips_film": "Маршруты аэрофотосъёмки",
        "sheet_frames": "Кадры",
        "photo_photo": "Снимок",
        "photo_index": "№ в маршруте",
        "photo_x_m": "Y (на восток), м",
        "photo_y_m": "X (на север), м",
        "photo_lon_deg": "Долгота, °",
        "photo_lat_deg": "Широта, °",
        "photo_gsd_cm": "Размер пикселя на местности, см",
        "photo_resolution_cm": "Линейное разрешение на местности L, см",
    },
}
