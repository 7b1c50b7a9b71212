#include "media/transmittance.h"

#include "media/majorant_tracking.h"
#include "render/scene.h"

namespace ps {

TransmittanceEstimate transmittance(const Scene& scene, Vec3 p, Vec3 ng, const Medium* medium, Vec3 target, float time,
                                    const SampledWavelengths* lambda, int hero, bool spectral, Rng& rng) {
    TransmittanceEstimate est;
    Ray ray = spawnRayTo(p, ng, target, time);
    for (int crossings = 0; crossings < 1024; ++crossings) {
        SurfaceInteraction si;
        ++est.rays;
        const bool hit = scene.intersect(ray, si);
        if (hit && si.material && !si.material->isInterface()) {
            est.T = Spectrum(0.0f);
            return est;
        }
        if (medium) {
            const float tEnd = hit ? si.t : ray.tMax;
            Spectrum Tmaj = sampleMajorant(*medium, ray, tEnd, rng.uniform(), rng, lambda, hero,
                                           [&](Vec3, const MediumProperties& mp, const Spectrum& sigmaMaj, const Spectrum& Tm) {
                // Ratio tracking: each null collision weighs by sigma_n / sigma_maj.
                const Spectrum sigmaN = clampZero(sigmaMaj - mp.sigmaA - mp.sigmaS);
                const float pdf = Tm[hero] * sigmaMaj[hero];
                est.T *= Tm * sigmaN / pdf;
                est.rL *= Tm * sigmaMaj / pdf;
                est.rU *= Tm * sigmaN / pdf;
                // Russian roulette on a small estimate (pbrt-v4's 0.05 and 0.75).
                const Spectrum Tr = est.T / channelMean(est.rL + est.rU, spectral);
                if (Tr.maxComponent() < 0.05f) {
                    if (rng.uniform() < 0.75f) est.T = Spectrum(0.0f);
                    else est.T /= 0.25f;
                }
                return !est.T.isBlack();
            });
            const float h = Tmaj[hero];
            if (h > 0) {
                est.T *= Tmaj / h;
                est.rL *= Tmaj / h;
                est.rU *= Tmaj / h;
            } else {
                est.T = Spectrum(0.0f);
            }
        }
        if (est.T.isBlack() || !est.T.isFinite()) {
            est.T = Spectrum(0.0f);
            return est;
        }
        if (!hit) return est;
        medium = si.mediumToward(ray.d, medium);
        ray = spawnRayTo(si.p, si.ng, target, time);
    }
    est.T = Spectrum(0.0f);
    return est;
}

}  // namespace ps
