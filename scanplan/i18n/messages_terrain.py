"""The engine's sentences about the terrain: heights above ground from a DEM
(:mod:`scanplan.geo.terrain`), film frames over the relief (:mod:`scanplan.geo.terrain_film`),
a height lowered over it. Part of the message catalogue: :data:`scanplan.i18n.messages.MESSAGES`
merges them (same template rules, see :mod:`scanplan.i18n.messages`). Plain data; no I/O (base
module)."""

from __future__ import annotations

TERRAIN: dict[str, dict[str, str]] = {
    "terrain_resolution": {
        "en": "over low ground the photos are too high above it: at a planned height of "
              "{height:g} m photo {photo:id} (strip {strip:id}) is {agl:.0f} m above the ground "
              "({flown:.0f} m with the height tolerance), {excess:.0f} m above the maximum "
              "planned height {limit:.0f} m set by {cid}; strips that fail: {count:d} "
              "({strips}; excess in m by strip — strip: m — {by}). {remedy}",
        "ru": "Над пониженным рельефом снимки получаются слишком высоко над землёй: при "
              "плановой высоте {height:g}~м снимок {photo:id} (маршрут {strip:id}) — "
              "{agl:.0f}~м над землёй ({flown:.0f}~м с учётом допуска), выше максимальной "
              "плановой высоты {limit:.0f}~м по условию {cid} на {excess:.0f}~м; не "
              "выполняется на маршрутах: {count:d} ({strips}; превышение по маршрутам — "
              "маршрут: м — {by}). {remedy}",
    },
    "terrain_resolution_lowered": {  # the part of terrain_height_lowered that says why
        "en": ". At the planned height of {height:g} m photo {photo:id} (strip {strip:id}) would "
              "be {agl:.0f} m above the ground ({flown:.0f} m with the height tolerance), "
              "{excess:.0f} m above the maximum planned height {limit:.0f} m set by {cid}; "
              "strips that would fail: {count:d} ({strips}; excess in m by strip — strip: m — "
              "{by}). {remedy}",
        "ru": " При плановой высоте {height:g}~м снимок {photo:id} (маршрут {strip:id}) был бы "
              "на {agl:.0f}~м над землёй ({flown:.0f}~м с учётом допуска), выше максимальной "
              "плановой высоты {limit:.0f}~м по условию {cid} на {excess:.0f}~м; не "
              "выполнялось бы на маршрутах: {count:d} ({strips}; превышение по маршрутам — "
              "маршрут: м — {by}). {remedy}",
    },
    "terrain_higher.constant": {
        "en": "To fly higher: fly each strip at its own altitude (⁅[terrain] altitude_mode = "
              "\"strip\"⁆), follow the terrain (⁅\"follow\"⁆) or split the block along the relief",
        "ru": "Чтобы лететь выше: задать каждому маршруту свою высоту или следовать рельефу "
              "(⁅[terrain] altitude_mode⁆) либо разделить блок по рельефу.",
    },
    "terrain_higher.strip": {
        "en": "To fly higher: follow the terrain (⁅[terrain] altitude_mode = \"follow\"⁆) or "
              "split the failing strips",
        "ru": "Чтобы лететь выше: следовать рельефу (⁅[terrain] altitude_mode⁆) или разделить "
              "невыполняющиеся маршруты.",
    },
    "terrain_higher.follow": {
        "en": "To fly higher: a smaller tolerance (⁅[terrain] follow_tolerance_m⁆)",
        "ru": "Чтобы лететь выше: уменьшить допуск (⁅[terrain] follow_tolerance_m⁆).",
    },
    "terrain_remedy.constant": {
        "en": "Remedies: fly each strip at its own altitude (⁅[terrain] altitude_mode = "
              "\"strip\"⁆), follow the terrain (⁅\"follow\"⁆), split the block along the "
              "relief, or lower the planned height to {max:.0f} m above the highest ground",
        "ru": "Выход: задать каждому маршруту свою высоту или следовать рельефу (⁅[terrain] "
              "altitude_mode⁆), разделить блок по рельефу или снизить плановую высоту до "
              "{max:.0f}~м над наивысшей точкой.",
    },
    "terrain_remedy.strip": {
        "en": "Remedies: follow the terrain (⁅[terrain] altitude_mode = \"follow\"⁆), split the "
              "failing strips, or lower the planned height to {max:.0f} m above each strip's "
              "highest ground",
        "ru": "Выход: следовать рельефу (⁅[terrain] altitude_mode⁆), разделить "
              "невыполняющиеся маршруты или снизить плановую высоту до {max:.0f}~м над "
              "наивысшей точкой каждого маршрута.",
    },
    "terrain_height_accuracy": {
        "en": "over the relief the photo highest above its ground is flown up to {agl:.0f} m "
              "above it, where the exposures spaced for {planned:g} m give an idealised "
              "stereo precision σ_Z = {sz:.3f} m, above the required {vz:g} m: fly a forward "
              "overlap of at least the standard one (now {overlap:g} %) or a lower height",
        "ru": "Над рельефом снимок с наибольшей высотой над местностью выполняется с высоты "
              "до {agl:.0f}~м, где при шаге фотографирования, рассчитанном на {planned:g}~м, "
              "идеализированная точность стереоизмерений σ_Z = {sz:.3f}~м больше требуемой "
              "{vz:g}~м: увеличьте продольное перекрытие не менее чем до стандартного (сейчас "
              "{overlap:g}~%) или снизьте высоту.",
    },
    "terrain_remedy.follow": {
        "en": "Remedies: a smaller tolerance (⁅[terrain] follow_tolerance_m⁆) or a planned height "
              "of at most {max:.0f} m",
        "ru": "Выход: уменьшить допуск (⁅[terrain] follow_tolerance_m⁆) или снизить плановую "
              "высоту до {max:.0f}~м.",
    },
    "terrain_forward_overlap": {
        "en": "over high ground the forward overlap drops to {value:.1f} % (photos {a:id} and "
              "{b:id}), below the planned {planned:g} % at {count:d|photo|photos}: "
              "{photos}.{floor} "
              "Remedies: hold the altitude over the highest ground (⁅[terrain] altitude_mode = "
              "\"constant\" or \"strip\"⁆), or raise the forward overlap "
              "(⁅[uav] forward_overlap_pct⁆)",
        "ru": "Над повышенным рельефом продольное перекрытие уменьшается до {value:.1f}~% (снимки "
              "{a:id} и {b:id}) — меньше планового {planned:g}~% у снимков: {count:d} "
              "({photos}).{floor} Выход: отсчитывать высоту от наивысшей точки блока или маршрута "
              "(⁅[terrain] altitude_mode⁆) или увеличить продольное перекрытие "
              "(⁅[uav] forward_overlap_pct⁆).",
    },
    "terrain_side_overlap": {
        "en": "over high ground the side overlap drops to {value:.1f} % (photos {a:id} and "
              "{b:id}), below the planned {planned:g} % at {count:d|photo|photos}: "
              "{photos}.{floor} "
              "Remedies: hold the altitude over the highest ground (⁅[terrain] altitude_mode = "
              "\"constant\"⁆), or raise the side overlap (⁅[uav] side_overlap_pct⁆)",
        "ru": "Над повышенным рельефом поперечное перекрытие уменьшается до {value:.1f}~% (снимки "
              "{a:id} и {b:id}) — меньше планового {planned:g}~% у снимков: {count:d} "
              "({photos}).{floor} Выход: отсчитывать высоту от наивысшей точки блока (⁅[terrain] "
              "altitude_mode⁆) или увеличить поперечное перекрытие (⁅[uav] side_overlap_pct⁆).",
    },
    "terrain_overlap_floor.forward": {
        "en": " At 50 % or less no ground point is on three photos: the block cannot be tied",
        "ru": " При 50~% и менее ни одна точка не изображается на трёх снимках: сеть не строится.",
    },
    "terrain_overlap_floor.side": {
        "en": " At 0 % or less there are gaps between the strips",
        "ru": " При 0~% и менее между маршрутами остаются разрывы.",
    },
    "terrain_no_ground": {
        "en": "{count:d} of {total:d} photo centres have no ground under them ({outside:d} "
              "outside the DEM, {nodata:d} on nodata): photos {photos}; they are checked at the "
              "lowest ground of the DEM ({low:.1f} m) for resolution and at the highest "
              "({high:.1f} m) for overlap",
        "ru": "Под центрами {count:d} из {total:d} снимков нет высоты рельефа ({outside:d} вне "
              "ЦМР, {nodata:d} — пропуски данных): снимки {photos}; разрешение для них "
              "проверено по наинизшей отметке ЦМР ({low:.1f}~м), перекрытие — по наивысшей "
              "({high:.1f}~м).",
    },
    "terrain_units_feet": {
        "en": "the DEM {file} has its horizontal coordinates in {unit}, and nothing says its "
              "heights are in metres: if they are in feet, state it (⁅[terrain] vertical_unit = "
              "\"ft\" or \"us-ft\"⁆)",
        "ru": "Плановые координаты ЦМР {file} заданы в {unit}, а единица высот не "
              "указана: если высоты в футах, укажите это (⁅[terrain] vertical_unit = «ft» или "
              "«us-ft»⁆).",
    },
    "terrain_geographic": {
        "en": "the DEM {file} is in geographic coordinates (cells of {cell:.2f}″): the photo "
              "centres were projected into it and sampled there; the DEM was not warped",
        "ru": "ЦМР {file} задана в географических координатах (ячейка {cell:.2f}″): центры "
              "снимков пересчитаны в её систему координат; сама ЦМР не перепроецировалась.",
    },
    "terrain_film_scale": {
        "en": "the relief changes the photo scale from {lo:scale} to {hi:scale}; the frame over "
              "the lowest ground {where} binds: the scan pixel is specified for it, {pixel:.1f} "
              "µm ({cid}), instead of {planned:.1f} µm on flat ground",
        "ru": "Рельеф изменяет масштаб снимков от {lo:scale} до {hi:scale}; определяет снимок "
              "над наинизшей точкой {where}: пиксель сканирования назначен по нему, "
              "{pixel:.1f}~мкм (условие {cid}), вместо {planned:.1f}~мкм для плоской "
              "местности.",
    },
    "terrain_film_where.dem": {
        "en": "(frame {frame:id}, strip {strip:id})",
        "ru": "(снимок {frame:id}, маршрут {strip:id})",
    },
    "terrain_film_where.range": {
        "en": "(the ground is given as a range: any frame may lie over {low:g} m)",
        "ru": "(отметки заданы диапазоном: любой снимок может оказаться над {low:g}~м)",
    },
    "spec.film_terrain": {
        "en": "{scale:scale} is the smallest candidate photo scale (fewest frames) whose every "
              "frame meets every constraint over the relief: flown at {scale:scale} over the "
              "highest ground, the frame over the lowest ground {where} is at {local:scale}, "
              "and the scan pixel is specified there. {explanation}{rejected}",
        "ru": "{scale:scale} — самый мелкий из рассмотренных масштабов снимков (наименьшее "
              "число снимков), при котором все условия выполняются на каждом снимке с учётом "
              "рельефа: при масштабе {scale:scale} над наивысшей точкой снимок над наинизшей "
              "точкой {where} получается в масштабе {local:scale}, и пиксель сканирования "
              "назначен по нему. {explanation}{rejected}",
    },
    "spec.film_archive_terrain": {
        "en": "the photos exist at {scale:scale} (archive photos; the scale is given, not "
              "chosen); over the relief their frames reach {local:scale} at the frame over "
              "the lowest ground {where}: scan them at {pixel:.1f} µm, which holds there. "
              "{explanation}",
        "ru": "Снимки уже получены в масштабе {scale:scale} (архивные снимки; масштаб задан, "
              "а не выбирается); с учётом рельефа их масштаб доходит до {local:scale} у снимка "
              "над наинизшей точкой {where}: сканировать их с пикселем {pixel:.1f}~мкм, "
              "который годится и для него. {explanation}",
    },
    "spec.film_terrain.rejected": {
        "en": " {scales:scale} was not taken: over the relief its frames reach {locals:scale}, "
              "where not every constraint can be met",
        "ru": " Масштаб {scales:scale} не принят: с учётом рельефа его снимки доходят до "
              "{locals:scale}, где не все условия выполнимы.",
    },
    "terrain_film_scale_changed": {
        "en": "over the relief {flat:scale} fails: flown over the highest ground, its frame "
              "over the lowest ground {where} would be at {local:scale}, where not every "
              "constraint can be met; the plan takes {scale:scale}, whose frames span "
              "{scale:scale} … {hi:scale}",
        "ru": "С учётом рельефа масштаб {flat:scale} не подходит: при полёте над наивысшей "
              "точкой его снимок над наинизшей точкой {where} был бы в масштабе {local:scale}, "
              "где не все условия выполнимы; принят масштаб {scale:scale}, снимки которого — от "
              "{scale:scale} до {hi:scale}.",
    },
    "terrain_height_lowered": {
        "en": "over the relief the flat-ground maximum height {flat:.0f} m is too high: with "
              "the altitude mode {mode} the worst photo meets {cid} up to {max:.0f} m above "
              "the reference ground, so the plan is flown at {recommended:g} m{why}",
        "ru": "Над рельефом максимальная высота для плоской местности {flat:.0f}~м слишком "
              "велика: в режиме {mode} наихудший снимок удовлетворяет условию {cid} до "
              "{max:.0f}~м над опорной отметкой, поэтому принята высота "
              "{recommended:g}~м.{why}",
    },
    "terrain_voids_filled": {
        "en": "the DEM {file} has no-data inside the area: {pixels:d} pixels ({area_m2:.0f} m², "
              "{share:.2f} % of the area) lie within {radius:g} m of known ground and were "
              "filled conservatively, with the highest known ground within {radius:g} m plus "
              "{margin:g} m for the altitude and the lowest minus {margin:g} m for the photo "
              "scale; {photos:d} photo centres stand on them",
        "ru": "В ЦМР {file} внутри участка есть пропуски данных: {pixels:d} пикселей "
              "({area_m2:.0f}~м², {share:.2f}~% площади) не дальше {radius:g}~м от известного "
              "рельефа заполнены с запасом — для высоты полёта наивысшей известной отметкой в "
              "радиусе {radius:g}~м плюс {margin:g}~м, для масштаба снимков наинизшей минус "
              "{margin:g}~м; на них приходятся центры {photos:d} снимков.",
    },
}
