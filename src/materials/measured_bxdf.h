// pbrt-v4's measured BRDF (Dupuy & Jakob 2018): reflection from tabulated data.
//   f(wo, wi) = R(u_i) D(wm) / (4 sigma(wo) cos(wi)),
// where wm is the half vector, D the tabulated NDF, sigma the projected microfacet area, and
// R the reflectance at u_i, the point of the visible-normal warp's sample space that maps
// to wm (found by inverting that warp). Sampling warps u by the luminance table, then by
// the visible-normal table to wm, and reflects wo about it; the pdf carries both warps'
// densities and the Jacobian from the unit square to directions.
//
// Both transport modes use f as is: the BRDF of a real (passive) material is reciprocal, so
// its adjoint f(wi, wo) is the same function; the tables reproduce it up to their
// interpolation error, and pbrt-v4 uses them unchanged in every integrator, so light tracing
// and BDPT render what pbrt-v4's do. Reflection only, so no radiance scaling either.
//
// Spectral mode: R at each of the path's wavelengths from the file's spectra (pbrt-v4), or
// for a file with RGB data only (which pbrt-v4 does not read) its RGB lifted as an unbounded
// sRGB spectrum; the sampling tables do not depend on the wavelength.
#pragma once
#include <memory>

#include "materials/bxdf.h"
#include "materials/measured_brdf.h"
#include "spectral/wavelengths.h"

namespace ps {

class MeasuredBxDF final : public BxDF {
public:
    // RGB mode: one BxDF that owns the tables.
    explicit MeasuredBxDF(std::shared_ptr<const MeasuredBRDF> brdf)
        : BxDF(false), owner_(std::move(brdf)), brdf_(owner_.get()) {}
    // Spectral mode, built per hit: brdf must outlive it (its material holds it).
    MeasuredBxDF(const MeasuredBRDF* brdf, const SampledWavelengths& lambda)
        : BxDF(false), brdf_(brdf), lambda_(lambda.lambda), spectral_(true) {}
    uint8_t flags() const override { return kReflection | kGlossy; }
    Spectrum f(Vec3 wo, Vec3 wi, TransportMode mode) const override;
    std::optional<BSDFSample> sample(Vec3 wo, float uc, Vec2 u, TransportMode mode) const override;
    float pdf(Vec3 wo, Vec3 wi, TransportMode mode) const override;
    BxDFEval evaluate(Vec3 wo, Vec3 wi, TransportMode mode) const override;

private:
    // f and pdf of wi given wo, both on the upper side (wo.z > 0).
    void fAndPdf(Vec3 wo, Vec3 wi, Spectrum* f, float* pdf) const;
    Spectrum reflectance(Vec2 ui, const float* woParams, Vec2 uWm, Vec2 uWo, float cosI) const;

    std::shared_ptr<const MeasuredBRDF> owner_;  // null in the per-hit spectral BxDFs
    const MeasuredBRDF* brdf_;
    SpectralValues lambda_{};
    bool spectral_ = false;
};

}  // namespace ps
