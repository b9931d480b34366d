// Loop and rep integer constants outside their documented ranges (instructions.md §12.1:
// count and start 0..255, step -128..127, w 0) are refused when the draw's pipeline is built,
// with a message naming the register and the component.
#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

const char* const kLoop = R"(
    vs_2_0
    dcl_position v0
    mov r0, v0
    loop aL, i3
    add r0, r0, c[aL]
    endloop
    mov oPos, r0
)";

const char* const kRep = R"(
    vs_2_0
    dcl_position v0
    mov r0, v0
    rep i3
    add r0, r0, c0
    endrep
    mov oPos, r0
)";

std::string error_with(const char* text, emu::Int4 value) {
    emu::StaticFlowConstants flow;
    flow.integers[3] = value;
    return lowering_error(assemble_or_fail(text), flow);
}

TEST(LoopConstants, OutOfRangeComponentsAreNamed) {
    EXPECT_NE(error_with(kLoop, {256, 0, 1, 0}).find("i3 = (256, 0, 1, 0): the iteration count (x) must be in 0..255"),
              std::string::npos);
    EXPECT_NE(error_with(kLoop, {-1, 0, 1, 0}).find("iteration count"), std::string::npos);
    EXPECT_NE(error_with(kLoop, {2, 256, 1, 0}).find("start value of aL (y)"), std::string::npos);
    EXPECT_NE(error_with(kLoop, {2, -1, 1, 0}).find("start value of aL (y)"), std::string::npos);
    EXPECT_NE(error_with(kLoop, {2, 0, 128, 0}).find("step of aL (z) must be in -128..127"), std::string::npos);
    EXPECT_NE(error_with(kLoop, {2, 0, -129, 0}).find("step of aL (z)"), std::string::npos);
    EXPECT_NE(error_with(kLoop, {2, 0, 1, 7}).find("unused component (w)"), std::string::npos);
    EXPECT_NE(error_with(kRep, {300, 0, 0, 0}).find("iteration count"), std::string::npos);
}

TEST(LoopConstants, TheRangeLimitsThemselvesAreAccepted) {
    // count 255, start 255 with step -128 stays a valid program: aL goes 255, 127, -1, ...
    // and reads outside c0..c255 give zero (instructions.md §9)
    EXPECT_EQ(error_with(kLoop, {255, 255, -128, 0}), "");
    EXPECT_EQ(error_with(kLoop, {0, 0, 127, 0}), "");
    // rep reads only x: y, z and w are unused
    EXPECT_EQ(error_with(kRep, {255, 999, 999, 999}), "");
}

}  // namespace
}  // namespace sm2::test
