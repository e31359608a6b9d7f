"""The report's figures, drawn with matplotlib and saved as SVG and PNG.

Every figure uses the same colour, marker and line style per sampler, so a
sampler is recognisable across plots, grids and the web page.
"""

import hashlib
import os

import matplotlib

matplotlib.use("Agg")  # no display: files only
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.patches import Rectangle  # noqa: E402
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter  # noqa: E402

# Colour-blind-aware and distinct; the presentation's five are drawn solid,
# the pbrt-v4 family dashed, so fifteen lines stay tellable apart.
PALETTE = {
    "standard": "#4d4d4d",
    "halton": "#1f77b4",
    "halton-rd": "#17becf",
    "halton-owen": "#9467bd",
    "blue-noise": "#2ca02c",
    "independent": "#8f8f8f",
    "stratified": "#8c564b",
    "sobol": "#ff7f0e",
    "sobol-xor": "#d4a000",
    "sobol-global-owen": "#a05a2c",
    "sobol-owen": "#d62728",
    "zsobol": "#e377c2",
    "sobol-bluenoise": "#00a087",
    "pmj02": "#7f7f00",
    "cascaded-sobol": "#5254a3",
}
MARKERS = "os^Dv<>pPhX*d"
PRESENTATION = {"standard", "halton", "halton-rd", "halton-owen", "blue-noise"}
REFERENCE_COLOUR = "#000000"

plt.rcParams.update({
    "font.size": 9,
    "axes.titlesize": 10,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "grid.linewidth": 0.5,
    "legend.fontsize": 8,
    "legend.frameon": False,
    "savefig.bbox": "tight",
    "svg.hashsalt": "pathlab",  # stable element ids: same data, same file
})


def colour(sampler):
    if sampler in PALETTE:
        return PALETTE[sampler]
    digest = hashlib.sha1(sampler.encode()).digest()
    return "#%02x%02x%02x" % (64 + digest[0] % 160, 64 + digest[1] % 160, 64 + digest[2] % 160)


# An external renderer's samplers ("name:sampler") are dotted with hollow
# markers, so they never pass for pathlab's; a biased point gets a red ring.
EXTERNAL_LINESTYLE = ":"
BIASED_COLOUR = "#e00000"


def style(sampler):
    external = ":" in sampler
    index = sorted(PALETTE).index(sampler) if sampler in PALETTE else len(sampler)
    linestyle = "-" if sampler in PRESENTATION or sampler not in PALETTE else "--"
    out = {
        "color": colour(sampler),
        "marker": MARKERS[index % len(MARKERS)],
        "linestyle": EXTERNAL_LINESTYLE if external else linestyle,
        "markersize": 3.5,
        "linewidth": 1.4,
    }
    if external:
        out.update(markerfacecolor="white", markersize=4.5)
    return out


def save(fig, directory, name):
    """Writes NAME.svg and NAME.png; returns the base name."""
    for ext, extra in (("svg", {}), ("png", {"dpi": 160})):
        fig.savefig(os.path.join(directory, f"{name}.{ext}"), metadata=_metadata(ext), **extra)
    plt.close(fig)
    return name


def _metadata(ext):
    # No creation date, so regenerating the same study gives the same files.
    return {"Date": None} if ext == "svg" else {"Software": "pathlab report"}


# --- convergence plots -------------------------------------------------------

METRIC_LABELS = {
    "mse": "MSE",
    "relmse": "relMSE",
    "flip": "mean FLIP",
}


def _draw_series(ax, x, series, sampler):
    st = style(sampler)
    ax.plot(x, series.mean, label=sampler, **st)
    if any(lo != hi for lo, hi in zip(series.lo, series.hi)):
        ax.fill_between(x, series.lo, series.hi, color=st["color"], alpha=0.15, linewidth=0)


def _slope_guide(ax, study, scene, metric):
    """A dashed line of slope −1 through the middle of the 1-spp values."""
    starts = [s.mean[0] for s in (study.series(scene, n, metric) for n in study.samplers(scene))
              if s.mean]
    spps = study.spps(scene)
    if not starts or len(spps) < 2:
        return
    y0 = float(np.exp(np.mean(np.log(starts)))) * 1.6
    x = np.array([spps[0], spps[-1]], dtype=float)
    ax.plot(x, y0 * spps[0] / x, color="#555", linestyle=(0, (1, 2)), linewidth=1,
            label="slope −1 (Monte Carlo)")


def _mark_biased(ax, study, scene, metric):
    """A red ring, and one legend entry, on every point the analysis calls biased."""
    labelled = False
    for sampler in study.samplers(scene):
        biased = set(study.biased_spps(scene, sampler))
        s = study.series(scene, sampler, metric)
        points = [(n, m) for n, m in zip(s.spp, s.mean) if n in biased]
        if not points:
            continue
        ax.plot([p[0] for p in points], [p[1] for p in points], linestyle="none", marker="o",
                markersize=9, markerfacecolor="none", markeredgecolor=BIASED_COLOUR,
                markeredgewidth=1.5, label=None if labelled else "biased (bias.csv)")
        labelled = True


def _renderer_legend(ax, study, scene):
    """One legend entry per external renderer: its samplers are the dotted lines."""
    for renderer in study.renderers(scene):
        ax.plot([], [], color="#555", linestyle=EXTERNAL_LINESTYLE, marker="o",
                markerfacecolor="white", label=f"{renderer}: external renderer (dotted)")


