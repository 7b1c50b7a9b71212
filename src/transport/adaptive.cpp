#include "transport/adaptive.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <numeric>

#include "render/distributed.h"
#include "transport/film_reduction.h"
#include "transport/sample_allocation.h"
#include "util/error.h"

namespace ps {

AdaptiveMode parseAdaptiveMode(const std::string& name) {
    if (name.empty() || name == "none") return AdaptiveMode::None;
    if (name == "sequential") return AdaptiveMode::Sequential;
    if (name == "twostage") return AdaptiveMode::TwoStage;
    throw InputError("unknown adaptive sampling mode \"" + name + "\" (available: sequential, twostage)");
}

namespace {

// The first, uniform share of the budget: a quarter, and at least enough for a variance.
int firstShare(int sppBudget) { return std::max(4, sppBudget / 4); }

// Camera samples taken so far by all processes, on rank 0 (elsewhere: this process's).
long long samplesOnRoot(const SamplePasses& passes) {
    std::vector<int64_t> n{passes.samplesDone()};
    distributed::sumToRoot(n);
    return n[0];
}

// The average samples per pixel the budget allows: spp, or fewer if at the rate measured
// so far the time limit would come first. Decided on rank 0, the same on every process.
int sppBudget(int spp, const SamplePasses& passes, const Monitor& monitor, size_t pixels) {
    if (monitor.timeLimit() <= 0) return spp;
    std::vector<int64_t> budget{samplesOnRoot(passes)};
    double rate = double(budget[0]) / std::max(monitor.elapsed(), 1e-6);
    double affordable = rate * monitor.timeLimit() / double(pixels);
    budget[0] = int64_t(std::clamp(affordable, 1.0, double(spp)));
    distributed::broadcastFromRoot(budget);
    return int(budget[0]);
}

// Every process's film summed into rank 0's (elsewhere left as it is).
void sumToRoot(Film& film) {
    if (distributed::size() == 1) return;
    Film::Accumulators sums = film.accumulators();
    distributed::sumToRoot(sums.fixed);
    distributed::sumToRoot(sums.counts);
    if (distributed::isRoot()) film.setAccumulators(sums);
}

// Brings every pixel of `film` up to target(i) samples, continuing its sample indices from
// have[i] (the samples it has from all processes, which each film holds only its share of;
// updated), in sub-passes of at most 64 samples per pixel (starting from 1 on an empty film,
// doubling), so that a stop request is honoured soon and leaves every pixel near the same
// count. The processes agree after every sub-pass whether to go on.
template <class Target>
bool fillTo(SamplePasses& passes, Film& film, std::vector<int>& have, SamplePasses::Stream stream, Target target) {
    int chunk = std::all_of(have.begin(), have.end(), [](int n) { return n == 0; }) ? 1 : 64;
    for (bool more = true; more; chunk = std::min(2 * chunk, 64)) {
        std::atomic<bool> unfinished{false};
        auto span = [&](size_t i) {
            int n = have[i], t = int(target(i));
            if (t > n + chunk) unfinished.store(true, std::memory_order_relaxed);
            return SampleSpan{n, std::max(n, std::min(t, n + chunk))};
        };
        if (distributed::anyOf(!passes.run(film, span, stream))) return false;
        for (size_t i = 0; i < have.size(); ++i) have[i] = span(i).end;
        more = unfinished.load();
    }
    return true;
}

// Stage-2 weights from the pilot: n_i proportional to the pixel's relative standard
// deviation per sample, sigma_i / sqrt(m_i^2 + eps), which minimises the summed relative
// variance sum_i sigma_i^2 / (n_i (m_i^2 + eps)) at a fixed total (the Neyman allocation of
// thesis ch. 2, with equal cost per sample). A few pilot samples estimate sigma_i poorly,
// above all for heavy-tailed path contributions, and a wrong allocation costs more than a
// uniform one, so (i) the relative variance is averaged over the pixel's 3x3 neighbourhood
// (neighbours mostly share their variance; 9x the pilot samples) and (ii) the weights are
// kept within [1/4, 4] x their mean, a defensive floor and cap. Both only use the pilot, so
// the image stays unbiased.
std::vector<double> twoStageWeights(const Film& pilot) {
    const int w = pilot.bounds().width(), h = pilot.bounds().height();
    std::vector<double> rel(pilot.pixelCount());
    for (size_t i = 0; i < rel.size(); ++i) {
        Film::PixelEstimate e = pilot.pixelEstimate(i);
        rel[i] = e.sampleVariance / (e.mean * e.mean + Film::kRelativeEpsilon);
    }
    std::vector<double> weight(rel.size());
    double mean = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double sum = 0;
            int n = 0;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    int xx = x + dx, yy = y + dy;
                    if (xx < 0 || yy < 0 || xx >= w || yy >= h) continue;
                    sum += rel[size_t(yy) * w + xx];
                    ++n;
                }
            double v = std::sqrt(sum / n);
            weight[size_t(y) * w + x] = v;
            mean += v / double(rel.size());
        }
    if (mean > 0)
        for (double& v : weight) v = std::clamp(v, 0.25 * mean, 4 * mean);
    return weight;
}

}  // namespace

