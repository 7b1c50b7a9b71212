// Drives an integrator over the image: tiles in parallel (oneTBB), sample passes, time
// budget and cancellation, progress on stderr, statistics.
#pragma once
#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>
#include "film/film.h"
#include "image/image.h"
#include "render/scene.h"
#include "transport/adaptive.h"
#include "transport/integrator.h"
#include "transport/render_monitor.h"

namespace ps {

struct CheckpointState;  // transport/checkpoint.h

struct RenderOptions {
    int spp = 16;
    double timeLimit = 0;        // seconds; 0 = none
    int threads = 0;             // 0 = all cores
    uint64_t seed = 0;
    std::string sampler = "sobol";  // see createSampler
    bool progress = true;        // progress bar on stderr
    ProgressCallback onProgress;  // also handed the progress bar's figures, when set (transport/render_monitor.h)
    const std::atomic<bool>* cancel = nullptr;  // set asynchronously (Ctrl-C) to stop early
    // Per-pixel sample counts (see transport/adaptive.h); spp is then the average. Not for
    // splatting integrators (light, bdpt): render() throws InputError.
    AdaptiveMode adaptive = AdaptiveMode::None;
    // Checkpoints (transport/checkpoint.h; uniform sampling, not Metropolis): continue from
    // `resume` (on rank 0 its sums; on every process where it stands), and after a whole pass,
    // once `checkpointEvery` seconds (>= 0) have passed since the last, sum the films on rank 0
    // and hand them to `checkpoint` there; and once more when the render stops early, with
    // the samples of the pass it stopped in (CheckpointState::partial).
    // A render that ends writes a last checkpoint too, so that a resume can raise --spp.
    const CheckpointState* resume = nullptr;
    double checkpointEvery = -1;
    // Where the sample sets after the first begin, ascending (uniform renders). A resume that
    // raises --spp from N starts a set at N: indices from N on come from a sampler of its own
    // seed sized for the new samples, so that both sets keep their stratification (each
    // sampler's points are laid out for its own count) and the image is an unbiased mean of
    // the two. Empty: one set, sized spp.
    std::vector<int> sampleSets;
    std::function<void(const CheckpointState&)> checkpoint;
    // What the result holds besides the image, for a caller that will not show or write it
    // to leave out: the error estimate (result.error and efficiency), the variance image and
    // the per-pixel sample counts. Without the first two the film keeps no luminance moments
    // (16 of its 56 bytes a pixel; a splatting film's half-buffers too), unless adaptive
    // sampling needs them.
    bool errorEstimate = true, varianceImage = true, pixelSamples = true;
    // Shadow-ray roulette (transport/shadow_roulette.h) in uniform renders: after each whole
    // pass, tau = shadowRoulette x the image's mean so far; 0: off.
    float shadowRoulette = 0;
    // `--stats`: each technique's figures (Integrator::techniques; uniform renders), and the
    // number K of independently scrambled sample sets the samples form (transport/
    // scrambled_sets.h), whose spread gives the variance (1: the samples' own). A pixel's
    // sample i is sample i / K of set i mod K, so that a render stopped early (`--time`) has
    // every set filled alike; not with sampleSets (resumes). The figures' variance comes from
    // `batches` batches of samples, each covering every pixel (the scrambled sets when there
    // are some; 1: s^2 / N of the samples).
    bool techniqueFigures = false;
    int batches = 1;
    int scramblings = 1;
    bool filmMoments() const { return errorEstimate || varianceImage || adaptive != AdaptiveMode::None; }
};

// What a Markov-chain render (transport/mlt/) adds to the statistics.
struct MetropolisStats {
    bool present = false;
    double b = 0;  // the integral of the target function over primary sample space
    int chains = 0;
    long long bootstrapSamples = 0, mutations = 0;
    long long pilotSamples = 0;  // multiplexed MLT: samples that learned the strategy choice
    long long twoStageSamples = 0;  // two-stage MLT: the pilot image's samples
    long long proposedLarge = 0, acceptedLarge = 0, proposedSmall = 0, acceptedSmall = 0;
    long long invalidProposals = 0;  // zero, negative or non-finite target: rejected, never splatted
    double bRelativeError = 0;      // standard error of b from the bootstrap, relative to b
    // Over several processes: per process, in rank order, the mutations its chains made and
    // their acceptance rate (rank 0's result; one entry without MPI).
    std::vector<long long> rankMutations;
    std::vector<double> rankAcceptance;
    bool multiplexed = false;       // the chains choose the path depth (proposals per depth)
    // Per path depth: its share of the image's luminance (sums to 1 over depths) and, when
    // the chains choose the depth, the proposals of that depth and how many were accepted,
    // and the probability with which a large step chooses it (the learned choice).
    struct Depth {
        double share = 0, chosen = 0;
        long long proposed = 0, accepted = 0;
        long long bootstrapSamples = 0;  // the bootstrap's samples of this depth (mmlt)
    };
    std::vector<Depth> depths;
    // Per mutation (Veach's MLT): proposals, those that failed before the acceptance test
    // (a ray escaped, a join was blocked: the chain stays) and acceptances.
    struct Kind {
        std::string name;
        long long proposed = 0, failed = 0, accepted = 0;
    };
    std::vector<Kind> kinds;
    static double rate(long long accepted, long long proposed) { return proposed ? double(accepted) / double(proposed) : 0.0; }
    double acceptanceRate() const {
        long long accepted = acceptedLarge + acceptedSmall, proposed = proposedLarge + proposedSmall;
        for (const Kind& k : kinds) {
            accepted += k.accepted;
            proposed += k.proposed;
        }
        return rate(accepted, proposed);
    }
};

// A render over several processes (render/distributed.h), as rank 0 reports it.
struct DistributedStats {
    int ranks = 1;
    std::vector<long long> rankSamples;  // per rank: camera samples taken
    std::vector<double> rankSeconds;     // per rank: render seconds
    double reductionBytes = 0;    // the film's sums, as each rank sends them to rank 0
    double reductionSeconds = 0;  // rank 0's time in the reductions
};

struct RenderResult {
    Image image;                 // the crop region, weighted mean per pixel
    Image variance;              // per pixel, the estimated variance of its mean luminance (Film::varianceImage)
    std::vector<int> pixelSamples;  // samples per pixel in the image (row-major crop region)
    double seconds = 0;
    double meanSpp = 0;          // samples actually taken per pixel, on average (a two-stage pilot included)
    double lightPaths = 0;       // splat normalisation: light paths traced / imaging ratio
    int targetSpp = 0;
    bool stoppedEarly = false;   // time budget or cancellation
    PathStats stats;
    long long rejectedSamples = 0;
    Film::ErrorEstimate error;  // per-pixel variance of the estimate, averaged over the image
    // Efficiency 1/(V T) with V the mean relative variance and T the render time (thesis eq. 2.26).
    double efficiency = 0;
    MetropolisStats metropolis;
    // RenderOptions::techniqueFigures: the integrator's techniques and their figures (one
    // more for the whole image), and the sets their variance came from (1: the samples' own).
    std::vector<RenderTechnique> techniques;
    std::vector<TechniqueTally::Figure> techniqueFigures;
    int techniqueBatches = 1;
    int scramblings = 1;
    std::vector<Image> depthImages;  // per path depth, if a Metropolis render was asked to record them
    DistributedStats distributed;
    int resumedSpp = 0;   // samples per pixel the render resumed from (RenderOptions::resume)
    int checkpoints = 0;  // checkpoints written
    std::string checkpointKept;  // what the last one holds ("64 spp in every pixel", ...)
};

// What a finished film gives every driver's result: the image (in the film's colour space),
// variance image, rejected samples, error estimate and efficiency (result.seconds set), splats
// normalised by lightPaths; what options leave out stays empty.
void filmResults(const Film& film, double lightPaths, const RenderSettings& settings, const RenderOptions& options,
                 RenderResult& result);

// Throws InputError if the integrator cannot render the scene with these options, or if the
// film would exceed the memory limit (util/memory_limit.h, naming the scene's Film
// directive): every process alike, before anything is allocated. render() starts with it.
void checkRenderable(const Scene& scene, const Integrator& integrator, const RenderOptions& options);

// Throws InputError as checkRenderable.
// Over several processes (render/distributed.h) every process calls it; each takes its share
// of the samples (Metropolis: of the chains), and rank 0's result holds the whole render, the
// same image as one process's; the others' results hold only their statistics.
RenderResult render(const Scene& scene, const Integrator& integrator, const RenderOptions& options);

}  // namespace ps
