"""The metrics against `pathlab compare --json`, and image files."""

import json

import numpy as np
import pytest

import pathlab

SETTINGS = dict(size=(48, 32), max_depth=4)


@pytest.fixture(scope="module")
def pair(tmp_path_factory):
    d = tmp_path_factory.mktemp("pair")
    ref = pathlab.render("cornell-box", sampler="sobol-owen", spp=64, **SETTINGS)
    test = pathlab.render("cornell-box", sampler="independent", spp=2, seed=5, **SETTINGS)
    pathlab.write_image(d / "ref.exr", ref)
    pathlab.write_image(d / "test.exr", test)
    return d, ref, test


def test_every_metric_equals_compare_json(cli, pair):
    d, ref, test = pair
    expected = json.loads(cli("compare", d / "ref.exr", d / "test.exr", "--json").stdout)
    assert pathlab.mse(ref, test) == expected["mse"]
    assert pathlab.rmse(ref, test) == expected["rmse"]
    assert pathlab.relmse(ref, test) == expected["relmse"]
    assert pathlab.RELMSE_EPSILON == expected["relmse_epsilon"]
    assert pathlab.psnr(ref, test) == expected["psnr"]
    assert pathlab.flip_stats(ref, test) == expected["flip"]
    assert pathlab.flip(ref, test) == expected["flip"]["mean"]


def test_ldr_flip_and_ppd_equal_compare(cli, pair):
    d, ref, test = pair
    expected = json.loads(cli("compare", d / "ref.exr", d / "test.exr", "--json", "--ldr",
                              "--ppd", 30, "--metric", "flip").stdout)
    assert pathlab.flip_stats(ref, test, mode="ldr", ppd=30) == expected["flip"]


def test_flip_map_matches_the_exr_error_map(cli, pair):
    d, ref, test = pair
    cli("compare", d / "ref.exr", d / "test.exr", "--metric", "flip", "--error-map",
        d / "map.exr")
    written = pathlab.read_image(d / "map.exr")
    flip_map = pathlab.flip_map(ref, test)
    assert flip_map.shape == (32, 48)
    assert np.array_equal(flip_map, written[:, :, 0])
    assert flip_map.mean() == pytest.approx(pathlab.flip(ref, test), rel=1e-5)


def test_identical_images_have_no_error(pair):
    _, ref, _ = pair
    assert pathlab.mse(ref, ref) == 0
    assert pathlab.psnr(ref, ref) == float("inf")


def test_metric_arguments_are_checked(pair):
    _, ref, test = pair
    with pytest.raises(ValueError, match="same size|size"):
        pathlab.mse(ref, test[:, :10])
    with pytest.raises(ValueError, match="reference"):
        pathlab.mse(ref[:, :, 0], test)
    with pytest.raises(ValueError, match="mode"):
        pathlab.flip(ref, test, mode="bright")
    with pytest.raises(ValueError, match="ppd"):
        pathlab.flip(ref, test, ppd=0)


@pytest.mark.parametrize("ext", ["exr", "pfm"])
def test_linear_files_keep_every_bit(tmp_path, pair, ext):
    _, _, test = pair
    path = tmp_path / ("image." + ext)
    pathlab.write_image(path, test)
    assert np.array_equal(pathlab.read_image(path), test)


def test_png_is_srgb_encoded(tmp_path):
    grey = np.full((2, 3, 3), 0.5, dtype=np.float32)
    pathlab.write_image(tmp_path / "g.png", grey)
    back = pathlab.read_image(tmp_path / "g.png")
    assert back.shape == (2, 3, 3)
    assert np.allclose(back, 0.5, atol=0.005)
    with pytest.raises(ValueError, match="missing"):
        pathlab.read_image(tmp_path / "missing.exr")


def test_error_spectrum_finds_a_sinusoid_and_white_noise_is_flat():
    h, w = 64, 64
    x = np.arange(w)[None, :, None]
    wave = np.broadcast_to(np.cos(2 * np.pi * 8 * x / w), (h, w, 3)).astype(np.float32)
    zero = np.zeros((h, w, 3), np.float32)
    freq, power = pathlab.error_spectrum(zero, wave)
    assert freq[8] == 8 / 64 and np.nanargmax(power) == 8
    noise = np.random.default_rng(1).normal(0, 0.5, (h, w, 1)).repeat(3, axis=2)
    _, flat = pathlab.error_spectrum(zero, noise)
    assert np.nanmean(flat[4:]) == pytest.approx(0.25, rel=0.1)
    with pytest.raises(ValueError, match="shape"):
        pathlab.error_spectrum(zero, zero[:10])


def test_error_spectrum_equals_the_cli_csv_and_json(cli, pair):
    d, ref, test = pair
    out = json.loads(cli("compare", d / "ref.exr", d / "test.exr", "--json",
                         "--error-spectrum", d / "spectrum.csv").stdout)
    rows = (d / "spectrum.csv").read_text().splitlines()
    assert rows[0] == "frequency,power"
    written = np.array([[float(v) for v in row.split(",")] for row in rows[1:]])
    freq, power = pathlab.error_spectrum(ref, test)
    assert np.array_equal(freq, written[:, 0]) and np.array_equal(power, written[:, 1])
    assert len(freq) == 32 // 2 + 1
    assert pathlab.low_frequency_fraction(ref, test) == out["low_frequency_fraction"]
    assert pathlab.low_frequency_fraction(ref, ref) is None
