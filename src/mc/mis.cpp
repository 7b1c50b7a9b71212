#include "mc/mis.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "util/error.h"

namespace ps {

double MisWeighting::weight(double p, const double* others, int n) const {
    if (!(p > 0)) return 0;
    constexpr int kMax = 64;
    double r[kMax];
    if (n > kMax) n = kMax;
    for (int i = 0; i < n; ++i) r[i] = others[i] / p;
    return weightFromRatios(r, n);
}

namespace {

// Cutoff and maximum compare densities. The same density computed along two code paths
// (a light's pdf when it is sampled and when a BSDF sample hits it; BDPT's stored and
// recomputed densities, up to a percent apart at close vertices) differs, and where
// techniques sample alike (a diffuse furnace: light and cosine sampling have equal
// densities) a comparison falling either way left both weights 0: with exact comparisons
// the maximum heuristic rendered the closed furnace 29% dark (path), 44% (bdpt); with a
// 1e-4 tolerance 4.7% and 17%. Densities within this relative distance of the largest
// count as the largest (residual: docs/mis.md).
constexpr double kTie = 1e-2;

}  // namespace

double MisWeighting::weightFromRatios(const double* r, int n) const {
    double sum = 0;
    switch (heuristic) {
        case MisHeuristic::Balance:
            for (int i = 0; i < n; ++i) sum += r[i];
            break;
        case MisHeuristic::Power:
            // Eq. 9.11 with the densities divided by this one's: p^b / sum p_k^b.
            for (int i = 0; i < n; ++i) sum += r[i] > 0 ? std::pow(r[i], double(beta)) : 0.0;
            break;
        case MisHeuristic::Cutoff: {
            // §9.2.4: techniques below alpha times the largest density drop out; the rest
            // are balanced. This one (ratio 1) may itself drop out.
            double largest = 1;
            for (int i = 0; i < n; ++i) largest = std::fmax(largest, r[i]);
            const double threshold = alpha * largest * (1 - kTie);
            if (!std::isfinite(largest) || 1 < threshold) return 0;
            for (int i = 0; i < n; ++i)
                if (r[i] >= threshold) sum += r[i];
            break;
        }
        case MisHeuristic::Maximum: {
            // §9.2.4: all weight to the technique of largest density; the techniques at
            // the largest density (within kTie, measured from the largest so that every
            // technique sees the same set) share it, so weights sum to one.
            double largest = 1;
            for (int i = 0; i < n; ++i) largest = std::fmax(largest, r[i]);
            const double threshold = largest * (1 - kTie);
            if (!std::isfinite(largest) || 1 < threshold) return 0;
            int ties = 0;
            for (int i = 0; i < n; ++i) ties += r[i] >= threshold;
            return 1.0 / (1 + ties);
        }
        case MisHeuristic::Uniform:
            for (int i = 0; i < n; ++i) sum += r[i] > 0 ? 1 : 0;
            break;
    }
    if (!std::isfinite(sum)) return 0;
    return 1 / (1 + sum);
}

namespace {

bool parseNumber(const std::string& text, float& out) {
    if (text.empty()) return false;
    char* end = nullptr;
    out = std::strtof(text.c_str(), &end);
    return *end == '\0' && std::isfinite(out);
}

}  // namespace

MisWeighting parseMisWeighting(const std::string& text) {
    const size_t colon = text.find(':');
    const std::string name = text.substr(0, colon);
    const bool hasValue = colon != std::string::npos;
    const std::string value = hasValue ? text.substr(colon + 1) : "";
    MisWeighting w;
    const std::string available =
        " (available: balance, power[:BETA], cutoff[:ALPHA], maximum, none; e.g. power:3, cutoff:0.05)";
    if (name == "balance" || name == "maximum" || name == "none") {
        if (hasValue) throw InputError("MIS heuristic \"" + name + "\" takes no parameter (\"" + text + "\")");
        w.heuristic = name == "balance" ? MisHeuristic::Balance
                      : name == "maximum" ? MisHeuristic::Maximum
                                          : MisHeuristic::Uniform;
    } else if (name == "power") {
        w.heuristic = MisHeuristic::Power;
        if (hasValue && !(parseNumber(value, w.beta) && w.beta > 0))
            throw InputError("MIS heuristic \"" + text + "\": the exponent BETA of power:BETA must be a number > 0");
    } else if (name == "cutoff") {
        w.heuristic = MisHeuristic::Cutoff;
        if (hasValue && !(parseNumber(value, w.alpha) && w.alpha >= 0 && w.alpha <= 1))
            throw InputError("MIS heuristic \"" + text + "\": ALPHA of cutoff:ALPHA must be a number in [0, 1]");
    } else {
        throw InputError("unknown MIS heuristic \"" + text + "\"" + available);
    }
    return w;
}

std::string misWeightingName(const MisWeighting& w) {
    char number[32];
    switch (w.heuristic) {
        case MisHeuristic::Balance: return "balance";
        case MisHeuristic::Maximum: return "maximum";
        case MisHeuristic::Uniform: return "none";
        case MisHeuristic::Power:
            if (w.beta == 2) return "power";
            std::snprintf(number, sizeof number, "%g", double(w.beta));
            return std::string("power:") + number;
        case MisHeuristic::Cutoff:
            std::snprintf(number, sizeof number, "%g", double(w.alpha));
            return std::string("cutoff:") + number;
    }
    return "power";
}

}  // namespace ps
