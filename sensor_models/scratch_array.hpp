#pragma once

#include <cstddef>
#include <memory>
#include <new>
#include <span>
#include <type_traits>
#include <utility>

namespace casmap::sensor_models {

/// Stack storage for up to N trivially destructible T of which only the first n are
/// constructed: per-pulse buffers in hot loops without zeroing all N elements (kMaxSubrays is
/// 37 while a pulse usually has 19 sub-rays). Never allocates.
template <class T, std::size_t N>
class ScratchArray {
    static_assert(std::is_trivially_destructible_v<T>);

public:
    ScratchArray() = default;
    ScratchArray(const ScratchArray&) = delete;
    ScratchArray& operator=(const ScratchArray&) = delete;

    /// Default-constructs elements [size(), n); n must not exceed N.
    void Construct(std::size_t n) {
        if (n > size_) {
            std::uninitialized_default_construct_n(data() + size_, n - size_);
            size_ = n;
        }
    }
    /// Constructs one more element from `args` (size() must be below N).
    template <class... Args>
    T& EmplaceBack(Args&&... args) {
        T* p = ::new (static_cast<void*>(data() + size_)) T{std::forward<Args>(args)...};
        ++size_;
        return *p;
    }
    [[nodiscard]] T* data() { return std::launder(reinterpret_cast<T*>(raw_)); }
    [[nodiscard]] const T* data() const { return std::launder(reinterpret_cast<const T*>(raw_)); }
    [[nodiscard]] std::size_t size() const { return size_; }
    T& operator[](std::size_t i) { return data()[i]; }
    const T& operator[](std::size_t i) const { return data()[i]; }
    [[nodiscard]] std::span<T> span() { return {data(), size_}; }
    [[nodiscard]] std::span<const T> span() const { return {data(), size_}; }

private:
    alignas(T) std::byte raw_[sizeof(T) * N];
    std::size_t size_ = 0;
};

}  // namespace casmap::sensor_models
