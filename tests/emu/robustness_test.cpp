// Bad input never crashes: random programs (any opcode, any operand, any modifier) go through
// Shader::create, lower and execute; each stage either works or says why.
#include <gtest/gtest.h>

#include <random>

#include "emu/engine_test_support.h"

namespace sm2::test {
namespace {

isa::Program random_program(std::mt19937& random) {
    auto pick = [&](unsigned n) { return static_cast<unsigned>(random() % n); };
    const auto table = isa::opcode_table();
    isa::Program program;
    program.version = isa::ShaderVersion{pick(2) ? ShaderType::Vertex : ShaderType::Pixel, 2, 0};
    const unsigned count = 1 + pick(pick(4) ? 6 : 24);
    for (unsigned k = 0; k < count; ++k) {
        const isa::OpcodeInfo& row = table[pick(static_cast<unsigned>(table.size()))];
        isa::Instruction ins;
        ins.opcode = row.opcode;
        ins.control = row.control;
        if (row.has_dest() || pick(8) == 0) {
            isa::DestinationParameter d;
            d.type = static_cast<RegisterType>(pick(3) ? 0 : pick(4) ? pick(10) : pick(20));
            d.index = static_cast<uint16_t>(pick(4) ? pick(4) : pick(300));
            d.write_mask = static_cast<uint8_t>(pick(16));
            d.saturate = pick(2);
            d.partial_precision = pick(2);
            d.shift = pick(16) == 0 ? 1 : 0;
            ins.dest = d;
        }
        const unsigned sources = pick(6) == 0 ? pick(5) : row.num_sources;
        for (unsigned s = 0; s < sources; ++s) {
            isa::SourceParameter p;
            p.type = static_cast<RegisterType>(pick(4) ? pick(4) : pick(20));
            if (pick(5) == 0) p.type = row.sources[s % 4] == isa::SourceKind::Label ? RegisterType::Label : RegisterType::ConstBool;
            p.index = static_cast<uint16_t>(pick(3) ? pick(20) : pick(2048));
            p.swizzle = static_cast<uint8_t>(pick(256));
            p.modifier = static_cast<isa::SourceModifier>(pick(3) ? pick(2) : pick(14));
            if (pick(6) == 0)
                p.relative = isa::RelativeAddress{pick(2) ? RegisterType::Address : RegisterType::Loop,
                                                  static_cast<uint8_t>(pick(256))};
            ins.sources.push_back(p);
        }
        for (auto& bits : ins.constant_bits) bits = static_cast<uint32_t>(random());
        program.instructions.push_back(std::move(ins));
    }
    return program;
}

class AnyTexture : public emu::Sampler {
public:
    void sample(const emu::TextureRequest&, std::array<emu::FloatLanes, 4>& texels) override {
        for (auto& c : texels) c.fill(0.5f);
    }
};

TEST(Robustness, RandomProgramsNeverCrash) {
    std::mt19937 random(20261121);
    unsigned created = 0, lowered = 0;
    AnyTexture texture;
    for (int round = 0; round < 20000; ++round) {
        auto shader = emu::Shader::create(random_program(random));
        if (!shader.shader) {
            EXPECT_FALSE(shader.error.empty());
            continue;
        }
        ++created;
        emu::StaticFlowConstants flow;
        for (auto& b : flow.booleans) b = random() % 2;
        for (auto& i : flow.integers)
            for (auto& v : i) v = random() % 4 == 0 ? static_cast<int32_t>(random()) : static_cast<int32_t>(random() % 9) - 3;
        emu::LoweringOptions options;
        options.max_executed_instructions = 2000;
        options.keep_dead_code = random() % 2;
        options.precision.precision = static_cast<emu::Precision>(random() % 3);
        options.precision.partial_precision_fp16 = random() % 2;
        options.precision.transcendentals = static_cast<emu::Transcendentals>(random() % 2);
        auto result = emu::lower(*shader.shader, flow, options);
        if (!result.executable) {
            EXPECT_FALSE(result.error.empty());
            continue;
        }
        ++lowered;
        (void)result.executable->describe();
        std::vector<Float4> constants(300);
        for (auto& c : constants)
            for (auto& x : c) x = static_cast<float>(static_cast<int>(random() % 2001) - 1000) / 100.0f;
        const auto file = result.executable->bind_constants(constants);
        if (result.executable->precision() == emu::Precision::Fp64) {
            emu::ReferenceBatch batch;
            emu::execute(*result.executable, file, batch, random() % 2 ? &texture : nullptr);
        } else {
            emu::Batch batch;
            for (auto& reg : batch.registers)
                for (auto& lanes : reg)
                    for (auto& x : lanes) x = static_cast<float>(static_cast<int>(random() % 2001) - 1000) / 100.0f;
            emu::execute(*result.executable, file, batch, random() % 2 ? &texture : nullptr);
        }
    }
    // The generator must reach the later stages often enough to mean something.
    EXPECT_GT(created, 2000u);
    EXPECT_GT(lowered, 500u) << created;
}

TEST(Robustness, TooSmallConstantFileIsRefused) {
    ProgramBuilder p(ShaderType::Vertex);
    p.op(Opcode::Mov, oPos(), {c(100)});
    const auto exe = lower_or_fail(p.program());
    emu::Batch batch;
    EXPECT_THROW(emu::execute(exe, emu::ConstantFile{}, batch), std::invalid_argument);
}

TEST(Robustness, HugeLoopCountsAreRefused) {
    ProgramBuilder p(ShaderType::Vertex);
    p.flow(Opcode::Loop, {aL(), i(0)}).op(Opcode::Add, rd(0), {r(0), c(0).rel_aL()}).flow(Opcode::EndLoop)
        .op(Opcode::Mov, oPos(), {r(0)});
    emu::StaticFlowConstants flow;
    flow.integers[0] = {2147483647, 2147483647, 2147483647, 0};  // aL would overflow 32 bits
    EXPECT_NE(lowering_error(p.program(), flow).find("iteration count (x) must be in 0..255"), std::string::npos);
}

TEST(Robustness, ExecutedInstructionLimitStopsLowering) {
    ProgramBuilder p(ShaderType::Vertex);
    p.flow(Opcode::Loop, {aL(), i(0)}).op(Opcode::Add, rd(0), {r(0), c(0).rel_aL()}).flow(Opcode::EndLoop)
        .op(Opcode::Mov, oPos(), {r(0)});
    emu::StaticFlowConstants flow;
    flow.integers[0] = {100, 0, 1, 0};  // loop + 100 x (add + endloop) + mov = 202 executed
    emu::LoweringOptions options;
    options.max_executed_instructions = 150;
    EXPECT_NE(lowering_error(p.program(), flow, options).find("executed-instruction limit"), std::string::npos);
    options.max_executed_instructions = 202;
    EXPECT_EQ(lowering_error(p.program(), flow, options), "");
}

}  // namespace
}  // namespace sm2::test
