// Internal to the image module: the per-format readers and encoders behind readImage and
// writeImage. Not for use elsewhere; image.h is the module's interface.
#pragma once
#include <cstdio>
#include <string>
#include <vector>
#include "image/image.h"

namespace ps::imageio {

// Largest accepted image, in pixels: 2^28 RGB floats are already 3 GiB.
constexpr long long kMaxPixels = 1LL << 28;
// No real compressed image holds more pixels per byte of file (1-bit PNG under maximal
// deflate is ~8000). Beyond this the header is corrupt, and decoders such as stb's BMP
// and TGA readers would otherwise zero-fill gigabytes from a few hundred bytes.
constexpr long long kMaxPixelsPerByte = 16384;
constexpr long long kAlwaysPlausiblePixels = 1LL << 20;

// Throws InputError unless 0 < w, h and w*h <= kMaxPixels (checked without overflow),
// and, when fileBytes >= 0, w*h is plausible for a file of that size, and the decoded image
// fits the memory limit (util/memory_limit.h).
void checkSize(const std::string& path, long long w, long long h, long long fileBytes = -1);

// What readImage recognised from the first bytes (or, failing that, the extension).
enum class FileFormat { Exr, Pfm, Hdr, Png, Other };

// Readers take the file already opened by readImage (positioned at the start).
Image readPfm(const std::string& path, std::FILE* f);
Image readExr(const std::string& path, long long fileBytes);
Image readHdr(const std::string& path, std::FILE* f, long long fileBytes);
Image readStb(const std::string& path, std::FILE* f, long long fileBytes, FileFormat format, ColorEncoding pngEncoding);

// Encoders produce the whole file in memory, so the atomic writer alone touches the disk.
// Each pixel value goes through finiteForOutput on the way.
std::vector<char> encodePfm(const Image& image);
std::vector<char> encodeExr(const Image& image);
std::vector<char> encodePng(const Image& image);

// NaN -> 0, +-Inf -> +-largest finite float: nothing non-finite reaches a file.
float finiteForOutput(float v);

}  // namespace ps::imageio
