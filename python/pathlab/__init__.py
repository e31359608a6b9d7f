"""pathlab from Python: render, draw sampler points, compute image metrics and
run or read studies, with numpy arrays in and out.

Rendering: load_scene, render, render_progressive. Samplers: samplers, points.
Metrics: mse, rmse, relmse, psnr, flip, flip_stats, flip_map, error_spectrum,
low_frequency_fraction.
Files: read_image, write_image. Studies: run_study, Study.

The functions call the same C++ library as the ``pathlab`` command line, so a
render equals ``pathlab render``'s EXR bit for bit and every metric equals
``pathlab compare --json`` to the last bit. Images are float32 arrays of shape
(height, width, 3) holding linear RGB, top row first. Bad input raises
``ValueError`` with the message the command line prints (naming the Python
argument). See docs/python.md.

    import pathlab
    ref = pathlab.render("cornell-box", sampler="sobol-owen", spp=1024, size=(128, 128))
    img = pathlab.render("cornell-box", sampler="independent", spp=16, size=(128, 128))
    print(pathlab.mse(ref, img), pathlab.flip(ref, img))
"""

import os as _os

from . import _pathlab
from ._pathlab import Scene
from .spectrum import LOW_FREQUENCY_LIMIT, error_spectrum, low_frequency_fraction
from .study import Study, run_study

__all__ = [
    "Scene", "load_scene", "builtin_scenes", "render", "render_progressive", "samplers",
    "points", "mse", "rmse", "relmse", "psnr", "flip", "flip_stats", "flip_map", "error_spectrum",
    "low_frequency_fraction", "LOW_FREQUENCY_LIMIT", "read_image", "write_image", "Study",
    "run_study", "RELMSE_EPSILON",
]

RELMSE_EPSILON = _pathlab.RELMSE_EPSILON


def load_scene(source, lenient=False, solid_angle_lights=False, light_sampler=None):
    """Load a scene once, to render it any number of times (from any thread).

    source: a built-in name ("cornell-box", "wolf") or a scene file: .json
        (pathlab's format), .obj (a bare model), .pbrt (pbrt-v4).
    lenient: pbrt-v4 files: substitute unsupported features with a warning
        instead of refusing the file (``pathlab render --lenient``).
    solid_angle_lights: sample rectangular lights by solid angle instead of by
        area (``--solid-angle-lights``).
    light_sampler: how next-event estimation picks a light, "uniform",
        "power" or "bvh" (``--light-sampler``); None keeps the file's choice
        (else power). It is built into the loaded scene (its light tree).

    Returns a pathlab.Scene (attributes: source, width, height, lenient,
    solid_angle_lights, light_sampler, defaults — the file's own sampler, spp,
    seed and max depth, None where it has none).
    Raises ValueError for an unknown name, a bad file or light sampler.
    """
    if light_sampler is not None and not isinstance(light_sampler, str):
        raise ValueError("light_sampler must be uniform, power or bvh, got %r" % (light_sampler,))
    return _pathlab.load_scene(_os.fspath(source), lenient, solid_angle_lights,
                               light_sampler or "")


def builtin_scenes():
    """The names load_scene and render accept without a file."""
    return _pathlab.builtin_scenes()


def _scene(scene, lenient, light_sampler):
    if isinstance(scene, Scene):
        if light_sampler is None or light_sampler == scene.light_sampler:
            return scene
        # The light sampler is part of the loaded scene: load it again, as it was.
        return load_scene(scene.source, lenient=scene.lenient,
                          solid_angle_lights=scene.solid_angle_lights, light_sampler=light_sampler)
    if isinstance(scene, (str, _os.PathLike)):
        return load_scene(scene, lenient=lenient, light_sampler=light_sampler)
    raise ValueError("scene must be a scene name, a file path or a pathlab.Scene, got %r"
                     % type(scene).__name__)


def _text(value, name):
    """A seed or size as the command line reads it (text), None as given."""
    if value is None:
        return None
    if name == "size":
        if isinstance(value, str):
            return value
        try:
            width, height = value
        except (TypeError, ValueError):
            raise ValueError("size must be (width, height) or 'WIDTHxHEIGHT', got %r" % (value,))
        return "%sx%s" % (width, height)
    if isinstance(value, bool):
        raise ValueError("seed must be an integer, got %r" % (value,))
    return str(value)


_INT64_MIN, _INT64_MAX = -(2 ** 63), 2 ** 63 - 1


def _int_or_none(value, name):
    """An integer keyword, saturated to 64 bits as the command line reads
    "99999999999999999999" (then refused by range, naming the value)."""
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, int):
        try:
            import numpy
            if isinstance(value, numpy.integer):
                return _int_or_none(int(value), name)
        except ImportError:
            pass
        raise ValueError("%s must be an integer, got %r" % (name, value))
    return min(max(value, _INT64_MIN), _INT64_MAX)


