// Uniform steps (uniform_steps.cpp): the arithmetic on constants alone runs once per draw, in
// the executable's prelude, and its readers read a derived constant with the same bits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

using emu::OperandKind;

emu::Executable lower_text(std::string_view text, bool hoist, emu::PrecisionOptions precision = {},
                           bool keep_dead_code = false) {
    emu::LoweringOptions options;
    options.hoist_uniform_steps = hoist;
    options.keep_dead_code = keep_dead_code;
    options.precision = precision;
    return lower_or_fail(assemble_or_fail(text), {}, options);
}

// Inputs that differ lane by lane (t0, t1, v0, v1).
void vary_inputs(emu::Batch& batch, uint32_t seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<float> value(-3.0f, 3.0f);
    for (unsigned s : {emu::slot::kTexCoordFirst, emu::slot::kTexCoordFirst + 1, emu::slot::kInputFirst, emu::slot::kInputFirst + 1})
        for (auto& component : batch.registers[s])
            for (float& v : component) v = value(random);
}

// Runs both executables (each with its own bound constants) on the same varying inputs and
// compares every bit of every output slot.
void expect_same_outputs(const emu::Executable& plain, const emu::Executable& hoisted,
                         const std::vector<Float4>& application) {
    for (uint32_t seed = 1; seed <= 4; ++seed) {
        auto a = std::make_unique<emu::Batch>();
        vary_inputs(*a, seed);
        auto b = std::make_unique<emu::Batch>(*a);
        emu::execute(plain, plain.bind_constants(application), *a);
        emu::execute(hoisted, hoisted.bind_constants(application), *b);
        for (unsigned s = emu::slot::kPosition; s < emu::slot::kCount; ++s)
            for (unsigned c = 0; c < 4; ++c)
                for (unsigned l = 0; l < emu::kBatchLanes; ++l)
                    ASSERT_TRUE(same_bits(a->registers[s][c][l], b->registers[s][c][l]))
                        << "slot " << s << " component " << c << " lane " << l;
    }
}

// bench_1024's pixel shader normalizes the light's half vector from constants alone.
constexpr std::string_view kHalfVector = R"(ps_2_0
def c1, 0.5, 0.5, 1, 0
dcl t0
add r5.xyz, c0, c1
nrm r6.xyz, r5
dp3_sat r4.y, t0, r6
mul r0, r4.y, c2
mov oC0, r0
)";

TEST(UniformSteps, TheHalfVectorIsComputedOncePerDraw) {
    const emu::Executable plain = lower_text(kHalfVector, false);
    const emu::Executable hoisted = lower_text(kHalfVector, true);
    EXPECT_EQ(plain.steps().size(), 5u);
    ASSERT_EQ(hoisted.steps().size(), 3u) << hoisted.describe();
    EXPECT_EQ(hoisted.describe(), "dp3_sat r4.y, t0, c32\nmul r0, r4.yyyy, c2\nmov oC0, r0\n");
    ASSERT_EQ(hoisted.prelude().steps.size(), 2u);
    EXPECT_EQ(hoisted.prelude().steps[0].opcode, Opcode::Add);
    EXPECT_EQ(hoisted.prelude().steps[1].opcode, Opcode::Nrm);
    ASSERT_EQ(hoisted.prelude().snapshots.size(), 1u);
    EXPECT_EQ(hoisted.prelude().snapshots[0].slot, emu::slot::kTempFirst + 6);
    EXPECT_EQ(hoisted.prelude().snapshots[0].after, 2u);
    EXPECT_EQ(hoisted.application_constant_count(), 32u);
    EXPECT_EQ(hoisted.constant_count(), 33u);

    const std::vector<Float4> application = {{0.267f, 0.535f, 0.802f, 0.0f}, {}, {1.2f, 1.1f, 1.0f, 1.0f}};
    const emu::ConstantFile bound = hoisted.bind_constants(application);
    ASSERT_EQ(bound.registers.size(), 33u);
    // By hand: c0 + c1 = (0.767, 1.035, 1.802); its length sqrt(0.588289 + 1.071225 + 3.247204)
    // = sqrt(4.906718) = 2.2151113; the direction (0.3462580, 0.4672451, 0.8135031).
    EXPECT_NEAR(bound.registers[32][0], 0.3462580f, 2e-7f);
    EXPECT_NEAR(bound.registers[32][1], 0.4672451f, 2e-7f);
    EXPECT_NEAR(bound.registers[32][2], 0.8135031f, 2e-7f);
    // The same bits as every lane's r6 in the shader as written.
    const emu::Executable kept = lower_text(kHalfVector, false, {}, true);
    emu::Batch batch;
    vary_inputs(batch, 7);
    emu::execute(kept, kept.bind_constants(application), batch);
    for (unsigned c = 0; c < 3; ++c)
        for (unsigned l = 0; l < emu::kBatchLanes; ++l)
            EXPECT_TRUE(same_bits(batch.temp(6)[c][l], bound.registers[32][c])) << "component " << c;
    expect_same_outputs(plain, hoisted, application);
}

