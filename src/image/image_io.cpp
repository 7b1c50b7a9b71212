// Image reading and writing: stb for 8/16-bit formats and Radiance HDR, OpenEXR for EXR,
// PFM by hand. Writes go through a temporary file renamed over the target.
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>

#include "image/image.h"
#include "util/error.h"
#include "util/path.h"

namespace ps {

namespace {

constexpr long long kMaxPixels = 1LL << 28;

void checkSize(const std::string& path, long long w, long long h) {
    if (w <= 0 || h <= 0 || w * h > kMaxPixels)
        throw InputError(path + ": image size " + std::to_string(w) + "x" + std::to_string(h) + " is out of range");
}

Image readPfm(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path + ": cannot open image: " + std::strerror(errno));
    std::string magic;
    long long w = 0, h = 0;
    double scale = 0;
    in >> magic >> w >> h >> scale;
    if (!in || (magic != "PF" && magic != "Pf")) throw InputError(path + ": not a PFM file (bad header)");
    in.get();  // the single whitespace after the scale
    checkSize(path, w, h);
    if (!std::isfinite(scale) || scale == 0) throw InputError(path + ": PFM scale must be finite and non-zero");
    int channels = magic == "PF" ? 3 : 1;
    std::vector<float> data(size_t(w * h * channels));
    in.read(reinterpret_cast<char*>(data.data()), std::streamsize(data.size() * sizeof(float)));
    if (size_t(in.gcount()) != data.size() * sizeof(float)) throw InputError(path + ": truncated PFM data");
    bool bigEndian = scale > 0;
    if (bigEndian)
        for (float& f : data) {
            uint32_t u;
            std::memcpy(&u, &f, 4);
            u = __builtin_bswap32(u);
            std::memcpy(&f, &u, 4);
        }
    Image img{int(w), int(h)};
    for (long long y = 0; y < h; ++y)  // PFM rows run bottom to top
        for (long long x = 0; x < w; ++x) {
            const float* p = &data[size_t(((h - 1 - y) * w + x) * channels)];
            img.set(int(x), int(y), channels == 3 ? Spectrum(p[0], p[1], p[2]) : Spectrum(p[0]));
        }
    return img;
}

Image readExr(const std::string& path) {
    try {
        Imf::InputFile file(path.c_str());
        Imath::Box2i dw = file.header().dataWindow();
        long long w = (long long)dw.max.x - dw.min.x + 1, h = (long long)dw.max.y - dw.min.y + 1;
        checkSize(path, w, h);
        const Imf::ChannelList& ch = file.header().channels();
        bool rgb = ch.findChannel("R") && ch.findChannel("G") && ch.findChannel("B");
        bool grey = ch.findChannel("Y") != nullptr;
        if (!rgb && !grey) throw InputError(path + ": EXR has neither R, G, B nor Y channels");
        std::vector<float> r(size_t(w * h)), g, b, a;
        Imf::FrameBuffer fb;
        auto slice = [&](std::vector<float>& buf) {
            char* base = reinterpret_cast<char*>(buf.data()) - (dw.min.x + (long long)dw.min.y * w) * sizeof(float);
            return Imf::Slice(Imf::FLOAT, base, sizeof(float), size_t(w) * sizeof(float));
        };
        if (rgb) {
            g.resize(r.size());
            b.resize(r.size());
            fb.insert("R", slice(r));
            fb.insert("G", slice(g));
            fb.insert("B", slice(b));
        } else {
            fb.insert("Y", slice(r));
        }
        if (ch.findChannel("A")) {
            a.resize(r.size());
            fb.insert("A", slice(a));
        }
        file.setFrameBuffer(fb);
        file.readPixels(dw.min.y, dw.max.y);
        Image img{int(w), int(h)};
        for (size_t i = 0; i < r.size(); ++i) {
            img.rgb[3 * i] = r[i];
            img.rgb[3 * i + 1] = rgb ? g[i] : r[i];
            img.rgb[3 * i + 2] = rgb ? b[i] : r[i];
        }
        img.alpha = std::move(a);
        return img;
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {
        throw InputError(path + ": cannot read EXR: " + e.what());
    }
}

// 8/16-bit formats and Radiance HDR through stb_image.
Image readStb(const std::string& path, ColorEncoding pngEncoding) {
    std::string ext = lowerExtension(path);
    FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) throw InputError(path + ": cannot open image: " + std::strerror(errno));
    int w = 0, h = 0, n = 0;
    if (!stbi_info_from_file(f, &w, &h, &n)) {
        std::fclose(f);
        throw InputError(path + ": not a readable image (" + stbi_failure_reason() + ")");
    }
    checkSize(path, w, h);
    bool hdr = stbi_is_hdr_from_file(f);
    bool sixteen = !hdr && stbi_is_16_bit_from_file(f);
    // Only PNG honours a linear encoding; every other 8-bit format is sRGB (PBRT-CONVENTIONS §6).
    bool srgb = !hdr && !(ext == ".png" && pngEncoding == ColorEncoding::Linear);
    Image img(w, h);
    int comps = n;
    if (hdr) {
        std::unique_ptr<float, void (*)(void*)> data(stbi_loadf_from_file(f, &w, &h, &comps, 0), stbi_image_free);
        std::fclose(f);
        if (!data) throw InputError(path + ": cannot decode image (" + stbi_failure_reason() + ")");
        for (size_t i = 0; i < size_t(w) * h; ++i)
            for (int c = 0; c < 3; ++c) img.rgb[3 * i + c] = data.get()[i * comps + (comps >= 3 ? c : 0)];
        return img;
    }
    std::vector<float> values(size_t(w) * h * comps);
    if (sixteen) {
        std::unique_ptr<stbi_us, void (*)(void*)> data(stbi_load_from_file_16(f, &w, &h, &comps, 0), stbi_image_free);
        std::fclose(f);
        if (!data) throw InputError(path + ": cannot decode image (" + stbi_failure_reason() + ")");
        for (size_t i = 0; i < values.size(); ++i) values[i] = data.get()[i] / 65535.0f;
    } else {
        std::unique_ptr<stbi_uc, void (*)(void*)> data(stbi_load_from_file(f, &w, &h, &comps, 0), stbi_image_free);
        std::fclose(f);
        if (!data) throw InputError(path + ": cannot decode image (" + stbi_failure_reason() + ")");
        for (size_t i = 0; i < values.size(); ++i) values[i] = data.get()[i] / 255.0f;
    }
    bool hasAlpha = comps == 2 || comps == 4;
    int colour = hasAlpha ? comps - 1 : comps;
    if (hasAlpha) img.alpha.resize(size_t(w) * h);
    for (size_t i = 0; i < size_t(w) * h; ++i) {
        for (int c = 0; c < 3; ++c) {
            float v = values[i * comps + (colour >= 3 ? c : 0)];
            img.rgb[3 * i + c] = srgb ? srgbToLinear(v) : v;
        }
        if (hasAlpha) img.alpha[i] = values[i * comps + comps - 1];
    }
    return img;
}

float finiteOrZero(float v) {
    if (std::isnan(v)) return 0;
    if (std::isinf(v)) return v > 0 ? std::numeric_limits<float>::max() : -std::numeric_limits<float>::max();
    return v;
}

void writeExr(const std::string& path, const Image& img) {
    Imf::Header header(img.width, img.height);
    header.compression() = Imf::ZIP_COMPRESSION;
    header.channels().insert("R", Imf::Channel(Imf::FLOAT));
    header.channels().insert("G", Imf::Channel(Imf::FLOAT));
    header.channels().insert("B", Imf::Channel(Imf::FLOAT));
    std::vector<float> data(img.rgb.size());
    for (size_t i = 0; i < data.size(); ++i) data[i] = finiteOrZero(img.rgb[i]);
    Imf::OutputFile file(path.c_str(), header);
    Imf::FrameBuffer fb;
    size_t xs = 3 * sizeof(float), ys = xs * img.width;
    char* base = reinterpret_cast<char*>(data.data());
    fb.insert("R", Imf::Slice(Imf::FLOAT, base, xs, ys));
    fb.insert("G", Imf::Slice(Imf::FLOAT, base + sizeof(float), xs, ys));
    fb.insert("B", Imf::Slice(Imf::FLOAT, base + 2 * sizeof(float), xs, ys));
    file.setFrameBuffer(fb);
    file.writePixels(img.height);
}

void writePfm(const std::string& path, const Image& img) {
    std::ofstream out(path, std::ios::binary);
    if (!out) throw InputError(path + ": cannot write: " + std::strerror(errno));
    out << "PF\n" << img.width << " " << img.height << "\n-1\n";
    std::vector<float> row(size_t(img.width) * 3);
    for (int y = img.height - 1; y >= 0; --y) {
        for (size_t i = 0; i < row.size(); ++i) row[i] = finiteOrZero(img.rgb[size_t(y) * img.width * 3 + i]);
        out.write(reinterpret_cast<const char*>(row.data()), std::streamsize(row.size() * sizeof(float)));
    }
    if (!out) throw InputError(path + ": write failed: " + std::strerror(errno));
}

void writePng(const std::string& path, const Image& img) {
    std::vector<unsigned char> data(img.rgb.size());
    for (size_t i = 0; i < data.size(); ++i) {
        float v = linearToSrgb(std::clamp(finiteOrZero(img.rgb[i]), 0.0f, 1.0f));
        data[i] = (unsigned char)std::lround(v * 255.0f);
    }
    if (!stbi_write_png(path.c_str(), img.width, img.height, 3, data.data(), img.width * 3))
        throw InputError(path + ": cannot write PNG");
}

}  // namespace

