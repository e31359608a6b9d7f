"""pathlab.run_study and pathlab.Study against `pathlab study`."""

import csv
import json

import pytest

import pathlab

SPEC = """
name = "tiny"
scenes = ["cornell-box"]
samplers = ["independent", "sobol-owen"]
spp = [1, 4]
seeds = 2
resolution = [16, 12]
max_depth = 3
metrics = ["mse", "relmse", "flip"]
[reference]
spp = 16
"""

# Columns that record when and how fast, not what was measured.
CIRCUMSTANTIAL = {"seconds", "finished_at", "git_commit"}


def measured(path):
    with open(path / "results.csv", newline="") as f:
        return [{k: v for k, v in row.items() if k not in CIRCUMSTANTIAL}
                for row in csv.DictReader(f)]


def test_a_study_from_python_equals_one_from_the_cli(cli, tmp_path):
    spec = tmp_path / "tiny.toml"
    spec.write_text(SPEC)
    cli("study", spec, "-o", tmp_path / "cli")
    study = pathlab.run_study(spec, tmp_path / "python", resume=False)
    rows = measured(tmp_path / "python")
    assert len(rows) == 2 * 2 * 2
    assert rows == measured(tmp_path / "cli")
    assert len(study.cells) == 8
    assert set(study.cells["sampler"]) == {"independent", "sobol-owen"}
    with open(tmp_path / "cli" / "analysis.json") as f:
        cli_analysis = json.load(f)
    assert study.analysis.keys() == cli_analysis.keys()


def test_a_study_from_toml_text_and_resumed(tmp_path):
    first = pathlab.run_study(SPEC, tmp_path / "s")
    again = pathlab.run_study(SPEC, tmp_path / "s", resume=True)
    assert len(again.cells) == len(first.cells) == 8
    assert list(again.cells["mse"]) == list(first.cells["mse"])
    image = pathlab.read_image(again.image_path(again.cells.iloc[0]))
    assert image.shape == (12, 16, 3)


def test_bad_specs_raise_value_error(tmp_path):
    with pytest.raises(ValueError, match="samplers|nope"):
        pathlab.run_study(SPEC.replace('"sobol-owen"', '"nope"'), tmp_path / "bad")
    with pytest.raises(ValueError, match="results.csv"):
        pathlab.Study(tmp_path)
