/* scanplan serve: the map of the page — the background, the drawn area, the plan's layers.
   The plan's layers are updated in place: a strip whose line did not change keeps its
   element, the photo centres are one canvas drawn from the packed coordinates. */
"use strict";
window.SP = window.SP || {};
(function (SP) {
  const PALETTE = ["#d94801", "#2171b5", "#238b45", "#6a51a3", "#cb181d", "#0e7c7b",
                   "#b8860b", "#7a0177"];
  SP.PALETTE = PALETTE;

  /* packed photo centres (mapdata.pack_lonlat): base64 of int32 lon, lat in 1e-7° */
  SP.unpack = function (packed) {
    const bin = atob(packed), bytes = new Uint8Array(bin.length);
    for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
    return new Int32Array(bytes.buffer);
  };

  /* every photo centre on one canvas, redrawn after a move or zoom */
  const PhotoLayer = L.Layer.extend({
    initialize() { this._pts = new Int32Array(0); },
    setPoints(pts) { this._pts = pts; this._redraw(); },
    count() { return this._pts.length / 2; },
    onAdd(map) {
      this._canvas = L.DomUtil.create("canvas", "photo-layer leaflet-zoom-hide");
      this._canvas.setAttribute("aria-hidden", "true");
      if (!map.getPane("photos")) map.createPane("photos").style.zIndex = 450;
      map.getPane("photos").style.pointerEvents = "none";
      map.getPane("photos").appendChild(this._canvas);
      map.on("moveend zoomend resize viewreset", this._redraw, this);
      this._redraw();
    },
    onRemove(map) {
      L.DomUtil.remove(this._canvas);
      map.off("moveend zoomend resize viewreset", this._redraw, this);
    },
    _redraw() {
      const map = this._map; if (!map) return;
      const size = map.getSize(), dpr = window.devicePixelRatio || 1, c = this._canvas;
      c.width = size.x * dpr; c.height = size.y * dpr;
      c.style.width = size.x + "px"; c.style.height = size.y + "px";
      L.DomUtil.setPosition(c, map.containerPointToLayerPoint([0, 0]));
      const ctx = c.getContext("2d");
      ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
      ctx.fillStyle = "rgba(40,40,40,0.75)";
      const p = this._pts;
      for (let i = 0; i < p.length; i += 2) {
        const pt = map.latLngToContainerPoint([p[i + 1] * 1e-7, p[i] * 1e-7]);
        if (pt.x < -2 || pt.y < -2 || pt.x > size.x + 2 || pt.y > size.y + 2) continue;
        ctx.fillRect(pt.x - 1.5, pt.y - 1.5, 3, 3);
      }
    },
  });

  SP.createMap = function (T, LANG, CFG) {
    const esc = SP.esc;
    const map = L.map("map", {preferCanvas: false, keyboard: true, tap: true})
      .setView([55.75, 37.62], 13);
    const scale = L.control.scale({imperial: false});
    scale._updateMetric = function (maxMeters) {  // the scale bar in the page's language
      const m = this._getRoundNum(maxMeters);
      this._updateScale(this._mScale, m < 1000 ? `${m} ${T.m}` : `${m / 1000} ${T.km}`,
                        m / maxMeters);
    };
    scale.addTo(map);
    map.getContainer().setAttribute("aria-label", T.map_label);

    /* ------------------------------------------------------------ the background */
    const sources = CFG.basemaps || [];
    let base = null, ortho = null, offlineShown = false;
    const note = document.getElementById("map-note");
    function showNote(html) {
      note.innerHTML = html ? html + `<button type="button" class="close" aria-label="` +
        `${esc(T.close)}">×</button>` : "";
      note.hidden = !html;
    }
    function offerChoices(why) {
      const opts = sources.filter((s) => s.id !== "none").map((s) =>
        `<button type="button" data-basemap="${esc(s.id)}">${esc(s.name)}</button>`).join(" ");
      showNote(`<p>${esc(why)}</p><p class="choices">${opts}` +
        ` <button type="button" data-basemap="ortho">${esc(T.basemap_ortho)}</button></p>`);
    }
    note.addEventListener("click", (e) => {
      if (e.target.closest("button.close")) { showNote(""); return; }
      const b = e.target.closest("button[data-basemap]");
      if (b && api.onBasemapChoice) api.onBasemapChoice(b.dataset.basemap);
    });
    function setBasemap(id) {
      if (base) { map.removeLayer(base); base = null; }
      offlineShown = false;
      const s = sources.find((x) => x.id === id);
      if (!s || s.id === "none") {
        if (!ortho) offerChoices(T.no_basemap);
        else showNote("");
        return;
      }
      showNote("");
      let failed = 0, loaded = 0;
      base = L.tileLayer(s.url, {maxZoom: s.max_zoom || 19, maxNativeZoom: s.max_zoom || 19,
        attribution: s.attribution ? esc(s.attribution) : ""});
      base.on("tileerror", () => {
        if (s.offline) return;  // an MBTiles file without a tile there: not "unreachable"
        failed += 1;
        if (!loaded && failed >= 4 && !offlineShown) {
          offlineShown = true; offerChoices(T.basemap_unreachable.replace("{name}", s.name));
        }
      });
      base.on("tileload", () => { loaded += 1; if (offlineShown) { offlineShown = false; showNote(""); } });
      base.addTo(map);
    }
    function setOrtho(info) {  // {url, bounds: [[s, w], [n, e]], attribution}
      if (ortho) { map.removeLayer(ortho); ortho = null; }
      if (!info) return;
      ortho = L.imageOverlay(info.url, info.bounds, {opacity: 1, className: "ortho",
        attribution: info.attribution ? esc(info.attribution) : "", alt: info.name || ""});
      ortho.addTo(map); ortho.bringToBack();
      showNote("");
    }

    /* ------------------------------------------------------------ drawing */
    map.pm.setLang(LANG === "ru" ? "ru" : "en");
    map.pm.addControls({position: "topleft", drawMarker: false, drawCircleMarker: false,
      drawPolyline: false, drawCircle: false, drawText: false, cutPolygon: false,
      rotateMode: false, drawRectangle: true, drawPolygon: true, editMode: true,
      dragMode: true, removalMode: true});
    // the drawing buttons as buttons: a name, the keyboard (Enter, Space), a state
    const NAMES = {"polygon": T.tool_polygon, "rectangle": T.tool_rectangle,
      "edit": T.tool_edit, "drag": T.tool_drag, "delete": T.tool_delete};
    document.querySelectorAll(".leaflet-pm-toolbar .button-container").forEach((c) => {
      const a = c.querySelector("a.leaflet-buttons-control-button");
      const icon = c.querySelector(".control-icon");
      if (!a || !icon) return;
      const kind = Object.keys(NAMES).find((k) => icon.classList.contains("leaflet-pm-icon-" + k));
      if (!kind) return;
      a.setAttribute("role", "button"); a.setAttribute("tabindex", "0");
      a.setAttribute("aria-label", NAMES[kind]); a.setAttribute("title", NAMES[kind]);
      a.dataset.tool = kind;
      a.addEventListener("keydown", (e) => {
        if (e.key === "Enter" || e.key === " ") { e.preventDefault(); a.click(); }
      });
    });
    // a cancel/finish action link of geoman: a name and the keyboard as well
    map.on("pm:buttonclick pm:actionclick pm:drawstart pm:globaleditmodetoggled", () =>
      setTimeout(() => document.querySelectorAll(".leaflet-pm-actions-container a")
        .forEach((a) => { a.setAttribute("role", "button"); a.setAttribute("tabindex", "0"); }), 0));

    /* ------------------------------------------------------------ the plan's layers */
    const areaLayer = L.layerGroup().addTo(map);
    const stripLayer = L.layerGroup().addTo(map);
    const takeoffLayer = L.layerGroup().addTo(map);
    const controlLayer = L.layerGroup().addTo(map);  // [control]: GCPs and checkpoints
    const photos = new PhotoLayer().addTo(map);
    const lines = L.svg({padding: 0.3}).addTo(map);  // each strip an element (class "strip")
    let areaKey = "";
    const strips = new Map();   // number -> {key, layers}
    const takeoffs = new Map(); // sortie -> marker
    let selectStrip = null;

    function stripText(p) {
      return T.strip_tip.replace("{n}", p.number).replace("{s}", p.sorties);
    }
    function drawArea(f, drawnNow) {
      const key = f && !drawnNow ? JSON.stringify(f.geometry) : "";
      if (key === areaKey) return;
      areaKey = key; areaLayer.clearLayers();
      if (key) {
        L.geoJSON(f, {pmIgnore: true, interactive: false, style: {color: "#1f3b57", weight: 2,
          fill: true, fillOpacity: 0.06}}).addTo(areaLayer);
      }
    }
    function drawStrips(feats) {
      const seen = new Set();
      for (const f of feats) {
        const p = f.properties, n = p.number;
        seen.add(n);
        const key = JSON.stringify(f.geometry.coordinates) + "|" + p.sortie + "|" + p.sorties;
        const old = strips.get(n);
        if (old && old.key === key) continue;
        if (old) old.layers.forEach((l) => stripLayer.removeLayer(l));
        const color = PALETTE[(p.sortie - 1) % PALETTE.length];
        const layers = f.geometry.coordinates.map((line) => L.polyline(
          line.map((c) => [c[1], c[0]]), {color, weight: 3, opacity: 0.9, pmIgnore: true,
            className: `strip strip-${n}`, renderer: lines})
          .bindTooltip(stripText(p)).on("click", () => selectStrip && selectStrip(n))
          .addTo(stripLayer));
        strips.set(n, {key, layers});
      }
      for (const [n, s] of strips) {
        if (!seen.has(n)) { s.layers.forEach((l) => stripLayer.removeLayer(l)); strips.delete(n); }
      }
    }
    function drawTakeoffs(feats) {
      const seen = new Set();
      for (const f of feats) {
        const p = f.properties, ll = [f.geometry.coordinates[1], f.geometry.coordinates[0]];
        seen.add(p.sortie);
        const old = takeoffs.get(p.sortie);
        if (old) { old.setLatLng(ll); continue; }
        takeoffs.set(p.sortie, L.marker(ll, {pmIgnore: true, keyboard: false,
          icon: L.divIcon({className: "takeoff-icon", html: String(p.sortie), iconSize: [18, 18]})})
          .bindTooltip(`${T.legend_takeoff} ${p.sortie}`).addTo(takeoffLayer));
      }
      for (const [k, m] of takeoffs) {
        if (!seen.has(k)) { takeoffLayer.removeLayer(m); takeoffs.delete(k); }
      }
    }
    function drawControl(feats) {  // a red dot per GCP, a blue one per checkpoint
      controlLayer.clearLayers();
      for (const f of feats) {
        const p = f.properties, gcp = p.kind === "gcp";
        L.circleMarker([f.geometry.coordinates[1], f.geometry.coordinates[0]], {
          radius: gcp ? 4 : 3.5, color: "#000", weight: 1, fillOpacity: 1, pmIgnore: true,
          fillColor: gcp ? "#c62828" : "#1565c0"})
          .bindTooltip(`${gcp ? T.legend_gcp : T.legend_check} ${p.id}`).addTo(controlLayer);
      }
    }
    /* the plan's map (GeoJSON of /api/view); ``drawnNow``: the area is the drawn layer */
    function showPlan(fc, drawnNow, directionDeg) {
      const by = {area: [], strip: [], photos: [], takeoff: [], gcp: [], check: []};
      for (const f of fc.features) (by[f.properties.kind] || []).push(f);
      showHandle(by.area[0], by.strip[0], directionDeg);
      drawArea(by.area[0], drawnNow);
      drawStrips(by.strip);
      drawTakeoffs(by.takeoff);
      drawControl([...by.gcp, ...by.check]);
      let every = "";
      if (by.photos.length) {
        const parts = by.photos.map((f) => SP.unpack(f.properties.packed));
        const all = new Int32Array(parts.reduce((n, a) => n + a.length, 0));
        let at = 0; for (const a of parts) { all.set(a, at); at += a.length; }
        photos.setPoints(all);
        const k = Math.max(...by.photos.map((f) => f.properties.every));
        if (k > 1) every = " (" + T.every.replace("{k}", k) + ")";
      } else photos.setPoints(new Int32Array(0));
      const e = document.getElementById("every"); if (e) e.textContent = every;
    }
    function clearPlan() { showPlan({features: []}, false, null); }

    /* ------------------------------------------------------------ the line direction */
    // a handle on a line from the area's centre along the strips: dragged (or moved with
    // the arrow keys) it turns the strips; the angle is the plan's, clockwise from grid
    // north, calibrated on the drawn strips (their true bearing against the plan's
    // direction: the meridian convergence, with no formula of our own)
    const R_EARTH_M = 6371008.8;
    const rad = Math.PI / 180;
    function bearing(a, b) {  // true bearing from a to b [°], [lat, lng] pairs
      const f1 = a[0] * rad, f2 = b[0] * rad, dl = (b[1] - a[1]) * rad;
      return Math.atan2(Math.sin(dl) * Math.cos(f2),
        Math.cos(f1) * Math.sin(f2) - Math.sin(f1) * Math.cos(f2) * Math.cos(dl)) / rad;
    }
    function along(c, deg, m) {  // the point m metres from c along the true bearing deg
      const b = deg * rad;
      return [c[0] + m * Math.cos(b) / R_EARTH_M / rad,
              c[1] + m * Math.sin(b) / (R_EARTH_M * Math.cos(c[0] * rad)) / rad];
    }
    let dir = null;  // {center, radius, offset, grid, marker, line}
    let onDirection = null;
    function removeHandle() {
      if (dir) { map.removeLayer(dir.marker); map.removeLayer(dir.line); dir = null; }
    }
    function placeHandle(grid) {
      const trueDeg = grid - dir.offset;
      const end = along(dir.center, trueDeg, dir.radius);
      dir.marker.setLatLng(end);
      dir.line.setLatLngs([along(dir.center, trueDeg + 180, dir.radius), end]);
      dir.grid = grid;
      const el = dir.marker.getElement();
      if (el) el.setAttribute("aria-valuenow", grid.toFixed(1));
    }
    function gridOf(latlng) {
      const g = (bearing(dir.center, [latlng.lat, latlng.lng]) + dir.offset) % 180;
      return Math.round((g < 0 ? g + 180 : g) * 10) / 10;
    }
    function showHandle(areaF, stripF, gridDeg) {
      if (!areaF || !stripF || gridDeg == null || !isFinite(gridDeg)) { removeHandle(); return; }
      const b = L.geoJSON(areaF).getBounds(), c = b.getCenter();
      const line = stripF.geometry.coordinates[0];
      const trueStrip = bearing([line[0][1], line[0][0]], [line[1][1], line[1][0]]);
      let offset = (gridDeg - trueStrip) % 180;
      if (offset > 90) offset -= 180;
      if (offset < -90) offset += 180;
      const radius = 0.45 * map.distance(b.getSouthWest(), b.getNorthEast());
      if (!dir) {
        const marker = L.marker(c, {draggable: true, keyboard: true, pmIgnore: true,
          title: T.direction_handle, alt: T.direction_handle,
          icon: L.divIcon({className: "direction-handle", iconSize: [22, 22], html: "⟳"})});
        const guide = L.polyline([c, c], {color: "#1f3b57", weight: 2, dashArray: "6 5",
          interactive: false, pmIgnore: true});
        dir = {marker, line: guide};
        guide.addTo(map); marker.addTo(map);
        marker.on("drag", (e) => placeHandle(gridOf(e.target.getLatLng())));
        marker.on("dragend", () => onDirection && onDirection(dir.grid));
        const el = marker.getElement();
        el.setAttribute("role", "slider");
        el.setAttribute("aria-label", T.direction_handle);
        el.setAttribute("aria-valuemin", "0"); el.setAttribute("aria-valuemax", "180");
        el.addEventListener("keydown", (e) => {
          const step = e.shiftKey ? 10 : 1;
          const by = {ArrowRight: step, ArrowUp: step, ArrowLeft: -step, ArrowDown: -step}[e.key];
          if (by === undefined) return;
          e.preventDefault(); e.stopPropagation();
          placeHandle(((dir.grid + by) % 180 + 180) % 180);
          if (onDirection) onDirection(dir.grid);
        });
      }
      Object.assign(dir, {center: [c.lat, c.lng], radius, offset});
      placeHandle(((gridDeg % 180) + 180) % 180);
    }

    const legend = L.control({position: "bottomright"});
    legend.onAdd = () => {
      const d = L.DomUtil.create("div", "legend");
      d.innerHTML = `<div><i style="background:#1f3b57"></i>${esc(T.legend_area)}</div>` +
        `<div><i style="background:${PALETTE[0]}"></i>${esc(T.legend_strip)}</div>` +
        `<div><i class="dot" style="background:#333"></i>${esc(T.legend_photo)}` +
        `<span id="every"></span></div>` +
        `<div><i class="dot" style="background:#1f3b57;border:1px solid #fff"></i>` +
        `${esc(T.legend_takeoff)}</div>`;
      return d;
    };
    legend.addTo(map);

    const api = {map, setBasemap, setOrtho, showPlan, clearPlan, drawArea, photos,
      strips, onBasemapChoice: null, offerChoices, removeHandle,
      get direction() { return dir ? dir.grid : null; },
      handleCenter: () => dir && dir.center,
      set onStrip(f) { selectStrip = f; }, set onDirection(f) { onDirection = f; }};
    return api;
  };
})(window.SP);
