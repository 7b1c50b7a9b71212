// Radiance RGBE (.hdr). Hand-written rather than stb_image's reader, which loops forever
// on a file that ends inside a run-length encoded scanline. Values match stb's decoding
// (mantissa * 2^(exponent-136), no half-step offset), which pbrt-v4 also uses.
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string_view>

#include "image/image_formats.h"
#include "util/error.h"

namespace ps::imageio {

namespace {

class HdrParser {
public:
    HdrParser(const std::string& path, std::vector<unsigned char> bytes) : path_(path), data_(std::move(bytes)) {}

    Image parse() {
        std::string_view id = line();
        if (id != "#?RADIANCE" && id != "#?RGBE") fail("not a Radiance HDR file (no #?RADIANCE line)");
        for (std::string_view l = line(); !l.empty(); l = line())
            if (l.substr(0, 7) == "FORMAT=" && l != "FORMAT=32-bit_rle_rgbe")
                fail("unsupported HDR pixel format \"" + std::string(l.substr(7)) + "\" (only 32-bit_rle_rgbe)");
        long long w = 0, h = 0;
        parseResolution(line(), w, h);
        checkSize(path_, w, h, (long long)data_.size());

        Image img{int(w), int(h)};
        std::vector<unsigned char> scan(size_t(w) * 4);
        for (long long y = 0; y < h; ++y) {
            readScanline(scan);
            float* out = &img.rgb[size_t(y) * size_t(w) * 3];
            for (long long x = 0; x < w; ++x) {
                const unsigned char* p = &scan[size_t(x) * 4];
                float f = p[3] ? std::ldexp(1.0f, int(p[3]) - 136) : 0.0f;
                for (int c = 0; c < 3; ++c) out[3 * x + c] = p[c] * f;
            }
        }
        return img;
    }

private:
    [[noreturn]] void fail(const std::string& what) const { throw InputError(path_ + ": " + what); }

    unsigned char byte() {
        if (pos_ >= data_.size()) fail("truncated HDR data");
        return data_[pos_++];
    }

    std::string_view line() {
        size_t start = pos_;
        while (pos_ < data_.size() && data_[pos_] != '\n') ++pos_;
        if (pos_ >= data_.size()) fail("truncated HDR header");
        return {reinterpret_cast<const char*>(data_.data()) + start, pos_++ - start};
    }

    // Only the standard orientation, as in stb: rows top to bottom, columns left to right.
    void parseResolution(std::string_view l, long long& w, long long& h) const {
        auto number = [&](std::string_view& s, long long& v) {
            auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
            s.remove_prefix(size_t(end - s.data()));
            return ec == std::errc();
        };
        std::string_view s = l;
        bool ok = s.substr(0, 3) == "-Y " && (s.remove_prefix(3), number(s, h)) && s.substr(0, 4) == " +X " &&
                  (s.remove_prefix(4), number(s, w)) && s.empty();
        if (!ok) fail("unsupported HDR resolution line \"" + std::string(l) + "\" (expected \"-Y height +X width\")");
    }

    void readScanline(std::vector<unsigned char>& scan) {
        const size_t w = scan.size() / 4;
        unsigned char head[4];
        for (unsigned char& b : head) b = byte();
        // New-style run-length encoding: 2, 2, then the width in 15 bits. It is only used for
        // widths 8..32767; anything else is a flat scanline of RGBE quadruples.
        if (head[0] != 2 || head[1] != 2 || (head[2] & 0x80) || w < 8 || w > 32767) {
            std::memcpy(scan.data(), head, 4);
            for (size_t i = 4; i < scan.size(); ++i) scan[i] = byte();
            return;
        }
        if (((size_t(head[2]) << 8) | head[3]) != w) fail("bad HDR scanline length");
        for (int c = 0; c < 4; ++c)  // each component separately
            for (size_t x = 0; x < w;) {
                unsigned count = byte();
                if (count > 128) {  // run of one value
                    count -= 128;
                    if (count > w - x) fail("bad run-length data in HDR scanline");
                    unsigned char v = byte();
                    for (; count > 0; --count) scan[4 * x++ + c] = v;
                } else {  // literal values
                    if (count > w - x) fail("bad run-length data in HDR scanline");
                    for (; count > 0; --count) scan[4 * x++ + c] = byte();
                }
            }
    }

    const std::string& path_;
    std::vector<unsigned char> data_;
    size_t pos_ = 0;
};

}  // namespace

Image readHdr(const std::string& path, std::FILE* f, long long fileBytes) {
    // Radiance files are compressed RGBE (4 bytes a pixel at most), so reading the whole
    // file is cheaper than the float image it becomes.
    std::vector<unsigned char> bytes;
    if (fileBytes >= 0) bytes.reserve(size_t(fileBytes));
    unsigned char buf[65536];
    size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) bytes.insert(bytes.end(), buf, buf + n);
    if (std::ferror(f)) throw InputError(path + ": cannot read image: " + std::strerror(errno));
    return HdrParser(path, std::move(bytes)).parse();
}

}  // namespace ps::imageio
