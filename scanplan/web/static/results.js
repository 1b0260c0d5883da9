/* scanplan serve: the page's results — the headline, the constraints with the documents'
   margins, the figures with the documents' units and decimals, the alternatives, the
   warnings, the charts (opened at their drawn size) and a strip's height profile over the
   DEM; the map's layers are map.js's. */
"use strict";
window.SP = window.SP || {};
(function (SP) {
  SP.createResults = function ({T, LANG, fmt, esc, $, M}) {
    const signed = (x) => x == null || !isFinite(x) ? "" : `${x >= 0 ? "+" : "−"}${fmt(Math.abs(x), 0)} %`;
    function areaText(km2) {  // the documents' km² with 3 decimals; a tiny area in m²
      if (km2 == null) return "—";
      return km2 >= 0.001 ? `${fmt(km2, 3)} ${T.km2}` : `${fmt(km2 * 1e6, 0)} ${T.m2}`;
    }
    function minutesText(s) {  // the documents' minutes with 1 decimal; under a minute in s
      if (!s) return "—";
      return s >= 60 ? `${fmt(s / 60, 1)} ${T.min}` : `${fmt(s, 0)} ${T.s}`;
    }
    function showResult(v, drawnNow) {
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
        rows = `<caption class="sr">${esc(T.constraints_caption)}</caption><tr><th scope="col">` +
          `${esc(T.constraint)}</th><th scope="col">${esc(T.limit)}</th><th scope="col">` +
          `${esc(T.max_h)}</th><th scope="col" title="${esc(T.margin_help)}">${esc(T.margin)}</th></tr>`;
        for (const [id, c] of Object.entries(u.constraints || {})) {
          const m = c.binding ? null : c.margin_pct;
          const lim = c.compares === "H" ? `${fmt(c.limit_m, 0)} ${T.m}` : `${fmt(c.limit_m, 3)} ${T.m}`;
          rows += `<tr class="${c.binding ? "binding" : ""}" data-id="${esc(id)}"><td><b>${esc(id)}</b> ` +
            `<small>${esc(names[id] || c.name)}</small></td><td>${lim}</td><td>${fmt(c.max_height_m, 0)}</td>` +
            `<td class="margin ${m != null && m < 0 ? "neg" : ""}">${signed(m)}</td></tr>`;
        }
        figs = [["gsd", `${fmt(s.gsd_m, 3)} ${T.m}`],
                ["ground_res", `${fmt(s.ground_resolution_m, 3)} ${T.m}`],
                ["sigma_z", `${fmt(s.sigma_z_m, 3)} ${T.m}`],
                ["strips", fmt(s.strips, 0)], ["photos", fmt(s.photos, 0)],
                ["sorties", fmt(s.sorties, 0)],
                ["flight_time", minutesText(s.flight_time_s)]];
      } else if (spec.film) {
        const s = spec.film;
        const sc = (doc.film.scenarios || []).find((x) => x.photo_scale === s.recommended_photo_scale);
        head = `<div class="label">${esc(T.rec_scale)}</div><div class="big" id="rec">` +
          `1:${fmt(s.recommended_photo_scale, 0)}</div>` +
          `<div class="label">${esc(T.scan_pixel)}: ${fmt(s.scan_pixel_um, 1)} ${esc(T.um)}` +
          (s.scanner_pixel_um ? ` → ${fmt(s.scanner_pixel_um, 1)} ${esc(T.um)}` : "") + `</div>` +
          `<div class="binding">${esc(T.binding)}: <b id="binding">${esc(name(s.binding))}</b></div>`;
        rows = `<caption class="sr">${esc(T.constraints_caption)}</caption><tr><th scope="col">` +
          `${esc(T.constraint)}</th><th scope="col">${esc(T.pixel)}</th>` +
          `<th scope="col">${esc(T.margin)}</th></tr>`;
        for (const [id, c] of Object.entries(sc ? sc.constraints : {})) {
          const m = c.binding ? null : c.margin_pct;
          rows += `<tr class="${c.binding ? "binding" : ""}" data-id="${esc(id)}"><td><b>${esc(id)}</b> ` +
            `<small>${esc(names[id] || c.name)}</small></td><td>${fmt(c.pixel_um, 1)}</td>` +
            `<td class="margin ${m != null && m < 0 ? "neg" : ""}">${signed(m)}</td></tr>`;
        }
        figs = [["frames", fmt(s.frames, 0)], ["strips", fmt(s.strips, 0)]];
      }
      if (doc.area && doc.area.georeferenced) {
        figs.unshift(["area_km2", areaText(doc.area.area_km2)],
                     ["plan_crs", v.crs || doc.area.crs_name || doc.area.crs]);
      }
      $("headline").innerHTML = head;
      $("constraints").innerHTML = rows;
      $("figures").innerHTML = "<dl>" + figs.map(([k, x]) =>
        `<dt>${esc(T[k])}</dt><dd data-k="${esc(k)}">${esc(x)}</dd>`)
        .join("") + "</dl>";
      showAlternatives(v.plans || doc.alternatives);
      const ws = v.warnings || [];
      $("warnings").innerHTML = ws.length ? `<h3>${esc(T.warnings)}</h3><ul>` + ws.map((w) =>
        `<li class="${esc(w.severity)}">${esc(w.text)}</li>`).join("") + "</ul>" : "";
      $("charts").innerHTML = Object.entries(v.charts || {}).map(([k, svg]) =>
        `<button type="button" class="chart" aria-describedby="chart-hint">` +
        `<img alt="${esc(T["chart_" + k] || T.chart)}" data-chart="${esc(k)}" ` +
        `src="data:image/svg+xml;charset=utf-8,${encodeURIComponent(svg)}"></button>`).join("") +
        (v.charts && Object.keys(v.charts).length ?
          `<p class="chart-hint" id="chart-hint">${esc(T.chart_open)}</p>` : "");
      const lay = (spec.uav || spec.film || {}).layout || {};
      M.showPlan(v.map, drawnNow, lay.direction_deg);
      takeProfiles(v.map);
    }
    /* the height profile of a strip over the DEM (terrain following): the ground under each
       photo and the flight altitude; a strip is chosen on the map or in the list */
    let profiles = new Map(), profileStrip = null;
    function takeProfiles(fc) {
      profiles = new Map(fc.features.filter((f) => f.properties.kind === "strip" &&
        f.properties.profile).map((f) => [f.properties.number, f.properties.profile]));
      const box = $("profile");
      if (!profiles.size) { box.hidden = true; box.innerHTML = ""; profileStrip = null; return; }
      if (!profiles.has(profileStrip)) profileStrip = profiles.keys().next().value;
      box.hidden = false;
      box.innerHTML = `<h3 id="profile-title">${esc(T.profile)}</h3>` +
        `<label for="profile-strip">${esc(T.profile_strip)}</label> <select id="profile-strip">` +
        [...profiles.keys()].map((n) => `<option value="${n}">${n}</option>`).join("") +
        `</select><div id="profile-chart"></div>`;
      $("profile-strip").value = String(profileStrip);
      $("profile-strip").addEventListener("change", (e) => showProfile(Number(e.target.value)));
      showProfile(profileStrip);
    }
    function showProfile(n) {
      const pr = profiles.get(n); if (!pr) return;
      profileStrip = n;
      if ($("profile-strip")) $("profile-strip").value = String(n);
      const W = 340, H = 180, L0 = 44, R0 = 8, T0 = 22, B0 = 30;
      const d = pr.d_m, g = pr.ground_m, a = pr.altitude_m;
      const dmax = Math.max(d[d.length - 1], 1);
      let lo = Math.min(...g), hi = Math.max(...a);
      const pad = Math.max(5, (hi - lo) * 0.08); lo -= pad; hi += pad;
      const x = (v) => L0 + (W - L0 - R0) * v / dmax;
      const y = (v) => T0 + (H - T0 - B0) * (hi - v) / (hi - lo);
      const line = (vs) => vs.map((v, i) => `${x(d[i]).toFixed(1)},${y(v).toFixed(1)}`).join(" ");
      const ground = `${x(0)},${y(lo)} ${line(g)} ${x(dmax)},${y(lo)}`;
      const ticks = (a0, a1, k) => { const st = Math.pow(10, Math.floor(Math.log10((a1 - a0) / k)));
        const step = [1, 2, 5, 10].map((m) => m * st).find((s) => (a1 - a0) / s <= k) || st * 10;
        const out = []; for (let v = Math.ceil(a0 / step) * step; v <= a1; v += step) out.push(v);
        return out; };
      const yt = ticks(lo, hi, 5).map((v) => `<line x1="${L0}" x2="${W - R0}" y1="${y(v)}" ` +
        `y2="${y(v)}" stroke="#e3e7eb"/><text x="${L0 - 4}" y="${y(v) + 4}" ` +
        `text-anchor="end">${fmt(v, 0)}</text>`).join("");
      const xt = ticks(0, dmax / 1000, 5).map((v) => `<text x="${x(v * 1000)}" y="${H - B0 + 14}" ` +
        `text-anchor="middle">${fmt(v, v < 1 && v > 0 ? 1 : 0)}</text>`).join("");
      $("profile-chart").innerHTML = `<svg viewBox="0 0 ${W} ${H}" width="100%" role="img" ` +
        `aria-label="${esc(T.profile_aria.replace("{n}", n))}" font-size="11" ` +
        `font-family="DejaVu Sans, sans-serif" fill="#26323e">${yt}${xt}` +
        `<polygon points="${ground}" fill="#c9b79c" stroke="#7a5c2e" stroke-width="1"/>` +
        `<polyline points="${line(a)}" fill="none" stroke="#2171b5" stroke-width="2"/>` +
        `<text x="${L0}" y="${H - 4}">${esc(T.profile_x)}</text>` +
        `<text x="4" y="13">${esc(T.profile_y)}</text>` +
        `</svg><p class="legend-line"><i class="sw" style="background:#2171b5"></i>` +
        `${esc(T.profile_flight)} <i class="sw" style="background:#c9b79c"></i>` +
        `${esc(T.profile_ground)}</p>`;
    }
    M.onStrip = (n) => { if (profiles.has(n)) { showProfile(n); $("profile").scrollIntoView({block: "nearest"}); } };

    /* a chart at the size it was drawn (its text as large as on paper) */
    $("charts").addEventListener("click", (e) => {
      const b = e.target.closest("button.chart"); if (!b) return;
      const img = b.querySelector("img");
      $("chart-dialog-img").src = img.src; $("chart-dialog-img").alt = img.alt;
      $("chart-dialog-title").textContent = img.alt;
      $("chart-dialog").showModal();
    });
    /* a table of the plan's alternatives, when the result carries them (a list of rows) */
    /* the plans compared, worded by the server as the documents word them (v.plans) */
    function plansHtml(p) {
      const n = p.head.length - 1;
      return `<h3>${esc(p.title)}</h3>` + (p.choice ? `<p class="choice">${esc(p.choice)}</p>` : "") +
        `<table class="plans"><tr>${p.head.slice(0, n).map((h) => `<th scope="col">${esc(h)}</th>`).join("")}</tr>` +
        p.rows.map((r) => `<tr class="${esc(r.flags.join(" "))}">` +
          r.cells.slice(0, n).map((c) => `<td>${esc(c)}</td>`).join("") + "</tr>" +
          `<tr class="why ${esc(r.flags.join(" "))}"><td colspan="${n}">${esc(r.cells[n])}</td></tr>`)
          .join("") + "</table>";
    }

    function showAlternatives(list) {
      const box = $("alternatives");
      if (list && Array.isArray(list.rows)) {
        box.innerHTML = list.rows.length ? plansHtml(list) : "";
        box.hidden = !list.rows.length;
        return;
      }
      if (!Array.isArray(list) || !list.length || typeof list[0] !== "object") {
        box.hidden = true; box.innerHTML = ""; return;
      }
      const cols = Object.keys(list[0]).filter((k) => typeof list[0][k] !== "object");
      box.innerHTML = `<h3>${esc(T.alternatives)}</h3><table><tr>` + cols.map((c) =>
        `<th scope="col">${esc(T["alt." + c] || c)}</th>`).join("") + "</tr>" + list.map((r) =>
        "<tr>" + cols.map((c) => `<td>${esc(typeof r[c] === "number" ?
          fmt(r[c], Number.isInteger(r[c]) ? 0 : 2) : r[c] == null ? "—" : r[c])}</td>`).join("") +
        "</tr>").join("") + "</table>";
      box.hidden = false;
    }

    return {showResult, takeProfiles};
  };
})(window.SP);
