// How correlated a Markov chain's samples are (thesis ch. 2, "The Metropolis method"): the
// integrated autocorrelation time tau = 1 + 2 sum_{k>=1} rho_k, so that the mean of N chain
// samples has the variance of N / tau independent ones (the effective sample size).
#pragma once
#include <span>

namespace ps {

struct AutocorrelationSummary {
    double tau = 1;  // integrated autocorrelation time (1 for independent samples)
    double ess = 0;  // effective sample size N / tau
    int lags = 0;    // lags summed
};

// Geyer's initial positive sequence estimator (Geyer 1992): sums the autocovariances in
// pairs Gamma_m = gamma_2m + gamma_2m+1 while Gamma_m stays positive, which keeps the
// noisy tail of the autocorrelation function out of the sum. tau may fall below 1 for
// negatively correlated chains (then ESS > N). A constant series gives tau = 1.
AutocorrelationSummary integratedAutocorrelation(std::span<const double> series);

}  // namespace ps