bool renderSequential(SamplePasses& passes, Film& film, const Monitor& monitor, int spp) {
    using Stream = SamplePasses::Stream;
    const size_t pixels = film.pixelCount();
    std::vector<int> have(pixels, 0);
    // With a time limit, a short first pass measures the rate that sizes the rest.
    const int calibration = monitor.timeLimit() > 0 ? std::min(4, firstShare(spp)) : firstShare(spp);
    if (!fillTo(passes, film, have, Stream::Main, [&](size_t) { return calibration; })) return false;
    const int budget = sppBudget(spp, passes, monitor, pixels);
    if (!fillTo(passes, film, have, Stream::Main, [&](size_t) { return std::max(calibration, firstShare(budget)); }))
        return false;
    // Under a time limit the rounds go on until it stops them (or spp is reached).
    const long long total = (long long)(monitor.timeLimit() > 0 ? spp : budget) * (long long)pixels;
    // Each round refines the eighth of the pixels with the largest relative variance of
    // the mean (the film's own error measure, thesis §2.4), by half the first pass each.
    const size_t perRound = std::max<size_t>(1, pixels / 8);
    const int step = std::max(1, firstShare(budget) / 2);
    // Over several processes each round is chosen on rank 0 from the whole film (every
    // process's exact sums: one process's film) and sent to the others, so the rounds, and
    // the image, are one process's bit for bit; `have` counts every process's samples.
    const bool shared = distributed::size() > 1;
    std::unique_ptr<Film> whole;
    if (shared && distributed::isRoot()) whole = std::make_unique<Film>(film.xRes(), film.yRes(), film.bounds());
    std::vector<double> error(pixels);
    auto taken = [&] { return std::accumulate(have.begin(), have.end(), 0LL); };
    while (taken() < total) {
        if (shared) sumFilmInto(film, *whole);
        const long long remaining = total - taken();
        const size_t k = std::min<size_t>(perRound, size_t(remaining));
        const int add = int(std::min<long long>(step, remaining / (long long)k));
        std::vector<int64_t> chosen(k);
        if (distributed::isRoot()) {
            const Film& f = shared ? *whole : film;
            for (size_t i = 0; i < pixels; ++i) error[i] = f.pixelEstimate(i).relativeVariance();
            const std::vector<size_t> largest = largestK(error, k);
            std::copy(largest.begin(), largest.end(), chosen.begin());
        }
        distributed::broadcastFromRoot(chosen);
        std::vector<long long> target(have.begin(), have.end());
        for (int64_t i : chosen) target[size_t(i)] += add;
        if (!fillTo(passes, film, have, Stream::Main, [&](size_t i) { return target[i]; })) return false;
    }
    return true;
}

bool renderTwoStage(SamplePasses& passes, Film& film, Film& pilot, const Monitor& monitor, int spp) {
    using Stream = SamplePasses::Stream;
    const size_t pixels = film.pixelCount();
    std::vector<int> have(pixels, 0);
    const int calibration = monitor.timeLimit() > 0 ? std::min(4, firstShare(spp)) : firstShare(spp);
    if (!fillTo(passes, pilot, have, Stream::Pilot, [&](size_t) { return calibration; })) {
        sumToRoot(pilot);
        return false;
    }
    const int budget = sppBudget(spp, passes, monitor, pixels);
    if (!fillTo(passes, pilot, have, Stream::Pilot, [&](size_t) { return std::max(calibration, firstShare(budget)); })) {
        sumToRoot(pilot);
        return false;
    }
    // The allocation from the whole pilot (its exact sums: the same as one process's), on
    // rank 0, which sends it to the others.
    sumToRoot(pilot);
    const long long pilotSamples = samplesOnRoot(passes);
    std::vector<int64_t> alloc(pixels);
    if (distributed::isRoot()) {
        const std::vector<double> weight = twoStageWeights(pilot);
        long long secondStage = (long long)budget * (long long)pixels - pilotSamples;
        if (monitor.timeLimit() > 0) {
            double rate = double(pilotSamples) / std::max(monitor.elapsed(), 1e-6);
            secondStage = std::min(secondStage, (long long)(rate * std::max(0.0, monitor.timeLimit() - monitor.elapsed())));
        }
        const std::vector<int> n = proportionalAllocation(weight, secondStage, 1);
        std::copy(n.begin(), n.end(), alloc.begin());
    }
    distributed::broadcastFromRoot(alloc);
    // In growing passes, so a time limit leaves every pixel near the same fraction of its
    // allocation; where it leaves a pixel none, the pilot stands in (still unbiased: which
    // pixels those are depends on the clock, not on the samples).
    std::fill(have.begin(), have.end(), 0);
    for (double f : {0.125, 0.25, 0.5, 1.0})
        if (!fillTo(passes, film, have, Stream::Main, [&](size_t i) { return std::max(1.0, std::ceil(double(alloc[i]) * f)); }))
            return false;
    return true;
}

}  // namespace ps
