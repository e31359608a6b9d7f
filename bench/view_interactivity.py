#!/usr/bin/env python3
"""`pathlab view`'s interactivity at 512×512 (docs/view.md, "Interactivity"):

1. latency: the time from a POST /api/settings that restarts accumulation
   (a new seed) until the first image of the new settings has been fetched
   as PNG, as the page does;
2. throughput: the wall time the view takes to accumulate SPP samples (from
   the restart until /api/status reports them), with a client streaming the
   status and the PNG every 200 ms like an open page, and without one,
   against `pathlab render` of the same image (its own clock).

    python3 bench/view_interactivity.py build/release/pathlab [SPP] [RUNS]
"""

import json
import re
import statistics
import subprocess
import sys
import tempfile
import threading
import time
import urllib.error
import urllib.request

SCENE = ["--scene", "cornell-box", "--size", "512x512", "--max-depth", "8"]


def request(url, body=None):
    data = None if body is None else json.dumps(body).encode()
    with urllib.request.urlopen(urllib.request.Request(url, data=data)) as res:
        raw = res.read()
        return json.loads(raw) if res.headers["Content-Type"] == "application/json" else raw


def wait_for(base, generation, spp, poll=0.005):
    while True:
        s = request(base + "/api/status")
        if s["generation"] == generation and s["spp"] >= spp:
            return s
        time.sleep(poll)


def latency(base, seed):
    start = time.perf_counter()
    generation = request(base + "/api/settings", {"seed": seed})["generation"]
    wait_for(base, generation, 1)
    request(base + "/api/image?which=a&format=png")
    return time.perf_counter() - start


def accumulate(base, seed, spp, stream):
    done = threading.Event()

    def page():
        while not done.is_set():
            request(base + "/api/status")
            try:
                request(base + "/api/image?which=a&format=png")
            except urllib.error.HTTPError as e:  # 404 until the first pass lands
                if e.code != 404:
                    raise
            time.sleep(0.2)

    streamer = threading.Thread(target=page) if stream else None
    start = time.perf_counter()
    generation = request(base + "/api/settings", {"seed": seed, "max_spp": spp})["generation"]
    if streamer:
        streamer.start()
    wait_for(base, generation, spp, poll=0.02)
    seconds = time.perf_counter() - start
    done.set()
    if streamer:
        streamer.join()
    return seconds


def render_seconds(binary, sampler, spp, out):
    r = subprocess.run([binary, "render", *SCENE, "--sampler", sampler, "--spp", str(spp),
                        "--seed", "0", "-o", out], capture_output=True, text=True, check=True)
    return float(re.search(r" in ([0-9.]+) s:", r.stderr).group(1))


def main():
    binary = sys.argv[1]
    spp = int(sys.argv[2]) if len(sys.argv) > 2 else 64
    runs = int(sys.argv[3]) if len(sys.argv) > 3 else 3
    sampler = "sobol-owen"
    view = subprocess.Popen([binary, "view", *SCENE, "--sampler", sampler, "--port", "0",
                             "--max-spp", "1"], stdout=subprocess.PIPE, text=True)
    try:
        base = re.search(r"(http://[^/]+)", view.stdout.readline()).group(1)
        lat = [latency(base, seed) for seed in range(1, 1 + 5 * runs)]
        with tempfile.TemporaryDirectory() as tmp:
            cli, quiet, streamed = [], [], []
            for run in range(runs):  # interleaved, so drift in load hits all three
                cli.append(render_seconds(binary, sampler, spp, tmp + "/r.exr"))
                quiet.append(accumulate(base, 100 + run, spp, stream=False))
                streamed.append(accumulate(base, 200 + run, spp, stream=True))
        request(base + "/api/stop", {})
        view.wait(timeout=30)
    finally:
        if view.poll() is None:
            view.kill()
    med = statistics.median
    print(f"first image after a restart: median {med(lat) * 1000:.0f} ms, "
          f"max {max(lat) * 1000:.0f} ms ({len(lat)} restarts)")
    print(f"{spp} spp at 512x512 ({sampler}): pathlab render {med(cli):.2f} s, "
          f"view {med(quiet):.2f} s (x{med(quiet) / med(cli):.3f}), "
          f"view streaming to a page {med(streamed):.2f} s (x{med(streamed) / med(cli):.3f})")


if __name__ == "__main__":
    main()
