// Multiple importance sampling heuristics (thesis ch. 9): how the samples of several
// techniques that can each produce the same point are weighted so that the weights sum to
// one there (eq. 9.4's condition for an unbiased combination).
#pragma once
#include <string>

namespace ps {

// Balance heuristic, thesis eq. 9.5 (one sample from each technique).
inline float balanceHeuristic(float pf, float pg) { return pf / (pf + pg); }

// Power heuristic with exponent 2, thesis eq. 9.11.
inline float powerHeuristic(float pf, float pg) {
    float f = pf * pf, g = pg * pg;
    if (f == 0) return 0;
    if (!(g < 1e30f)) return 0;  // the other technique is (near) certain
    return f / (f + g);
}

// The heuristics of thesis ch. 9: balance (§9.2.2), and power, cutoff and maximum
// (§9.2.4); Uniform gives each technique that can produce the point the same weight (what
// `--mis none` means: no importance in the weighting, not "no weights").
enum class MisHeuristic { Balance, Power, Cutoff, Maximum, Uniform };

// A heuristic and its parameter: beta for power (2: the thesis's recommendation), alpha
// for cutoff (a technique whose density is below alpha times the largest gets weight 0).
struct MisWeighting {
    MisHeuristic heuristic = MisHeuristic::Power;
    float beta = 2;
    float alpha = 0.1f;

    MisWeighting() = default;
    MisWeighting(MisHeuristic h) : heuristic(h) {}  // NOLINT: a heuristic with its default parameter

    // Power with beta = 2: the default, on BDPT's and the path tracer's fast paths.
    bool isDefault() const { return heuristic == MisHeuristic::Power && beta == 2; }
    // The weight of the technique with density `p`, among techniques whose densities at
    // the same point are `others[0..n-1]` (0: cannot produce it). Ties of the maximum
    // heuristic (densities within a relative 1% of the largest, beyond rounding) share
    // the weight equally, so the weights still sum to one.
    double weight(double p, const double* others, int n) const;
    // Two techniques (the path tracer's light and BSDF sampling, the mc study).
    double weight(double pf, double pg) const { return weight(pf, &pg, 1); }
    // From the ratios r[i] = p_other / p_this alone (every heuristic is invariant to a
    // common scale of the densities): what BDPT's walks give.
    double weightFromRatios(const double* ratios, int n) const;
};

// "balance", "power" (beta 2), "power:BETA" (BETA > 0), "cutoff" (alpha 0.1),
// "cutoff:ALPHA" (0 <= ALPHA <= 1), "maximum", "none"; throws InputError otherwise.
MisWeighting parseMisWeighting(const std::string& text);
// The canonical spelling (parseMisWeighting's inverse): "power" for beta 2, "power:3", ...
std::string misWeightingName(const MisWeighting& w);

}  // namespace ps
