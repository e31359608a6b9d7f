#!/usr/bin/env python3
"""A notebook-style walk through pathlab's Python API: draw a few samplers'
points, run a small study, and plot each sampler's error against its sample
count (log-log) with matplotlib.

    PYTHONPATH=build/release/python python3 examples/convergence_plot.py --out out/example

The plot goes to OUT/convergence.png; the study to OUT/study (run again with
the same OUT and finished cells are reused). --tiny makes everything small
enough for a test.
"""

import argparse
import os

import matplotlib

matplotlib.use(os.environ.get("MPLBACKEND", "Agg"))
import matplotlib.pyplot as plt  # noqa: E402 (the backend is chosen first)
import numpy as np  # noqa: E402

import pathlab  # noqa: E402

SAMPLERS = ["independent", "halton-owen", "sobol-owen", "pmj02"]


def study_spec(tiny):
    size, spp, ref = ((24, 16), [1, 2, 4, 8], 64) if tiny else ((128, 128), [1, 4, 16, 64], 1024)
    return f"""
name = "convergence-example"
scenes = ["cornell-box"]
samplers = {SAMPLERS!r}
spp = {spp!r}
seeds = 2
resolution = [{size[0]}, {size[1]}]
metrics = ["mse"]
[reference]
spp = {ref}
""".replace("'", '"')


def mean_mse(cells):
    """(sampler → (spp list, mean MSE list)), the mean over seeds."""
    curves = {}
    rows = cells.to_dict("records") if hasattr(cells, "to_dict") else cells
    for row in rows:
        curves.setdefault(row["sampler"], {}).setdefault(row["spp"], []).append(row["mse"])
    return {s: (sorted(c), [float(np.mean(c[n])) for n in sorted(c)]) for s, c in curves.items()}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default="out/example")
    parser.add_argument("--tiny", action="store_true")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)

    # 1. Points: 64 samples of one pixel in its first two dimensions.
    fig, axes = plt.subplots(1, len(SAMPLERS) + 1, figsize=(4 * (len(SAMPLERS) + 1), 4))
    for ax, name in zip(axes, SAMPLERS):
        p = pathlab.points(name, 64, dims=(0, 1), seed=1)
        ax.scatter(p[:, 0], p[:, 1], s=6)
        ax.set(title=name, xlim=(0, 1), ylim=(0, 1), aspect="equal", xticks=[], yticks=[])

    # 2. A study: every sampler at every spp, two seeds, against one reference.
    study = pathlab.run_study(study_spec(args.tiny), os.path.join(args.out, "study"))

    # 3. Convergence: MSE against spp, and the least-squares slope in log-log
    #    (−1 for independent sampling; steeper is better).
    ax = axes[-1]
    for name, (spp, mse) in mean_mse(study.cells).items():
        slope = np.polyfit(np.log(spp), np.log(mse), 1)[0]
        print(f"{name:12s} slope {slope:+.2f}")
        ax.loglog(spp, mse, marker="o", label=f"{name} ({slope:+.2f})")
    ax.set(xlabel="samples per pixel", ylabel="MSE", title="cornell-box convergence")
    ax.legend(fontsize=8)
    fig.tight_layout()
    path = os.path.join(args.out, "convergence.png")
    fig.savefig(path, dpi=80)
    print("wrote", path)


if __name__ == "__main__":
    main()
