// Material "measured": the tensor-file reader (round trip, clear errors), and the measured
// BxDF on a file generated from an analytic GGX reflector (measured_tensor_writer.h): f
// against the analytic BRDF, sample() against pdf() and f(), the sampled estimator against
// uniform sampling, chi-square of sampled directions, spectra converted like other spectra.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <unistd.h>

#include "materials/create.h"
#include "materials/measured_bxdf.h"
#include "materials/tensor_file.h"
#include "math/warp.h"
#include "measured_tensor_writer.h"
#include "param_builder.h"
#include "scene/spectra.h"
#include "stats.h"
#include "util/error.h"

using namespace ps;
using namespace ps::test;
namespace fs = std::filesystem;

namespace {

struct TempDir {
    fs::path dir = fs::temp_directory_path() / ("pathspace-measured-" + std::to_string(getpid()));
    TempDir() { fs::create_directories(dir); }
    ~TempDir() { fs::remove_all(dir); }
    std::string write(const std::string& name, const std::string& bytes) const {
        std::string p = (dir / name).string();
        writeBytes(p, bytes);
        return p;
    }
};

MeasuredBxDF bxdfFor(const TempDir& t, const std::string& name, const GgxTableSpec& spec) {
    return MeasuredBxDF(MeasuredBRDF::load(t.write(name, tensorFileBytes(ggxTensorFields(spec)))));
}

// The message of the InputError that creating `Material "measured"` with this file throws.
std::string materialError(const std::string& file) {
    Params p;
    p.s("filename", file);
    try {
        createMaterial("measured", p, TextureRegistry{}, {}, "/");
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no error)";
}

}  // namespace

TEST(MeasuredReader, RoundTrip) {
    TempDir t;
    GgxTableSpec spec;
    std::vector<TensorField> fields = ggxTensorFields(spec);
    TensorFile tf = TensorFile::read(t.write("a.bsdf", tensorFileBytes(fields)));
    for (const TensorField& f : fields) {
        ASSERT_TRUE(tf.has(f.name)) << f.name;
        EXPECT_EQ(tf.shape(f.name), f.shape) << f.name;
        if (f.type != 10) continue;
        std::vector<float> v = tf.floats(f.name, f.shape.size());
        ASSERT_EQ(v.size() * 4, f.bytes.size()) << f.name;
        EXPECT_EQ(std::memcmp(v.data(), f.bytes.data(), f.bytes.size()), 0) << f.name;
    }
}

TEST(MeasuredReader, ClearLocatedErrors) {
    TempDir t;
    std::string good = tensorFileBytes(ggxTensorFields(GgxTableSpec{}));
    struct Case {
        const char* what;
        std::string file, expect;
    };
    std::vector<TensorField> noSigma = ggxTensorFields(GgxTableSpec{});
    noSigma.erase(noSigma.begin() + 3);
    std::vector<TensorField> badShape = ggxTensorFields(GgxTableSpec{});
    badShape[4].shape = {1, 6, 64, 32};  // vndf against 12 theta_i values
    std::string badMagic = good;
    badMagic[0] = 'T';
    std::vector<Case> cases = {
        {"missing", (t.dir / "absent.bsdf").string(), "cannot open tensor file"},
        {"wrong magic", t.write("magic.bsdf", badMagic), "not a tensor file"},
        {"truncated data", t.write("cut.bsdf", good.substr(0, good.size() / 2)), "past the end of the file (truncated?)"},
        {"truncated header", t.write("head.bsdf", good.substr(0, 40)), "truncated in the header"},
        {"missing field", t.write("nosigma.bsdf", tensorFileBytes(noSigma)), "no field \"sigma\""},
        {"shape mismatch", t.write("shape.bsdf", tensorFileBytes(badShape)), "field \"vndf\" has shape [1, 6, 64, 32]"},
    };
    for (const Case& c : cases) {
        std::string msg = materialError(c.file);
        std::printf("  %s: %s\n", c.what, msg.c_str());
        EXPECT_NE(msg.find("test.pbrt:"), std::string::npos) << c.what << ": " << msg;  // the directive's place
        EXPECT_NE(msg.find("error:"), std::string::npos) << c.what << ": " << msg;
        EXPECT_NE(msg.find(c.file), std::string::npos) << c.what << ": " << msg;
        EXPECT_NE(msg.find(c.expect), std::string::npos) << c.what << ": " << msg;
    }
}

