/* scanplan serve: the page. No engine here: the project is sent to the JSON API, which plans
   it as `scanplan plan` does; this script draws what comes back. */
"use strict";
(function () {
  const CFG = JSON.parse(document.getElementById("config").textContent);
  const T = CFG.texts, LANG = CFG.lang;
  const params = new URLSearchParams(location.search);
  const TOKEN = params.get("token") || "";
  const $ = (id) => document.getElementById(id);
  const fmt = (x, d) => x == null || !isFinite(x) ? "—" :
    Number(x).toLocaleString(LANG === "ru" ? "ru-RU" : "en-GB",
                             {minimumFractionDigits: d, maximumFractionDigits: d});
  const esc = (s) => String(s).replace(/[&<>"']/g, (c) => ({"&": "&amp;", "<": "&lt;",
    ">": "&gt;", '"': "&quot;", "'": "&#39;"}[c]));

  document.querySelectorAll("[data-t]").forEach((el) => { el.textContent = T[el.dataset.t]; });
  document.title = T.title;
  const other = LANG === "ru" ? "en" : "ru";
  const otherParams = new URLSearchParams(location.search);
  otherParams.set("lang", other);
  $("lang-other").href = "?" + otherParams.toString();
  $("camera-search").placeholder = T.search_camera;
  $("scanner-search").placeholder = T.search_scanner;

  /* ---------------------------------------------------------------- state */
  const state = {
    platform: "uav", camera: null, scanner: null,
    polygon: null,            // [[lon, lat], ...] drawn on the map
    areaFile: null,           // {name, id} an uploaded area file
    dem: null,                // {name, id}
    fields: {},               // "section.key" -> input element
    inputs: [], catalogue: {cameras: [], scanners: []},
    seq: 0, controller: null, fitted: false,
  };

  async function api(path, options) {
    const opts = Object.assign({headers: {}}, options || {});
    if (TOKEN) opts.headers["X-Scanplan-Token"] = TOKEN;
    return fetch("api/" + path, opts);
  }

  /* ---------------------------------------------------------------- map */
  const map = L.map("map", {preferCanvas: true}).setView([55.75, 37.62], 14);
  L.control.scale({imperial: false}).addTo(map);
  let tileLayer = null;
  function setTiles(kind) {
    if (tileLayer) { map.removeLayer(tileLayer); tileLayer = null; }
    if (kind === "none") return;
    const url = kind === "osm" ? "https://tile.openstreetmap.org/{z}/{x}/{y}.png" : kind;
    tileLayer = L.tileLayer(url, {maxZoom: 19,
      attribution: kind === "osm" ? "© OpenStreetMap contributors" : ""}).addTo(map);
  }
  // the address may choose between the built-in layers; another tile server only by --tiles
  const asked = params.get("tiles");
  const tiles = ["osm", "none"].includes(asked) ? asked : CFG.tiles || "osm";
  const tilesSelect = $("tiles");
  if (!["osm", "none"].includes(tiles)) {
    const o = document.createElement("option"); o.value = tiles; o.textContent = tiles;
    tilesSelect.appendChild(o);
  }
  tilesSelect.value = tiles;
  setTiles(tiles);
  tilesSelect.addEventListener("change", () => setTiles(tilesSelect.value));

  map.pm.setLang(LANG === "ru" ? "ru" : "en");
  map.pm.addControls({position: "topleft", drawMarker: false, drawCircleMarker: false,
    drawPolyline: false, drawCircle: false, drawText: false, cutPolygon: false,
    rotateMode: false, drawRectangle: true, drawPolygon: true, editMode: true,
    dragMode: true, removalMode: true});
  let drawn = null;
  const planLayer = L.layerGroup().addTo(map);
  const palette = ["#d94801", "#2171b5", "#238b45", "#6a51a3", "#cb181d", "#0e7c7b",
                   "#b8860b", "#7a0177"];

  /* a number with the decimals of its key's registry record (GET /api/inputs: digits) */
  function digitsOf(key) {
    const row = state.inputs.find((r) => r.section + "." + r.key === key);
    return row && row.digits != null ? row.digits : null;
  }
  const withDigits = (x, d) => d == null ? x : Number(x.toFixed(d));
  function drawnRing(layer) {
    const ll = layer.getLatLngs()[0], d = digitsOf("area.polygon");
    return ll.map((p) => [withDigits(p.lng, d), withDigits(p.lat, d)]);
  }
  function useDrawn(layer) {
    if (drawn && drawn !== layer) map.removeLayer(drawn);
    drawn = layer;
    state.polygon = drawnRing(layer); state.areaFile = null;
    $("block-w").value = ""; $("block-l").value = "";
    $("area-status").textContent = T.area_drawn;
    layer.on("pm:edit pm:dragend", () => { state.polygon = drawnRing(layer); schedule(); });
    schedule();
  }
  map.on("pm:create", (e) => useDrawn(e.layer));
  map.on("pm:remove", (e) => {
    if (e.layer === drawn) { drawn = null; state.polygon = null; setAreaStatus(); schedule(); }
  });
  function clearArea() {
    if (drawn) { map.removeLayer(drawn); drawn = null; }
    state.polygon = null; state.areaFile = null; state.fitted = false;
    setAreaStatus();
  }
  function setAreaStatus() {
    $("area-status").textContent = state.areaFile ? `${T.area_file}: ${state.areaFile.name}`
      : state.polygon ? T.area_drawn : T.no_area;
  }
  $("clear-area").addEventListener("click", () => {
    clearArea(); $("block-w").value = ""; $("block-l").value = ""; schedule();
  });
  ["block-w", "block-l"].forEach((id) => $(id).addEventListener("input", () => {
    if ($("block-w").value || $("block-l").value) {
      if (drawn) { map.removeLayer(drawn); drawn = null; }
      state.polygon = null; state.areaFile = null; setAreaStatus();
    }
    schedule();
  }));

  const legend = L.control({position: "bottomright"});
  legend.onAdd = () => {
    const d = L.DomUtil.create("div", "legend");
    d.innerHTML = `<div><i style="background:#1f3b57"></i>${esc(T.legend_area)}</div>` +
      `<div><i style="background:${palette[0]}"></i>${esc(T.legend_strip)}</div>` +
      `<div><i class="dot" style="background:#333"></i>${esc(T.legend_photo)}` +
      `<span id="every"></span></div>` +
      `<div><i class="dot" style="background:#1f3b57;border:1px solid #fff"></i>` +
      `${esc(T.legend_takeoff)}</div>`;
    return d;
  };
  legend.addTo(map);

  function showMap(fc) {
    planLayer.clearLayers();
    let every = "";
    const renderer = L.canvas({padding: 0.2});  // thousands of photo centres
    const lines = L.svg();  // a few hundred strips, each an element (class "strip")
    for (const f of fc.features) {
      const p = f.properties, g = f.geometry;
      if (p.kind === "area" && !drawn) {
        L.geoJSON(f, {pmIgnore: true, style: {color: "#1f3b57", weight: 2, fill: true,
          fillOpacity: 0.06}}).addTo(planLayer);
      } else if (p.kind === "strip") {
        const color = palette[(p.sortie - 1) % palette.length];
        g.coordinates.forEach((line) => L.polyline(line.map((c) => [c[1], c[0]]),
          {color, weight: 2.5, opacity: 0.9, pmIgnore: true, className: `strip strip-${p.number}`,
           renderer: lines}).bindTooltip(`${T.strips} ${p.number} · ${T.sorties} ${p.sorties}`)
          .addTo(planLayer));
      } else if (p.kind === "photos") {
        for (const c of g.coordinates) {
          L.circleMarker([c[1], c[0]], {radius: 1.6, color: "#333", weight: 0,
            fillOpacity: 0.7, renderer, pmIgnore: true, interactive: false}).addTo(planLayer);
        }
        if (p.every > 1) every = " (" + T.every.replace("{k}", p.every) + ")";
      } else if (p.kind === "takeoff") {
        L.marker([g.coordinates[1], g.coordinates[0]], {pmIgnore: true,
          icon: L.divIcon({className: "takeoff-icon", html: String(p.sortie),
            iconSize: [18, 18]})}).bindTooltip(`${T.legend_takeoff} ${p.sortie}`)
          .addTo(planLayer);
      }
    }
    const e = document.getElementById("every"); if (e) e.textContent = every;
    if (!state.fitted && fc.features.length && !drawn) {
      const b = L.geoJSON(fc.features[0]).getBounds();
      if (b.isValid()) { map.fitBounds(b, {padding: [20, 20]}); state.fitted = true; }
    }
  }

  /* ---------------------------------------------------------------- uploads */
  async function upload(file) {
    const r = await api("upload?name=" + encodeURIComponent(file.name),
                        {method: "POST", body: file});
    const body = await r.json();
    if (!r.ok) throw new Error(body.detail || r.statusText);
    return body;
  }
  async function takeAreaFile(file) {
    $("area-status").textContent = file.name + " …";
    try {
      const u = await upload(file);
      if (drawn) { map.removeLayer(drawn); drawn = null; }
      state.polygon = null; state.areaFile = {name: u.name, id: u.id}; state.fitted = false;
      $("block-w").value = ""; $("block-l").value = "";
      setAreaStatus(); schedule();
    } catch (err) { $("area-status").textContent = err.message; }
  }
  $("area-file").addEventListener("change", (e) => {
    if (e.target.files[0]) takeAreaFile(e.target.files[0]);
  });
  const drop = $("drop");
  ["dragenter", "dragover"].forEach((n) => drop.addEventListener(n, (e) => {
    e.preventDefault(); drop.classList.add("over"); }));
  ["dragleave", "drop"].forEach((n) => drop.addEventListener(n, (e) => {
    e.preventDefault(); drop.classList.remove("over"); }));
  drop.addEventListener("drop", (e) => {
    if (e.dataTransfer.files[0]) takeAreaFile(e.dataTransfer.files[0]);
  });
  $("dem-file").addEventListener("change", async (e) => {
    const file = e.target.files[0];
    if (!file) { state.dem = null; $("dem-status").textContent = T.dem_none; schedule(); return; }
    $("dem-status").textContent = file.name + " …";
    try {
      const u = await upload(file);
      state.dem = {name: u.name, id: u.id};
      $("dem-status").textContent = u.name; schedule();
    } catch (err) { $("dem-status").textContent = err.message; }
  });
  $("dem-status").textContent = T.dem_none;

  /* ---------------------------------------------------------------- catalogue */
  function picker(inputId, listId, items, describe, onPick) {
    const input = $(inputId), list = $(listId);
    function show() {
      const words = input.value.toLowerCase().split(/\s+/).filter(Boolean);
      const hits = items().filter((it) => {
        const text = (it.id + " " + it.name).toLowerCase();
        return words.every((w) => text.includes(w));
      }).slice(0, 40);
      list.innerHTML = hits.map((it) => `<li data-id="${esc(it.id)}">${esc(it.name)}` +
        ` <small>${esc(describe(it))}</small></li>`).join("");
    }
    input.addEventListener("input", show);
    input.addEventListener("focus", show);
    list.addEventListener("click", (e) => {
      const li = e.target.closest("li"); if (!li) return;
      const it = items().find((x) => x.id === li.dataset.id);
      list.innerHTML = ""; input.value = "";
      onPick(it);
    });
  }
  const cameraItems = () => state.catalogue.cameras.filter((c) =>
    state.platform === "film" ? c.kind === "film" : c.kind !== "film");
  picker("camera-search", "camera-list", cameraItems,
    (c) => `${c.id} · f ${fmt(c.focal_mm, 0)} mm` + (c.pixel_um ? ` · ${fmt(c.pixel_um, 2)} µm` : ""),
    (c) => { state.camera = c; $("camera-chosen").textContent = `${T.chosen}: ${c.name} (${c.id})`;
             schedule(); });
  picker("scanner-search", "scanner-list", () => state.catalogue.scanners,
    (s) => s.pixels_um.map((p) => fmt(p, 1)).join(", ") + " µm",
    (s) => { state.scanner = s; $("scanner-chosen").textContent = `${T.chosen}: ${s.name} (${s.id})`;
             schedule(); });
  document.querySelectorAll("input[name=platform]").forEach((r) => r.addEventListener("change",
    () => {
      state.platform = r.value; state.camera = null; $("camera-chosen").textContent = "";
      $("scanner-box").hidden = r.value !== "film";
      showFields(); schedule();
    }));

  /* ---------------------------------------------------------------- the form */
  const MAIN = {
    uav: ["map.scale", "map.relief_interval_m", "uav.height_m", "uav.forward_overlap_pct",
          "uav.side_overlap_pct", "uav.speed_ms", "uav.max_flight_time_min", "area.direction_deg"],
    film: ["map.scale", "map.relief_interval_m", "film.photo_scales", "film.forward_overlap_pct",
           "film.side_overlap_pct", "area.direction_deg"],
  };
  const START = {"map.scale": "2000", "map.relief_interval_m": "1"};
  const SKIP = new Set(["uav.camera", "film.camera", "film.scanner"]);

  function fieldFor(row) {
    const div = document.createElement("div");
    div.className = "field";
    const id = "f-" + row.section.replace(".", "-") + "-" + row.key;
    const label = T["lbl." + row.section + "." + row.key] || row.label ||
      row.help.split(/ [\[(:]/)[0];
    const shown = T["unit." + row.unit] || row.unit;
    const unit = row.unit && !label.endsWith(", " + row.unit) && !label.endsWith(", " + shown)
      ? ` [${shown}]` : "";
    let range = "";
    if (row.min != null) range = ` ${row.min_open ? "(" : "["}${row.min} … ${row.max}${row.max_open ? ")" : "]"}`;
    div.innerHTML = `<label for="${id}">${esc(label)}${esc(unit)} <code>${esc(row.section)}.` +
      `${esc(row.key)}</code></label>`;
    let el;
    if (row.choices.length) {
      el = document.createElement("select");
      el.innerHTML = `<option value=""></option>` + row.choices.map((c) =>
        `<option value="${esc(c)}">${esc(c)}</option>`).join("");
    } else {
      el = document.createElement("input");
      el.type = "text";
      el.placeholder = row.default == null ? "" : typeof row.default === "number"
        ? String(withDigits(row.default, row.digits)) : String(row.default);
    }
    el.id = id; el.title = row.help + range; el.dataset.kind = row.kind;
    el.dataset.key = row.section + "." + row.key;
    if (START[el.dataset.key]) el.value = START[el.dataset.key];
    el.addEventListener("input", schedule);
    el.addEventListener("change", schedule);
    div.appendChild(el);
    state.fields[el.dataset.key] = el;
    return div;
  }
  function buildForm(rows) {
    state.inputs = rows;
    const main = $("main-fields"), more = $("more-fields");
    const byKey = Object.fromEntries(rows.map((r) => [r.section + "." + r.key, r]));
    const mainKeys = new Set([...MAIN.uav, ...MAIN.film]);
    for (const k of mainKeys) if (byKey[k]) main.appendChild(fieldFor(byKey[k]));
    const sections = {};
    for (const r of rows) {
      const k = r.section + "." + r.key;
      if (r.managed || mainKeys.has(k) || SKIP.has(k)) continue;
      (sections[r.section] = sections[r.section] || []).push(r);
    }
    for (const [sec, list] of Object.entries(sections)) {
      const fs = document.createElement("fieldset");
      fs.dataset.section = sec;
      fs.innerHTML = `<legend>[${esc(sec)}]</legend>`;
      list.forEach((r) => fs.appendChild(fieldFor(r)));
      more.appendChild(fs);
    }
    showFields();
  }
  const platformOf = (key) => key.startsWith("uav") ? "uav" : key.startsWith("film") ? "film" : "";
  function showFields() {
    for (const [key, el] of Object.entries(state.fields)) {
      const p = platformOf(key);
      const mainOther = MAIN[state.platform === "uav" ? "film" : "uav"].includes(key) &&
        !MAIN[state.platform].includes(key);
      el.parentElement.hidden = (p && p !== state.platform) || mainOther;
    }
    document.querySelectorAll("#more-fields fieldset").forEach((fs) => {
      const p = platformOf(fs.dataset.section);
      fs.hidden = p && p !== state.platform;
    });
  }
  function value(el) {
    const text = el.value.trim();
    if (text === "") return undefined;
    const num = (s) => { const x = Number(s.replace(",", ".")); return isNaN(x) ? s : x; };
    switch (el.dataset.kind) {
      case "number": case "int": return num(text);
      case "scale": case "feature": case "crs": case "direction": return num(text);
      case "scales": return text.split(/[;\s]+|,\s+/).filter(Boolean).map(num);
      case "range": return text.split(/[;\s]+|,\s+/).filter(Boolean).map(num);
      default: return text;
    }
  }

  /* ---------------------------------------------------------------- the request */
  function request() {
    const project = {project: {locale: LANG}};
    const files = {};
    for (const [key, el] of Object.entries(state.fields)) {
      if (el.parentElement.hidden) continue;
      const v = value(el);
      if (v === undefined) continue;
      const dot = key.lastIndexOf(".");
      const sec = key.slice(0, dot), k = key.slice(dot + 1);
      (project[sec] = project[sec] || {})[k] = v;
    }
    const plat = state.platform;
    project[plat] = project[plat] || {};
    if (state.camera) project[plat].camera = state.camera.id;
    if (plat === "film" && state.scanner) project.film.scanner = state.scanner.id;
    const area = project.area = project.area || {};
    if (state.areaFile) { area.file = state.areaFile.name; files[state.areaFile.name] = state.areaFile.id; }
    else if (state.polygon) area.polygon = state.polygon;
    else if ($("block-w").value || $("block-l").value) {
      area.width_m = value({value: $("block-w").value, dataset: {kind: "number"}});
      area.length_m = value({value: $("block-l").value, dataset: {kind: "number"}});
    }
    if (!area.file && !area.polygon && area.width_m == null && area.length_m == null) {
      delete area.direction_deg;
    }
    if (!Object.keys(area).length) delete project.area;
    if (state.dem) {
      (project.terrain = project.terrain || {}).dem = state.dem.name;
      files[state.dem.name] = state.dem.id;
    }
    return {project, files};
  }

  let timer = null;
  function schedule() { clearTimeout(timer); timer = setTimeout(plan, 250); }

  async function plan() {
    const seq = ++state.seq;
    if (state.controller) state.controller.abort();
    const controller = state.controller = new AbortController();
    $("state").textContent = T.planning;
    document.body.dataset.planning = "1";
    const t0 = performance.now();
    let r, body;
    try {
      r = await api("view", {method: "POST", signal: controller.signal,
        headers: {"Content-Type": "application/json"}, body: JSON.stringify(request())});
      body = await r.json();
    } catch (err) {
      if (err.name === "AbortError") return;
      body = {detail: String(err)}; r = {ok: false};
    }
    if (seq !== state.seq) return;
    delete document.body.dataset.planning;
    const ms = Math.round(performance.now() - t0);
    markFields(r.ok ? null : body);
    if (!r.ok) {
      $("state").textContent = T.error;
      $("error").hidden = false; $("error").textContent = body.detail;
      document.body.dataset.result = "error";
      return;
    }
    $("error").hidden = true;
    $("state").textContent = T.planned_in.replace("{ms}", fmt(ms, 0));
    showResult(body);
    document.body.dataset.result = "ok";
    document.body.dataset.seq = String(seq);
  }
  function markFields(err) {
    Object.values(state.fields).forEach((el) => el.parentElement.classList.remove("bad"));
    if (!err || !err.field) return;
    const m = /([a-z_.]+)\.([a-z_0-9]+)(?: \(line \d+\))?$/.exec(err.field);
    if (m && state.fields[m[1] + "." + m[2]]) state.fields[m[1] + "." + m[2]].parentElement.classList.add("bad");
  }

  /* ---------------------------------------------------------------- results */
  function showResult(v) {
    const doc = v.plan, names = v.names || {};
    const spec = doc.specification || {};
    const name = (id) => id ? `${id} — ${names[id] || id}` : "—";
    let head = "", rows = "", figs = [];
    if (spec.uav) {
      const s = spec.uav, u = doc.uav;
      head = `<div class="label">${esc(T.rec_height)}</div><div class="big" id="rec">` +
        `${fmt(s.recommended_height_m, 0)} ${esc(T.m)}</div>` +
        `<div class="label">${esc(T.max_height)}: ${fmt(s.max_planned_height_m, 0)} ${esc(T.m)}</div>` +
        `<div class="binding">${esc(T.binding)}: <b id="binding">${esc(name(s.binding))}</b></div>`;
      rows = `<tr><th>${esc(T.constraint)}</th><th>${esc(T.limit)}</th>` +
        `<th>${esc(T.max_h)}</th><th title="${esc(T.margin_help)}">${esc(T.margin)}</th></tr>`;
      const margins = v.margins_pct || {};
      for (const [id, c] of Object.entries(u.constraints || {})) {
        const m = margins[id] != null ? margins[id] : c.margin_pct;
        const lim = c.compares === "H" ? `${fmt(c.limit_m, 0)} ${T.m}` : `${fmt(c.limit_m * 100, 2)} ${T.cm}`;
        rows += `<tr class="${c.binding ? "binding" : ""}" data-id="${esc(id)}"><td><b>${esc(id)}</b> ` +
          `<small>${esc(names[id] || c.name)}</small></td><td>${lim}</td><td>${fmt(c.max_height_m, 0)}</td>` +
          `<td class="margin ${m < 0 ? "neg" : ""}">${fmt(m, 1)} %</td></tr>`;
      }
      figs = [["gsd", `${fmt(s.gsd_m * 100, 2)} ${T.cm}`],
              ["ground_res", `${fmt(s.ground_resolution_m * 100, 2)} ${T.cm}`],
              ["sigma_z", `${fmt(s.sigma_z_m, 3)} ${T.m}`],
              ["strips", fmt(s.strips, 0)], ["photos", fmt(s.photos, 0)],
              ["sorties", fmt(s.sorties, 0)],
              ["flight_time", s.flight_time_s ? `${fmt(s.flight_time_s / 60, 0)} ${T.min}` : "—"]];
    } else if (spec.film) {
      const s = spec.film;
      const sc = (doc.film.scenarios || []).find((x) => x.photo_scale === s.recommended_photo_scale);
      head = `<div class="label">${esc(T.rec_scale)}</div><div class="big" id="rec">` +
        `1:${fmt(s.recommended_photo_scale, 0)}</div>` +
        `<div class="label">${esc(T.scan_pixel)}: ${fmt(s.scan_pixel_um, 1)} ${esc(T.um)}` +
        (s.scanner_pixel_um ? ` → ${fmt(s.scanner_pixel_um, 1)} ${esc(T.um)}` : "") + `</div>` +
        `<div class="binding">${esc(T.binding)}: <b id="binding">${esc(name(s.binding))}</b></div>`;
      rows = `<tr><th>${esc(T.constraint)}</th><th>${esc(T.pixel)}</th><th></th>` +
        `<th>${esc(T.margin)}</th></tr>`;
      for (const [id, c] of Object.entries(sc ? sc.constraints : {})) {
        rows += `<tr class="${c.binding ? "binding" : ""}" data-id="${esc(id)}"><td><b>${esc(id)}</b> ` +
          `<small>${esc(names[id] || c.name)}</small></td><td>${fmt(c.pixel_um, 1)}</td><td></td>` +
          `<td class="margin ${c.margin_pct < 0 ? "neg" : ""}">${fmt(c.margin_pct, 1)} %</td></tr>`;
      }
      figs = [["frames", fmt(s.frames, 0)], ["strips", fmt(s.strips, 0)]];
    }
    if (doc.area && doc.area.georeferenced) {
      figs.unshift(["area_km2", `${fmt(doc.area.area_km2, 2)} ${T.km2}`],
                   ["plan_crs", v.crs || doc.area.crs_name || doc.area.crs]);
    }
    $("headline").innerHTML = head;
    $("constraints").innerHTML = rows;
    $("figures").innerHTML = "<dl>" + figs.map(([k, x]) =>
      `<dt>${esc(T[k])}</dt><dd data-k="${esc(k)}">${esc(x)}</dd>`)
      .join("") + "</dl>";
    const ws = v.warnings || [];
    $("warnings").innerHTML = ws.length ? `<h3>${esc(T.warnings)}</h3><ul>` + ws.map((w) =>
      `<li class="${esc(w.severity)}">${esc(w.text)}</li>`).join("") + "</ul>" : "";
    $("plans").innerHTML = plansHtml(v.plans);
    $("charts").innerHTML = Object.entries(v.charts || {}).map(([k, svg]) =>
      `<img alt="${esc(k)}" data-chart="${esc(k)}" src="data:image/svg+xml;charset=utf-8,` +
      `${encodeURIComponent(svg)}">`).join("");
    showMap(v.map);
  }

  /* the plans compared, worded by the server as the documents word them */
  function plansHtml(p) {
    if (!p || !p.rows || !p.rows.length) return "";
    const n = p.head.length - 1;
    return `<h3>${esc(p.title)}</h3>` + (p.choice ? `<p class="choice">${esc(p.choice)}</p>` : "") +
      `<table class="plans"><tr>${p.head.slice(0, n).map((h) => `<th>${esc(h)}</th>`).join("")}</tr>` +
      p.rows.map((r) => `<tr class="${esc(r.flags.join(" "))}">` +
        r.cells.slice(0, n).map((c) => `<td>${esc(c)}</td>`).join("") + `</tr>` +
        `<tr class="why ${esc(r.flags.join(" "))}"><td colspan="${n}">${esc(r.cells[n])}</td></tr>`)
        .join("") + "</table>";
  }

  /* ---------------------------------------------------------------- downloads */
  document.querySelectorAll("button.dl").forEach((b) => b.addEventListener("click", async () => {
    const what = b.dataset.what;
    $("dl-status").textContent = T.rendering;
    const path = what === "toml" ? "project.toml" : "download/" + what;
    const r = await api(path, {method: "POST", headers: {"Content-Type": "application/json"},
                              body: JSON.stringify(request())});
    if (!r.ok) { $("dl-status").textContent = (await r.json()).detail; return; }
    const blob = await r.blob();
    const cd = r.headers.get("Content-Disposition") || "";
    const m = /filename="([^"]+)"/.exec(cd);
    const a = document.createElement("a");
    a.href = URL.createObjectURL(blob); a.download = m ? m[1] : "scanplan." + what;
    document.body.appendChild(a); a.click(); a.remove();
    setTimeout(() => URL.revokeObjectURL(a.href), 10000);
    $("dl-status").textContent = a.download;
  }));

  /* ---------------------------------------------------------------- start */
  setAreaStatus();
  $("state").textContent = T.start;
  api("inputs?lang=" + LANG).then((r) => r.json()).then(buildForm);
  api("catalogue?lang=" + LANG).then((r) => r.json()).then((c) => {
    state.catalogue = c; document.body.dataset.catalogue = String(c.cameras.length);
  });
  window.scanplanMap = map;  // for the browser tests and the console
})();
