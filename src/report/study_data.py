"""Reading a study directory (docs/study-output.md) into plain Python data.

results.sqlite is the source of truth for the cells; analysis.json supplies
the study runner's derived numbers, and anything it lacks is recomputed here
with the same definitions so an interrupted study still gets a report.
"""

import json
import math
import os
import sqlite3
from collections import defaultdict

# The canonical sampler order, the registry's: the presentation's five, then
# pbrt-v4's and those of recent papers.
SAMPLER_ORDER = [
    "standard", "halton", "halton-rd", "halton-owen", "blue-noise", "independent",
    "stratified", "sobol", "sobol-xor", "sobol-global-owen", "sobol-owen", "zsobol",
    "sobol-bluenoise", "pmj02", "cascaded-sobol",
]


class StudyError(Exception):
    """The directory is not a usable study (reported as bad input)."""


def sampler_sort_key(name):
    if name in SAMPLER_ORDER:
        return (0, SAMPLER_ORDER.index(name), name)
    # An external renderer's samplers ("name:sampler") after pathlab's, by renderer.
    return (1, 0, name)


def renderer_of(sampler):
    """The external renderer a sampler belongs to ("cycles" of "cycles:sobol"), or None."""
    return sampler.split(":", 1)[0] if ":" in sampler else None


def _rows(db, sql):
    db.row_factory = sqlite3.Row
    return [dict(r) for r in db.execute(sql)]


def _read_json(path):
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


class Series:
    """One sampler's metric against spp: mean, min and max over seeds."""

    def __init__(self, spp, mean, lo, hi, seconds):
        self.spp, self.mean, self.lo, self.hi, self.seconds = spp, mean, lo, hi, seconds


