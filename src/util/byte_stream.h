// The state of a render in flight as bytes (a Metropolis checkpoint's chains): values and
// vectors of trivially copyable types appended in the machine's byte order, and read back
// in the same order. A read past the end throws InputError: damaged data is refused, never
// read out of bounds.
#pragma once
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "util/error.h"

namespace ps {

class ByteWriter {
public:
    template <class T>
    void put(const T& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        const size_t at = bytes_.size();
        bytes_.resize(at + sizeof(T));
        std::memcpy(bytes_.data() + at, &v, sizeof(T));
    }
    template <class T>
    void putVector(const std::vector<T>& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        put(uint64_t(v.size()));
        putBytes(v.data(), v.size() * sizeof(T));
    }
    void putBytes(const void* data, size_t n) {
        if (n == 0) return;
        const size_t at = bytes_.size();
        bytes_.resize(at + n);
        std::memcpy(bytes_.data() + at, data, n);
    }
    std::vector<char>& bytes() { return bytes_; }

private:
    std::vector<char> bytes_;
};

class ByteReader {
public:
    // `what` names the data in the error a damaged one raises.
    ByteReader(std::span<const char> bytes, std::string what) : bytes_(bytes), what_(std::move(what)) {}
    template <class T>
    T get() {
        static_assert(std::is_trivially_copyable_v<T>);
        T v;
        std::memcpy(&v, take(sizeof(T)), sizeof(T));
        return v;
    }
    template <class T>
    std::vector<T> getVector() {
        static_assert(std::is_trivially_copyable_v<T>);
        const uint64_t n = get<uint64_t>();
        if (n > (bytes_.size() - at_) / sizeof(T)) fail();
        std::vector<T> v(static_cast<size_t>(n));
        if (n > 0) std::memcpy(v.data(), take(size_t(n) * sizeof(T)), size_t(n) * sizeof(T));
        return v;
    }
    std::span<const char> getSpan(size_t n) { return {take(n), n}; }
    bool atEnd() const { return at_ == bytes_.size(); }
    [[noreturn]] void fail() const { throw InputError(what_ + ": damaged (its contents end early or do not parse)"); }

private:
    const char* take(size_t n) {
        if (n > bytes_.size() - at_) fail();
        const char* p = bytes_.data() + at_;
        at_ += n;
        return p;
    }
    std::span<const char> bytes_;
    size_t at_ = 0;
    std::string what_;
};

}  // namespace ps
