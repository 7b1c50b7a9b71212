#include "transport/mlt/startup_budget.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "mc/rng.h"
#include "render/distributed.h"

namespace ps {

int64_t startupProbeSamples(int64_t planned) { return std::clamp<int64_t>(planned / 50, 256, 4096); }

double startupFraction(double timeLimit, int64_t planned, int64_t probed, const std::function<void()>& probe) {
    if (!(timeLimit > 0) || planned <= 0 || probed <= 0) return 1.0;
    // Timed the second time: the first pays for what a render's first samples set up (its
    // threads, their scratch memory), which would make the start-up look several times dearer.
    probe();
    const auto start = std::chrono::steady_clock::now();
    probe();
    const double local = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    double seconds = local;
    {
        distributed::Purpose purpose("start-up budget");
        seconds = double(distributed::maxOf(int64_t(std::ceil(local * 1e6)))) * 1e-6;
    }
    const double wanted = double(planned) * seconds / double(probed);
    const double allowed = std::max(0.0, kStartupShare * timeLimit - 2 * seconds);
    return wanted > allowed ? allowed / wanted : 1.0;
}

int64_t scaledCount(int64_t count, double fraction, int64_t floor) {
    if (fraction >= 1) return count;
    return std::min(count, std::max(floor, int64_t(double(count) * fraction)));
}

uint64_t startupProbeSeed(uint64_t seed) { return mix64(seed ^ 0x3243f6a8885a308dULL); }

}  // namespace ps