def plot_vs_spp(ax, study, scene, metric):
    for sampler in study.samplers(scene):
        s = study.series(scene, sampler, metric)
        if s.spp:
            _draw_series(ax, s.spp, s, sampler)
    _mark_biased(ax, study, scene, metric)
    _renderer_legend(ax, study, scene)
    if metric in ("mse", "relmse"):
        _slope_guide(ax, study, scene, metric)
    floor = study.noise_floor(scene, metric) if metric in ("mse", "relmse") else None
    if floor:
        ax.axhline(floor, color=REFERENCE_COLOUR, linestyle="-", linewidth=0.8, alpha=0.7,
                   label="reference noise floor")
    ax.set_xscale("log", base=2)
    ax.set_yscale("log")
    ax.set_xlabel("samples per pixel")
    ax.set_ylabel(METRIC_LABELS[metric])
    ax.set_title(f"{METRIC_LABELS[metric]} vs spp")
    spps = study.spps(scene)
    ax.set_xticks(spps, [str(n) for n in spps])
    ax.xaxis.set_minor_formatter(NullFormatter())
    _label_short_log_axis(ax)


def _label_short_log_axis(ax):
    """Ticks at 1, 2, 3, 5 × 10^k when the y range spans under two decades
    (FLIP's usually does), so the axis is never left with one number."""
    low, high = ax.get_ylim()
    if low > 0 and high / low < 100:
        ax.yaxis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 3.0, 5.0)))
        ax.yaxis.set_major_formatter(FuncFormatter(lambda y, _: f"{y:.3g}"))
        ax.yaxis.set_minor_formatter(NullFormatter())


def plot_vs_time(ax, study, scene):
    for sampler in study.samplers(scene):
        s = study.series(scene, sampler, "mse")
        # An external renderer's cells without render times have none to plot.
        if s.spp and any(t > 0 for t in s.seconds):
            _draw_series(ax, s.seconds, s, sampler)
    target = study.analysis[scene]["target_mse"]
    if target:
        ax.axhline(target, color="#555", linestyle="--", linewidth=0.8, label="target error")
    floor = study.noise_floor(scene)
    if floor:
        ax.axhline(floor, color=REFERENCE_COLOUR, linestyle="-", linewidth=0.8, alpha=0.7,
                   label="reference noise floor")
    budget = study.time_budget()
    if budget:
        ax.axvline(budget, color="#555", linestyle="-.", linewidth=0.8, label="time budget")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("render time (s)")
    ax.set_ylabel("MSE")
    ax.set_title("MSE vs time (equal-time view)")


PLOTS = [
    ("mse-spp", lambda ax, st, sc: plot_vs_spp(ax, st, sc, "mse")),
    ("relmse-spp", lambda ax, st, sc: plot_vs_spp(ax, st, sc, "relmse")),
    ("flip-spp", lambda ax, st, sc: plot_vs_spp(ax, st, sc, "flip")),
    ("mse-time", plot_vs_time),
]


def convergence_figures(study, scene, directory, slug):
    """One figure per plot, plus the four together; returns their base names."""
    names = []
    for suffix, draw in PLOTS:
        fig, ax = plt.subplots(figsize=(4.6, 3.4))
        draw(ax, study, scene)
        # Beside the axes, where it never hides a line; none when nothing is
        # labelled (matplotlib would warn on stderr).
        if ax.get_legend_handles_labels()[1]:
            ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0)
        names.append(save(fig, directory, f"{slug}-{suffix}"))
    fig, axes = plt.subplots(2, 2, figsize=(9.2, 6.8))
    for ax, (_, draw) in zip(axes.flat, PLOTS):
        draw(ax, study, scene)
    handles, labels = axes.flat[3].get_legend_handles_labels()
    more_h, more_l = axes.flat[0].get_legend_handles_labels()
    for h, label in zip(more_h, more_l):
        if label not in labels:
            handles.append(h)
            labels.append(label)
    fig.legend(handles, labels, loc="lower center", ncol=min(len(labels), 6),
               bbox_to_anchor=(0.5, -0.02 - 0.025 * (len(labels) // 7)))
    fig.suptitle(f"{scene}: convergence (band: min–max over seeds)")
    fig.tight_layout(rect=(0, 0.06, 1, 1))
    combined = save(fig, directory, f"{slug}-convergence")
    return names, combined


# --- the comparison grid -----------------------------------------------------

def comparison_grid(study, scene, spps, crop, directory, slug):
    """The presentation's grid: Original and every sampler, full and zoomed."""
    columns = [("Original", study.reference_png(scene), REFERENCE_COLOUR)]
    columns += [(s, None, colour(s)) for s in study.samplers(scene)]
    rows = len(spps) * 2
    fig, axes = plt.subplots(rows, len(columns), squeeze=False,
                             figsize=(1.45 * len(columns), 1.5 * rows))
    x, y, w, h = crop["x"], crop["y"], crop["w"], crop["h"]
    for r, spp in enumerate(spps):
        for c, (name, path, col) in enumerate(columns):
            path = path or study.image_path(scene, name, spp)
            full, zoom = axes[2 * r][c], axes[2 * r + 1][c]
            if os.path.isfile(path):
                img = mpimg.imread(path)
                full.imshow(img, interpolation="nearest")
                zoom.imshow(img[y:y + h, x:x + w], interpolation="nearest")
                full.add_patch(Rectangle((x - 0.5, y - 0.5), w, h, fill=False,
                                         edgecolor="#ffdd00", linewidth=1))
            for ax in (full, zoom):
                ax.set_xticks([])
                ax.set_yticks([])
                for spine in ax.spines.values():
                    spine.set_edgecolor(col)
                    spine.set_linewidth(1.5)
            if r == 0:
                full.set_title(name, color=col, fontsize=8)
            if c == 0:
                full.set_ylabel(f"{spp} spp", fontsize=8)
                zoom.set_ylabel("zoom", fontsize=8)
    fig.tight_layout(pad=0.3, h_pad=0.2, w_pad=0.2)
    return save(fig, directory, f"{slug}-grid")
