"""Report labels of the ground control and checkpoints (``[control]``), merged into
:data:`scanplan.i18n.labels.LABELS`: the control section of the PDF and the workbook, the
terminal's lines, the map's legend and the names inside the exported files."""

from __future__ import annotations

CONTROL: dict[str, dict[str, str]] = {
    "en": {
        "control_points": "Ground control and checkpoints",
        "control_mode": "Control of the block",
        "control_mode_gcp": "ground control points (GCPs)",
        "control_mode_rtk": "RTK camera positions, GCPs at the corners and the centre",
        "control_mode_ppk": "PPK camera positions, GCPs at the corners and the centre",
        "control_mode_direct": "direct georeferencing, no GCPs",
        "control_gcps": "Ground control points (GCPs)",
        "control_checkpoints": "Independent checkpoints",
        "control_corners": "GCPs at the corners of the blocks",
        "control_spacing_m": "GCP spacing along the boundary and of the interior grid, m",
        "control_inset_m": "Markers inside the boundary by at least, m",
        "control_separation_m": "Least distance from a checkpoint to a GCP, m",
        "control_per_100_photos": "GCPs per 100 photos",
        "control_per_ha": "GCPs per hectare",
        "control_max_bases": "Largest distance from a photo centre to its nearest GCP, "
                             "in bases",
        "control_min_photos": "Fewest photos that see a marker",
        "control_sigma_xy": "Survey precision of the markers, horizontal (RMSE_H), m",
        "control_sigma_z": "Survey precision of the markers, vertical (RMSE_Z), m",
        "control_budget": "Error budget at checkpoints, at best",
        "control_budget_z": "Vertical RMSE at best = √(σ_Z² + σ_control² + σ_checkpoint²), m",
        "control_budget_h": "Horizontal RMSE_H at best = √(σ_image² + σ_control² + "
                            "σ_checkpoint²), m",
        "control_sigma_model_z": "σ_Z of the block (idealised stereo precision), m",
        "control_sigma_model_h": "σ of the block in plan (√2·σ_px·GSD), m",
        "control_target_z": "Required height accuracy V_z, m",
        "control_target_h": "Required planimetric accuracy V_s·Mk, m",
        "control_at_best": "at best",
        "control_at_best_note": "The RMSE at best is the least the checkpoints can show: the "
                                "block's own precision, the control's and the checkpoints' "
                                "survey errors added as independent errors; calibration, image "
                                "blur and the identification of the markers add to it.",
        "control_check": "Control precision against the target",
        "control_ratio": "target / precision",
        "control_ok": "met",
        "control_not_ok": "not met",
        "control_axis_z": "height",
        "control_axis_h": "plan",
        "control_rules": "Layout rules",
        "control_rule": "rule",
        "control_value": "value",
        "control_status": "status",
        "control_source": "source",
        "control_gcp": "GCP",
        "control_check_point": "checkpoint",
        "control_checkpoints_asprs": "the count of the ASPRS table for the area",
        "control_checkpoints_project": "as given in the project",
        "status_foreign": "foreign recommendation",
        "status_assumption": "assumption",
        "control_rule_asprs_checkpoints": "Checkpoints (ASPRS Ed. 2, Table C.1, first row)",
        "control_rule_asprs_checkpoints_area_km2": "…for a project area up to, km²",
        "control_rule_asprs_control_ratio": "Control and checkpoints more accurate than the "
                                            "product by (ASPRS Ed. 2)",
        "control_rule_eea_control_ratio_min": "GCPs more precise than the target by at least "
                                              "(EEA)",
        "control_rule_eea_control_ratio_recommended": "…recommended (EEA)",
        "control_rule_interior_gcp_per_ha": "Interior GCPs per hectare",
        "control_rule_inset_footprint": "Inset from the boundary, of the shorter footprint "
                                        "side",
        "control_rule_check_separation": "Least checkpoint–GCP distance, of the GCP spacing",
        "control_rule_rtk_interior_gcps": "RTK/PPK: interior GCPs per block",
        "control_rule_max_marker_slope_pct": "Steepest ground for a marker, %",
        "control_sheet": "Control",
        "pdf_warn_control_too_coarse": "Ground control too coarse for the target",
        "pdf_warn_control_budget_z": "Height target not reachable at checkpoints",
        "pdf_warn_control_steep": "Markers on steep ground",
        "map_legend_gcp": "GCPs",
        "map_legend_checkpoint": "Checkpoints",
        "control_source_scanplan": "the planner's own layout rule (no norm read gives one)",
        "control_source_practice": "common practice (no norm read gives a number)",
    },
    "ru": {
        "control_points": "Опознаки и контрольные точки",
        "control_mode": "Привязка блока",
        "control_mode_gcp": "по опознакам",
        "control_mode_rtk": "центры фотографирования RTK, опознаки в углах и в центре",
        "control_mode_ppk": "центры фотографирования PPK, опознаки в углах и в центре",
        "control_mode_direct": "прямое геопозиционирование, без опознаков",
        "control_gcps": "Опознаки (планово-высотные)",
        "control_checkpoints": "Независимые контрольные точки",
        "control_corners": "Опознаки в углах блоков",
        "control_spacing_m": "Расстояние между опознаками по границе и в сетке внутри, м",
        "control_inset_m": "Отступ маркеров от границы участка не менее, м",
        "control_separation_m": "Наименьшее расстояние от контрольной точки до опознака, м",
        "control_per_100_photos": "Опознаков на 100 снимков",
        "control_per_ha": "Опознаков на гектар",
        "control_max_bases": "Наибольшее удаление центра снимка от ближайшего опознака, "
                             "в базисах",
        "control_min_photos": "Наименьшее число снимков, на которых виден маркер",
        "control_sigma_xy": "Точность определения маркеров в плане (СКП), м",
        "control_sigma_z": "Точность определения маркеров по высоте (СКП), м",
        "control_budget": "Бюджет ошибок на контрольных точках, в лучшем случае",
        "control_budget_z": "СКП по высоте в лучшем случае = √(σ_Z² + σ_опознаков² + "
                            "σ_контрольных точек²), м",
        "control_budget_h": "СКП в плане в лучшем случае = √(σ_снимка² + σ_опознаков² + "
                            "σ_контрольных точек²), м",
        "control_sigma_model_z": "σ_Z блока (идеализированная стереоточность), м",
        "control_sigma_model_h": "σ блока в плане (√2·σ_px·GSD), м",
        "control_target_z": "Требуемая точность по высоте V_z, м",
        "control_target_h": "Требуемая точность в плане V_s·Mk, м",
        "control_at_best": "в лучшем случае",
        "control_at_best_note": "СКП в лучшем случае — наименьшая, какую могут показать "
                                "контрольные точки: собственная точность блока, ошибки "
                                "определения опознаков и контрольных точек, сложенные как "
                                "независимые; калибровка, смаз изображения и опознавание "
                                "маркеров добавят к ней.",
        "control_check": "Точность привязки относительно требуемой",
        "control_ratio": "требуемая / точность",
        "control_ok": "выполнено",
        "control_not_ok": "не выполнено",
        "control_axis_z": "высота",
        "control_axis_h": "план",
        "control_rules": "Правила размещения",
        "control_rule": "правило",
        "control_value": "значение",
        "control_status": "статус",
        "control_source": "источник",
        "control_gcp": "опознак",
        "control_check_point": "контрольная точка",
        "control_checkpoints_asprs": "число по таблице ASPRS для площади участка",
        "control_checkpoints_project": "как задано в проекте",
        "status_foreign": "зарубежная рекомендация",
        "status_assumption": "допущение",
        "control_rule_asprs_checkpoints": "Контрольных точек (ASPRS, ред. 2, табл. C.1, "
                                          "первая строка)",
        "control_rule_asprs_checkpoints_area_km2": "…для площади участка до, км²",
        "control_rule_asprs_control_ratio": "Опознаки и контрольные точки точнее продукции "
                                            "в (ASPRS, ред. 2), раз",
        "control_rule_eea_control_ratio_min": "Опознаки точнее требуемой точности не менее "
                                              "чем в (EEA), раз",
        "control_rule_eea_control_ratio_recommended": "…рекомендуется (EEA), раз",
        "control_rule_interior_gcp_per_ha": "Опознаков внутри участка на гектар",
        "control_rule_inset_footprint": "Отступ от границы, доля меньшей стороны кадра на "
                                        "местности",
        "control_rule_check_separation": "Наименьшее расстояние контрольная точка — "
                                         "опознак, доля шага опознаков",
        "control_rule_rtk_interior_gcps": "RTK/PPK: опознаков внутри блока",
        "control_rule_max_marker_slope_pct": "Наибольшая крутизна склона под маркером, %",
        "control_sheet": "Привязка",
        "pdf_warn_control_too_coarse": "Привязка грубее требуемой точности",
        "pdf_warn_control_budget_z": "Требуемая точность по высоте недостижима на "
                                     "контрольных точках",
        "pdf_warn_control_steep": "Маркеры на крутых склонах",
        "map_legend_gcp": "Опознаки",
        "map_legend_checkpoint": "Контрольные точки",
        "control_source_scanplan": "правило размещения планировщика (в прочитанных нормах "
                                   "его нет)",
        "control_source_practice": "распространённая практика (в прочитанных нормах числа "
                                   "нет)",
    },
}
"""Label key → text per locale."""
