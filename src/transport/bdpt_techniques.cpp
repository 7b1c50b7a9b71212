// BDPT's strategies as --stats' techniques (transport/technique_tally.h): every (s, t) up to
// maxdepth, at BDPTIntegrator::techniqueIndex(s, t), then the path tracer's samples at a light
// path share below 1.
#include "transport/bdpt.h"

namespace ps {

std::vector<RenderTechnique> BDPTIntegrator::techniques() const {
    std::vector<RenderTechnique> out;
    for (int d = 0; d <= paths_.maxDepth(); ++d)
        for (int t = 0; t <= d + 2; ++t) {
            const int s = d + 2 - t;
            RenderTechnique k;
            k.name = "s";  // appended piecewise: GCC 12's false -Wrestrict (as in strategy_images.cpp)
            k.name += std::to_string(s);
            k.name += "_t";
            k.name += std::to_string(t);
            k.s = s;
            k.t = t;
            k.splat = t <= 1;
            // (1, 1) is never connected (produce); t = 0 exists only with lens hits.
            k.possible = !(s == 1 && t == 1) && (t > 0 || lensHits_);
            out.push_back(k);
        }
    if (pathTracer_) out.push_back(RenderTechnique{"path"});
    return out;
}

}  // namespace ps
