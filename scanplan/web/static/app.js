/* scanplan serve: the page. No engine here: the project is sent to the JSON API, which plans
   it as `scanplan plan` does; this script keeps the work (browser storage), draws what comes
   back (map.js) and speaks the page's language. */
"use strict";
(function (SP) {
  const CFG = JSON.parse(document.getElementById("config").textContent);
  const T = CFG.texts, LANG = CFG.lang;
  const params = new URLSearchParams(location.search);
  const TOKEN = params.get("token") || "";
  const STORE = "scanplan.page.v1";
  const $ = (id) => document.getElementById(id);
  const NF = (d) => new Intl.NumberFormat(LANG === "ru" ? "ru-RU" : "en-GB",
    {minimumFractionDigits: d, maximumFractionDigits: d});
  const fmt = (x, d) => x == null || !isFinite(x) ? "—" : NF(d).format(x);
  const esc = SP.esc = (s) => String(s).replace(/[&<>"']/g, (c) => ({"&": "&amp;", "<": "&lt;",
    ">": "&gt;", '"': "&quot;", "'": "&#39;"}[c]));

  document.querySelectorAll("[data-t]").forEach((el) => { el.textContent = T[el.dataset.t]; });
  document.querySelectorAll("[data-t-label]").forEach((el) =>
    el.setAttribute("aria-label", T[el.dataset.tLabel]));
  document.title = T.title;
  const otherParams = new URLSearchParams(location.search);
  otherParams.set("lang", LANG === "ru" ? "en" : "ru");
  $("lang-other").href = "?" + otherParams.toString();
  $("lang-other").setAttribute("lang", LANG === "ru" ? "en" : "ru");
  $("camera-search").placeholder = T.search_camera;
  $("scanner-search").placeholder = T.search_scanner;
  $("area-file").setAttribute("aria-describedby", "drop-hint");

  /* ---------------------------------------------------------------- state */
  const state = {
    platform: "uav", cameras: {uav: null, film: null}, scanner: null,
    polygon: null,            // [[lon, lat], ...] drawn on the map or opened
    areaFile: null,           // {name, id}: name as the project names it, id of the upload
    dem: null,                // {name, id}
    basemap: null, ortho: null,  // the background's id; {name, id} an orthophoto upload
    extra: {},                // keys of an opened project the form has no field for
    fields: {},               // "section.key" -> input element
    inputs: [], catalogue: {cameras: [], scanners: []},
    seq: 0, controller: null, fitted: false, restoring: true, lastOk: null,
  };
  const PAGE_ID = Array.from(crypto.getRandomValues(new Uint8Array(12)),
    (b) => "abcdefghijklmnopqrstuvwxyz0123456789"[b % 36]).join("");

  async function api(path, options) {
    const opts = Object.assign({headers: {}}, options || {});
    if (TOKEN) opts.headers["X-Scanplan-Token"] = TOKEN;
    return fetch("api/" + path, opts);
  }
  const withLang = (path) => path + (path.includes("?") ? "&" : "?") + "lang=" + LANG;

  /* ---------------------------------------------------------------- the map */
  if (TOKEN) for (const b of CFG.basemaps) if (b.url) b.url += "?token=" + encodeURIComponent(TOKEN);
  const M = SP.createMap(T, LANG, CFG);
  const map = M.map;
  let drawn = null;

  function digitsOf(key) {
    const row = state.inputs.find((r) => r.section + "." + r.key === key);
    return row && row.digits != null ? row.digits : null;
  }
  const withDigits = (x, d) => d == null ? x : Number(x.toFixed(d));
  function drawnRing(layer) {
    const ll = layer.getLatLngs()[0], d = digitsOf("area.polygon");
    return ll.map((p) => [withDigits(p.lng, d), withDigits(p.lat, d)]);
  }
  function watchDrawn(layer) {
    layer.on("pm:edit pm:dragend pm:vertexadded pm:vertexremoved", () => {
      state.polygon = drawnRing(layer); state.extra = dropKeys(state.extra, "area");
      schedule();
    });
  }
  function useDrawn(layer) {
    if (drawn && drawn !== layer) map.removeLayer(drawn);
    drawn = layer;
    state.polygon = drawnRing(layer); state.areaFile = null;
    $("block-w").value = ""; $("block-l").value = "";
    setAreaStatus();
    watchDrawn(layer);
    M.drawArea(null, true);
    schedule();
  }
  function drawPolygon(ring) {  // an opened or restored polygon, editable as a drawn one
    if (drawn) { map.removeLayer(drawn); drawn = null; }
    if (!ring || ring.length < 3) return;
    drawn = L.polygon(ring.map((c) => [c[1], c[0]]), {color: "#1f3b57", weight: 2}).addTo(map);
    watchDrawn(drawn);
    if (!state.fitted) { map.fitBounds(drawn.getBounds(), {padding: [20, 20]}); state.fitted = true; }
  }
  map.on("pm:create", (e) => useDrawn(e.layer));
  map.on("pm:remove", (e) => {
    if (e.layer === drawn) { drawn = null; state.polygon = null; setAreaStatus(); schedule(); }
  });
  function clearArea() {
    if (drawn) { map.removeLayer(drawn); drawn = null; }
    state.polygon = null; state.areaFile = null; state.fitted = false;
    M.drawArea(null, false);
    setAreaStatus();
  }
  function defaultName() {  // a plan without a name is named after its area file
    return state.areaFile ? state.areaFile.name.split("/").pop().replace(/\.[^.]*$/, "")
      : T.default_name;
  }
  function setAreaStatus() {
    if (state.fields["project.name"]) state.fields["project.name"].placeholder = defaultName();
    $("area-status").textContent = state.areaFile ? `${T.area_file}: ${state.areaFile.name}`
      : state.polygon ? T.area_drawn : T.no_area;
  }
  $("clear-area").addEventListener("click", () => {
    clearArea(); $("block-w").value = ""; $("block-l").value = ""; schedule();
  });
  ["block-w", "block-l"].forEach((id) => $(id).addEventListener("input", () => {
    if ($("block-w").value || $("block-l").value) {
      if (drawn) { map.removeLayer(drawn); drawn = null; }
      state.polygon = null; state.areaFile = null; setAreaStatus(); M.drawArea(null, false);
    }
    schedule();
  }));
  const dropKeys = (extra, section) => Object.fromEntries(Object.entries(extra).filter(
    ([s]) => s !== section));

  /* the outline of an uploaded area before it can be planned (no camera chosen yet) */
  async function previewArea() {
    if (!state.areaFile) return;
    const {project, files} = request();
    const r = await api(withLang("area"), {method: "POST", body: JSON.stringify(
      {project: {area: project.area}, files}), headers: {"Content-Type": "application/json"}});
    if (!r.ok) return;
    const fc = await r.json();
    if (!state.lastOk) M.drawArea(fc.features[0], false);
    fitTo(fc);
  }
  /* the direction handle sets the direction field (as typed: the plan follows) */
  M.onDirection = (deg) => {
    const el = state.fields["area.direction_deg"]; if (!el) return;
    el.value = NF(1).format(deg).replace(/\s/g, ""); delete el.dataset.orig;
    schedule();
  };
  function fitTo(fc) {
    if (state.fitted || !fc.features.length) return;
    const b = L.geoJSON(fc.features[0]).getBounds();
    if (b.isValid()) { map.fitBounds(b, {padding: [20, 20]}); state.fitted = true; }
  }

  /* ---------------------------------------------------------------- the background */
  const basemapSelect = $("basemap");
  basemapSelect.innerHTML = (CFG.basemaps || []).map((s) =>
    `<option value="${esc(s.id)}">${esc(s.name)}</option>`).join("") +
    `<option value="ortho">${esc(T.basemap_ortho)}</option>`;
  function setBasemap(id, quiet) {
    state.basemap = id; basemapSelect.value = id;
    $("ortho-row").hidden = id !== "ortho";
    M.setBasemap(id === "ortho" ? "none" : id);
    if (id === "ortho" && state.ortho) showOrtho();
    else M.setOrtho(null);
    $("basemap-status").textContent = id === "ortho" && state.ortho ? state.ortho.name : "";
    if (!quiet) { save(); schedule(); }
  }
  basemapSelect.addEventListener("change", () => setBasemap(basemapSelect.value));
  M.onBasemapChoice = (id) => {
    setBasemap(id);
    if (id === "ortho") { $("ortho-file").focus(); }
  };
  async function showOrtho() {
    const r = await api(withLang("basemap/" + state.ortho.id));
    const body = await r.json();
    if (!r.ok) { $("basemap-status").textContent = errorText(body); M.setOrtho(null); return; }
    M.setOrtho({url: "api/basemap/" + state.ortho.id + "/image.png" +
      (TOKEN ? "?token=" + encodeURIComponent(TOKEN) : ""), bounds: body.bounds,
      name: state.ortho.name, attribution: state.ortho.name});
    $("basemap-status").textContent = `${state.ortho.name} · ${body.width} × ${body.height}`;
    if (!state.fitted) { map.fitBounds(body.bounds); state.fitted = true; }
  }
  $("ortho-file").addEventListener("change", async (e) => {
    const file = e.target.files[0]; e.target.value = "";
    if (!file) return;
    $("basemap-status").textContent = file.name + " …";
    try {
      const u = await upload(file);
      state.ortho = {name: u.name, id: u.id};
      setBasemap("ortho");
    } catch (err) { $("basemap-status").textContent = err.message; }
  });

  /* ---------------------------------------------------------------- uploads */
  async function upload(file) {
    const r = await api(withLang("upload?name=" + encodeURIComponent(file.name)),
                        {method: "POST", body: file,
                         headers: {"Content-Type": "application/octet-stream"}});
    const body = await r.json();
    if (!r.ok) throw new Error(errorText(body) || r.statusText);
    return body;
  }
  async function takeAreaFile(file) {
    $("area-status").textContent = file.name + " …";
    try {
      const u = await upload(file);
      if (drawn) { map.removeLayer(drawn); drawn = null; }
      state.polygon = null; state.areaFile = {name: u.name, id: u.id}; state.fitted = false;
      state.extra = dropKeys(state.extra, "area");
      $("block-w").value = ""; $("block-l").value = "";
      setAreaStatus(); previewArea(); schedule();
    } catch (err) { $("area-status").textContent = err.message; }
  }
  $("area-file").addEventListener("change", (e) => {
    const f = e.target.files[0];
    e.target.value = "";  // the same file chosen again after Clear is taken again
    if (f) takeAreaFile(f);
  });
  const drop = $("drop");
  ["dragenter", "dragover"].forEach((n) => drop.addEventListener(n, (e) => {
    e.preventDefault(); drop.classList.add("over"); }));
  ["dragleave", "drop"].forEach((n) => drop.addEventListener(n, (e) => {
    e.preventDefault(); drop.classList.remove("over"); }));
  drop.addEventListener("drop", (e) => {
    if (e.dataTransfer.files[0]) takeAreaFile(e.dataTransfer.files[0]);
  });
  drop.addEventListener("click", () => $("area-file").click());
  drop.addEventListener("keydown", (e) => {
    if (e.key === "Enter" || e.key === " ") { e.preventDefault(); $("area-file").click(); }
  });
  function setDem(dem) {
    state.dem = dem;
    $("dem-status").textContent = dem ? dem.name : T.dem_none;
    $("dem-remove").hidden = !dem;
  }
  $("dem-file").addEventListener("change", async (e) => {
    const file = e.target.files[0]; e.target.value = "";
    if (!file) return;
    $("dem-status").textContent = file.name + " …";
    try {
      const u = await upload(file);
      setDem({name: u.name, id: u.id}); schedule();
    } catch (err) { $("dem-status").textContent = err.message; }
  });
  $("dem-remove").addEventListener("click", () => { setDem(null); schedule(); $("dem-file").focus(); });

  /* a project file (or the zip of Everything) opened again: the page takes its values */
  $("open-file").addEventListener("change", async (e) => {
    const file = e.target.files[0]; e.target.value = "";
    if (!file) return;
    $("open-status").textContent = file.name + " …";
    try {
      const u = await upload(file);
      const r = await api(withLang("open"), {method: "POST", body: JSON.stringify({id: u.id}),
        headers: {"Content-Type": "application/json"}});
      const body = await r.json();
      if (!r.ok) throw new Error(errorText(body));
      applyProject(body.project, body.files);
      $("open-status").textContent = body.missing.length ?
        T.open_missing.replace("{files}", body.missing.join(", ")) : `${T.opened}: ${file.name}`;
      schedule();
    } catch (err) { $("open-status").textContent = err.message; }
  });

  /* ---------------------------------------------------------------- catalogue: comboboxes */
  function picker(inputId, listId, items, describe, onPick) {
    const input = $(inputId), list = $(listId);
    let hits = [], active = -1;
    function close() {
      list.innerHTML = ""; hits = []; active = -1;
      input.setAttribute("aria-expanded", "false"); input.removeAttribute("aria-activedescendant");
    }
    function mark() {
      [...list.children].forEach((li, i) => {
        li.classList.toggle("active", i === active);
        li.setAttribute("aria-selected", i === active ? "true" : "false");
      });
      if (active >= 0) {
        input.setAttribute("aria-activedescendant", list.children[active].id);
        list.children[active].scrollIntoView({block: "nearest"});
      } else input.removeAttribute("aria-activedescendant");
    }
    function show() {
      const words = input.value.toLowerCase().split(/\s+/).filter(Boolean);
      hits = items().filter((it) => {
        const text = (it.id + " " + it.name).toLowerCase();
        return words.every((w) => text.includes(w));
      }).slice(0, 40);
      list.innerHTML = hits.map((it, i) => `<li role="option" id="${listId}-${i}" ` +
        `aria-selected="false" data-id="${esc(it.id)}">${esc(it.name)}` +
        ` <small>${esc(describe(it))}</small></li>`).join("");
      active = hits.length ? 0 : -1;
      input.setAttribute("aria-expanded", hits.length ? "true" : "false");
      mark();
    }
    function pick(it) { close(); input.value = ""; onPick(it); }
    input.addEventListener("input", show);
    input.addEventListener("focus", show);
    input.addEventListener("blur", () => setTimeout(close, 150));
    input.addEventListener("keydown", (e) => {
      if (e.key === "ArrowDown" || e.key === "ArrowUp") {
        e.preventDefault();
        if (!hits.length) { show(); return; }
        active = (active + (e.key === "ArrowDown" ? 1 : hits.length - 1)) % hits.length;
        mark();
      } else if (e.key === "Enter" && active >= 0 && hits[active]) {
        e.preventDefault(); pick(hits[active]);
      } else if (e.key === "Escape") close();
    });
    list.addEventListener("mousedown", (e) => e.preventDefault());  // keep the focus
    list.addEventListener("click", (e) => {
      const li = e.target.closest("li"); if (!li) return;
      pick(items().find((x) => x.id === li.dataset.id));
    });
  }
  const cameraItems = () => state.catalogue.cameras.filter((c) =>
    state.platform === "film" ? c.kind === "film" : c.kind !== "film");
  function setCamera(c) {
    state.cameras[state.platform] = c;
    $("camera-chosen").textContent = c ? `${T.chosen}: ${c.name} (${c.id})` : T.no_camera;
  }
  function setScanner(s) {
    state.scanner = s;
    $("scanner-chosen").textContent = s ? `${T.chosen}: ${s.name} (${s.id})` : "";
  }
  picker("camera-search", "camera-list", cameraItems,
    (c) => `${c.id} · f ${fmt(c.focal_mm, 0)} ${T.unit_mm}` +
      (c.pixel_um ? ` · ${fmt(c.pixel_um, 2)} ${T.um}` : ""),
    (c) => { setCamera(c); schedule(); });
  picker("scanner-search", "scanner-list", () => state.catalogue.scanners,
    (s) => s.pixels_um.map((p) => fmt(p, 1)).join(", ") + " " + T.um,
    (s) => { setScanner(s); schedule(); });
  function setPlatform(p) {
    state.platform = p;
    document.querySelector(`input[name=platform][value=${p}]`).checked = true;
    setCamera(state.cameras[p]);  // each platform keeps its own camera
    $("scanner-box").hidden = p !== "film";
    showFields();
  }
  document.querySelectorAll("input[name=platform]").forEach((r) => r.addEventListener("change",
    () => { setPlatform(r.value); schedule(); }));

  /* ---------------------------------------------------------------- the form */
  const MAIN = {
    uav: ["map.scale", "map.relief_interval_m", "uav.height_m", "uav.forward_overlap_pct",
          "uav.side_overlap_pct", "uav.speed_ms", "uav.max_flight_time_min", "area.direction_deg",
          "uav.crosshatch"],
    film: ["map.scale", "map.relief_interval_m", "film.photo_scales", "film.forward_overlap_pct",
           "film.side_overlap_pct", "area.direction_deg"],
  };
  const START = {"map.scale": "2000", "map.relief_interval_m": "1"};
  const SKIP = new Set(["uav.camera", "film.camera", "film.scanner"]);

  function labelOf(row) {
    if (T["lbl." + row.section + "." + row.key]) return T["lbl." + row.section + "." + row.key];
    if (row.label) return row.label;
    const head = row.help.split(/ \[| \(default|, e\.g\.|; | \(GOST/)[0].trim();
    return head.charAt(0).toUpperCase() + head.slice(1);
  }
  function fieldFor(row) {
    const div = document.createElement("div");
    div.className = "field";
    const id = "f-" + row.section.replace(/\./g, "-") + "-" + row.key;
    const label = labelOf(row);
    const shown = T["unit." + row.unit] || row.unit;
    const unit = row.unit && !label.endsWith(", " + row.unit) && !label.endsWith(", " + shown)
      ? `, ${shown}` : "";
    let range = "";
    if (row.min != null) range = ` ${row.min_open ? "(" : "["}${row.min} … ${row.max}${row.max_open ? ")" : "]"}`;
    div.innerHTML = `<label for="${id}">${esc(label)}${esc(unit)}</label>`;
    let el;
    if (row.kind === "bool") {  // a checkbox whose value reads "true" or "" like a text's
      el = document.createElement("input");
      el.type = "checkbox";
      div.classList.add("check");
      Object.defineProperty(el, "value", {
        get() { return this.checked ? "true" : ""; },
        set(v) { this.checked = v === true || v === "true"; }});
    } else if (row.choices.length) {
      el = document.createElement("select");
      el.innerHTML = `<option value=""></option>` + row.choices.map((c) =>
        `<option value="${esc(c)}">${esc(c)}</option>`).join("");
    } else {
      el = document.createElement("input");
      el.type = "text";
      el.placeholder = row.default == null ? "" : typeof row.default === "number"
        ? NF(row.digits == null ? 0 : row.digits).format(row.default) : String(row.default);
      if (row.kind === "number" || row.kind === "int") el.inputMode = "decimal";
    }
    el.id = id; el.title = row.help + range; el.dataset.kind = row.kind;
    el.dataset.key = row.section + "." + row.key;
    el.setAttribute("aria-describedby", id + "-err");
    if (START[el.dataset.key]) el.value = START[el.dataset.key];
    const onEdit = () => { delete el.dataset.orig; schedule(); };
    // a text field plans on every keystroke; its "change" on leaving it is no new edit
    el.addEventListener(el.tagName === "SELECT" || el.type === "checkbox" ? "change" : "input",
                        onEdit);
    if (el.type === "checkbox") div.insertBefore(el, div.firstChild); else div.appendChild(el);
    const err = document.createElement("p");
    err.className = "field-error"; err.id = id + "-err";
    div.appendChild(err);
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
      fs.innerHTML = `<legend>${esc(T["sec." + sec] || sec)}</legend>`;
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
    if (el.dataset.orig !== undefined) return JSON.parse(el.dataset.orig);  // as opened
    const text = el.value.trim();
    if (text === "") return undefined;
    const num = (s) => { const x = Number(s.replace(",", ".")); return isNaN(x) ? s : x; };
    switch (el.dataset.kind) {
      case "bool": return text === "true" ? true : undefined;
      case "number": case "int": return num(text);
      case "scale": case "feature": case "crs": case "direction": case "checkpoints":
        return num(text);
      case "scales": case "range": case "point":
        return text.split(/[;\s]+|,\s+/).filter(Boolean).map(num);
      default: return text;
    }
  }
  function shownValue(v) {
    if (Array.isArray(v)) return v.map((x) => String(x)).join(", ");
    return String(v);
  }

  /* an opened project's tables into the page: fields, camera, area, files */
  function applyProject(tables, files) {
    state.extra = {};
    for (const el of Object.values(state.fields)) { el.value = ""; delete el.dataset.orig; }
    const film = tables.film || {}, uav = tables.uav || {};
    const platform = film.camera || (tables.film && !tables.uav) ? "film" : "uav";
    const find = (id) => state.catalogue.cameras.find((c) => c.id === id) || null;
    state.cameras = {uav: uav.camera ? find(uav.camera) : null,
                     film: film.camera ? find(film.camera) : null};
    setScanner(film.scanner ? state.catalogue.scanners.find((s) => s.id === film.scanner) || null
                            : null);
    setPlatform(platform);
    clearArea(); $("block-w").value = ""; $("block-l").value = ""; setDem(null);
    for (const [sec, table] of Object.entries(tables)) {
      for (const [k, v] of Object.entries(table)) {
        const key = sec + "." + k;
        if (key === "project.locale") continue;
        if ((sec === "uav" || sec === "film") && k === "camera" && find(v)) continue;
        if (key === "film.scanner" && state.scanner) continue;
        if (key === "area.polygon") { state.polygon = v; continue; }
        if (key === "area.file" && files[v]) { state.areaFile = {name: v, id: files[v].id}; continue; }
        if (key === "terrain.dem" && files[v]) { setDem({name: v, id: files[v].id}); continue; }
        if (key === "map.basemap" && files[v]) {
          state.ortho = {name: v, id: files[v].id}; state.basemap = "ortho"; continue;
        }
        if (key === "area.width_m") { $("block-w").value = String(v); continue; }
        if (key === "area.length_m") { $("block-l").value = String(v); continue; }
        const el = state.fields[key];
        if (el && !(el.parentElement.hidden && platformOf(key) && platformOf(key) !== platform)) {
          el.value = shownValue(v); el.dataset.orig = JSON.stringify(v);
        } else (state.extra[sec] = state.extra[sec] || {})[k] = v;
      }
    }
    state.fitted = false;
    if (state.polygon) drawPolygon(state.polygon);
    setAreaStatus();
    if (state.areaFile) previewArea();
    if (state.basemap === "ortho" && state.ortho) setBasemap("ortho", true);
  }

  /* ---------------------------------------------------------------- the request */
  function request() {
    const project = {project: {locale: LANG}};
    const files = {};
    for (const [sec, table] of Object.entries(state.extra)) {
      project[sec] = Object.assign({}, table);
    }
    for (const [key, el] of Object.entries(state.fields)) {
      if (el.parentElement.hidden) continue;
      const v = value(el);
      if (v === undefined) continue;
      const dot = key.lastIndexOf(".");
      const sec = key.slice(0, dot), k = key.slice(dot + 1);
      (project[sec] = project[sec] || {})[k] = v;
    }
    const plat = state.platform, cam = state.cameras[plat];
    if (cam) (project[plat] = project[plat] || {}).camera = cam.id;
    if (plat === "film" && state.scanner) (project.film = project.film || {}).scanner = state.scanner.id;
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
    // the documents' title: never the server's "project" (its project file's name)
    if (!project.project.name) project.project.name = defaultName();
    if (state.basemap === "ortho" && state.ortho) {  // printed on the PDF's map page too
      (project.map = project.map || {}).basemap = state.ortho.name;
      files[state.ortho.name] = state.ortho.id;
    } else if (project.map) delete project.map.basemap;
    return {project, files};
  }

  /* ---------------------------------------------------------------- kept in the browser */
  function save() {
    if (state.restoring) return;
    const fields = {};
    for (const [key, el] of Object.entries(state.fields)) {
      if (el.value !== "" || el.dataset.orig !== undefined) {
        fields[key] = el.dataset.orig !== undefined ? {text: el.value, orig: el.dataset.orig}
          : {text: el.value};
      }
    }
    const kept = {platform: state.platform, polygon: state.polygon, areaFile: state.areaFile,
      dem: state.dem, basemap: state.basemap, ortho: state.ortho, extra: state.extra,
      cameras: {uav: state.cameras.uav && state.cameras.uav.id,
                film: state.cameras.film && state.cameras.film.id},
      scanner: state.scanner && state.scanner.id, fields,
      block: [$("block-w").value, $("block-l").value], more: $("more").open,
      view: {center: map.getCenter(), zoom: map.getZoom()}};
    try { localStorage.setItem(STORE, JSON.stringify(kept)); } catch (e) { /* full or denied */ }
  }
  map.on("moveend", save);
  async function stillKept(file) {  // an upload the server still keeps, else null
    if (!file) return null;
    const r = await api("upload/" + encodeURIComponent(file.id));
    return r.ok ? file : null;
  }
  async function restore() {
    let kept = null;
    try { kept = JSON.parse(localStorage.getItem(STORE) || "null"); } catch (e) { kept = null; }
    if (!kept) { state.restoring = false; setBasemap(CFG.basemap_default, true); return false; }
    const find = (id) => state.catalogue.cameras.find((c) => c.id === id) || null;
    state.cameras = {uav: kept.cameras && kept.cameras.uav ? find(kept.cameras.uav) : null,
                     film: kept.cameras && kept.cameras.film ? find(kept.cameras.film) : null};
    setScanner(kept.scanner ? state.catalogue.scanners.find((s) => s.id === kept.scanner) || null
                            : null);
    setPlatform(kept.platform === "film" ? "film" : "uav");
    for (const el of Object.values(state.fields)) el.value = "";
    for (const [key, f] of Object.entries(kept.fields || {})) {
      const el = state.fields[key]; if (!el) continue;
      el.value = f.text; if (f.orig !== undefined) el.dataset.orig = f.orig;
    }
    state.extra = kept.extra || {};
    $("block-w").value = (kept.block || [])[0] || ""; $("block-l").value = (kept.block || [])[1] || "";
    $("more").open = !!kept.more;
    if (kept.view) { map.setView(kept.view.center, kept.view.zoom); state.fitted = true; }
    const [areaFile, dem, ortho] = await Promise.all(
      [stillKept(kept.areaFile), stillKept(kept.dem), stillKept(kept.ortho)]);
    const lost = [[kept.areaFile, areaFile], [kept.dem, dem], [kept.ortho, ortho]]
      .filter(([a, b]) => a && !b).map(([a]) => a.name);
    state.areaFile = areaFile; setDem(dem); state.ortho = ortho;
    state.polygon = kept.polygon || null;
    if (state.polygon && !state.areaFile) drawPolygon(state.polygon);
    setAreaStatus();
    if (lost.length) $("area-status").textContent = T.upload_lost.replace("{files}", lost.join(", "));
    state.restoring = false;
    setBasemap(kept.basemap || CFG.basemap_default, true);
    if (state.areaFile) previewArea();
    return true;
  }
  $("new-plan").addEventListener("click", () => {
    try { localStorage.removeItem(STORE); } catch (e) { /* denied */ }
    location.reload();
  });

  /* ---------------------------------------------------------------- planning */
  const GATHER_MS = 40;  // edits closer together than this are planned as one
  let timer = null, lastEdit = -Infinity;
  function schedule() {
    save();
    clearTimeout(timer);
    const now = performance.now(), alone = now - lastEdit > GATHER_MS;
    lastEdit = now;
    // the first edit after a pause is planned at once; a burst's later ones once it stops
    // (stale edits are dropped, here and on the server)
    if (alone) { timer = null; plan(); } else timer = setTimeout(plan, GATHER_MS);
  }
  function ready() {  // what a plan needs before it is asked for
    return !!state.cameras[state.platform] || !!(state.extra[state.platform] || {}).camera;
  }

  async function plan() {
    if (state.restoring) return;
    if (!ready()) {
      $("state").textContent = T.need_camera;
      markStale(!!state.lastOk);
      return;
    }
    const body0 = JSON.stringify(request());
    if (body0 === state.sent) return;  // nothing changed since (shown, or on its way)
    state.sent = body0;
    const seq = ++state.seq;
    if (state.controller) state.controller.abort();
    const controller = state.controller = new AbortController();
    $("state").textContent = T.planning;
    document.body.dataset.planning = "1";
    const t0 = performance.now();
    let r, body;
    try {
      r = await api(withLang("view"), {method: "POST", signal: controller.signal,
        headers: {"Content-Type": "application/json", "X-Scanplan-Edit": `${PAGE_ID}/${seq}`},
        body: body0});
      body = await r.json();
    } catch (err) {
      if (err.name === "AbortError") return;
      body = {detail: String(err)}; r = {ok: false, status: 0};
    }
    if (seq !== state.seq || r.status === 409) return;  // a newer edit is on its way
    state.controller = null;
    delete document.body.dataset.planning;
    const ms = Math.round(performance.now() - t0);
    markFields(r.ok ? null : body);
    if (!r.ok) {
      $("state").textContent = T.error;
      const e = body.page;
      $("error").hidden = false;
      $("error").textContent = e && e.label ? `${e.label}: ${e.text}` : errorText(body);
      markStale(!!state.lastOk);
      document.body.dataset.result = "error";
      document.body.dataset.seq = String(seq);
      return;
    }
    $("error").hidden = true;
    markStale(false);
    if ($("dl-status").dataset.error) { $("dl-status").textContent = ""; delete $("dl-status").dataset.error; }
    $("state").textContent = T.planned_in.replace("{ms}", fmt(ms, 0));
    const t1 = performance.now();
    showResult(body);
    state.lastOk = body;
    document.body.dataset.result = "ok";
    document.body.dataset.drawMs = String(Math.round(performance.now() - t1));
    document.body.dataset.requestMs = String(ms);  // sent → answer read (for the benchmark)
    document.body.dataset.seq = String(seq);
  }
  function errorText(body) {
    if (!body) return "";
    if (body.page && body.page.text) return (body.page.label ? body.page.label + ": " : "") + body.page.text;
    return typeof body.detail === "string" ? body.detail : JSON.stringify(body.detail);
  }
  function markStale(on) {
    $("result-body").classList.toggle("stale", on);
    $("stale-note").hidden = !on;
    document.getElementById("map-wrap").classList.toggle("stale", on);
  }
  function markFields(err) {
    for (const el of Object.values(state.fields)) {
      el.parentElement.classList.remove("bad"); el.removeAttribute("aria-invalid");
      el.parentElement.querySelector(".field-error").textContent = "";
    }
    if (!err || !err.page || !err.page.key) return;
    const el = state.fields[err.page.key];
    if (!el) return;
    el.parentElement.classList.add("bad"); el.setAttribute("aria-invalid", "true");
    el.parentElement.querySelector(".field-error").textContent = err.page.text;
    if (el.closest("details")) el.closest("details").open = true;
  }

  /* ---------------------------------------------------------------- results (results.js) */
  const R = SP.createResults({T, LANG, fmt, esc, $, M});
  const showResult = (v) => {
    R.showResult(v, !!drawn);
    fitTo(v.map);
  };

  /* ---------------------------------------------------------------- downloads */
  document.querySelectorAll("button.dl").forEach((b) => b.addEventListener("click", async () => {
    const what = b.dataset.what;
    $("dl-status").textContent = T.rendering;
    const path = what === "toml" ? "project.toml" : "download/" + what;
    let r;
    try {
      r = await api(withLang(path), {method: "POST", headers: {"Content-Type": "application/json"},
                                     body: JSON.stringify(request())});
    } catch (err) { $("dl-status").textContent = String(err); return; }
    if (!r.ok) {
      $("dl-status").textContent = errorText(await r.json()); $("dl-status").dataset.error = "1";
      return;
    }
    delete $("dl-status").dataset.error;
    const blob = await r.blob();
    const cd = r.headers.get("Content-Disposition") || "";
    const m = /filename="([^"]+)"/.exec(cd);
    const a = document.createElement("a");
    a.href = URL.createObjectURL(blob); a.download = m ? m[1] : "scanplan." + what;
    document.body.appendChild(a); a.click(); a.remove();
    setTimeout(() => URL.revokeObjectURL(a.href), 10000);
    $("dl-status").textContent = `${T.downloaded}: ${a.download}`;
  }));

  /* ---------------------------------------------------------------- start */
  setAreaStatus(); setDem(null); setCamera(null);
  $("state").textContent = T.start;
  Promise.all([
    api("inputs?lang=" + LANG).then((r) => r.json()).then(buildForm),
    api("catalogue?lang=" + LANG).then((r) => r.json()).then((c) => {
      state.catalogue = c; document.body.dataset.catalogue = String(c.cameras.length);
    }),
  ]).then(restore).then((had) => {
    document.body.dataset.ready = "1";
    if (had) plan(); else $("state").textContent = T.start;
  });
  window.scanplanMap = map;  // for the browser tests and the console
  window.scanplanMapLayers = M;
  window.scanplanPage = {state, request, plan, lastDirection: () => {
    const sp = state.lastOk && state.lastOk.plan.specification;
    const lay = sp && (sp.uav || sp.film || {}).layout;
    return lay ? lay.direction_deg : null;
  }};
})(window.SP);
