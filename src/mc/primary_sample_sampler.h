// Primary-sample-space Metropolis sampling (Kelemen et al. 2002; thesis ch. 11 builds
// Metropolis light transport on the same Metropolis-Hastings step): a Markov chain over the
// unit hypercube of random numbers that a Monte Carlo estimator consumes. The chain's state
// is the vector of every value read so far; each iteration proposes a new vector, the
// estimator runs on it unchanged (it only calls get1D / get2D), and the chain accepts or
// rejects. Both mutations are symmetric (T(x -> y) = T(y -> x)), so the acceptance
// probability is min(1, f(y) / f(x)).
//
// Values are mutated lazily, when they are read: a large step draws a value afresh, a small
// step moves it by a normal deviate of standard deviation sigma on the torus [0,1). A value
// not read for n accepted iterations catches up on the n small steps it missed in one normal
// step of sigma * sqrt(n) (the sum of independent normals; wrapping commutes with the sum),
// or is drawn afresh if a large step was accepted in between. Rejection restores every value
// the proposal touched, bit for bit.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "mc/metropolis.h"
#include "mc/padded_strata.h"
#include "mc/rng.h"
#include "mc/sampler.h"
#include "util/byte_stream.h"

namespace ps {

struct PrimarySampleParams {
    double sigma = 0.01;                // small-step standard deviation (pbrt-v4's default)
    double largeStepProbability = 0.3;  // chance that an iteration is a large step
    int streamCount = 1;                // dimension streams (see startStream)
    // Partial small steps: with this probability a small step moves only the streams of one
    // of `partialSteps` (bit masks of streams, chosen uniformly), the others keep their
    // values. The choice does not depend on the state, so the step stays symmetric; a
    // target whose streams are the two subpaths of a path then has steps that keep one
    // subpath while the other moves (as the lens and caustic perturbations of thesis
    // 11.4.3 do in path space). 0: every small step moves every stream.
    double partialStepProbability = 0;
    struct PartialStep {
        uint32_t streams = 0;  // bit mask
        double sigma = 0.01;   // its standard deviation
    };
    std::vector<PartialStep> partialSteps;
};

class PrimarySampleSampler final : public Sampler {
public:
    // chainSeed keys the chain's own random stream: the mutations and the values drawn afresh.
    // The same seed and the same sequence of calls give the same values (replay).
    PrimarySampleSampler(uint64_t chainSeed, const PrimarySampleParams& params);

    // Starts the next proposal. The first iteration of a chain is always a large step (every
    // value fresh); afterwards a large step with probability largeStepProbability.
    void startIteration();
    void startIteration(bool largeStep);  // the step kind chosen by the caller (every stream)
    // As startIteration(), but a partial step, when one is taken, is partialSteps[kind]: the
    // caller may choose it from the chain's state, provided that no partial step changes
    // what decides it (each class of states then has a symmetric kernel of its own, and the
    // chance of a partial step is the same in every class).
    void startIterationOfKind(size_t kind);
    // Keeps the proposal as the chain's state, or restores the state before it.
    void accept();
    void reject();
    bool largeStep() const { return largeStep_; }
    // The streams the proposal's small step moves (every bit: all of them) and its standard
    // deviation.
    uint32_t movedStreams() const { return moved_; }
    double stepSigma() const { return params_.sigma * std::sqrt(stepUnits_); }
    // Accepted iterations so far (between iterations; a proposal under way is the next one).
    int64_t acceptedIterations() const { return iteration_; }

