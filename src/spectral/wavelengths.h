// The wavelengths one camera or light path carries (pbrt-v4's SampledWavelengths): four
// per path, the first one drawn, the others at fixed offsets so that together they
// stratify the visible range.
#pragma once
#include <array>

namespace ps {

constexpr int kWavelengthSamples = 4;
using SpectralValues = std::array<float, kWavelengthSamples>;

// The range every spectrum is integrated over (nm), that of the CIE tables.
constexpr float kLambdaMin = 360, kLambdaMax = 830;

// pbrt-v4's visible-wavelength density, proportional to 1/cosh^2(0.0072 (lambda - 538)) on
// [360, 830] nm and zero outside: it follows the luminous efficiency curve closely enough
// that the Y estimate of a flat spectrum has low variance, and it is invertible in closed
// form. Normalised here exactly (pbrt's rounded constant integrates to 0.99996).
float visibleWavelengthPdf(float lambda);
// The inverse of its distribution function: u in [0,1] -> lambda in [360, 830].
float sampleVisibleWavelength(float u);

struct SampledWavelengths {
    SpectralValues lambda{};  // nm
    SpectralValues pdf{};     // density of each lambda[i] (per nm); 0 once terminated
    float u = 0;              // sampleVisible's number, from which the four were made

    // lambda[i] = inverse CDF of (u + i/4) mod 1: one stratum of the density's quantiles
    // each, every one marginally distributed by the density.
    static SampledWavelengths sampleVisible(float u);
    // lambda[0] = lo + u (hi - lo), then steps of (hi - lo)/4 wrapping around to lo.
    static SampledWavelengths sampleUniform(float u, float lo = kLambdaMin, float hi = kLambdaMax);

    // Keeps only lambda[0], for interactions whose direction depends on the wavelength
    // (dispersion). Each lambda[i] alone is an unbiased single-wavelength estimator; the
    // average of four with lambda[0] surviving is unbiased if lambda[0]'s weight is scaled by
    // 4, which dividing its pdf by 4 does (the film averages over the four and skips pdf 0).
    void terminateSecondary();
    bool secondaryTerminated() const;
    // How often terminateSecondary was called, effective or not: a walk learns from it
    // whether a surface's own BxDF is dispersive even once an earlier one terminated.
    int terminationRequests = 0;
};

}  // namespace ps
