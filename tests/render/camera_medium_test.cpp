// The warning for a camera whose declared medium (pbrt-v4's CameraMedium) contradicts the
// medium boundaries around it (render/camera_medium_check.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "render/camera_medium_check.h"
#include "render/scene_builder.h"
#include "scene/parser.h"
#include "util/error.h"

using namespace ps;

namespace {

// A fog box of side 2 at the origin; the camera at `eye`, declared in `cameraMedium`.
std::unique_ptr<Scene> fogBoxScene(const char* eye, const char* cameraMedium) {
    setWarningsQuiet(true);
    std::string file = std::string(R"(
        LookAt )") + eye + R"(  0 0 0  0 1 0
        MakeNamedMedium "fog" "string type" "homogeneous" "rgb sigma_a" [ 0.1 0.1 0.1 ] "rgb sigma_s" [ 0.5 0.5 0.5 ]
        )" + (cameraMedium[0] ? std::string("MediumInterface \"") + cameraMedium + "\"" : std::string()) + R"(
        Camera "perspective"
        WorldBegin
        LightSource "point" "point3 from" [ 0 0.5 0 ]
        AttributeBegin
          Material "interface"
          MediumInterface "fog" ""
          Shape "trianglemesh" "point3 P" [ -1 -1 -1  1 -1 -1  1 1 -1  -1 1 -1  -1 -1 1  1 -1 1  1 1 1  -1 1 1 ]
            "integer indices" [ 0 2 1 0 3 2  4 5 6 4 6 7  0 1 5 0 5 4  3 7 6 3 6 2  0 4 7 0 7 3  1 2 6 1 6 5 ]
        AttributeEnd
    )";
    return buildScene(parseSceneString(file, ".", "<test>"));
}

}  // namespace

// Probes from inside the box cross its faces outward: the camera's side is the inside, fog.
TEST(CameraMedium, BoundariesAroundAPointImplyItsMedium) {
    auto inside = fogBoxScene("0 0 0.5", "fog");
    const auto m = mediumImpliedAt(*inside, {0, 0, 0.5f});
    ASSERT_TRUE(m.has_value());
    EXPECT_EQ(*m, inside->cameraMedium());
    EXPECT_NE(*m, nullptr);
    const auto outside = mediumImpliedAt(*inside, {0, 0, 5});
    ASSERT_TRUE(outside.has_value());
    EXPECT_EQ(*outside, nullptr);
}

// Cases that must not warn first: a warning prints once per distinct text, so each case looks
// only at the warnings it added.
TEST(CameraMedium, ContradictedDeclarationsWarn) {
    struct Case {
        const char *eye, *declared;
        bool warns;
    } cases[] = {
        {"0 0 0.5", "fog", false},  // inside, declared inside
        {"0 0 5", "", false},       // outside, declared in none
        {"0 0 0.5", "", true},      // inside, declared in no medium
        {"0 0 5", "fog", true},     // outside, declared in fog
    };
    for (const Case& c : cases) {
        const size_t before = warningMessages().size();
        auto scene = fogBoxScene(c.eye, c.declared);
        const auto w = warningMessages();
        const bool warned = std::any_of(w.begin() + long(before), w.end(), [](const std::string& m) {
            return m.find("the camera is declared in") != std::string::npos;
        });
        EXPECT_EQ(warned, c.warns) << "eye " << c.eye << ", declared '" << c.declared << "'";
        if (warned) std::printf("  %s\n", w.back().c_str());
    }
}