def _render_arguments(scene, sampler, spp, seed, size, max_depth, threads, russian_roulette,
                      roulette_depth, lenient, progress, progress_interval, light_sampler,
                      spectral):
    """render()'s keywords checked and converted: the scene and settings
    arguments of _pathlab.render, then the progress callback and interval."""
    threads = _int_or_none(threads, "threads")
    roulette_depth = _int_or_none(roulette_depth, "roulette_depth")
    interval = float(progress_interval)
    if not interval > 0:
        raise ValueError("progress_interval must be a positive number of seconds, got %r"
                         % (progress_interval,))
    if progress is not None and not callable(progress):
        raise ValueError("progress must be callable, got %r" % (progress,))
    if sampler is not None and not isinstance(sampler, str):
        raise ValueError("sampler must be a sampler name (see pathlab.samplers()), got %r"
                         % (sampler,))
    if not isinstance(spectral, bool):
        raise ValueError("spectral must be True or False, got %r" % (spectral,))
    settings = (_scene(scene, lenient, light_sampler), sampler, _int_or_none(spp, "spp"),
                _text(seed, "seed"), _text(size, "size"), _int_or_none(max_depth, "max_depth"),
                bool(russian_roulette), 2 if roulette_depth is None else roulette_depth,
                threads or 0, spectral)
    return settings, progress, interval


def render(scene, sampler=None, spp=None, seed=None, size=None, max_depth=None, threads=None,
           russian_roulette=True, roulette_depth=None, lenient=False, progress=None,
           progress_interval=0.1, return_stats=False, light_sampler=None, spectral=False):
    """Render one image; returns a float32 array (height, width, 3), linear RGB.

    scene: a pathlab.Scene from load_scene (reused: no reload), a built-in
        name, or a scene file path (.json, .obj, .pbrt; loaded for this call).
    sampler, spp, seed, max_depth: as ``pathlab render``'s --sampler, --spp,
        --seed, --max-depth. None takes the scene file's choice, else the
        command line's default (independent, 16, 0, 8). pathlab.samplers()
        lists the sampler names.
    size: (width, height) or "WIDTHxHEIGHT"; None renders at the scene's size.
    threads: worker threads; None or 0 uses every core. The image is the same
        bit for bit at any thread count.
    russian_roulette, roulette_depth: --no-russian-roulette and
        --roulette-depth (default 2 bounces before roulette may end a path).
    light_sampler: "uniform", "power" or "bvh", as --light-sampler; None
        keeps the scene's (a loaded Scene of another choice is loaded again:
        load_scene(..., light_sampler=...) once for repeated renders).
    spectral: four sampled wavelengths per path instead of RGB, as
        --spectral (docs/spectral.md); the image is linear sRGB either way.
    progress: called as progress(done_tiles, total_tiles) every
        progress_interval seconds from the calling thread; an exception it
        raises stops the render and propagates.

    The GIL is released while rendering. Ctrl-C stops the render within a
    tile and raises KeyboardInterrupt. With return_stats=True the result is
    (image, stats) where stats holds seconds, paths, rays, shadow_rays,
    non_finite, the settings used and "variance" (the per-pixel variance of
    the mean, an array like the image).
    """
    settings, progress, interval = _render_arguments(
        scene, sampler, spp, seed, size, max_depth, threads, russian_roulette, roulette_depth,
        lenient, progress, progress_interval, light_sampler, spectral)
    return _pathlab.render(*settings, progress, interval, bool(return_stats))


def render_progressive(scene, spp, step, **options):
    """Yield (spp_so_far, image) for step, 2·step, … up to spp (the last may
    be spp itself): each image is the render at that sample count, bit for
    bit what render(scene, spp=n, ...) returns.

    Each step continues the previous one: for a progressive sampler
    (samplers()[i]["progressive"]) only the new samples are rendered, so all
    steps together cost about one render of spp (plus a little per step;
    steps of at least 8 spp keep the renderer's ray packets full). Other
    samplers render each step from the first sample again (about
    spp²/(2·step) samples per pixel in all): use few steps with them.
    Wrap it in tqdm for a bar:
    ``for n, img in tqdm(pathlab.render_progressive(s, 256, 32)): ...``.
    The scene is loaded once. options are render()'s keywords; with
    return_stats=True each image is (image, stats), stats of that step alone
    (its seconds and paths) plus "continued" (did it continue the last step?).
    """
    spp = _int_or_none(spp, "spp")
    step = _int_or_none(step, "step")
    if spp is None or spp < 1:
        raise ValueError("spp must be at least 1, got %r" % (spp,))
    if step is None or step < 1:
        raise ValueError("step must be at least 1, got %r" % (step,))
    return_stats = bool(options.pop("return_stats", False))
    options["spp"] = spp
    settings, progress, interval = _render_arguments(
        scene, **{k: options.pop(k, v) for k, v in _RENDER_DEFAULTS.items()})
    if options:
        raise TypeError("render_progressive() got an unexpected keyword argument %r"
                        % sorted(options)[0])
    _pathlab.Progressive(*settings)  # checks the settings now, not at the first step
    counts = list(range(step, spp, step)) + [spp]
    return _Progressive(settings, counts, (progress, interval, return_stats))


