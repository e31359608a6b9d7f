#!/usr/bin/env python3
"""Reduces pbrt-v4's named spectra to the constants pathlab renders with in RGB.

pathlab renders in linear sRGB, so a spectral index of refraction is reduced
once, here, and the results are written to src/scene/named_spectra.cpp.

Input: a C/C++ source that holds the published tables as interleaved
(wavelength nm, value) arrays — pbrt-v4's src/pbrt/util/spectrum.cpp, whose
tables redistribute the CIE 1931 2-degree colour-matching functions and
illuminant D65 (CIE 15:2004), and measured optical constants of metals and
Schott glasses from refractiveindex.info (CC0). Only numbers computed from the
tables are written out; the tables themselves are not copied.

Method:
  * metals: what a renderer sees of a metal is its Fresnel reflectance F(θ, λ),
    not η and k, and F is far from linear in them, so reducing η and k to RGB
    separately tints the metal (gold: red −4.6%, blue +3.6% at normal
    incidence). Instead the spectral reflectance F(θ, λ) of the measured η, k
    (unpolarised conductor Fresnel) is reduced to linear sRGB at each of 32
    Gauss–Legendre nodes in cos θ, and per channel the (η, k) pair whose Fresnel
    curve fits those 32 values best is found, weighted by cos θ (the projected
    solid angle a diffuse-like illumination gives each direction; Gulbrandsen
    2014 argues the same for artist-friendly metallic Fresnel). A spectral
    reduction is X = ∫ s x̄ D65 dλ / ∫ ȳ D65 dλ (likewise Y, Z), at 1 nm
    steps over 360–830 nm, and XYZ goes to linear sRGB with the sRGB (D65)
    matrix; a constant spectrum c becomes (c, c, c). Outside a table's
    wavelength range the spectrum is 0, as pbrt-v4's piecewise-linear spectra
    are. A reflectance outside the sRGB gamut (gold's red is 1.02) cannot be
    reached by any (η, k): the fit comes as close as Fresnel allows.
    MgO and TiO2 (k < 1 everywhere: dielectrics) keep η and k projected one by
    one.
  * glasses: the index at the helium d line, 587.56 nm (the catalogue's n_d),
    by linear interpolation in the table.

Usage: scripts/named_spectra_rgb.py PATH/TO/spectrum.cpp
"""
import re
import sys

import numpy as np

METALS = ["Ag", "Al", "Au", "Cu", "CuZn", "MgO", "TiO2"]
GLASSES = {  # pbrt-v4 name -> table name
    "glass-BK7": "GlassBK7_eta",
    "glass-BAF10": "GlassBAF10_eta",
    "glass-FK51A": "GlassFK51A_eta",
    "glass-LASF9": "GlassLASF9_eta",
    "glass-F5": "GlassSF5_eta",
    "glass-F10": "GlassSF10_eta",
    "glass-F11": "GlassSF11_eta",
}
XYZ_TO_SRGB = np.array([[3.2404542, -1.5371385, -0.4985314],
                        [-0.9692660, 1.8760108, 0.0415560],
                        [0.0556434, -0.2040259, 1.0572252]])
D_LINE_NM = 587.56


def read_tables(path):
    text = open(path, encoding="utf-8").read()
    tables = {}
    for m in re.finditer(r"const Float (\w+)\[[^\]]*\]\s*=\s*\{([^}]*)\}", text):
        nums = re.findall(r"[-+]?\d*\.?\d+(?:[eE][-+]?\d+)?", m.group(2))
        tables[m.group(1)] = np.array([float(x) for x in nums])
    return tables


def interleaved(values):
    return values[0::2], values[1::2]


def piecewise(values, lam):
    x, y = interleaved(values)
    out = np.interp(lam, x, y)
    out[(lam < x[0]) | (lam > x[-1])] = 0.0
    return out


def to_rgb(spectrum, lam, cmf, illum):
    norm = np.sum(cmf[1] * illum)
    xyz = np.array([np.sum(spectrum * c * illum) for c in cmf]) / norm
    return np.maximum(XYZ_TO_SRGB @ xyz, 0.0)


