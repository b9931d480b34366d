// Surfaces: texels in their format's exact memory layout (formats.cpp describes the layouts).
#include "sm2/runtime/surface.h"

#include <cstring>
#include <stdexcept>
#include <string>

#include "dxt.h"

namespace sm2::runtime {

namespace {
[[noreturn]] void bad(const std::string& what) { throw std::invalid_argument("Surface: " + what); }
}  // namespace

Surface::Surface(Format format, uint32_t width, uint32_t height, uint32_t depth)
    : format_(format), width_(width), height_(height), depth_(depth) {
    const FormatInfo* info = format_info(format);
    if (info == nullptr || info->bytes == 0) bad("unknown format " + std::to_string(static_cast<uint32_t>(format)));
    if (width == 0 || height == 0 || depth == 0) bad("zero size");
    if (width > 16384 || height > 16384 || depth > 16384) bad("size above 16384");
    if (info->kind == FormatKind::Compressed) {
        row_pitch_ = size_t{(width + 3) / 4} * info->bytes;
        slice_pitch_ = row_pitch_ * ((height + 3) / 4);
    } else {
        row_pitch_ = size_t{width} * info->bytes;
        slice_pitch_ = row_pitch_ * height;
    }
    texel_bytes_ = info->bytes;
    decoder_ = texel_decoder(format);
    encoder_ = texel_encoder(format);
    // Value-initialized (zero): resize() on the empty vector, which the compiler turns into one
    // memset; assign(n, byte{0}) through CacheLineAllocator stored byte by byte (15 M
    // instructions of bench_1024's run).
    data_.resize(slice_pitch_ * depth);
}

Float4 Surface::read(uint32_t x, uint32_t y, uint32_t z) const {
    if (x >= width_ || y >= height_ || z >= depth_) throw std::out_of_range("Surface::read: texel outside the surface");
    const std::byte* slice = data_.data() + z * slice_pitch_;
    if (dxt::is_dxt(format_)) {
        const std::byte* block = slice + (y / 4) * row_pitch_ + (x / 4) * dxt::block_bytes(format_);
        return dxt::to_float(dxt::decode_texel(format_, block, x % 4, y % 4));
    }
    if (decoder_ == nullptr) return decode_texel(format_, slice);  // throws: no texel layout
    return decoder_(slice + y * row_pitch_ + size_t{x} * texel_bytes_);
}

void Surface::write(uint32_t x, uint32_t y, uint32_t z, const Float4& value) {
    if (x >= width_ || y >= height_ || z >= depth_) throw std::out_of_range("Surface::write: texel outside the surface");
    if (dxt::is_dxt(format_)) throw std::invalid_argument("Surface::write: compressed formats are written as blocks");
    if (encoder_ == nullptr) return encode_texel(format_, value, data_.data());  // throws: no texel layout
    encoder_(value, data_.data() + z * slice_pitch_ + y * row_pitch_ + size_t{x} * texel_bytes_);
}

void Surface::fill(const Float4& value) {
    if (dxt::is_dxt(format_)) throw std::invalid_argument("Surface::fill: compressed formats are written as blocks");
    const FormatInfo* info = format_info(format_);
    std::byte texel[16];
    encode_texel(format_, value, texel);
    for (size_t at = 0; at + info->bytes <= data_.size(); at += info->bytes) std::memcpy(data_.data() + at, texel, info->bytes);
}

}  // namespace sm2::runtime
