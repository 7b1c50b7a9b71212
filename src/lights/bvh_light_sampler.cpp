#include "lights/bvh_light_sampler.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <tuple>

namespace ps {

namespace {

constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;
// Below this depth, splits follow the cost; from it on, the median, so that no way down needs
// more than 64 bits for fewer than 2^32 lights.
constexpr int kCostSplitDepth = 32;
constexpr int kBuckets = 12;

// pbrt-v4's cost of a group of lights (Conty Estevez and Kulla's heuristic): power times the
// measure of the directions it may emit in (the cosine-weighted solid angle of its normals'
// cone widened by the emission range) times its surface area; kr favours cutting the box
// across its long side.
float splitCost(const LightBounds& b, const Bounds3& parent, int dim) {
    if (b.phi == 0) return 0;
    const float thetaO = safeAcos(b.cosTheta_o), thetaE = safeAcos(b.cosTheta_e);
    const float thetaW = std::min(thetaO + thetaE, kPi);
    const float sinThetaO = safeSqrt(1 - sqr(b.cosTheta_o));
    const float mOmega = 2 * kPi * (1 - b.cosTheta_o) +
                         kPi / 2 * (2 * thetaW * sinThetaO - std::cos(thetaO - 2 * thetaW) -
                                    2 * thetaO * sinThetaO + b.cosTheta_o);
    const Vec3 d = parent.diagonal();
    const float kr = maxComponent(d) / d[dim];
    return b.phi * mOmega * kr * b.bounds.surfaceArea();
}

// The importances of a node's two children at ctx; nodes[i + 1] is the first.
inline void childImportances(const auto& nodes, int i, const LightSampleContext& ctx, float c[2]) {
    c[0] = nodes[size_t(i) + 1].importance.at(ctx.p, ctx.ng);
    c[1] = nodes[size_t(nodes[size_t(i)].childOrSlot)].importance.at(ctx.p, ctx.ng);
}

}  // namespace

BVHLightSampler::BVHLightSampler(std::span<const Light* const> lights)
    : lights_(lights.begin(), lights.end()), place_(lights.size(), Place::None), trail_(lights.size(), 0),
      slotOf_(lights.size(), -1), power_(lights) {
    std::vector<Member> bounded;
    std::vector<LightBounds> bounds(lights.size());
    for (size_t i = 0; i < lights.size(); ++i) {
        std::optional<LightBounds> b = lights[i]->bounds();
        if (!b) {
            infinite_.push_back(lights[i]);
            place_[i] = Place::Infinite;
        } else if (b->phi > 0 && std::isfinite(b->phi)) {
            // A light of no power is never chosen (it gives nothing).
            bounded.push_back({int(i), b->phi});
            bounds[i] = *b;
            place_[i] = Place::Tree;
        }
    }
    std::vector<Entry> entries = group(bounded, bounds);
    if (!entries.empty()) {
        nodes_.reserve(2 * entries.size() - 1);
        build(entries, bounded, 0, int(entries.size()), 0, 0);
    }
}

std::vector<BVHLightSampler::Entry> BVHLightSampler::group(std::vector<Member>& members,
                                                           const std::vector<LightBounds>& bounds) {
    // Sorted by every part of their bounds but power, equal bounds are neighbours.
    auto key = [&](const Member& m) {
        const LightBounds& b = bounds[size_t(m.light)];
        return std::make_tuple(b.bounds.lo.x, b.bounds.lo.y, b.bounds.lo.z, b.bounds.hi.x, b.bounds.hi.y,
                               b.bounds.hi.z, b.w.x, b.w.y, b.w.z, b.cosTheta_o, b.cosTheta_e, b.twoSided);
    };
    std::stable_sort(members.begin(), members.end(), [&](const Member& a, const Member& b) { return key(a) < key(b); });
    std::vector<Entry> entries;
    for (size_t i = 0; i < members.size();) {
        size_t j = i + 1;
        LightBounds united = bounds[size_t(members[i].light)];
        while (j < members.size() && key(members[j]) == key(members[i])) {
            united = unite(united, bounds[size_t(members[j].light)]);
            ++j;
        }
        entries.push_back({int(i), int(j - i), united});
        i = j;
    }
    return entries;
}

LightBounds BVHLightSampler::build(std::vector<Entry>& entries, const std::vector<Member>& members, int begin, int end, uint64_t trail, int depth) {
    depth_ = std::max(depth_, depth);
    const size_t index = nodes_.size();
    if (end - begin == 1) {
        const Entry& e = entries[size_t(begin)];
        double total = 0;
        for (int k = 0; k < e.count; ++k) total += members[size_t(e.first + k)].phi;
        const int first = int(slotLight_.size());
        double running = 0;
        for (int k = 0; k < e.count; ++k) {
            const Member& m = members[size_t(e.first + k)];
            slotOf_[size_t(m.light)] = int(slotLight_.size());
            slotLight_.push_back(m.light);
            slotShare_.push_back(float(m.phi / total));
            running += m.phi;
            slotCdf_.push_back(k + 1 == e.count ? 1.0f : float(running / total));
            trail_[size_t(m.light)] = trail;
        }
        nodes_.push_back(Node{LightImportance(e.bounds), first, e.count});
        return e.bounds;
    }
    const int mid = split(entries, begin, end, depth);
    nodes_.emplace_back();  // filled once both children exist
    const LightBounds first = build(entries, members, begin, mid, trail, depth + 1);
    const int second = int(nodes_.size());
    const LightBounds bounds = unite(first, build(entries, members, mid, end, trail | (uint64_t(1) << depth), depth + 1));
    nodes_[index] = Node{LightImportance(bounds), second, 0};
    return bounds;
}

int BVHLightSampler::split(std::vector<Entry>& entries, int begin, int end, int depth) const {
    Bounds3 bounds, centroids;
    for (int i = begin; i < end; ++i) {
        bounds.expand(entries[size_t(i)].bounds.bounds);
        centroids.expand(entries[size_t(i)].bounds.centroid());
    }
    // Clamped before the conversion: lights at enormous coordinates make the offset inf or NaN
    // (inf - inf), and converting either to int is undefined (found by the scene fuzzer).
    auto bucketOf = [&](const Entry& e, int dim) {
        const float o = centroids.offset(e.bounds.centroid())[dim];
        return o > 0 ? std::min(int(kBuckets * std::min(o, 1.0f)), kBuckets - 1) : 0;
    };

    float bestCost = std::numeric_limits<float>::infinity();
    int bestDim = -1, bestBucket = -1;
    for (int dim = 0; dim < 3 && depth < kCostSplitDepth; ++dim) {
        if (!(centroids.hi[dim] > centroids.lo[dim]) || !(bounds.diagonal()[dim] > 0)) continue;
        std::array<LightBounds, kBuckets> bucket;
        std::array<int, kBuckets> count{};
        for (int i = begin; i < end; ++i) {
            int b = bucketOf(entries[size_t(i)], dim);
            bucket[size_t(b)] = unite(bucket[size_t(b)], entries[size_t(i)].bounds);
            ++count[size_t(b)];
        }
        // Costs of splitting after each bucket, from running unions from both ends.
        std::array<LightBounds, kBuckets> above;
        std::array<int, kBuckets> countAbove{};
        for (int b = kBuckets - 1; b > 0; --b) {
            above[size_t(b)] = b + 1 < kBuckets ? unite(above[size_t(b) + 1], bucket[size_t(b)]) : bucket[size_t(b)];
            countAbove[size_t(b)] = (b + 1 < kBuckets ? countAbove[size_t(b) + 1] : 0) + count[size_t(b)];
        }
        LightBounds below;
        int countBelow = 0;
        for (int b = 0; b < kBuckets - 1; ++b) {
            below = unite(below, bucket[size_t(b)]);
            countBelow += count[size_t(b)];
            if (countBelow == 0 || countAbove[size_t(b) + 1] == 0) continue;  // one side empty
            float cost = splitCost(below, bounds, dim) + splitCost(above[size_t(b) + 1], bounds, dim);
            if (cost > 0 && cost < bestCost) {
                bestCost = cost;
                bestDim = dim;
                bestBucket = b;
            }
        }
    }
    if (bestDim >= 0) {
        auto first = entries.begin() + begin, last = entries.begin() + end;
        auto mid = std::partition(first, last, [&](const Entry& e) { return bucketOf(e, bestDim) <= bestBucket; });
        if (mid != first && mid != last) return int(mid - entries.begin());
    }
    // No useful cost (lights on a line or at one point have no surface area): halve along the
    // centroids' widest spread, so that the tree still follows where the lights are.
    const Vec3 spread = centroids.diagonal();
    const int dim = spread.x >= spread.y && spread.x >= spread.z ? 0 : (spread.y >= spread.z ? 1 : 2);
    const int mid = (begin + end) / 2;
    std::nth_element(entries.begin() + begin, entries.begin() + mid, entries.begin() + end,
                     [dim](const Entry& a, const Entry& b) { return a.bounds.centroid()[dim] < b.bounds.centroid()[dim]; });
    return mid;
}

bool BVHLightSampler::rootImportances(const LightSampleContext& ctx, float c[2]) const {
    if (nodes_.empty()) {
        c[0] = c[1] = 0;
        return false;
    }
    if (nodes_[0].leaf()) {
        c[0] = infinite_.empty() ? 1.0f : nodes_[0].importance.at(ctx.p, ctx.ng);
        c[1] = 0;
    } else {
        childImportances(nodes_, 0, ctx, c);
    }
    return c[0] > 0 || c[1] > 0;
}

SampledLight BVHLightSampler::sample(const LightSampleContext& ctx, float u) const {
    // One leaf and nothing at infinity (an area light of one quad or mesh): the choice is the
    // leaf's, the same at every point.
    if (nodes_.size() == 1 && infinite_.empty()) return chooseInLeaf(nodes_[0], u, 1);
    float c[2];
    const bool treeCanLight = rootImportances(ctx, c);
    const float pInfinite = infiniteShare(treeCanLight);
    if (u < pInfinite) {
        const size_t n = infinite_.size();
        const size_t i = std::min(size_t(u / pInfinite * float(n)), n - 1);
        return {infinite_[i], pInfinite / float(n)};
    }
    if (!treeCanLight) return {};
    // The rest of u, rescaled to [0, 1), chooses the way down; at each node the part of it
    // left after the choice is rescaled again for the next.
    u = std::min((u - pInfinite) / (1 - pInfinite), kOneMinusEpsilon);
    float pmf = 1 - pInfinite;
    int node = 0;
    while (!nodes_[size_t(node)].leaf()) {
        if (node != 0) childImportances(nodes_, node, ctx, c);
        const float total = c[0] + c[1];
        if (!(total > 0)) return {};  // neither child can light ctx (nor could any leaf below)
        const float p0 = c[0] / total;
        int child;
        if (u < p0) {
            child = 0;
            u = std::min(u / p0, kOneMinusEpsilon);
        } else {
            child = 1;
            u = std::min((u - p0) / (1 - p0), kOneMinusEpsilon);
        }
        pmf *= c[child] / total;
        node = child == 0 ? node + 1 : nodes_[size_t(node)].childOrSlot;
    }
    return chooseInLeaf(nodes_[size_t(node)], u, pmf);
}

SampledLight BVHLightSampler::chooseInLeaf(const Node& leaf, float u, float pmf) const {
    int slot = leaf.childOrSlot;
    if (leaf.leafLights > 1 && leaf.leafLights <= 8) {
        // Counted without branches: u is random, and a search's branches mispredict.
        for (int k = 0; k < leaf.leafLights - 1; ++k) slot += u >= slotCdf_[size_t(leaf.childOrSlot + k)];
    } else if (leaf.leafLights > 8) {
        const auto first = slotCdf_.begin() + slot, last = first + (leaf.leafLights - 1);
        slot = int(std::upper_bound(first, last, u) - slotCdf_.begin());
    }
    return {lights_[size_t(slotLight_[size_t(slot)])], pmf * slotShare_[size_t(slot)]};
}

// The same walk as sample's, in the same order of operations (so the two agree to the last
// bit), following the light's trail instead of u.
float BVHLightSampler::pmf(const LightSampleContext& ctx, const Light* light) const {
    if (!light || light->index < 0 || size_t(light->index) >= lights_.size()) return 0;
    const Place place = place_[size_t(light->index)];
    if (place == Place::None) return 0;
    float c[2];
    const bool treeCanLight = rootImportances(ctx, c);
    const float pInfinite = infiniteShare(treeCanLight);
    if (place == Place::Infinite) return pInfinite / float(infinite_.size());
    if (!treeCanLight) return 0;
    const uint64_t trail = trail_[size_t(light->index)];
    float pmf = 1 - pInfinite;
    int node = 0, depth = 0;
    while (!nodes_[size_t(node)].leaf()) {
        if (node != 0) childImportances(nodes_, node, ctx, c);
        const float total = c[0] + c[1];
        const int child = int((trail >> depth++) & 1);
        if (!(c[child] > 0)) return 0;
        pmf *= c[child] / total;
        node = child == 0 ? node + 1 : nodes_[size_t(node)].childOrSlot;
    }
    return pmf * slotShare_[size_t(slotOf_[size_t(light->index)])];
}

}  // namespace ps
