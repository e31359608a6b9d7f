"""The error's power spectrum: how a render's noise is distributed over
spatial frequencies (blue-noise error, Georgiev & Fajardo 2016; Heitz &
Belcour 2019, "Distributing Monte Carlo errors as a blue noise in screen
space", whose figures are this radially averaged spectrum)."""

import numpy as np

from . import _pathlab

LOW_FREQUENCY_LIMIT = _pathlab.LOW_FREQUENCY_LIMIT


def _check_shapes(reference, test):
    ref, tst = np.shape(reference), np.shape(test)
    if len(ref) != 3 or ref[2] != 3:
        raise ValueError("reference must be an H×W×3 array of linear RGB")
    if tst != ref:
        raise ValueError("test must have the reference's shape %s, got %s" % (ref, tst))


def error_spectrum(reference, test):
    """The radially averaged power spectrum of test − reference, the numbers
    ``pathlab compare --error-spectrum OUT.csv`` writes, bit for bit.

    The error is averaged over the three channels and its periodogram
    |DFT|² / (width·height) averaged over rings one frequency step of the
    shorter side wide. Returns (frequency, power), float64 arrays: frequency in
    cycles per pixel from 0 to 0.5; power such that white noise of variance σ²
    is flat at σ². power[0] is the DC term alone, width·height·(mean error)²;
    the other rings hold no DC. Low power at low frequency means a blue-noise
    error. Arrays are converted to float32 first, as images are stored.
    """
    _check_shapes(reference, test)
    return _pathlab.error_spectrum(reference, test)


def low_frequency_fraction(reference, test):
    """The share of the error's power below LOW_FREQUENCY_LIMIT (0.125 cycles
    per pixel, a quarter of Nyquist), DC excluded: π/64 ≈ 0.049 for white
    noise, less for blue noise. None when the error is constant. Equals
    ``pathlab compare --json``'s "low_frequency_fraction"."""
    _check_shapes(reference, test)
    return _pathlab.low_frequency_fraction(reference, test)
