// The bootstrap of a Markov-chain render (thesis ch. 11, "start-up bias"): independent
// samples estimate b, the integral of the target, and the chains' initial states are drawn
// from them in proportion to their weights, so that b times the chains' average is
// unbiased from the first mutation on.
//
// A target may split its samples into groups (multiplexed MLT: the path depths), whose
// samples differ in cost and in spread by orders of magnitude. Then a pilot, sampling every
// group equally, learns two things before the bootstrap proper:
//  - how often the chains' large steps should choose each strategy (each strategy's part
//    of b, mixed with the target's default choice), and
//  - how many of the bootstrap's samples each group gets: in proportion to the spread of
//    its samples over the square root of their cost (Neyman allocation: the least variance
//    of b for the time), mixed with a share for every group. Each sample is weighted by
//    the bootstrap's size over its group's, so b's estimate stays unbiased.
// The pilot's samples are used for nothing else: what it learns does not depend on the
// bootstrap proper, and the argument against start-up bias holds as it is.
#pragma once
#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/task_arena.h>

#include "transport/mlt/metropolis.h"

namespace ps {

// How a run of bootstrap samples is split into groups: group g has samples start[g] ..
// start[g] + count[g] - 1 of the run.
struct BootstrapAllocation {
    std::vector<int64_t> start, count;
    int64_t total = 0;
    // As equal as whole numbers allow (the first total % groups groups one more).
    static BootstrapAllocation even(int64_t total, int groups);
    // share[g] (summing to 1) of total, at least one sample per group.
    static BootstrapAllocation proportional(int64_t total, const std::vector<double>& share);
    int groupOf(int64_t j) const;
    // The weight of a sample of group g relative to its target value: samples of a group
    // with few samples stand for more.
    double scale(int g) const { return double(total) / double(count[size_t(g)]); }
};

// What the chains need of the bootstrap, and what the statistics report of it.
struct Bootstrap {
    StrategyChoice choice;        // the strategy choice, learned if there was a pilot
    BootstrapAllocation groups;   // the bootstrap proper's samples by group
    int64_t first = 0;            // index of its first sample (the pilot's come before)
    int64_t pilotSamples = 0;
    std::vector<double> weights;  // per sample, its states' total weight
    std::vector<double> cumulative;
    double sum = 0, b = 0, bRelativeError = 0;
    bool cancelled = false;
};

// The tools of one render that the bootstrap shares with the chains.
struct BootstrapContext {
    const MetropolisIntegrator& integrator;
    const PrimarySampleParams& pss;
    uint64_t seed;
    const std::atomic<bool>* cancel;  // may be null
    tbb::task_arena& arena;
    tbb::enumerable_thread_specific<ChainEvaluator>& evaluators;
    std::atomic<long long>* progress = nullptr;  // counts the samples taken (a progress bar's), may be null
};

// The bootstrap of `samples` samples, its pilot's included (bootstrapIndexCount, or fewer
// to fit a time budget: startup_budget.h).
Bootstrap runBootstrap(const BootstrapContext& ctx, int64_t samples);

// `count` samples as the bootstrap's pilot takes them (every group alike), from streams of
// their own, their results unused: what a start-up's samples cost (startup_budget.h).
void probeBootstrap(const BootstrapContext& ctx, int64_t count);

// The indices the bootstrap's samples (its pilot's included) may take: 0 .. this - 1.
int64_t bootstrapIndexCount(const MetropolisIntegrator& integrator);

// Two-stage MLT's pilot (pilot_importance.h): `count` independent BDPT samples (every
// depth and strategy: a multiplexed sample of one strategy would leave B too noisy) from
// index `first` on (past the bootstrap's), each contribution's luminance added to the tile
// it lands in (PilotImportance::learn). Made before the bootstrap, whose weights it divides.
void runImportancePilot(const BootstrapContext& ctx, int64_t first, int64_t count, PilotImportance& importance);

// The key of bootstrap sample i's random stream. The seed is mixed before the index enters:
// keyed on seed ^ constant directly, nearby seeds would give largely the same set of keys
// over a range of indices (shifted), and renders with different seeds would share most of
// their bootstrap samples.
uint64_t bootstrapSeed(uint64_t seed, int64_t i);

// A chain's initial state, drawn with the chain's rng in proportion to the bootstrap's
// weights and replayed: the sampler holding it (its proposal accepted) and the state.
// False if the replay does not reproduce the bootstrap's weights and target value.
bool startChain(const BootstrapContext& ctx, const Bootstrap& boot, Rng& rng,
                std::unique_ptr<PrimarySampleSampler>& sampler, ChainState& x);

}  // namespace ps
