// Bidirectional path tracing (thesis ch. 10): one camera and one light subpath per pixel
// sample, every connection strategy (s light vertices, t camera vertices) evaluated and
// combined by multiple importance sampling (thesis ch. 9). Strategies with t = 1 land on
// other pixels and are splatted.
#pragma once
#include <memory>
#include <optional>
#include <vector>
#include "mc/mis.h"
#include "mc/primary_sample_sampler.h"
#include "transport/integrator.h"
#include "transport/path_tracer.h"
#include "transport/strategy_images.h"
#include "transport/subpaths.h"

namespace ps {

class BDPTIntegrator final : public Integrator {
public:
    // mis: how the strategies that can produce a path are weighted (thesis ch. 9, mc/mis.h).
    BDPTIntegrator(const Scene& scene, int maxDepth, MisWeighting mis = {});
    Spectrum Li(const Ray& ray, SampleContext& ctx) const override;
    bool splats() const override { return true; }
    bool supportsSpectral() const override { return true; }
    // Every strategy (s, t) up to maxdepth, at techniqueIndex(s, t) (--stats' figures); with a
    // light path share below 1, then the samples without a light subpath ("path").
    std::vector<RenderTechnique> techniques() const override;
    // Depth d = s + t - 2 holds t = 0 .. d + 2 after the d (d + 5) / 2 slots of smaller depths.
    static int techniqueIndex(int s, int t) {
        const int d = s + t - 2;
        return d * (d + 5) / 2 + t;
    }

    // One strategy's contribution for the subpath prefixes (s, t), unweighted, and its MIS
    // weight. For t = 1, *pRaster receives the film position. Exposed for tests.
    struct Connection {
        Spectrum L;          // unweighted contribution
        float weight = 0;    // MIS weight
        Vec2 pRaster;
        float recomputedWeight = 0;  // see recomputeWeights
        bool dispersive = false;     // see PathContribution (set by produce)
    };
    // Running sums of the MIS terms along each subpath (the terms of every heuristic multiply
    // along a path): camera[m] sums, over the strategies that would sample camera vertices
    // 1..m by connection, the terms of the density ratios from there to m; light[m] likewise
    // over light vertices 0..m. With them a weight costs O(1) instead of a walk along both
    // subpaths. Entries exist up to n - 2 (the last vertex has no reverse density yet).
    // The light sums include the s = 1 strategy's light choice (lightChoiceRatio of the light
    // subpath's first two vertices, kept in lightChoice).
    struct MisPrefixes {
        const double* camera = nullptr;
        const double* light = nullptr;
        float lightChoice = 1;
    };
    MisPrefixes misPrefixes(const PathVertex* light, int nLight, const PathVertex* camera, int nCamera,
                            ScratchBuffer& scratch) const;

    // S: Sampler, PaddedSobolSampler or IndependentSampler (as for Subpaths' walks).
    // `prefixes`: misPrefixes() of these subpaths, or null to walk them per weight.
    // `splatTo`: the camera sample whose film lens connections (t = 1) will splat to, warned
    // of the position before the visibility test (a cache hint), and whose wavelengths the
    // sampled light points emit at (spectral mode; null: RGB).
    // `lambda`: the wavelengths where splatTo is null (a Markov chain's sample).
    template <typename S>
    Connection connect(PathVertex* light, PathVertex* camera, int s, int t, S& sampler, PathStats& stats,
                       bool weighted = true, const MisPrefixes* prefixes = nullptr,
                       const SampleContext* splatTo = nullptr, const SampledWavelengths* lambda = nullptr,
                       const MediaSample* media = nullptr) const;
    // The reverse densities of the vertices at and next to a connection (area measure):
    // what the weight needs beyond the densities stored by the walks.
    struct EndpointDensities {
        float pt = 0, ptMinus = 0, qs = 0, qsMinus = 0;
        float lightChoice = -1;  // s = 1: Subpaths::lightChoiceRatio of the join (-1: evaluate it)
    };
    // The MIS weight of strategy (s, t) for the path its vertices form. `sampled` replaces
    // light[0] (s = 1) or camera[0] (t = 1): the vertex the connection itself sampled
    // (null: those entries already hold it).
    // `known`: the endpoint densities if the connection computed them (s, t > 1), else
    // they are evaluated here.
    float misWeight(const PathVertex* light, const PathVertex* camera, const PathVertex* sampled, int s, int t,
                    const EndpointDensities* known = nullptr, const MisPrefixes* prefixes = nullptr) const;
    const Subpaths& subpaths() const { return paths_; }

