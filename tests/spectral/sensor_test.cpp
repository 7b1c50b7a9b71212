#include <gtest/gtest.h>

#include "spectral/named_spectra.h"
#include "spectral_test_util.h"

using namespace ps;
using namespace ps::test;

namespace {

void expectIdentity(const Matrix3& m, double tol) {
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) EXPECT_NEAR(m.a[i][j], i == j ? 1.0 : 0.0, tol) << i << "," << j;
}

}  // namespace

// A light "spectrum L" of D65 with scale 1 emits D65 / (its photometric integral) (pbrt-v4
// lights divide by SpectrumToPhotometric); seen directly through the cie1931 sensor it is
// sRGB (1,1,1), within 4 standard errors per channel.
TEST(Sensor, D65LightGivesSrgbWhite) {
    const SpectrumSource d65 = *namedSpectrum("stdillum-D65");
    const Sensor sensor = Sensor::create({}, srgbColorSpace()).sensor;
    const Estimate e = sensorEstimate(sensor, d65, 1 / d65.photometric(), 400000, 3);
    for (int c = 0; c < 3; ++c) {
        EXPECT_LT(std::fabs(e.mean[c] - 1), 4 * e.stderr_[c]) << c << " " << e.mean[c] << " +- " << e.stderr_[c];
        EXPECT_LT(e.stderr_[c], 3e-3);
    }
}

// "rgb L [1 1 1]" in sRGB: the RGB illuminant spectrum over its photometric integral comes
// back as (1,1,1): exactly on the 1 nm grid, and within 4 sigma through the sensor.
TEST(Sensor, RgbIlluminantWhiteRoundTrip) {
    const SpectrumSource L = SpectrumSource::rgbIlluminant(srgbColorSpace(), {1, 1, 1});
    const double scale = 1 / L.photometric();
    const XYZ xyz{innerProduct(L, kCieX) * scale, innerProduct(L, kCieY) * scale, innerProduct(L, kCieZ) * scale};
    const auto rgb = colorimetry(srgbColorSpace()).rgbFromXYZ * xyz;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(rgb[c], 1.0, 1e-5) << c;

    const Estimate e = sensorEstimate(Sensor::create({}, srgbColorSpace()).sensor, L, scale, 200000, 5);
    for (int c = 0; c < 3; ++c) EXPECT_LT(std::fabs(e.mean[c] - 1), 4 * e.stderr_[c]) << c << " " << e.mean[c];
}

TEST(Sensor, IsoAndExposureTimeScale) {
    const SampledWavelengths w = SampledWavelengths::sampleVisible(0.37f);
    const SpectralValues L{0.3f, 1.2f, 0.7f, 2.0f};
    const auto base = Sensor::create({}, srgbColorSpace()).sensor.toOutputRGB(L, w);
    SensorSettings s;
    s.iso = 150;
    s.exposureTime = 0.5f;
    const Sensor scaled = Sensor::create(s, srgbColorSpace()).sensor;
    EXPECT_FLOAT_EQ(scaled.imagingRatio(), 0.75f);
    const auto rgb = scaled.toOutputRGB(L, w);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(rgb[c], 0.75 * base[c], 1e-6 * std::fabs(base[c]) + 1e-9);
    EXPECT_FLOAT_EQ(Sensor::create({}, srgbColorSpace()).sensor.imagingRatio(), 1.0f);
}

// White balancing to the temperature of the space's own white changes nothing: D65 is the
// daylight at 6500 K (6504 K after pbrt's 1.4388/1.4380 rescaling), ACES' D60 at 6000 K.
TEST(Sensor, WhiteBalanceAtTheSpacesOwnWhiteIsTheIdentity) {
    SensorSettings s;
    s.whiteBalance = 6500;
    expectIdentity(Sensor::create(s, srgbColorSpace()).sensor.whiteBalance(), 2e-4);  // measured 1.0e-4
    s.whiteBalance = 6000;
    expectIdentity(Sensor::create(s, *namedColorSpace("aces2065-1")).sensor.whiteBalance(), 6e-4);  // measured 4.6e-4
    s.whiteBalance = 0;
    expectIdentity(Sensor::create(s, srgbColorSpace()).sensor.whiteBalance(), 0);
}

// White balance for T makes the light it is named after neutral: a 3000 K source (below
// 4000 K the reference is the blackbody) and a 5000 K daylight come out grey.
TEST(Sensor, WhiteBalanceNeutralisesItsIlluminant) {
    for (float T : {3000.0f, 5000.0f}) {
        SensorSettings s;
        s.whiteBalance = T;
        const Sensor sensor = Sensor::create(s, srgbColorSpace()).sensor;
        auto d = std::make_shared<DenseSpectrum>(daylightSpectrum(T));
        const SpectrumSource src = SpectrumSource::dense(d);
        const XYZ xyz{innerProduct(src, kCieX), innerProduct(src, kCieY), innerProduct(src, kCieZ)};
        const auto rgb = sensor.outputFromSensor() * xyz;
        EXPECT_NEAR(rgb[0] / rgb[1], 1.0, 1e-3) << T;
        EXPECT_NEAR(rgb[2] / rgb[1], 1.0, 1e-3) << T;
        // Without white balance the same light is far from neutral.
        const auto raw = Sensor::create({}, srgbColorSpace()).sensor.outputFromSensor() * xyz;
        EXPECT_GT(std::fabs(raw[2] / raw[1] - 1), 0.1) << T;
    }
}

