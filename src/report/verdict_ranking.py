"""The verdict's arithmetic: rankings with the seeds' spread, ratios to a
baseline across scenes, and the plain-language paragraph (docs/study.md,
"The verdict").

Definitions, kept here in one place:

- A sampler's value at an spp is the mean over its seeds; its interval is
  [min, max] over the seeds (the seed spread).
- Its rank is 1 + the number of samplers that beat it beyond the spread:
  whose whole interval lies below its own (hi < lo). Samplers whose intervals
  overlap can share a rank: they are tied. Lower error ranks first.
- Equal-time error is MSE × render time: for a Monte Carlo estimator MSE
  falls as 1/time, so the product is the inverse of the efficiency
  1 / (variance × time) of Veach's thesis (1997, ch. 2) and pbrt-v4 §2.1.4.
  It ranks samplers as their MSE at one equal render time would, where each
  keeps converging at the rate of plain Monte Carlo from this spp.
- Across scenes, each sampler's value is the geometric mean over the scenes
  of its ratio to the baseline's mean value on that scene; its interval is
  the range, over seeds, of the same geometric mean of each seed's ratio.
"""

import math

METRICS = ("mse", "flip", "equal_time")
METRIC_LABELS = {"mse": "MSE", "flip": "ꟻLIP", "equal_time": "equal time (MSE × time)"}


class Entry:
    """One sampler's values over seeds, with its mean and interval."""

    def __init__(self, name, values):
        values = [float(v) for v in values if v is not None and math.isfinite(float(v))]
        self.name, self.values = name, values
        self.mean = sum(values) / len(values) if values else None
        self.lo = min(values) if values else None
        self.hi = max(values) if values else None
        self.rank, self.tied = None, False


def rank(entries):
    """Ranks entries with a value (lower first); returns them in rank order.

    Entries without a value are left out. Ties: see the module's docstring.
    """
    ranked = [e for e in entries if e.mean is not None]
    for e in ranked:
        e.rank = 1 + sum(1 for other in ranked if other is not e and other.hi < e.lo)
    for e in ranked:
        e.tied = any(other is not e and other.rank == e.rank for other in ranked)
    return sorted(ranked, key=lambda e: (e.rank, e.mean, e.name))


def equal_time_values(mses, seconds):
    """Per seed MSE × seconds; None where either is missing or time is not positive."""
    out = []
    for m, t in zip(mses, seconds):
        ok = m is not None and t is not None and float(t) > 0
        out.append(float(m) * float(t) if ok else None)
    return out


def geometric_mean(values):
    values = [v for v in values if v is not None]
    if not values or any(v <= 0 for v in values):
        return None
    return math.exp(sum(math.log(v) for v in values) / len(values))


def across_scenes(per_scene, baseline):
    """Entries of every sampler present on all scenes, as ratios to `baseline`.

    `per_scene` maps scene -> {sampler: {seed: value}}. A sampler's value is
    the geometric mean over scenes of (its mean / the baseline's mean); each
    seed's geometric mean of ratios gives the interval. Returns [] when the
    baseline is missing from a scene.
    """
    if not per_scene or any(baseline not in samplers for samplers in per_scene.values()):
        return []
    common = set.intersection(*(set(s) for s in per_scene.values()))
    base = {scene: Entry(baseline, samplers[baseline].values()).mean
            for scene, samplers in per_scene.items()}
    if any(not b or b <= 0 for b in base.values()):
        return []
    entries = []
    for name in sorted(common):
        ratios = [Entry(name, per_scene[s][name].values()).mean for s in per_scene]
        mean = geometric_mean([r / base[s] if r is not None else None
                               for r, s in zip(ratios, per_scene)])
        seeds = set.intersection(*(set(per_scene[s][name]) for s in per_scene))
        per_seed = [geometric_mean([_ratio(per_scene[s][name].get(k), base[s]) for s in per_scene])
                    for k in sorted(seeds)]
        e = Entry(name, [v for v in per_seed if v is not None])
        if mean is None or e.mean is None:
            continue
        e.mean = mean  # the ratio of means, not the mean of per-seed ratios
        e.lo, e.hi = min(e.lo, mean), max(e.hi, mean)
        entries.append(e)
    return entries


def _ratio(value, base):
    if value is None or not math.isfinite(float(value)):
        return None
    return float(value) / base


# --- the paragraph -----------------------------------------------------------

GROUP_PHRASES = {
    "diffuse/indirect": "diffuse scenes lit mostly indirectly",
    "glossy": "glossy scenes",
    "refractive": "refractive scenes",
    "environment": "environment-lit scenes",
    "depth of field": "depth-of-field scenes",
    "many lights": "scenes with many lights",
    "textured": "textured scenes",
}


def group_phrase(tag):
    return GROUP_PHRASES.get(tag, f"{tag} scenes")


def fmt_ratio(value):
    return f"{value:.2f}×" if value >= 0.095 else f"{value:.3f}×"


def leaders_phrase(ranked):
    """"X (0.41×)" or "X and Y, tied (0.41× and 0.45×)" for the rank-1 entries."""
    top = [e for e in ranked if e.rank == 1]
    if not top:
        return None
    names = [e.name for e in top]
    values = [fmt_ratio(e.mean) for e in top]
    if len(top) == 1:
        return f"{names[0]} ({values[0]})"
    return (f"{', '.join(names[:-1])} and {names[-1]}, tied within the seeds' spread "
            f"({', '.join(values[:-1])} and {values[-1]})")


def focus_spp(spps, preferred=16):
    """The spp the paragraph speaks of: 16 when measured, else the middle one."""
    spps = sorted(spps)
    if not spps:
        return None
    return preferred if preferred in spps else spps[len(spps) // 2]


def _scene_list(names):
    return ", ".join(names) if len(names) <= 3 else f"{len(names)} scenes"


def verdict_paragraph(spp, baseline, scene_count, overall, groups, largest=None):
    """The plain-language answer from the rankings.

    overall: {metric: ranked entries at `spp`}; groups: [(tag, scene names,
    ranked MSE entries at `spp`)]; largest: (spp, ranked MSE entries) or None.
    """
    scenes = f"{scene_count} scene" + ("s" if scene_count != 1 else "")
    lead = leaders_phrase(overall.get("mse", []))
    if lead is None:
        return "The study holds too little to rank its samplers across scenes."
    text = [f"At {spp} spp, across the {scenes}, the lowest MSE is {lead}, "
            f"as a geometric mean of the ratio to {baseline}'s MSE."]
    others = []
    for metric in ("flip", "equal_time"):
        phrase = leaders_phrase(overall.get(metric, []))
        if phrase:
            others.append(f"by {METRIC_LABELS[metric]} it is {phrase}")
    if others:
        sentence = "; ".join(others)
        text.append(" " + sentence[0].upper() + sentence[1:] + ".")
    by_group = [f"on {group_phrase(tag)} ({_scene_list(names)}), {leaders_phrase(r)}"
                for tag, names, r in groups if leaders_phrase(r)]
    if by_group:
        text.append(" By MSE " + "; ".join(by_group) + ".")
    if largest and largest[0] != spp and leaders_phrase(largest[1]):
        text.append(f" At {largest[0]} spp the lowest MSE is {leaders_phrase(largest[1])}.")
    text.append(" Ratios below 1 beat the baseline; samplers whose seed ranges overlap"
                " are called tied.")
    return "".join(text)
