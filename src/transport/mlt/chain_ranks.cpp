#include "transport/mlt/chain_ranks.h"

namespace ps::chain_ranks {

void perProcess(MetropolisStats& ms, const std::vector<long long>& done, const std::vector<long long>& accepted,
                const std::vector<long long>& proposed) {
    const size_t k = size_t(distributed::size());
    ms.rankMutations.assign(k, 0);
    std::vector<long long> a(k, 0), p(k, 0);
    for (size_t c = 0; c < done.size(); ++c) {
        ms.rankMutations[c % k] += done[c];
        a[c % k] += accepted[c];
        p[c % k] += proposed[c];
    }
    ms.rankAcceptance.resize(k);
    for (size_t r = 0; r < k; ++r) ms.rankAcceptance[r] = MetropolisStats::rate(a[r], p[r]);
}

}  // namespace ps::chain_ranks
