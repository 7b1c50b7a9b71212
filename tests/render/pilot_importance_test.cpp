// Two-stage MLT's pilot image (transport/mlt/pilot_importance.h): its tiles and the
// brightness it divides the chains' target by.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "transport/mlt/pilot_importance.h"

using namespace ps;

// About samplesPerTile pilot samples per tile: 100 x 60 pixels, 6000 samples (one a pixel)
// at 400 a tile: tiles of 20 x 20 pixels, 5 x 3 of them.
TEST(PilotImportance, TilesHoldAboutTheSamplesAsked) {
    const PixelBounds bounds{0, 100, 0, 60};
    PilotImportance p(bounds, 6000, 0, 1, 400);
    EXPECT_EQ(p.tileSize(), 20);
    EXPECT_EQ(p.tiles(), 15);
    EXPECT_EQ(p.tileOf(Vec2(0.5f, 0.5f)), 0);
    EXPECT_EQ(p.tileOf(Vec2(99.5f, 59.5f)), 14);
    EXPECT_EQ(p.tileOf(Vec2(25.f, 45.f)), 2 * 5 + 1);
    // Splats reach past the pixel bounds by the filter's radius: the nearest tile.
    EXPECT_EQ(p.tileOf(Vec2(-1.f, -1.f)), 0);
    EXPECT_EQ(p.tileOf(Vec2(101.f, 61.f)), 14);
    // A crop window's tiles start at its corner.
    PilotImportance crop(PixelBounds{40, 140, 10, 70}, 6000, 0, 1, 400);
    EXPECT_EQ(crop.tileOf(Vec2(40.5f, 10.5f)), 0);
    EXPECT_EQ(crop.tileOf(Vec2(39.f, 9.f)), 0);
}

TEST(PilotImportance, BrightnessIsEachTilesMeanPerPixelWithAFloor) {
    // 30 x 20 pixels in tiles of 20: 2 x 1 tiles, the second 10 pixels wide.
    PilotImportance p(PixelBounds{0, 30, 0, 20}, 600, 0, 1, 400);
    ASSERT_EQ(p.tileSize(), 20);
    ASSERT_EQ(p.tiles(), 2);
    EXPECT_EQ(p.at(Vec2(5.f, 5.f)), 1.0);  // before the pilot: the plain target
    p.finish({400.0, 2.0}, 0.1);
    // Per pixel: 400 / 400 = 1 and 2 / 200 = 0.01; the image mean is 402 / 600 = 0.67,
    // whose tenth, 0.067, lifts the dark tile.
    EXPECT_DOUBLE_EQ(p.at(Vec2(5.f, 5.f)), 1.0);
    EXPECT_DOUBLE_EQ(p.at(Vec2(25.f, 5.f)), 0.1 * 402.0 / 600.0);
    // A pilot that found no light leaves every tile alike.
    p.finish({0.0, 0.0}, 0.1);
    EXPECT_EQ(p.at(Vec2(5.f, 5.f)), p.at(Vec2(25.f, 5.f)));
    EXPECT_GT(p.at(Vec2(5.f, 5.f)), 0.0);
}

// The black level L0 in pixel luminance: divisor sqrt(B^2 + L0^2), B per pixel of pixel value
// (a pixel's value is its samples' mean luminance times the imaging ratio).
TEST(PilotImportance, BlackLevelIsAddedInQuadratureInPixelUnits) {
    // 600 samples over 600 pixels: one a pixel. Imaging ratio 2: a sample luminance of 1 is a
    // pixel value of 2, so L0 = 0.5 is 0.25 in the sums' unit.
    PilotImportance p(PixelBounds{0, 30, 0, 20}, 600, 0.5, 2.0, 400);
    p.finish({400.0, 2.0}, 0.1);
    EXPECT_DOUBLE_EQ(p.at(Vec2(5.f, 5.f)), std::hypot(1.0, 0.25));
    EXPECT_DOUBLE_EQ(p.at(Vec2(25.f, 5.f)), std::hypot(0.1 * 402.0 / 600.0, 0.25));
    // Twice the samples per pixel: the sums' unit halves, the level doubles in it.
    PilotImportance q(PixelBounds{0, 30, 0, 20}, 1200, 0.5, 2.0, 800);
    ASSERT_EQ(q.tiles(), 2);
    q.finish({800.0, 4.0}, 0.1);
    EXPECT_DOUBLE_EQ(q.at(Vec2(5.f, 5.f)), std::hypot(2.0, 0.5));
}
