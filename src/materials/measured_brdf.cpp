#include "materials/measured_brdf.h"

#include <cmath>
#include <filesystem>
#include <map>
#include <mutex>
#include <stdexcept>

#include "materials/tensor_file.h"
#include "math/spectrum.h"
#include "scene/spectra.h"
#include "util/error.h"

namespace ps {

namespace {

std::string shapeText(const std::vector<uint64_t>& s) {
    std::string out = "[";
    for (size_t i = 0; i < s.size(); ++i) out += (i ? ", " : "") + std::to_string(s[i]);
    return out + "]";
}

// A field's shape must equal `want` where `want` is non-zero.
void checkShape(const TensorFile& tf, const std::string& name, const std::vector<uint64_t>& want, const std::string& why) {
    const std::vector<uint64_t>& s = tf.shape(name);
    bool ok = s.size() == want.size();
    for (size_t i = 0; ok && i < s.size(); ++i) ok = want[i] == 0 || s[i] == want[i];
    if (!ok) throw InputError(tf.path() + ": field \"" + name + "\" has shape " + shapeText(s) + "; " + why);
}

// A warp or interpolant built from a field; its own complaints name the field.
PiecewiseLinear2D table(const TensorFile& tf, const std::string& name, const std::vector<float>& data, int x, int y,
                        std::vector<std::vector<float>> params, PiecewiseLinear2D::Mode mode) {
    try {
        return PiecewiseLinear2D(data.data(), x, y, std::move(params), mode);
    } catch (const std::invalid_argument& e) {
        throw InputError(tf.path() + ": field \"" + name + "\": " + e.what());
    }
}

std::shared_ptr<const MeasuredBRDF> read(const std::string& path) {
    using Mode = PiecewiseLinear2D::Mode;
    TensorFile tf = TensorFile::read(path);
    auto b = std::make_shared<MeasuredBRDF>();
    std::vector<float> thetaI = tf.floats("theta_i", 1), phiI = tf.floats("phi_i", 1);
    if (thetaI.empty() || phiI.empty()) throw InputError(path + ": fields \"theta_i\" and \"phi_i\" must not be empty");
    const uint64_t nPhi = phiI.size(), nTheta = thetaI.size();
    const std::string perWo = "it must be [phi_i, theta_i, ...] = [" + std::to_string(nPhi) + ", " + std::to_string(nTheta) + ", ...]";
    b->isotropic = nPhi <= 2;
    if (!b->isotropic) {
        // pbrt-v4 takes anisotropic data over the full circle only (no symmetry folding).
        float span = phiI.back() - phiI.front();
        if (!(span > 0) || std::lrint(2 * kPi / span) != 1)
            throw InputError(path + ": field \"phi_i\" must span the full circle (2 pi) for anisotropic data");
    }

    std::vector<float> ndf = tf.floats("ndf", 2), sigma = tf.floats("sigma", 2);
    std::vector<float> vndf = tf.floats("vndf", 4), lum = tf.floats("luminance", 4);
    checkShape(tf, "vndf", {nPhi, nTheta, 0, 0}, perWo);
    checkShape(tf, "luminance", {nPhi, nTheta, 0, 0}, perWo);
    const auto& ls = tf.shape("luminance");
    if (ls[2] != ls[3]) throw InputError(path + ": field \"luminance\" must be square in its last two dimensions, not " + shapeText(ls));
    const uint64_t n = ls[2];
    const std::vector<std::vector<float>> wo = {phiI, thetaI};
    auto dims = [&](const std::string& f, int i) { return int(std::min<uint64_t>(tf.shape(f)[i], 1u << 30)); };
    b->ndf = table(tf, "ndf", ndf, dims("ndf", 1), dims("ndf", 0), {}, Mode::Interpolant);
    b->sigma = table(tf, "sigma", sigma, dims("sigma", 1), dims("sigma", 0), {}, Mode::Interpolant);
    b->vndf = table(tf, "vndf", vndf, dims("vndf", 3), dims("vndf", 2), wo, Mode::Warp);
    b->luminance = table(tf, "luminance", lum, int(n), int(n), wo, Mode::Warp);

    // The reflectance, per channel, on luminance's grid.
    const std::string sameGrid = "it must be [phi_i, theta_i, channels, n, n] with n = " + std::to_string(n) + " as in \"luminance\"";
    std::vector<float> rgb;
    if (tf.has("rgb")) {
        rgb = tf.floats("rgb", 5);
        checkShape(tf, "rgb", {nPhi, nTheta, 3, n, n}, sameGrid + " and 3 channels");
    } else {
        if (!tf.has("spectra")) throw InputError(path + ": the tensor file has neither an \"rgb\" nor a \"spectra\" field");
        std::vector<float> spectra = tf.floats("spectra", 5), lambda = tf.floats("wavelengths", 1);
        checkShape(tf, "spectra", {nPhi, nTheta, lambda.size(), n, n}, sameGrid + " and one channel per wavelength");
        if (lambda.empty()) throw InputError(path + ": field \"wavelengths\" must not be empty");
        for (size_t k = 0; k < lambda.size(); ++k)
            if (!std::isfinite(lambda[k]) || (k > 0 && !(lambda[k] > lambda[k - 1])))
                throw InputError(path + ": field \"wavelengths\" must be finite and strictly increasing");
        std::vector<Spectrum> w = reflectanceSampleWeights(lambda);
        const size_t plane = size_t(n) * n, slices = size_t(nPhi) * nTheta;
        rgb.assign(slices * 3 * plane, 0.0f);
        for (size_t s = 0; s < slices; ++s)
            for (size_t k = 0; k < lambda.size(); ++k)
                for (int c = 0; c < 3; ++c) {
                    const float* src = &spectra[(s * lambda.size() + k) * plane];
                    float* dst = &rgb[(s * 3 + c) * plane];
                    for (size_t i = 0; i < plane; ++i) dst[i] += w[k][c] * src[i];
                }
        b->spectra = table(tf, "spectra", spectra, int(n), int(n), {phiI, thetaI, lambda}, Mode::Interpolant);
        b->hasSpectra = true;
    }
    b->rgb = table(tf, tf.has("rgb") ? "rgb" : "spectra", rgb, int(n), int(n), {phiI, thetaI, {0, 1, 2}}, Mode::Interpolant);
    return b;
}

}  // namespace

std::shared_ptr<const MeasuredBRDF> MeasuredBRDF::load(const std::string& path) {
    static std::mutex mutex;
    static std::map<std::string, std::weak_ptr<const MeasuredBRDF>> cache;
    // Keyed by the file's state too, so a file rewritten in between is read again.
    std::error_code ec;
    std::string key = path + '\n' + std::to_string(std::filesystem::file_size(path, ec)) + '\n' +
                      std::to_string(std::filesystem::last_write_time(path, ec).time_since_epoch().count());
    std::lock_guard<std::mutex> lock(mutex);
    if (auto b = cache[key].lock()) return b;
    auto b = read(path);
    cache[key] = b;
    return b;
}

}  // namespace ps
