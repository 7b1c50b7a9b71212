// The sample dimensions a subpath walk reads (Subpaths::kDimensionsPerVertex): every vertex
// has its own block of numbers in its stream, whatever earlier vertices drew conditionally,
// so that a Markov chain's small step on one vertex's numbers (thesis ch. 11; primary sample
// space) changes that vertex and not, by shifting every later number, the rest of the path.
#include <gtest/gtest.h>

#include <new>
#include <vector>

#include "render_helpers.h"
#include "transport/bdpt.h"

using namespace ps;
using namespace ps::test;

namespace {

// Records which (stream, index) each value came from; the values cycle through a fixed set
// that keeps walks going (Russian roulette survives with 0.9).
class RecordingSampler final : public Sampler {
public:
    struct Read {
        int stream, index;
    };
    std::vector<Read> reads;
    void startPixelSample(int, int, int) override { next_.assign(8, 0); }
    void startStream(int s) override { stream_ = s; }
    void seekDimension(int i) override { next_[size_t(stream_)] = i; }
    float get1D() override {
        reads.push_back({stream_, next_[size_t(stream_)]++});
        return kValues[reads.size() % 4];
    }
    Vec2 get2D() override {
        float a = get1D();
        return {a, get1D()};
    }
    std::unique_ptr<Sampler> clone() const override { return std::make_unique<RecordingSampler>(*this); }

private:
    static constexpr float kValues[4] = {0.31f, 0.92f, 0.57f, 0.95f};
    int stream_ = 0;
    std::vector<int> next_ = std::vector<int>(8, 0);
};

// A closed diffuse box (walks rarely escape) with a glossy-plus-diffuse floor (two lobes: a
// lobe choice is drawn there, not elsewhere).
const char* kScene = R"(
    LookAt 0 0.5 0.9  0 0.5 0  0 1 0
    Camera "perspective" "float fov" [ 60 ]
    Film "rgb" "integer xresolution" [ 8 ] "integer yresolution" [ 8 ]
    Integrator "bdpt" "integer maxdepth" [ 8 ]
    WorldBegin
    AttributeBegin
      AreaLightSource "diffuse" "rgb L" [ 1 1 1 ]
      Shape "bilinearmesh" "point3 P" [ -0.2 0.99 -0.2   0.2 0.99 -0.2   -0.2 0.99 0.2   0.2 0.99 0.2 ]
    AttributeEnd
    Material "coateddiffuse" "rgb reflectance" [ 0.5 0.5 0.5 ] "float roughness" [ 0.2 ]
    Shape "bilinearmesh" "point3 P" [ -0.5 0 0.5   0.5 0 0.5   -0.5 0 -0.5   0.5 0 -0.5 ]
    Material "diffuse" "rgb reflectance" [ 0.9 0.9 0.9 ]
    Shape "bilinearmesh" "point3 P" [ -0.5 1 -0.5   0.5 1 -0.5   -0.5 1 0.5   0.5 1 0.5 ]
    Shape "bilinearmesh" "point3 P" [ -0.5 0 -0.5   0.5 0 -0.5   -0.5 1 -0.5   0.5 1 -0.5 ]
    Shape "bilinearmesh" "point3 P" [ -0.5 0 0.5   -0.5 0 -0.5   -0.5 1 0.5   -0.5 1 -0.5 ]
    Shape "bilinearmesh" "point3 P" [ 0.5 0 -0.5   0.5 0 0.5   0.5 1 -0.5   0.5 1 0.5 ]
    Shape "bilinearmesh" "point3 P" [ -0.5 0 1   0.5 0 1   -0.5 1 1   0.5 1 1 ]
)";

}  // namespace

