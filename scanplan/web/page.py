"""The page of ``scanplan serve`` in English and Russian.

The HTML (``static/index.html``) holds no words of its own: every text the page shows is a
key of :data:`TEXTS`, in both languages (a test checks that both have every key), filled in
by the script from the configuration this module puts into the page.
"""

from __future__ import annotations

import html
import json

from .._version import __version__

__all__ = ["TEXTS", "page_html"]

TEXTS: dict[str, dict[str, str]] = {
    "en": {
        "title": "scanplan — plan on the map",
        "area": "Area", "draw": "Draw the area on the map (polygon tool, top left)",
        "drop": "…or drop a KML, KMZ, GeoJSON, GeoPackage or vertex CSV here",
        "choose_file": "Choose a file", "no_area": "No area yet",
        "area_file": "Area from", "area_drawn": "Area drawn on the map",
        "block": "…or an abstract block, width × length [m]",
        "clear_area": "Clear",
        "dem": "Terrain (DEM, GeoTIFF)", "dem_none": "No DEM: flat ground",
        "platform": "Camera type", "platform_uav": "Digital (UAV, aircraft)",
        "platform_film": "Film (scanned)", "search_camera": "Search the catalogue…",
        "scanner": "Scanner", "search_scanner": "Search the scanners…",
        "chosen": "Chosen", "main": "Main inputs", "more": "All inputs of the project file",
        "tiles": "Map", "tiles_osm": "OpenStreetMap", "tiles_none": "None (offline)",
        "results": "Result", "planning": "Planning…", "error": "Not planned",
        "rec_height": "Recommended flight height", "max_height": "Maximum planned height",
        "rec_scale": "Recommended photo scale", "scan_pixel": "Scan pixel",
        "binding": "Binding constraint", "constraint": "Constraint", "limit": "Limit",
        "margin": "Margin",
        "margin_help": "How much higher than the planned height the flight may go before "
                       "the constraint binds; film: the scan pixel's margin",
        "max_h": "Max. height, m", "pixel": "Pixel, µm",
        "gsd": "GSD (ground pixel size)", "ground_res": "Ground resolution L",
        "sigma_z": "σ_Z (height RMS)",
        "strips": "Strips", "photos": "Photos", "sorties": "Sorties", "frames": "Frames",
        "flight_time": "Flight time", "warnings": "Warnings", "chart": "Chart",
        "downloads": "Downloads", "dl_toml": "Project file (TOML)", "dl_pdf": "PDF",
        "dl_xlsx": "Workbook", "dl_zip": "Everything (zip)", "rendering": "Rendering…",
        "cm": "cm", "m": "m", "min": "min", "um": "µm", "ms": "ms",
        "legend_strip": "flight lines", "legend_photo": "photo centres",
        "legend_takeoff": "take-off", "legend_area": "area",
        "legend_gcp": "GCP", "legend_check": "checkpoint",
        "start": "Draw or drop the area and choose a camera: the plan follows every change.",
        "every": "1 in {k} shown", "planned_in": "planned in {ms} ms", "lang_other": "Русский",
        "area_km2": "Area size", "km2": "km²", "plan_crs": "Planning CRS",
        "lbl.uav.speed_ms": "Ground speed", "lbl.uav.max_flight_time_min":
        "Flight time of one sortie", "lbl.area.direction_deg": "Flight-line direction",
        "lbl.film.photo_scales": "Candidate photo scales",
        "unit.m": "m", "unit.m/s": "m/s", "unit.min": "min", "unit.s": "s", "unit.mm": "mm",
        "unit.µm": "µm", "unit.cm": "cm", "unit.h": "h", "unit.rad/s": "rad/s",
        "unit.lines/mm": "lines/mm",
    },
    "ru": {
        "title": "scanplan — проект на карте",
        "area": "Участок", "draw": "Нарисуйте участок на карте (многоугольник, слева вверху)",
        "drop": "…или перетащите сюда KML, KMZ, GeoJSON, GeoPackage или CSV вершин",
        "choose_file": "Выбрать файл", "no_area": "Участок не задан",
        "area_file": "Участок из файла", "area_drawn": "Участок нарисован на карте",
        "block": "…или условный блок, ширина × длина [м]",
        "clear_area": "Очистить",
        "dem": "Рельеф (ЦМР, GeoTIFF)", "dem_none": "Без ЦМР: ровная местность",
        "platform": "Тип камеры", "platform_uav": "Цифровая (БВС, самолёт)",
        "platform_film": "Плёночная (сканирование)", "search_camera": "Поиск по каталогу…",
        "scanner": "Сканер", "search_scanner": "Поиск сканера…",
        "chosen": "Выбрано", "main": "Основные данные", "more": "Все ключи файла проекта",
        "tiles": "Подложка", "tiles_osm": "OpenStreetMap", "tiles_none": "Нет (без сети)",
        "results": "Результат", "planning": "Расчёт…", "error": "Не рассчитано",
        "rec_height": "Рекомендуемая высота полёта", "max_height": "Максимальная плановая высота",
        "rec_scale": "Рекомендуемый масштаб снимков", "scan_pixel": "Пиксель сканирования",
        "binding": "Определяющее условие", "constraint": "Условие", "limit": "Предел",
        "margin": "Запас",
        "margin_help": "На сколько можно подняться выше плановой высоты, пока ограничение "
                       "не станет определяющим; плёнка: запас по пикселю сканирования",
        "max_h": "Наиб. высота, м", "pixel": "Пиксель, мкм",
        "gsd": "GSD (размер пикселя на местности)", "ground_res": "Разрешение на местности L",
        "sigma_z": "σ_Z (СКО по высоте)",
        "strips": "Маршруты", "photos": "Снимки", "sorties": "Вылеты", "frames": "Кадры",
        "flight_time": "Время полёта", "warnings": "Предупреждения", "chart": "График",
        "downloads": "Скачать", "dl_toml": "Файл проекта (TOML)", "dl_pdf": "PDF",
        "dl_xlsx": "Книга Excel", "dl_zip": "Всё (zip)", "rendering": "Формирование…",
        "cm": "см", "m": "м", "min": "мин", "um": "мкм", "ms": "мс",
        "legend_strip": "маршруты", "legend_photo": "центры снимков",
        "legend_takeoff": "взлёт", "legend_area": "участок",
        "legend_gcp": "опознак", "legend_check": "контрольная точка",
        "start": "Нарисуйте или перетащите участок и выберите камеру: расчёт следует за "
                 "каждым изменением.",
        "every": "показан 1 из {k}", "planned_in": "рассчитано за {ms} мс", "lang_other": "English",
        "area_km2": "Площадь", "km2": "км²", "plan_crs": "Система координат расчёта",
        "lbl.uav.speed_ms": "Путевая скорость", "lbl.uav.max_flight_time_min":
        "Продолжительность одного вылета", "lbl.area.direction_deg": "Направление маршрутов",
        "lbl.film.photo_scales": "Масштабы снимков (варианты)",
        "unit.m": "м", "unit.m/s": "м/с", "unit.min": "мин", "unit.s": "с", "unit.mm": "мм",
        "unit.µm": "мкм", "unit.cm": "см", "unit.h": "ч", "unit.rad/s": "рад/с",
        "unit.lines/mm": "мм⁻¹",
    },
}


def page_html(lang: str, tiles: str = "osm") -> str:
    """The page in ``lang`` (``"en"`` or ``"ru"``) with the default tile layer ``tiles``
    (``"osm"``, ``"none"`` or a URL template with ``{z}/{x}/{y}``)."""
    from pathlib import Path

    lang = lang if lang in TEXTS else "en"
    config = {"lang": lang, "texts": TEXTS[lang], "tiles": tiles, "version": __version__}
    text = (Path(__file__).parent / "static" / "index.html").read_text(encoding="utf-8")
    blob = json.dumps(config, ensure_ascii=False).replace("</", "<\\/")
    return (text.replace("{{lang}}", lang)
            .replace("{{title}}", html.escape(TEXTS[lang]["title"]))
            .replace("{{config}}", blob))
