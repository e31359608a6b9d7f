"""The report's verdict page, report/verdict.html: per scene, per difficulty
and over all scenes, the samplers ranked at each spp by MSE, by ꟻLIP and by
equal-time error, with the seeds' spread, and a paragraph saying it in words.

The definitions are verdict_ranking.py's; docs/study.md ("The verdict") gives
them for readers. The page is self-contained, like index.html.
"""

import html
import os
import re
import time
import tomllib
from collections import defaultdict

import verdict_ranking as vr

PAGE = "verdict.html"
UNTAGGED = "untagged"
STYLE = """
body { margin: 0; color: #1d1f23; font: 14px/1.45 system-ui, "DejaVu Sans", sans-serif; }
main { max-width: 1240px; margin: 0 auto; padding: 0 20px 40px; }
h1 { font-size: 24px; margin: 22px 0 6px; }
h2 { font-size: 20px; margin: 30px 0 8px; padding-top: 12px; border-top: 2px solid #1d1f23; }
h3 { font-size: 15px; margin: 18px 0 6px; color: #5c6370; }
a { color: #2458b3; }
.answer { font-size: 16px; max-width: 900px; background: #f5f6f8; border-left: 4px solid #2458b3;
          padding: 10px 14px; }
.note { color: #5c6370; font-size: 12.5px; max-width: 900px; }
table.ranking { border-collapse: collapse; margin: 6px 0 14px; }
.ranking th, .ranking td { border: 1px solid #d9dce1; padding: 4px 8px; vertical-align: top;
                           text-align: left; }
.ranking th { background: #f5f6f8; }
.ranking ol { margin: 0; padding: 0; list-style: none; }
.ranking li { white-space: nowrap; font-size: 12.5px; }
.rank { display: inline-block; min-width: 2.2em; color: #5c6370; }
.first { font-weight: 600; }
.spread { color: #5c6370; }
.tag { font-size: 12px; border: 1px solid #d9dce1; border-radius: 3px; padding: 1px 6px;
       margin-left: 8px; color: #5c6370; font-weight: normal; }
"""


def esc(text):
    return html.escape(str(text), quote=True)


def slug(name):
    return re.sub(r"[^A-Za-z0-9._-]+", "-", name).strip("-") or "scene"


def difficulty_tags(study):
    """Scene -> difficulty, from the [difficulty] table of DIR/spec.toml."""
    try:
        with open(study.path("spec.toml"), "rb") as f:
            table = tomllib.load(f).get("difficulty") or {}
    except (OSError, tomllib.TOMLDecodeError):
        table = {}
    return {scene: str(table.get(scene) or UNTAGGED) for scene in study.scenes()}


def collect(study):
    """{scene: {spp: {metric: {sampler: {seed: value}}}}} of the study's cells."""
    data = defaultdict(lambda: defaultdict(lambda: {m: defaultdict(dict) for m in vr.METRICS}))
    for c in study.cells:
        cell = data[c["scene"]][int(c["spp"])]
        seed = int(c["seed"])
        mse = c.get("mse")
        cell["mse"][c["sampler"]][seed] = mse
        if c.get("flip") is not None:
            cell["flip"][c["sampler"]][seed] = c["flip"]
        (time_value,) = vr.equal_time_values([mse], [c.get("seconds")])
        if time_value is not None:
            cell["equal_time"][c["sampler"]][seed] = time_value
    return data


def baseline_of(study, scenes):
    """independent when every scene has it, else the first sampler they share."""
    shared = [s for s in study.samplers()
              if all(s in study.samplers(scene) for scene in scenes)]
    if "independent" in shared:
        return "independent"
    return shared[0] if shared else None


def scene_rankings(data, scene, spp, baseline):
    """{metric: ranked entries}, values as ratios to the baseline's mean."""
    out = {}
    for metric in vr.METRICS:
        per_sampler = data[scene][spp][metric]
        if baseline in per_sampler:
            out[metric] = vr.rank(vr.across_scenes({scene: per_sampler}, baseline))
        else:
            out[metric] = vr.rank([vr.Entry(n, v.values()) for n, v in per_sampler.items()])
    return out


def group_rankings(data, scenes, spp, baseline):
    out = {}
    for metric in vr.METRICS:
        per_scene = {s: data[s][spp][metric] for s in scenes}
        out[metric] = vr.rank(vr.across_scenes(per_scene, baseline))
    return out


def common_spps(data, scenes):
    sets = [set(data[s]) for s in scenes]
    return sorted(set.intersection(*sets)) if sets else []


