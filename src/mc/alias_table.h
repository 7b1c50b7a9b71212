// Discrete sampling in constant time by Walker's alias method (thesis §2.4's sampling by
// inversion, for a discrete distribution, traded for a table built once): each of the n
// equal slots of [0,1) holds one outcome with probability `keep` and hands the rest of its
// width to an alias. Used where a few outcomes are drawn per path vertex (choosing a light).
#pragma once
#include <span>
#include <vector>

namespace ps {

class AliasTable {
public:
    AliasTable() = default;
    // Negative or non-finite weights count as 0; an all-zero table becomes uniform.
    explicit AliasTable(std::span<const float> weights);

    int size() const { return int(slots_.size()); }
    // Outcome i with probability pmf(i), from u in [0,1).
    int sample(float u) const {
        const int n = size();
        float x = u * float(n);
        int slot = int(x);
        if (slot >= n) slot = n - 1;
        const Slot& s = slots_[size_t(slot)];
        return x - float(slot) < s.keep ? slot : s.alias;
    }
    float pmf(int i) const { return slots_[size_t(i)].pmf; }

private:
    struct Slot {
        float keep = 1;  // probability that the slot keeps its own outcome
        int alias = 0;   // outcome for the rest of the slot
        float pmf = 0;   // this outcome's probability
    };
    std::vector<Slot> slots_;
};

}  // namespace ps
