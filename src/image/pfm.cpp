// Portable float map: "PF" (RGB) or "Pf" (grey), width, height, then a scale whose sign
// gives the byte order (negative = little endian). Rows run bottom to top.
#include <sys/stat.h>

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "image/image_formats.h"
#include "util/error.h"

namespace ps::imageio {

namespace {

bool isSpace(int c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

// One header field. The single whitespace character ending it is consumed too, which is
// exactly what the format puts between the scale and the pixel data.
std::string headerToken(std::FILE* f) {
    int c;
    while ((c = std::getc(f)) != EOF && isSpace(c)) {}
    std::string tok;
    while (c != EOF && !isSpace(c) && tok.size() < 64) {
        tok += char(c);
        c = std::getc(f);
    }
    return tok;
}

template <typename T>
bool parseWhole(const std::string& tok, T& value) {
    auto [end, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), value);
    return ec == std::errc() && end == tok.data() + tok.size() && !tok.empty();
}

uint32_t bits(float v) { uint32_t u; std::memcpy(&u, &v, 4); return u; }
float fromBits(uint32_t u) { float v; std::memcpy(&v, &u, 4); return v; }

}  // namespace

Image readPfm(const std::string& path, std::FILE* f) {
    std::string magic = headerToken(f);
    if (magic != "PF" && magic != "Pf") throw InputError(path + ": not a PFM file (header must start with PF or Pf)");
    int channels = magic == "PF" ? 3 : 1;
    std::string ws = headerToken(f), hs = headerToken(f), ss = headerToken(f);
    long long w = 0, h = 0;
    if (!parseWhole(ws, w) || !parseWhole(hs, h))
        throw InputError(path + ": bad PFM header: size \"" + ws + " " + hs + "\" is not a valid width and height");
    checkSize(path, w, h);
    double scale = 0;
    if (!parseWhole(ss, scale) || !std::isfinite(scale) || scale == 0)
        throw InputError(path + ": bad PFM header: scale \"" + ss + "\" must be a finite non-zero number");

    // Check the length before allocating: a short file must not cost gigabytes first.
    size_t count = size_t(w) * size_t(h) * channels;
    struct stat st;
    long pos = std::ftell(f);
    if (fstat(fileno(f), &st) == 0 && S_ISREG(st.st_mode) && pos >= 0 &&
        (unsigned long long)(st.st_size - pos) < count * sizeof(float))
        throw InputError(path + ": truncated PFM data (" + std::to_string(count * sizeof(float)) +
                         " bytes of pixels expected, " + std::to_string(st.st_size - pos) + " present)");
    std::vector<float> data(count);
    if (std::fread(data.data(), sizeof(float), count, f) != count) throw InputError(path + ": truncated PFM data");

    bool fileLittle = scale < 0;
    if (fileLittle != (std::endian::native == std::endian::little))
        for (float& v : data) v = fromBits(__builtin_bswap32(bits(v)));
    // pbrt-v4 multiplies by |scale|; nearly every file has 1, so this is normally a no-op.
    float mag = float(std::abs(scale));
    if (mag != 1.0f)
        for (float& v : data) v *= mag;

    Image img{int(w), int(h)};
    for (long long y = 0; y < h; ++y) {
        const float* src = &data[size_t(h - 1 - y) * size_t(w) * channels];
        float* dst = &img.rgb[size_t(y) * size_t(w) * 3];
        for (long long x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) dst[3 * x + c] = src[x * channels + (channels == 3 ? c : 0)];
    }
    return img;
}

std::vector<char> encodePfm(const Image& img) {
    std::string header = "PF\n" + std::to_string(img.width) + " " + std::to_string(img.height) + "\n-1\n";
    size_t rowFloats = size_t(img.width) * 3;
    std::vector<char> out(header.size() + rowFloats * img.height * sizeof(float));
    std::memcpy(out.data(), header.data(), header.size());
    char* p = out.data() + header.size();
    for (int y = img.height - 1; y >= 0; --y) {
        const float* row = &img.rgb[size_t(y) * rowFloats];
        for (size_t i = 0; i < rowFloats; ++i, p += 4) {
            uint32_t u = bits(finiteForOutput(row[i]));
            if constexpr (std::endian::native == std::endian::big) u = __builtin_bswap32(u);
            std::memcpy(p, &u, 4);
        }
    }
    return out;
}

}  // namespace ps::imageio
