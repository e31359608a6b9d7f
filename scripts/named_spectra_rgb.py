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
  * metals (eta and k separately): the spectrum s(λ) is projected onto CIE XYZ
    under illuminant D65, X = ∫ s x̄ D65 dλ / ∫ ȳ D65 dλ (likewise Y, Z), at 1 nm
    steps over 360–830 nm, and XYZ goes to linear sRGB with the sRGB (D65)
    matrix. A constant spectrum c therefore becomes (c, c, c). Outside a table's
    wavelength range the spectrum is 0, as pbrt-v4's piecewise-linear spectra
    are.
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


def main():
    t = read_tables(sys.argv[1])
    lam = t["CIE_lambda"]
    cmf = [t["CIE_X"], t["CIE_Y"], t["CIE_Z"]]
    illum = piecewise(t["CIE_Illum_D6500"], lam)
    white = to_rgb(np.ones_like(lam), lam, cmf, illum)
    assert np.allclose(white, 1, atol=2e-3), white
    print("// metals: name, eta RGB, k RGB")
    for m in METALS:
        eta = to_rgb(piecewise(t[m + "_eta"], lam), lam, cmf, illum)
        k = to_rgb(piecewise(t[m + "_k"], lam), lam, cmf, illum)
        print('{"%s", {%.4ff, %.4ff, %.4ff}, {%.4ff, %.4ff, %.4ff}},' % ((m,) + tuple(eta) + tuple(k)))
    print("// glasses: name, n at %.2f nm" % D_LINE_NM)
    for name, table in GLASSES.items():
        x, y = interleaved(t[table])
        print('{"%s", %.5ff},' % (name, np.interp(D_LINE_NM, x, y)))


if __name__ == "__main__":
    main()
