// pbrt-v4's Sampler directive mapped onto our samplers: names, sample counts and warnings.
#include <gtest/gtest.h>

#include "render_helpers.h"

using namespace ps;

namespace {

struct Mapped {
    std::string sampler;
    int spp;
    int warnings;
};

Mapped mapSampler(const std::string& samplerLine) {
    setWarningsQuiet(true);
    std::string text = samplerLine + R"(
        Film "rgb" "integer xresolution" [ 8 ] "integer yresolution" [ 8 ]
        WorldBegin
        Shape "sphere" "float radius" [ 1 ]
    )";
    int before = warningCount();
    auto scene = buildScene(parseSceneString(text, ".", "<test>"));
    return {scene->settings().sampler, scene->settings().spp, warningCount() - before};
}

}  // namespace

TEST(SamplerOptions, PbrtNamesMapToOurs) {
    struct Case {
        const char* line;
        const char* sampler;
        int spp, warnings;
    } cases[] = {
        {R"(Sampler "halton" "integer pixelsamples" 8)", "halton", 8, 0},
        {R"(Sampler "zsobol")", "zsobol", 16, 0},
        {R"(Sampler "sobol" "integer pixelsamples" 32)", "sobol", 32, 0},
        {R"(Sampler "paddedsobol" "string randomization" "owen")", "sobol", 16, 0},
        {R"(Sampler "independent")", "independent", 4, 0},
        {R"(Sampler "stratified" "integer xsamples" 3 "integer ysamples" 5)", "stratified", 15, 0},
        {R"(Sampler "stratified" "bool jitter" false)", "stratified", 16, 1},
        {R"(Sampler "pmj02bn" "integer pixelsamples" 64)", "sobol", 64, 1},
        {R"(Sampler "zsobol" "string randomization" "none")", "zsobol", 16, 1},
    };
    for (const Case& c : cases) {
        Mapped m = mapSampler(c.line);
        EXPECT_EQ(m.sampler, c.sampler) << c.line;
        EXPECT_EQ(m.spp, c.spp) << c.line;
        EXPECT_EQ(m.warnings, c.warnings) << c.line;
        EXPECT_NE(createSampler(m.sampler, 0, m.spp, 8), nullptr) << c.line;
    }
}

// Without a Sampler directive pbrt implies "zsobol"; we use our own default instead.
TEST(SamplerOptions, NoDirectiveGivesOurDefault) {
    Mapped m = mapSampler("");
    EXPECT_EQ(m.sampler, RenderSettings{}.sampler);
    EXPECT_EQ(m.sampler, RenderOptions{}.sampler);
    EXPECT_EQ(m.sampler, samplerNames().front());
    EXPECT_EQ(m.spp, 16);
    EXPECT_EQ(m.warnings, 0);
}
