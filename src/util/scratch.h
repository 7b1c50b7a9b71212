// Bump allocator for per-sample temporaries (BSDFs, textures results); reset after each
// camera sample so shading allocates nothing from the heap in the render loop.
#pragma once
#include <cstddef>
#include <memory>
#include <new>
#include <utility>
#include <vector>

namespace ps {

class ScratchBuffer {
public:
    explicit ScratchBuffer(size_t bytes = 64 * 1024) : size_(bytes), data_(new std::byte[bytes]) {}
    ScratchBuffer(const ScratchBuffer&) = delete;
    ScratchBuffer& operator=(const ScratchBuffer&) = delete;
    ScratchBuffer(ScratchBuffer&&) = default;
    ScratchBuffer& operator=(ScratchBuffer&&) = default;

    // Objects built here must be trivially destructible or not need destruction.
    template <typename T, typename... Args>
    T* alloc(Args&&... args) {
        void* p = allocBytes(sizeof(T), alignof(T));
        return new (p) T(std::forward<Args>(args)...);
    }
    void* allocBytes(size_t bytes, size_t align) {
        size_t offset = (offset_ + align - 1) & ~(align - 1);
        if (offset + bytes > size_) {
            // Keep the old block alive until reset; grow for the next allocations.
            retired_.push_back(std::move(data_));
            size_ = std::max(2 * size_, bytes + align);
            data_.reset(new std::byte[size_]);
            offset = 0;
        }
        offset_ = offset + bytes;
        return data_.get() + offset;
    }
    void reset() {
        offset_ = 0;
        retired_.clear();
    }

private:
    size_t size_, offset_ = 0;
    std::unique_ptr<std::byte[]> data_;
    std::vector<std::unique_ptr<std::byte[]>> retired_;
};

}  // namespace ps