    // Dimension streams: each stream has its own sequence of values, so that what one stream
    // consumes never shifts another's values. Selected again within
    // an iteration, a stream continues where it stopped; every iteration starts each stream
    // at its first value.
    void startStream(int stream) override { stream_ = stream < params_.streamCount ? stream : 0; }
    void seekDimension(int index) override { streamIndex_[size_t(stream_)] = index >= 0 ? index : 0; }
    // Sets the value of `stream` at `index` in the proposal under way (in [0,1)): a state
    // placed by the caller, restored by a rejection like any other value.
    void set(int stream, int index, double value);
    // The first iteration's fresh values as sample i of a set of n (a Markov-chain render's
    // bootstrap, whose mean weight b scales the whole image: thesis §2.7 on stratification):
    // the first kStratifiedValues values of each stream come, two at a time, from sample i of
    // n of a PaddedStrata set keyed by `key` (padded_strata.h). Every value is still uniform
    // on its own, which is all that an unbiased b and an unbiased start of the chains use;
    // the other values and every later iteration are drawn as before. Called before the
    // first iteration's values are read.
    static constexpr int kStratifiedValues = 8;
    void stratifyFirstIteration(uint64_t key, int64_t i, int64_t n);
    // A new random stream for the mutations from here on; the stored values stay. A chain
    // started from a replayed bootstrap sample takes its own stream this way.
    void reseed(uint64_t chainSeed);

    float get1D() override;
    Vec2 get2D() override;
    // Ignored (a chain has no pixels): every stream restarts at its first value.
    void startPixelSample(int, int, int) override { restartStreams(); }
    // Every stream back to its first value within the proposal under way: a second
    // evaluation of the same proposal reads the same values.
    void restartStreams();
    std::unique_ptr<Sampler> clone() const override { return std::make_unique<PrimarySampleSampler>(*this); }

    // The state, for tests: the stored values and the iteration at which each was last
    // modified (-1: never read, or only by rejected proposals).
    struct Value {
        double value = 0;
        int64_t modified = -1;
        double steps = 0;  // the variance, in units of sigma^2, of its stream's accepted small steps that it has taken
        double backupValue = 0, backupSteps = 0;
        int64_t backupModified = -1;
    };
    const std::vector<Value>& values(int stream = 0) const { return streams_[size_t(stream)]; }
    bool sameState(const PrimarySampleSampler& o) const;

    // The chain's whole state between iterations (a checkpoint): the values with their
    // iterations and backups, the iteration counters and the random stream with its spare
    // normal deviate, so that the restored chain goes on bit for bit. Not the parameters,
    // which the restoring render has (its checkpoint's settings match).
    void save(ByteWriter& out) const;
    void load(ByteReader& in);

private:
    double read(int stream, size_t index);
    double stratified(int stream, size_t index) const;
    double small(double v, double units);

    PrimarySampleParams params_;
    Rng rng_;
    NormalPairs normals_;
    std::vector<std::vector<Value>> streams_;  // per stream, its values by index
    int64_t iteration_ = 0;        // the proposal's iteration number (accepted ones + 1)
    int64_t lastLargeStep_ = 0;    // iteration of the last accepted large step
    bool largeStep_ = true;
    uint32_t moved_ = ~0u;          // the streams the proposal's small step moves
    double stepUnits_ = 1;          // its variance in units of sigma^2
    // Per stream, the variance of the accepted small steps that moved it, in units of
    // sigma^2: with every step of sigma, their number (exact in a double).
    std::vector<double> smallSteps_;
    int stream_ = 0;
    std::vector<int64_t> streamIndex_;  // each stream's next value this iteration
    struct Touched {
        uint32_t stream, index;
    };
    std::vector<Touched> touched_;  // the values the proposal under way modified
    PaddedStrata strata_;  // the first iteration's set, if any
};

// The acceptance probability of a proposal with target value fy from a state with fx, for
// symmetric mutations: min(1, fy / fx). A proposal whose value is zero, negative or not
// finite is never accepted (and, weighted by this probability, never recorded).
inline double acceptanceProbability(double fx, double fy) {
    if (!(fy > 0) || !std::isfinite(fy)) return 0;
    if (!(fx > 0) || !std::isfinite(fx)) return 1;
    return std::min(1.0, fy / fx);
}

}  // namespace ps
