// PLY reader. The file is read (or gunzipped) into memory in one go, the header becomes a list
// of element descriptions, and one body loop, templated on the encoding, decodes every element:
// a binary value costs a bounds check and a switch on its type, with no virtual calls or streams.
// Every count from the file is checked against the bytes that remain before it sizes anything,
// and the mesh it would make against the memory limit, so a corrupt or hostile file ends in an
// InputError, never in a crash, a hang or a huge allocation.
#include "scene/ply.h"

#include <sys/stat.h>
#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <charconv>
#include <cfloat>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string_view>
#include <utility>

#include "util/memory_limit.h"
#include "util/input_files.h"

namespace ps {

namespace {

constexpr uint64_t kMaxInflatedBytes = uint64_t(2) << 30;  // gzip output cap (2 GiB)
constexpr uint64_t kMaxAsciiCount = uint64_t(1) << 28;     // instances of one element, ASCII
constexpr uint64_t kMaxListCount = uint64_t(1) << 16;      // items in one list

[[noreturn]] void fail(const std::string& path, const std::string& what) { throw InputError(path + ": " + what); }

// File text quoted in a message: short, and printable even when the file is binary junk.
std::string quote(std::string_view s) {
    std::string out = "\"";
    for (char c : s.substr(0, 60)) out += (c >= 32 && c < 127) ? c : '?';
    if (s.size() > 60) out += "...";
    return out + "\"";
}

// A number from the file in a message: whole numbers in full, others to float precision.
std::string num(double v) {
    char buf[32];
    bool whole = std::fabs(v) < 1e18 && v == std::floor(v);
    std::snprintf(buf, sizeof buf, whole ? "%.0f" : "%.9g", v);
    return buf;
}

// ---- reading the file ----

struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

// Initial buffer for inflating. gzip's trailer holds the size mod 2^32, but a hostile file can
// fake it, so it is trusted only up to a ratio meshes rarely beat; past that the buffer grows.
size_t inflatedSizeHint(std::FILE* f, uint64_t compressedSize) {
    unsigned char t[4];
    if (compressedSize < 18 || std::fseek(f, -4, SEEK_END) != 0 || std::fread(t, 1, 4, f) != 4) return 0;
    uint64_t isize = t[0] | uint64_t(t[1]) << 8 | uint64_t(t[2]) << 16 | uint64_t(t[3]) << 24;
    return size_t(std::min({isize, compressedSize * 16, kMaxInflatedBytes}));
}

std::string inflateFile(const std::string& path, size_t sizeHint) {
    std::unique_ptr<gzFile_s, int (*)(gzFile)> gz(gzopen(path.c_str(), "rb"), gzclose);
    if (!gz) fail(path, std::string("cannot open gzip file: ") + std::strerror(errno));
    gzbuffer(gz.get(), 1 << 17);
    std::string out;
    out.reserve(sizeHint);
    constexpr size_t kChunk = size_t(1) << 20;
    for (;;) {
        size_t old = out.size();
        out.resize(old + kChunk);
        int n = gzread(gz.get(), out.data() + old, unsigned(kChunk));
        out.resize(old + size_t(std::max(n, 0)));
        if (n <= 0) break;
        if (out.size() > kMaxInflatedBytes) fail(path, "gzip data inflates to more than 2 GiB");
    }
    int err = Z_OK;
    std::string_view msg = gzerror(gz.get(), &err);
    if (msg.starts_with(path + ": ")) msg.remove_prefix(path.size() + 2);  // zlib names the file too
    if (err != Z_OK) fail(path, "corrupt gzip data: " + std::string(msg));
    return out;
}

// The whole file, decompressed if it is gzip (magic bytes 1f 8b, or a ".gz" name).
std::string readFileBytes(const std::string& path) {
    FilePtr f(std::fopen(path.c_str(), "rb"));
    if (!f) fail(path, std::string("cannot open PLY file: ") + std::strerror(errno));
    struct stat st;
    if (fstat(fileno(f.get()), &st) != 0 || !S_ISREG(st.st_mode)) fail(path, "not a regular file");
    uint64_t size = uint64_t(st.st_size);
    unsigned char magic[2] = {0, 0};
    size_t got = std::fread(magic, 1, 2, f.get());
    if ((got == 2 && magic[0] == 0x1f && magic[1] == 0x8b) || path.ends_with(".gz"))
        return inflateFile(path, inflatedSizeHint(f.get(), size));
    std::string data(size, '\0');
    std::rewind(f.get());
    if (std::fread(data.data(), 1, data.size(), f.get()) != data.size())
        fail(path, std::string("read error: ") + std::strerror(errno));
    return data;
}

// ---- header ----

enum class Format { Ascii, BinaryLE, BinaryBE };
enum class Scalar : uint8_t { I8, U8, I16, U16, I32, U32, F32, F64 };

constexpr size_t sizeOf(Scalar t) {
    constexpr size_t kSizes[] = {1, 1, 2, 2, 4, 4, 4, 8};
    return kSizes[int(t)];
}

bool parseScalar(std::string_view name, Scalar& t) {
    static constexpr std::pair<std::string_view, Scalar> kNames[] = {
        {"char", Scalar::I8},   {"int8", Scalar::I8},     {"uchar", Scalar::U8},   {"uint8", Scalar::U8},
        {"short", Scalar::I16}, {"int16", Scalar::I16},   {"ushort", Scalar::U16}, {"uint16", Scalar::U16},
        {"int", Scalar::I32},   {"int32", Scalar::I32},   {"uint", Scalar::U32},   {"uint32", Scalar::U32},
        {"float", Scalar::F32}, {"float32", Scalar::F32}, {"double", Scalar::F64}, {"float64", Scalar::F64}};
    for (const auto& [n, s] : kNames)
        if (name == n) {
            t = s;
            return true;
        }
    return false;
}

// What a property feeds in the mesh. Values of Skip properties are read and dropped. X Y Z,
// NX NY NZ and U V stay consecutive: vertices are assembled from those runs.
enum class Role : uint8_t { Skip, X, Y, Z, NX, NY, NZ, U, V, Corners, FaceIndex, Count };

struct Property {
    std::string name;
    Scalar type = Scalar::F32;  // value type, or item type of a list
    bool isList = false;
    Scalar countType = Scalar::U8;
    Role role = Role::Skip;
};

struct Element {
    std::string name;
    uint64_t count = 0;
    std::vector<Property> props;
    bool fixedSize() const {
        return std::none_of(props.begin(), props.end(), [](const Property& p) { return p.isList; });
    }
};

struct Header {
    Format format = Format::Ascii;
    std::vector<Element> elements;
    size_t bodyOffset = 0;
};

std::vector<std::string_view> splitWords(std::string_view line) {
    std::vector<std::string_view> words;
    constexpr std::string_view kSpace = " \t\r\v\f";
    size_t i = line.find_first_not_of(kSpace);
    while (i != std::string_view::npos) {
        size_t e = std::min(line.find_first_of(kSpace, i), line.size());
        words.push_back(line.substr(i, e - i));
        i = line.find_first_not_of(kSpace, e);
    }
    return words;
}

class HeaderParser {
public:
    HeaderParser(const std::string& path, std::string_view data) : path_(path), data_(data) {}

