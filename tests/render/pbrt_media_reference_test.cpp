// Agreement with pbrt-v4 on participating media as it defines them: small coloured scenes of
// our own (tests/data/pbrt-v4/media-*.pbrt) against pbrt-v4's volpath renders of the same
// files, rendered by our path tracer (pbrt-v4's volpath) in spectral mode, as pbrt-v4 renders:
// block means of luminance within 4 sigma, the image's mean luminance and its mean R, G and B
// each within 4 sigma of pbrt-v4's, sigma under 0.5%, no allowance. The measured agreement of
// each scene is in tests/data/pbrt-v4/README.md ("Media").
#include <gtest/gtest.h>

#include "pbrt_reference_helpers.h"

using namespace ps::test;

// A homogeneous fog box (chromatic sigma_a and sigma_s, g 0.6) bounded by an interface mesh,
// a diffuse sphere inside it taking the fog from the ray, under an area light.
TEST(PbrtMediaReference, HomogeneousFogBox) {
    expectPbrtReference("media-fog-box.pbrt", "media-fog-box-4096spp.exr", 4096, 32, 0, true);
}

// The camera inside a medium (the MediumInterface in effect at Camera): a room of thin haze
// (g -0.3) with a sphere of a denser medium nested in it (MediumInterface "jade" "haze").
TEST(PbrtMediaReference, CameraInHazeWithANestedMedium) {
    expectPbrtReference("media-haze-room.pbrt", "media-haze-room-4096spp.exr", 4096, 16, 0, true);
}

// uniformgrid: an 8x8x8 density with chromatic coefficients times "scale", and emission
// ("Le" normalised by its luminance times an 8x8x8 "Lescale" grid), lit by a spotlight.
TEST(PbrtMediaReference, UniformGridWithEmission) {
    expectPbrtReference("media-uniformgrid.pbrt", "media-uniformgrid-4096spp.exr", 4096, 16, 0, true);
}

// rgbgrid: 4x4x4 RGB sigma_a and sigma_s in a box turned and stretched by the medium's transform.
TEST(PbrtMediaReference, RgbGrid) {
    expectPbrtReference("media-rgbgrid.pbrt", "media-rgbgrid-4096spp.exr", 4096, 8, 0, true);
}

// pbrt-v4's procedural cloud in a stretched box, under a distant light and a sky.
TEST(PbrtMediaReference, Cloud) {
    expectPbrtReference("media-cloud.pbrt", "media-cloud-4096spp.exr", 4096, 16, 0, true);
}

// The NanoVDB test grid (tests/data/media/tiny.nvdb) turned and scaled, under a point light.
TEST(PbrtMediaReference, NanoVDBGrid) {
    expectPbrtReference("media-nanovdb.pbrt", "media-nanovdb-2048spp.exr", 2048, 8, 0, true);
}