class Study:
    def __init__(self, directory):
        self.dir = os.path.abspath(directory)
        db_path = os.path.join(self.dir, "results.sqlite")
        if not os.path.isfile(db_path):
            raise StudyError(f"'{directory}' is not a study directory (no results.sqlite)")
        try:
            db = sqlite3.connect(db_path)
            self.cells = _rows(db, "SELECT * FROM cells")
            self.references = {r["scene"]: r for r in _rows(db, 'SELECT * FROM "references"')}
            self.info = {r["key"]: r["value"] for r in _rows(db, "SELECT key, value FROM study")}
            db.close()
        except sqlite3.Error as e:
            raise StudyError(f"'{db_path}' is not a readable study database: {e}") from None
        self.cells = [c for c in self.cells if c.get("mse") is not None]
        if not self.cells:
            raise StudyError(f"'{directory}' has no finished cells yet")
        analysis = _read_json(os.path.join(self.dir, "analysis.json"))
        if analysis is None:
            analysis = (_read_json(os.path.join(self.dir, "results.json")) or {}).get("analysis")
        self.runner_analysis = analysis or {}
        self._by_key = defaultdict(list)
        for c in self.cells:
            self._by_key[(c["scene"], c["sampler"], int(c["spp"]))].append(c)
        self.analysis = {s: self._scene_analysis(s) for s in self.scenes()}
        # bias.csv's rows by (scene, sampler, spp); empty for older studies.
        self.bias = {(b["scene"], b["sampler"], int(b["spp"])): b
                     for b in self.runner_analysis.get("bias") or []}
        self.bias_tolerance = self.runner_analysis.get("bias_tolerance")

    # --- what the study holds -------------------------------------------------
    def scenes(self):
        seen = []
        for c in self.cells:
            if c["scene"] not in seen:
                seen.append(c["scene"])
        # Scenes with a reference first, in the order the runner finished them.
        return sorted(seen, key=lambda s: (s not in self.references, seen.index(s)))

    def samplers(self, scene=None):
        names = {c["sampler"] for c in self.cells if scene is None or c["scene"] == scene}
        return sorted(names, key=sampler_sort_key)

    def spps(self, scene, sampler=None):
        return sorted({int(c["spp"]) for c in self.cells
                       if c["scene"] == scene and (sampler is None or c["sampler"] == sampler)})

    def seeds(self):
        return sorted({int(c["seed"]) for c in self.cells})

    def cell(self, scene, sampler, spp, seed=0):
        for c in self._by_key.get((scene, sampler, spp), []):
            if int(c["seed"]) == seed:
                return c
        return None

    def biased_spps(self, scene, sampler):
        """The spp at which the analysis calls `sampler` biased on `scene`."""
        return [spp for (sc, sa, spp), b in sorted(self.bias.items())
                if sc == scene and sa == sampler and b.get("biased") == "1"]

    def renderers(self, scene=None):
        """The external renderers whose cells the study holds."""
        return sorted({renderer_of(s) for s in self.samplers(scene) if renderer_of(s)})

    def path(self, relative):
        return os.path.join(self.dir, relative)

    def image_path(self, scene, sampler, spp, kind=""):
        """Seed 0's tone-mapped PNG (kind "") or error map (kind "flip"/"relse")."""
        suffix = f"-{kind}" if kind else ""
        return self.path(f"images/{scene}/{sampler}/spp{spp}-seed0{suffix}.png")

    def reference_png(self, scene):
        return self.path(f"references/{scene}.png")

    def series(self, scene, sampler, metric):
        spp, mean, lo, hi, secs = [], [], [], [], []
        for n in self.spps(scene, sampler):
            cells = self._by_key[(scene, sampler, n)]
            values = [float(c[metric]) for c in cells
                      if c.get(metric) is not None and math.isfinite(float(c[metric]))]
            if not values:
                continue
            spp.append(n)
            mean.append(sum(values) / len(values))
            lo.append(min(values))
            hi.append(max(values))
            secs.append(sum(float(c["seconds"]) for c in cells) / len(cells))
        return Series(spp, mean, lo, hi, secs)

    def noise_floor(self, scene, metric="mse"):
        """The reference's own error in `metric` (mse or relmse), or None."""
        a = self.runner_analysis.get("scenes", {}).get(scene, {})
        if a.get(f"noise_floor_{metric}") is not None:
            return float(a[f"noise_floor_{metric}"])
        ref = self.references.get(scene) or {}
        return ref.get(f"noise_{metric}")

    def time_budget(self):
        try:
            value = float(self.info.get("time_budget_seconds") or 0)
        except ValueError:
            return None
        return value if value > 0 else None

    # --- derived numbers --------------------------------------------------------
    def target_sampler(self, scene):
        wanted = self.runner_analysis.get("target_sampler", "standard")
        names = self.samplers(scene)
        for name in (wanted, "standard", "independent"):
            if name in names:
                return name
        return names[0]

    def _scene_analysis(self, scene):
        """The runner's analysis for `scene`, completed where it has gaps."""
        runner = self.runner_analysis.get("scenes", {}).get(scene, {})
        target_name = self.target_sampler(scene)
        target_series = self.series(scene, target_name, "mse")
        target_mse = runner.get("target_mse", target_series.mean[-1] if target_series.mean else None)
        independent = self.series(scene, "independent", "mse")
        out = {"target_mse": target_mse, "target_sampler": target_name,
               "target_spp": target_series.spp[-1] if target_series.spp else None,
               "samplers": {}}
        for name in self.samplers(scene):
            mine = runner.get("samplers", {}).get(name, {})
            mse, rel = self.series(scene, name, "mse"), self.series(scene, name, "relmse")
            computed = {
                "slope_mse": _loglog_slope(mse.spp, mse.mean),
                "slope_relmse": _loglog_slope(rel.spp, rel.mean),
                "mse_ratio_to_independent": _ratios(mse, independent),
                "time_to_target_seconds": _time_to_target(mse, target_mse),
                "low_frequency_fraction": _by_spp(
                    self.series(scene, name, "low_frequency_fraction")),
            }
            for key, value in computed.items():
                mine.setdefault(key, value)
            out["samplers"][name] = mine
        return out


def _by_spp(series):
    """A series' means keyed by spp as text, as analysis.json keys them."""
    return {str(n): v for n, v in zip(series.spp, series.mean)}


def _loglog_slope(xs, ys):
    points = [(math.log(x), math.log(y)) for x, y in zip(xs, ys) if x > 0 and y > 0]
    if len(points) < 2:
        return None
    mx = sum(p[0] for p in points) / len(points)
    my = sum(p[1] for p in points) / len(points)
    sxx = sum((p[0] - mx) ** 2 for p in points)
    if sxx == 0:
        return None
    return sum((p[0] - mx) * (p[1] - my) for p in points) / sxx


def _ratios(series, independent):
    base = dict(zip(independent.spp, independent.mean))
    return {str(n): m / base[n] for n, m in zip(series.spp, series.mean) if base.get(n)}


def _time_to_target(series, target):
    """Seconds at which the MSE curve first reaches `target`, in log-log."""
    if not target or not series.spp or not any(t > 0 for t in series.seconds):
        return None
    points = list(zip(series.seconds, series.mean))
    if points[0][1] <= target:
        return points[0][0]
    for (t0, e0), (t1, e1) in zip(points, points[1:]):
        if e1 <= target < e0 and t0 > 0 and t1 > 0 and e1 > 0:
            a = (math.log(target) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(t0) + a * (math.log(t1) - math.log(t0)))
    return None
