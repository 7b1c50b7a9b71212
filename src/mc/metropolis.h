// The Metropolis-Hastings method (thesis ch. 2, "The Metropolis method"; ch. 11 builds
// Metropolis light transport on it): a Markov chain whose stationary density is f / (integral
// of f) for any unnormalised f >= 0. From x, propose y with density T(x -> y) and accept
// with probability min(1, f(y) T(y -> x) / (f(x) T(x -> y))); otherwise repeat x.
#pragma once
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "mc/rng.h"

namespace ps {

class MetropolisProposal {
public:
    virtual ~MetropolisProposal() = default;
    // Writes a proposal y for the current state x.
    virtual void propose(std::span<const double> x, std::span<double> y, Rng& rng) = 0;
    // T(y -> x) / T(x -> y): 1 for symmetric proposals.
    virtual double transitionRatio(std::span<const double> x, std::span<const double> y) const = 0;
};

// Gaussian random walk with step sigma per coordinate. On the unit cube the step wraps
// around (a torus), which keeps the proposal symmetric and never leaves the domain.
class RandomWalkProposal final : public MetropolisProposal {
public:
    RandomWalkProposal(double sigma, bool wrapToUnitCube) : sigma_(sigma), wrap_(wrapToUnitCube) {}
    void propose(std::span<const double> x, std::span<double> y, Rng& rng) override;
    double transitionRatio(std::span<const double>, std::span<const double>) const override { return 1.0; }

private:
    double sigma_;
    bool wrap_;
};

// Independent proposals from a density g (independent of x): ratio g(x) / g(y). Good when
// g resembles f; with g = f every proposal is accepted and the chain is i.i.d.
class IndependenceProposal final : public MetropolisProposal {
public:
    using Sample = std::function<void(Rng&, std::span<double>)>;
    using Pdf = std::function<double(std::span<const double>)>;
    IndependenceProposal(Sample sample, Pdf pdf) : sample_(std::move(sample)), pdf_(std::move(pdf)) {}
    void propose(std::span<const double>, std::span<double> y, Rng& rng) override { sample_(rng, y); }
    double transitionRatio(std::span<const double> x, std::span<const double> y) const override {
        double gy = pdf_(y);
        return gy > 0 ? pdf_(x) / gy : 0.0;
    }

private:
    Sample sample_;
    Pdf pdf_;
};

struct MetropolisChain {
    int dims = 0;
    std::vector<double> states;  // samples x dims, row-major, burn-in excluded
    int64_t proposals = 0, accepted = 0;
    double acceptanceRate() const { return proposals ? double(accepted) / double(proposals) : 0.0; }
    std::span<const double> state(size_t i) const { return {states.data() + i * dims, size_t(dims)}; }
    // One coordinate as a series, for autocorrelation.h.
    std::vector<double> coordinate(int d) const;
};

// Runs burnIn + samples steps from start (where f must be > 0) and keeps the last `samples`.
// The acceptance counts cover the kept steps only.
MetropolisChain runMetropolis(const std::function<double(std::span<const double>)>& f, MetropolisProposal& proposal,
                              std::span<const double> start, int samples, int burnIn, Rng& rng);

// A standard normal deviate (Box-Muller), for random-walk steps.
double standardNormal(Rng& rng);

// Standard normal deviates two at a time: Box-Muller gives an independent pair for one
// logarithm and one sine-cosine, half standardNormal's cost per deviate (the small steps of
// primary-sample-space Metropolis draw one per value read).
class NormalPairs {
public:
    double next(Rng& rng);
    void reset() { haveSpare_ = false; }

private:
    double spare_ = 0;
    bool haveSpare_ = false;
};

}  // namespace ps
