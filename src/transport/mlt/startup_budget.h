// A Markov-chain render's start-up under a time budget (--time): the two-stage pilot, the
// strategy pilot and the bootstrap (thesis ch. 11) come before any chain runs, and at their
// default sizes they can take longer than a short budget. So, with a budget, a probe first
// times a few samples of the start-up's kind, and the start-up's sample counts shrink until
// it fits in a quarter of the budget (the chains keep the rest).
//
// The probe's samples are drawn from streams of their own and used for nothing else: the
// start-up's size depends on how long they took, never on the values of the samples that
// estimate b, so b stays an unbiased estimate.
#pragma once
#include <atomic>
#include <cstdint>
#include <functional>

namespace ps {

// The share of the budget the start-up may take.
constexpr double kStartupShare = 0.25;

// How many samples to probe before a start-up of `planned` samples.
int64_t startupProbeSamples(int64_t planned);

// The fraction (<= 1) of the planned start-up samples that fits in kStartupShare of
// `timeLimit` seconds (0: no budget, 1), given that probe() takes `probed` samples (run
// twice, timed the second time; the probe's own time counts against the share). Every
// process calls it together (the slowest process's time decides, so all agree), the probe
// splitting its samples over the processes as the start-up does.
double startupFraction(double timeLimit, int64_t planned, int64_t probed, const std::function<void()>& probe);

// `count` scaled by `fraction`, at least `floor` (and never more than count).
int64_t scaledCount(int64_t count, double fraction, int64_t floor);

// The seed of the probe's own streams, for a render seeded with `seed`: apart from every
// stream the start-up and the chains draw from.
uint64_t startupProbeSeed(uint64_t seed);

}  // namespace ps
