// Metropolis light transport over BDPT (thesis ch. 11): the machinery every Markov-chain
// integrator shares, and the interface through which each gives its target function.
//
// A chain is not a per-camera-ray estimate, so these integrators have their own driver,
// renderMetropolis, which render() hands them to:
//  - bootstrap (bootstrap.h): N independent samples estimate b, the integral of the target
//    over primary sample space, and the chains' initial states are drawn from them in
//    proportion to their weights (no start-up bias, thesis ch. 11); each drawn sample is
//    replayed and must reproduce its weights bit for bit, and the state drawn from it its
//    target value (to 1e-5 where the state's own evaluation takes another code path);
//  - expected values: every iteration splats the current state with weight 1 - a and the
//    proposal with weight a, each contribution divided by its sample's target value;
//  - the image is scaled by b / (mutations made per film pixel), so an interrupted render
//    is normalised by the mutations it made;
//  - each chain owns its random streams (keyed by the seed and its index) and a fixed share
//    of the mutations, and splats accumulate in fixed point: the image does not depend on
//    the thread count;
//  - the chains' even and odd halves fill the film's two half-buffers, whose difference
//    gives the error estimate (independent chains, unlike the correlated samples of one).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>
#include "mc/primary_sample_sampler.h"
#include "transport/bdpt.h"
#include "transport/integrator.h"
#include "transport/mlt/pilot_importance.h"
#include "transport/mlt/strategy_choice.h"
#include "transport/renderer.h"
#include "transport/spectral_film.h"

namespace ps {

struct MetropolisParams {
    int bootstrapSamples = 100000;
    int chains = 1000;
    double largeStepProbability = 0.3;
    double sigma = 0.01;
    // Multiplexed MLT: the fraction of the bootstrap samples spent first on a pilot that
    // learns how often to choose each (depth, strategy) pair and how many of the bootstrap's
    // samples each depth gets; 0: no pilot (each depth and strategy equally).
    double strategyPilot = 0.1;
    // For tests: also record the image of each path depth (RenderResult::depthImages).
    bool depthImages = false;
    // The share of small steps that move only the camera subpath and the connection (a lens
    // perturbation in primary sample space).
    double cameraStepProbability = 0.5;
    // Two-stage MLT (pilot_importance.h): pilot samples, as a fraction of the bootstrap's,
    // make an image whose brightness per tile divides the target; 0: the plain target.
    double twoStage = 0;
    // Its black level (pilot_importance.h), in pixel luminance: the target evens the relative
    // error above it and leaves the absolute error below it as the plain target does.
    double twoStageBlackLevel = 0.1;
    // The pilot image's samples: twoStage times the bootstrap's (`bootstrap` of them, when a
    // time budget cut their number: startup_budget.h).
    int64_t twoStageSamples(int64_t bootstrap) const {
        return int64_t(std::ceil(twoStage * double(std::max<int64_t>(1, bootstrap))));
    }
    int64_t twoStageSamples() const { return twoStageSamples(bootstrapSamples); }
};

// A sample of a chain: its splats (each strategy's share of the path, at its film position)
// and its target value.
struct ChainState {
    std::vector<BDPTIntegrator::PathContribution> splats;
    double f = 0;
    int depth = -1;     // the path depth the sample chose (multiplexed MLT), else -1
    int strategy = -1;  // the strategy it chose (an index of the integrator's choice), else -1
};

// One of the states a bootstrap sample stands for: the strategy it chose (-1: the target
// chooses none), its weight (a chain starts from it in proportion; a sample's weights sum
// to its estimate of b) and its target value.
struct BootstrapState {
    int strategy = -1;
    double weight = 0, f = 0;
};

// One thread's tools for evaluating the sample a sampler holds.
struct ChainEvaluator {
    ScratchBuffer scratch;
    PathStats stats;
    ChainState sample;  // a bootstrap sample's own state
    std::vector<BDPTIntegrator::PathContribution> contributions;
    // Spectral mode: the wavelengths of the sample under evaluation, as drawn and as its
    // walks left them (a dispersive vertex terminates the secondary ones).
    SampledWavelengths lambda, lambdaAfterWalks;
    // Two-stage MLT: the pilot image whose brightness divides the target (null: none).
    const PilotImportance* importance = nullptr;
    double brightness(Vec2 pRaster) const { return importance ? importance->at(pRaster) : 1.0; }
};

class MetropolisIntegrator : public Integrator {
public:
    MetropolisIntegrator(const Scene& scene, int maxDepth, const MetropolisParams& params, MisWeighting mis);
    // Not a per-ray estimator: render() runs renderMetropolis instead.
    Spectrum Li(const Ray& ray, SampleContext& ctx) const final;
    bool splats() const final { return true; }
    bool supportsSpectral() const final { return true; }
    virtual const char* name() const = 0;
    // The sample the sampler holds (its iteration started): splats and target value. A
    // target that chooses among strategies chooses with the probabilities of `choice`.
    virtual void evaluate(PrimarySampleSampler& sampler, const StrategyChoice& choice, ChainEvaluator& ev,
                          ChainState& out) const = 0;
    // The target's discrete choice among strategies with its default probabilities, which
    // the driver may replace by learned ones (its groups are the path depths); empty if the
    // target makes no such choice.
    virtual StrategyChoice defaultChoice() const { return {}; }
    // Dimension streams the target reads.
    virtual int streamCount() const { return BDPTIntegrator::kStreamCount; }
    // Bootstrap samples for the parameter's count (multiplexed MLT: per path depth; the
    // pilot that learns the strategy choice included).
    virtual int64_t bootstrapCount() const { return params_.bootstrapSamples; }
    // Groups of bootstrap samples (multiplexed MLT: the path depths) and the relative cost
    // of a sample of each: the bootstrap learns how many samples each group gets.
    virtual int bootstrapGroups() const { return 1; }
    virtual double groupCost(int) const { return 1; }
    // A bootstrap sample of `group` (the sampler's first iteration under way): the states
    // with positive weight it stands for, each weighted by `scale` times its part of the
    // target's integral. By default the sample itself, weighted by scale times its target
    // value. A chain started from one of the states replays this call, then chooseStrategy
    // and evaluate in the same iteration.
    virtual void bootstrapSample(PrimarySampleSampler& sampler, int group, double scale, const StrategyChoice& choice,
                                 ChainEvaluator& ev, std::vector<BootstrapState>& out) const;
    // Places the values that make evaluate choose `strategy`: at (u1, u2) in [0,1)^2 within
    // their intervals of `choice`.
    virtual void chooseStrategy(PrimarySampleSampler&, int /*strategy*/, const StrategyChoice&, double /*u1*/,
                                double /*u2*/) const {}
    // Whether the chain itself chooses a path depth (per-depth acceptance statistics).
    virtual bool choosesDepth() const { return false; }
    // The partial small steps (primary_sample_sampler.h) a state takes: camera steps move the
    // camera subpath and the connection, light steps the light subpath and the connection.
    // A state whose camera subpath is the lens vertex alone (t = 1) takes light steps, as a
    // camera step could not move it under a pinhole. Neither kind moves the strategy that
    // decides the kind, so the kernel stays symmetric.
    enum PartialStepKind : size_t { kCameraSteps = 0, kLightSteps = 1 };
    virtual PartialStepKind partialStepKind(const ChainState&) const { return kCameraSteps; }

