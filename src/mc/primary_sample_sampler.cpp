#include "mc/primary_sample_sampler.h"

#include <algorithm>
#include <cmath>

#include "mc/metropolis.h"

namespace ps {

PrimarySampleSampler::PrimarySampleSampler(uint64_t chainSeed, const PrimarySampleParams& params)
    : params_(params) {
    if (params_.streamCount < 1) params_.streamCount = 1;
    streamIndex_.assign(size_t(params_.streamCount), 0);
    smallSteps_.assign(size_t(params_.streamCount), 0);
    streams_.resize(size_t(params_.streamCount));
    reseed(chainSeed);
}

void PrimarySampleSampler::reseed(uint64_t chainSeed) {
    rng_.seed(mix64(chainSeed), chainSeed ^ 0x2545f4914f6cdd1dULL);
    normals_.reset();
}

void PrimarySampleSampler::save(ByteWriter& out) const {
    out.put(rng_);
    out.put(normals_);
    out.put(iteration_);
    out.put(lastLargeStep_);
    out.put(uint8_t(largeStep_));
    out.put(uint32_t(streams_.size()));
    for (const std::vector<Value>& s : streams_) out.putVector(s);
    out.putVector(smallSteps_);
}

void PrimarySampleSampler::load(ByteReader& in) {
    rng_ = in.get<Rng>();
    normals_ = in.get<NormalPairs>();
    iteration_ = in.get<int64_t>();
    lastLargeStep_ = in.get<int64_t>();
    largeStep_ = in.get<uint8_t>() != 0;
    if (in.get<uint32_t>() != streams_.size()) in.fail();
    for (std::vector<Value>& s : streams_) s = in.getVector<Value>();
    smallSteps_ = in.getVector<double>();
    if (smallSteps_.size() != streams_.size()) in.fail();
    touched_.clear();
    restartStreams();
}

void PrimarySampleSampler::restartStreams() {
    stream_ = 0;
    std::fill(streamIndex_.begin(), streamIndex_.end(), 0);
}

void PrimarySampleSampler::startIteration() { startIterationOfKind(~size_t(0)); }

void PrimarySampleSampler::startIterationOfKind(size_t kind) {
    const bool large = iteration_ == 0 || rng_.uniformDouble() < params_.largeStepProbability;
    startIteration(large);
    if (!large && params_.partialStepProbability > 0 && !params_.partialSteps.empty() &&
        rng_.uniformDouble() < params_.partialStepProbability) {
        const size_t n = params_.partialSteps.size();
        const size_t k = kind < n ? kind : std::min(n - 1, size_t(rng_.uniformDouble() * double(n)));
        const PrimarySampleParams::PartialStep& p = params_.partialSteps[k];
        moved_ = p.streams;
        stepUnits_ = (p.sigma / params_.sigma) * (p.sigma / params_.sigma);
    }
}

void PrimarySampleSampler::startIteration(bool largeStep) {
    ++iteration_;
    largeStep_ = largeStep || iteration_ == 1;
    moved_ = ~0u;
    stepUnits_ = 1;
    touched_.clear();
    restartStreams();
}

void PrimarySampleSampler::accept() {
    strata_ = PaddedStrata();  // the first iteration's alone
    if (largeStep_)
        lastLargeStep_ = iteration_;
    else
        for (size_t k = 0; k < smallSteps_.size(); ++k)
            if (moved_ >> k & 1u) smallSteps_[k] += stepUnits_;
    touched_.clear();
}

void PrimarySampleSampler::reject() {
    strata_ = PaddedStrata();
    for (const Touched& t : touched_) {
        Value& v = streams_[t.stream][t.index];
        v.value = v.backupValue;
        v.modified = v.backupModified;
        v.steps = v.backupSteps;
    }
    touched_.clear();
    --iteration_;
}

// Small steps of a total variance of `units` sigma^2 at once (n steps of sigma: n units): a
// normal deviate of sigma * sqrt(units), wrapped.
double PrimarySampleSampler::small(double v, double units) {
    v += params_.sigma * std::sqrt(units) * normals_.next(rng_);
    v -= std::floor(v);
    return v < 1.0 ? v : 0.0;  // v just below 0 can round up to 1
}

double PrimarySampleSampler::read(int stream, size_t index) {
    std::vector<Value>& values = streams_[size_t(stream)];
    if (index >= values.size()) values.resize(index + 1);
    Value& x = values[index];
    if (x.modified == iteration_) return x.value;  // read twice by one proposal
    // Bring the value to the chain's current state (the last accepted iteration): a value
    // never read, or not read since an accepted large step, is uniform there; otherwise it
    // has missed the small steps its stream took since it was last read (every accepted
    // iteration since, unless partial steps left the stream alone).
    const int64_t current = iteration_ - 1;
    const double steps = smallSteps_[size_t(stream)];
    if (x.modified < 0 || x.modified < lastLargeStep_) {
        x.value = rng_.uniformDouble();
        x.modified = current;
        x.steps = steps;
    } else if (x.steps < steps) {
        x.value = small(x.value, steps - x.steps);
        x.modified = current;
        x.steps = steps;
    }
    // That state is what a rejection restores; then this iteration's own step.
    x.backupValue = x.value;
    x.backupModified = x.modified;
    x.backupSteps = x.steps;
    if (largeStep_) {
        // A stratified value still takes its draw: the chain's random stream stays the same.
        const double u = rng_.uniformDouble();
        x.value = iteration_ == 1 && strata_.active() && index < size_t(kStratifiedValues) ? stratified(stream, index) : u;
    } else if (moved_ >> stream & 1u) {
        x.value = small(x.value, stepUnits_);
        x.steps = steps + stepUnits_;
    }
    x.modified = iteration_;
    touched_.push_back({uint32_t(stream), uint32_t(index)});
    return x.value;
}

void PrimarySampleSampler::stratifyFirstIteration(uint64_t key, int64_t i, int64_t n) { strata_ = PaddedStrata(key, i, n); }

double PrimarySampleSampler::stratified(int stream, size_t index) const {
    return strata_.value(uint64_t(stream) * 64 + index / 2, index % 2 == 1);
}

void PrimarySampleSampler::set(int stream, int index, double value) {
    stream = stream < params_.streamCount ? stream : 0;
    read(stream, size_t(index));  // marks it as the proposal's, with its backup
    streams_[size_t(stream)][size_t(index)].value = std::clamp(value, 0.0, 0x1.fffffffffffffp-1);
}

float PrimarySampleSampler::get1D() {
    float u = float(read(stream_, size_t(streamIndex_[size_t(stream_)]++)));
    return u < 1.0f ? u : 0x1.fffffep-1f;  // a double just below 1 rounds to 1.0f
}

Vec2 PrimarySampleSampler::get2D() {
    float a = get1D();
    return {a, get1D()};
}

bool PrimarySampleSampler::sameState(const PrimarySampleSampler& o) const {
    if (iteration_ != o.iteration_ || lastLargeStep_ != o.lastLargeStep_ || smallSteps_ != o.smallSteps_ ||
        streams_.size() != o.streams_.size())
        return false;
    for (size_t k = 0; k < streams_.size(); ++k) {
        const std::vector<Value>&a = streams_[k], &b = o.streams_[k];
        if (a.size() != b.size()) return false;
        for (size_t i = 0; i < a.size(); ++i)
            if (a[i].value != b[i].value || a[i].modified != b[i].modified || a[i].steps != b[i].steps) return false;
    }
    return true;
}

}  // namespace ps
