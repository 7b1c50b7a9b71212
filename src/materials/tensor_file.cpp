#include "materials/tensor_file.h"

#include <cstring>
#include <fstream>
#include <sstream>

#include "util/error.h"

namespace ps {

namespace {

size_t typeSize(TensorFile::Type t) {
    using T = TensorFile::Type;
    switch (t) {
    case T::UInt8: case T::Int8: return 1;
    case T::UInt16: case T::Int16: case T::Float16: return 2;
    case T::UInt32: case T::Int32: case T::Float32: return 4;
    case T::UInt64: case T::Int64: case T::Float64: return 8;
    default: return 0;
    }
}

// Reads little-endian values from the file's bytes, failing with `what` past the end.
class Cursor {
public:
    Cursor(const std::string& path, const std::string& bytes) : path_(path), bytes_(bytes) {}
    template <typename T>
    T get(const std::string& what) {
        T v;
        need(sizeof(T), what);
        std::memcpy(&v, bytes_.data() + pos_, sizeof(T));
        pos_ += sizeof(T);
        return v;
    }
    std::string str(size_t n, const std::string& what) {
        need(n, what);
        std::string s = bytes_.substr(pos_, n);
        pos_ += n;
        return s;
    }

private:
    void need(size_t n, const std::string& what) const {
        if (bytes_.size() - pos_ < n) throw InputError(path_ + ": tensor file truncated in the header (" + what + ")");
    }
    const std::string& path_;
    const std::string& bytes_;
    size_t pos_ = 0;
};

}  // namespace

TensorFile TensorFile::read(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path + ": cannot open tensor file: " + std::strerror(errno));
    std::ostringstream ss;
    ss << in.rdbuf();
    const std::string bytes = ss.str();

    TensorFile tf;
    tf.path_ = path;
    Cursor c(path, bytes);
    if (bytes.size() < 12 || std::memcmp(bytes.data(), "tensor_file", 12) != 0)
        throw InputError(path + ": not a tensor file (it does not begin with \"tensor_file\")");
    c.str(12, "magic");
    uint8_t major = c.get<uint8_t>("version"), minor = c.get<uint8_t>("version");
    if (major != 1 || minor != 0)
        throw InputError(path + ": tensor file version " + std::to_string(major) + "." + std::to_string(minor) + " is not supported (only 1.0)");
    uint32_t nFields = c.get<uint32_t>("field count");
    for (uint32_t i = 0; i < nFields; ++i) {
        std::string at = "field " + std::to_string(i + 1) + " of " + std::to_string(nFields);
        uint16_t nameLength = c.get<uint16_t>(at);
        std::string name = c.str(nameLength, at);
        at = "field " + quoteForMessage(name, 40);
        uint16_t rank = c.get<uint16_t>(at);
        uint8_t type = c.get<uint8_t>(at);
        uint64_t offset = c.get<uint64_t>(at);
        Field f;
        f.type = Type(type);
        size_t elem = typeSize(f.type);
        if (elem == 0) throw InputError(path + ": " + at + " has an unknown element type (" + std::to_string(type) + ")");
        // The product of the shape is checked against the file size as it grows, so a huge
        // or overflowing shape fails cleanly instead of allocating.
        uint64_t size = elem;
        for (uint16_t d = 0; d < rank; ++d) {
            uint64_t extent = c.get<uint64_t>(at);
            f.shape.push_back(extent);
            if (extent != 0 && size > bytes.size() / extent) size = UINT64_MAX;
            else size *= extent;
        }
        if (offset > bytes.size() || size > bytes.size() - offset)
            throw InputError(path + ": " + at + ": its data lies past the end of the file (truncated?)");
        f.bytes = bytes.substr(offset, size);
        tf.fields_[name] = std::move(f);
    }
    return tf;
}

const TensorFile::Field& TensorFile::field(const std::string& name) const {
    auto it = fields_.find(name);
    if (it == fields_.end()) throw InputError(path_ + ": the tensor file has no field \"" + name + "\"");
    return it->second;
}

const std::vector<uint64_t>& TensorFile::shape(const std::string& name) const { return field(name).shape; }

std::vector<float> TensorFile::floats(const std::string& name, size_t rank) const {
    const Field& f = field(name);
    if (f.type != Type::Float32) throw InputError(path_ + ": field \"" + name + "\" must hold float32 values");
    if (f.shape.size() != rank)
        throw InputError(path_ + ": field \"" + name + "\" must have " + std::to_string(rank) + " dimensions, not " +
                         std::to_string(f.shape.size()));
    std::vector<float> v(f.bytes.size() / 4);
    std::memcpy(v.data(), f.bytes.data(), v.size() * 4);
    return v;
}

}  // namespace ps
