// readImage: opens the file once (so a missing or unreadable file reports the real errno),
// recognises the format from its first bytes and hands it to the matching reader.
#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <memory>

#include "image/image_formats.h"
#include "util/error.h"
#include "util/memory_limit.h"
#include "util/path.h"
#include "util/input_files.h"

namespace ps {

namespace imageio {

void checkSize(const std::string& path, long long w, long long h, long long fileBytes) {
    const std::string size = std::to_string(w) + "x" + std::to_string(h);
    // Division instead of w*h: header fields can be large enough to overflow the product.
    if (w <= 0 || h <= 0 || w > kMaxPixels / h)
        throw InputError(path + ": image size " + size + " is out of range (at most " +
                         std::to_string(kMaxPixels) + " pixels)");
    if (fileBytes >= 0 && w * h > std::max(kAlwaysPlausiblePixels, fileBytes * kMaxPixelsPerByte))
        throw InputError(path + ": image size " + size + " is implausible for a file of " +
                         std::to_string(fileBytes) + " bytes (corrupt header?)");
    // RGB and alpha as floats: the most the decoded Image holds (a decoder's own 1-8 bytes per
    // pixel are freed once it is converted).
    requireMemory(path + ": image " + size, double(w) * double(h) * 4 * sizeof(float));
}

}  // namespace imageio

namespace {

using imageio::FileFormat;

bool isSpace(unsigned char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

// Content decides over the extension, so a mislabelled file still reads correctly.
FileFormat sniff(const unsigned char* b, size_t n, const std::string& ext) {
    if (n >= 4 && b[0] == 0x76 && b[1] == 0x2f && b[2] == 0x31 && b[3] == 0x01) return FileFormat::Exr;
    if (n >= 3 && b[0] == 'P' && (b[1] == 'F' || b[1] == 'f') && isSpace(b[2]))
        return FileFormat::Pfm;
    if (n >= 2 && b[0] == '#' && b[1] == '?') return FileFormat::Hdr;  // #?RADIANCE or #?RGBE
    if (n >= 4 && b[0] == 0x89 && b[1] == 'P' && b[2] == 'N' && b[3] == 'G') return FileFormat::Png;
    // Unrecognised content: let the reader the name promises explain what is wrong.
    if (ext == ".exr") return FileFormat::Exr;
    if (ext == ".pfm") return FileFormat::Pfm;
    if (ext == ".hdr") return FileFormat::Hdr;
    return FileFormat::Other;
}

}  // namespace

Image readImage(const std::string& path, ColorEncoding pngEncoding) {
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), std::fclose);
    if (!f) throw InputError(path + ": cannot open image: " + std::strerror(errno));
    noteInputFile(path);
    struct stat st;
    if (fstat(fileno(f.get()), &st) != 0) throw InputError(path + ": cannot open image: " + std::strerror(errno));
    if (S_ISDIR(st.st_mode)) throw InputError(path + ": cannot open image: is a directory");
    const long long bytes = S_ISREG(st.st_mode) ? (long long)st.st_size : -1;  // unknown for pipes

    unsigned char magic[4] = {};
    size_t n = std::fread(magic, 1, sizeof magic, f.get());
    if (std::ferror(f.get())) throw InputError(path + ": cannot read image: " + std::strerror(errno));
    std::rewind(f.get());

    FileFormat format = sniff(magic, n, lowerExtension(path));
    switch (format) {
    case FileFormat::Exr: f.reset(); return imageio::readExr(path, bytes);  // OpenEXR opens it itself
    case FileFormat::Pfm: return imageio::readPfm(path, f.get());  // exact length check instead
    case FileFormat::Hdr: return imageio::readHdr(path, f.get(), bytes);
    default: return imageio::readStb(path, f.get(), bytes, format, pngEncoding);
    }
}

}  // namespace ps
