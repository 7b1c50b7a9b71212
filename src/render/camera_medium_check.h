// Whether the medium a scene file declares for the camera (pbrt-v4's CameraMedium: the outside
// medium of the MediumInterface current at the Camera directive) matches the medium
// boundaries around the camera. pbrt-v4 trusts the declaration; a camera placed inside a fog
// box but declared outside it renders the fog as seen from outside, silently.
#pragma once
#include <optional>

#include "math/vec.h"

namespace ps {

class Scene;
class Medium;

// The medium the boundaries around p imply: along each of 26 directions, the first surface
// that changes medium (others do not change it) gives the medium on p's side. Present only
// when at least one direction crosses a boundary and all that do agree (open surfaces and
// grazing probes make directions disagree; then nothing is claimed).
std::optional<const Medium*> mediumImpliedAt(const Scene& scene, Vec3 p);

}  // namespace ps
