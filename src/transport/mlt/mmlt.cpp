#include "transport/mlt/mmlt.h"

#include <cmath>

namespace ps {

namespace {
// Depth 0 (an emitter seen directly) has one strategy, the camera ray finding it (its BDPT
// weight is 1); depth d > 0 has d + 2 (s = 0 .. d + 1).
int strategiesOfDepth(int depth) { return depth == 0 ? 1 : depth + 2; }
}  // namespace

MMLTIntegrator::MMLTIntegrator(const Scene& scene, int maxDepth, const MetropolisParams& params,
                               MisWeighting mis)
    : MetropolisIntegrator(scene, maxDepth, params, mis) {
    // The chain chooses each subpath's length: roulette would only add zeros to the target.
    bdpt_.setRoulette(false);
    // Its strategies are (s, t >= 1), one at a time: no t = 0 (coverage.h says so).
    bdpt_.disableLensHits();
    for (int d = 0; d <= this->maxDepth(); ++d) {
        firstOfDepth_.push_back(int(strategies_.size()));
        for (int s = 0; s < strategiesOfDepth(d); ++s) strategies_.emplace_back(d, s);
    }
}

StrategyChoice MMLTIntegrator::defaultChoice() const {
    // A camera that no connection reaches has no t = 1 strategy (s = d + 1): it gets none of
    // the samples of its depth.
    const bool lensConnects = scene_.camera().hasImportance();
    std::vector<float> w;
    for (const auto& [d, s] : strategies_) {
        const bool reachesLens = d == 0 || s < d + 1 || lensConnects;
        const int count = strategiesOfDepth(d) - (d > 0 && !lensConnects ? 1 : 0);
        w.push_back(reachesLens ? 1.0f / float(count) : 0.0f);
    }
    return {w, firstOfDepth_};
}

void MMLTIntegrator::bootstrapSample(PrimarySampleSampler& sampler, int depth, double scale,
                                     const StrategyChoice& choice, ChainEvaluator& ev,
                                     std::vector<BootstrapState>& out) const {
    out.clear();
    CameraSample cs = filmSample(sampler);
    SampledWavelengths* lambda = wavelengths(sampler, ev);
    float cameraWeight = 1;
    Ray ray = scene_.camera().generateRay(cs, &cameraWeight);
    ev.contributions.clear();
    if (cameraWeight > 0)
        bdpt_.contributions(ray, cs.pFilm, sampler, ev.scratch, ev.stats, ev.contributions, depth, lambda);
    ev.scratch.reset();
    for (BDPTIntegrator::PathContribution& c : ev.contributions) {
        c.L = toRendering(c, ev) * cameraWeight;
        const int k = firstOfDepth_[size_t(depth)] + c.s;
        const double B = ev.brightness(c.pRaster);
        const double weight = scale * c.L.luminance() / B;
        c.L /= choice.pmf(k);  // as evaluate scales it
        const double f = c.L.luminance() / B;
        if (std::isfinite(weight) && weight > 0 && std::isfinite(f) && f > 0) out.push_back({k, weight, f});
    }
}

void MMLTIntegrator::chooseStrategy(PrimarySampleSampler& sampler, int strategy, const StrategyChoice& choice,
                                    double u1, double u2) const {
    if (strategy < 0 || strategy >= choice.size()) return;
    double v1, v2;
    choice.place(strategy, u1, u2, v1, v2);
    sampler.set(kStrategyStream, 0, v1);
    sampler.set(kStrategyStream, 1, v2);
}

MetropolisIntegrator::PartialStepKind MMLTIntegrator::partialStepKind(const ChainState& x) const {
    if (x.strategy < 0 || x.strategy >= int(strategies_.size())) return kCameraSteps;
    const auto [depth, s] = strategies_[size_t(x.strategy)];
    return depth + 2 - s == 1 ? kLightSteps : kCameraSteps;
}

void MMLTIntegrator::evaluate(PrimarySampleSampler& sampler, const StrategyChoice& choice, ChainEvaluator& ev,
                              ChainState& out) const {
    out.splats.clear();
    out.f = 0;
    sampler.startStream(kStrategyStream);
    float pmf = 0;
    const float u1 = sampler.get1D();
    const int k = choice.sample(u1, sampler.get1D(), &pmf);
    const auto [depth, s] = strategies_[size_t(k)];
    const int t = depth + 2 - s;
    out.depth = depth;
    out.strategy = k;

    CameraSample cs = filmSample(sampler);
    SampledWavelengths* lambda = wavelengths(sampler, ev);
    float cameraWeight = 1;
    Ray ray = scene_.camera().generateRay(cs, &cameraWeight);
    BDPTIntegrator::PathContribution c;
    if (pmf > 0 && cameraWeight > 0 &&
        bdpt_.strategyContribution(ray, cs.pFilm, s, t, sampler, ev.scratch, ev.stats, c, lambda)) {
        c.L = toRendering(c, ev) * cameraWeight / pmf;
        const double f = c.L.luminance() / ev.brightness(c.pRaster);
        if (std::isfinite(f) && f > 0) {
            out.f = f;
            out.splats.push_back(c);
        }
    }
    ev.scratch.reset();
}

}  // namespace ps