// f against the analytic BRDF the file was made from, over wo and wi on a grid of the
// tabulated range. The tables interpolate linearly in the square-root theta parameterisation
// on a 32x32 grid with 12 theta_i slices: errors of a few percent where the lobe is bright.
TEST(MeasuredBxDF, MatchesTheAnalyticBRDF) {
    TempDir t;
    GgxTableSpec spec;
    MeasuredBxDF b = bxdfFor(t, "ggx.bsdf", spec);
    double sumErr = 0, sumRef = 0, worst = 0;
    int n = 0;
    for (float co : {0.95f, 0.7f, 0.4f, 0.2f})
        for (float ci = 0.1f; ci < 1; ci += 0.1f)
            for (float phi = 0; phi < 6.28f; phi += 0.5f) {
                Vec3 wo = directionAt(co, 0.4f), wi = directionAt(ci, phi);
                Spectrum f = b.f(wo, wi, TransportMode::Radiance), ref = ggxReference(spec, wo, wi);
                // Compare f cos(wi), the quantity rendered.
                for (int c = 0; c < 3; ++c) {
                    double e = std::fabs(double(f[c]) - ref[c]) * ci;
                    sumErr += e;
                    sumRef += ref[c] * ci;
                    worst = std::max(worst, e / (ref[c] * ci + 0.05));
                }
                ++n;
            }
    double rel = sumErr / sumRef;
    std::printf("  %d direction pairs: mean |f - f_ref| cos / mean f_ref cos = %.4f; worst |diff| / (f_ref cos + 0.05) = %.4f\n",
                n, rel, worst);
    EXPECT_LT(rel, 0.03);
    EXPECT_LT(worst, 0.15);
    // Colour: the rgb field's reflectance carries through exactly.
    Vec3 wo = directionAt(0.8f, 0.2f), wi = directionAt(0.6f, 3.0f);
    Spectrum f = b.f(wo, wi, TransportMode::Radiance);
    EXPECT_NEAR(f.r / f.g, spec.R.r / spec.R.g, 1e-5);
    EXPECT_NEAR(f.b / f.g, spec.R.b / spec.R.g, 1e-5);
    // Reflection only, on either side, and both modes alike.
    EXPECT_TRUE(b.f(wo, Vec3(wi.x, wi.y, -wi.z), TransportMode::Radiance).isBlack());
    Spectrum below = b.f(-wo, -wi, TransportMode::Radiance);
    EXPECT_FLOAT_EQ(below.g, f.g);
    EXPECT_FLOAT_EQ(b.f(wo, wi, TransportMode::Importance).g, f.g);
}

TEST(MeasuredBxDF, SampleAgreesWithPdfAndF) {
    TempDir t;
    MeasuredBxDF b = bxdfFor(t, "ggx.bsdf", GgxTableSpec{});
    Rng rng(3);
    double worstPdf = 0, worstF = 0, sumPdf = 0;
    int ok = 0;
    for (int i = 0; i < 20000; ++i) {
        Vec3 wo = directionAt(0.05f + 0.95f * rng.uniform(), 6.28f * rng.uniform());
        if (i % 2) wo = -wo;
        auto s = b.sample(wo, rng.uniform(), Vec2(rng.uniform(), rng.uniform()), TransportMode::Radiance);
        if (!s) continue;
        ++ok;
        EXPECT_TRUE(sameHemisphere(wo, s->wi));
        BxDFEval e = b.evaluate(wo, s->wi, TransportMode::Radiance);
        worstPdf = std::max(worstPdf, std::fabs(double(e.pdfFwd) / s->pdf - 1));
        sumPdf += std::fabs(double(e.pdfFwd) / s->pdf - 1);
        worstPdf = std::max(worstPdf, std::fabs(double(b.pdf(wo, s->wi, TransportMode::Radiance)) / s->pdf - 1));
        worstF = std::max(worstF, std::fabs(double(e.f.g) - s->f.g) / std::max(1e-3f, s->f.g));
        EXPECT_FLOAT_EQ(e.pdfRev, b.pdf(s->wi, wo, TransportMode::Importance));
    }
    std::printf("  %d samples: relative |pdf() - sample pdf| mean %.3g, largest %.3g; largest |f() - sample f| %.3g\n", ok,
                sumPdf / ok, worstPdf, worstF);
    // pdf() recomputes wm and its angles from wo + wi in float: near the pole (small u, sin
    // theta) that round trip moves the density by up to about 1%.
    EXPECT_GT(ok, 15000);
    EXPECT_LT(sumPdf / ok, 1e-4);
    EXPECT_LT(worstPdf, 2e-2);
    EXPECT_LT(worstF, 2e-3);
}

