// The `subsurface` material's "reflectance" + "mfp" form, as pbrt-v4 reads it (materials.h:
// SubsurfaceMaterial; bssrdf.cpp: ComputeBeamDiffusionBSSRDF, SubsurfaceFromDiffuse): the
// single-scattering albedo rho whose photon-beam-diffusion profile (Habel, Christensen and
// Jarosz 2013: single scattering plus the multiple-scattering dipole with Grosjean's diffusion
// coefficient, both through a boundary of index eta) reflects `reflectance` in all; then
// sigma_t = 1 / mfp. pbrt-v4 renders the profile as a BSSRDF; we walk the medium it names.
#pragma once
#include <vector>

namespace ps {

struct EffectiveAlbedoTable {
    // rho on pbrt-v4's grid (1 - exp(-8 i / 99)) / (1 - exp(-8)), i < 100, dense near 1,
    // and the total diffuse reflectance rho_eff of a half space of that albedo (sigma_t = 1).
    std::vector<float> rho, rhoEff;
};

// For phase asymmetry g and relative index eta (inside over outside).
EffectiveAlbedoTable effectiveAlbedoTable(float g, float eta);

// The albedo whose rho_eff is `reflectance` (clamped to [0, 1]), by inverting the table's
// Catmull-Rom spline (0 or 1 beyond its ends).
float albedoForReflectance(const EffectiveAlbedoTable& table, float reflectance);

// The profile's parts at radius r (sigma_t = 1 units scale out), exposed for tests:
// single scattering and the multiple-scattering dipole, each as radiant exitance per unit
// area (pbrt-v4's BeamDiffusionSS and BeamDiffusionMS).
double beamDiffusionSingle(double sigmaS, double sigmaA, double g, double eta, double r);
double beamDiffusionMultiple(double sigmaS, double sigmaA, double g, double eta, double r);
// The first two Fresnel moments 2 int_0^1 Fr(mu) mu^k dmu (k = 1, 2) by d'Eon and Irving's
// polynomial fits (2011), as pbrt-v4 evaluates them.
double fresnelMoment1(double eta);
double fresnelMoment2(double eta);

}  // namespace ps