float srgbToLinear(float v) {
    if (v <= 0.04045f) return v / 12.92f;
    return std::pow((v + 0.055f) / 1.055f, 2.4f);
}

float linearToSrgb(float v) {
    if (v <= 0.0031308f) return 12.92f * v;
    return 1.055f * std::pow(v, 1 / 2.4f) - 0.055f;
}

bool isWritableImageExtension(const std::string& path) {
    std::string ext = lowerExtension(path);
    return ext == ".exr" || ext == ".png" || ext == ".pfm";
}

Image readImage(const std::string& path, ColorEncoding pngEncoding) {
    if (!std::filesystem::exists(path)) throw InputError(path + ": cannot open image: No such file or directory");
    if (std::filesystem::is_directory(path)) throw InputError(path + ": is a directory, not an image");
    std::string ext = lowerExtension(path);
    if (ext == ".pfm") return readPfm(path);
    if (ext == ".exr") return readExr(path);
    return readStb(path, pngEncoding);
}

void writeImage(const std::string& path, const Image& image) {
    std::string ext = lowerExtension(path);
    if (!isWritableImageExtension(path))
        throw InputError(path + ": unsupported output format \"" + ext + "\" (supported: .exr, .png, .pfm)");
    std::filesystem::path target(path);
    std::string tmp = (target.parent_path() / (target.stem().string() + ".tmp-" + std::to_string(getpid()) + ext)).string();
    try {
        if (ext == ".exr") writeExr(tmp, image);
        else if (ext == ".pfm") writePfm(tmp, image);
        else writePng(tmp, image);
    } catch (const InputError&) {
        std::remove(tmp.c_str());
        throw;
    } catch (const std::exception& e) {
        std::remove(tmp.c_str());
        throw InputError(path + ": cannot write: " + e.what());
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        std::string err = std::strerror(errno);
        std::remove(tmp.c_str());
        throw InputError(path + ": cannot write: " + err);
    }
}

}  // namespace ps
