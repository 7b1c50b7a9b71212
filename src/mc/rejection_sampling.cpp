#include "mc/rejection_sampling.h"

namespace ps {

bool RejectionSampler::sample(Rng& rng, std::span<double> x, int64_t maxTries) {
    for (int64_t t = 0; t < maxTries; ++t) {
        ++tries_;
        propose_(rng, x);
        double bound = envelope_ * pdf_(x), fx = target_(x);
        if (fx > bound) ++violations_;
        if (rng.uniformDouble() * bound < fx) {
            ++accepted_;
            return true;
        }
    }
    return false;
}

}  // namespace ps
