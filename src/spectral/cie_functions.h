// The CIE 1931 2° colour-matching functions x̄, ȳ, z̄ between their 5-nm
// samples (CIE 15:2004 tables, from cie_data.h), interpolated linearly as
// pbrt-v4 interpolates its tabulated spectra, and the quadrature every
// spectral integral of pathlab uses.
#pragma once

#include <vector>

#include "core/math.h"

namespace pathlab::spectral {

// x̄(λ), ȳ(λ), z̄(λ) at λ in nm; 0 outside [360, 830].
Vec3f cieXyzMatching(float lambdaNm);
double cieX(double lambdaNm);
double cieY(double lambdaNm);
double cieZ(double lambdaNm);

// ∫ ȳ(λ) dλ over 360–830 nm of the interpolated table (exact: the trapezoid
// rule on its knots). pbrt-v4's CIE_Y_integral, 106.856895, sums its 1-nm
// table; docs/spectral.md compares the two.
double cieYIntegral();

// Nodes and weights integrating f over [360, 830] nm as Σ w_k f(λ_k): the
// composite Simpson rule on 1-nm panels, whose knots include every table's
// (5-nm and 1-nm tables starting at whole nanometres), so the integral of a
// product of two interpolated tables — quadratic on each panel — is exact.
struct Quadrature {
    std::vector<double> lambda, weight;
};
const Quadrature& fineQuadrature();
// Simpson's 3/8 rule on 5-nm panels (283 nodes, as Jakob & Hanika's optimiser):
// exact for the tables' products (quadratic between 5-nm knots) times any
// cubic; the RGB-to-spectrum optimiser's inner loop.
const Quadrature& coarseQuadrature();

}  // namespace pathlab::spectral
