// Adaptive sample placement (thesis ch. 2, "Adaptive sampling"; §5.3.1 for its use in
// rendering). Deciding how many samples to take from the samples themselves biases the
// estimate: the naive sequential rule stops more often right after a run of small values,
// when the sample variance happens to be low (Kirk and Arvo 1991). The two-stage scheme is
// unbiased: pilot samples only decide the allocation, and only fresh samples enter the estimate.
#pragma once
#include "mc/mc_estimate.h"
#include "mc/rng.h"

namespace ps {

// Independent samples until the estimated standard error falls to targetError (checked
// from minSamples on) or maxSamples are taken. Biased.
McEstimate estimateSequential(const Integrand& f, int dims, double targetError, int minSamples, int maxSamples,
                              Rng& rng);

struct TwoStageOptions {
    int cellsPerAxis = 4;   // strata: a grid over the first min(dims, 2) coordinates
    int pilotPerCell = 4;   // first stage (discarded after choosing the allocation)
    int budget = 1024;      // total evaluations, pilot included
};

// Stage 1: pilotPerCell samples per cell estimate each cell's standard deviation sigma_j.
// Stage 2: the rest of the budget is allocated in proportion to volume_j * sigma_j (Neyman
// allocation, optimal for stratified sampling), at least 2 per cell, and the estimate is
// sum_j volume_j * mean_j over stage-2 samples only. Unbiased.
McEstimate estimateTwoStage(const Integrand& f, int dims, const TwoStageOptions& options, Rng& rng);

}  // namespace ps