    // The dimension streams of one sample (see Sampler::startStream): the camera subpath
    // (after the film and lens position), the light subpath, and the connections.
    static constexpr int kCameraStream = 0, kLightStream = 1, kConnectionStream = 2, kStreamCount = 3;
    // In the connection stream each strategy reads its own block of values (a lens or light
    // point: at most 3), ordered by depth and then s.
    static constexpr int kDimensionsPerConnection = 3;
    static int connectionDimension(int s, int t) {
        int depth = s + t - 2;
        return kDimensionsPerConnection * (depth * (depth + 3) / 2 + s);
    }
    // One strategy's MIS-weighted contribution and where it lands on the film. `dispersive`
    // (spectral mode): its path has a dispersive vertex, so only the first wavelength counts;
    // otherwise all four do, even if the sample's other vertices terminated them (each
    // strategy's value is then an estimate of its own, whatever the subpaths beyond it did,
    // and one strategy evaluated alone gives the same).
    struct PathContribution {
        Vec2 pRaster;
        Spectrum L;
        int s = 0, t = 0;
        bool dispersive = false;
    };
    // Every strategy's weighted contribution of the camera subpath along `ray` (generated
    // at film position pFilm) and one light subpath, without depositing them: what a Markov
    // chain over primary samples (transport/mlt/) needs to know before it accepts a sample.
    // onlyDepth >= 0: the strategies of that path depth alone, from subpaths just long
    // enough for it: what strategyContribution gives for each of them (to rounding: the
    // compiler may fuse multiply-adds differently in the two code paths).
    // `lambda`: the sample's wavelengths in spectral mode (null: RGB); the contributions are
    // values at them.
    void contributions(const Ray& ray, Vec2 pFilm, PrimarySampleSampler& sampler, ScratchBuffer& scratch,
                       PathStats& stats, std::vector<PathContribution>& out, int onlyDepth = -1,
                       SampledWavelengths* lambda = nullptr) const;
    // Strategy (s, t) alone (multiplexed Metropolis): subpaths of exactly s light and t
    // camera vertices and their connection, MIS-weighted. False if the subpaths end
    // earlier or the connection carries nothing.
    bool strategyContribution(const Ray& ray, Vec2 pFilm, int s, int t, PrimarySampleSampler& sampler,
                              ScratchBuffer& scratch, PathStats& stats, PathContribution& out,
                              SampledWavelengths* lambda = nullptr) const;
    void setRoulette(bool on) { paths_.setRoulette(on); }
    // Whether the t = 0 strategy is used (thesis §10.2: light subpaths that reach the lens by
    // themselves, lens_hits.h): on by default through a thin lens, with or without media.
    // Multiplexed Metropolis, which samples one strategy (s, t >= 1) at a time, turns it off.
    bool lensHits() const { return lensHits_; }
    void disableLensHits();
    // The t = 0 strategy for one crossing of the lens by the light subpath: the path of
    // light[0 .. hit.index - 1] and the lens vertex, its contribution (beta We, landing at
    // pRaster) and MIS weight. Exposed for tests.
    Connection connectLens(const PathVertex* light, const LensHit& hit, ScratchBuffer& scratch,
                           const MisPrefixes* prefixes = nullptr) const;
    // The expected number of light subpaths per camera subpath, in (0, 1] (1: one each, the
    // classic pairing). Below 1 a camera sample is a whole BDPT sample with this probability
    // and a path tracer's sample otherwise: an unbiased mix of two estimators wherever both
    // sample a path, while the paths only light subpaths reach count 1 / share
    // (lightSubpathScale). Where light subpaths add little (mostly direct light), small
    // shares cost what path tracing costs. Rendering only: Metropolis keeps the pairing.
    void setLightPathShare(float share);
    float lightPathShare() const { return lightPathShare_; }
    // The factor of a strategy's contribution at the light path share: 1 / share for a path
    // that no sample without a light subpath could make, else 1. Exposed for tests.
    float lightSubpathScale(const PathVertex* light, int s, int t) const;
    // For tests: connect() also computes each weight from densities evaluated afresh at the
    // join, not those its BSDF evaluations produced, into Connection::recomputedWeight.
    void recomputeWeights(bool on) { recomputeWeights_ = on; }
    // Also record each strategy's contribution up to path depth maxDepth (memory: about
    // 12 bytes per pixel per strategy image); with lens hits, the t = 0 strategies' too.
    void recordStrategies(int maxDepth);
    const StrategyImages* strategyImages() const { return strategies_.get(); }
    StrategyImages* strategyImages() { return strategies_.get(); }

private:
    template <typename S, typename Deposit>
    void produce(const Ray& ray, S& sampler, ScratchBuffer& scratch, PathStats& stats, const SampleContext* splatTo,
                 Deposit&& deposit, int onlyDepth = -1, SampledWavelengths* lambda = nullptr) const;
    template <typename S>
    Spectrum estimate(const Ray& ray, S& sampler, SampleContext& ctx) const;

