"""pathlab.samplers and pathlab.points against `pathlab samplers` / `points`."""

import csv

import numpy as np
import pytest

import pathlab


def test_sobol_gives_the_first_points_of_the_sobol_sequence():
    expected = np.array([[0, 0], [0.5, 0.5], [0.75, 0.25], [0.25, 0.75]], dtype=np.float32)
    assert np.array_equal(pathlab.points("sobol", 4), expected)


def test_samplers_are_the_cli_list(cli):
    rows = cli("samplers").stdout.strip().splitlines()[1:]
    names = [row.split()[0] for row in rows]
    listed = pathlab.samplers()
    assert [s["name"] for s in listed] == names
    for s, row in zip(listed, rows):
        fields = row.split()
        dims = "unbounded" if s["dimensions"] is None else str(s["dimensions"])
        assert fields[1:4] == [dims, "yes" if s["randomized"] else "no",
                               "yes" if s["progressive"] else "no"]
        assert row.rstrip().endswith(s["description"])


@pytest.mark.parametrize("sampler,dims", [("sobol-owen", (0, 1)), ("halton", (3, 4)),
                                          ("pmj02", (4, 9)), ("blue-noise", (5, 6))])
def test_points_equal_the_cli_csv(cli, tmp_path, sampler, dims):
    out = tmp_path / "points.csv"
    cli("points", "--sampler", sampler, "--count", 64, "--dims", "%d,%d" % dims, "--pixel",
        "3,2", "--seed", 7, "-o", out)
    with open(out) as f:
        rows = list(csv.DictReader(f))
    expected = np.array([[float(r["x"]), float(r["y"])] for r in rows], dtype=np.float32)
    got = pathlab.points(sampler, 64, dims=dims, pixel=(3, 2), seed=7)
    assert np.array_equal(got, expected)


def test_every_dimension_is_drawn_as_the_renderer_draws_it():
    # Without a lens: pixel (0, 1), then per bounce light choice (1D), light
    # point (2D), BSDF lobe (1D), BSDF direction (2D), roulette (1D).
    table = pathlab.points("sobol-owen", 32, dims=range(9), seed=1)
    assert table.shape == (32, 9)
    for draw in [(0, 1), (3, 4), (6, 7), (2, 5), (5, 8)]:
        assert np.array_equal(table[:, list(draw)],
                              pathlab.points("sobol-owen", 32, dims=draw, seed=1))
    assert len(np.unique(table[:, 2])) > 1


def test_bad_points_arguments_name_the_argument():
    with pytest.raises(ValueError, match="count"):
        pathlab.points("sobol", 0)
    with pytest.raises(ValueError, match="dims"):
        pathlab.points("sobol", 4, dims=(2, 2))
    with pytest.raises(ValueError, match="nope"):
        pathlab.points("nope", 4)
    with pytest.raises(ValueError, match="pixel"):
        pathlab.points("sobol", 4, pixel=(5, 0), resolution=(4, 4))
