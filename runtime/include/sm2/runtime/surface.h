// A surface: one level (or cube face, or volume level) of texels stored in their D3DFORMAT's
// exact memory layout. Textures are arrays of surfaces; render targets are surfaces.
#pragma once

#include <cstddef>
#include <cstdint>
#include <new>
#include <vector>

#include "sm2/runtime/formats.h"

namespace sm2::runtime {

// Texel storage starts on a 64-byte cache line (malloc gives 16 bytes): a render target's rows
// then split into the same whole lines as the tiles do (32 texels of 4 bytes are two lines), so
// the block paths' 8-texel row loads and stores never straddle two lines, and no line is shared
// by two tiles, which two threads may be writing at once.
// The storage also reaches at least kReadSlack bytes past its last element (whole lines): the
// sampler's block path reads a 1- or 2-byte texel as the 32-bit word at its offset (ignoring
// the bytes above it), so the word of a level's last texel stays inside the allocation without
// a per-lane test. The slack's bytes are never written and never decoded.
template <class T>
struct CacheLineAllocator {
    using value_type = T;
    static constexpr size_t kLine = 64, kReadSlack = 3;
    static constexpr std::align_val_t kAlignment{kLine};
    CacheLineAllocator() = default;
    template <class U>
    explicit CacheLineAllocator(const CacheLineAllocator<U>&) noexcept {}
    // (std::vector asks for at most max_size() = SIZE_MAX / sizeof(T) elements, whose bytes plus
    // the slack and the rounding could still wrap: the size saturates instead, which no
    // operator new satisfies.)
    T* allocate(size_t n) {
        const size_t bytes = n > (SIZE_MAX - kReadSlack - kLine) / sizeof(T)
                                 ? SIZE_MAX
                                 : (n * sizeof(T) + kReadSlack + kLine - 1) / kLine * kLine;
        return static_cast<T*>(::operator new(bytes, kAlignment));
    }
    void deallocate(T* p, size_t) noexcept { ::operator delete(p, kAlignment); }
    friend bool operator==(const CacheLineAllocator&, const CacheLineAllocator&) { return true; }
};
using TexelBytes = std::vector<std::byte, CacheLineAllocator<std::byte>>;

class Surface {
public:
    Surface() = default;
    // Zero-filled storage. Compressed formats round width/height up to whole 4x4 blocks.
    Surface(Format format, uint32_t width, uint32_t height, uint32_t depth = 1);

    [[nodiscard]] Format format() const { return format_; }
    [[nodiscard]] uint32_t width() const { return width_; }
    [[nodiscard]] uint32_t height() const { return height_; }
    [[nodiscard]] uint32_t depth() const { return depth_; }
    // Bytes from one row of texels (or of 4x4 blocks) to the next, and from one slice to the next.
    [[nodiscard]] size_t row_pitch() const { return row_pitch_; }
    [[nodiscard]] size_t slice_pitch() const { return slice_pitch_; }
    [[nodiscard]] TexelBytes& bytes() { return data_; }
    [[nodiscard]] const TexelBytes& bytes() const { return data_; }

    // The value a sampler sees at integer texel (x, y, z); coordinates must be in range.
    [[nodiscard]] Float4 read(uint32_t x, uint32_t y, uint32_t z = 0) const;
    // Stores with the format's conversion (not for compressed formats).
    void write(uint32_t x, uint32_t y, uint32_t z, const Float4& value);
    void fill(const Float4& value);

private:
    Format format_ = Format::Unknown;
    uint32_t width_ = 0, height_ = 0, depth_ = 0;
    size_t row_pitch_ = 0, slice_pitch_ = 0;
    unsigned texel_bytes_ = 0;
    TexelDecoder decoder_ = nullptr;  // looked up once: read/write run per pixel
    TexelEncoder encoder_ = nullptr;
    TexelBytes data_;
};

}  // namespace sm2::runtime
