// A free flight through one medium by delta tracking (pbrt-v4's volpath loop over
// SampleT_maj): at each tentative collision the hero channel's probabilities choose
// absorption, a real scattering or a null collision. Every channel's throughput follows the
// hero's choices; rU collects the ratios of each channel's density of those choices to the
// hero's (spectral MIS over wavelengths, Wilkie et al. 2014), rL (if given) what light
// sampling's ratio tracking would have had for the same null collisions. Shared by the path
// tracer (volpath.cpp) and the camera and light subpaths (subpaths_media.cpp).
#pragma once
#include "media/majorant_tracking.h"

namespace ps {

// One tentative collision's estimate of the light a medium emits along a flight (pbrt-v4's
// volpath adds sigma_a Le at every tentative majorant collision, whatever the collision then
// turns out to be): beta T_maj sigma_a Le / pdf, with pdf = sigma_maj T_maj in the hero
// channel, over the channel mean of the whole path's densities rU sigma_maj T_maj / pdf
// (spectral MIS). The path tracer and BDPT's camera walks share it, so that both estimate
// the same integral the same way.
inline Spectrum emissionAtCollision(const MediumProperties& mp, const Spectrum& sigmaMaj, const Spectrum& Tm,
                                    const Spectrum& beta, const Spectrum& rU, int h, bool spectral) {
    if (mp.Le.isBlack()) return {};
    const float pdf = sigmaMaj[h] * Tm[h];
    if (!(pdf > 0)) return {};
    const Spectrum rE = rU * sigmaMaj * Tm / pdf;
    if (rE.isBlack()) return {};
    return beta * Tm / pdf * mp.sigmaA * mp.Le / channelMean(rE, spectral);
}

enum class FlightEnd { Passed, Scattered, Absorbed };

struct Flight {
    FlightEnd end = FlightEnd::Passed;
    Vec3 p;  // the scattering point
};

// Along ray up to tEnd in `medium`; u gives the first flight and uEvent (if in [0, 1)) the
// first collision's choice, the rest come from rng. emission(props, sigmaMaj, Tmaj) sees every tentative
// collision before it is resolved (emissive media). On Scattered, beta and rU include
// T_maj sigma_s / pdf; on Passed, T_maj / pdf of reaching tEnd. Absorbed also stands for a
// throughput that vanished.
template <typename Emission>
Flight deltaTrack(const Medium& medium, const Ray& ray, float tEnd, float u, Rng& rng, const SampledWavelengths* lambda,
                  int h, Spectrum& beta, Spectrum& rU, Spectrum* rL, Emission&& emission, float uEvent = -1) {
    Flight f;
    Spectrum Tmaj = sampleMajorant(medium, ray, tEnd, u, rng, lambda, h,
                                   [&](Vec3 p, const MediumProperties& mp, const Spectrum& sigmaMaj, const Spectrum& Tm) {
        emission(mp, sigmaMaj, Tm);
        const float pAbsorb = mp.sigmaA[h] / sigmaMaj[h], pScatter = mp.sigmaS[h] / sigmaMaj[h];
        const float uMode = uEvent >= 0 ? uEvent : rng.uniform();
        uEvent = -1;
        if (uMode < pAbsorb) {
            f.end = FlightEnd::Absorbed;
            return false;
        }
        if (uMode < pAbsorb + pScatter) {
            const float pdf = Tm[h] * mp.sigmaS[h];
            beta *= Tm * mp.sigmaS / pdf;
            rU *= Tm * mp.sigmaS / pdf;
            f.end = beta.isBlack() || rU.isBlack() ? FlightEnd::Absorbed : FlightEnd::Scattered;
            f.p = p;
            return false;
        }
        // A null collision: the flight goes on.
        const Spectrum sigmaN = clampZero(sigmaMaj - mp.sigmaA - mp.sigmaS);
        const float pdf = Tm[h] * sigmaN[h];
        if (!(pdf > 0)) {
            f.end = FlightEnd::Absorbed;
            return false;
        }
        beta *= Tm * sigmaN / pdf;
        rU *= Tm * sigmaN / pdf;
        if (rL) *rL *= Tm * sigmaMaj / pdf;
        if (beta.isBlack() || rU.isBlack()) {
            f.end = FlightEnd::Absorbed;
            return false;
        }
        return true;
    });
    if (f.end != FlightEnd::Passed) return f;
    const float th = Tmaj[h];
    if (!(th > 0) || !beta.isFinite()) {
        f.end = FlightEnd::Absorbed;
        return f;
    }
    beta *= Tmaj / th;
    rU *= Tmaj / th;
    if (rL) *rL *= Tmaj / th;
    return f;
}

}  // namespace ps
