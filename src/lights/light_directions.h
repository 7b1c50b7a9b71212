// The frame of a point light whose emission is a table over directions (goniometric and
// projection lights): world directions map to the light's own directions through the
// inverse of its transform. A transform that scales non-uniformly (or shears) does not keep
// solid angle under this mapping, so densities over directions carry its Jacobian; for
// rotations and uniform scales the Jacobian is 1.
#pragma once
#include <cmath>
#include "math/transform.h"

namespace ps {

class LightDirections {
public:
    explicit LightDirections(const Transform& worldFromLight)
        : worldFromLight_(worldFromLight), lightFromWorld_(worldFromLight.inverse()),
          absDet_(std::fabs(worldFromLight.linearDeterminant())) {}
    Vec3 position() const { return worldFromLight_.point({0, 0, 0}); }
    // Unit light-space direction of unit world direction w, and back.
    Vec3 toLight(Vec3 w) const { return normalize(lightFromWorld_.vector(w)); }
    Vec3 toWorld(Vec3 wLight) const { return normalize(worldFromLight_.vector(wLight)); }
    // A density over light-space directions at unit wLight, as a density over world directions:
    // d omega_world = |det M| / |M wLight|^3 d omega_light (M the transform's linear part).
    float toWorldDensity(float pdfLight, Vec3 wLight) const {
        double l = length(worldFromLight_.vector(wLight));
        return absDet_ > 0 ? float(pdfLight * (l * l * l / absDet_)) : 0.0f;
    }

private:
    Transform worldFromLight_, lightFromWorld_;
    double absDet_ = 1;
};

}  // namespace ps
