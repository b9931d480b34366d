// Texture resources: 2D textures, cube textures (6 faces) and volume textures, each with a mip
// chain of Surfaces. Level k measures max(1, floor(size / 2^k)) in every dimension.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "sm2/runtime/formats.h"
#include "sm2/runtime/surface.h"

namespace sm2::runtime {

enum class TextureType : uint8_t { Texture2D, Cube, Volume };

// D3DCUBEMAP_FACES
enum class CubeFace : uint8_t { PositiveX = 0, NegativeX = 1, PositiveY = 2, NegativeY = 3, PositiveZ = 4, NegativeZ = 5 };

class Texture {
public:
    static constexpr uint32_t kMaxSize2D = 4096;      // 2D and cube: per side
    static constexpr uint32_t kMaxSizeVolume = 512;   // volume: per side

    // levels = 0: the full chain down to 1x1(x1) for power-of-two sizes; 1 for other sizes.
    // Throws std::invalid_argument for sizes out of range, a format that is not a texture format,
    // more levels than the chain has, more than one level on a non-power-of-two texture (D3D9's
    // conditional NONPOW2 support), or DXTn level-0 sizes that are not multiples of 4.
    static Texture create_2d(Format format, uint32_t width, uint32_t height, uint32_t levels = 0);
    static Texture create_cube(Format format, uint32_t size, uint32_t levels = 0);
    static Texture create_volume(Format format, uint32_t width, uint32_t height, uint32_t depth,
                                 uint32_t levels = 0);

    Texture() = default;

    [[nodiscard]] TextureType type() const { return type_; }
    [[nodiscard]] Format format() const { return format_; }
    [[nodiscard]] uint32_t width() const { return width_; }
    [[nodiscard]] uint32_t height() const { return height_; }
    [[nodiscard]] uint32_t depth() const { return depth_; }
    [[nodiscard]] uint32_t levels() const { return levels_; }
    [[nodiscard]] uint32_t faces() const { return type_ == TextureType::Cube ? 6u : 1u; }
    [[nodiscard]] uint32_t level_width(uint32_t level) const { return level_size(width_, level); }
    [[nodiscard]] uint32_t level_height(uint32_t level) const { return level_size(height_, level); }
    [[nodiscard]] uint32_t level_depth(uint32_t level) const { return level_size(depth_, level); }

    // Level `level` of face `face` (0 for 2D and volume textures); throws std::out_of_range.
    [[nodiscard]] Surface& surface(uint32_t level, uint32_t face = 0);
    [[nodiscard]] const Surface& surface(uint32_t level, uint32_t face = 0) const;

    // Fills levels 1.. from level 0 with a 2x2 (volumes: 2x2x2) box filter, per face, averaging
    // the decoded values in float and encoding them with the format's rounding. A dimension of
    // size 1 repeats its texel. Throws std::invalid_argument for DXTn (no encoder), before it
    // writes anything.
    void generate_mips();

    // A DXTn texture's texels decoded to A8R8G8B8, level for level and face for face (the
    // blocks decode to 8-bit RGBA: dxt.h), for the sampler's 16-lane path, which reads them in
    // place of the blocks. Made on first use and kept until a write access (the non-const
    // surface()) drops it: 8 (DXT1) or 4 times the blocks' memory while kept. Null for the
    // other formats, and where the copies alive would pass the process's budget for them
    // (set_decoded_dxt_budget(); 1 GiB unless set), which leaves the lookups to the sampler's
    // per-lane path. Thread-safe against itself and against surface().
    [[nodiscard]] std::shared_ptr<const Texture> decoded_dxt() const;
    // The most bytes all decoded_dxt() copies alive at once may hold; returns the previous one.
    static uint64_t set_decoded_dxt_budget(uint64_t bytes);

    [[nodiscard]] static uint32_t level_size(uint32_t size, uint32_t level) {
        return level >= 32 ? 1u : (size >> level) == 0 ? 1u : size >> level;
    }
    // Levels of the full chain for the largest dimension: floor(log2(max)) + 1.
    [[nodiscard]] static uint32_t full_chain(uint32_t width, uint32_t height, uint32_t depth = 1);

private:
    static Texture create(TextureType type, Format format, uint32_t width, uint32_t height,
                          uint32_t depth, uint32_t levels);

    TextureType type_ = TextureType::Texture2D;
    Format format_ = Format::Unknown;
    uint32_t width_ = 0, height_ = 0, depth_ = 0, levels_ = 0;
    std::vector<Surface> surfaces_;  // face-major: surfaces_[face * levels_ + level]
    mutable std::shared_ptr<const Texture> decoded_dxt_;  // decoded_dxt()'s copy while it holds
};

}  // namespace sm2::runtime
