#include "scene/ply.h"

#include <zlib.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "util/error.h"

namespace ps {

namespace {

constexpr size_t kMaxBytes = size_t(2) << 30;   // 2 GiB after decompression
constexpr long long kMaxCount = 1LL << 28;      // elements per PLY element type
constexpr long long kMaxListLength = 1 << 16;

enum class Format { Ascii, BinaryLE, BinaryBE };
enum class Scalar { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

int scalarSize(Scalar s) {
    switch (s) {
        case Scalar::Int8: case Scalar::UInt8: return 1;
        case Scalar::Int16: case Scalar::UInt16: return 2;
        case Scalar::Int32: case Scalar::UInt32: case Scalar::Float32: return 4;
        case Scalar::Float64: return 8;
    }
    return 1;
}

bool parseScalar(const std::string& name, Scalar& s) {
    static const std::pair<const char*, Scalar> names[] = {
        {"char", Scalar::Int8},    {"int8", Scalar::Int8},       {"uchar", Scalar::UInt8},    {"uint8", Scalar::UInt8},
        {"short", Scalar::Int16},  {"int16", Scalar::Int16},     {"ushort", Scalar::UInt16},  {"uint16", Scalar::UInt16},
        {"int", Scalar::Int32},    {"int32", Scalar::Int32},     {"uint", Scalar::UInt32},    {"uint32", Scalar::UInt32},
        {"float", Scalar::Float32}, {"float32", Scalar::Float32}, {"double", Scalar::Float64}, {"float64", Scalar::Float64}};
    for (auto& [n, v] : names)
        if (name == n) {
            s = v;
            return true;
        }
    return false;
}

struct Property {
    std::string name;
    Scalar type = Scalar::Float32;
    bool isList = false;
    Scalar countType = Scalar::UInt8;
};

struct Element {
    std::string name;
    long long count = 0;
    std::vector<Property> props;
};

// Reads values from the body in any of the three encodings.
class Body {
public:
    Body(const std::string& path, const std::string& data, size_t pos, Format f) : path_(path), data_(data), pos_(pos), format_(f) {}

