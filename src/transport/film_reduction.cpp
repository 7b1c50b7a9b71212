#include "transport/film_reduction.h"

namespace ps {

bool sumCountsToRoot(long long& samples, PathStats& stats, const CheckpointState* resume) {
    std::vector<int64_t> n{samples, int64_t(stats.cameraPaths), int64_t(stats.lightPaths), int64_t(stats.rays),
                           int64_t(stats.shadowRays), int64_t(stats.guarded),
                           int64_t(stats.shadowRaysSkipped)};
    distributed::sumToRoot(n);
    if (!distributed::isRoot()) return false;
    samples = n[0] + (resume ? resume->samples : 0);
    stats = {uint64_t(n[1]), uint64_t(n[2]), uint64_t(n[3]), uint64_t(n[4]), uint64_t(n[5]), uint64_t(n[6])};
    if (resume) stats += resume->stats;
    return true;
}

bool sumAllToRoot(const Film& film, CheckpointState& state, const CheckpointState* resume) {
    if (distributed::isRoot()) {
        state.sums.fixed.reserve(film.pixelCount() * Film::kPixelSums);
        state.sums.counts.reserve(film.pixelCount() + 1);
    }
    sumFilmToRoot(film, resume, [&](size_t, size_t, const std::vector<Fixed>& fixed, const std::vector<int64_t>& counts) {
        state.sums.fixed.insert(state.sums.fixed.end(), fixed.begin(), fixed.end());
        state.sums.counts.insert(state.sums.counts.end(), counts.begin(), counts.end());
    });
    return sumCountsToRoot(state.samples, state.stats, resume);
}

void sumFilmInto(const Film& film, Film& whole) {
    sumFilmToRoot(film, nullptr, [&](size_t b, size_t e, const std::vector<Fixed>& fixed, const std::vector<int64_t>& counts) {
        if (b < e) whole.setPixelSums(b, e, fixed.data(), counts.data());
        else whole.setOtherCounts(counts);
    });
}

bool reduceToRoot(Film& film, long long samples, RenderResult& result, const CheckpointState* resume) {
    DistributedStats& d = result.distributed;
    d.ranks = distributed::size();
    distributed::Purpose purpose("film");
    for (double n : distributed::gatherToRoot(double(samples))) d.rankSamples.push_back((long long)n);
    d.rankSeconds = distributed::gatherToRoot(result.seconds);
    if (d.ranks == 1 && !resume) return true;
    sumFilmToRoot(film, resume, [&](size_t b, size_t e, const std::vector<Fixed>& fixed, const std::vector<int64_t>& counts) {
        if (b < e) film.setPixelSums(b, e, fixed.data(), counts.data());
        else film.setOtherCounts(counts);
    });
    const bool root = sumCountsToRoot(samples, result.stats, resume);
    d.reductionBytes = distributed::traffic().bytes;  // every collective so far (the caller may add later ones)
    d.reductionSeconds = distributed::traffic().seconds;
    return root;
}

}  // namespace ps
