// A spectrum as a scene parameter defines it, in the forms pbrt-v4 has (util/spectrum.h):
// evaluated at any wavelength, at a path's sampled wavelengths, and bounded above.
#pragma once
#include <array>
#include <memory>
#include <span>
#include <variant>
#include <vector>

#include "spectral/colorimetry.h"
#include "spectral/piecewise_linear.h"
#include "spectral/sigmoid_polynomial.h"
#include "spectral/wavelengths.h"

namespace ps {

class SpectrumSource {
  public:
    enum class Kind { Constant, PiecewiseLinear, Dense, Blackbody, RGBAlbedo, RGBUnbounded, RGBIlluminant };

    SpectrumSource() : SpectrumSource(constant(0)) {}

    static SpectrumSource constant(float c);
    // (lambda[i], value[i]) with lambda increasing, zero outside (an inline `spectrum` or an
    // .spd file in pbrt-v4: neither is extended to the visible range).
    static SpectrumSource piecewiseLinear(std::vector<float> lambda, std::vector<float> value);
    static SpectrumSource piecewiseLinear(PiecewiseLinearTable table);
    static SpectrumSource dense(std::shared_ptr<const DenseSpectrum> s);
    // Planck's law at `kelvin`, divided by its value at the peak wavelength 2.8977721e-3 / T m
    // (Wien), so that its maximum is 1 (pbrt-v4's BlackbodySpectrum).
    static SpectrumSource blackbody(float kelvin);
    // RGB lifted through `space`'s coefficient table (rgb in [0,1]; pbrt-v4 rejects > 1 when
    // parsing, here it is clamped).
    static SpectrumSource rgbAlbedo(const RGBColorSpace& space, std::array<float, 3> rgb);
    // scale * S(rgb / scale) with scale = 2 max(rgb): the polynomial is fitted to a colour at
    // half brightness, where the sigmoid form reaches the most saturated colours.
    static SpectrumSource rgbUnbounded(const RGBColorSpace& space, std::array<float, 3> rgb);
    // The unbounded form times `space`'s standard illuminant (1 nm, nearest-nm lookup), so that
    // RGB (1,1,1) emits the space's white.
    static SpectrumSource rgbIlluminant(const RGBColorSpace& space, std::array<float, 3> rgb);

    Kind kind() const;
    float at(float lambda) const;
    SpectralValues sample(const SampledWavelengths& w) const;
    float maxValue() const;

    // pbrt-v4's SpectrumToPhotometric: sum over the 1 nm grid of ybar times the spectrum,
    // except that an RGB illuminant counts its illuminant alone (its RGB is a multiplier
    // the light keeps). Lights divide their `scale` by it.
    double photometric() const;

  private:
    struct Constant {
        float c;
    };
    struct Tabulated {
        std::shared_ptr<const PiecewiseLinearTable> table;
    };
    struct Dense {
        std::shared_ptr<const DenseSpectrum> s;
    };
    struct Blackbody {
        float kelvin, normalization;
    };
    struct RGBAlbedo {
        SigmoidPolynomial poly;
    };
    struct RGBUnbounded {
        float scale;
        SigmoidPolynomial poly;
    };
    struct RGBIlluminant {
        float scale;
        SigmoidPolynomial poly;
        const DenseSpectrum* illuminant;
    };
    using Variant = std::variant<Constant, Tabulated, Dense, Blackbody, RGBAlbedo, RGBUnbounded, RGBIlluminant>;
    explicit SpectrumSource(Variant v) : v_(std::move(v)) {}
    Variant v_;
};

// Planck's law: spectral radiance of a blackbody at `kelvin` (W / (m^2 sr m)), lambda in nm.
double planck(double lambdaNm, double kelvin);

// Integrals over the 1 nm grid 360..830 (pbrt-v4's InnerProduct), XYZ / kCieYIntegral.
XYZ spectrumToXYZ(const SpectrumSource& s);
double innerProduct(const SpectrumSource& s, const float* table1nm);

// The CIE daylight illuminant at colour temperature `kelvin` (pbrt-v4's Spectra::D): the
// temperature is first rescaled by 1.4388/1.4380 (the revised c2 of Planck's law, as the
// CIE's D65 = 6504 K); below 4000 K, where the daylight locus is undefined, the normalised
// blackbody instead. Sampled at 1 nm.
DenseSpectrum daylightSpectrum(float kelvin);

}  // namespace ps
