"""pathlab.render against `pathlab render`: the same image bit for bit, the
same refusals, one load for many renders, Ctrl-C and threads."""

import _thread
import pathlib
import threading

import numpy as np
import pytest

import pathlab
from conftest import cli_error

SETTINGS = dict(sampler="sobol-owen", spp=4, seed=3, size=(40, 24), max_depth=5)


def cli_render(cli, tmp_path, scene="cornell-box", extra=()):
    out = tmp_path / "cli.exr"
    cli("render", "--scene", scene, "--sampler", "sobol-owen", "--spp", 4, "--seed", 3,
        "--size", "40x24", "--max-depth", 5, *extra, "-o", out)
    return pathlab.read_image(out)


def same_bits(a, b):
    return a.shape == b.shape and np.array_equal(a.view(np.uint32), b.view(np.uint32))


def test_render_equals_the_cli_exr_bit_for_bit(cli, tmp_path):
    image = pathlab.render("cornell-box", **SETTINGS)
    assert image.dtype == np.float32 and image.shape == (24, 40, 3)
    assert image.max() > 0
    assert same_bits(image, cli_render(cli, tmp_path))


def test_render_options_reach_the_renderer(cli, tmp_path):
    extra = ("--no-russian-roulette", "--roulette-depth", 3)
    image = pathlab.render("cornell-box", russian_roulette=False, roulette_depth=3, **SETTINGS)
    assert same_bits(image, cli_render(cli, tmp_path, extra=extra))
    assert not same_bits(image, pathlab.render("cornell-box", **SETTINGS))


def test_a_loaded_scene_renders_the_same_as_its_name():
    scene = pathlab.load_scene("cornell-box")
    assert (scene.width, scene.height) == (512, 512)
    first = pathlab.render(scene, **SETTINGS)
    assert same_bits(first, pathlab.render(scene, **SETTINGS))
    assert same_bits(first, pathlab.render("cornell-box", **SETTINGS))
    other_seed = dict(SETTINGS, seed=4)
    assert not same_bits(first, pathlab.render(scene, **other_seed))


@pytest.mark.parametrize("keyword,value,flag,text", [
    ("spp", 0, "--spp", "0"),
    ("spp", 10 ** 20, "--spp", "99999999999999999999"),
    ("max_depth", 2000, "--max-depth", "2000"),
    ("size", (0, 5), "--size", "0x5"),
    ("seed", -1, "--seed", "-1"),
    ("sampler", "no-such-sampler", "--sampler", "no-such-sampler"),
])
def test_bad_arguments_raise_the_cli_message_naming_the_argument(cli, tmp_path, keyword, value,
                                                                 flag, text):
    settings = dict(SETTINGS, **{keyword: value})
    with pytest.raises(ValueError) as error:
        pathlab.render("cornell-box", **settings)
    result = cli("render", "--scene", "cornell-box", flag, text, "-o", tmp_path / "x.exr",
                 check=False)
    expected = cli_error(result)
    # The CLI names its flag, Python its keyword; the message is the same.
    if flag != "--sampler":
        assert expected.startswith(flag)
        expected = keyword + expected[len(flag):]
    assert str(error.value) == expected


def test_a_missing_scene_file_raises_the_cli_message(cli, tmp_path):
    missing = str(tmp_path / "missing.json")
    with pytest.raises(ValueError) as error:
        pathlab.load_scene(missing)
    result = cli("render", "--scene", missing, "-o", tmp_path / "x.exr", check=False)
    assert str(error.value) == cli_error(result)


def test_progress_reports_tiles_and_its_exception_stops_the_render():
    calls = []
    pathlab.render("cornell-box", progress=lambda done, total: calls.append((done, total)),
                   **SETTINGS)
    assert calls and calls[-1] == (6, 6)  # 40×24 in 16×16 tiles

    def refuse(done, total):
        raise RuntimeError("stop here")

    with pytest.raises(RuntimeError, match="stop here"):
        pathlab.render("cornell-box", progress=refuse, **SETTINGS)