// A temporary written twice by uniform steps: each reader reads the value of its own point.
TEST(UniformSteps, EachReaderReadsTheValueOfItsPoint) {
    constexpr std::string_view text = R"(ps_2_0
dcl t0
dcl t1
mov r0, c0
mul r1, r0, t0
add r0, c1, c2
mad r1, r0, t1, r1
mov oC0, r1
)";
    const emu::Executable hoisted = lower_text(text, true);
    EXPECT_EQ(hoisted.describe(), "mul r1, c32, t0\nmad r1, c33, t1, r1\nmov oC0, r1\n");
    const std::vector<Float4> application = {{1.0f, 2.0f, 3.0f, 4.0f}, {0.5f, 0.25f, -1.0f, 8.0f}, {0.25f, 0.5f, 3.0f, -8.0f}};
    const emu::ConstantFile bound = hoisted.bind_constants(application);
    ASSERT_EQ(bound.registers.size(), 34u);
    EXPECT_EQ(bound.registers[32], (Float4{1.0f, 2.0f, 3.0f, 4.0f}));
    EXPECT_EQ(bound.registers[33], (Float4{0.75f, 0.75f, 2.0f, 0.0f}));
    expect_same_outputs(lower_text(text, false), hoisted, application);
}

// A lane value written into part of a temporary after a uniform step wrote all of it: the
// components left uniform are still read as a constant, a read of the whole register becomes a
// read of the lanes again (and keeps its uniform step).
TEST(UniformSteps, ALaneValueEndsTheUniformPartOnly) {
    constexpr std::string_view text = R"(ps_2_0
dcl t0
dcl t1
mov r0, c0
mul r1, r0, t0
mov r0.y, t0.x
mul r4, r0.x, t1
add r2, r0, t1
add r3, r1, r2
add r3, r3, r4
mov oC0, r3
)";
    const emu::Executable hoisted = lower_text(text, true);
    EXPECT_EQ(hoisted.describe(),
              "mov r0.xzw, c0\nmul r1, c32, t0\nmov r0.y, t0.xxxx\nmul r4, c32.xxxx, t1\nadd r2, r0, t1\n"
              "add r3, r1, r2\nadd r3, r3, r4\nmov oC0, r3\n");
    const std::vector<Float4> application = {{-2.0f, 5.0f, 0.0f, -0.0f}};
    expect_same_outputs(lower_text(text, false), hoisted, application);
}

bool has_opcode(std::span<const emu::Step> steps, Opcode opcode) {
    return std::any_of(steps.begin(), steps.end(), [&](const emu::Step& step) { return step.opcode == opcode; });
}

// dst reads a.yz and b.yw, lit x, y and w, crs x, y and z, nrm x, y, z and w only for a w
// result (lowering marks their sources read for all four channels): each is uniform when those
// components are, whatever the others hold, and not when one of them holds a lane value.
TEST(UniformSteps, DstLitCrsAndNrmNeedOnlyTheComponentsTheyRead) {
    constexpr std::string_view uniform = R"(vs_2_0
dcl_position v0
dcl_texcoord v1
mov r0, c0
mov r0.xw, v0
mov r1, c1
mov r1.xz, v1
dst r2, r0, r1
mov r3, c2
mov r3.z, v0.x
lit r4, r3
mov r5, c3
mov r5.w, v1.x
crs r6.xyz, r5, c4
nrm r7.xyz, r5
add r8, r2, r4
add r8.xyz, r8, r6
add r8.xyz, r8, r7
mov oPos, v0
mov oT0, r8
mad oT1, r0, r1, r5
add oT2, r3, v1
)";
    const std::vector<Float4> application = {{0.5f, -2.0f, 3.0f, 0.25f}, {1.5f, 4.0f, -1.0f, 2.0f},
                                             {0.75f, 0.5f, 9.0f, 20.0f}, {1.0f, -3.0f, 2.0f, 7.0f},
                                             {0.0f, 2.0f, -5.0f, 1.0f},  {3.0f, 1.0f, 0.5f, -1.0f}};
    const emu::Executable hoisted = lower_text(uniform, true);
    for (const Opcode opcode : {Opcode::Dst, Opcode::Lit, Opcode::Crs, Opcode::Nrm}) {
        EXPECT_FALSE(has_opcode(hoisted.steps(), opcode)) << hoisted.describe();
        EXPECT_TRUE(has_opcode(hoisted.prelude().steps, opcode));
    }
    expect_same_outputs(lower_text(uniform, false), hoisted, application);

    constexpr std::string_view lanes = R"(vs_2_0
