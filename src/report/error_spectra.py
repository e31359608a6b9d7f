"""Screen-space error in the report: each sampler's error spectrum at 1, 4 and
16 spp, and the low-frequency error fraction in the summary table.

The spectra are the CSVs the study writes beside each seed-0 cell
(images/SCENE/SAMPLER/spp{N}-seed0-spectrum.csv, computed in C++ by
metrics/error_spectrum.h, the numbers `pathlab compare --error-spectrum`
gives); nothing is recomputed here. Blue-noise error (Georgiev & Fajardo
2016; Heitz & Belcour 2019) shows as little power left of the dotted line.
"""

import csv
import math
import os

import figures
from figures import plt

SPECTRUM_SPPS = (1, 4, 16)
LOW_FREQUENCY_LIMIT = 0.125  # cycles per pixel, a quarter of Nyquist (kLowFrequencyLimit)
WHITE_NOISE_FRACTION = math.pi / 64  # the disc |f| < 1/8 over the square of frequencies


def spectrum_path(study, scene, sampler, spp):
    return study.path(f"images/{scene}/{sampler}/spp{spp}-seed0-spectrum.csv")


def read_spectrum(path):
    """(frequency, power) of the rings after the DC row, or None without a file."""
    if not os.path.isfile(path):
        return None
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    if not rows or rows[0] != ["frequency", "power"] or len(rows) < 3:
        return None
    body = [(float(a), float(b)) for a, b in rows[2:]]
    return [f for f, _ in body], [p for _, p in body]


def spectrum_spps(study, scene):
    return [n for n in SPECTRUM_SPPS if n in study.spps(scene)]


def _draw_panel(ax, study, scene, spp):
    drawn = False
    for sampler in study.samplers(scene):
        spectrum = read_spectrum(spectrum_path(study, scene, sampler, spp))
        if spectrum is None:
            continue
        st = figures.style(sampler)
        ax.plot(*spectrum, label=sampler, color=st["color"], linestyle=st["linestyle"],
                linewidth=1.2)
        drawn = True
    ax.set_yscale("log")
    ax.set_xlim(0, 0.5)
    ax.axvline(LOW_FREQUENCY_LIMIT, color="#888888", linestyle=":", linewidth=1)
    ax.set_title(f"{spp} spp")
    ax.set_xlabel("frequency (cycles/pixel)")
    return drawn


def spectra_figure(study, scene, directory, slug):
    """The spectra at 1, 4 and 16 spp side by side; None when the study has none."""
    spps = spectrum_spps(study, scene)
    if not spps:
        return None
    fig, axes = plt.subplots(1, len(spps), figsize=(3.3 * len(spps), 2.9), sharey=True,
                             squeeze=False)
    drawn = [_draw_panel(ax, study, scene, n) for ax, n in zip(axes[0], spps)]
    if not any(drawn):
        plt.close(fig)
        return None
    axes[0][0].set_ylabel("error power")
    handles, labels = [], []
    for ax in axes[0]:
        for h, label in zip(*ax.get_legend_handles_labels()):
            if label not in labels:
                handles.append(h)
                labels.append(label)
    axes[0][-1].legend(handles, labels, loc="upper left", bbox_to_anchor=(1.02, 1.0),
                       borderaxespad=0)
    fig.tight_layout()
    return figures.save(fig, directory, f"{slug}-error-spectra")


def table_columns(study, scene):
    """The summary table's low-frequency columns as (name, getter of the scene
    analysis of one sampler): the fraction's mean over the seeds at each spp."""
    cols = []
    for n in spectrum_spps(study, scene):
        if any((study.cell(scene, s, n) or {}).get("low_frequency_fraction") is not None
               for s in study.samplers(scene)):
            cols.append((f"low-freq. error, {n} spp",
                         lambda a, n=n: (a.get("low_frequency_fraction") or {}).get(str(n))))
    return cols


def section(study, scene, directory, slug):
    """The scene's "Screen-space error" block, or "" for a study without spectra."""
    base = spectra_figure(study, scene, directory, slug)
    if base is None:
        return ""
    caption = "Error spectra at " + ", ".join(f"{n}" for n in spectrum_spps(study, scene)) + " spp"
    note = ("Radially averaged power spectrum of each sampler's signed error (image − "
            "reference, mean of the three channels) in seed 0, against frequency in cycles "
            "per pixel up to Nyquist; white noise is flat at its variance. Left of the dotted "
            f"line (a quarter of Nyquist) lies the power the <i>low-freq. error</i> columns of "
            f"the summary count, as a share of the total: {WHITE_NOISE_FRACTION:.3f} for "
            "white noise, less for error spread as blue noise, which looks smoother at the "
            "same MSE. Data: <code>images/…/spp{N}-seed0-spectrum.csv</code>.")
    return (f'<h3>Screen-space error</h3><figure class="spectra"><img src="figures/'
            f'{base}.svg" alt="{caption}"><figcaption>{caption} · <a href="figures/{base}.svg">'
            f'SVG</a> · <a href="figures/{base}.png">PNG</a></figcaption></figure>'
            f'<p class="note">{note}</p>')
