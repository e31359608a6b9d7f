"""The example script runs headless and draws its convergence plot."""

import os
import pathlib
import subprocess
import sys

EXAMPLE = pathlib.Path(__file__).resolve().parents[2] / "examples" / "convergence_plot.py"


def test_the_convergence_example_draws_its_plot(tmp_path):
    env = dict(os.environ, MPLBACKEND="Agg")
    result = subprocess.run([sys.executable, str(EXAMPLE), "--out", str(tmp_path), "--tiny"],
                            capture_output=True, text=True, env=env)
    assert result.returncode == 0, result.stderr
    plot = tmp_path / "convergence.png"
    assert plot.stat().st_size > 10000
    assert plot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "slope" in result.stdout