// The reflected fraction of light from wo, estimated by importance sampling and by uniform
// hemisphere sampling of f cos: two independent estimators of one integral.
TEST(MeasuredBxDF, ImportanceSamplingAgreesWithUniformSampling) {
    TempDir t;
    MeasuredBxDF b = bxdfFor(t, "ggx.bsdf", GgxTableSpec{});
    for (float co : {0.9f, 0.5f, 0.2f}) {
        Vec3 wo = directionAt(co, 1.0f);
        MeanSE is = furnace(b, wo, TransportMode::Radiance, 100000, 5);
        Rng rng(6);
        MeanSE uni = meanAndError(400000, [&] {
            Vec3 wi = sampleUniformHemisphere(Vec2(rng.uniform(), rng.uniform()));
            return double(b.f(wo, wi, TransportMode::Radiance).g) * wi.z / uniformHemispherePdf();
        });
        double sigma = std::hypot(is.se, uni.se), z = (is.mean - uni.mean) / sigma;
        std::printf("  cos wo %.1f: importance %.5f +- %.5f, uniform %.5f +- %.5f, diff %.2f sigma\n", co, is.mean, is.se,
                    uni.mean, uni.se, z);
        EXPECT_LT(std::fabs(z), 4.0);
        EXPECT_LT(4 * sigma, 0.02 * uni.mean);  // precise enough to see a 2% bias
    }
}

TEST(MeasuredBxDF, SampledDirectionsFollowPdf) {
    TempDir t;
    MeasuredBxDF b = bxdfFor(t, "ggx.bsdf", GgxTableSpec{});
    const SphereGrid grid(16, 32);
    const int n = 200000;
    for (float co : {0.9f, 0.3f}) {
        Vec3 wo = directionAt(co, 0.7f);
        std::vector<double> observed(grid.cells(), 0);
        Rng rng(8);
        for (int i = 0; i < n; ++i)
            if (auto s = b.sample(wo, rng.uniform(), Vec2(rng.uniform(), rng.uniform()), TransportMode::Radiance))
                observed[grid.cellOf(s->wi)] += 1;
        std::vector<double> expected = grid.integrate([&](Vec3 wi) { return n * double(b.pdf(wo, wi, TransportMode::Radiance)); }, 6);
        double total = 0;
        for (double e : expected) total += e / n;
        auto r = chiSquare(observed, expected);
        std::printf("  cos wo %.1f: chi2 %.1f, dof %d, p %.3g; integral of pdf %.4f\n", co, r.chi2, r.dof, r.pValue, total);
        EXPECT_GT(r.pValue, 1e-4);
        EXPECT_LE(total, 1.005);  // 1 less the samples that fall below the horizon
        EXPECT_GT(total, 0.9);
    }
}

// A `spectra` file: its reflectance converted with the same CIE/D65 integration as every
// other reflectance spectrum; a flat spectrum gives the same f as the grey rgb file.
TEST(MeasuredBxDF, SpectraConvertLikeOtherSpectra) {
    TempDir t;
    GgxTableSpec rgbSpec, specSpec;
    rgbSpec.R = Spectrum(rgbSpec.R.g);
    specSpec.wavelengths = {360, 500, 650, 830};
    MeasuredBxDF a = bxdfFor(t, "grey_rgb.bsdf", rgbSpec), s = bxdfFor(t, "grey_spectra.bsdf", specSpec);
    Vec3 wo = directionAt(0.8f, 0.2f), wi = directionAt(0.6f, 3.0f);
    Spectrum fa = a.f(wo, wi, TransportMode::Radiance), fs = s.f(wo, wi, TransportMode::Radiance);
    std::printf("  flat spectrum: f = (%.6f %.6f %.6f), grey rgb: %.6f\n", fs.r, fs.g, fs.b, fa.g);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(fs[c], fa.g, 1e-4 * fa.g);
    // The sample weights against the reflectance conversion of a spectrum within [0, 1].
    std::vector<float> lambda{360, 450, 520, 610, 700, 830}, v{0.1f, 0.8f, 0.3f, 0.6f, 0.9f, 0.9f};
    std::vector<Spectrum> w = reflectanceSampleWeights(lambda);
    Spectrum sum, ref = sampledSpectrumToRGB(lambda, v, SpectrumKind::Albedo);
    for (size_t k = 0; k < v.size(); ++k) sum += w[k] * v[k];
    std::printf("  weights: (%.5f %.5f %.5f), albedo conversion (%.5f %.5f %.5f)\n", sum.r, sum.g, sum.b, ref.r, ref.g, ref.b);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c], ref[c], 2e-3);
}
