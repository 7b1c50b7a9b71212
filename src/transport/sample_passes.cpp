#include "transport/sample_passes.h"

#include <algorithm>

#include <tbb/parallel_for.h>

#include "mc/rng.h"
#include "render/distributed.h"
#include "transport/renderer.h"
#include "util/error.h"

namespace ps {

namespace {

constexpr int kTileSize = 16;

}  // namespace

SamplePasses::SamplePasses(const Scene& scene, const Integrator& integrator, const RenderOptions& options,
                           std::atomic<bool>& stop, std::atomic<long long>& samplesDone)
    : scene_(scene), integrator_(integrator), stop_(stop), samplesDone_(samplesDone),
      imagingRatio_(scene.settings().imagingRatio), hasLens_(scene.camera().usesLensSample()),
      hasMotion_(scene.hasMotion()), rouletteSeed_(mix64(options.seed ^ 0x243f6a8885a308d3ULL)), share_{distributed::rank(), distributed::size()},
      states_([this] {
          ThreadState s;
          for (const std::unique_ptr<Sampler>& p : prototypes_) s.samplers.push_back(p->clone());
          if (techniqueCount_ > 0) {
              const PixelBounds& b = scene_.pixelBounds();
              s.tally = TechniqueTally(techniqueCount_, batchCount_, Vec2(float(b.x0), float(b.y0)),
                                       Vec2(float(b.x1), float(b.y1)));
          }
          return s;
      }),
      arena_(options.threads > 0 ? options.threads : tbb::task_arena::automatic) {
    const PixelBounds& b = scene.pixelBounds();
    for (int y = b.y0; y < b.y1; y += kTileSize)
        for (int x = b.x0; x < b.x1; x += kTileSize)
            tiles_.push_back({x, std::min(x + kTileSize, b.x1), y, std::min(y + kTileSize, b.y1)});
    const int spp = std::max(1, options.spp);
    const int resolution = std::max(scene.camera().params().xRes, scene.camera().params().yRes);
    setStarts_.push_back(0);
    if (options.scramblings > 1) {
        interleave_ = options.scramblings;  // sets i mod K (RenderOptions::scramblings)
        setStarts_.assign(size_t(interleave_), 0);
    } else {
        for (int start : options.sampleSets)
            if (start > setStarts_.back() && start < spp) setStarts_.push_back(start);
    }
    if (scene.settings().spectral) spectral_.emplace(scene.settings());
    if (options.techniqueFigures) {
        techniqueCount_ = int(integrator.techniques().size());
        // Batches of whole passes over the image: their means are independent (the scrambled
        // sets, or independent samples) and each respects the pixels' stratification, which
        // s^2 / N over all samples would count as noise.
        // The scrambled sets are the batches; independent samples are dealt to them in turn (so
        // that a render stopped early fills them evenly); one scrambled sequence is cut into
        // ranges (every K-th point of it would be a structured subset, far from its mean).
        batchCount_ = interleave_ > 1 ? interleave_ : std::max(1, options.batches);
        interleavedBatches_ = interleave_ > 1 || options.sampler == "independent";
        if (!interleavedBatches_) batchStarts_ = scramblingStarts(spp, batchCount_);
        // Film::image gives a splat the widened film's pixel count over the light paths (the
        // samples over the imaging ratio): over the crop's pixels, this much of the mean.
        const Vec2 r = scene.filter().radius();
        const Camera::Params& cp = scene.camera().params();
        splatScale_ = double(imagingRatio_) * (cp.xRes + 2.0 * r.x) * (cp.yRes + 2.0 * r.y) / double(b.area());
    }
    if (options.scramblings > 1 && int(setStarts_.size()) == options.scramblings) {
        // The half-images are summed over processes with the film; the pixels' set sums are
        // each process's, so over several processes their variance is s^2 / n again.
        if (integrator.splats()) scrambledHalves_ = true;
        else if (share_.count == 1) scrambled_ = std::make_unique<ScrambledPixelVariance>(size_t(b.area()), options.scramblings);
    }
    // The pilot of a two-stage render and every later sample set draw from samplers of their
    // own seeds; the first set's is the render's seed itself.
    for (uint64_t stream : {0, 1})
        for (size_t set = 0; set < setStarts_.size(); ++set) {
            const uint64_t seed = stream == 0 && set == 0 ? options.seed
                                  : stream == 1 && set == 0 ? mix64(options.seed ^ 0x5bd1e9955bd1e995ULL)
                                                            : mixWithKey(mix64(options.seed ^ (0x9e3779b97f4a7c15ULL * stream)), set);
            const int count = interleave_ > 1 ? (spp - int(set) + interleave_ - 1) / interleave_
                                              : (set + 1 < setStarts_.size() ? setStarts_[set + 1] : spp) - setStarts_[set];
            prototypes_.push_back(createSampler(options.sampler, seed, count, resolution));
            if (!prototypes_.back()) {
                std::string names;
                for (const std::string& n : samplerNames()) names += (names.empty() ? "" : ", ") + n;
                throw InputError("unknown sampler \"" + options.sampler + "\" (available: " + names + ")");
            }
        }
}

bool SamplePasses::run(Film& film, const std::function<SampleSpan(size_t)>& spanOf, Stream stream,
                       std::vector<uint64_t>* taken) {
    const Filter& filter = scene_.filter();
    const PixelBounds& b = film.bounds();
    std::atomic<bool> skipped{false};
    arena_.execute([&] {
        tbb::parallel_for(size_t(0), tiles_.size(), [&](size_t ti) {
            if (stop_.load(std::memory_order_relaxed)) {
                skipped = true;
                return;
            }
            ThreadState& st = states_.local();
            const size_t sets = setStarts_.size();
            const Tile& t = tiles_[ti];
            long long count = 0;
            for (int py = t.y0; py < t.y1; ++py)
                for (int px = t.x0; px < t.x1; ++px) {
                    const size_t pixel = size_t(py - b.y0) * size_t(b.width()) + size_t(px - b.x0);
                    SampleSpan span = spanOf(pixel);
                    // The first index of this process's share, then every share_.count-th.
                    const int first = span.begin + int((size_t(share_.index) + size_t(share_.count) -
                                                        (pixel + size_t(span.begin)) % size_t(share_.count)) %
                                                       size_t(share_.count));
                    uint64_t mine = 0;
                    for (int si = first; si < span.end; si += share_.count) {
                        const int k = si - span.begin;
                        if (k < 64 && (span.taken >> k & 1)) continue;
                        if (taken) mine |= uint64_t(1) << k;
                        ++count;
                        const SetIndex at = setOf(si);
                        const size_t set = size_t(at.set);
                        Sampler& sampler = *st.samplers[size_t(stream) * sets + set];
                        sampler.startPixelSample(px, py, at.index);
                        FilterSample fs = filter.sample(sampler.getPixel2D());
                        CameraSample cs;
                        cs.pFilm = {px + 0.5f + fs.offset.x, py + 0.5f + fs.offset.y};
                        cs.pLens = hasLens_ ? sampler.get2D() : Vec2(0.5f, 0.5f);
                        if (hasMotion_) cs.time = sampler.get1D();
                        // Spectral mode: the sample's wavelengths, from the next dimension.
                        SampledWavelengths lambda;
                        if (spectral_) lambda = SpectralFilm::sampleWavelengths(sampler.get1D());
                        float cameraWeight = 1;
                        Ray ray = scene_.camera().generateRay(cs, &cameraWeight);
                        // The half-buffer a splatting film puts the sample in: its index's parity,
                        // or with scrambled sets, the half of the sets it belongs to.
                        const int half = scrambledHalves_ ? int(2 * set >= setStarts_.size()) : si;
                        SampleContext ctx{sampler, st.scratch, st.stats, film, half, px, py, fs.weight, nullptr, nullptr, {}};
                        if (spectral_) {
                            ctx.lambda = &lambda;
                            ctx.sensor = &*spectral_;
                        }
                        if (techniqueCount_ > 0) ctx.tally = &st.tally;
                        if (shadowTau_ > 0)
                            ctx.roulette = {shadowTau_, hashCombine(hashCombine(rouletteSeed_, pixel), uint64_t(si)),
                                            ctx.sensor, ctx.lambda};
                        // A ray the lens blocks is a black sample (still counted).
                        Spectrum L = cameraWeight > 0 ? integrator_.Li(ray, ctx) * cameraWeight : Spectrum(0.0f);
                        if (spectral_) L = spectral_->toRendering(L, lambda);
                        st.scratch.reset();
                        if (techniqueCount_ > 0) {
                            // Interleaved batches are the scrambled sets when there are some.
                            const int batch = interleavedBatches_ ? si % batchCount_
                                                                  : int(std::upper_bound(batchStarts_.begin(),
                                                                                         batchStarts_.end(), si) -
                                                                        batchStarts_.begin());
                            st.tally.endSample(batch, double(cameraWeight) * imagingRatio_ * fs.weight, splatScale_,
                                               fs.weight);
                        }
                        if (scrambled_) scrambled_->add(int(set), pixel, double((L * imagingRatio_).luminance()));
                        film.addSample(px, py, L * imagingRatio_, fs.weight, half);
                    }
                    if (taken) (*taken)[pixel] |= mine;
                }
            samplesDone_.fetch_add(count, std::memory_order_relaxed);
        });
    });
    return !skipped.load();
}

SamplePasses::SetIndex SamplePasses::setOf(int si) const {
    if (interleave_ > 1) return {si % interleave_, si / interleave_};
    const int set = int(std::upper_bound(setStarts_.begin(), setStarts_.end(), si) - setStarts_.begin()) - 1;
    return {set, si - setStarts_[size_t(set)]};
}

TechniqueTally SamplePasses::techniqueTally() const {
    TechniqueTally total;
    for (const ThreadState& st : states_) total.merge(st.tally);
    return total;
}

PathStats SamplePasses::stats() const {
    PathStats total;
    for (const ThreadState& st : states_) total += st.stats;
    return total;
}

}  // namespace ps
