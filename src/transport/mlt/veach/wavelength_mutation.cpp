#include "transport/mlt/veach/wavelength_mutation.h"

namespace ps {

bool WavelengthMutation::applies(const MltPath& x) const {
    if (!space_.spectral()) return false;
    for (const MltVertex& v : x)
        if (v.dispersive && v.isSpecularSurface()) return false;
    return true;
}

bool WavelengthMutation::propose(const MltPath& x, Rng& rng, ScratchBuffer& arena, MltPath& y, double* ratio) const {
    if (!applies(x)) return false;
    PathSpace::copyAt(x, space_.drawWavelengths(rng), arena, y);
    *ratio = 1;
    return true;
}

}  // namespace ps
