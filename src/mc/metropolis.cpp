#include "mc/metropolis.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace ps {

double standardNormal(Rng& rng) {
    double u1 = 1.0 - rng.uniformDouble();  // (0, 1]: log is finite
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * rng.uniformDouble());
}

double NormalPairs::next(Rng& rng) {
    if (haveSpare_) {
        haveSpare_ = false;
        return spare_;
    }
    const double r = std::sqrt(-2.0 * std::log(1.0 - rng.uniformDouble()));
    const double phi = 2.0 * std::numbers::pi * rng.uniformDouble();
    spare_ = r * std::sin(phi);
    haveSpare_ = true;
    return r * std::cos(phi);
}

void RandomWalkProposal::propose(std::span<const double> x, std::span<double> y, Rng& rng) {
    for (size_t d = 0; d < x.size(); ++d) {
        double v = x[d] + sigma_ * standardNormal(rng);
        if (wrap_) {
            v -= std::floor(v);
            if (v >= 1.0) v = 0.0;
        }
        y[d] = v;
    }
}

std::vector<double> MetropolisChain::coordinate(int d) const {
    std::vector<double> c(states.size() / size_t(dims));
    for (size_t i = 0; i < c.size(); ++i) c[i] = states[i * dims + d];
    return c;
}

MetropolisChain runMetropolis(const std::function<double(std::span<const double>)>& f, MetropolisProposal& proposal,
                              std::span<const double> start, int samples, int burnIn, Rng& rng) {
    MetropolisChain chain;
    chain.dims = int(start.size());
    std::vector<double> x(start.begin(), start.end()), y(start.size());
    double fx = f(x);
    if (!(fx > 0)) throw std::invalid_argument("metropolis: f must be positive at the start state");
    chain.states.reserve(size_t(samples) * start.size());
    for (int step = 0; step < burnIn + samples; ++step) {
        proposal.propose(x, y, rng);
        double fy = f(y);
        double a = fy > 0 ? fy * proposal.transitionRatio(x, y) / fx : 0.0;
        bool accept = a >= 1.0 || rng.uniformDouble() < a;
        if (accept) {
            x.swap(y);
            fx = fy;
        }
        if (step >= burnIn) {
            ++chain.proposals;
            chain.accepted += accept;
            chain.states.insert(chain.states.end(), x.begin(), x.end());
        }
    }
    return chain;
}

}  // namespace ps