    // One strategy's path before weighting: its unweighted contribution (visibility
    // included), the endpoint densities where its BSDF evaluations gave them, and the
    // vertex it sampled (s = 1: on a light; t = 1: on the lens, landing at pRaster). The
    // join functions fill a fresh Join and leave L black where the strategy gives nothing.
    struct Join {
        Spectrum L;
        EndpointDensities known;
        bool haveKnown = false;
        std::optional<PathVertex> sampled;
        Vec2 pRaster;
        // Shadow-ray roulette (no media): the joins leave the visibility test from `from` to
        // `to` to connect(), which first knows the weighted contribution.
        bool deferVisibility = false;
        const PathVertex* from = nullptr;
        const PathVertex* to = nullptr;
        // Visibility of a and b now, or (deferVisibility) left to connect(): whether the
        // connection may carry light.
        bool visibleNowOrLater(const PathVertex& a, const PathVertex& b, const Subpaths& paths, PathStats& stats) {
            if (!deferVisibility) return paths.visible(a, b, stats);
            from = &a;
            to = &b;
            return true;
        }
    };
    // `media` (scenes with media): transmittance replaces visibility (Subpaths::connectThrough);
    // `stream`: the connection's Rng stream.
    void joinEmitter(const PathVertex* camera, int t, const SampledWavelengths* lambda, const MediaSample* media,
                     Join& j) const;
    template <typename S>
    void joinLens(const PathVertex& qs, S& sampler, PathStats& stats, const SampleContext* splatTo,
                  const MediaSample* media, uint64_t stream, Join& j) const;
    template <typename S>
    void joinLight(const PathVertex& pt, S& sampler, PathStats& stats, const SampledWavelengths* lambda,
                   const MediaSample* media, uint64_t stream, Join& j) const;
    void joinInner(const PathVertex& qs, const PathVertex& pt, PathStats& stats, const MediaSample* media,
                   uint64_t stream, Join& j) const;
    // joinInner where either vertex is in a medium: BSDFs or phase functions evaluated alone,
    // the weight's densities left to misWeight.
    void joinInnerInMedia(const PathVertex& qs, const PathVertex& pt, PathStats& stats, const MediaSample& media,
                          uint64_t stream, Join& j) const;
    // The t = 0 strategy's density of lens vertex `lens` over the camera's (1 / lens area),
    // from `rev`, the light walk's density there from its neighbour `next` per unit area
    // across the segment (lens vertices carry no normal: the lens cosine is applied here);
    // 0 without lens hits.
    float lensRatio(float rev, const PathVertex& lens, const PathVertex& next) const;
    // misWeight for the heuristics off the prefix-sum path (see general_).
    float weightFromEveryRatio(const PathVertex* light, const PathVertex* camera, const PathVertex* qs,
                               const PathVertex* pt, int s, int t, const EndpointDensities& rev, float choice) const;

    Subpaths paths_;
    MisWeighting mis_;
    // The prefix-sum path's heuristic (balance, power 2, uniform: their terms factor along
    // a path). general_: any other (power with another beta, cutoff, maximum), whose
    // weights take every strategy's density ratio one by one (weightFromEveryRatio).
    MisHeuristic heuristic_;
    bool general_ = false;
    std::unique_ptr<StrategyImages> strategies_;
    bool recomputeWeights_ = false;
    float lightPathShare_ = 1;
    std::unique_ptr<PathTracer> pathTracer_;  // the samples without a light subpath (share < 1)
    bool lensHits_ = false;
    // The technique after every strategy up to maxdepth (the first slot of depth maxdepth + 1):
    // the path tracer's samples.
    int pathTechniqueIndex() const { return techniqueIndex(paths_.maxDepth() + 3, 0); }
};

}  // namespace ps
