// PNG, JPEG, TGA and BMP in (stb_image's other formats are refused); PNG out. Radiance HDR has
// its own reader (hdr.cpp).
// The stb implementation lives in Debian's libstb, so no *_IMPLEMENTATION defines here.
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "image/image_formats.h"
#include "util/error.h"

namespace ps::imageio {

namespace {

[[noreturn]] void stbFailure(const std::string& path) {
    const char* reason = stbi_failure_reason();
    throw InputError(path + ": not a readable image (stb: " + (reason ? reason : "unknown error") + ")");
}

// 8-bit sRGB decoding is a table lookup: image textures can have many megapixels.
const std::array<float, 256>& srgbTable() {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t;
        for (int i = 0; i < 256; ++i) t[i] = srgbToLinear(i / 255.0f);
        return t;
    }();
    return table;
}

// Spreads 1-4 channel samples into img: grey becomes R=G=B, a 2nd/4th channel is alpha
// (kept linear: value/maxValue). Colour goes through decode (sRGB or plain scaling).
template <typename T, typename Decode>
void unpack(const T* data, int comps, Image& img, float maxValue, Decode decode) {
    size_t n = size_t(img.width) * size_t(img.height);
    bool alpha = comps == 2 || comps == 4;
    int colours = alpha ? comps - 1 : comps;
    if (alpha) img.alpha.resize(n);
    for (size_t i = 0; i < n; ++i) {
        const T* p = data + i * size_t(comps);
        for (int c = 0; c < 3; ++c) img.rgb[3 * i + c] = decode(p[colours >= 3 ? c : 0]);
        if (alpha) img.alpha[i] = float(p[comps - 1]) / maxValue;
    }
}

template <typename T>
using StbPtr = std::unique_ptr<T, void (*)(void*)>;

// stb reads through these so we learn whether it asked for bytes past the end: its
// decoders then carry on with zeros (or, for raw TGA rows, unset memory) and "succeed".
struct Source {
    std::FILE* f;
    bool pastEnd = false;
};

int readBytes(void* user, char* data, int size) {
    auto* s = static_cast<Source*>(user);
    size_t n = std::fread(data, 1, size_t(size), s->f);
    if (n == 0) s->pastEnd = true;
    return int(n);
}
void skipBytes(void* user, int n) {
    std::FILE* f = static_cast<Source*>(user)->f;
    std::fseek(f, n, SEEK_CUR);
    // fseek clears the end-of-file flag, and stb's scanning loops stop only on atEnd:
    // read one byte so a skip past the end is noticed (as stb's own stdio reader does).
    int c = std::fgetc(f);
    if (c != EOF) std::ungetc(c, f);
}
int atEnd(void* user) {
    auto* s = static_cast<Source*>(user);
    return std::feof(s->f) || std::ferror(s->f);
}
const stbi_io_callbacks kCallbacks = {readBytes, skipBytes, atEnd};

// Where a file's JPEG SOI marker ends, read as stb reads it: 0xFF, any number of 0xFF fill
// bytes, then 0xD8 (a fuzzed file with 80 fill bytes slipped past a plain two-byte test);
// 0 if the file does not start with one.
long afterJpegSoi(std::FILE* f) {
    std::rewind(f);
    int c = std::fgetc(f);
    if (c != 0xFF) return 0;
    while ((c = std::fgetc(f)) == 0xFF) {
    }
    return c == 0xD8 ? std::ftell(f) : 0;
}

// Debian's stb_image (2022-09) overruns its Huffman arrays when a JPEG DHT table declares more
// than 256 codes (found by fuzz/image_fuzzer). Such files are corrupt: reject them before stb
// sees them. Walks every marker segment, including those between the scans of a progressive file.
void checkJpegHuffmanTables(const std::string& path, std::FILE* f, long afterSoi) {
    std::rewind(f);
    std::vector<unsigned char> b;
    unsigned char buf[65536];
    size_t got;
    while ((got = std::fread(buf, 1, sizeof buf, f)) > 0) b.insert(b.end(), buf, buf + got);
    std::rewind(f);
    const size_t n = b.size();
    size_t pos = size_t(afterSoi);
    while (pos + 4 <= n) {
        if (b[pos] != 0xFF) {  // entropy-coded data: look for the next marker
            ++pos;
            continue;
        }
        const unsigned m = b[pos + 1];
        if (m == 0xFF) { ++pos; continue; }  // fill byte
        if (m == 0x00 || m == 0x01 || (m >= 0xD0 && m <= 0xD7)) { pos += 2; continue; }  // no length
        if (m == 0xD9) break;                                                             // EOI
        const size_t len = size_t(b[pos + 2]) << 8 | b[pos + 3];
        if (m != 0xC4) {
            pos += 2 + len;
            continue;
        }
        // Read tables exactly as stb does: while the declared length is not used up, even if a
        // table runs past it, with zeros past the end of the file.
        auto at = [&](size_t i) -> size_t { return i < n ? b[i] : 0; };
        long long left = (long long)len - 2;
        size_t p = pos + 4;
        while (left > 0 && p < n) {
            size_t codes = 0;
            for (size_t i = 1; i <= 16; ++i) codes += at(p + i);
            if (codes > 256)
                throw InputError(path + ": corrupt JPEG: a Huffman table declares " + std::to_string(codes) +
                                 " codes (at most 256)");
            p += 17 + codes;
            left -= 17 + (long long)codes;
        }
        pos = p;
    }
}

}  // namespace

