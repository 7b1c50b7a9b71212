#include "verify/block_statistics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

namespace ps::verify {

namespace {

double luminance(double r, double g, double b) { return 0.2126 * r + 0.7152 * g + 0.0722 * b; }

// The inverse-variance weighted mean of values with standard errors errs, and its error.
// A zero error (a noiseless estimate) takes the plain mean of the noiseless ones.
Estimate pooledEstimate(const std::vector<double>& values, const std::vector<double>& errs) {
    double sw = 0, swx = 0, plain = 0;
    int exact = 0;
    for (size_t i = 0; i < values.size(); ++i) {
        if (!(errs[i] > 0)) {
            plain += values[i];
            ++exact;
            continue;
        }
        const double w = 1 / (errs[i] * errs[i]);
        sw += w;
        swx += w * values[i];
    }
    if (exact > 0) return {plain / exact, 0};
    return sw > 0 ? Estimate{swx / sw, std::sqrt(1 / sw)} : Estimate{};
}

// The standard normal's upper quantile: the z with P(Z > z) = p, by bisection of erfc.
double normalUpperQuantile(double p) {
    double lo = 0, hi = 40;
    for (int i = 0; i < 100; ++i) {
        const double mid = 0.5 * (lo + hi);
        (0.5 * std::erfc(mid / std::sqrt(2.0)) > p ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

std::string fmt(const char* f, double a, double b = 0) {
    char buf[160];
    std::snprintf(buf, sizeof buf, f, a, b);
    return buf;
}

}  // namespace

int blockOf(int x, int y, int nx, int ny, int w, int h) { return (y * ny / h) * nx + x * nx / w; }

BlockPixels blockPixels(int i, int nx, int ny, int w, int h) {
    // The smallest p with p * n / size >= b: where block b's pixels begin.
    auto first = [](int b, int n, int size) { return (b * size + n - 1) / n; };
    const int bx = i % nx, by = i / nx;
    return {first(bx, nx, w), first(bx + 1, nx, w), first(by, ny, h), first(by + 1, ny, h)};
}

ImageSummary summarise(const Image& img, int nx, int ny) {
    ImageSummary s;
    s.blocks.assign(size_t(nx) * ny, 0.0);
    std::vector<int> counts(s.blocks.size(), 0);
    double sum[3] = {0, 0, 0};
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const Spectrum v = img.get(x, y);
            const int b = blockOf(x, y, nx, ny, img.width, img.height);
            s.blocks[size_t(b)] += luminance(v.r, v.g, v.b);
            ++counts[size_t(b)];
            sum[0] += v.r;
            sum[1] += v.g;
            sum[2] += v.b;
        }
    for (size_t b = 0; b < s.blocks.size(); ++b) s.blocks[b] /= std::max(1, counts[b]);
    const double n = std::max(1.0, double(img.width) * img.height);
    for (int c = 0; c < 3; ++c) s.channels[c] = sum[c] / n;
    s.image = luminance(s.channels[0], s.channels[1], s.channels[2]);
    return s;
}

void RunSet::add(const Image& img) {
    runs_.push_back(summarise(img, nx_, ny_));
    if (sum_.rgb.empty()) sum_ = Image(img.width, img.height);
    const float k = float(runs_.size());
    for (size_t i = 0; i < sum_.rgb.size() && i < img.rgb.size(); ++i) sum_.rgb[i] += (img.rgb[i] - sum_.rgb[i]) / k;
}

// The mean of one summary figure over the renders and its standard error from their spread.
template <typename Get>
Estimate acrossRuns(const std::vector<ImageSummary>& runs, Get get) {
    double s = 0, s2 = 0;
    for (const ImageSummary& r : runs) {
        const double v = get(r);
        s += v;
        s2 += v * v;
    }
    const double k = double(runs.size()), m = k > 0 ? s / k : 0;
    return {m, k > 1 ? std::sqrt(std::max(0.0, (s2 / k - m * m) / (k - 1))) : 0};
}

Estimate RunSet::image() const {
    return acrossRuns(runs_, [](const ImageSummary& r) { return r.image; });
}
Estimate RunSet::block(int i) const {
    return acrossRuns(runs_, [i](const ImageSummary& r) { return r.blocks[size_t(i)]; });
}
Estimate RunSet::channel(int c) const {
    return acrossRuns(runs_, [c](const ImageSummary& r) { return r.channels[c]; });
}

Reference referenceFrom(const RunSet& runs, const std::string& what) {
    Reference r;
    r.what = what;
    r.dof = std::max(1, runs.runs() - 1);
    for (int i = 0; i < runs.blockCount(); ++i) r.blocks.push_back(runs.block(i));
    r.image = runs.image();
    for (int c = 0; c < 3; ++c) r.channels[c] = runs.channel(c);
    return r;
}

Reference exactReference(double value, int blockCount) {
    Reference r;
    r.what = "exact";
    r.blocks.assign(size_t(blockCount), Estimate{value, 0});
    r.image = {value, 0};
    r.compareChannels = false;
    return r;
}

Reference pooledOf(const std::vector<const RunSet*>& others, const std::string& what) {
    Reference r;
    r.what = what;
    if (others.empty()) return r;
    r.dof = 0;
    for (const RunSet* o : others) r.dof += std::max(1, o->runs() - 1);
    auto pooled = [&](auto&& get) {
        std::vector<double> v, e;
        for (const RunSet* o : others) {
            const Estimate x = get(*o);
            v.push_back(x.mean);
            e.push_back(x.stdErr);
        }
        return pooledEstimate(v, e);
    };
    for (int i = 0; i < others.front()->blockCount(); ++i)
        r.blocks.push_back(pooled([i](const RunSet& o) { return o.block(i); }));
    r.image = pooled([](const RunSet& o) { return o.image(); });
    for (int c = 0; c < 3; ++c) r.channels[c] = pooled([c](const RunSet& o) { return o.channel(c); });
    return r;
}

double chiSquareUpperQuantile(int dof, double p) {
    const double z = normalUpperQuantile(p), k = std::max(1, dof), a = 2.0 / (9.0 * k);
    return k * std::pow(1 - a + z * std::sqrt(a), 3);
}

double studentTwoSidedTail(double t, double nu) {
    if (nu > 1e6) return std::erfc(std::fabs(t) / std::sqrt(2.0));
    // The density integrated over u = atan(x) from atan|t| to pi/2 (Simpson's rule): the
    // substitution maps the tail onto a finite interval where the integrand is smooth.
    const double c = std::exp(std::lgamma((nu + 1) / 2) - std::lgamma(nu / 2)) / std::sqrt(nu * M_PI);
    auto f = [&](double u) {
        const double cu = std::cos(u);
        if (cu <= 0) return 0.0;
        const double x = std::tan(u);
        return c * std::pow(1 + x * x / nu, -(nu + 1) / 2) / (cu * cu);
    };
    const double a = std::atan(std::fabs(t)), b = M_PI / 2;
    const int n = 400;
    const double h = (b - a) / n;
    double sum = f(a) + f(b);
    for (int i = 1; i < n; ++i) sum += f(a + i * h) * (i % 2 ? 4 : 2);
    return 2 * sum * h / 3;
}

double fourSigmaEquivalent(double nu) {
    // Welch's nu is continuous; to 1% it changes the bound by far less than 1%.
    nu = nu > 1e4 ? 1e9 : std::max(1.0, std::round(nu * 100) / 100);
    thread_local std::map<double, double> known;
    if (auto it = known.find(nu); it != known.end()) return it->second;
    const double p = std::erfc(4 / std::sqrt(2.0));
    double lo = 4, hi = 200;
    for (int i = 0; i < 40; ++i) {
        const double mid = 0.5 * (lo + hi);
        (studentTwoSidedTail(mid, nu) > p ? lo : hi) = mid;
    }
    return known[nu] = 0.5 * (lo + hi);
}

namespace {

// The normal deviate with the same two-sided tail as t has under Student's t with nu degrees
// of freedom: block z-scores whose squares a chi-square bound can sum.
double normalEquivalent(double t, double nu) {
    if (t == 0) return 0;
    return std::copysign(normalUpperQuantile(0.5 * studentTwoSidedTail(t, nu)), t);
}

// Welch-Satterthwaite: the degrees of freedom of a difference of two means whose standard
// errors a and b have nuA and nuB.
double welch(double a, double nuA, double b, double nuB) {
    const double a2 = a * a, b2 = b * b;
    const double den = a2 * a2 / nuA + b2 * b2 / nuB;
    return den > 0 ? (a2 + b2) * (a2 + b2) / den : 1e9;
}

}  // namespace

Verdict compare(const RunSet& x, const Reference& ref, double blockFloor) {
    Verdict v;
    const double nuX = std::max(1, x.runs() - 1);
    auto critical = [&](double seX, double seRef) { return fourSigmaEquivalent(welch(seX, nuX, seRef, ref.dof)); };
    const Estimate xi = x.image();
    const double se = std::hypot(xi.stdErr, ref.image.stdErr);
    const double refMean = ref.image.mean;
    v.critical = critical(xi.stdErr, ref.image.stdErr);
    v.ratio = refMean != 0 ? xi.mean / refMean : (xi.mean == 0 ? 1 : INFINITY);
    v.imageZ = (xi.mean - refMean) / std::max(se, 1e-300);
    if (xi.mean == refMean) v.imageZ = 0;
    v.resolution = refMean > 0 ? v.critical * se / refMean : INFINITY;
    auto fail = [&](const std::string& why) {
        v.agrees = false;
        v.why += (v.why.empty() ? "" : "; ") + why;
    };
    if (std::fabs(v.imageZ) > v.critical)
        fail(fmt("image mean %.4g of the reference's (%.1f sigma)", v.ratio, v.imageZ));
    for (int c = 0; ref.compareChannels && c < 3; ++c) {
        const Estimate xc = x.channel(c);
        const double sc = std::hypot(xc.stdErr, ref.channels[c].stdErr);
        v.channelZ[c] = (xc.mean - ref.channels[c].mean) / std::max(sc, 1e-300);
        if (xc.mean == ref.channels[c].mean) v.channelZ[c] = 0;
        if (std::fabs(v.channelZ[c]) > critical(xc.stdErr, ref.channels[c].stdErr))
            fail(std::string(c == 0 ? "red" : c == 1 ? "green" : "blue") + fmt(" channel off by %.1f sigma", v.channelZ[c]));
    }
    // Squared block z-scores. A floor of a quarter of blockFloor in quadrature keeps a dim
    // block with an underestimated error from dominating the sum.
    const double floorSe = 0.25 * blockFloor * std::fabs(refMean);
    double worst = -1;
    for (int i = 0; i < x.blockCount() && size_t(i) < ref.blocks.size(); ++i) {
        const Estimate xb = x.block(i), rb = ref.blocks[size_t(i)];
        const double d = xb.mean - rb.mean, sb = std::hypot(xb.stdErr, rb.stdErr);
        const double t = d == 0 ? 0 : d / std::max(std::hypot(sb, floorSe), 1e-300);
        const double z = normalEquivalent(t, welch(xb.stdErr, nuX, rb.stdErr, ref.dof));
        v.blockZ.push_back(z);
        v.chi2 += z * z;
        if (std::fabs(z) > worst) {
            worst = std::fabs(z);
            v.worstBlock = i;
        }
        v.blocksBeyond += std::fabs(d) > critical(xb.stdErr, rb.stdErr) * sb + blockFloor * std::fabs(refMean);
    }
    v.chi2Limit = chiSquareUpperQuantile(int(v.blockZ.size()), 1e-6);
    if (v.chi2 > v.chi2Limit) fail(fmt("blocks' chi-square %.1f above its bound %.1f", v.chi2, v.chi2Limit));
    if (v.blocksBeyond > 0)
        fail(fmt("%.0f block(s) beyond 4 sigma + %.0f%% of the image mean", v.blocksBeyond, 100 * blockFloor));
    return v;
}

}  // namespace ps::verify
