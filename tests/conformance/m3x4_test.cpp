// m3x4 d, s0, s1: four dp3 rows (w of the vector and of the rows ignored).
#include <gtest/gtest.h>

#include "conformance/matrix_test_support.h"

namespace sm2::test {
namespace {

TEST(M3x4, FourDotProductsOfXyz) {
    // v = (1, 2, 3, 100): 1+4+9 = 14, 5+12+21 = 38, 9+20+33 = 62, 13+28+45 = 86
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::M3x4, rd(0), {c(0), c(1)}, matrix_constants({1, 2, 3, 100})), 14.0f, 38.0f, 62.0f, 86.0f);
}

TEST(M3x4, SwizzledVector) {
    // v.zyxw = (3, 2, 1, _): 3+4+3 = 10, 15+12+7 = 34, 27+20+11 = 58, 39+28+15 = 82
    EXPECT_FLOAT4_EQ(run_instruction(Opcode::M3x4, rd(0), {c(0).swz("zyxw"), c(1)}, matrix_constants({1, 2, 3, 100})), 10.0f, 34.0f, 58.0f, 82.0f);
}

}  // namespace
}  // namespace sm2::test
