// A render over several processes (render/distributed.h) ends, or checkpoints, by adding
// every process's film sums and counts on rank 0: exact integers, so the result is one
// process's, bit for bit, whatever the split of the samples.
#pragma once
#include <cstdint>
#include <vector>

#include "film/film.h"
#include "render/distributed.h"
#include "transport/checkpoint.h"
#include "transport/renderer.h"
#include "util/error.h"

namespace ps {

// Every process's film sums, plus a resumed render's, summed on rank 0 a chunk of pixels at
// a time through a small buffer, so that no process copies its whole film (for a large film
// the copy, new memory, costs many times the reduction: bench/README). Rank 0 gets each
// chunk as take(first pixel, end pixel, sums, counts) in Film::accumulators()'s layout, then
// the counts after the pixels' (splats, rejected samples) as take(pixels, pixels, {}, counts).
template <class Take>
void sumFilmToRoot(const Film& film, const CheckpointState* resume, Take take) {
    constexpr size_t kChunk = 4096;  // pixels: 640 KB of sums
    const size_t n = film.pixelCount(), k = Film::kPixelSums;
    if (resume && distributed::isRoot() && (resume->sums.fixed.size() != n * k || resume->sums.counts.size() != n + film.otherCounts().size()))
        throw InputError("--resume: the checkpoint's film has another size than this render's");
    std::vector<Fixed> fixed;
    std::vector<int64_t> counts;
    for (size_t b = 0; b < n; b += kChunk) {
        const size_t e = std::min(n, b + kChunk);
        fixed.resize((e - b) * k);
        counts.resize(e - b);
        film.pixelSums(b, e, fixed.data(), counts.data());
        distributed::sumToRoot(fixed);
        distributed::sumToRoot(counts);
        if (!distributed::isRoot()) continue;
        if (resume) {
            for (size_t i = 0; i < fixed.size(); ++i) fixed[i] += resume->sums.fixed[b * k + i];
            for (size_t i = 0; i < counts.size(); ++i) counts[i] += resume->sums.counts[b + i];
        }
        take(b, e, fixed, counts);
    }
    counts = film.otherCounts();
    distributed::sumToRoot(counts);
    if (!distributed::isRoot()) return;
    if (resume)
        for (size_t i = 0; i < counts.size(); ++i) counts[i] += resume->sums.counts[n + i];
    take(n, n, std::vector<Fixed>{}, counts);
}

// The samples and path statistics of every process (`samples` and `stats`: this process's),
// plus a resumed render's, summed on rank 0; false elsewhere.
bool sumCountsToRoot(long long& samples, PathStats& stats, const CheckpointState* resume);

// A checkpoint's sums: every process's film and the resumed render's, on rank 0 (false elsewhere).
bool sumAllToRoot(const Film& film, CheckpointState& state, const CheckpointState* resume);

// Rank 0's `whole` (a film of the same bounds, or `film` itself) gets the sum of every
// process's `film`; the others' is left as it is.
void sumFilmInto(const Film& film, Film& whole);

// Sums every process's film and statistics, and a resumed render's, into rank 0's (exact
// integer sums: the same bits as one process taking every sample); `samples` is this
// process's count (camera samples, or a Markov chain's mutations), which result.distributed
// reports per process with its seconds (result.seconds) and the reduction's cost. False on
// the other ranks, whose film is then partial.
bool reduceToRoot(Film& film, long long samples, RenderResult& result, const CheckpointState* resume = nullptr);

}  // namespace ps