def test_ctrl_c_interrupts_a_render_before_it_ends():
    scene = pathlab.load_scene("cornell-box")
    calls = []
    timer = threading.Timer(0.3, _thread.interrupt_main)
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            # 1024 tiles of a fraction of a second, a minute or more in all:
            # only an interrupted render returns before its last tile.
            pathlab.render(scene, sampler="independent", spp=512,
                           progress=lambda done, total: calls.append((done, total)),
                           progress_interval=0.02)
    finally:
        timer.cancel()
    assert calls, "the progress callback never ran"
    # Never the report of a finished render (32×32 tiles); under load the
    # interrupt may even come before the first tile (total still 0).
    assert all(done < 1024 for done, _ in calls)


def test_two_python_threads_render_at_once_deterministically():
    scene = pathlab.load_scene("cornell-box")
    expected = pathlab.render(scene, **SETTINGS)
    results = {}

    def work(name, threads):
        results[name] = [pathlab.render(scene, threads=threads, **SETTINGS) for _ in range(3)]

    workers = [threading.Thread(target=work, args=(n, t)) for n, t in (("a", 1), ("b", 3))]
    for w in workers:
        w.start()
    for w in workers:
        w.join()
    for images in results.values():
        assert len(images) == 3
        assert all(same_bits(expected, image) for image in images)


@pytest.mark.parametrize("sampler", ["sobol-owen", "pmj02"])  # continued, re-rendered
def test_render_progressive_yields_the_render_at_each_count(sampler):
    scene = pathlab.load_scene("cornell-box")
    settings = dict(SETTINGS, sampler=sampler)
    del settings["spp"]
    steps = pathlab.render_progressive(scene, spp=5, step=2, **settings)
    assert len(steps) == 3
    seen = []
    for spp, image in steps:
        seen.append(spp)
        assert same_bits(image, pathlab.render(scene, spp=spp, **settings))
    assert seen == [2, 4, 5]


def test_render_progressive_continues_each_step_from_the_last():
    """A progressive sampler's step renders only its new samples (its paths),
    yet equals the render of the step's spp, variance included; a sampler that
    is not progressive renders each step whole."""
    settings = dict(SETTINGS)
    del settings["spp"]
    pixels = 40 * 24
    previous = 0
    for spp, (image, stats) in pathlab.render_progressive("cornell-box", 7, 3, return_stats=True,
                                                          **settings):
        assert stats["continued"] and stats["spp"] == spp
        assert stats["paths"] == pixels * (spp - previous)
        whole, whole_stats = pathlab.render("cornell-box", spp=spp, return_stats=True, **settings)
        assert same_bits(image, whole)
        assert same_bits(stats["variance"], whole_stats["variance"])
        previous = spp
    assert previous == 7
    steps = pathlab.render_progressive("cornell-box", 4, 2, return_stats=True,
                                       **dict(settings, sampler="pmj02"))
    for spp, (_, stats) in steps:
        assert not stats["continued"] and stats["paths"] == pixels * spp


def test_render_progressive_iterates_again_from_the_start():
    settings = dict(SETTINGS)
    del settings["spp"]
    steps = pathlab.render_progressive("cornell-box", 4, 2, **settings)
    first, second = list(steps), list(steps)
    assert [n for n, _ in first] == [n for n, _ in second] == [2, 4]
    assert all(same_bits(a, b) for (_, a), (_, b) in zip(first, second))


def test_render_progressive_refuses_bad_settings_before_the_first_step():
    with pytest.raises(ValueError, match="max_depth must be between 0 and 1024, got 5000"):
        pathlab.render_progressive("cornell-box", 4, 2, max_depth=5000)
    with pytest.raises(ValueError, match="unknown sampler 'nope'"):
        pathlab.render_progressive("cornell-box", 4, 2, sampler="nope")
    with pytest.raises(TypeError, match="unexpected keyword argument 'colour'"):
        pathlab.render_progressive("cornell-box", 4, 2, colour=1)


