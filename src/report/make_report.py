#!/usr/bin/env python3
"""Writes STUDY/report/: index.html, figures/*.svg|png and the images it shows.

Run by `pathlab report STUDY`. The page opens from disk with no server and no
network: styles, script and data are inlined, and every image it shows is a
relative path inside report/. Exit codes: 0 done, 2 not a study, 1 failure.
"""

import argparse
import html
import json
import os
import re
import shutil
import subprocess
import sys
import time

import numpy as np

import error_spectra
import figures
import verdict
from study_data import Study, StudyError

GRID_SPPS = (1, 8)  # the presentation's two columns of the comparison grid
TABLE_SPPS = (1, 8, 64)
WOLF_CREDIT = ("Wolf model from 0 A.D. © 2010 Wildfire Games, "
               "licensed under CC-BY-SA-3.0.")


def slug(name):
    return re.sub(r"[^A-Za-z0-9._-]+", "-", name).strip("-") or "scene"


def esc(text):
    return html.escape(str(text), quote=True)


def fmt(value, digits=3):
    if value is None:
        return "—"
    if isinstance(value, (int, np.integer)):
        return str(value)
    if value == 0:
        return "0"
    if abs(value) >= 1e4 or abs(value) < 1e-3:
        return f"{value:.{digits - 1}e}"
    return f"{value:.{digits}g}"


# --- choosing the zoomed region ---------------------------------------------

def _magma_inverse():
    """Luminance → error value for the magma colour map (monotonic in luminance)."""
    lut = figures.plt.get_cmap("magma")(np.linspace(0, 1, 256))[:, :3]
    return lut @ np.array([0.2126, 0.7152, 0.0722]), np.linspace(0, 1, 256)


def _error_image(study, scene, sampler, spp):
    """Per-pixel error of seed 0: the FLIP map, else the tone-mapped difference."""
    flip_path = study.image_path(scene, sampler, spp, "flip")
    if os.path.isfile(flip_path):
        rgb = figures.mpimg.imread(flip_path)[..., :3]
        lum_lut, values = _magma_inverse()
        return np.interp(rgb @ np.array([0.2126, 0.7152, 0.0722]), lum_lut, values)
    test_path, ref_path = study.image_path(scene, sampler, spp), study.reference_png(scene)
    if os.path.isfile(test_path) and os.path.isfile(ref_path):
        diff = figures.mpimg.imread(test_path)[..., :3] - figures.mpimg.imread(ref_path)[..., :3]
        return (diff ** 2).mean(axis=2)
    return None


