// The realistic camera's aperture shape (pbrt-v4's "aperture" parameter): a transmission
// mask over the aperture stop's bounding square, looked up bilinearly (zero outside), and
// scaled so that its mean over the square is pi/4, the fraction a circular stop covers:
// every shape passes the light of the circular stop of the same diameter.
#pragma once
#include <string>
#include <vector>
#include "image/image.h"
#include "math/vec.h"

namespace ps {

class ApertureMask {
public:
    ApertureMask() = default;  // empty: blocks every ray
    // The built-in shapes "gaussian", "square", "pentagon", "star" (256x256); false for any
    // other name.
    static bool builtin(const std::string& name, ApertureMask* out);
    // An image's mean of R, G, B per pixel (linear); image row 0 (the top) lies at +y.
    static ApertureMask fromImage(const Image& img);

    // Transmission at uv in [0,1]^2 over the stop's square (u along +x, v along +y).
    float lookup(Vec2 uv) const;
    int width() const { return w_; }
    int height() const { return h_; }
    float texel(int x, int y) const { return v_[size_t(y) * w_ + x]; }

private:
    ApertureMask(int w, int h) : w_(w), h_(h), v_(size_t(w) * h, 0.0f) {}
    float& at(int x, int y) { return v_[size_t(y) * w_ + x]; }
    // Rows are stored from v = 0 upwards; shapes are drawn top row first, like an image.
    void flipRows();
    void normalise();
    // 1 inside the closed polygon (vertices in [-1,1]^2, drawn like an image: row 0 at -1).
    static ApertureMask polygon(const std::vector<Vec2>& vertices);

    int w_ = 0, h_ = 0;
    std::vector<float> v_;
};

}  // namespace ps