TEST(Sensor, UnsupportedSensorFallsBackToCie1931) {
    SensorSettings s;
    s.name = "canon_eos_100d";
    const Sensor::Created c = Sensor::create(s, srgbColorSpace());
    EXPECT_NE(c.unsupported.find("canon_eos_100d"), std::string::npos);
    EXPECT_TRUE(Sensor::create({}, srgbColorSpace()).unsupported.empty());
    const SampledWavelengths w = SampledWavelengths::sampleVisible(0.5f);
    const SpectralValues L{1, 1, 1, 1};
    EXPECT_EQ(c.sensor.toOutputRGB(L, w), Sensor::create({}, srgbColorSpace()).sensor.toOutputRGB(L, w));
}

// Terminated secondary wavelengths (pdf 0) are skipped, not divided by.
TEST(Sensor, ZeroPdfWavelengthsContributeNothing) {
    SampledWavelengths w = SampledWavelengths::sampleVisible(0.2f);
    w.terminateSecondary();
    const SpectralValues L{1, 5, 5, 5};
    const auto xyz = Sensor::create({}, srgbColorSpace()).sensor.toSensorXYZ(L, w);
    const double expectY = denseLookup(kCieY, w.lambda[0]) / w.pdf[0] / 4;
    EXPECT_NEAR(xyz[1], expectY, 1e-9 + 1e-6 * expectY);
    for (double v : xyz) EXPECT_TRUE(std::isfinite(v));
}

// sensorRGB, the exact answer the render tests expect in spectral mode, checked for "rgb L"
// emitters (rgbIlluminant / photometric): it returns the RGB (to the tables' round-trip
// accuracy); the 1 nm sum agrees with the sensor's continuous integral (midpoints of 0.01 nm
// steps; the matching functions at the nearest nm, as the sensor looks them up); and it is the
// mean of the sensor's estimate, both the Monte Carlo one and its average over a 10^5-point
// midpoint grid of the wavelength sample u (a quadrature of its expectation).
TEST(Sensor, SensorRGBIsTheSensorsExpectation) {
    const Sensor sensor = Sensor::create({}, srgbColorSpace()).sensor;
    const std::array<float, 3> colours[] = {{1, 1, 1}, {2, 3, 4}, {0.8f, 0.9f, 1}, {1, 0, 0}, {0.2f, 0.5f, 0.9f}};
    for (const auto& rgb : colours) {
        const SpectrumSource s = SpectrumSource::rgbIlluminant(srgbColorSpace(), rgb);
        const double scale = 1 / s.photometric();
        const auto exact = sensorRGB(sensor, [&](double l) { return s.at(float(l)) * scale; });
        XYZ fine{0, 0, 0};
        for (int k = 0; k < (kCieSamples - 1) * 100; ++k) {
            const float l = kCieLambdaMin + (k + 0.5f) / 100;
            const double v = s.at(l) * scale / 100;
            fine[0] += denseLookup(kCieX, l) * v;
            fine[1] += denseLookup(kCieY, l) * v;
            fine[2] += denseLookup(kCieZ, l) * v;
        }
        const auto continuous = sensor.outputFromSensor() * fine;
        const Estimate e = sensorEstimate(sensor, s, scale, 400000, 9);
        const int n = 100000;
        std::array<double, 3> quadrature{0, 0, 0};
        for (int k = 0; k < n; ++k) {
            const SampledWavelengths w = SampledWavelengths::sampleVisible(float((k + 0.5) / n));
            SpectralValues L = s.sample(w);
            for (float& v : L) v = float(v * scale);
            const auto rgbk = sensor.toOutputRGB(L, w);
            for (int c = 0; c < 3; ++c) quadrature[c] += rgbk[c] / n;
        }
        const double max = std::max({rgb[0], rgb[1], rgb[2]});
        for (int c = 0; c < 3; ++c) {
            std::printf("rgb %g: channel %d sensorRGB %.6f, continuous %.6f, quadrature %.6f, Monte Carlo %.6f +- %.6f\n",
                        rgb[c], c, exact[c], continuous[c], quadrature[c], e.mean[c], e.stderr_[c]);
            EXPECT_NEAR(exact[c], rgb[c], 1e-3 * max) << c;         // measured 4e-4 (red of 2 3 4)
            EXPECT_NEAR(exact[c], continuous[c], 1e-4 * max) << c;  // measured 2e-5
            EXPECT_NEAR(exact[c], quadrature[c], 3e-5 * max) << c;  // measured 1.4e-5
            EXPECT_LT(std::fabs(e.mean[c] - exact[c]), 4 * e.stderr_[c]) << c;
        }
    }
}
