// pbrt-v4's hair scattering model (Chiang et al. 2016, on d'Eon et al. 2011): a fibre seen
// as a rough dielectric cylinder. The local frame has the fibre along +x and the surface
// normal on +z; h in [-1, 1] is where across the fibre's width the ray hit it.
//
// Scattering is a sum of lobes p = 0 (reflection), 1 (transmission through), 2 (one internal
// reflection) and 3 (all longer paths): each a longitudinal lobe Mp (the von Mises-Fisher
// cone with Bessel I0, variance from beta_m, tilted by the cuticle angle alpha), an azimuthal
// lobe Np (a trimmed logistic of width from beta_n around the refracted exit azimuth, uniform
// for p = 3) and an attenuation Ap (Fresnel and absorption sigma_a along the internal path).
// f |cos wi| is the sum of the lobes, so with sigma_a = 0 the albedo is exactly 1.
//
// The model is not reciprocal (Ap, the tilts and the exit azimuth depend on wo only), so
// TransportMode::Importance returns the adjoint f*(wo, wi) = f(wi, wo): light tracing and
// BDPT then estimate the image path tracing does. No radiance scaling of refraction enters:
// light that refracts into the fibre refracts out again, the eta^2 factors cancel (the sample's
// eta is 1). Sampling follows the radiance form (lobe by Ap, Mp and Np exactly); in
// importance mode the azimuth is mirrored, where the adjoint's lobes lie (its exit azimuths
// are those of f(wo, .) reflected, e.g. +2 gamma_o for the reflection instead of -2 gamma_o).
// pdf() is the exact density of each mode's sampling.
//
// In spectral mode the four channels are the path's wavelengths and the lobe is chosen by the
// mean of Ap over all four (pbrt-v4's Average); in RGB mode by the mean of r, g, b, and the
// fourth channel repeats g.
//
// h is taken as given. Where it is a property of the surface point (ribbons, meshes) the
// adjoint is exact. On flat and cylinder curves pbrt-v4 derives h from the ray that found
// the hit, so a light-tracing vertex has the light ray's h, not the camera side's.
#pragma once
#include <array>
#include "geometry/fibre_kind.h"
#include "materials/bxdf.h"
#include "spectral/wavelengths.h"

namespace ps {

struct HairParams {
    float h = 0;            // offset across the fibre, -1 .. 1
    float eta = 1.55f;      // index of refraction of the fibre
    Spectrum sigmaA;        // absorption per unit of the fibre's radius
    float betaM = 0.3f;     // longitudinal roughness, 0.01 .. 1
    float betaN = 0.3f;     // azimuthal roughness, 0.01 .. 1
    float alphaDegrees = 2; // tilt of the cuticle scales
    bool spectral = false;  // sigmaA holds four wavelengths' values (else r, g, b and g)
    FibreKind fibre = FibreKind::None;  // the shape it lies on: which adjoint applies (hair_bxdf.cpp)
};

class HairBxDF final : public BxDF {
public:
    static constexpr int kPMax = 3;  // lobes 0 .. kPMax - 1 explicitly, kPMax for the rest

    explicit HairBxDF(const HairParams& p);
    uint8_t flags() const override { return kReflection | kGlossy; }
    Spectrum f(Vec3 wo, Vec3 wi, TransportMode mode) const override;
    std::optional<BSDFSample> sample(Vec3 wo, float uc, Vec2 u, TransportMode mode) const override;
    float pdf(Vec3 wo, Vec3 wi, TransportMode mode) const override;

    // pbrt-v4's absorption of melanin concentrations, given in RGB; in spectral mode (lambda
    // not null) that RGB lifted as an unbounded sRGB spectrum at lambda, as pbrt-v4 does.
    static Spectrum sigmaAFromConcentration(float eumelanin, float pheomelanin, const SampledWavelengths* lambda = nullptr);
    // The absorption that gives a fibre of azimuthal roughness betaN the multiply-scattered
    // colour c (Chiang et al.'s fit), per channel (colour or wavelength).
    static Spectrum sigmaAFromReflectance(const Spectrum& c, float betaN);

private:
    struct Lobes;  // everything that depends on wo only (hair_bxdf.cpp)
    Lobes lobes(Vec3 wo, double h) const;  // h: the offset of the ray along wo
    // pbrt-v4's f(wo, wi), the radiance form.
    Spectrum radiance(const Lobes& L, Vec3 wi) const;
    // f under importance transport (hair_bxdf.cpp says why it is not f(wi, wo)).
    Spectrum adjoint(Vec3 wo, Vec3 wi) const;
    double density(const Lobes& L, double sinThetaI, double cosThetaI, double dphi) const;

    double h_, eta_;
    FibreKind fibre_;
    std::array<double, 4> sigmaA_;
    int meanChannels_;  // channels whose mean chooses the lobe: 3 (RGB) or 4 (spectral)
    std::array<double, kPMax + 1> v_;  // longitudinal variance per lobe
    double s_;                         // logistic scale of Np
    std::array<double, kPMax> sin2kAlpha_, cos2kAlpha_;
};

}  // namespace ps
