// pbrt-v4's "cloud" medium (media.h: CloudMedium): a procedural density in [0, 1] inside the
// box p0..p1 (the medium's space, placed by the CTM), made of five octaves of Perlin noise at
// `frequency`, its lookup point displaced by two octaves of the noise's difference gradient
// (`wispiness`), scaled by `density` and thinning with height y, with a solid base below
// y = 1/2. sigma_a and sigma_s are multiplied by it; the phase function is Henyey-Greenstein g.
// pbrt-v4 bounds the whole box by sigma_a + sigma_s; we walk a 16^3 majorant grid whose cells
// bound the density from its height profile (see cellBound).
#pragma once
#include "media/density_medium.h"

namespace ps {

class CloudMedium final : public DensityMedium {
public:
    struct Shape {
        float density = 1, wispiness = 1, frequency = 5;
    };
    CloudMedium(const MediumBox& box, MediumSpectrum sigmaA, MediumSpectrum sigmaS, float g, Shape shape);

    // pbrt-v4's CloudMedium::Density.
    float density(Vec3 pMedium) const override;
    // A bound on density over the cell [lo, hi] of the box's unit coordinates.
    float cellBound(Vec3 lo, Vec3 hi) const;

private:
    Shape shape_;
};

}  // namespace ps