// stb_image grows its buffer for a PNG's image data to each IDAT chunk's declared length
// before reading it, so a 117-byte file declaring a 2 GiB chunk made it allocate 2 GiB (found
// by fuzz/image_fuzzer). Every chunk must fit in the bytes that remain: walk the chunk
// headers (length, type, data, CRC) before stb sees the file.
void checkPngChunks(const std::string& path, std::FILE* f, long long fileBytes) {
    static const unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    std::rewind(f);
    unsigned char sig[8];
    if (std::fread(sig, 1, 8, f) != 8 || std::memcmp(sig, kSignature, 8) != 0) return;  // not PNG
    long long pos = 8;
    unsigned char head[8];
    while (std::fread(head, 1, 8, f) == 8) {
        unsigned long long length = (unsigned long long)head[0] << 24 | head[1] << 16 | head[2] << 8 | head[3];
        std::string type(reinterpret_cast<const char*>(head + 4), 4);
        long long left = fileBytes - pos - 12;  // after this chunk's length, type and CRC
        if ((long long)length > left)
            throw InputError(path + ": corrupt PNG: chunk " + quoteForMessage(type) + " declares " +
                             std::to_string(length) + " bytes, but only " + std::to_string(std::max(0LL, left)) +
                             " remain in the file");
        if (type == "IEND") break;
        pos += 12 + (long long)length;
        if (std::fseek(f, long(length) + 4, SEEK_CUR) != 0) break;
    }
}

// stb_image also decodes PNM, GIF, PSD and PIC, which pathspace does not offer; their decoders
// have not had our checks (a fuzzed PNM header overflowed stb's integer parser: UB). Refuse
// them by their magic numbers, the same tests stb uses, before any stb code runs.
void refuseUndocumentedFormats(const std::string& path, std::FILE* f) {
    std::rewind(f);
    unsigned char b[4] = {};
    size_t n = std::fread(b, 1, 4, f);
    const char* name = nullptr;
    if (n >= 2 && b[0] == 'P' && (b[1] == '5' || b[1] == '6')) name = "PNM (PGM/PPM)";
    else if (n >= 4 && std::memcmp(b, "GIF8", 4) == 0) name = "GIF";
    else if (n >= 4 && std::memcmp(b, "8BPS", 4) == 0) name = "PSD";
    else if (n >= 4 && b[0] == 0x53 && b[1] == 0x80 && b[2] == 0xF6 && b[3] == 0x34) name = "Softimage PIC";
    if (name)
        throw InputError(path + ": " + name + " images are not supported (use PNG, JPEG, TGA, BMP, EXR, HDR or PFM)");
}

Image readStb(const std::string& path, std::FILE* f, long long fileBytes, FileFormat format, ColorEncoding pngEncoding) {
    // Every stb call starts a fresh context at the current position: rewind before each.
    refuseUndocumentedFormats(path, f);
    if (long afterSoi = afterJpegSoi(f)) checkJpegHuffmanTables(path, f, afterSoi);
    if (fileBytes >= 0) checkPngChunks(path, f, fileBytes);
    std::rewind(f);
    Source src{f};
    int w = 0, h = 0, comps = 0;
    if (!stbi_info_from_callbacks(&kCallbacks, &src, &w, &h, &comps)) stbFailure(path);
    checkSize(path, w, h, fileBytes);  // before decoding allocates anything
    std::rewind(f);
    bool sixteen = stbi_is_16_bit_from_callbacks(&kCallbacks, &src);
    // Only PNG may be declared linear; other 8/16-bit formats are always sRGB (PBRT-CONVENTIONS §6).
    bool srgb = !(format == FileFormat::Png && pngEncoding == ColorEncoding::Linear);

    std::rewind(f);
    src.pastEnd = false;
    int lw = 0, lh = 0;
    Image img(w, h);
    if (sixteen) {
        StbPtr<stbi_us> data(stbi_load_16_from_callbacks(&kCallbacks, &src, &lw, &lh, &comps, 0), stbi_image_free);
        if (!data) stbFailure(path);
        if (lw != w || lh != h) throw InputError(path + ": image size changed between header and data");
        unpack(data.get(), comps, img, 65535.0f, [&](stbi_us v) {
            float u = v / 65535.0f;
            return srgb ? srgbToLinear(u) : u;
        });
    } else {
        StbPtr<stbi_uc> data(stbi_load_from_callbacks(&kCallbacks, &src, &lw, &lh, &comps, 0), stbi_image_free);
        if (!data) stbFailure(path);
        if (lw != w || lh != h) throw InputError(path + ": image size changed between header and data");
        const auto& table = srgbTable();
        unpack(data.get(), comps, img, 255.0f, [&](stbi_uc v) { return srgb ? table[v] : v / 255.0f; });
    }
    if (src.pastEnd) throw InputError(path + ": truncated image data");
    return img;
}

std::vector<char> encodePng(const Image& img) {
    std::vector<unsigned char> px(img.rgb.size());
    for (size_t i = 0; i < px.size(); ++i) {
        float v = std::clamp(finiteForOutput(img.rgb[i]), 0.0f, 1.0f);
        px[i] = (unsigned char)std::lround(linearToSrgb(v) * 255.0f);
    }
    // The callback runs inside C code, so it must not throw: failures are recorded instead.
    struct Sink {
        std::vector<char> bytes;
        bool failed = false;
    } sink;
    auto append = [](void* ctx, void* data, int size) {
        auto* s = static_cast<Sink*>(ctx);
        try {
            s->bytes.insert(s->bytes.end(), static_cast<char*>(data), static_cast<char*>(data) + size);
        } catch (...) {
            s->failed = true;
        }
    };
    if (!stbi_write_png_to_func(append, &sink, img.width, img.height, 3, px.data(), img.width * 3) || sink.failed)
        throw std::runtime_error("PNG encoding failed (out of memory)");
    return std::move(sink.bytes);
}

}  // namespace ps::imageio