    Header parse() {
        std::string_view line;
        if (!nextLine(line) || splitWords(line) != std::vector<std::string_view>{"ply"})
            fail(path_, "not a PLY file (it does not start with a \"ply\" line)");
        bool haveFormat = false;
        for (;;) {
            if (!nextLine(line)) fail(path_, "PLY header has no end_header line");
            auto w = splitWords(line);
            if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
            if (w[0] == "end_header" && w.size() == 1) break;
            if (w[0] == "format" && w.size() == 3 && !haveFormat) {
                parseFormat(w[1], w[2]);
                haveFormat = true;
            } else if (w[0] == "element" && w.size() == 3) {
                header_.elements.push_back({std::string(w[1]), parseCount(w[2]), {}});
            } else if (w[0] == "property" && !header_.elements.empty() && (w.size() == 3 || w.size() == 5)) {
                header_.elements.back().props.push_back(parseProperty(w, line));
            } else {
                badLine(line);
            }
        }
        if (!haveFormat) fail(path_, "PLY header has no format line");
        header_.bodyOffset = pos_;
        return std::move(header_);
    }

private:
    bool nextLine(std::string_view& line) {
        if (pos_ >= data_.size()) return false;
        size_t eol = std::min(data_.find('\n', pos_), data_.size());
        line = data_.substr(pos_, eol - pos_);
        pos_ = std::min(eol + 1, data_.size());
        ++lineNo_;
        return true;
    }
    [[noreturn]] void badLine(std::string_view line) {
        fail(path_, "bad PLY header line " + std::to_string(lineNo_) + ": " + quote(line));
    }
    void parseFormat(std::string_view name, std::string_view version) {
        if (name == "ascii") header_.format = Format::Ascii;
        else if (name == "binary_little_endian") header_.format = Format::BinaryLE;
        else if (name == "binary_big_endian") header_.format = Format::BinaryBE;
        else fail(path_, "unsupported PLY format " + quote(name));
        double v = 0;
        auto [end, ec] = std::from_chars(version.data(), version.data() + version.size(), v);
        if (ec != std::errc() || end != version.data() + version.size() || v != 1.0)
            fail(path_, "unsupported PLY version " + quote(version) + " (only 1.0 exists)");
    }
    uint64_t parseCount(std::string_view s) {
        uint64_t n = 0;
        auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), n);
        if (ec != std::errc() || end != s.data() + s.size())
            fail(path_, "bad element count " + quote(s) + " on PLY header line " + std::to_string(lineNo_));
        return n;
    }
    Property parseProperty(const std::vector<std::string_view>& w, std::string_view line) {
        Property p;
        p.isList = w[1] == "list";
        if (p.isList != (w.size() == 5)) badLine(line);
        p.name = std::string(w.back());
        std::string_view type = p.isList ? w[3] : w[1];
        if (p.isList && !parseScalar(w[2], p.countType)) type = w[2];
        else if (parseScalar(type, p.type)) return p;
        fail(path_, "unknown PLY property type " + quote(type) + " on header line " + std::to_string(lineNo_));
    }

