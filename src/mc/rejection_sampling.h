// Rejection sampling (thesis ch. 2, "Sampling random variables: the rejection method"):
// to sample an unnormalised density f, propose X from a density g we can sample, with an
// envelope f <= M g, and accept with probability f(X) / (M g(X)). Each try succeeds with
// probability (integral of f) / M, so for a normalised f the acceptance rate is 1/M.
#pragma once
#include <cstdint>
#include <functional>
#include <span>

#include "mc/rng.h"

namespace ps {

class RejectionSampler {
public:
    using Density = std::function<double(std::span<const double>)>;
    using Proposal = std::function<void(Rng&, std::span<double>)>;
    RejectionSampler(int dims, Density target, Proposal propose, Density proposalPdf, double envelope)
        : dims_(dims), target_(std::move(target)), propose_(std::move(propose)), pdf_(std::move(proposalPdf)),
          envelope_(envelope) {}

    // Writes one sample of the target into x (size dims). Gives up after maxTries (returns
    // false), so a target that is zero almost everywhere cannot hang the caller.
    bool sample(Rng& rng, std::span<double> x, int64_t maxTries = 1 << 20);

    int dims() const { return dims_; }
    int64_t tries() const { return tries_; }
    int64_t accepted() const { return accepted_; }
    double acceptanceRate() const { return tries_ ? double(accepted_) / double(tries_) : 0.0; }
    // Points where f > M g break the method (the envelope is not one); counted, not hidden.
    int64_t envelopeViolations() const { return violations_; }

private:
    int dims_;
    Density target_;
    Proposal propose_;
    Density pdf_;
    double envelope_;
    int64_t tries_ = 0, accepted_ = 0, violations_ = 0;
};

}  // namespace ps