// Each vertex i of a camera walk reads its direction at block 4 + 4i (+0, +1), its lobe
// choice at +2 and its roulette at +3 of the camera stream, in that order; a light walk the
// same from 5. Checked over many walks, which differ in which vertices draw a lobe choice and
// which are past the roulette's start.
TEST(SampleDimensions, EveryVertexReadsItsOwnBlock) {
    setWarningsQuiet(true);
    auto scene = buildScene(parseSceneString(kScene, ".", "<test>"));
    BDPTIntegrator bdpt(*scene, 8);
    const Subpaths& paths = bdpt.subpaths();
    ScratchBuffer scratch;
    PathStats stats;
    int conditionalReads = 0, vertices = 0;
    for (int i = 0; i < 64; ++i) {
        RecordingSampler sampler;
        sampler.startPixelSample(0, 0, i);
        CameraSample cs{{float(i % 8) + 0.5f, float(i / 8) + 0.5f}, {0.5f, 0.5f}};
        Ray ray = scene->camera().generateRay(cs);
        auto* camera = static_cast<PathVertex*>(scratch.allocBytes(sizeof(PathVertex) * 10, alignof(PathVertex)));
        auto* light = static_cast<PathVertex*>(scratch.allocBytes(sizeof(PathVertex) * 10, alignof(PathVertex)));
        sampler.startStream(BDPTIntegrator::kCameraStream);
        sampler.seekDimension(Subpaths::kCameraStartDimensions);
        Sampler& walks = sampler;  // the walks' generic instantiation
        int n = paths.cameraSubpath(ray, walks, scratch, stats, camera);
        sampler.startStream(BDPTIntegrator::kLightStream);
        n += paths.lightSubpath(walks, 0.0f, scratch, stats, light);
        vertices += n;
        int lastBlock[8] = {-1, -1, -1, -1, -1, -1, -1, -1};
        for (const RecordingSampler::Read& r : sampler.reads) {
            const int start = r.stream == BDPTIntegrator::kCameraStream ? Subpaths::kCameraStartDimensions
                                                                         : Subpaths::kLightStartDimensions;
            if (r.stream == BDPTIntegrator::kLightStream && r.index < start) continue;  // the emission sample
            ASSERT_GE(r.index, start) << "stream " << r.stream;
            const int block = (r.index - start) / Subpaths::kDimensionsPerVertex;
            const int slot = (r.index - start) % Subpaths::kDimensionsPerVertex;
            // Blocks are visited in order, each vertex's direction first.
            ASSERT_GE(block, lastBlock[r.stream]) << "stream " << r.stream << " index " << r.index;
            if (block > lastBlock[r.stream]) {
                EXPECT_EQ(slot, 0) << "stream " << r.stream << " index " << r.index;
            }
            lastBlock[r.stream] = block;
            conditionalReads += slot >= 2;
            // Slot 2 is the lobe choice: read only at a vertex whose BxDF draws one (a roulette
            // read that followed on from the direction would land there too).
            if (slot == 2) {
                const PathVertex& v = (r.stream == BDPTIntegrator::kCameraStream ? camera : light)[block + 1];
                EXPECT_TRUE(v.bxdf && v.bxdf->usesLobeSample()) << "stream " << r.stream << " index " << r.index;
            }
        }
        scratch.reset();
    }
    std::printf("[ dims     ] %d vertices, %d lobe-choice and roulette reads, each in its vertex's block\n", vertices,
                conditionalReads);
    EXPECT_GT(conditionalReads, 50) << "the walks must draw lobe choices and roulette";
}

// The connections of a BDPT sample: strategy (s, t) reads its block of the connection stream,
// ordered by depth and then s.
TEST(SampleDimensions, ConnectionBlocksAreDistinct) {
    std::vector<int> seen;
    for (int depth = 0; depth <= 6; ++depth)
        for (int s = 0; s <= depth + 1; ++s) seen.push_back(BDPTIntegrator::connectionDimension(s, depth + 2 - s));
    for (size_t i = 1; i < seen.size(); ++i) EXPECT_EQ(seen[i], seen[i - 1] + BDPTIntegrator::kDimensionsPerConnection);
    EXPECT_EQ(seen[0], 0);
}
