// Monte Carlo estimators and their error (thesis §2.3-2.4): running mean and unbiased
// sample variance by Welford's update (numerically stable), standard error, MSE against a
// known value, and efficiency 1/(V T) (thesis eq. 2.26: variance times time).
#pragma once
#include <cmath>
#include <cstdint>

namespace ps {

class RunningStats {
public:
    void add(double x) {
        ++n_;
        double d = x - mean_;
        mean_ += d / double(n_);
        m2_ += d * (x - mean_);
    }
    // Chan et al.'s parallel combination of two independent accumulations.
    void merge(const RunningStats& o) {
        if (o.n_ == 0) return;
        if (n_ == 0) {
            *this = o;
            return;
        }
        int64_t n = n_ + o.n_;
        double d = o.mean_ - mean_;
        mean_ += d * double(o.n_) / double(n);
        m2_ += o.m2_ + d * d * double(n_) * double(o.n_) / double(n);
        n_ = n;
    }
    int64_t count() const { return n_; }
    double mean() const { return mean_; }
    // Unbiased sample variance of one sample (divides by n - 1).
    double variance() const { return n_ > 1 ? m2_ / double(n_ - 1) : 0.0; }
    // Variance and standard error of the mean estimator.
    double varianceOfMean() const { return n_ > 0 ? variance() / double(n_) : 0.0; }
    double standardError() const { return std::sqrt(varianceOfMean()); }

private:
    int64_t n_ = 0;
    double mean_ = 0, m2_ = 0;
};

// Mean squared error of an estimate against the exact value: variance plus bias squared.
inline double meanSquaredError(double variance, double bias) { return variance + bias * bias; }

// Efficiency of an estimator whose variance is V and cost T seconds (thesis eq. 2.26).
inline double efficiency(double variance, double seconds) {
    return variance > 0 && seconds > 0 ? 1.0 / (variance * seconds) : 0.0;
}

}  // namespace ps
