// pbrt-v4's `subsurface` material as a random walk: a dielectric boundary (eta, roughness)
// around a homogeneous medium of sigma_a, sigma_s and Henyey-Greenstein g. The scene
// builder gives every shape with this material that medium as its inside (the outside stays
// the current medium), so the integrators' own medium transport walks light through it:
// no BSSRDF, and nothing new in any integrator. pbrt-v4 instead renders a photon-beam-
// diffusion BSSRDF of the same coefficients (bssrdf.h); the walk is the exact transport that
// the BSSRDF approximates, so the two images differ by the approximation (docs/scene-format.md).
#pragma once
#include "materials/materials.h"
#include "media/medium.h"

namespace ps {

struct SubsurfaceInterior {
    MediumSpectrum sigmaA, sigmaS;  // scale included
    float g = 0;
};

class SubsurfaceMaterial final : public Material {
public:
    SubsurfaceMaterial(float eta, Roughness r, SubsurfaceInterior interior)
        : boundary_(IndexOfRefraction{eta, std::nullopt}, std::move(r)), interior_(std::move(interior)) {}
    const BxDF* bxdf(const MaterialEvalContext& ctx, ScratchBuffer& buf) const override { return boundary_.bxdf(ctx, buf); }
    const SubsurfaceInterior& interior() const { return interior_; }

private:
    DielectricMaterial boundary_;
    SubsurfaceInterior interior_;
};

}  // namespace ps