    // A whole BDPT sample from the sampler (every depth, every strategy, each contribution
    // in the rendering space's RGB at its film position): pssmlt's state, and two-stage MLT's
    // pilot samples for every variant.
    void bdptSample(PrimarySampleSampler& sampler, ChainEvaluator& ev,
                    std::vector<BDPTIntegrator::PathContribution>& out) const;

    const BDPTIntegrator& bdpt() const { return bdpt_; }
    int maxDepth() const { return bdpt_.subpaths().maxDepth(); }
    const MetropolisParams& params() const { return params_; }
    MetropolisParams& params() { return params_; }

protected:
    // The film position, uniform over the film widened by the filter radius (the area over
    // which the film normalises splats, Film::image), and the lens position: the first
    // four values of the camera stream.
    CameraSample filmSample(PrimarySampleSampler& sampler) const;
    // Spectral mode: the sample's wavelengths, from a camera-stream value past the path's
    // time (a primary sample like any other: mutations move it, rejections restore it),
    // held in ev; the walks' copy (ev.lambdaAfterWalks), or null in RGB mode. Call after
    // filmSample.
    SampledWavelengths* wavelengths(PrimarySampleSampler& sampler, ChainEvaluator& ev) const;
    // A contribution at the sample's wavelengths as the chain takes it: the rendering space's
    // RGB, whose luminance is the target (as in RGB mode) and which is what is splatted.
    // Only a strategy through a dispersive vertex loses the secondary wavelengths.
    Spectrum toRendering(const BDPTIntegrator::PathContribution& c, const ChainEvaluator& ev) const {
        return sensor_ ? sensor_->toRendering(c.L, c.dispersive ? ev.lambdaAfterWalks : ev.lambda) : c.L;
    }

    const Scene& scene_;
    BDPTIntegrator bdpt_;
    MetropolisParams params_;
    Vec2 margin_, filmSize_;
    std::optional<SpectralFilm> sensor_;  // spectral mode's sensor (empty in RGB mode)
};

// The end of every Markov-chain render: the image from the film's splats scaled by
// b / mutations (result.metropolis holds both), the sample counts and whether it stopped
// early (`total`: the mutations asked); returns the film's "light paths" normalisation.
double finishChains(const Scene& scene, const Film& film, const RenderOptions& options, long long total,
                    bool bootstrapCancelled, RenderResult& result);

// The Markov-chain driver: options.spp is the number of mutations per film pixel (crop
// region); threads, seed, time limit, cancellation and progress as for render().
// Throws InputError for what the integrator does not render (before any work: every process alike).
RenderResult renderMetropolis(const Scene& scene, const MetropolisIntegrator& integrator, const RenderOptions& options);

}  // namespace ps
