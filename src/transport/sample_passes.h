// Runs passes of camera samples over the film: each pass takes, for every pixel, a range
// of sample indices (the same for all pixels in a uniform render, per pixel in an adaptive
// one), with tiles in parallel (oneTBB). Results do not depend on the thread schedule:
// every pixel's samples are a function of (pixel, sample index, seed) and a tile owns its pixels.
// In a render over K processes (render/distributed.h) each takes its share of every range:
// sample i of pixel p belongs to process (p + i) mod K, so even a one-sample pass is split
// evenly, and the films of all processes add up to the film of one (Film::accumulators).
#pragma once
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/task_arena.h>

#include "film/film.h"
#include "render/scene.h"
#include "transport/integrator.h"
#include "transport/scrambled_sets.h"
#include "transport/spectral_film.h"
#include "transport/technique_tally.h"

namespace ps {

struct RenderOptions;

struct SampleSpan {
    int begin = 0, end = 0;  // sample indices [begin, end) of one pixel
    // Bit k set: index begin + k was taken before (by an interrupted pass a checkpoint
    // recorded) and is skipped. Only for spans of at most 64 indices.
    uint64_t taken = 0;
};

class SamplePasses {
public:
    // Which sample stream: the pilot of a two-stage render draws from an independently
    // seeded sampler, so its samples are independent of those that enter the image.
    enum class Stream { Main = 0, Pilot = 1 };

    SamplePasses(const Scene& scene, const Integrator& integrator, const RenderOptions& options,
                 std::atomic<bool>& stop, std::atomic<long long>& samplesDone);

    // spanOf(pixel index in the crop region, row-major) -> the indices to take there.
    // Tiles not started when `stop` is raised are skipped; returns false if that happened.
    // `taken` (one entry per pixel, spans of at most 64 indices): gains the bits, relative to
    // each span's begin, of the samples this process took, so that an interrupted pass can
    // be continued exactly (by any number of processes).
    bool run(Film& film, const std::function<SampleSpan(size_t pixel)>& spanOf, Stream stream = Stream::Main,
             std::vector<uint64_t>* taken = nullptr);
    bool stopped() const { return stop_.load(); }
    long long samplesDone() const { return samplesDone_.load(); }
    size_t pixelCount() const { return size_t(scene_.pixelBounds().area()); }
    PathStats stats() const;
    // This process's share: samples with (pixel + index) mod count == index.
    struct Share {
        int index = 0, count = 1;
    };
    Share share() const { return share_; }
    // The shadow-ray roulette's threshold for the passes that follow (0: off); between passes.
    void setShadowTau(float tau) { shadowTau_ = tau; }
    // RenderOptions::techniqueFigures: every thread's technique sums, merged (empty if off).
    TechniqueTally techniqueTally() const;
    int techniqueBatches() const { return batchCount_; }
    // RenderOptions::scramblings > 1 for a film of the pixels' own samples: its error estimate
    // from the sets' spread (transport/scrambled_sets.h); null otherwise.
    const ScrambledPixelVariance* scrambledVariance() const { return scrambled_.get(); }
    // Whether the error estimate comes from the scrambled sets (the pixels' or the half-images').
    bool scramblingsEstimate() const { return scrambledHalves_ || scrambled_; }

private:
    struct Tile {
        int x0, x1, y0, y1;
    };
    // Per stream, then per sample set (RenderOptions::sampleSets): sampler stream * sets + set.
    struct ThreadState {
        std::vector<std::unique_ptr<Sampler>> samplers;
        ScratchBuffer scratch;
        PathStats stats;
        TechniqueTally tally;  // --stats' technique figures (empty: off)
    };

    const Scene& scene_;
    const Integrator& integrator_;
    std::atomic<bool>& stop_;
    std::atomic<long long>& samplesDone_;
    std::vector<Tile> tiles_;
    const float imagingRatio_;
    const bool hasLens_;
    const bool hasMotion_;  // the camera sample draws a time (only then: static scenes keep their streams)
    float shadowTau_ = 0;         // setShadowTau
    uint64_t rouletteSeed_ = 0;   // the roulette's numbers: a hash of it, the pixel and the sample index
    std::optional<SpectralFilm> spectral_;  // spectral mode's sensor (empty in RGB mode)
    Share share_;
    // The sample set of a pixel's sample index, and its index within the set.
    struct SetIndex {
        int set, index;
    };
    SetIndex setOf(int si) const;
    std::vector<int> setStarts_;  // 0, then RenderOptions::sampleSets (ranges; one entry a set if interleaved)
    int interleave_ = 1;          // RenderOptions::scramblings > 1: sample i in set i mod K at index i / K
    double splatScale_ = 0;       // a unit splat's share of the image mean (Film::image's normalisation)
    int techniqueCount_ = 0;      // RenderOptions::techniqueFigures: the integrator's techniques (0: off)
    // The technique figures' batches (RenderOptions::batches): the scrambled sets, sample i in
    // batch i mod K (independent samples), or ranges of indices with batches 2..K beginning
    // at batchStarts_.
    int batchCount_ = 1;
    bool interleavedBatches_ = false;
    std::vector<int> batchStarts_;
    // RenderOptions::scramblings > 1: the sample sets are independent scramblings. A splatting
    // film's two half-images then take the first and the last half of the sets (not even and
    // odd indices, which one scrambled point set correlates); other films keep their sets'
    // sums per pixel here.
    bool scrambledHalves_ = false;
    std::unique_ptr<ScrambledPixelVariance> scrambled_;
    std::vector<std::unique_ptr<Sampler>> prototypes_;
    tbb::enumerable_thread_specific<ThreadState> states_;
    tbb::task_arena arena_;
};

}  // namespace ps
