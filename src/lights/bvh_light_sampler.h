// pbrt-v4's "bvh" light sampler: lights chosen in proportion to an estimate of what each
// gives the receiving point (LightBounds::importance), found by descending a binary tree
// over the lights' bounds. At each node the two children's importances at the point decide
// the way down, so one choice costs a walk from the root to a leaf, and the probability of
// the chosen light is the product of the choices made on the way (pmf walks the same way).
//
// Lights without bounds (infinite and distant lights) are not in the tree: each of them
// counts as much as the whole tree, so with k of them one of them is chosen, uniformly, with
// probability k / (k + 1) (pbrt-v4's rule). Unlike pbrt-v4, where no bounded light can light
// the point (the root's importance there is zero), the lights at infinity take all of the
// probability instead of wasting the sample.
//
// Lights whose bounds are the same but for their power (the two triangles of a quad have the
// same box) share a leaf, where one is chosen by power: the tree would choose between them in
// the same proportion at every point, since their importances differ by the power factor
// alone, but at the cost of two importances per choice.
#pragma once
#include <cstdint>
#include <vector>
#include "lights/light_bounds.h"
#include "lights/light_sampler.h"

namespace ps {

class BVHLightSampler final : public LightSampler {
public:
    explicit BVHLightSampler(std::span<const Light* const> lights);
    SampledLight sample(const LightSampleContext& ctx, float u) const override;
    float pmf(const LightSampleContext& ctx, const Light* light) const override;
    // Without a point: by power.
    SampledLight sample(float u) const override { return power_.sample(u); }
    float pmf(const Light* light) const override { return power_.pmf(light); }

    // The tree's size and depth (for tests of its construction).
    int nodeCount() const { return int(nodes_.size()); }
    int depth() const { return depth_; }

private:
    struct Node {
        LightImportance importance;
        // A leaf: its first slot in slotLight_; otherwise the second child's node (the first
        // child is the next node).
        int childOrSlot = -1;
        int leafLights = 0;  // 0: not a leaf
        bool leaf() const { return leafLights > 0; }
    };
    // A group of lights with the same bounds but for power (often one light): the tree's
    // leaves. Its lights are members[first, first + count) of the build; bounds has their total
    // power.
    struct Entry {
        int first, count;
        LightBounds bounds;
    };
    struct Member {
        int light;
        float phi;
    };
    // Builds the subtree over entries [begin, end) from node nodes_.size() on and returns its
    // bounds; trail holds the way down to it (bit d: the second child at depth d).
    LightBounds build(std::vector<Entry>& entries, const std::vector<Member>& members, int begin, int end,
                      uint64_t trail, int depth);
    // Where to split [begin, end): the bucket split of least cost (pbrt-v4's surface area and
    // orientation heuristic), else the median along the widest spread of centroids. Reorders
    // entries and returns the middle.
    int split(std::vector<Entry>& entries, int begin, int end, int depth) const;
    // The importances at ctx of the root's two children (of the root itself, in c[0], when it
    // is a leaf); true when any is positive. A tree of one leaf without lights at infinity
    // needs none: its choice is the same wherever the point is (where the leaf cannot light
    // the point, what it gives is zero whatever its probability).
    bool rootImportances(const LightSampleContext& ctx, float c[2]) const;
    // The probability that one of the lights at infinity is chosen.
    float infiniteShare(bool treeCanLight) const {
        if (infinite_.empty()) return 0;
        return treeCanLight ? float(infinite_.size()) / float(infinite_.size() + 1) : 1.0f;
    }

    std::vector<const Light*> lights_, infinite_;
    // The light of leaf that u in [0, 1) chooses by power, its probability times pmf.
    SampledLight chooseInLeaf(const Node& leaf, float u, float pmf) const;
    // Gathers the lights with the same bounds but for power into entries, sorting members so
    // that each entry's are consecutive
    // their lights).
    static std::vector<Entry> group(std::vector<Member>& members, const std::vector<LightBounds>& bounds);

    std::vector<Node> nodes_;  // nodes_[0] is the root
    // The leaves' lights, by slot: each leaf's are consecutive; the chance of each within its
    // leaf, and their running sum (which sample() searches).
    std::vector<int> slotLight_;
    std::vector<float> slotShare_, slotCdf_;
    enum class Place : uint8_t { None, Tree, Infinite };
    std::vector<Place> place_;      // by light index
    std::vector<uint64_t> trail_;   // by light index: the way from the root to its leaf
    std::vector<int> slotOf_;       // by light index
    int depth_ = 0;
    PowerLightSampler power_;
};

}  // namespace ps
