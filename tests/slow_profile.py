"""The slow profile: the suites and tests that ``pytest -m slow`` runs and the README's test
command (``pytest -n auto``, which deselects ``slow`` in pyproject's addopts) leaves out.

CI runs both profiles, so nothing here is dropped: each entry is a whole-document sweep (every
example rendered to PDF and workbook, in both languages), a process killed or a server started,
a browser driven, or a fuzz/hostile-input campaign — each module took 15 s or more of a worker
on a 2-core machine, each single test 6 s or more.
:func:`conftest.pytest_collection_modifyitems` marks them; an entry that names no collected
test is an error, so the list cannot rot.
"""

from __future__ import annotations

SLOW_MODULES: frozenset[str] = frozenset({
    "test_campaign",
    "test_documents_text",
    "test_faults",
    "test_folder_sets",
    "test_fuzz",
    "test_help_examples",
    "test_hostile",
    "test_hostile_gis",
    "test_hostile_outputs",
    "test_install",
    "test_messages",
    "test_mission_trigger",
    "test_output_safety",
    "test_proj_offline",
    "test_run_folder",
    "test_sortie_count",
    "test_web_browser",
})
"""Modules slow as a whole: the browser, fuzz, kill, hostile-input and every-document suites."""

SLOW_TESTS: dict[str, frozenset[str]] = {
    "test_afs_norms": frozenset({"test_survey_design_sheet_in_workbook_and_pdf"}),
    "test_api_toplevel": frozenset({
        "test_batch_jobs_1_and_2_write_identical_files",
        "test_to_dict_is_the_cli_json",
    }),
    "test_area_site": frozenset({"test_the_swap_is_in_the_terminal_the_json_and_the_workbook"}),
    "test_bounded_errors": frozenset({"test_an_area_uploaded_as_flight_kml_is_once_in_the_zip"}),
    "test_catalogue": frozenset({"test_aerial_survey_wording_not_uav"}),
    "test_cli_console": frozenset({
        "test_quiet_and_verbose",
        "test_without_pdf_engine_the_rest_is_written",
    }),
    "test_consistency": frozenset({"test_inverse_table_both_columns_in_the_reports"}),
    "test_control": frozenset({"test_with_the_valley_dem_markers_leave_steep_ground"}),
    "test_crosshatch": frozenset({"test_the_documents_say_crosshatch_and_fly_both_passes"}),
    "test_documents_path": frozenset({
        "test_write_writes_every_file_plan_out_writes_byte_for_byte",
    }),
    "test_examples_headline": frozenset({"test_batch_shows_each_projects_warnings"}),
    "test_fast_reports": frozenset({
        "test_subsetting_without_layout_tables_gives_the_same_pdf",
        "test_the_stylesheet_parsed_once_gives_the_same_pages",
        "test_plan_out_with_and_without_the_worker_is_byte_identical",
    }),
    "test_geo_export_cli": frozenset({"test_a_terrain_plan_flies_its_missions_above_sea_level"}),
    "test_geo_export_dji": frozenset({
        "test_every_sortie_has_a_dji_route",
        "test_no_geoid_no_dji_file",
    }),
    "test_geo_export_wpl": frozenset({
        "test_town_examples_write_a_waypoint_file_beside_every_plan",
    }),
    "test_geo_lines": frozenset({
        "test_auto_picks_what_the_one_at_a_time_search_picked",
        "test_rectangle_layout_is_the_block_formulas",
    }),
    "test_geo_reports": frozenset({
        "test_a_large_block_keeps_its_photos_in_the_csv_only",
        "test_pdf_has_the_map_page_and_strips_table",
    }),
    "test_height_accuracy": frozenset({"test_pdf_inputs_show_the_ceiling_and_the_target_gsd"}),
    "test_init": frozenset({"test_every_catalogue_camera_gives_a_file_that_plans"}),
    "test_layers": frozenset({"test_the_package_guard_sees_a_lazy_circle"}),
    "test_limits": frozenset({"test_every_in_domain_motion_gives_a_result_or_not_feasible"}),
    "test_map_tiles": frozenset({
        "test_offline_the_pdf_is_made_without_background_and_says_so",
        "test_tiles_are_printed_under_the_flight_with_their_attribution",
    }),
    "test_pipeline_shape": frozenset({
        "test_10_a_type_checker_reads_the_api",
        "test_8_documents_are_rendered_only_by_documents_py",
        "test_9_no_ungrouped_number_with_a_unit_in_any_document",
        "test_9_no_underscore_between_letters_in_a_pdf",
        "test_9_no_latin_gsd_in_russian_documents_but_as_a_symbol",
    }),
    "test_plan_choice": frozenset({
        "test_a_spike_under_a_line_no_longer_keeps_the_height_lowered_for_it",
        "test_the_pdf_and_the_workbook_print_the_heights_flown",
        "test_the_photo_table_is_said_beside_the_report_only_when_written",
        "test_the_plans_compared_are_printed_everywhere",
    }),
    "test_references": frozenset({"test_the_pdf_and_the_workbook_of_one_run_number_a_work_alike"}),
    "test_report_layout": frozenset({"test_workbook_chart_legend_gives_a_height_as_the_pdf_does"}),
    "test_report_pdf": frozenset({
        "test_english_title_approval_and_binding",
        "test_fonts_kept_across_reports_give_the_same_pdf",
        "test_the_formulas_heading_is_not_left_alone_at_a_page_foot",
    }),
    "test_rules_registry": frozenset({"test_dummy_constraint_flows_into_the_workbook_and_pdf"}),
    "test_russian_surveyor_text": frozenset({
        "test_no_shape_coefficient_with_a_decimal_point_in_a_russian_workbook",
    }),
    "test_sortie_time_as_flown": frozenset({"test_no_sortie_exceeds_its_battery_as_flown"}),
    "test_strip_sorties": frozenset({"test_the_workbook_strips_sheet_shows_both_sorties"}),
    "test_svgchart": frozenset({"test_a_plan_with_both_reports_imports_no_matplotlib"}),
    "test_terrain_exports": frozenset({
        "test_strip_and_follow_missions_hold_every_altitude_of_the_plan",
    }),
    "test_terrain_film": frozenset({
        "test_failing_photos_are_marked_and_the_flat_map_is_unchanged",
        "test_text_excel_and_pdf_report_the_local_scales",
        "test_the_map_colours_photos_by_height_above_ground_in_one_raster_layer",
    }),
    "test_terrain_project": frozenset({
        "test_a_pinned_mode_that_costs_far_more_is_a_warning_with_the_saving",
        "test_strip_and_follow_modes_allow_a_higher_plan",
        "test_the_valley_shows_what_flat_ground_misses",
        "test_the_workbook_has_a_terrain_sheet_per_strip",
    }),
    "test_web_api": frozenset({
        "test_bad_input_is_422_with_the_cli_message",
        "test_every_example_through_the_api_is_plan_json",
        "test_pdf_and_workbook_downloads",
        "test_the_project_file_round_trips_to_the_cli",
        "test_the_zip_holds_reports_missions_gis_and_a_project_that_runs",
        "test_no_job_folder_is_left_behind",
    }),
    "test_web_documents": frozenset({
        "test_only_the_latest_quiet_request_is_rendered_ahead",
        "test_the_downloads_are_the_download_jobs_bytes",
        "test_a_download_after_the_view_is_the_rendered_one",
    }),
    "test_web_page": frozenset({
        "test_the_downloaded_zip_opens_with_its_files",
        "test_the_basemap_is_printed_on_the_pdf_map_page",
    }),
}
"""Single slow tests (every parameter of each) in modules that are otherwise quick."""