    const std::string& path_;
    std::string_view data_;
    size_t pos_ = 0;
    int lineNo_ = 0;
    Header header_;
};

// ---- body sources: one value at a time; false at the end of the data ----

template <class T, bool Swap>
T load(const char* p) {
    char b[sizeof(T)];
    std::memcpy(b, p, sizeof(T));
    if constexpr (Swap) std::reverse(b, b + sizeof(T));
    T v;
    std::memcpy(&v, b, sizeof(T));
    return v;
}

template <bool Swap>
double decode(Scalar t, const char* p) {
    switch (t) {
        case Scalar::I8: return double(int8_t(p[0]));
        case Scalar::U8: return double(uint8_t(p[0]));
        case Scalar::I16: return load<int16_t, Swap>(p);
        case Scalar::U16: return load<uint16_t, Swap>(p);
        case Scalar::I32: return load<int32_t, Swap>(p);
        case Scalar::U32: return load<uint32_t, Swap>(p);
        case Scalar::F32: return load<float, Swap>(p);
        case Scalar::F64: return load<double, Swap>(p);
    }
    return 0;
}

// Swap: the file's byte order is not the host's.
template <bool Swap>
class BinarySource {
public:
    static constexpr bool kAscii = false;
    BinarySource(std::string_view data, size_t offset) : p_(data.data() + offset), end_(data.data() + data.size()) {}

    bool read(Scalar t, double& v) {
        size_t n = sizeOf(t);
        if (size_t(end_ - p_) < n) return false;
        v = decode<Swap>(t, p_);
        p_ += n;
        return true;
    }
    bool skip(Scalar t, uint64_t count) {  // count <= kMaxListCount: no overflow
        uint64_t n = sizeOf(t) * count;
        if (uint64_t(end_ - p_) < n) return false;
        p_ += n;
        return true;
    }
    // Most instances of e that the remaining bytes can hold (lists may be empty).
    uint64_t maxInstances(const Element& e) const {
        uint64_t minBytes = 0;
        for (const Property& p : e.props) minBytes += sizeOf(p.isList ? p.countType : p.type);
        return uint64_t(end_ - p_) / minBytes;
    }

private:
    const char* p_;
    const char* end_;
};

