"""The records a norm set and the camera catalogue are made of: the smallest map objects,
cameras, lens MTF curves, the largest GSD per plan scale, scanner steps. Plain frozen
dataclasses (the norms layer; :mod:`scanplan.norms.store` loads them)."""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import Any


@dataclass(frozen=True)
class MapObject:
    """The smallest object a map scale shows (norm table ``objects``)."""

    map_scale: int
    name: str
    name_ru: str
    size_m: float
    shape: str
    source: str
    status: str = ""
    """norm, recommendation, estimate or practice (``""``: not stated)."""


PITCH_TOLERANCE = 0.02
"""Largest relative difference between a published pixel pitch and sensor width / image
width that the catalogue accepts (a published pitch is rounded, e.g. 3.3 µm for 3.2765 µm)."""


@dataclass(frozen=True)
class Camera:
    """A camera of the catalogue (film or digital).

    ``sensor_width_mm``/``image_width_px`` lie across track when the camera is mounted
    ``landscape`` (the default), as in QGroundControl. For a digital camera with an image
    width, ``pixel_um`` is the exact pitch sensor width / image width (square pixels) and
    ``published_pixel_um`` the rounded value a data sheet prints, if any.
    """

    id: str
    kind: str
    name: str
    sensor_width_mm: float
    sensor_height_mm: float
    focal_mm: float
    pixel_um: float | None = None
    image_width_px: int | None = None
    image_height_px: int | None = None
    f_number: float | None = None
    shutter: str = ""
    min_trigger_interval_s: float | None = None
    resolving_power_lpmm: float | None = None
    source: str = ""
    platform: str = ""
    orientation: str = ""
    note: str = ""
    published_pixel_um: float | None = None
    name_ru: str = ""

    def row(self) -> dict[str, Any]:
        """The catalogue row as written in ``cameras.csv`` (the published pitch, not the
        derived one, under ``pixel_um``)."""
        d = asdict(self)
        d["pixel_um"] = d.pop("published_pixel_um")
        return d

    @property
    def carrier(self) -> str:
        """``"uav"`` or ``"aircraft"`` (the ``platform`` column, or the kind's default)."""
        return self.platform or ("aircraft" if self.kind == "film" else "uav")

    def frame(self, orientation: str | None = None) -> tuple[float, float, int | None,
                                                          int | None]:
        """The imaged frame as mounted: (across, along [mm], across, along [px]).

        With an image size the frame is image size × pitch (square pixels, so the along
        side is image height × sensor width / image width, as QGroundControl's footprint);
        without one, the sensor's published sides.

        Parameters
        ----------
        orientation : {"landscape", "portrait"}, optional
            Default: the catalogue's, else landscape. Portrait puts the image height
            across track.
        """
        o = orientation or self.orientation or "landscape"
        w_px, h_px = self.image_width_px, self.image_height_px
        if self.pixel_um is not None and w_px and h_px:
            w_mm, h_mm = self.sensor_width_mm, h_px * self.sensor_width_mm / w_px
        else:
            w_mm, h_mm = self.sensor_width_mm, self.sensor_height_mm
        if o == "portrait":
            return h_mm, w_mm, h_px, w_px
        return w_mm, h_mm, w_px, h_px


@dataclass(frozen=True)
class LensCurve:
    """A lens MTF table of one camera at one image point (table ``lens_mtf``)."""

    freq_lpmm: tuple[float, ...]
    mtf: tuple[float, ...]
    source: str = ""


@dataclass(frozen=True)
class GsdLimit:
    """One row of the table ``gsd_limits``: the largest GSD of the photos for a plan scale.

    ГОСТ Р 59562-2021, Appendix Б, Table Б.1 in the bundled set; ``area`` is ``general`` or
    ``dense_urban`` (towns with dense multi-storey buildings).
    """

    map_scale: int
    area: str
    max_gsd_cm: float
    source: str = ""
    status: str = ""
    """norm, recommendation, estimate or practice (``""``: not stated)."""


@dataclass(frozen=True)
class ScannerStep:
    """One scan pixel a scanner offers, with what its source publishes about it."""

    scanner: str
    name: str
    pixel_um: float
    bit_depth: str = ""
    frame_scan_min: float | None = None
    note: str = ""
    source: str = ""
