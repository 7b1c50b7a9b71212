// Minimal PNG writer for tests: 16-bit samples (which stb_image_write cannot produce) or
// any IHDR, with the image data in uncompressed deflate blocks.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace ps::test {

inline uint32_t pngCrc(const std::string& bytes) {
    uint32_t c = 0xffffffffu;
    for (unsigned char b : bytes) {
        c ^= b;
        for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
    }
    return ~c;
}

inline void putBE32(std::string& s, uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8) s += char((v >> shift) & 0xff);
}

inline void pngChunk(std::string& png, const std::string& type, const std::string& data) {
    putBE32(png, uint32_t(data.size()));
    std::string body = type + data;
    png += body;
    putBE32(png, pngCrc(body));
}

inline std::string pngSignatureAndHeader(uint32_t w, uint32_t h, int bitDepth, int colourType) {
    std::string png = "\x89PNG\r\n\x1a\n";
    std::string ihdr;
    putBE32(ihdr, w);
    putBE32(ihdr, h);
    ihdr += char(bitDepth);
    ihdr += char(colourType);
    ihdr += std::string(3, '\0');  // deflate, adaptive filtering, no interlace
    pngChunk(png, "IHDR", ihdr);
    return png;
}

// colourType: 0 grey, 2 RGB, 4 grey+alpha, 6 RGBA. samples: row-major, channels interleaved.
inline std::string png16(uint32_t w, uint32_t h, int colourType, const std::vector<uint16_t>& samples) {
    int channels = colourType == 0 ? 1 : colourType == 2 ? 3 : colourType == 4 ? 2 : 4;
    std::string raw;
    size_t k = 0;
    for (uint32_t y = 0; y < h; ++y) {
        raw += char(0);  // filter: none
        for (uint32_t i = 0; i < w * uint32_t(channels); ++i, ++k) {
            raw += char(samples[k] >> 8);
            raw += char(samples[k] & 0xff);
        }
    }
    std::string z = "\x78\x01";
    for (size_t pos = 0; pos == 0 || pos < raw.size();) {
        size_t n = std::min<size_t>(raw.size() - pos, 65535);
        bool last = pos + n == raw.size();
        z += char(last ? 1 : 0);
        z += char(n & 0xff);
        z += char(n >> 8);
        z += char(~n & 0xff);
        z += char((~n >> 8) & 0xff);
        z += raw.substr(pos, n);
        pos += n;
        if (last) break;
    }
    uint32_t a = 1, b = 0;  // Adler-32 of the uncompressed data
    for (unsigned char c : raw) {
        a = (a + c) % 65521;
        b = (b + a) % 65521;
    }
    putBE32(z, (b << 16) | a);

    std::string png = pngSignatureAndHeader(w, h, 16, colourType);
    pngChunk(png, "IDAT", z);
    pngChunk(png, "IEND", "");
    return png;
}

}  // namespace ps::test
