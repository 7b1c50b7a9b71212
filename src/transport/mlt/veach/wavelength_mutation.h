// Spectral mode's mutation of a path's wavelengths alone (path_space.h MltVertex::lambda):
// the vertices stay, the path is given wavelengths drawn afresh from the sensor's density,
// and its BxDFs and emission are evaluated again at them. The state's measure takes the
// wavelengths in that density, so the draw has density 1 both ways and T(y -> x) / T(x -> y)
// is 1: the acceptance is f(y) / f(x), the change of the path's colour (thesis §11.3's
// detailed balance with the wavelengths one more coordinate of the state).
//
// The other mutations keep a path's wavelengths (a path made afresh draws its own), so
// without this one a chain would move them only when the bidirectional mutation replaces
// the whole path. A path through a dispersive specular vertex is refused: its direction
// there follows lambda[0], so new wavelengths would give it no contribution.
#pragma once
#include "transport/mlt/veach/path_space.h"

namespace ps {

class WavelengthMutation {
public:
    explicit WavelengthMutation(const PathSpace& space) : space_(space) {}
    // Spectral mode, and no dispersive specular vertex on x (the same for every path with
    // x's vertices, so the choice's probability is symmetric).
    bool applies(const MltPath& x) const;
    // y: x at new wavelengths, its BxDFs in `arena`; *ratio = T(y -> x) / T(x -> y) = 1.
    bool propose(const MltPath& x, Rng& rng, ScratchBuffer& arena, MltPath& y, double* ratio) const;

private:
    const PathSpace& space_;
};

}  // namespace ps