def test_return_stats_counts_the_paths():
    image, stats = pathlab.render("cornell-box", return_stats=True, **SETTINGS)
    assert stats["paths"] == 40 * 24 * 4
    assert stats["sampler"] == "sobol-owen" and stats["seed"] == 3
    assert stats["variance"].shape == image.shape


def test_a_pbrt_files_sampler_and_depth_apply_where_the_call_is_silent(cli, tmp_path):
    source = pathlib.Path(__file__).resolve().parents[2] / "scenes" / "pbrt" / "instances.pbrt"
    scene = pathlab.load_scene(source)
    assert scene.defaults["sampler"] == "zsobol" and scene.defaults["max_depth"] == 5
    out = tmp_path / "cli.exr"
    cli("render", "--scene", source, "--size", "24x16", "--spp", 2, "-o", out)
    assert same_bits(pathlab.render(scene, size=(24, 16), spp=2), pathlab.read_image(out))


MANY_LIGHTS = str(pathlib.Path(__file__).resolve().parents[2] / "scenes/pbrt/many-lights.pbrt")


def test_light_sampler_and_spectral_equal_the_cli(cli, tmp_path, monkeypatch):
    # The user's cache, as the C++ tests use it: spectral mode's RGB-to-spectrum
    # table (15 s of CPU to make, validated on every read) is made once, not
    # once per test. Nothing else is cached by a render.
    monkeypatch.delenv("PATHLAB_CACHE")
    # 200 lights of unequal power: each strategy makes its own image.
    images = {}
    for light_sampler in ("uniform", "power", "bvh"):
        images[light_sampler] = pathlab.render(MANY_LIGHTS, light_sampler=light_sampler,
                                               **SETTINGS)
        cli_image = cli_render(cli, tmp_path, MANY_LIGHTS, ("--light-sampler", light_sampler))
        assert same_bits(images[light_sampler], cli_image), light_sampler
    assert not same_bits(images["uniform"], images["power"])
    assert not same_bits(images["power"], images["bvh"])
    # A loaded scene of another choice is loaded again, as it was.
    scene = pathlab.load_scene(MANY_LIGHTS, light_sampler="uniform")
    assert scene.light_sampler == "uniform"
    assert same_bits(pathlab.render(scene, **SETTINGS), images["uniform"])
    assert same_bits(pathlab.render(scene, light_sampler="bvh", **SETTINGS), images["bvh"])
    # Spectral, as --spectral; progressive steps are the renders of their spp.
    spectral = pathlab.render(MANY_LIGHTS, light_sampler="bvh", spectral=True, **SETTINGS)
    cli_image = cli_render(cli, tmp_path, MANY_LIGHTS, ("--light-sampler", "bvh", "--spectral"))
    assert same_bits(spectral, cli_image)
    assert not same_bits(spectral, images["bvh"])
    steps = dict(SETTINGS)
    del steps["spp"]
    last = list(pathlab.render_progressive(MANY_LIGHTS, 4, 2, light_sampler="bvh",
                                           spectral=True, **steps))[-1]
    assert last[0] == 4 and same_bits(last[1], spectral)


@pytest.mark.parametrize("keywords,text", [
    (dict(light_sampler="nearest"), "light_sampler must be one of uniform, power, bvh, got 'nearest'"),
    (dict(light_sampler=3), "light_sampler must be uniform, power or bvh, got 3"),
    (dict(spectral="yes"), "spectral must be True or False, got 'yes'"),
])
def test_bad_light_sampler_or_spectral_raise_naming_them(keywords, text):
    with pytest.raises(ValueError) as error:
        pathlab.render("cornell-box", **dict(SETTINGS, **keywords))
    assert str(error.value) == text
