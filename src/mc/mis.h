// Multiple importance sampling heuristics (thesis §9.2): weights for a sample drawn with
// density pf when another technique would have drawn it with density pg.
#pragma once

namespace ps {

// Balance heuristic, thesis eq. 9.5 (one sample from each technique).
inline float balanceHeuristic(float pf, float pg) { return pf / (pf + pg); }

// Power heuristic with exponent 2, thesis eq. 9.11.
inline float powerHeuristic(float pf, float pg) {
    float f = pf * pf, g = pg * pg;
    if (f == 0) return 0;
    if (!(g < 1e30f)) return 0;  // the other technique is (near) certain
    return f / (f + g);
}

}  // namespace ps
