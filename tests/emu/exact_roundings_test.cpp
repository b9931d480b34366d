// Roundings that cannot change a value (exact_roundings.cpp): which steps lose theirs when a
// shader is lowered, and that random executables give the same bits in every register with and
// without them.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "emu/engine_test_support.h"
#include "emu/random_executables.h"
#include "emu/src/exact_roundings.h"

namespace sm2::test {
namespace {

using emu::ResultRounding;

// Every step's result feeds oC0, so none is dead code. c0.z = 0.1 has no fp24 or fp16
// encoding; 0.25, 2 and 0 have both.
constexpr std::string_view kSelections = R"(ps_2_0
def c0, 0.25, 2, 0.1, 0
dcl t0
mov r0, t0
max r1, r0, c0.x
min r2, r1, c0.z
abs r3, r2
cmp r4, t0, r1, c0.w
add r5, r3, r4
mov_pp r6, r5
mov r7, r6
mov_pp r8, r7
add r9, r8, r2
mov_pp r10, r1
add r11, r9, r10
mov oC0, r11
)";

std::string roundings(const emu::Executable& executable) {
    std::ostringstream out;
    for (const emu::Step& step : executable.steps())
        out << (step.dest.rounding == ResultRounding::Fp24   ? "24 "
                : step.dest.rounding == ResultRounding::Fp16 ? "16 "
                                                             : "- ");
    return out.str();
}

emu::Executable lower_selections(emu::PrecisionOptions precision) {
    emu::LoweringOptions options;
    options.precision = precision;
    return lower_or_fail(assemble_or_fail(kSelections), {}, options);
}

TEST(ExactRoundings, Fp24KeepsTheRoundingsOfNewValuesOnly) {
    // mov r0, t0 rounds the interpolated t0; max of r0 and 0.25 is one of two fp24 values; min
    // with 0.1 may be 0.1; abs, cmp's choice of r1 or 0, the _pp movs (fp24 like every step in
    // this mode) and the output's copy take fp24 values; add makes new ones.
    EXPECT_EQ(roundings(lower_selections({emu::Precision::Fp24})), "24 - 24 - - 24 - - - 24 - 24 - ");
}

TEST(ExactRoundings, Fp16KeepsTheHalfRoundingOfAnFp24Value) {
    // With _pp as s10e5: mov_pp r6, r5 rounds r5 (an fp24 value) to half; r6 is then a half,
    // which fp24 holds (mov r7) and which the next _pp copy keeps (mov_pp r8). r1, the max of
    // two fp24 values, is no half: mov_pp r10, r1 rounds.
    emu::PrecisionOptions fp16{emu::Precision::Fp24};
    fp16.partial_precision_fp16 = true;
    EXPECT_EQ(roundings(lower_selections(fp16)), "24 - 24 - - 24 16 - - 24 16 24 - ");
    // fp32 with _pp as s10e5: only the _pp steps round; mov r7 copies the half as it is.
    emu::PrecisionOptions pp_only;
    pp_only.partial_precision_fp16 = true;
    EXPECT_EQ(roundings(lower_selections(pp_only)), "- - - - - - 16 - - - 16 - - ");
}

TEST(ExactRoundings, Fp32HasNone) { EXPECT_EQ(roundings(lower_selections({})), "- - - - - - - - - - - - - "); }

// Half the component-wise steps turned into selections of the same arity (mov, abs, min, max,
// cmp), so that chains of them form: the generator picks them 5 times in 32.
std::vector<emu::Step> more_selections(std::span<const emu::Step> generated, random_executables::Random& random) {
    std::vector<emu::Step> steps(generated.begin(), generated.end());
    for (emu::Step& step : steps) {
        if (random_executables::chance(random, 50)) continue;
        switch (step.opcode) {
        case Opcode::Frc:
        case Opcode::Sgn: step.opcode = random_executables::chance(random, 50) ? Opcode::Mov : Opcode::Abs; break;
        case Opcode::Add:
        case Opcode::Sub:
        case Opcode::Mul:
        case Opcode::Slt:
        case Opcode::Sge: step.opcode = random_executables::chance(random, 50) ? Opcode::Min : Opcode::Max; break;
        case Opcode::Mad:
        case Opcode::Lrp: step.opcode = Opcode::Cmp; break;
        default: break;
        }
    }
    return steps;
}

// Random pixel executables with fp24 and fp16 roundings (and _pp steps among the fp24 ones),
// some constants def'd (special values, many of them fp24 or fp16 values, some not): the
// interpreter gives every register, a0 and the killed lanes the same bits with and without the
// roundings drop_exact_roundings() clears.
TEST(ExactRoundings, RandomExecutablesKeepTheirBits) {
    using namespace random_executables;
    Random random(20261205);
    unsigned dropped = 0, kept = 0;
    for (const Rounding rounding : {Rounding::Fp24, Rounding::Fp16})
        for (unsigned program = 0; program < 600; ++program) {
            const unsigned constant_count = 8 + pick(random, 24);
            ProgramGenerator generator(random, Mode{rounding, emu::Transcendentals::Exact}, constant_count);
            if (chance(random, 50)) generator.favour_uniform_steps();
            const emu::Executable random_steps = generator.generate(4 + pick(random, 40));
            const emu::Executable generated(random_steps.version(), random_steps.precision(), constant_count,
                                            more_selections(random_steps.steps(), random), {},
                                            random_steps.executed_instructions());
            emu::ConstantFile constants = random_constants(random, constant_count);
            std::vector<std::pair<unsigned, std::array<float, 4>>> defs;
            for (unsigned c = 0; c < constant_count; ++c)
                if (chance(random, 60)) defs.emplace_back(c, constants.registers[c]);
            std::vector<emu::Step> steps(generated.steps().begin(), generated.steps().end());
            emu::drop_exact_roundings(steps, defs);
            for (size_t i = 0; i < steps.size(); ++i)
                if (steps[i].dest.rounding != generated.steps()[i].dest.rounding) ++dropped;
                else if (steps[i].dest.rounding != ResultRounding::None) ++kept;
            const emu::Executable rewritten(generated.version(), generated.precision(), constant_count, steps, {},
                                            generated.executed_instructions());
            for (unsigned b = 0; b < 4; ++b) {
                auto input = std::make_unique<emu::Batch>();
                randomize(*input, random, constant_count);
                auto as_generated = std::make_unique<emu::Batch>(*input);
                auto as_rewritten = std::make_unique<emu::Batch>(*input);
                emu::execute(generated, constants, *as_generated);
                emu::execute(rewritten, constants, *as_rewritten);
                for (unsigned s = 0; s < emu::slot::kCount; ++s)
                    for (unsigned c = 0; c < 4; ++c)
                        for (unsigned l = 0; l < emu::kBatchLanes; ++l)
                            ASSERT_TRUE(same_bits(as_generated->registers[s][c][l], as_rewritten->registers[s][c][l]))
                                << "program " << program << " batch " << b << " slot " << s << " component " << c
                                << " lane " << l << ":\n"
                                << generated.describe();
                ASSERT_EQ(as_generated->address, as_rewritten->address);
                ASSERT_EQ(as_generated->killed, as_rewritten->killed);
            }
        }
    // Both kinds occur often enough to mean something.
    EXPECT_GT(dropped, 500u);
    EXPECT_GT(kept, 5000u);
    std::printf("roundings dropped %u, kept %u\n", dropped, kept);
}

}  // namespace
}  // namespace sm2::test
