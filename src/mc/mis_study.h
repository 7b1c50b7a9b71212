// The two-technique integrand of thesis ch. 9 (Veach's glossy highlights, figs. 9.2 and
// 9.3): light reflected by a glossy surface from a spherical light, estimated with one
// sample of light sampling and one of BSDF sampling combined by a MIS heuristic. Small
// lights on rough surfaces favour light sampling, large lights on sharp surfaces BSDF
// sampling; the heuristics of §9.2 are compared by the variance they give in every case
// (`pathspace mc --study mis`, docs/mis.md).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "mc/mis.h"

namespace ps {

// One case: a light of angular radius lightRadius (radians, a cap of directions) whose
// centre lies `offset` radians from the mirror direction, reflected by a Phong lobe of
// exponent `exponent` about the mirror direction. The integrand over directions w is
//   f(w) = L(w) p_bsdf(w), L = 1 on the cap, p_bsdf = (n + 1) / (2 pi) cos^n(angle to mirror)
// (the lobe's own sampling density, so BSDF sampling is exact but for the cap's edge).
struct GlossyHighlight {
    double lightRadius = 0.1, offset = 0.05, exponent = 100;
    double exact() const;  // by quadrature over the cap (relative error < 1e-7)
    // The two techniques: a uniform direction in the cap, and a direction of the lobe.
    // Each returns the direction's density under both techniques and f there.
    struct Sample {
        double f = 0, pLight = 0, pBsdf = 0;
    };
    Sample sampleLight(double u1, double u2) const;
    Sample sampleBsdf(double u1, double u2) const;
};

// A strategy of the study: one sample of each technique weighted by `mis` (the
// multi-sample model of §9.2, n1 = n2 = 1), or, with `alone` set, two samples of one
// technique (0: light, 1: BSDF), so every strategy costs two samples.
struct MisStrategy {
    std::string name;
    MisWeighting mis;
    int alone = -1;
};
// balance, power (beta 2), cutoff (alpha 0.1), maximum, light alone, BSDF alone.
std::vector<MisStrategy> misStudyStrategies();

struct MisStudyCell {
    GlossyHighlight setup;
    double exact = 0;
    std::vector<double> mean, variance, seconds;  // per strategy: one estimate's mean and variance
};
// The 4 x 4 grid of fig. 9.2: light radii from small to large, exponents from rough to
// sharp; `samples` estimates per strategy and case.
std::vector<MisStudyCell> runMisStudy(const std::vector<MisStrategy>& strategies, int samples, uint64_t seed);

}  // namespace ps
