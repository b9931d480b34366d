// Texture resources and box-filtered mip generation.
#include "sm2/runtime/texture.h"

#include <array>
#include <atomic>
#include <mutex>
#include <stdexcept>
#include <string>

#include "dxt.h"

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

void Texture::generate_mips() {
    const FormatInfo* info = format_info(format_);
    if (info == nullptr || info->kind == FormatKind::Compressed) bad("mip generation needs an uncompressed format");
    for (uint32_t f = 0; f < faces(); ++f) {
        for (uint32_t l = 1; l < levels_; ++l) {
            const Surface& src = surface(l - 1, f);
            Surface& dst = surface(l, f);
            auto src_index = [](uint32_t i, uint32_t size) { return i < size ? i : size - 1; };
            for (uint32_t z = 0; z < dst.depth(); ++z)
                for (uint32_t y = 0; y < dst.height(); ++y)
                    for (uint32_t x = 0; x < dst.width(); ++x) {
                        Float4 sum{0, 0, 0, 0};
                        const uint32_t zn = src.depth() > 1 ? 2 : 1;
                        for (uint32_t dz = 0; dz < zn; ++dz)
                            for (uint32_t dy = 0; dy < 2; ++dy)
                                for (uint32_t dx = 0; dx < 2; ++dx) {
                                    const Float4 t = src.read(src_index(2 * x + dx, src.width()),
                                                              src_index(2 * y + dy, src.height()),
                                                              src_index(2 * z + dz, src.depth()));
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
