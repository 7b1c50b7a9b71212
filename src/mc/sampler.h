// Sample placement behind one interface: for pixel (x, y) and sample index i, a
// deterministic stream of 1-D and 2-D values, independent of which thread asks.
#pragma once
#include <cstdint>
#include <memory>
#include "math/vec.h"
#include "mc/rng.h"

namespace ps {

class Sampler {
public:
    virtual ~Sampler() = default;
    virtual void startPixelSample(int px, int py, int sampleIndex) = 0;
    virtual float get1D() = 0;
    virtual Vec2 get2D() = 0;
    // The film position within the pixel (its own dimension pair).
    virtual Vec2 getPixel2D() { return get2D(); }
    virtual std::unique_ptr<Sampler> clone() const = 0;
};

// Independent uniform samples (thesis §2.7.1's baseline): one PCG stream per pixel sample.
class IndependentSampler final : public Sampler {
public:
    explicit IndependentSampler(uint64_t seed) : seed_(seed) {}
    void startPixelSample(int px, int py, int sampleIndex) override {
        uint64_t pixel = (uint64_t(uint32_t(px)) << 32) | uint32_t(py);
        rng_.seed(hashCombine(mix64(pixel), seed_), mix64(uint64_t(sampleIndex) ^ (seed_ << 20)));
    }
    float get1D() override { return rng_.uniform(); }
    Vec2 get2D() override {
        float a = rng_.uniform();
        return {a, rng_.uniform()};
    }
    std::unique_ptr<Sampler> clone() const override { return std::make_unique<IndependentSampler>(seed_); }

private:
    uint64_t seed_;
    Rng rng_;
};

}  // namespace ps