// Whitespace-separated numbers; element boundaries need not match lines.
class AsciiSource {
public:
    static constexpr bool kAscii = true;
    AsciiSource(const std::string& path, std::string_view data, size_t offset)
        : path_(path), data_(data), p_(data.data() + offset), end_(data.data() + data.size()) {}

    bool read(Scalar, double& v) {
        while (p_ < end_ && isSpace(*p_)) ++p_;
        if (p_ == end_) return false;
        const char* start = p_;
        while (p_ < end_ && !isSpace(*p_)) ++p_;
        const char* b = (*start == '+' && p_ - start > 1) ? start + 1 : start;  // from_chars rejects '+'
        auto [end, ec] = std::from_chars(b, p_, v);
        if (ec == std::errc::result_out_of_range && end == p_)  // strtod tells overflow from underflow
            v = std::strtod(std::string(b, p_).c_str(), nullptr);
        else if (ec != std::errc() || end != p_)
            fail(path_, "bad number " + quote(std::string_view(start, size_t(p_ - start))) + " in ASCII PLY data on line " +
                            std::to_string(1 + std::count(data_.data(), start, '\n')));
        return true;
    }
    bool skip(Scalar t, uint64_t count) {
        double v;
        for (uint64_t i = 0; i < count; ++i)
            if (!read(t, v)) return false;
        return true;
    }
    // Every value takes a character and a separator, except perhaps the very last one.
    uint64_t maxInstances(const Element& e) const { return (uint64_t(end_ - p_) + 1) / (2 * e.props.size()); }

private:
    static bool isSpace(char c) { return c == ' ' || c == '\n' || c == '\r' || c == '\t' || c == '\v' || c == '\f'; }
    const std::string& path_;
    std::string_view data_;
    const char* p_;
    const char* end_;
};

// ---- mesh assembly ----

// One decoded element instance: the last value of each scalar role, and the leading entries
// and length of the vertex index list.
struct Instance {
    double value[int(Role::Count)] = {};
    double corner[4] = {};
    uint64_t corners = 0;
};

std::string plural(const Element& e) {
    if (e.name == "vertex") return "vertices";
    if (e.name == "face") return "faces";
    return "\"" + e.name + "\" elements";
}

class PlyReader {
public:
    explicit PlyReader(const std::string& path) : path_(path), data_(readFileBytes(path)) {}

    PlyMesh read() {
        header_ = HeaderParser(path_, data_).parse();
        assignRoles();
        switch (header_.format) {
            case Format::Ascii: readBody(AsciiSource(path_, data_, header_.bodyOffset)); break;
            case Format::BinaryLE:
                readBody(BinarySource<std::endian::native != std::endian::little>(data_, header_.bodyOffset));
                break;
            case Format::BinaryBE:
                readBody(BinarySource<std::endian::native != std::endian::big>(data_, header_.bodyOffset));
                break;
        }
        if (skippedFaces_ > 0)
            warning(path_ + ": skipped " + std::to_string(skippedFaces_) +
                    " face(s) with other than 3 or 4 vertices (pbrt-v4 reads only triangles and quads)");
        return std::move(mesh_);
    }

private:
    Element* findElement(std::string_view name) {
        Element* found = nullptr;
        for (Element& e : header_.elements)
            if (e.name == name) {
                if (found) fail(path_, "PLY header has more than one \"" + e.name + "\" element");
                found = &e;
            }
        return found;
    }
    static Property* findProperty(Element& e, std::string_view name, bool scalarOnly) {
        for (Property& p : e.props)
            if (p.name == name && !(scalarOnly && p.isList)) return &p;
        return nullptr;
    }

    void assignRoles() {
        Element* vertices = findElement("vertex");
        if (!vertices) fail(path_, "PLY file has no vertex element");
        if (vertices->count > uint64_t(INT_MAX))
            fail(path_, "too many vertices (" + std::to_string(vertices->count) + "); at most 2^31-1 are supported");
        assignVertexRoles(*vertices);
        Element* faces = findElement("face");
        if (faces) assignFaceRoles(*faces);
        vertices_ = vertices;
        faces_ = faces;
    }

