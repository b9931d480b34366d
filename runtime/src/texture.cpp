// Texture resources and box-filtered mip generation.
#include "sm2/runtime/texture.h"

#include <array>
#include <atomic>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <string>

#include "dxt.h"
#include "format_layout.h"

namespace sm2::runtime {

namespace {
// Guards every Texture's decoded_dxt_ (one lock for all: taken once per draw and DXTn stage,
// and by write accesses to DXTn textures).
std::mutex& decoded_dxt_mutex() {
    static std::mutex mutex;
    return mutex;
}

// The bytes of the decoded_dxt() copies alive, and their budget. Atomic: a copy gives its bytes
// back when its last owner lets it go, which may be under decoded_dxt_mutex() (surface()).
std::atomic<uint64_t> decoded_dxt_bytes{0};
std::atomic<uint64_t> decoded_dxt_budget{uint64_t{1} << 30};

[[noreturn]] void bad(const std::string& what) { throw std::invalid_argument("Texture: " + what); }
bool pow2(uint32_t v) { return v != 0 && (v & (v - 1)) == 0; }
}  // namespace

uint32_t Texture::full_chain(uint32_t width, uint32_t height, uint32_t depth) {
    uint32_t m = width > height ? width : height;
    m = m > depth ? m : depth;
    uint32_t n = 1;
    while (m > 1) {
        m >>= 1;
        ++n;
    }
    return n;
}

Texture Texture::create(TextureType type, Format format, uint32_t width, uint32_t height, uint32_t depth,
                        uint32_t levels) {
    const FormatInfo* info = format_info(format);
    if (info == nullptr || !info->texture) bad("format " + std::to_string(static_cast<uint32_t>(format)) + " is not a texture format");
    const uint32_t limit = type == TextureType::Volume ? kMaxSizeVolume : kMaxSize2D;
    if (width == 0 || height == 0 || depth == 0) bad("zero size");
    if (width > limit || height > limit || depth > limit)
        bad("size above " + std::to_string(limit) + " per side");
    if (info->kind == FormatKind::Compressed && (width % 4 != 0 || height % 4 != 0))
        bad("DXTn sizes must be multiples of 4");
    const bool power_of_two = pow2(width) && pow2(height) && pow2(depth);
    const uint32_t chain = full_chain(width, height, depth);
    if (levels == 0) levels = power_of_two ? chain : 1;
    if (levels > chain) bad("more levels than the mip chain has");
    if (!power_of_two && levels > 1) bad("non-power-of-two textures have one level (conditional NONPOW2)");

    Texture t;
    t.type_ = type;
    t.format_ = format;
    t.width_ = width;
    t.height_ = height;
    t.depth_ = depth;
    t.levels_ = levels;
    const uint32_t faces = type == TextureType::Cube ? 6 : 1;
    t.surfaces_.reserve(size_t{faces} * levels);
    for (uint32_t f = 0; f < faces; ++f)
        for (uint32_t l = 0; l < levels; ++l)
            t.surfaces_.emplace_back(format, level_size(width, l), level_size(height, l), level_size(depth, l));
    return t;
}

Texture Texture::create_2d(Format format, uint32_t width, uint32_t height, uint32_t levels) {
    return create(TextureType::Texture2D, format, width, height, 1, levels);
}
Texture Texture::create_cube(Format format, uint32_t size, uint32_t levels) {
    return create(TextureType::Cube, format, size, size, 1, levels);
}
Texture Texture::create_volume(Format format, uint32_t width, uint32_t height, uint32_t depth, uint32_t levels) {
    return create(TextureType::Volume, format, width, height, depth, levels);
}

Surface& Texture::surface(uint32_t level, uint32_t face) {
    if (level >= levels_ || face >= faces()) throw std::out_of_range("Texture::surface: no such level or face");
    if (dxt::is_dxt(format_)) {
        // The caller may write the blocks: the decoded copy no longer holds.
        const std::lock_guard lock(decoded_dxt_mutex());
        decoded_dxt_.reset();
    }
    return surfaces_[size_t{face} * levels_ + level];
}
const Surface& Texture::surface(uint32_t level, uint32_t face) const {
    if (level >= levels_ || face >= faces()) throw std::out_of_range("Texture::surface: no such level or face");
    return surfaces_[size_t{face} * levels_ + level];
}

std::shared_ptr<const Texture> Texture::decoded_dxt() const {
    if (!dxt::is_dxt(format_)) return nullptr;
    const std::lock_guard lock(decoded_dxt_mutex());
    if (decoded_dxt_) return decoded_dxt_;
    uint64_t bytes = 0;
    for (uint32_t l = 0; l < levels_; ++l)
        bytes += uint64_t{4} * faces() * level_width(l) * level_height(l) * level_depth(l);
    // (Only the deleter changes the count concurrently, and it only lowers it.)
    if (decoded_dxt_bytes.load() + bytes > decoded_dxt_budget.load()) return nullptr;
    auto made = std::make_unique<Texture>(create(type_, Format::A8R8G8B8, width_, height_, depth_, levels_));
    decoded_dxt_bytes.fetch_add(bytes);
    const std::shared_ptr<Texture> decoded(made.release(), [bytes](const Texture* t) {
        delete t;
        decoded_dxt_bytes.fetch_sub(bytes);
    });
    const unsigned block_bytes = dxt::block_bytes(format_);
    std::array<dxt::Rgba8, 16> texels;
    for (uint32_t f = 0; f < faces(); ++f)
        for (uint32_t l = 0; l < levels_; ++l) {
            // (The const overload: the non-const one would drop the copy being made.)
            const Surface& blocks = surface(l, f);
            Surface& out = decoded->surfaces_[size_t{f} * levels_ + l];
            // Levels below 4 texels a side keep a whole block, of which they read the first texels.
            for (uint32_t z = 0; z < out.depth(); ++z)
                for (uint32_t by = 0; by < (out.height() + 3) / 4; ++by)
                    for (uint32_t bx = 0; bx < (out.width() + 3) / 4; ++bx) {
                        const std::byte* block = blocks.bytes().data() + size_t{z} * blocks.slice_pitch() +
                                                 size_t{by} * blocks.row_pitch() + size_t{bx} * block_bytes;
                        dxt::decode_block(format_, block, texels);
                        for (uint32_t y = 0; y < 4 && 4 * by + y < out.height(); ++y)
                            for (uint32_t x = 0; x < 4 && 4 * bx + x < out.width(); ++x) {
                                const dxt::Rgba8 t = texels[4 * y + x];
                                // A8R8G8B8 in memory: blue, green, red, alpha.
                                std::byte* texel = out.bytes().data() + size_t{z} * out.slice_pitch() +
                                                   size_t{4 * by + y} * out.row_pitch() + size_t{4 * bx + x} * 4;
                                texel[0] = static_cast<std::byte>(t.b);
                                texel[1] = static_cast<std::byte>(t.g);
                                texel[2] = static_cast<std::byte>(t.r);
                                texel[3] = static_cast<std::byte>(t.a);
                            }
                    }
        }
    decoded_dxt_ = decoded;
    return decoded_dxt_;
}

uint64_t Texture::set_decoded_dxt_budget(uint64_t bytes) { return decoded_dxt_budget.exchange(bytes); }

namespace {

// Four bytes of a texel and their values on the way (GCC vectors: SSE2 or wider).
typedef uint8_t Bytes4 __attribute__((vector_size(4)));
typedef int32_t Ints4 __attribute__((vector_size(16)));
typedef float Floats4 __attribute__((vector_size(16)));
typedef double Doubles4 __attribute__((vector_size(32)));

// The source index of a box filter's tap: the last texel of a side of 1 (or an odd side's end).
uint32_t tap_index(uint32_t i, uint32_t size) { return i < size ? i : size - 1; }

// generate_mips()'s box filter for a level of texels whose every stored channel is an 8-bit
// UNORM in its own byte (layout::bytewise_unorm8: A8R8G8B8, X8R8G8B8, A8B8G8R8, A8, ...), byte
// by byte with Surface::read()'s and Surface::write()'s values instead of a Float4 a tap: each
// tap's byte as read() decodes it (v / 255 in float), the taps summed in the
// generic loop's order and scaled in float, the sum stored as the encoder rounds it (round(255 v)
// in double, halves up); a byte no channel stores is 0, as the encoder leaves it.
// (Cloned for AVX2: SSE2 alone has no byte-to-int widening, which it spelled byte by byte.)
__attribute__((target_clones("arch=x86-64-v3", "default")))
void box_filter_bytes(const layout::Layout& lay, unsigned texel_bytes, const Surface& src, Surface& dst) {
    std::array<bool, 4> stored{};
    for (const layout::Channel& c : lay.rgba)
        if (c.type == layout::Type::Unorm) stored[c.shift / 8] = true;
    const Ints4 stored_mask{stored[0] ? -1 : 0, stored[1] ? -1 : 0, stored[2] ? -1 : 0, stored[3] ? -1 : 0};
    const uint32_t zn = src.depth() > 1 ? 2 : 1;
    const float scale = 1.0f / static_cast<float>(4 * zn);
    const std::byte* const in = src.bytes().data();
    std::byte* const out = dst.bytes().data();
    for (uint32_t z = 0; z < dst.depth(); ++z)
        for (uint32_t y = 0; y < dst.height(); ++y)
            for (uint32_t x = 0; x < dst.width(); ++x) {
                // The taps in the generic loop's order: z, then y, then x.
                std::array<const std::byte*, 8> taps{};
                unsigned count = 0;
                for (uint32_t dz = 0; dz < zn; ++dz)
                    for (uint32_t dy = 0; dy < 2; ++dy)
                        for (uint32_t dx = 0; dx < 2; ++dx)
                            taps[count++] = in + tap_index(2 * z + dz, src.depth()) * src.slice_pitch() +
                                            tap_index(2 * y + dy, src.height()) * src.row_pitch() +
                                            size_t{tap_index(2 * x + dx, src.width())} * texel_bytes;
                std::byte* const texel = out + z * dst.slice_pitch() + y * dst.row_pitch() + size_t{x} * texel_bytes;
                if (texel_bytes == 4) {
                    // The four bytes at once, the same operations (a conversion of x + 0.5 >= 0
                    // truncates as floor does).
                    Floats4 sum{0.0f, 0.0f, 0.0f, 0.0f};
                    for (unsigned t = 0; t < count; ++t) {
                        int32_t word;
                        std::memcpy(&word, taps[t], 4);
                        // (The bytes by a shift per lane: GCC widens a byte vector byte by byte.)
                        const Ints4 tap = (Ints4{word, word, word, word} >> Ints4{0, 8, 16, 24}) & 0xFF;
                        sum += __builtin_convertvector(tap, Floats4) / 255.0f;
                    }
                    Doubles4 scaled = __builtin_convertvector(sum * scale, Doubles4) * 255.0;
                    scaled = scaled > 255.0 ? Doubles4{255.0, 255.0, 255.0, 255.0} : scaled;
                    const Ints4 rounded = __builtin_convertvector(scaled + 0.5, Ints4) & stored_mask;
                    const Bytes4 bytes = __builtin_convertvector(rounded, Bytes4);
                    std::memcpy(texel, &bytes, 4);
                    continue;
                }
                for (unsigned b = 0; b < texel_bytes; ++b) {
                    float sum = 0.0f;
                    for (unsigned t = 0; t < count; ++t) sum += static_cast<float>(static_cast<uint8_t>(taps[t][b])) / 255.0f;
                    const double scaled = static_cast<double>(sum * scale) * 255.0;
                    const double clamped = scaled > 255.0 ? 255.0 : scaled;  // (never below 0, never NaN)
                    texel[b] = stored[b] ? static_cast<std::byte>(layout::round_to_uint(clamped)) : std::byte{0};
                }
            }
}

}  // namespace

void Texture::generate_mips() {
    // (Every refusal comes before the first write: Device::generate_mip_sub_levels() works in
    // place.)
    const FormatInfo* info = format_info(format_);
    if (info == nullptr || info->kind == FormatKind::Compressed) bad("mip generation needs an uncompressed format");
    const layout::Layout lay = layout::layout_of(format_);
    const bool bytes = lay.valid && layout::bytewise_unorm8(lay) && info->bytes <= 4;
    for (uint32_t f = 0; f < faces(); ++f) {
        for (uint32_t l = 1; l < levels_; ++l) {
            const Surface& src = surface(l - 1, f);
            Surface& dst = surface(l, f);
            if (bytes) {
                box_filter_bytes(lay, info->bytes, src, dst);
                continue;
            }
            for (uint32_t z = 0; z < dst.depth(); ++z)
                for (uint32_t y = 0; y < dst.height(); ++y)
                    for (uint32_t x = 0; x < dst.width(); ++x) {
                        Float4 sum{0, 0, 0, 0};
                        const uint32_t zn = src.depth() > 1 ? 2 : 1;
                        for (uint32_t dz = 0; dz < zn; ++dz)
                            for (uint32_t dy = 0; dy < 2; ++dy)
                                for (uint32_t dx = 0; dx < 2; ++dx) {
                                    const Float4 t = src.read(tap_index(2 * x + dx, src.width()),
                                                              tap_index(2 * y + dy, src.height()),
                                                              tap_index(2 * z + dz, src.depth()));
                                    for (unsigned c = 0; c < 4; ++c) sum[c] += t[c];
                                }
                        const float scale = 1.0f / static_cast<float>(4 * zn);
                        for (float& c : sum) c *= scale;
                        dst.write(x, y, z, sum);
                    }
        }
    }
}

}  // namespace sm2::runtime
