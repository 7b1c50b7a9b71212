// Adaptive sample placement in the renderer (thesis ch. 2, "Adaptive sampling", and §5.3.1):
// pixels get different numbers of samples, decided from samples already taken.
//
// Sequential: a uniform first pass, then rounds that give more samples to the pixels with
// the largest estimated relative error, until the budget is spent; every sample enters the
// image. Biased: a pixel stops being refined when its samples so far happen to agree, so
// pixels that have not yet seen a rare large value keep a low mean (Kirk and Arvo 1991).
//
// Two-stage: a pilot pass from an independently seeded sampler only estimates each
// pixel's variance and fixes the allocation; the pilot is then discarded and the image is
// the mean of the second-stage samples alone. As the second stage is independent of the
// pilot, each pixel's count is independent of its samples, and the image is unbiased.
#pragma once
#include <string>

#include "film/film.h"
#include "transport/render_monitor.h"
#include "transport/sample_passes.h"

namespace ps {

enum class AdaptiveMode { None, Sequential, TwoStage };

// "none", "sequential", "twostage"; throws InputError for other names.
AdaptiveMode parseAdaptiveMode(const std::string& name);

// Each takes an adaptive render's samples into `film` (non-splatting), spending spp samples
// per pixel on average, or less if the monitor's time limit comes first (the time budget is
// turned into a sample budget from the rate measured in the first pass). Returns false if
// stopped early (time limit or cancellation); the film is then still a correct image.
// Over several processes (render/distributed.h) every process calls them and takes its share
// of every pass; the processes agree after every pass whether to stop.
// Sequential: each round's pixels are chosen on rank 0 from every process's film summed
// there (a second film on rank 0), the same as one process's choice.
bool renderSequential(SamplePasses& passes, Film& film, const Monitor& monitor, int spp);
// `pilot`: an empty film of film's pixels, for the first stage. Rank 0 sums every process's
// pilot, computes the allocation from it and sends it to the others, so it is one process's
// allocation, and the image too, bit for bit. On return rank 0's pilot is the whole pilot:
// once the films are summed, film.adoptEmptyPixels(pilot) there fills the pixels a stop left
// without second-stage samples.
bool renderTwoStage(SamplePasses& passes, Film& film, Film& pilot, const Monitor& monitor, int spp);

}  // namespace ps