    void assignVertexRoles(Element& e) {
        for (auto [name, role] : {std::pair{"x", Role::X}, {"y", Role::Y}, {"z", Role::Z}}) {
            Property* p = findProperty(e, name, false);
            if (!p) fail(path_, std::string("PLY vertices have no \"") + name + "\" property");
            if (p->isList) fail(path_, std::string("PLY vertex property \"") + name + "\" is a list, not a number");
            p->role = role;
        }
        Property* n[3] = {findProperty(e, "nx", true), findProperty(e, "ny", true), findProperty(e, "nz", true)};
        hasNormals_ = n[0] && n[1] && n[2];
        if (hasNormals_) {
            n[0]->role = Role::NX;
            n[1]->role = Role::NY;
            n[2]->role = Role::NZ;
        }
        // The first complete pair wins, in pbrt-v4's order.
        static constexpr std::pair<const char*, const char*> kUV[] = {
            {"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"}, {"texture_s", "texture_t"}};
        for (auto [un, vn] : kUV) {
            Property *u = findProperty(e, un, true), *v = findProperty(e, vn, true);
            if (u && v) {
                u->role = Role::U;
                v->role = Role::V;
                hasUV_ = true;
                break;
            }
        }
    }

    void assignFaceRoles(Element& e) {
        Property* idx = findProperty(e, "vertex_indices", false);
        if (!idx && (idx = findProperty(e, "vertex_index", false)))
            warning(path_ + ": PLY face property \"vertex_index\" read as \"vertex_indices\"; pbrt-v4 does not accept it");
        if (idx && !idx->isList) fail(path_, "PLY face property \"" + idx->name + "\" is a number, not a list");
        if (idx) idx->role = Role::Corners;
        else if (e.count > 0) fail(path_, "PLY faces have no \"vertex_indices\" list");
        if (Property* fi = findProperty(e, "face_indices", true)) {
            fi->role = Role::FaceIndex;
            hasFaceIndices_ = true;
        }
    }

    template <class Src>
    void readBody(Src src) {
        for (const Element& e : header_.elements) {
            if (e.props.empty() || e.count == 0) continue;  // takes no bytes
            if (Src::kAscii && e.count > kMaxAsciiCount)
                fail(path_, "PLY element \"" + e.name + "\" count " + std::to_string(e.count) + " exceeds the limit of 2^28");
            uint64_t fit = src.maxInstances(e);
            if (!Src::kAscii && e.fixedSize() && e.count > fit) truncated(e, fit, Src::kAscii);
            // No more instances than the data can hold: a short file claiming more fails as truncated.
            const uint64_t n = std::min(e.count, fit);
            requireMemory(path_ + ": a mesh of " + std::to_string(n) + " " + plural(e), double(n) * bytesPer(e));
            reserve(e, n);
            Instance in;
            for (uint64_t i = 0; i < e.count; ++i) {
                if (!readInstance(src, e, i, in)) truncated(e, i, Src::kAscii);
                if (&e == vertices_) addVertex(in, i);
                else if (&e == faces_) addFace(in, i);
            }
        }
    }

    [[noreturn]] void truncated(const Element& e, uint64_t got, bool ascii) {
        fail(path_, std::string("truncated ") + (ascii ? "ASCII" : "binary") + " PLY: expected " + std::to_string(e.count) +
                        " " + plural(e) + ", got " + std::to_string(got));
    }

    // What one instance of e adds to the mesh: a vertex's arrays, or a face's indices (at
    // least a triangle's). 0 for elements the mesh does not keep.
    double bytesPer(const Element& e) const {
        if (&e == vertices_) return sizeof(Vec3) * (hasNormals_ ? 2 : 1) + (hasUV_ ? sizeof(Vec2) : 0);
        if (&e == faces_) return sizeof(int) * (hasFaceIndices_ ? 4 : 3);
        return 0;
    }

    // Sizes come from counts already bounded by the data left, never from the header alone.
    void reserve(const Element& e, uint64_t n) {
        if (&e == vertices_) {
            mesh_.P.reserve(n);
            if (hasNormals_) mesh_.N.reserve(n);
            if (hasUV_) mesh_.uv.reserve(n);
        } else if (&e == faces_) {
            mesh_.triIndices.reserve(3 * n);
            if (hasFaceIndices_) mesh_.faceIndices.reserve(n);
        }
    }

