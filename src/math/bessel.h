// The modified Bessel function of the first kind of order 0, and its logarithm for
// arguments where I0 itself overflows (the hair model's longitudinal lobes need both).
#pragma once
#include <cmath>

namespace ps {

// Power series sum_i (x^2/4)^i / (i!)^2, summed until the terms stop mattering: accurate
// to double rounding for |x| <= 700 (I0 overflows a little beyond).
inline double besselI0(double x) {
    const double q = x * x / 4;
    double term = 1, sum = 1;
    for (int i = 1; i < 500; ++i) {
        term *= q / (double(i) * i);
        sum += term;
        if (term < sum * 1e-17) break;
    }
    return sum;
}

// log I0(x): the series below 30; above, the asymptotic expansion
// e^x / sqrt(2 pi x) (1 + 1/(8x) + 9/(128x^2) + 225/(3072x^3) + 11025/(98304x^4)),
// whose first neglected term is below 1e-8 there.
inline double logBesselI0(double x) {
    x = std::fabs(x);
    if (x < 30) return std::log(besselI0(x));
    const double r = 1 / x;
    const double series = 1 + r * (1.0 / 8 + r * (9.0 / 128 + r * (225.0 / 3072 + r * (11025.0 / 98304))));
    return x - 0.5 * std::log(2 * M_PI * x) + std::log(series);
}

}  // namespace ps
