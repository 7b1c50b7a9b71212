// Jakob & Hanika's spectral form: a quadratic in wavelength squashed into [0,1] by a
// sigmoid, smooth and bounded, three numbers per RGB (pbrt-v4's RGBSigmoidPolynomial).
#pragma once
#include <algorithm>
#include <cmath>

namespace ps {

struct SigmoidPolynomial {
    float c0 = 0, c1 = 0, c2 = 0;  // c0 lambda^2 + c1 lambda + c2, lambda in nm

    // S(x) = 1/2 + x / (2 sqrt(1 + x^2)); infinite x (grey 0 or 1) gives exactly 0 or 1.
    static float sigmoid(float x) {
        if (std::isinf(x)) return x > 0 ? 1.0f : 0.0f;
        return 0.5f + x / (2 * std::sqrt(1 + x * x));
    }
    float operator()(float lambda) const { return sigmoid((c0 * lambda + c1) * lambda + c2); }

    // The sigmoid is monotonic, so the maximum over [360, 830] is at an end or at the
    // quadratic's vertex.
    float maxValue() const {
        float m = std::max((*this)(360), (*this)(830));
        const float vertex = -c1 / (2 * c0);
        if (vertex >= 360 && vertex <= 830) m = std::max(m, (*this)(vertex));
        return m;
    }
};

}  // namespace ps
