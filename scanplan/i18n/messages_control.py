"""The sentences about ground control and checkpoints (:mod:`scanplan.project.control`).
Part of the message catalogue: :data:`scanplan.i18n.messages.MESSAGES` merges them (same
template rules, see :mod:`scanplan.i18n.messages`). Plain data; no I/O (base module)."""

from __future__ import annotations

CONTROL: dict[str, dict[str, str]] = {
    "control_too_coarse": {
        "en": "the ground control's precision ({sigma:.3f} m, axis {axis}) is only "
              "{ratio:.1f} times finer than the target ({target:.3f} m); {source} asks for "
              "{required:g} times: survey the GCPs and checkpoints more precisely "
              "(⁅[control] gcp_sigma_xy_m, gcp_sigma_z_m|the survey's precision⁆)",
        "ru": "Точность планово-высотной привязки ({sigma:.3f}~м, ось {axis}) лишь в "
              "{ratio:.1f} раза выше требуемой ({target:.3f}~м); {source} требует "
              "{required:g}-кратного запаса: определите опознаки и контрольные точки точнее "
              "(⁅[control] gcp_sigma_xy_m, gcp_sigma_z_m|точность их определения⁆).",
    },
    "control_budget_z": {
        "en": "even at best the checkpoints can show an RMSE of {rmse:.3f} m in height "
              "(σ_Z, the control and the checkpoints' own survey together), more than the "
              "{target:.3f} m the map needs: fly lower or survey the markers more precisely",
        "ru": "даже в лучшем случае СКП по высоте на контрольных точках составит "
              "{rmse:.3f}~м (σ_Z, ошибки опознаков и самих контрольных точек вместе), больше "
              "требуемых {target:.3f}~м: снизьте высоту съёмки или определяйте маркеры точнее",
    },
    "control_steep": {
        "en": "{n:,d|marker stands|markers stand} on ground steeper than the layout allows, "
              "with no flatter place near: move them in the field",
        "ru": "{n:,d|маркер стоит|маркера стоят|маркеров стоят} на более крутом склоне, чем "
              "допускает схема, и рядом нет места положе: перенесите их при полевых работах",
    },
    "control_source.asprs_control_ratio": {
        "en": "ASPRS Positional Accuracy Standards, Edition 2 (2023)",
        "ru": "стандарт точности ASPRS, ред. 2 (2023)",
    },
    "control_source.eea_control_ratio_min": {
        "en": "the EEA (Copernicus in situ requirement 321)",
        "ru": "EEA (требование 321 программы «Коперник»)",
    },
}
"""Message code → template per locale."""
