// The binary "tensor file" of the RGL material database (Dupuy & Jakob 2018), read as
// pbrt-v4 reads it: a 12-byte magic "tensor_file\0", version 1.0, a uint32 field count,
// then per field its name (uint16 length + bytes), rank (uint16), element type (uint8),
// the byte offset of its data (uint64) and its shape (rank uint64s). Little-endian.
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace ps {

class TensorFile {
public:
    enum class Type : uint8_t { Invalid, UInt8, Int8, UInt16, Int16, UInt32, Int32, UInt64, Int64, Float16, Float32, Float64 };
    struct Field {
        Type type = Type::Invalid;
        std::vector<uint64_t> shape;
        std::string bytes;  // the raw data
    };

    // Throws InputError "PATH: ..." (no location: the caller adds the directive's) for a
    // missing file, a wrong magic or version, a truncated header or a field whose data lies
    // past the end of the file.
    static TensorFile read(const std::string& path);

    const std::string& path() const { return path_; }
    bool has(const std::string& name) const { return fields_.count(name) != 0; }
    // The field's data as floats, checking that it exists, is float32 and has the given rank
    // (InputError naming the file and the field otherwise).
    std::vector<float> floats(const std::string& name, size_t rank) const;
    // Its shape (the field must exist).
    const std::vector<uint64_t>& shape(const std::string& name) const;

private:
    const Field& field(const std::string& name) const;
    std::string path_;
    std::map<std::string, Field> fields_;
};

}  // namespace ps
