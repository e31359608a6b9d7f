#!/usr/bin/env python3
"""The Python module's overhead: pathlab.render of the Cornell box at 256² ×
64 spp against `pathlab render` of the same image, neither counting process
start.

    PYTHONPATH=build/release/python /usr/bin/python3 bench/python_overhead.py \
        build/release/pathlab [RUNS]

The CLI's time is the render time it prints ("rendered … in T s": the
renderer's own clock, without starting the process, loading the scene or
writing the EXR). Python's is the wall time of the pathlab.render call on a
scene loaded once: the renderer plus everything the binding adds (settings,
the worker thread, the GIL, the Ctrl-C polling, the copy into numpy). Runs
alternate between the two so that drift in the machine's load hits both; the
medians and their ratio are printed, and the time the Python call spends
outside the renderer (its wall time less the renderer's clock), which does not
depend on how busy the machine is.

Then the cost of pathlab.render_progressive to the same 64 spp in steps of
STEPS (default 8,32: eight images, two) against one pathlab.render of 64 spp,
alternating too: each step continues the previous one, so the whole should
cost about one render plus what each pass costs beyond its samples.

    ... bench/python_overhead.py build/release/pathlab [RUNS [STEPS]]
"""

import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

import pathlab

SETTINGS = dict(sampler="sobol-owen", spp=64, seed=0, size=(256, 256), max_depth=8)


def cli_seconds(binary, out):
    result = subprocess.run(
        [binary, "render", "--scene", "cornell-box", "--sampler", SETTINGS["sampler"], "--spp",
         str(SETTINGS["spp"]), "--seed", "0", "--size", "256x256", "--max-depth", "8", "-o", out],
        capture_output=True, text=True, check=True)
    return float(re.search(r" in ([0-9.]+) s:", result.stderr).group(1))


def python_seconds(scene):
    """The call's wall time, and the part of it outside the renderer."""
    start = time.perf_counter()
    _, stats = pathlab.render(scene, return_stats=True, **SETTINGS)
    wall = time.perf_counter() - start
    return wall, wall - stats["seconds"]


def progressive_seconds(scene, step):
    start = time.perf_counter()
    for _ in pathlab.render_progressive(scene, SETTINGS["spp"], step,
                                        **{k: v for k, v in SETTINGS.items() if k != "spp"}):
        pass
    return time.perf_counter() - start


def compare_progressive(scene, runs, step_sizes):
    whole, steps = [], {step: [] for step in step_sizes}
    for _ in range(runs):
        start = time.perf_counter()
        pathlab.render(scene, **SETTINGS)
        whole.append(time.perf_counter() - start)
        for step in step_sizes:
            steps[step].append(progressive_seconds(scene, step))
    w = statistics.median(whole)
    print("one pathlab.render median %.4f s  (min %.4f)" % (w, min(whole)))
    for step, seconds in steps.items():
        p = statistics.median(seconds)
        print("render_progressive, steps of %2d spp (%d images): median %.4f s (min %.4f), "
              "%+.2f%% (medians), %+.2f%% (minima)"
              % (step, -(-SETTINGS["spp"] // step), p, min(seconds), 100 * (p / w - 1),
                 100 * (min(seconds) / min(whole) - 1)))


def main():
    binary = sys.argv[1]
    runs = int(sys.argv[2]) if len(sys.argv) > 2 else 10
    step_sizes = [int(s) for s in (sys.argv[3] if len(sys.argv) > 3 else "8,32").split(",")]
    scene = pathlab.load_scene("cornell-box")
    with tempfile.TemporaryDirectory() as tmp:
        out = tmp + "/cli.exr"
        cli_seconds(binary, out), python_seconds(scene)  # warm caches, TBB's pool
        cli, py, binding = [], [], []
        for _ in range(runs):
            cli.append(cli_seconds(binary, out))
            wall, outside = python_seconds(scene)
            py.append(wall)
            binding.append(outside)
        same = (pathlab.read_image(out) == pathlab.render(scene, **SETTINGS)).all()
    c, p = statistics.median(cli), statistics.median(py)
    print("cornell-box 256x256, 64 spp, %s, %d runs each" % (SETTINGS["sampler"], runs))
    print("CLI render     median %.4f s  (min %.4f)" % (c, min(cli)))
    print("pathlab.render median %.4f s  (min %.4f)" % (p, min(py)))
    print("Python / CLI   %+.2f%% (medians), %+.2f%% (minima); same image: %s"
          % (100 * (p / c - 1), 100 * (min(py) / min(cli) - 1), same))
    # Independent of the machine's load: what the binding adds around render().
    b = statistics.median(binding)
    print("binding        median %.5f s outside render() (%.3f%% of the call)" % (b, 100 * b / p))
    compare_progressive(scene, runs, step_sizes)
    print("load average   %.2f %.2f %.2f" % os.getloadavg())


if __name__ == "__main__":
    main()