    double read(Scalar s) {
        if (format_ == Format::Ascii) return readAscii();
        int n = scalarSize(s);
        if (pos_ + n > data_.size()) throw InputError(path_ + ": truncated binary PLY data");
        unsigned char b[8];
        std::memcpy(b, data_.data() + pos_, n);
        pos_ += n;
        if (format_ == Format::BinaryBE) std::reverse(b, b + n);
        switch (s) {
            case Scalar::Int8: return double(int8_t(b[0]));
            case Scalar::UInt8: return double(b[0]);
            case Scalar::Int16: { int16_t v; std::memcpy(&v, b, 2); return v; }
            case Scalar::UInt16: { uint16_t v; std::memcpy(&v, b, 2); return v; }
            case Scalar::Int32: { int32_t v; std::memcpy(&v, b, 4); return v; }
            case Scalar::UInt32: { uint32_t v; std::memcpy(&v, b, 4); return v; }
            case Scalar::Float32: { float v; std::memcpy(&v, b, 4); return v; }
            case Scalar::Float64: { double v; std::memcpy(&v, b, 8); return v; }
        }
        return 0;
    }
    size_t remaining() const { return data_.size() - pos_; }

private:
    double readAscii() {
        while (pos_ < data_.size() && std::isspace(static_cast<unsigned char>(data_[pos_]))) ++pos_;
        if (pos_ >= data_.size()) throw InputError(path_ + ": truncated ASCII PLY data");
        size_t end = pos_;
        while (end < data_.size() && !std::isspace(static_cast<unsigned char>(data_[end]))) ++end;
        double v = 0;
        const char* b = data_.data() + pos_;
        if (*b == '+') ++b;
        auto [p, ec] = std::from_chars(b, data_.data() + end, v);
        if (ec != std::errc() || p != data_.data() + end)
            throw InputError(path_ + ": bad number \"" + data_.substr(pos_, std::min<size_t>(end - pos_, 30)) + "\" in ASCII PLY");
        pos_ = end;
        return v;
    }
    const std::string& path_;
    const std::string& data_;
    size_t pos_;
    Format format_;
};

std::string readAll(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path + ": cannot open PLY file: " + std::strerror(errno));
    unsigned char magic[2] = {0, 0};
    in.read(reinterpret_cast<char*>(magic), 2);
    in.seekg(0);
    if (magic[0] == 0x1f && magic[1] == 0x8b) {
        in.close();
        gzFile f = gzopen(path.c_str(), "rb");
        if (!f) throw InputError(path + ": cannot open PLY file");
        std::string out;
        char buf[1 << 16];
        int n;
        while ((n = gzread(f, buf, sizeof buf)) > 0) {
            out.append(buf, size_t(n));
            if (out.size() > kMaxBytes) {
                gzclose(f);
                throw InputError(path + ": decompressed PLY is larger than 2 GiB");
            }
        }
        int err = 0;
        gzerror(f, &err);
        gzclose(f);
        if (n < 0 || (err != Z_OK && err != Z_STREAM_END)) throw InputError(path + ": corrupt gzip data");
        return out;
    }
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

}  // namespace

PlyMesh readPly(const std::string& path) {
    std::string data = readAll(path);
    // ---- header ----
    size_t pos = 0;
    auto nextLine = [&](std::string& line) {
        if (pos >= data.size()) return false;
        size_t e = data.find('\n', pos);
        if (e == std::string::npos) e = data.size();
        line = data.substr(pos, e - pos);
        if (!line.empty() && line.back() == '\r') line.pop_back();
        pos = e + 1;
        return true;
    };
    std::string line;
    if (!nextLine(line) || line != "ply") throw InputError(path + ": not a PLY file (missing \"ply\" magic)");
    Format format = Format::Ascii;
    bool haveFormat = false;
    std::vector<Element> elements;
    while (true) {
        if (!nextLine(line)) throw InputError(path + ": PLY header has no end_header");
        std::istringstream ls(line);
        std::string kw;
        ls >> kw;
        if (kw.empty() || kw == "comment" || kw == "obj_info") continue;
        if (kw == "end_header") break;
        if (kw == "format") {
            std::string f, version;
            ls >> f >> version;
            if (f == "ascii") format = Format::Ascii;
            else if (f == "binary_little_endian") format = Format::BinaryLE;
            else if (f == "binary_big_endian") format = Format::BinaryBE;
            else throw InputError(path + ": unsupported PLY format \"" + f + "\"");
            haveFormat = true;
        } else if (kw == "element") {
            Element e;
            ls >> e.name >> e.count;
            if (!ls || e.count < 0 || e.count > kMaxCount)
                throw InputError(path + ": bad element count in PLY header line \"" + line + "\"");
            elements.push_back(e);
        } else if (kw == "property") {
            if (elements.empty()) throw InputError(path + ": PLY property before any element");
            Property p;
            std::string t;
            ls >> t;
            if (t == "list") {
                std::string ct, it;
                ls >> ct >> it >> p.name;
                p.isList = true;
                if (!parseScalar(ct, p.countType) || !parseScalar(it, p.type))
                    throw InputError(path + ": bad PLY list property \"" + line + "\"");
            } else {
                ls >> p.name;
                if (!parseScalar(t, p.type)) throw InputError(path + ": unknown PLY property type \"" + t + "\"");
            }
            if (p.name.empty()) throw InputError(path + ": PLY property without a name");
            elements.back().props.push_back(p);
        } else {
            throw InputError(path + ": bad PLY header line \"" + line + "\"");
        }
    }
    if (!haveFormat) throw InputError(path + ": PLY header has no format line");

    // ---- body ----
    Body body(path, data, std::min(pos, data.size()), format);
    PlyMesh mesh;
    long long nVertices = -1;
    size_t skippedFaces = 0;
    bool warnedVertexIndex = false;
    for (const Element& el : elements) {
        if (format != Format::Ascii) {
            // Cheap sanity check before allocating: every element needs at least its fixed bytes.
            long long minBytes = 0;
            for (const Property& p : el.props) minBytes += p.isList ? scalarSize(p.countType) : scalarSize(p.type);
            if (minBytes > 0 && el.count > (long long)(body.remaining() / size_t(minBytes)))
                throw InputError(path + ": truncated binary PLY: " + std::to_string(el.count) + " " + el.name +
                                 " elements do not fit in the file");
        }
        if (el.name == "vertex") {
            int ix = -1, iy = -1, iz = -1, inx = -1, iny = -1, inz = -1, iu = -1, iv = -1;
            for (int i = 0; i < int(el.props.size()); ++i) {
                const std::string& n = el.props[i].name;
                if (el.props[i].isList) continue;
                if (n == "x") ix = i; else if (n == "y") iy = i; else if (n == "z") iz = i;
                else if (n == "nx") inx = i; else if (n == "ny") iny = i; else if (n == "nz") inz = i;
                else if (n == "u" || n == "s" || n == "texture_u" || n == "texture_s") iu = i;
                else if (n == "v" || n == "t" || n == "texture_v" || n == "texture_t") iv = i;
            }
            if (ix < 0 || iy < 0 || iz < 0) throw InputError(path + ": PLY vertices lack x, y or z");
            bool normals = inx >= 0 && iny >= 0 && inz >= 0, uvs = iu >= 0 && iv >= 0;
            nVertices = el.count;
            mesh.P.resize(size_t(el.count));
            if (normals) mesh.N.resize(size_t(el.count));
            if (uvs) mesh.uv.resize(size_t(el.count));
            std::vector<double> vals(el.props.size());
            for (long long v = 0; v < el.count; ++v) {
                for (size_t i = 0; i < el.props.size(); ++i) {
                    const Property& p = el.props[i];
                    if (p.isList) {
                        double n = body.read(p.countType);
                        if (n < 0 || n > kMaxListLength) throw InputError(path + ": bad list length in PLY vertex");
                        for (int k = 0; k < int(n); ++k) body.read(p.type);
                        vals[i] = 0;
                    } else {
                        vals[i] = body.read(p.type);
                    }
                }
                Vec3 P(float(vals[ix]), float(vals[iy]), float(vals[iz]));
                if (!isFinite(P)) throw InputError(path + ": vertex " + std::to_string(v) + " has a non-finite coordinate");
                mesh.P[size_t(v)] = P;
                if (normals) mesh.N[size_t(v)] = Vec3(float(vals[inx]), float(vals[iny]), float(vals[inz]));
                if (uvs) mesh.uv[size_t(v)] = Vec2(float(vals[iu]), float(vals[iv]));
            }
        } else if (el.name == "face") {
            int iidx = -1, iface = -1;
            for (int i = 0; i < int(el.props.size()); ++i) {
                if (el.props[i].name == "vertex_indices" && el.props[i].isList) iidx = i;
                else if (el.props[i].name == "vertex_index" && el.props[i].isList && iidx < 0) {
                    iidx = i;
                    if (!warnedVertexIndex) warning(path + ": PLY face list \"vertex_index\" accepted (pbrt-v4 requires \"vertex_indices\")");
                    warnedVertexIndex = true;
                } else if (el.props[i].name == "face_indices" && !el.props[i].isList) {
                    iface = i;
                }
            }
            if (iidx < 0) throw InputError(path + ": PLY faces lack a \"vertex_indices\" list");
            if (nVertices < 0) throw InputError(path + ": PLY faces come before the vertices");
            int idx[4] = {0, 0, 0, 0};
            for (long long f = 0; f < el.count; ++f) {
                int n = 0;
                for (int i = 0; i < int(el.props.size()); ++i) {
                    const Property& p = el.props[i];
                    if (!p.isList) {
                        double v = body.read(p.type);
                        if (i == iface) mesh.faceIndices.push_back(int(v));
                        continue;
                    }
                    double cnt = body.read(p.countType);
                    if (cnt < 0 || cnt > kMaxListLength || cnt != std::floor(cnt))
                        throw InputError(path + ": bad list length " + std::to_string(cnt) + " in PLY face " + std::to_string(f));
                    for (int k = 0; k < int(cnt); ++k) {
                        double v = body.read(p.type);
                        if (i != iidx) continue;
                        if (v < 0 || v >= double(nVertices) || v != std::floor(v))
                            throw InputError(path + ": face " + std::to_string(f) + " has vertex index " + std::to_string((long long)v) +
                                             " out of range [0, " + std::to_string(nVertices) + ")");
                        if (k < 4) idx[k] = int(v);
                    }
                    if (i == iidx) n = int(cnt);
                }
                if (n == 3) mesh.triIndices.insert(mesh.triIndices.end(), idx, idx + 3);
                else if (n == 4) mesh.quadIndices.insert(mesh.quadIndices.end(), idx, idx + 4);
                else ++skippedFaces;
            }
        } else {
            // Unknown element: skip its values.
            for (long long k = 0; k < el.count; ++k)
                for (const Property& p : el.props) {
                    if (p.isList) {
                        double n = body.read(p.countType);
                        if (n < 0 || n > kMaxListLength) throw InputError(path + ": bad list length in PLY element \"" + el.name + "\"");
                        for (int j = 0; j < int(n); ++j) body.read(p.type);
                    } else {
                        body.read(p.type);
                    }
                }
        }
    }
    if (nVertices < 0) throw InputError(path + ": PLY file has no vertex element");
    if (skippedFaces) warning(path + ": " + std::to_string(skippedFaces) + " PLY face(s) with other than 3 or 4 vertices skipped");
    if (!mesh.faceIndices.empty() && mesh.faceIndices.size() != mesh.triIndices.size() / 3 + mesh.quadIndices.size() / 4)
        mesh.faceIndices.clear();
    return mesh;
}

}  // namespace ps
