#include "camera/spherical_mapping.h"

#include "math/equal_area.h"

namespace ps {

Vec3 sphericalCameraDirection(SphericalMapping m, Vec2 uv) {
    Vec3 d;
    if (m == SphericalMapping::Equirectangular) {
        // No wrap: theta slightly outside [0, pi] still gives a unit vector, continued over the pole.
        float theta = kPi * uv.y, phi = 2 * kPi * uv.x;
        float sinTheta = std::sin(theta);
        d = {sinTheta * std::cos(phi), sinTheta * std::sin(phi), std::cos(theta)};
    } else {
        d = equalAreaSquareToSphere(wrapEqualAreaSquare(uv));
    }
    // Both maps put their pole on z; the camera's "up" is +y.
    return {d.x, d.z, d.y};
}

}  // namespace ps
