"""The page of ``scanplan serve`` in English and Russian.

The HTML (``static/index.html``) holds no words of its own: every text the page shows is a
key of :data:`TEXTS`, in both languages (a test checks that both have every key), filled in
by the script from the configuration this module puts into the page.
"""

from __future__ import annotations

import html
import json
from typing import Any

from .._version import __version__

__all__ = ["TEXTS", "page_html"]

TEXTS: dict[str, dict[str, str]] = {
    "en": {
        "title": "scanplan — plan on the map",
        "skip": "Skip to the inputs", "new_plan": "New plan",
        "map_label": "Map: the area, the flight lines and the photo centres",
        "inputs_label": "Inputs",
        "choose_area": "Choose an area file", "block_w": "Block width, m",
        "block_l": "Block length, m", "remove": "Remove",
        "open": "Open a project file or the downloaded zip", "opened": "Opened",
        "open_missing": "Opened; upload {files} as well (the project names it)",
        "upload_lost": "The server no longer keeps {files}: choose it again",
        "basemap": "Background map", "basemap_ortho": "An orthophoto, GeoTIFF or MBTiles…",
        "ortho_choose": "Choose a GeoTIFF or MBTiles",
        "no_basemap": "No background map: the area is "
        "drawn blind. Choose one:",
        "basemap_unreachable": "{name} does not answer (offline?). Choose another background:",
        "camera": "Camera", "no_camera": "No camera chosen yet",
        "need_camera": "Choose a camera: the plan follows.",
        "stale": "These results are of the last inputs that could be planned, not of the ones "
                 "shown now.",
        "constraints_caption": "The constraints and their limits",
        "tool_polygon": "Draw a polygon", "tool_rectangle": "Draw a rectangle",
        "tool_edit": "Edit vertices: drag one, click a midpoint to add one, right-click to "
                     "remove one", "tool_drag": "Move the whole area",
        "tool_delete": "Erase the area",
        "strip_tip": "Strip {n} · sortie {s}", "m2": "m²", "s": "s", "unit_mm": "mm",
        "downloaded": "Downloaded", "alternatives": "Alternatives", "close": "Close",
        "default_name": "Survey plan",
        "profile": "Strip profile over the DEM", "profile_strip": "Strip (or click one on "
        "the map)", "profile_x": "distance along the strip, km", "profile_y": "height, m",
        "profile_flight": "flight altitude", "profile_ground": "ground under each photo",
        "profile_aria": "Strip {n}: the ground under each photo and the flight altitude",
        "direction_handle": "Flight-line direction: drag the handle or use the arrow keys",
        "chart_open": "Click a chart to see it at full size.",
        "chart_height": "GSD and ground resolution L against the flight height",
        "chart_constraints": "The constraints' scan pixel against the photo scale",
        "sec.project": "Project and signatures", "sec.norms": "Norms",
        "sec.norms.block_relief": "Norms: relief of a block", "sec.norms.gsd_limits":
        "Norms: largest GSD", "sec.film": "Film camera", "sec.uav": "Digital camera and flight",
        "sec.uav.atmosphere": "Atmosphere", "sec.uav.motion": "Image motion",
        "sec.uav.target": "Target contrast", "sec.area": "Area and flight lines",
        "sec.flight": "Flight", "sec.terrain": "Terrain", "sec.site": "Site",
        "sec.schedule": "Schedule", "sec.map": "Map",
        "lbl.project.name": "Project name", "lbl.project.approver_position":
        "Approved by: position", "lbl.project.approver_name": "Approved by: name",
        "lbl.project.agreed_position": "Agreed by (customer): position",
        "lbl.project.agreed_name": "Agreed by (customer): name",
        "lbl.project.agreed_organisation": "Agreed by (customer): organisation",
        "lbl.project.purpose": "Purpose of the survey", "lbl.project.height_system":
        "Height system",
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
        "tiles_osm": "OpenStreetMap", "tiles_none": "None (offline)",
        "results": "Result", "planning": "Planning…", "error": "Not planned",
        "rec_height": "Recommended flight height", "max_height": "Maximum planned height",
        "rec_scale": "Recommended photo scale", "scan_pixel": "Scan pixel",
        "binding": "Binding constraint", "constraint": "Constraint", "limit": "Limit",
        "margin": "Margin",
        "margin_help": "The constraint's headroom over the binding one, as in the "
                       "documents: how much larger its limit is (UAV: its maximum planned "
                       "height; film: its scan pixel)",
        "max_h": "Max. height, m", "pixel": "Pixel, µm",
        "gsd": "GSD (ground pixel size)", "ground_res": "Ground resolution L",
        "sigma_z": "σ_Z (height RMS)",
        "strips": "Strips", "photos": "Photos", "sorties": "Sorties", "frames": "Frames",
        "flight_time": "Flight time", "warnings": "Warnings", "chart": "Chart",
        "downloads": "Downloads", "dl_toml": "Project file (TOML)", "dl_pdf": "PDF",
        "dl_xlsx": "Workbook", "dl_zip": "Everything (zip)", "rendering": "Rendering…",
        "cm": "cm", "m": "m", "km": "km", "min": "min", "um": "µm", "ms": "ms",
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
        "skip": "К исходным данным", "new_plan": "Новый проект",
        "map_label": "Карта: участок, маршруты и центры снимков",
        "inputs_label": "Исходные данные",
        "choose_area": "Выбрать файл участка", "block_w": "Ширина блока, м",
        "block_l": "Длина блока, м", "remove": "Убрать",
        "open": "Открыть файл проекта или скачанный zip", "opened": "Открыт",
        "open_missing": "Открыт; загрузите также {files} (файл назван в проекте)",
        "upload_lost": "Сервер больше не хранит {files}: выберите файл снова",
        "basemap": "Подложка", "basemap_ortho": "Ортофотоплан, GeoTIFF или MBTiles…",
        "ortho_choose": "Выбрать GeoTIFF или MBTiles",
        "no_basemap": "Нет подложки: участок рисуется "
        "вслепую. Выберите:",
        "basemap_unreachable": "{name} не отвечает (нет сети?). Выберите другую подложку:",
        "camera": "Аэрофотоаппарат", "no_camera": "Аэрофотоаппарат не выбран",
        "need_camera": "Выберите аэрофотоаппарат: расчёт последует.",
        "stale": "Показаны результаты последних данных, по которым удалось рассчитать, а не "
                 "текущих.",
        "constraints_caption": "Условия и их пределы",
        "tool_polygon": "Нарисовать многоугольник", "tool_rectangle": "Нарисовать прямоугольник",
        "tool_edit": "Править вершины: перетащить, щелчок по середине стороны — добавить, "
                     "правый щелчок — удалить", "tool_drag": "Переместить весь участок",
        "tool_delete": "Стереть участок",
        "strip_tip": "Маршрут {n} · вылет {s}", "m2": "м²", "s": "с", "unit_mm": "мм",
        "downloaded": "Скачано", "alternatives": "Варианты", "close": "Закрыть",
        "default_name": "План съёмки",
        "profile": "Профиль маршрута по ЦМР", "profile_strip": "Маршрут (или щёлкните по "
        "нему на карте)", "profile_x": "расстояние вдоль маршрута, км",
        "profile_y": "высота, м", "profile_flight": "высота полёта",
        "profile_ground": "рельеф под каждым снимком",
        "profile_aria": "Маршрут {n}: рельеф под каждым снимком и высота полёта",
        "direction_handle": "Направление маршрутов: перетащите маркер или нажимайте стрелки",
        "chart_open": "Щелчок по графику открывает его в полном размере.",
        "chart_height": "GSD и разрешение на местности L в зависимости от высоты полёта",
        "chart_constraints": "Пиксель сканирования по условиям в зависимости от масштаба "
                             "снимков",
        "sec.project": "Проект и подписи", "sec.norms": "Нормативы",
        "sec.norms.block_relief": "Нормативы: рельеф блока", "sec.norms.gsd_limits":
        "Нормативы: наибольший GSD", "sec.film": "Плёночная камера",
        "sec.uav": "Цифровая камера и полёт", "sec.uav.atmosphere": "Атмосфера",
        "sec.uav.motion": "Сдвиг изображения", "sec.uav.target": "Контраст объекта",
        "sec.area": "Участок и маршруты", "sec.flight": "Полёт", "sec.terrain": "Рельеф",
        "sec.site": "Место работ", "sec.schedule": "Календарь", "sec.map": "Карта",
        "lbl.project.name": "Название проекта", "lbl.project.approver_position":
        "Утверждает: должность", "lbl.project.approver_name": "Утверждает: ФИО",
        "lbl.project.agreed_position": "Согласовано (заказчик): должность",
        "lbl.project.agreed_name": "Согласовано (заказчик): ФИО",
        "lbl.project.agreed_organisation": "Согласовано (заказчик): организация",
        "lbl.project.purpose": "Назначение работ", "lbl.project.height_system":
        "Система высот",
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
        "tiles_osm": "OpenStreetMap", "tiles_none": "Нет (без сети)",
        "results": "Результат", "planning": "Расчёт…", "error": "Не рассчитано",
        "rec_height": "Рекомендуемая высота полёта", "max_height": "Максимальная плановая высота",
        "rec_scale": "Рекомендуемый масштаб снимков", "scan_pixel": "Пиксель сканирования",
        "binding": "Определяющее условие", "constraint": "Условие", "limit": "Предел",
        "margin": "Запас",
        "margin_help": "Запас условия относительно определяющего, как в документах: "
                       "насколько больше его предел (БВС: наибольшая плановая высота; "
                       "плёнка: пиксель сканирования)",
        "max_h": "Наиб. высота, м", "pixel": "Пиксель, мкм",
        "gsd": "GSD (размер пикселя на местности)", "ground_res": "Разрешение на местности L",
        "sigma_z": "σ_Z (СКО по высоте)",
        "strips": "Маршруты", "photos": "Снимки", "sorties": "Вылеты", "frames": "Кадры",
        "flight_time": "Время полёта", "warnings": "Предупреждения", "chart": "График",
        "downloads": "Скачать", "dl_toml": "Файл проекта (TOML)", "dl_pdf": "PDF",
        "dl_xlsx": "Книга Excel", "dl_zip": "Всё (zip)", "rendering": "Формирование…",
        "cm": "см", "m": "м", "km": "км", "min": "мин", "um": "мкм", "ms": "мс",
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


def page_html(lang: str, basemaps: list[dict[str, Any]] | None = None,
              default: str = "none") -> str:
    """The page in ``lang`` (``"en"`` or ``"ru"``) offering the background maps ``basemaps``
    (:meth:`scanplan.web.basemap.Basemaps.page_list`; "none" always) with ``default`` shown
    first."""
    from pathlib import Path

    lang = lang if lang in TEXTS else "en"
    none = {"id": "none", "name": TEXTS[lang]["tiles_none"]}
    config = {"lang": lang, "texts": TEXTS[lang], "basemaps": [*(basemaps or []), none],
              "basemap_default": default, "version": __version__}
    text = (Path(__file__).parent / "static" / "index.html").read_text(encoding="utf-8")
    blob = json.dumps(config, ensure_ascii=False).replace("</", "<\\/")
    return (text.replace("{{lang}}", lang)
            .replace("{{title}}", html.escape(TEXTS[lang]["title"]))
            .replace("{{config}}", blob))