# render()'s keywords after scene, and their defaults.
_RENDER_DEFAULTS = dict(sampler=None, spp=None, seed=None, size=None, max_depth=None,
                        threads=None, russian_roulette=True, roulette_depth=None, lenient=False,
                        progress=None, progress_interval=0.1, light_sampler=None, spectral=False)


class _Progressive:
    """The iterator of render_progressive; len() is the number of images.
    Each iteration starts a new accumulation."""

    def __init__(self, settings, counts, call):
        self._settings, self._counts, self._call = settings, counts, call

    def __len__(self):
        return len(self._counts)

    def __iter__(self):
        accumulation = _pathlab.Progressive(*self._settings)
        for n in self._counts:
            yield n, accumulation.advance(n, *self._call)


def samplers():
    """Every sampler as a dict: name, description, dimensions (native count,
    None when unbounded), randomized (does the seed change it?), progressive
    (are its first N samples the N-spp render?). As ``pathlab samplers``."""
    return _pathlab.samplers()


def points(sampler, count, dims=(0, 1), pixel=(0, 0), seed=0, spp=None, resolution=None):
    """The samples 0..count-1 a pixel receives, as a float32 array (count, D).

    dims: the sampler dimensions, in the renderer's layout (0, 1 = the pixel
        position; docs/rendering.md). Two dimensions give exactly
        ``pathlab points --dims I,J``; dims=range(D) gives every dimension of
        a path up to D, each drawn as the renderer draws it.
    pixel: (x, y); resolution: (width, height) of the image the sampler is
        built for (default: the smallest holding the pixel); spp: the
        sampler's samples per pixel (default: count).

    points("sobol", 4) is (0, 0), (.5, .5), (.75, .25), (.25, .75).
    """
    dims = [_int_or_none(d, "dims") for d in dims]
    res = None if resolution is None else tuple(resolution)
    return _pathlab.points(sampler, _int_or_none(count, "count"), dims, tuple(pixel),
                           _text(seed, "seed"), _int_or_none(spp, "spp"), res)


def mse(reference, test):
    """Mean of (test − reference)² over pixels and channels (as pathlab compare)."""
    return _pathlab.mse(reference, test)


def rmse(reference, test):
    """Square root of mse (as pathlab compare)."""
    return _pathlab.rmse(reference, test)


def relmse(reference, test, epsilon=RELMSE_EPSILON):
    """Mean of (test − reference)² / (reference² + epsilon), epsilon 0.01 as
    pathlab compare uses."""
    return _pathlab.relmse(reference, test, epsilon)


def psnr(reference, test, peak=1.0):
    """10·log10(peak² / mse) in dB; inf for identical images."""
    return _pathlab.psnr(reference, test, peak)


def flip_stats(reference, test, mode="hdr", ppd=None):
    """FLIP (Andersson et al. 2020; HDR-FLIP 2021) of test against reference:
    the dict of ``pathlab compare --json``'s "flip" (mean, weighted_median,
    q1, q3, min, max, ppd, mode, exposures).

    mode: "hdr" (linear, unbounded; compare's choice for EXR/PFM files) or
        "ldr" (inputs clamped to [0, 1]; its choice for two PNGs).
    ppd: pixels per degree, 1 to 1000 (default 67.02).
    """
    return _pathlab.flip(reference, test, mode, ppd)


def flip(reference, test, mode="hdr", ppd=None):
    """The mean FLIP error (flip_stats(...)["mean"])."""
    return flip_stats(reference, test, mode, ppd)["mean"]


def flip_map(reference, test, mode="hdr", ppd=None):
    """FLIP's per-pixel error, a float32 array (height, width) in [0, 1]."""
    return _pathlab.flip_map(reference, test, mode, ppd)


def read_image(path):
    """Read an EXR, PNG (sRGB decoded to linear) or PFM file as a float32
    array (height, width, 3)."""
    return _pathlab.read_image(_os.fspath(path))


def write_image(path, image, exposure=0.0):
    """Write image (height, width, 3) as EXR, PNG (sRGB, clamped after
    scaling by 2**exposure) or PFM, by the extension; atomically."""
    _pathlab.write_image(_os.fspath(path), image, float(exposure))
