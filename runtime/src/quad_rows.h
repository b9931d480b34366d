// A batch whose 4 quads lie side by side in one quad row, x0, x0 + 2, x0 + 4 and x0 + 6 at y0
// (interpolate()'s lane order: lane 4q + i at (x0 + 2q + (i & 1), y0 + (i >> 1))): its pixels are
// two runs of 8 in rows y0 and y0 + 1, which the output merger's and the depth test's block
// kernels read and write by row loads and stores instead of a gather and a scatter.
#pragma once

#include <array>
#include <cstdint>

#include <immintrin.h>

#include "sm2/emu/batch.h"

namespace sm2::runtime {

// kRowLane[r][c]: the lane of row r, column c.
constexpr std::array<std::array<unsigned, 8>, 2> kRowLane = {{{0, 1, 4, 5, 8, 9, 12, 13}, {2, 3, 6, 7, 10, 11, 14, 15}}};

// The bits of `lanes` of kRowLane[row], in its order: the row's lane pairs (bits 4j + 2 row and
// 4j + 2 row + 1) gathered into one byte by two shift-and-merge steps.
constexpr __mmask8 row_mask(emu::LaneMask lanes, unsigned row) {
    uint32_t m = (lanes >> (2 * row)) & 0x3333u;
    m = (m | m >> 2) & 0x0F0Fu;
    m = (m | m >> 4) & 0x00FFu;
    return static_cast<__mmask8>(m);
}
// Every pattern of a row's 8 lanes, placed by the table, with the other row's lanes all clear
// and all set: the row's byte comes back, whatever the other row holds.
constexpr bool row_masks_follow_the_table() {
    for (unsigned row = 0; row < 2; ++row)
        for (unsigned pattern = 0; pattern < 256; ++pattern) {
            unsigned lanes = 0, other = 0;
            for (unsigned c = 0; c < 8; ++c) {
                lanes |= (pattern >> c & 1u) << kRowLane[row][c];
                other |= 1u << kRowLane[1 - row][c];
            }
            if (row_mask(static_cast<emu::LaneMask>(lanes), row) != pattern ||
                row_mask(static_cast<emu::LaneMask>(lanes | other), row) != pattern)
                return false;
        }
    return true;
}
static_assert(row_masks_follow_the_table());

}  // namespace sm2::runtime
