// pbrt-v4's stochastic layered BSDF (its LayeredBxDF, after Guo, Hašan,
// Yan & Zhao 2018, "Position-Free Monte Carlo Simulation for Arbitrary
// Layered BSDFs"): a dielectric coating over an opaque base (Lambertian for
// coateddiffuse, a conductor for coatedconductor), with between them a slab of
// the given thickness of a homogeneous medium (σt = 1, single-scattering
// albedo `albedo`, Henyey–Greenstein phase function of asymmetry g; with a
// black albedo, a pure absorber). Two-sided, as pbrt-v4's coated materials.
//
// f, pdf and sample are Monte Carlo estimates from a random walk between the
// layers of at most maxDepth events, averaged over nSamples walks for f and
// pdf; their random numbers come from a WalkNumbers stream (walk_numbers.h).
// f is an unbiased estimate of the layered BSDF; sample's weight f·|cosθ|/pdf
// is an unbiased estimate of the BSDF over the density of the walk's exit
// direction, which has no closed form: pdf is pbrt-v4's approximation of it
// for multiple importance sampling (one- and three-segment terms, mixed
// 9:1 with the uniform sphere density), and the sample's pdf is only
// proportional to the walk's density (BsdfSample::pdfIsProportional).
#pragma once

#include "render/bsdf.h"
#include "render/layered/dielectric_interface.h"
#include "render/layered/walk_numbers.h"

namespace pathlab {

// A sample of the layered BSDF in the colour a path carries: the direction,
// pdf and flags of `sample` (whose f is not set), and f in that colour.
template <class Colour>
struct LayeredSampleOf {
    BsdfSample sample;
    Colour f;
};

struct LayerParameters {
    float thickness = 0.01f;
    Vec3f albedo{0.0f};  // of the medium between the layers; black: no scattering
    float g = 0;         // Henyey–Greenstein asymmetry
    int maxDepth = 10;
    int nSamples = 1;
};

class LayeredBsdf {
  public:
    // base must be opaque and reflective: diffuse or conductor.
    LayeredBsdf(DielectricInterface coating, Bsdf base, LayerParameters params);

    // No lobe that is not a delta: next-event estimation cannot help.
    bool isSpecular() const;
    Vec3f f(Vec3f wo, Vec3f wi, WalkNumbers& r) const;
    float pdf(Vec3f wo, Vec3f wi, WalkNumbers& r) const;
    // uc and u drive the sampling of the coating where the walk enters it
    // (the vertex's lobe and direction dimensions); the walk draws the rest.
    std::optional<BsdfSample> sample(Vec3f wo, float uc, Vec2f u, WalkNumbers& r) const;

    // f and sample in another colour than RGB (layered_walk.h): `colours`
    // gives the medium's albedo and the base's values in that colour, and
    // turns the coating's colourless values into it. The walk — its
    // directions, its densities and the numbers it draws from r — is the
    // same as in RGB, which is their instance with RgbLayerColours.
    template <class Colours>
    typename Colours::Colour fIn(Vec3f wo, Vec3f wi, WalkNumbers& r, const Colours& colours) const;
    template <class Colours>
    std::optional<LayeredSampleOf<typename Colours::Colour>> sampleIn(Vec3f wo, float uc, Vec2f u,
                                                                      WalkNumbers& r,
                                                                      const Colours& colours) const;

    const DielectricInterface& coating() const { return top_; }
    const Bsdf& base() const { return bottom_; }
    const LayerParameters& parameters() const { return params_; }

  private:
    float transmittance(float dz, Vec3f w) const;
    float connectionPdf(Vec3f wi, Vec3f w) const;
    template <class Colours>
    typename Colours::Colour walkF(Vec3f wi, const BsdfSample& wos, const BsdfSample& wis,
                                   WalkNumbers& r, const Colours& colours) const;
    float pdfThreeSegments(Vec3f wo, Vec3f wi, WalkNumbers& r) const;

    DielectricInterface top_;
    Bsdf bottom_;
    LayerParameters params_;
};

// Henyey–Greenstein phase function (Henyey & Greenstein 1941) in pbrt-v4's
// convention: both directions point away from the scattering point, so
// forward scattering (g > 0) favours wi ≈ −wo.
float henyeyGreenstein(Vec3f wo, Vec3f wi, float g);
// A direction distributed as henyeyGreenstein(wo, ·, g); its density is the
// phase function itself.
Vec3f sampleHenyeyGreenstein(Vec3f wo, float g, Vec2f u);

}  // namespace pathlab