def ranking_list(ranked):
    if not ranked:
        return '<span class="spread">not measured</span>'
    items = []
    for e in ranked:
        mark = f"={e.rank}" if e.tied else str(e.rank)
        spread = (f' <span class="spread">[{vr.fmt_ratio(e.lo)}–{vr.fmt_ratio(e.hi)}]</span>'
                  if e.hi > e.lo else "")
        cls = ' class="first"' if e.rank == 1 else ""
        items.append(f'<li{cls}><span class="rank">{mark}</span>{esc(e.name)} '
                     f'{vr.fmt_ratio(e.mean)}{spread}</li>')
    return f"<ol>{''.join(items)}</ol>"


def ranking_table(rows):
    """rows: [(spp, {metric: ranked})] as one table, a row per spp."""
    head = "".join(f"<th>by {esc(vr.METRIC_LABELS[m])}</th>" for m in vr.METRICS)
    body = "".join(f"<tr><th>{spp} spp</th>"
                   + "".join(f"<td>{ranking_list(r.get(m, []))}</td>" for m in vr.METRICS)
                   + "</tr>" for spp, r in rows)
    return f'<table class="ranking"><tr><th></th>{head}</tr>{body}</table>'


def answer(data, scenes, tags, baseline):
    spps = common_spps(data, scenes)
    spp = vr.focus_spp(spps)
    if spp is None:
        return "The study holds no spp measured on every scene."
    overall = group_rankings(data, scenes, spp, baseline)
    groups = []
    for tag in sorted(set(tags.values())):
        members = [s for s in scenes if tags[s] == tag]
        if tag != UNTAGGED and len(set(tags.values())) > 1:
            groups.append((tag, members, group_rankings(data, members, spp, baseline)["mse"]))
    largest = (spps[-1], group_rankings(data, scenes, spps[-1], baseline)["mse"])
    return vr.verdict_paragraph(spp, baseline, len(scenes), overall, groups, largest)


def page_body(study, data, tags, baseline):
    scenes = [s for s in study.scenes() if s in data]
    paragraph = answer(data, scenes, tags, baseline)
    parts = [f'<h1>Verdict: {esc(study.info.get("name") or "study")}</h1>',
             '<p><a href="index.html">← the full report</a></p>',
             f'<p class="answer" id="answer">{esc(paragraph)}</p>',
             f'<p class="note">Each entry: rank, sampler, its error as a ratio to '
             f'<b>{esc(baseline)}</b>\'s (below 1 is better), and in brackets the range over '
             f'{len(study.seeds())} seed(s). A sampler ranks behind only those whose whole '
             f'range lies below its own; "=" marks a rank shared within the seeds\' spread '
             f'(tied). Across scenes, the geometric mean of the per-scene ratios. Equal time: '
             f'MSE × render time, the inverse of Monte Carlo efficiency. ꟻLIP: HDR-ꟻLIP.</p>']
    spps = common_spps(data, scenes)
    parts.append(f'<h2 id="overall">All {len(scenes)} scenes</h2>')
    parts.append(ranking_table([(n, group_rankings(data, scenes, n, baseline)) for n in spps]))
    if len(set(tags.values())) > 1:
        for tag in sorted(set(tags.values())):
            members = [s for s in scenes if tags[s] == tag]
            parts.append(f'<h2 id="group-{slug(tag)}">{esc(vr.group_phrase(tag)).capitalize()}'
                         f'</h2><p class="note">{esc(", ".join(members))}</p>')
            rows = [(n, group_rankings(data, members, n, baseline))
                    for n in common_spps(data, members)]
            parts.append(ranking_table(rows))
    for scene in scenes:
        parts.append(f'<h2 id="scene-{slug(scene)}" class="scene">{esc(scene)}'
                     f'<span class="tag">{esc(tags[scene])}</span></h2>')
        rows = [(n, scene_rankings(data, scene, n, baseline)) for n in sorted(data[scene])]
        parts.append(ranking_table(rows))
    parts.append(f'<p class="note">Written by <code>pathlab report</code> on '
                 f'{time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())}.</p>')
    return "".join(parts), paragraph


def write(study, report_dir):
    """Writes report_dir/verdict.html; returns (href, link text, paragraph) or None."""
    data = collect(study)
    scenes = [s for s in study.scenes() if s in data]
    baseline = baseline_of(study, scenes)
    if baseline is None:
        return None
    body, paragraph = page_body(study, data, difficulty_tags(study), baseline)
    page = (f'<!DOCTYPE html><html lang="en"><head><meta charset="utf-8">'
            f'<meta name="viewport" content="width=device-width, initial-scale=1">'
            f'<title>pathlab verdict: {esc(study.info.get("name") or "")}</title>'
            f'<style>{STYLE}</style></head><body><main>{body}</main></body></html>')
    with open(os.path.join(report_dir, PAGE), "w", encoding="utf-8") as f:
        f.write(page)
    return PAGE, "Verdict across scenes", paragraph
