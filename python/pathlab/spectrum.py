"""The error's power spectrum: how a render's noise is distributed over
spatial frequencies (blue-noise error, Georgiev & Fajardo 2016; Heitz &
Belcour 2019, "Distributing Monte Carlo errors as a blue noise in screen
space", whose figures are this radially averaged spectrum)."""

import numpy as np


def error_spectrum(reference, test):
    """The radially averaged power spectrum of test − reference.

    The error is averaged over the three channels, its mean removed, and its
    periodogram |DFT|² / (width·height) averaged over rings of one frequency
    step. Returns (frequency, power): frequency in cycles per pixel from 0 to
    0.5, power such that white noise of variance σ² is flat at σ² (the
    integral of the periodogram is the error's variance, Parseval).
    Low power at low frequency means a blue-noise error.
    """
    ref = np.asarray(reference, dtype=np.float64)
    tst = np.asarray(test, dtype=np.float64)
    if ref.ndim != 3 or ref.shape[2] != 3:
        raise ValueError("reference must be an H×W×3 array of linear RGB")
    if tst.shape != ref.shape:
        raise ValueError("test must have the reference's shape %s, got %s"
                         % (ref.shape, tst.shape))
    error = (tst - ref).mean(axis=2)
    error -= error.mean()
    h, w = error.shape
    power = np.abs(np.fft.fft2(error)) ** 2 / error.size
    fy = np.fft.fftfreq(h)[:, None]
    fx = np.fft.fftfreq(w)[None, :]
    # Rings one step of the coarser axis wide: radius in units of 1/min(w, h).
    n = min(w, h)
    ring = np.rint(np.sqrt(fx ** 2 + fy ** 2) * n).astype(int)
    rings = n // 2 + 1
    inside = ring < rings
    total = np.bincount(ring[inside], weights=power[inside], minlength=rings)
    count = np.bincount(ring[inside], minlength=rings)
    with np.errstate(invalid="ignore"):
        mean = np.where(count > 0, total / np.maximum(count, 1), np.nan)
    return np.arange(rings) / n, mean