    template <class Src>
    bool readInstance(Src& src, const Element& e, uint64_t index, Instance& in) {
        for (const Property& p : e.props) {
            if (!p.isList) {
                if (!src.read(p.type, in.value[int(p.role)])) return false;
                continue;
            }
            double n;
            if (!src.read(p.countType, n)) return false;
            uint64_t count = listCount(n, e, index, p);
            if (p.role != Role::Corners) {
                if (!src.skip(p.type, count)) return false;
                continue;
            }
            in.corners = count;
            uint64_t kept = std::min<uint64_t>(count, 4);
            for (uint64_t k = 0; k < kept; ++k)
                if (!src.read(p.type, in.corner[k])) return false;
            if (!src.skip(p.type, count - kept)) return false;
        }
        return true;
    }

    uint64_t listCount(double n, const Element& e, uint64_t index, const Property& p) {
        if (!(n >= 0 && n <= double(kMaxListCount) && n == std::floor(n)))
            fail(path_, "bad list length " + num(n) + " for \"" + p.name + "\" of PLY " + e.name + " " + std::to_string(index) +
                            " (must be an integer from 0 to " + std::to_string(kMaxListCount) + ")");
        return uint64_t(n);
    }

    // Converts to float, failing on NaN, infinity and values beyond float's range.
    void toFloats(const double* v, float* out, int n, uint64_t vertex, const char* what) {
        for (int i = 0; i < n; ++i) {
            if (!(std::fabs(v[i]) <= double(FLT_MAX)))
                fail(path_, "PLY vertex " + std::to_string(vertex) + " has " +
                                (std::isfinite(v[i]) ? "an out-of-range " : "a non-finite ") + what + " value " + num(v[i]));
            out[i] = float(v[i]);
        }
    }

    void addVertex(const Instance& in, uint64_t i) {
        const double* v = in.value;
        float f[3];
        toFloats(v + int(Role::X), f, 3, i, "position");
        mesh_.P.emplace_back(f[0], f[1], f[2]);
        if (hasNormals_) {
            toFloats(v + int(Role::NX), f, 3, i, "normal");
            mesh_.N.emplace_back(f[0], f[1], f[2]);
        }
        if (hasUV_) {
            toFloats(v + int(Role::U), f, 2, i, "uv");
            mesh_.uv.emplace_back(f[0], f[1]);
        }
    }

    void addFace(const Instance& in, uint64_t i) {
        if (hasFaceIndices_) {
            double fi = in.value[int(Role::FaceIndex)];
            if (!(fi >= INT_MIN && fi <= INT_MAX && fi == std::floor(fi)))
                fail(path_, "PLY face " + std::to_string(i) + " has a bad face_indices value " + num(fi));
            mesh_.faceIndices.push_back(int(fi));
        }
        if (in.corners != 3 && in.corners != 4) {
            ++skippedFaces_;
            return;
        }
        std::vector<int>& out = in.corners == 3 ? mesh_.triIndices : mesh_.quadIndices;
        for (uint64_t k = 0; k < in.corners; ++k) {
            double c = in.corner[k];
            if (c != std::floor(c)) fail(path_, "PLY face " + std::to_string(i) + " has a non-integer vertex index " + num(c));
            if (!(c >= 0 && c < double(vertices_->count)))
                fail(path_, "PLY face " + std::to_string(i) + " has vertex index " + num(c) + " out of range [0, " +
                                std::to_string(vertices_->count) + ")");
            out.push_back(int(c));
        }
    }

    const std::string& path_;
    std::string data_;
    Header header_;
    const Element* vertices_ = nullptr;
    const Element* faces_ = nullptr;
    bool hasNormals_ = false, hasUV_ = false, hasFaceIndices_ = false;
    uint64_t skippedFaces_ = 0;
    PlyMesh mesh_;
};

}  // namespace

PlyMesh readPly(const std::string& path) {
    noteInputFile(path);
    return PlyReader(path).read();
}

}  // namespace ps
