// OpenEXR through the generic InputFile/OutputFile API: float slices give float32 pixels
// bit for bit and convert half or uint channels on the way in.
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>

#include <algorithm>
#include <cstring>

#include "image/image_formats.h"
#include "util/error.h"

namespace ps::imageio {

namespace {

// OutputFile seeks back to patch its offset table, so the buffer supports seekp.
class MemoryOStream : public Imf::OStream {
public:
    MemoryOStream() : Imf::OStream("<memory>") {}
    void write(const char c[], int n) override {
        if (pos_ + size_t(n) > data.size()) data.resize(pos_ + size_t(n));
        std::memcpy(data.data() + pos_, c, size_t(n));
        pos_ += size_t(n);
    }
    uint64_t tellp() override { return pos_; }
    void seekp(uint64_t pos) override { pos_ = size_t(pos); }
    std::vector<char> data;

private:
    size_t pos_ = 0;
};

std::string channelNames(const Imf::ChannelList& channels) {
    std::string names;
    for (auto it = channels.begin(); it != channels.end(); ++it) names += (names.empty() ? "" : ", ") + std::string(it.name());
    return names.empty() ? "none" : names;
}

}  // namespace

Image readExr(const std::string& path, long long fileBytes) {
    try {
        Imf::InputFile file(path.c_str());
        // The data window is the image, as in pbrt-v4 (a crop render stores only its crop).
        const Imath::Box2i dw = file.header().dataWindow();
        long long w = (long long)dw.max.x - dw.min.x + 1, h = (long long)dw.max.y - dw.min.y + 1;
        checkSize(path, w, h, fileBytes);
        const Imf::ChannelList& ch = file.header().channels();
        bool rgb = ch.findChannel("R") && ch.findChannel("G") && ch.findChannel("B");
        if (!rgb && !ch.findChannel("Y"))
            throw InputError(path + ": EXR has no R, G, B or Y channels (it has: " + channelNames(ch) + ")");

        Image img{int(w), int(h)};
        const Imath::Box2i disp = file.header().displayWindow();
        if (disp != dw) {  // a crop: where it lies in its film
            img.filmWidth = disp.max.x - disp.min.x + 1;
            img.filmHeight = disp.max.y - disp.min.y + 1;
            img.x0 = dw.min.x - disp.min.x;
            img.y0 = dw.min.y - disp.min.y;
        }
        Imf::FrameBuffer fb;
        const size_t xs = 3 * sizeof(float), ys = xs * size_t(w);
        char* base = reinterpret_cast<char*>(img.rgb.data());
        if (rgb) {
            fb.insert("R", Imf::Slice::Make(Imf::FLOAT, base, dw, xs, ys));
            fb.insert("G", Imf::Slice::Make(Imf::FLOAT, base + sizeof(float), dw, xs, ys));
            fb.insert("B", Imf::Slice::Make(Imf::FLOAT, base + 2 * sizeof(float), dw, xs, ys));
        } else {
            fb.insert("Y", Imf::Slice::Make(Imf::FLOAT, base, dw, xs, ys));  // spread below
        }
        if (ch.findChannel("A")) {
            img.alpha.resize(size_t(w) * size_t(h));
            fb.insert("A", Imf::Slice::Make(Imf::FLOAT, img.alpha.data(), dw, sizeof(float), sizeof(float) * size_t(w)));
        }
        file.setFrameBuffer(fb);
        file.readPixels(dw.min.y, dw.max.y);
        if (!rgb)
            for (size_t i = 0; i < img.rgb.size(); i += 3) img.rgb[i + 1] = img.rgb[i + 2] = img.rgb[i];
        return img;
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {
        // OpenEXR's messages usually repeat the file name; ours leads with it regardless.
        throw InputError(path + ": cannot read EXR: " + e.what());
    }
}

std::vector<char> encodeExr(const Image& img) {
    std::vector<float> pixels(img.rgb.size());
    std::transform(img.rgb.begin(), img.rgb.end(), pixels.begin(), finiteForOutput);
    Imf::Header header(img.width, img.height);
    if (img.filmWidth > 0 && img.filmHeight > 0) {
        header.displayWindow() = Imath::Box2i({0, 0}, {img.filmWidth - 1, img.filmHeight - 1});
        header.dataWindow() = Imath::Box2i({img.x0, img.y0}, {img.x0 + img.width - 1, img.y0 + img.height - 1});
    }
    header.compression() = Imf::ZIP_COMPRESSION;
    for (const char* name : {"R", "G", "B"}) header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    Imf::FrameBuffer fb;
    const size_t xs = 3 * sizeof(float), ys = xs * size_t(img.width);
    char* base = reinterpret_cast<char*>(pixels.data());
    const Imath::Box2i dw = header.dataWindow();  // the slices start at its first pixel
    fb.insert("R", Imf::Slice::Make(Imf::FLOAT, base, dw, xs, ys));
    fb.insert("G", Imf::Slice::Make(Imf::FLOAT, base + sizeof(float), dw, xs, ys));
    fb.insert("B", Imf::Slice::Make(Imf::FLOAT, base + 2 * sizeof(float), dw, xs, ys));
    MemoryOStream stream;
    {
        // The offset table is written when the file object is destroyed.
        Imf::OutputFile file(stream, header);
        file.setFrameBuffer(fb);
        file.writePixels(img.height);  // from the data window's first row
    }
    return std::move(stream.data);
}

}  // namespace ps::imageio