dcl_position v0
dcl_texcoord v1
mov r0, c0
mov r0.xz, v0
mov r1, c1
mov r1.xw, v1
dst r2, r0, r1
mov r3, c2
mov r3.y, v0.x
lit r4, r3
mov r5, c3
mov r5.w, v1.x
nrm r7, r5
mov r6, c4
mov r6.z, v0.y
crs r8.xyz, r6, c5
mov oPos, v0
add oT0, r2, r4
mov oT1, r7
mov oT2.xyz, r8
)";
    const emu::Executable kept = lower_text(lanes, true);
    for (const Opcode opcode : {Opcode::Dst, Opcode::Lit, Opcode::Crs, Opcode::Nrm})
        EXPECT_TRUE(has_opcode(kept.steps(), opcode)) << kept.describe();
    expect_same_outputs(lower_text(lanes, false), kept, application);
}

// Special values reach the derived constant as the lanes would have computed them: the legacy
// 0 * inf = 0, rsq(0) = inf, NaN, in fp32 and in the fp24 and fp16 (_pp) modes, whose roundings
// the prelude applies as the per-lane steps do.
TEST(UniformSteps, SpecialValuesAndRoundingModesKeepTheirBits) {
    constexpr std::string_view text = R"(ps_2_0
dcl t0
mul r0, c0, c1
rsq r1.x, c0.x
rcp r1.y, c1.w
log r1.z, c0.w
add_pp r1.w, c1.x, c0.y
exp r2.x, c0.y
mad r2, r0, r1, r2.x
mul r3, r2, t0
mov oC0, r3
)";
    const std::vector<Float4> application = {{0.0f, 1e-3f, kInf, 3.3f}, {kInf, kNaN, 0.0f, -0.0f}};
    for (const emu::PrecisionOptions precision :
         {emu::PrecisionOptions{emu::Precision::Fp32, emu::Transcendentals::Exact, false},
          emu::PrecisionOptions{emu::Precision::Fp32, emu::Transcendentals::Fast, false},
          emu::PrecisionOptions{emu::Precision::Fp24, emu::Transcendentals::Exact, false},
          emu::PrecisionOptions{emu::Precision::Fp24, emu::Transcendentals::Exact, true}}) {
        const emu::Executable hoisted = lower_text(text, true, precision);
        ASSERT_EQ(hoisted.steps().size(), 2u) << hoisted.describe();
        EXPECT_EQ(hoisted.prelude().steps.size(), 7u);
        expect_same_outputs(lower_text(text, false, precision), hoisted, application);
    }
}

// Left as they are: fp64 (its temporaries are doubles), a shader that reads constants
// relatively (the derived registers would lie in its range), the debugger's lowering (every
// step kept), and a shader with nothing uniform.
TEST(UniformSteps, WhereNothingIsHoisted) {
    const emu::Executable fp64 = lower_text(kHalfVector, true, {emu::Precision::Fp64, emu::Transcendentals::Exact, false});
    EXPECT_TRUE(fp64.prelude().steps.empty());
    EXPECT_EQ(fp64.steps().size(), 5u);
    const emu::Executable debug = lower_text(kHalfVector, true, {}, true);
    EXPECT_TRUE(debug.prelude().snapshots.empty());
    constexpr std::string_view relative = R"(vs_2_0
dcl_position v0
mova a0.x, v0.x
add r0, c1, c2
mul r1, r0, c[a0.x + 3]
mov oPos, r1
)";
    emu::LoweringOptions options;
    options.hoist_uniform_steps = true;
    options.constant_count = 256;
    const emu::Executable with_relative = lower_or_fail(assemble_or_fail(relative), {}, options);
    EXPECT_TRUE(with_relative.prelude().snapshots.empty());
    EXPECT_EQ(with_relative.steps().size(), 4u);
    constexpr std::string_view lanes_only = R"(ps_2_0
dcl t0
mul r0, t0, c0
mov oC0, r0
)";
    const emu::Executable plain = lower_text(lanes_only, true);
    EXPECT_TRUE(plain.prelude().snapshots.empty());
    EXPECT_EQ(plain.constant_count(), 32u);
}

}  // namespace
}  // namespace sm2::test