def choose_crop(study, scene, spps, width, height):
    """The square where the samplers' errors, summed, are largest.

    Summing over every sampler picks a region that is hard for all of them
    (edges, caustics, penumbrae), rather than one sampler's artefact.
    """
    side = max(8, min(width, height) // 5)
    total = np.zeros((height, width))
    for sampler in study.samplers(scene):
        for spp in spps:
            err = _error_image(study, scene, sampler, spp)
            if err is not None and err.shape == total.shape:
                total += err
    # Box sums of every side×side window through an integral image.
    integral = np.pad(total.cumsum(0).cumsum(1), ((1, 0), (1, 0)))
    sums = (integral[side:, side:] - integral[:-side, side:]
            - integral[side:, :-side] + integral[:-side, :-side])
    y, x = np.unravel_index(int(np.argmax(sums)), sums.shape)
    return {"x": int(x), "y": int(y), "w": side, "h": side}


# --- images ------------------------------------------------------------------

class ImageCopier:
    """Copies the PNGs the page shows into report/images/, returning relative paths."""

    def __init__(self, report_dir):
        self.report_dir = report_dir

    def copy(self, source, relative):
        if not os.path.isfile(source):
            return None
        target = os.path.join(self.report_dir, relative)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(source, target)
        return relative


def scene_images(study, scene, copier):
    """{sampler: {spp: {"image", "flip", "relse", metrics}}} for seed 0."""
    s = slug(scene)
    out = {}
    for sampler in study.samplers(scene):
        per_spp = {}
        for spp in study.spps(scene, sampler):
            entry = {}
            for kind in ("", "flip", "relse"):
                rel = f"images/{s}/{slug(sampler)}/spp{spp}{'-' + kind if kind else ''}.png"
                path = copier.copy(study.image_path(scene, sampler, spp, kind), rel)
                if path:
                    entry[kind or "image"] = path
            if "image" not in entry:
                continue
            cell = study.cell(scene, sampler, spp) or {}
            for key in ("mse", "relmse", "flip", "seconds"):
                entry[f"{key}_value"] = cell.get(key)
            per_spp[str(spp)] = entry
        if per_spp:
            out[sampler] = per_spp
    return out


def image_size(path):
    img = figures.mpimg.imread(path)
    return img.shape[1], img.shape[0]


# --- HTML pieces -------------------------------------------------------------

def figure_block(base, caption):
    return (f'<figure class="plot"><img src="figures/{esc(base)}.svg" alt="{esc(caption)}">'
            f'<figcaption>{esc(caption)} · <a href="figures/{esc(base)}.svg">SVG</a> · '
            f'<a href="figures/{esc(base)}.png">PNG</a></figcaption></figure>')


def table_columns(study, scene):
    spps = study.spps(scene)
    ratio_spps = [n for n in TABLE_SPPS if n in spps]
    # The study's largest spp too, where samplers differ the most.
    if spps[-1] not in ratio_spps:
        ratio_spps.append(spps[-1])
    has_independent = "independent" in study.samplers(scene)
    cols = [("MSE slope", lambda a: a.get("slope_mse")),
            ("relMSE slope", lambda a: a.get("slope_relmse"))]
    if has_independent:
        for n in ratio_spps:
            cols.append((f"MSE ÷ independent @{n} spp",
                         lambda a, n=n: (a.get("mse_ratio_to_independent") or {}).get(str(n))))
    cols.append(("time to target (s)", lambda a: a.get("time_to_target_seconds")))
    if study.time_budget():
        cols.append((f"MSE at {fmt(study.time_budget())} s",
                     lambda a: (a.get("error_at_time_budget") or {}).get("mse")))
    return cols + error_spectra.table_columns(study, scene)


def clear_winner(analysis, samplers, spp, best):
    """True when the best sampler's highest MSE over the seeds at `spp` is below every
    other sampler's lowest: a difference the seeds' spread cannot explain."""
    def cell(s):
        return (analysis["samplers"][s].get("by_spp") or {}).get(str(spp)) or {}
    if len(best) != 1 or cell(best[0]).get("mse_max") is None:
        return False
    top = cell(best[0])["mse_max"]
    others = [cell(s).get("mse_min") for s in samplers if s != best[0]]
    return all(low is not None and top < low for low in others)


def results_table(study, scene):
    analysis = study.analysis[scene]
    samplers = study.samplers(scene)
    cols = table_columns(study, scene)
    values = {s: [get(analysis["samplers"][s]) for _, get in cols] for s in samplers}
    # The equal-time column only when the study measured it.
    keep = [i for i, (name, _) in enumerate(cols)
            if not name.startswith("MSE at ") or any(values[s][i] is not None for s in samplers)]
    cols = [cols[i] for i in keep]
    values = {s: [v[i] for i in keep] for s, v in values.items()}
    # Lower is better in every column: steeper (more negative) slopes, smaller
    # ratios, shorter times, smaller errors.
    ratio_spp = {i: int(name.split("@")[1].split()[0]) for i, (name, _) in enumerate(cols)
                 if "@" in name}
    winners = []
    for i in range(len(cols)):
        present = [values[s][i] for s in samplers if values[s][i] is not None]
        best = min(present) if present else None
        if i in ratio_spp and best is not None and not clear_winner(
                analysis, samplers, ratio_spp[i], [s for s in samplers if values[s][i] == best]):
            best = None
        winners.append(best)
    head = "".join(f"<th>{esc(name)}</th>" for name, _ in cols) + "<th>bias</th>"
    rows = []
    for s in samplers:
        cells = []
        for i, v in enumerate(values[s]):
            win = v is not None and v == winners[i] and len(samplers) > 1
            cls = ' class="winner"' if win else ""
            by_spp = analysis["samplers"][s].get("by_spp") or {}
            floor = i in ratio_spp and (by_spp.get(str(ratio_spp[i])) or {}).get(
                "below_noise_floor")
            mark = '<sup title="within 2× the reference noise floor">*</sup>' if floor else ""
            cells.append(f"<td{cls}>{esc(fmt(v))}{mark}</td>")
        cells.append(bias_cell(study, scene, s))
        rows.append(f'<tr><th><span class="swatch" style="background:{figures.colour(s)}"></span>'
                    f'{esc(s)}</th>{"".join(cells)}</tr>')
    target = analysis["target_mse"]
    note = (f"Target error: MSE {fmt(target)}, what <b>{esc(analysis['target_sampler'])}</b> "
            f"reaches at {analysis['target_spp']} spp. " if target else "")
    note += ("Slopes are least-squares fits of log error against log spp over the mean of the "
             "seeds (−1 is plain Monte Carlo). Ratios below 1 beat independent random numbers. "
             "Best value per column highlighted; in a ratio column only when the best "
             "sampler's MSE over the seeds stays below every other sampler's (ranges apart).")
    correction = study.runner_analysis.get("mse_correction")
    if correction:
        note += f" MSE correction: {esc(correction.rstrip('.'))}."
    if "<sup" in "".join(rows):
        note += " * marks an MSE within twice the reference's noise floor: not meaningful."
    if "independent" not in samplers:
        note += " The study has no <b>independent</b> sampler, so ratios to it are omitted."
    note += bias_note(study)
    return (f'<table class="results"><thead><tr><th>sampler</th>{head}</tr></thead>'
            f'<tbody>{"".join(rows)}</tbody></table><p class="note">{note}</p>')


def bias_cell(study, scene, sampler):
    """The bias verdict in words: where the sampler is biased, and by how much."""
    rows = [b for (sc, sa, _), b in sorted(study.bias.items()) if sc == scene and sa == sampler]
    biased = [b for b in rows if b.get("biased") == "1"]
    if biased:
        worst = max(biased, key=lambda b: abs(b["bias"]))
        spps = ", ".join(str(b["spp"]) for b in biased)
        return (f'<td class="biased">biased at {esc(spps)} spp '
                f'({100 * worst["bias"]:+.2g}% at {worst["spp"]})</td>')
    if rows and all(b.get("biased") == "deterministic" for b in rows):
        return '<td title="the seed does not change its images">deterministic error</td>'
    if rows and all(b.get("biased") == "0" for b in rows):
        return "<td>none found</td>"
    return "<td>—</td>"


def bias_note(study):
    tolerance = study.bias_tolerance
    if tolerance is None:
        return ""
    return (" Bias: the mean over the seeds of (image mean − reference mean) ÷ reference mean; "
            "<b>biased</b> where its Student-t 95% interval lies wholly beyond "
            f"±{100 * tolerance:.2g}% (bias.csv). A sampler the seed does not randomise has a "
            "deterministic error instead, which no number of seeds can tell from bias.")


def region_spps(study, scene, ratios):
    """Every spp of a short list (up to four), else those of the summary table."""
    spps = study.spps(scene)
    wanted = list(spps) if len(spps) <= 4 else [n for n in TABLE_SPPS if n in spps]
    if spps and spps[-1] not in wanted:
        wanted.append(spps[-1])
    return [n for n in wanted if str(n) in ratios]


def regions_section(study, scene, edge_png):
    """Ratios to independent over the pixels a visible emitter's outline crosses and
    over the rest (analysis.json "regions"), or nothing when the study lacks them."""
    runner = study.runner_analysis.get("scenes", {}).get(scene, {})
    regions = runner.get("regions")
    samplers = study.samplers(scene)
    if not regions or not regions.get("edge_pixels") or "independent" not in samplers:
        return ""
    by_region = {s: (runner.get("samplers", {}).get(s, {}).get("mse_ratio_by_region") or {})
                 for s in samplers}
    spps = region_spps(study, scene, (by_region["independent"].get("edge") or {}))
    if not spps:
        return ""
    head = "".join(f"<th>edge @{n}</th><th>rest @{n}</th>" for n in spps)
    rows = []
    for s in samplers:
        edge, rest = by_region[s].get("edge") or {}, by_region[s].get("rest") or {}
        cells = "".join(f"<td>{esc(fmt(edge.get(str(n))))}</td><td>{esc(fmt(rest.get(str(n))))}"
                        f"</td>" for n in spps)
        rows.append(f'<tr><th><span class="swatch" style="background:{figures.colour(s)}">'
                    f'</span>{esc(s)}</th>{cells}</tr>')
    edge_px, px = regions["edge_pixels"], regions["pixels"]
    share = (regions.get("independent_edge_share") or {}).get(str(spps[-1]))
    held = (f"; they hold {100 * share:.0f}% of <b>independent</b>'s error at {spps[-1]} spp"
            if share is not None else "")
    note = (f"The outline of a directly visible emitter crosses {edge_px} of {px} pixels "
            f"({100 * edge_px / px:.2g}%){held}. In those pixels the integrand is a step "
            "between the emitter and its surroundings, and a sampler acts on it only through "
            "the pixel dimensions; everywhere else the error is that of the light transport. "
            "MSE ratios to independent over each region, each less its own noise floor.")
    table = (f'<table class="results regions"><thead><tr><th>sampler</th>{head}</tr></thead>'
             f'<tbody>{"".join(rows)}</tbody></table>')
    if edge_png:
        table = (f'<div class="regions-host">{table}<figure class="edge-map"><img src="'
                 f'{esc(edge_png)}" alt="emitter-edge pixels of {esc(scene)}"><figcaption>'
                 f'Emitter-edge pixels in cyan</figcaption></figure></div>')
    return f'<h3>Where the error is</h3>{table}<p class="note">{note}</p>'


def findings(study, scene):
    """One sentence per question a reader asks first."""
    a = study.analysis[scene]["samplers"]
    spps = study.spps(scene)
    top = spps[-1]
    at_top = {s: study.series(scene, s, "mse") for s in a}
    at_top = {s: dict(zip(v.spp, v.mean)).get(top) for s, v in at_top.items()}
    at_top = {s: v for s, v in at_top.items() if v is not None}
    items = []
    if at_top:
        best = min(at_top, key=at_top.get)
        items.append(f"Lowest MSE at {top} spp: <b>{esc(best)}</b> ({fmt(at_top[best])}).")
    slopes = {s: v["slope_mse"] for s, v in a.items() if v.get("slope_mse") is not None}
    if slopes:
        best = min(slopes, key=slopes.get)
        items.append(f"Fastest convergence: <b>{esc(best)}</b> (MSE slope {fmt(slopes[best])}).")
    times = {s: v["time_to_target_seconds"] for s, v in a.items()
             if v.get("time_to_target_seconds") is not None}
    if times:
        best = min(times, key=times.get)
        items.append(f"First to the target error: <b>{esc(best)}</b> "
                     f"({fmt(times[best])} s).")
    biased = {s: study.biased_spps(scene, s) for s in a}
    biased = {s: v for s, v in biased.items() if v}
    if biased:
        words = "; ".join(f"<b>{esc(s)}</b> at {', '.join(str(n) for n in v)} spp"
                          for s, v in biased.items())
        items.append(f'<span class="biased">Biased</span>: {words} (see the bias column).')
    regions = study.runner_analysis.get("scenes", {}).get(scene, {}).get("regions") or {}
    share = (regions.get("independent_edge_share") or {}).get(str(top))
    if regions.get("edge_pixels") and share is not None:
        items.append(f"{100 * share:.0f}% of <b>independent</b>'s error at {top} spp lies on "
                     f"the {regions['edge_pixels']} pixels of the emitters' outline "
                     f"({100 * regions['edge_pixels'] / regions['pixels']:.2g}% of the image): "
                     f"see <i>Where the error is</i>.")
    return "<ul class=\"findings\">" + "".join(f"<li>{i}</li>" for i in items) + "</ul>"


def reference_caption(study, scene, width, height):
    ref = study.references.get(scene) or {}
    parts = [f"{width}×{height}"]
    if ref.get("spp"):
        parts.append(f"{ref['spp']} spp with {ref.get('sampler') or '?'}")
    if ref.get("seconds"):
        parts.append(f"{fmt(float(ref['seconds']))} s")
    floor = study.noise_floor(scene)
    if floor:
        parts.append(f"noise floor MSE {fmt(floor)}")
    if ref.get("exposure") is not None:
        parts.append(f"exposure {float(ref['exposure']):+g} stops")
    return "Reference: " + ", ".join(parts)


def scene_section(study, scene, data, figure_names, extra=""):
    s = slug(scene)
    width, height = data["width"], data["height"]
    credit = f'<p class="credit">{esc(WOLF_CREDIT)}</p>' if "wolf" in scene.lower() else ""
    plots, combined = figure_names
    plot_html = "".join(figure_block(base, caption) for base, caption in zip(
        plots, ["MSE vs spp", "relMSE vs spp", "mean FLIP vs spp", "MSE vs render time"]))
    return f"""
<section class="scene" id="scene-{esc(s)}" data-scene="{esc(scene)}">
  <h2>{esc(scene)}</h2>{credit}
  <div class="overview">
    <figure class="reference"><img src="{esc(data['reference'])}" alt="reference of {esc(scene)}"
      width="{width}" height="{height}">
      <figcaption>{esc(reference_caption(study, scene, width, height))}</figcaption></figure>
    <div class="summary">{findings(study, scene)}
      <p class="note">Seeds: {len(study.seeds())}; bands in the plots span the lowest to the
      highest error over the seeds. Images show seed 0.</p>
      <img class="headline" src="figures/{esc(plots[0])}.svg" alt="MSE vs spp"></div>
  </div>
  <h3>Comparison grid</h3>
  <div class="grid-host"></div>
  <p class="note">The yellow square marks the region with the most error (mean HDR-FLIP against
  the reference, summed over every sampler at {esc(", ".join(str(n) for n in data['gridSpps']))}
  spp); it is shown magnified below
  each image. Paper version: <a href="figures/{esc(s)}-grid.svg">SVG</a> ·
  <a href="figures/{esc(s)}-grid.png">PNG</a>.</p>
  <h3>Image comparer</h3>
  <div class="comparer-host"></div>
  <h3>Convergence</h3>
  <div class="plots">{plot_html}</div>
  <p class="note">All four in one figure: <a href="figures/{esc(combined)}.svg">SVG</a> ·
  <a href="figures/{esc(combined)}.png">PNG</a>.</p>
  <h3>Summary</h3>
  {results_table(study, scene)}
  {regions_section(study, scene, data.get("edge"))}
  {extra}
</section>"""


# --- sampler gallery ---------------------------------------------------------

def gallery(samplers, pathlab, figures_dir):
    """Each sampler's first two dimensions in one pixel, with their spectrum."""
    if not pathlab:
        return ('<p class="note">The sampler gallery needs the pathlab binary '
                '(<code>pathlab points</code>); it was not given.</p>')
    cards = []
    for name in samplers:
        base = f"points-{slug(name)}"
        try:
            for ext in ("svg", "png"):
                subprocess.run([pathlab, "points", "--sampler", name, "--count", "256",
                                "--dims", "0,1", "-o", os.path.join(figures_dir, f"{base}.{ext}")],
                               check=True, capture_output=True, text=True, timeout=120)
        except (OSError, subprocess.SubprocessError) as e:
            detail = getattr(e, "stderr", "") or str(e)
            return ('<p class="note">The sampler gallery is not available: '
                    f'<code>pathlab points</code> failed ({esc(detail.strip()[:200])}).</p>')
        cards.append(f'<figure class="sampler-card" style="border-color:{figures.colour(name)}">'
                     f'<figcaption><span class="swatch" style="background:'
                     f'{figures.colour(name)}"></span>{esc(name)} · '
                     f'<a href="figures/{base}.svg">SVG</a> · <a href="figures/{base}.png">PNG</a>'
                     f'</figcaption><img src="figures/{base}.svg" alt="{esc(name)} points"></figure>')
    return ('<p class="note">256 samples of one pixel in dimensions 0 and 1 (the position inside '
            'the pixel), and their radially averaged power spectrum: white noise is flat at 1, '
            'a well-stratified set has little power at low frequencies. <b>blue-noise</b> and '
            '<b>zsobol</b> are blue across pixels, not within one pixel\'s samples: what shows '
            'their design is the spectrum of the error image (docs/samplers.md), not these '
            'points.</p>'
            f'<div class="gallery">{"".join(cards)}</div>')


# --- the page ----------------------------------------------------------------

def colour_mode(info):
    """RGB or spectral, and spectral mode's wavelength sampling (docs/rendering.md)."""
    if info.get("spectral", "false") != "true":
        return "RGB"
    return f"spectral ({info.get('wavelengths', 'visible')} wavelengths)"


def header(study):
    info = study.info
    scenes = study.scenes()
    meta = [
        ("scenes", ", ".join(scenes)),
        ("samplers", ", ".join(study.samplers())),
        ("spp", ", ".join(str(n) for n in sorted({int(c["spp"]) for c in study.cells}))),
        ("seeds", ", ".join(str(n) for n in study.seeds())),
        ("cells", str(len(study.cells))),
        ("resolution", f"{info.get('width', '?')}×{info.get('height', '?')}"),
        ("max depth", info.get("max_depth", "?")),
        ("colour", colour_mode(info)),
        ("reference", f"{info.get('reference_spp', '?')} spp, "
                      f"{info.get('reference_sampler', '?')}, seed {info.get('reference_seed', '?')}"),
        ("Russian roulette", f"after {info.get('roulette_depth', '2')} bounces"
                             if info.get("russian_roulette", "true") == "true" else "off"),
        ("threads", ", ".join(str(n) for n in sorted({int(c["threads"]) for c in study.cells
                                                       if c.get("threads") not in (None, "")
                                                       and not c.get("source_hash")}))
         or "?"),
        ("commit", info.get("git_commit", "?")),
        ("created", info.get("created_at", "?")),
    ]
    if study.time_budget():
        meta.insert(-2, ("time budget", f"{fmt(study.time_budget())} s"))
    dl = "".join(f"<div><dt>{esc(k)}</dt><dd>{esc(v)}</dd></div>" for k, v in meta)
    nav = "".join(f'<a href="#scene-{esc(slug(s))}">{esc(s)}</a>' for s in scenes)
    return (f'<header><h1>Sampling study: {esc(info.get("name") or os.path.basename(study.dir))}'
            f'</h1><dl class="meta">{dl}</dl><nav>{nav}<a href="#gallery">sampler gallery</a>'
            f'</nav></header>')


# Pages beside index.html: each module's write(study, report_dir) writes its
# page and returns (href, link text, one-paragraph summary) or None.
EXTRA_PAGES = (verdict,)


def extra_pages(study, report_dir):
    """Writes the extra pages; returns index.html's links to them."""
    links = []
    for module in EXTRA_PAGES:
        page = module.write(study, report_dir)
        if page:
            href, text, summary = page
            links.append(f'<p class="page-link"><a href="{esc(href)}"><b>{esc(text)}</b></a>: '
                         f'{esc(summary)}</p>')
    return "".join(links)


def render_page(assets, title, body, data):
    with open(os.path.join(assets, "template.html"), encoding="utf-8") as f:
        page = f.read()
    with open(os.path.join(assets, "comparer.js"), encoding="utf-8") as f:
        script = f.read()
    # "</" inside inline JSON would end the script element early.
    payload = json.dumps(data, separators=(",", ":")).replace("</", "<\\/")
    for key, value in (("TITLE", esc(title)), ("BODY", body), ("DATA", payload),
                       ("SCRIPT", script)):
        page = page.replace("{{" + key + "}}", value)
    return page


def build(study, report_dir, assets, pathlab):
    figures_dir = os.path.join(report_dir, "figures")
    os.makedirs(figures_dir)
    copier = ImageCopier(report_dir)
    sections, scenes_data = [], []
    for scene in study.scenes():
        s = slug(scene)
        reference = copier.copy(study.reference_png(scene), f"images/{s}/reference.png")
        if reference is None:
            print(f"report: scene {scene} has no reference PNG; skipped", file=sys.stderr)
            continue
        width, height = image_size(os.path.join(report_dir, reference))
        spps = study.spps(scene)
        grid_spps = [n for n in GRID_SPPS if n in spps] or spps[:2]
        crop = choose_crop(study, scene, grid_spps, width, height)
        data = {"name": scene, "slug": s, "width": width, "height": height,
                "reference": reference,
                "edge": copier.copy(study.path(f"references/{scene}-edge.png"),
                                    f"images/{s}/reference-edge.png"),
                "samplers": study.samplers(scene), "spps": spps,
                "gridSpps": grid_spps, "crop": crop,
                "images": scene_images(study, scene, copier)}
        figure_names = figures.convergence_figures(study, scene, figures_dir, s)
        figures.comparison_grid(study, scene, grid_spps, crop, figures_dir, s)
        spectra = error_spectra.section(study, scene, figures_dir, s)
        sections.append(scene_section(study, scene, data, figure_names, spectra))
        scenes_data.append(data)
    if not scenes_data:
        raise StudyError(f"'{study.dir}' has no scene with a reference image yet")
    body = header(study) + extra_pages(study, report_dir) + "".join(sections)
    own = [s for s in study.samplers() if ":" not in s]  # external ones have no points
    body += (f'<section id="gallery"><h2>Sampler gallery</h2>'
             f'{gallery(own, pathlab, figures_dir)}</section>')
    body += (f'<footer>Written by <code>pathlab report</code> on '
             f'{time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())} from '
             f'<code>{esc(study.dir)}</code>.</footer>')
    palette = {name: figures.colour(name) for name in study.samplers()}
    data = {"scenes": scenes_data, "palette": palette, "referenceColour": figures.REFERENCE_COLOUR}
    page = render_page(assets, f"pathlab report: {study.info.get('name') or ''}", body, data)
    with open(os.path.join(report_dir, "index.html"), "w", encoding="utf-8") as f:
        f.write(page)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("study", help="the study directory")
    parser.add_argument("--pathlab", help="the pathlab binary, for the sampler gallery")
    parser.add_argument("--error-file", help="where to write a bad-input message")
    args = parser.parse_args()

    def bad_input(message):
        if args.error_file:
            with open(args.error_file, "w", encoding="utf-8") as f:
                f.write(message)
        else:
            print(f"pathlab: error: {message}", file=sys.stderr)
        return 2

    assets = os.path.dirname(os.path.abspath(__file__))
    try:
        study = Study(args.study)
    except StudyError as e:
        return bad_input(str(e))
    final = os.path.join(study.dir, "report")
    # Build beside the target and swap it in, so a report that exists is complete.
    staging = os.path.join(study.dir, f".report.tmp.{os.getpid()}")
    shutil.rmtree(staging, ignore_errors=True)
    try:
        build(study, staging, assets, args.pathlab)
        old = final + f".old.{os.getpid()}"
        if os.path.exists(final):
            os.rename(final, old)
        os.rename(staging, final)
        shutil.rmtree(old, ignore_errors=True)
    except StudyError as e:
        shutil.rmtree(staging, ignore_errors=True)
        return bad_input(str(e))
    except BaseException:
        shutil.rmtree(staging, ignore_errors=True)
        raise
    return 0


if __name__ == "__main__":
    sys.exit(main())
