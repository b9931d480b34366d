// Shared by the matrix macro suites: run "mNxM r0, c0, c1" with rows c1.. and return r0.
#pragma once

#include "emu/engine_test_support.h"

namespace sm2::test {

// Rows (1,2,3,4), (5,6,7,8), (9,10,11,12), (13,14,15,16).
inline std::vector<Float4> matrix_constants(Float4 vector) {
    return {vector, {1, 2, 3, 4}, {5, 6, 7, 8}, {9, 10, 11, 12}, {13, 14, 15, 16}};
}

}  // namespace sm2::test
