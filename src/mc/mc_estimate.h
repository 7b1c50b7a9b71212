// What every estimator of the Monte Carlo toolbox returns, and the integrand type it takes.
// Cost is counted twice: evaluations of the integrand (the unit the thesis compares
// techniques in) and wall-clock seconds, for efficiency 1/(V T) (estimator.h).
#pragma once
#include <chrono>
#include <cstdint>
#include <functional>
#include <span>

#include "mc/estimator.h"

namespace ps {

// An integrand over [0,1)^s (or over a domain reached through a mapping, e.g. importance
// sampling); the span's size is s.
using Integrand = std::function<double(std::span<const double>)>;

struct McEstimate {
    double value = 0;
    // Estimated from the samples themselves as if they were independent; for stratified and
    // quasi-Monte Carlo point sets this is conservative (their true error is smaller), and
    // only the spread over independent runs measures it (convergence.h).
    double standardError = 0;
    int64_t evaluations = 0;
    double seconds = 0;
};

class Stopwatch {
public:
    double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

private:
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

// Call after allocating and before an estimator's loop. glibc's AVX-512 memset (used for
// small zero-filled vectors) leaves the upper vector state dirty; until a vzeroupper, every
// SSE instruction pays a transition penalty, and libm's exp/pow wrappers are SSE code:
// measured 10x slower integrands on the build machine (Xeon, GCC 12, glibc 2.36).
inline void clearUpperVectorState() {
#if defined(__AVX__)
    __builtin_ia32_vzeroupper();
#endif
}

// An estimate that is the mean of independent per-sample values.
inline McEstimate estimateFromStats(const RunningStats& s, int64_t evaluations, double seconds) {
    return {s.mean(), s.standardError(), evaluations, seconds};
}

}  // namespace ps
