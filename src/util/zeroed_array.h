// A fixed-size array of all-zero elements from calloc: large blocks come from the kernel
// already zeroed, so nothing is written until the array is used, and its pages are touched
// (and zeroed) by the threads that use them, not one memset on the calling thread (for a
// 2-megapixel film that memset was a tenth of a 1-spp render's process time, bench/README).
// T must be an implicit-lifetime type whose all-zero bytes are its zero value.
#pragma once
#include <cstdlib>
#include <new>
#include <type_traits>
#include <utility>

namespace ps {

template <typename T>
class ZeroedArray {
    static_assert(std::is_trivially_destructible_v<T> && std::is_trivially_copyable_v<T>);

public:
    ZeroedArray() = default;
    explicit ZeroedArray(size_t n) : size_(n) {
        if (n == 0) return;
        data_ = static_cast<T*>(std::calloc(n, sizeof(T)));
        if (!data_) throw std::bad_alloc();
    }
    ZeroedArray(ZeroedArray&& o) noexcept : data_(std::exchange(o.data_, nullptr)), size_(std::exchange(o.size_, 0)) {}
    ZeroedArray& operator=(ZeroedArray&& o) noexcept {
        std::swap(data_, o.data_);
        std::swap(size_, o.size_);
        return *this;
    }
    ZeroedArray(const ZeroedArray&) = delete;
    ZeroedArray& operator=(const ZeroedArray&) = delete;
    ~ZeroedArray() { std::free(data_); }

    size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }
    T& operator[](size_t i) { return data_[i]; }
    const T& operator[](size_t i) const { return data_[i]; }
    T* begin() { return data_; }
    T* end() { return data_ + size_; }
    const T* begin() const { return data_; }
    const T* end() const { return data_ + size_; }

private:
    T* data_ = nullptr;
    size_t size_ = 0;
};

}  // namespace ps