def conductor_fresnel(eta, k, cos_theta):
    """Unpolarised Fresnel reflectance of a conductor of complex index η + ik."""
    n = eta + 1j * k
    sin2 = 1.0 - cos_theta * cos_theta
    cos_t = np.sqrt(1.0 - sin2 / (n * n))
    rs = (cos_theta - n * cos_t) / (cos_theta + n * cos_t)
    rp = (n * cos_theta - cos_t) / (n * cos_theta + cos_t)
    return 0.5 * (np.abs(rs) ** 2 + np.abs(rp) ** 2)


def fit_eta_k(cosines, weights, target):
    """(η, k) minimising Σ w (F(η, k, cos) − target)², by a coarse grid in
    (log η, k) refined four times around the best node. η stays at or above
    0.05 (silver, the lowest of the tables, is 0.05 in blue) and k at or above
    1, as for every metal in the visible: unbounded, an out-of-gamut target
    drives k to 0 and η towards 0, a dielectric in total reflection."""
    log_eta, k_range = (np.log(0.05), 2.0), (1.0, 12.0)
    best = None
    for _ in range(5):
        le = np.linspace(*log_eta, 61)
        kk = np.linspace(*k_range, 61)
        E, K = np.meshgrid(np.exp(le), kk, indexing="ij")
        F = conductor_fresnel(E[..., None], K[..., None], cosines)
        err = np.sum(weights * (F - target) ** 2, axis=-1)
        i, j = np.unravel_index(np.argmin(err), err.shape)
        best = (E[i, j], K[i, j])
        dle, dk = (log_eta[1] - log_eta[0]) / 10, (k_range[1] - k_range[0]) / 10
        log_eta = (le[i] - dle, le[i] + dle)
        k_range = (max(kk[j] - dk, 1.0), kk[j] + dk)
    return best


def metal_rgb(eta_spectrum, k_spectrum, lam, cmf, illum):
    nodes, gl_weights = np.polynomial.legendre.leggauss(32)
    cosines = 0.5 * (nodes + 1.0)
    weights = gl_weights * cosines
    reflectance = np.array([
        to_rgb(conductor_fresnel(np.maximum(eta_spectrum, 1e-4), k_spectrum, c), lam, cmf, illum)
        for c in cosines])  # [cos, channel]
    fits = [fit_eta_k(cosines, weights, reflectance[:, c]) for c in range(3)]
    return np.array([f[0] for f in fits]), np.array([f[1] for f in fits])


def main():
    t = read_tables(sys.argv[1])
    lam = t["CIE_lambda"]
    cmf = [t["CIE_X"], t["CIE_Y"], t["CIE_Z"]]
    illum = piecewise(t["CIE_Illum_D6500"], lam)
    white = to_rgb(np.ones_like(lam), lam, cmf, illum)
    assert np.allclose(white, 1, atol=2e-3), white
    print("// metals: name, eta RGB, k RGB")
    for m in METALS:
        eta_s, k_s = piecewise(t[m + "_eta"], lam), piecewise(t[m + "_k"], lam)
        if np.max(k_s) > 1.0:
            eta, k = metal_rgb(eta_s, k_s, lam, cmf, illum)
        else:  # MgO, TiO2: dielectrics, nothing to fit
            eta, k = to_rgb(eta_s, lam, cmf, illum), to_rgb(k_s, lam, cmf, illum)
        print('{"%s", {%.4ff, %.4ff, %.4ff}, {%.4ff, %.4ff, %.4ff}},' % ((m,) + tuple(eta) + tuple(k)))
    print("// glasses: name, n at %.2f nm" % D_LINE_NM)
    for name, table in GLASSES.items():
        x, y = interleaved(t[table])
        print('{"%s", %.5ff},' % (name, np.interp(D_LINE_NM, x, y)))


if __name__ == "__main__":
    main()
