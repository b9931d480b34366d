// Validator tests: one or more programs per rule of registers-and-limits.md §10 that break it,
// valid programs that must pass (the worked examples of bytecode.md §13 and a few realistic
// shaders), budget edges, and hand-built odd Programs that must not crash the validator.
// Expected results are derived from the spec files, instruction by instruction.
#include <gtest/gtest.h>

#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "isa/program_builder.h"
#include "isa/worked_examples.h"
#include "sm2/isa/bytecode.h"
#include "sm2/isa/validator.h"

namespace sm2::isa {
namespace {

using builder::parse_program;

std::string dump(const std::vector<Violation>& violations) {
    std::ostringstream out;
    for (const Violation& v : violations) {
        out << "  [" << rule_name(v.rule) << "] #";
        if (v.instruction == SIZE_MAX) out << "-";
        else out << v.instruction;
        out << " line " << v.location.line << ": " << v.message << "\n";
    }
    return out.str();
}

std::vector<Violation> check(std::string_view text, const ValidationOptions& options = {}) {
    return validate(parse_program(text), options);
}

::testing::AssertionResult Clean(const std::vector<Violation>& violations) {
    if (violations.empty()) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "expected no violations, got:\n" << dump(violations);
}

bool matches(const Violation& v, Rule rule, size_t index, std::string_view text) {
    return v.rule == rule && v.instruction == index && v.message.find(text) != std::string::npos;
}

// The violations contain one with this rule, instruction index and message substring.
::testing::AssertionResult Has(const std::vector<Violation>& violations, Rule rule, size_t index,
                               std::string_view text) {
    for (const Violation& v : violations)
        if (matches(v, rule, index, text)) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure()
           << "no [" << rule_name(rule) << "] at #" << (index == SIZE_MAX ? std::string("-") : std::to_string(index))
           << " containing '" << text << "'; got:\n"
           << dump(violations);
}

// Exactly one violation, and it is this one.
::testing::AssertionResult Only(const std::vector<Violation>& violations, Rule rule, size_t index,
                                std::string_view text) {
    if (violations.size() == 1 && matches(violations[0], rule, index, text))
        return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure()
           << "expected only [" << rule_name(rule) << "] at #" << (index == SIZE_MAX ? std::string("-") : std::to_string(index))
           << " containing '" << text << "'; got:\n"
           << dump(violations);
}

std::string repeat(std::string_view line, int n) {
    std::string s;
    for (int i = 0; i < n; ++i) (s += line) += '\n';
    return s;
}

// D3DSINCOSCONST1/2 (bytecode.md §8) as raw bits for def.
constexpr const char* kSinCosDefs =
    "def c1, 0xB5D00D01, 0xB7B60B61, 0x3B2AAAAB, 0x39888889\n"
    "def c2, 0xBCAAAAAB, 0xBE000000, 0x3F800000, 0x3F000000\n";

// ===================================================================================
// Valid programs
// ===================================================================================

Program decode_or_die(const std::vector<uint32_t>& tokens) {
    DecodeResult r = decode(tokens);
    EXPECT_TRUE(r.ok()) << (r.error ? r.error->to_string() : "");
    return r.ok() ? *r.program : Program{};
}

// bytecode.md §13, Example A: ps_2_0 with texld/texldp_pp, mul_pp, lrp_sat. All of it is
// documented as valid: _sat on lrp and _pp on texldp are allowed (§7), c0.x is a whitelisted
// replicate swizzle, t0.xy covers the 2D lookup, the cube lookup through t1 reads .xyzw (texldp).
TEST(ValidatorExamples, ExampleA) {
    const Program p = decode_or_die(examples::kExampleA);
    EXPECT_TRUE(Clean(validate(p)));
}

// Example B: vs_2_0 with m4x4, mova + c[a0.x + 5], sincos with the documented constants, oFog.
TEST(ValidatorExamples, ExampleB) {
    const Program p = decode_or_die(examples::kExampleB);
    EXPECT_TRUE(Clean(validate(p)));
}

// Example C: vs_2_0 loop/aL, if, call/label/ret.
TEST(ValidatorExamples, ExampleC) {
    const Program p = decode_or_die(examples::kExampleC);
    EXPECT_TRUE(Clean(validate(p)));
}

TEST(ValidatorValid, VertexTransformAndLightingWithLoop) {
    EXPECT_TRUE(Clean(check(R"(
        vs_2_0
        dcl_position v0
        dcl_normal v1
        dcl_texcoord0 v2
        defi i0, 3, 16, 2, 0
        def c15, 0, 0, 0, 1
        m4x4 oPos, v0, c0
        m3x3 r0.xyz, v1, c4
        nrm r1.xyz, r0
        mov r2, c15
        loop aL, i0
        dp3 r3.x, r1, c[aL]
        max r3.x, r3.x, c15.x
        mad r2.xyz, r3.x, c[aL + 1], r2
        endloop
        mov oD0, r2
        mov oT0.xy, v2
    )")));
}

// if/else writing on both arms, callnz into a subroutine that reads what the caller wrote,
// mova with two components, lit, sgn, expp/logp, oFog/oPts.
TEST(ValidatorValid, VertexFlowControlAndSpecialInstructions) {
    EXPECT_TRUE(Clean(check(R"(
        vs_2_0
        dcl_position v0
        dcl_texcoord0 v1
        defb b0, true
        def c20, 1, 0.5, 0, 8
        mov r0, v0
        if b0
        mov r1, c20
        else
        mov r1, -c20.wzyx
        endif
        mova a0.xy, v1
        add r2, r1, c[a0.y + 10]
        callnz l2, !b0
        lit r3, r2
        sgn r4, r3, r5, r6
        expp r4.w, r2.x
        logp r4.z, r2.y
        mov oFog, r4.w
        mov oPts, c20.y
        mov oD0, r4
        m4x4 oPos, r0, c0
        ret
        label l2
        mul r2, r2, c[a0.x]
        ret
    )")));
}

TEST(ValidatorValid, PixelShaderWithEveryClass) {
    EXPECT_TRUE(Clean(check(std::string(R"(
        ps_2_0
        dcl t0.xy
        dcl t1.xyz
        dcl_pp v0
        dcl_2d s0
        dcl_cube s1
        def c0, 0.5, 0.5, 0.5, 1
    )") + kSinCosDefs + R"(
        texld r0, t0, s0
        dp3 r1.x, t1, t1
        rsq r1.x, r1.x
        mul r1.xyz, t1, r1.x
        texld_pp r2, r1, s1
        mad_sat r3, r0, v0, -r2
        cmp r3, r3, r3.yzxw, c0
        dp2add r4.x, r0, c0, c0.w
        sincos r5.xy, r4.x, c1, c2
        crs r6.xyz, r3, r1
        nrm r7, r3
        pow r8.x, r5.y, c0.x
        abs r8.y, r5.x
        frc r8.z, r0.w
        mov r8.w, c0.w
        texkill r3
        m3x2 r9.xy, r3, c0
        mov oC0, r3
        mov oC1, r8
        mov oDepth, r4.x
    )")));
}

// Comment instructions are skipped everywhere (indices still count them).
TEST(ValidatorValid, CommentsAreSkipped) {
    EXPECT_TRUE(Clean(check(R"(
        ps_2_0
        #comment
        dcl t0
        #comment
        dcl_2d s0
        texld r0, t0, s0
        #comment
        mov oC0, r0
    )")));
}

// ===================================================================================
// No profile; rule names
// ===================================================================================

TEST(Validator, NoProfileIsOneViolation) {
    Program p;
    p.version = {ShaderType::Vertex, 3, 0};
    p.instructions.resize(3);  // nops: never looked at
    const auto v = validate(p);
    ASSERT_EQ(v.size(), 1u) << dump(v);
    EXPECT_EQ(v[0].rule, Rule::Structure);
    EXPECT_EQ(v[0].instruction, SIZE_MAX);
    EXPECT_NE(v[0].message.find("vs_3_0"), std::string::npos);
}

TEST(Validator, RuleNames) {
    EXPECT_EQ(rule_name(Rule::Structure), "structure");
    EXPECT_EQ(rule_name(Rule::OpcodeVersion), "opcode-version");
    EXPECT_EQ(rule_name(Rule::Operands), "operands");
    EXPECT_EQ(rule_name(Rule::SetupFirst), "setup-first");
    EXPECT_EQ(rule_name(Rule::InputDeclared), "input-declared");
    EXPECT_EQ(rule_name(Rule::SamplerDeclared), "sampler-declared");
    EXPECT_EQ(rule_name(Rule::TempInitialized), "temp-initialized");
    EXPECT_EQ(rule_name(Rule::AddressRegister), "address-register");
    EXPECT_EQ(rule_name(Rule::RelativeAddressing), "relative-addressing");
    EXPECT_EQ(rule_name(Rule::SourceModifiers), "source-modifiers");
    EXPECT_EQ(rule_name(Rule::DestModifiers), "dest-modifiers");
    EXPECT_EQ(rule_name(Rule::Swizzle), "swizzle");
    EXPECT_EQ(rule_name(Rule::WriteMask), "write-mask");
    EXPECT_EQ(rule_name(Rule::ReadPorts), "read-ports");
    EXPECT_EQ(rule_name(Rule::InstructionOperands), "instruction-operands");
    EXPECT_EQ(rule_name(Rule::SlotBudget), "slot-budget");
    EXPECT_EQ(rule_name(Rule::DependentReads), "dependent-reads");
    EXPECT_EQ(rule_name(Rule::FlowControl), "flow-control");
    EXPECT_EQ(rule_name(Rule::Outputs), "outputs");
}

TEST(Validator, ViolationCarriesLocationAndMnemonic) {
    const auto v = check("ps_2_0\n\ndcl t0\ndcl_2d s0\ntexld oC0, t0, s0\nmov oC0, r0\n");
    ASSERT_TRUE(Has(v, Rule::Operands, 2, "texld: destination must be a temporary register r#, got oC0"));
    for (const Violation& x : v) {
        if (x.instruction == 2) {
            EXPECT_EQ(x.location.line, 5u);
        }
    }
}

// ===================================================================================
// Rule 2: opcode allowed in the version
// ===================================================================================

TEST(ValidatorRule2, VertexOnlyOpcodeInPixelShader) {
    EXPECT_TRUE(Has(check(R"(
        ps_2_0
        def c0, 1, 1, 1, 1
        sge r0, c0, c0
        mov oC0, c0
    )"), Rule::OpcodeVersion, 1, "sge: not available in ps_2_0"));
}

TEST(ValidatorRule2, PixelOnlyOpcodeInVertexShader) {
    EXPECT_TRUE(Has(check(R"(
        vs_2_0
        dcl_position v0
        cmp r0, v0, v0, v0
        mov oPos, v0
    )"), Rule::OpcodeVersion, 1, "cmp: not available in vs_2_0"));
}

TEST(ValidatorRule2, FlowControlAndIntegerDefsInPixelShader) {
    const auto v = check(R"(
        ps_2_0
        defi i0, 1, 0, 0, 0
        def c0, 1, 1, 1, 1
        rep i0
        endrep
        mov oC0, c0
    )");
    EXPECT_TRUE(Has(v, Rule::OpcodeVersion, 0, "defi: not available in ps_2_0"));
    EXPECT_TRUE(Has(v, Rule::OpcodeVersion, 2, "rep: not available in ps_2_0"));
    EXPECT_TRUE(Has(v, Rule::OpcodeVersion, 3, "endrep: not available in ps_2_0"));
}

TEST(ValidatorRule2, UnknownOpcode) {
    Program p = parse_program("ps_2_0\ndef c0, 1, 1, 1, 1\nmov oC0, c0\n");
    Instruction odd;
    odd.opcode = static_cast<Opcode>(0x77);
    p.instructions.insert(p.instructions.begin() + 1, odd);
    EXPECT_TRUE(Only(validate(p), Rule::OpcodeVersion, 1, "unknown opcode"));
}

// ===================================================================================
// Rule 3: operand count, register kinds, register ranges
// ===================================================================================

TEST(ValidatorRule3, TempOutOfRangeInPixelShader) {
    // ps_2_0 has r0..r11 (Wine encodes up to r31: RegisterFile::encodable, not count).
    EXPECT_TRUE(Only(check(R"(
        ps_2_0
        def c0, 1, 1, 1, 1
        mov r12, c0
        mov oC0, c0
    )"), Rule::Operands, 1, "r12 is out of range (r0..r11 in ps_2_0)"));
}

TEST(ValidatorRule3, IntegerAndBoolRegistersDoNotExistInPixelShader) {
    const auto v = check(R"(
        ps_2_0
        def c0, 1, 1, 1, 1
        mov r0, i0
        mov r1, b0
        mov oC0, c0
    )");
    EXPECT_TRUE(Has(v, Rule::Operands, 1, "i# registers do not exist in ps_2_0"));
    EXPECT_TRUE(Has(v, Rule::Operands, 2, "b# registers do not exist in ps_2_0"));
}

TEST(ValidatorRule3, ConstantAndInputRanges) {
    const auto v = check(R"(
        vs_2_0
        dcl_position v0
        mov r0, c256
        m4x4 oPos, v0, c254
    )");
    EXPECT_TRUE(Has(v, Rule::Operands, 1, "c256 is out of range (c0..c255 in vs_2_0)"));
    EXPECT_TRUE(Has(v, Rule::Operands, 2, "matrix rows c254..c257 run past the end"));
    EXPECT_TRUE(Has(check("ps_2_0\ndcl v2\nmov oC0, v2\n"), Rule::Operands, 0, "v2 is out of range"));
}

TEST(ValidatorRule3, WrongRegisterKinds) {
    const auto v = check(R"(
        vs_2_0
        dcl_position v0
        mov a0.x, v0
        mov r0, oPos
        add r1, v0, i0
        m4x4 oPos, v0, c0
    )");
    EXPECT_TRUE(Has(v, Rule::Operands, 1, "mov: destination must be a writable register"));
    EXPECT_TRUE(Has(v, Rule::Operands, 1, "a0 is written only by mova"));
    EXPECT_TRUE(Has(v, Rule::Operands, 2, "source 0 must be a value register"));
    EXPECT_TRUE(Has(v, Rule::Operands, 3, "source 1 must be a value register (r#, v#, c#, t#), got i0"));

    const auto p = check(R"(
        ps_2_0
        dcl t0
        dcl_2d s0
        texld oC0, t0, s0
        texld r0, t0, c0
        texkill c0
        mov oC0, t0
    )");
    EXPECT_TRUE(Has(p, Rule::Operands, 2, "texld: destination must be a temporary register r#, got oC0"));
    EXPECT_TRUE(Has(p, Rule::Operands, 3, "source 1 must be a sampler s#, got c0"));
    EXPECT_TRUE(Has(p, Rule::Operands, 4, "texkill: destination must be a texture coordinate t# or a temporary r#, got c0"));
}

TEST(ValidatorRule3, DeclarationsAndDefinitionsOfWrongRegisters) {
    const auto v = check(R"(
        vs_2_0
        dcl_position r0
        def i0, 1, 1, 1, 1
        dcl_position v0
        mov oPos, v0
    )");
    EXPECT_TRUE(Has(v, Rule::Operands, 0, "r0 cannot be declared in vs_2_0"));
    EXPECT_TRUE(Has(v, Rule::Operands, 1, "def: cannot define i0"));
}

TEST(ValidatorRule3, LabelOutOfRange) {
    EXPECT_TRUE(Has(check(R"(
        vs_2_0
        dcl_position v0
        call l16
        mov oPos, v0
        ret
        label l16
        ret
    )"), Rule::Operands, 1, "l16 is out of range (l0..l15 in vs_2_0)"));
}

TEST(ValidatorRule3, HandBuiltShapes) {
    Program p = parse_program(R"(
        vs_2_0
        dcl_position v0
        add r0, v0, v0
        add r1, v0, v0
        mov oPos, v0
        nop
    )");
    p.instructions[1].dest.reset();                 // missing destination
    p.instructions[2].sources.pop_back();           // too few sources
    p.instructions[4].dest = DestinationParameter{};  // nop takes none
    const auto v = validate(p);
    EXPECT_TRUE(Has(v, Rule::Operands, 1, "add: missing destination"));
    EXPECT_TRUE(Has(v, Rule::Operands, 2, "add: has 1 source(s), needs 2"));
    EXPECT_TRUE(Has(v, Rule::Operands, 4, "nop: takes no destination"));
    EXPECT_EQ(v.size(), 3u) << dump(v);
}

TEST(ValidatorRule3, PredicationDoesNotExistInVs20) {
    Program p = parse_program("vs_2_0\ndcl_position v0\nmov oPos, v0\n");
    p.instructions[1].predicate = SourceParameter{RegisterType::Predicate, 0, kSwizzleIdentity,
                                                  SourceModifier::None, std::nullopt};
    EXPECT_TRUE(Only(validate(p), Rule::Operands, 1, "predication is not available in vs_2_0"));
}

// ===================================================================================
// Rule 4: dcl/def before the first executable instruction
// ===================================================================================

TEST(ValidatorRule4, DefinitionAfterAnInstruction) {
    EXPECT_TRUE(Only(check(R"(
        ps_2_0
        def c0, 1, 1, 1, 1
        mov r0, c0
        def c1, 0, 0, 0, 0
        mov oC0, r0
    )"), Rule::SetupFirst, 2, "def: declarations and definitions must come before the first instruction (mov at 1)"));
}

TEST(ValidatorRule4, DeclarationAfterAnInstruction) {
    EXPECT_TRUE(Has(check(R"(
        vs_2_0
        dcl_position v0
        mov oPos, v0
        dcl_normal v1
    )"), Rule::SetupFirst, 2, "dcl: declarations"));
}

// ===================================================================================
// Rule 5: inputs declared, components declared
// ===================================================================================

TEST(ValidatorRule5, VertexInputNotDeclared) {
    EXPECT_TRUE(Only(check(R"(
        vs_2_0
        dcl_position v0
        add r0, v1, c0
        mov oPos, v0
    )"), Rule::InputDeclared, 1, "add: v1 is read but not declared"));
}

TEST(ValidatorRule5, PixelComponentsNotDeclared) {
    // mov reads all four components of t0; only .xy is declared.
    EXPECT_TRUE(Only(check(R"(
        ps_2_0
        dcl t0.xy
        mov oC0, t0
    )"), Rule::InputDeclared, 1, "mov: reads t0.zw but the dcl declares only .xy"));
    // A swizzle decides the components read: t0.x replicated reads only x.
    EXPECT_TRUE(Clean(check("ps_2_0\ndcl t0.xy\nmov r0, t0.x\nmov oC0, r0\n")));
    // A cube lookup reads .xyz of its coordinate.
    EXPECT_TRUE(Only(check(R"(
        ps_2_0
        dcl t0.xy
        dcl_cube s0
        texld r0, t0, s0
        mov oC0, r0
    )"), Rule::InputDeclared, 2, "texld: reads t0.z but the dcl declares only .xy"));
    // texkill reads all four components of its register.
    EXPECT_TRUE(Has(check(R"(
        ps_2_0
        dcl t0.xyz
        def c0, 0, 0, 0, 0
        texkill t0
        mov oC0, c0
    )"), Rule::InputDeclared, 2, "texkill: reads t0.w"));
    EXPECT_TRUE(Only(check(R"(
        ps_2_0
        def c0, 0, 0, 0, 0
        add r0, v0, c0
        mov oC0, r0
    )"), Rule::InputDeclared, 1, "add: v0 is read but not declared"));
}

TEST(ValidatorRule5, DuplicateDeclarations) {
    const auto v = check(R"(
        vs_2_0
        dcl_position v0
        dcl_texcoord0 v1
        dcl_texcoord0 v2
        dcl_normal v0
        mov oPos, v0
    )");
    EXPECT_TRUE(Has(v, Rule::InputDeclared, 2, "dcl: usage 5 index 0 is already declared at instruction 1"));
    EXPECT_TRUE(Has(v, Rule::InputDeclared, 3, "dcl: v0 is declared twice"));
}

TEST(ValidatorRule5, PixelInputTakesNoUsage) {
    EXPECT_TRUE(Has(check(R"(
        ps_2_0
        dcl_texcoord0 t0
        mov oC0, t0
    )"), Rule::InputDeclared, 0, "ps_2_0 input declarations take no usage"));
}

// ===================================================================================
// Rule 6: samplers declared with a known type
// ===================================================================================

TEST(ValidatorRule6, SamplerNotDeclared) {
    EXPECT_TRUE(Only(check(R"(
        ps_2_0
        dcl t0
        dcl_2d s0
        texld r0, t0, s1
        mov oC0, r0
    )"), Rule::SamplerDeclared, 2, "texld: sampler s1 is not declared"));
}

TEST(ValidatorRule6, SamplerTypeUnknownOr1D) {
    const auto v = check(R"(
        ps_2_0
        dcl t0
        dcl s0
        dcl_1d s1
        dcl_2d s1
        texld r0, t0, s0
        mov oC0, r0
    )");
    EXPECT_TRUE(Has(v, Rule::SamplerDeclared, 1, "dcl: s0 needs a known texture type"));
    EXPECT_TRUE(Has(v, Rule::SamplerDeclared, 2, "dcl: s1 needs a known texture type"));
    EXPECT_TRUE(Has(v, Rule::SamplerDeclared, 3, "dcl: s1 is declared twice"));
    EXPECT_EQ(v.size(), 3u) << dump(v);
}

// ===================================================================================
// Rule 7: temps written before read (per component, along every static path)
// ===================================================================================

TEST(ValidatorRule7, ReadBeforeWrite) {
    EXPECT_TRUE(Only(check(R"(
        ps_2_0
        def c0, 1, 1, 1, 1
        add r0, r1, c0
        mov oC0, r0
    )"), Rule::TempInitialized, 1, "add: reads r1.xyzw before it is written"));
}

TEST(ValidatorRule7, PerComponent) {
    EXPECT_TRUE(Only(check(R"(
        ps_2_0
        def c0, 1, 1, 1, 1
        mov r0.xy, c0
        mov r1, r0
        mov oC0, r1
    )"), Rule::TempInitialized, 2, "mov: reads r0.zw before"));
    // With a mask, only the components feeding it are read.
    EXPECT_TRUE(Clean(check(R"(
        ps_2_0
        def c0, 1, 1, 1, 1
        mov r0.xy, c0
        mov r1, c0
        mov r1.xy, r0
        add r1.w, r0.y, c0
        mov oC0, r1
    )")));
}

TEST(ValidatorRule7, TexldCoordinateTemp) {
    // A 2D lookup reads .xy of an r# coordinate: .xy written is enough.
    EXPECT_TRUE(Clean(check(R"(
        ps_2_0
        dcl_2d s0
        def c0, 0.5, 0.5, 0, 0
        mov r0.xy, c0
        texld r1, r0, s0
        mov oC0, r1
    )")));
    // texldp also reads .w.
    EXPECT_TRUE(Only(check(R"(
        ps_2_0
        dcl_2d s0
        def c0, 0.5, 0.5, 0, 0
        mov r0.xy, c0
        texldp r1, r0, s0
        mov oC0, r1
    )"), Rule::TempInitialized, 3, "texldp: reads r0.w before"));
}

TEST(ValidatorRule7, IfElseIsAnIntersection) {
    // Written on one arm only: not written after endif.
    EXPECT_TRUE(Only(check(R"(
        vs_2_0
        dcl_position v0
        if b0
        mov r0, v0
        else
        mov r1, v0
        endif
        mov oPos, r0
    )"), Rule::TempInitialized, 6, "mov: reads r0.xyzw"));
    // Written on both arms: fine.
    EXPECT_TRUE(Clean(check(R"(
        vs_2_0
        dcl_position v0
        if b0
        mov r0, v0
        else
        mov r0, -v0
        endif
        mov oPos, r0
    )")));
    // if without else: the empty arm writes nothing.
    EXPECT_TRUE(Only(check(R"(
        vs_2_0
        dcl_position v0
        if !b1
        mov r0, v0
        endif
        mov oPos, r0
    )"), Rule::TempInitialized, 4, "mov: reads r0"));
}

TEST(ValidatorRule7, LoopBodyMayRunZeroTimes) {
    EXPECT_TRUE(Only(check(R"(
        vs_2_0
        dcl_position v0
        rep i0
        mov r0, v0
        endrep
        mov oPos, r0
    )"), Rule::TempInitialized, 4, "mov: reads r0"));
    // The first iteration reads a temp the body writes only later.
    EXPECT_TRUE(Only(check(R"(
        vs_2_0
        dcl_position v0
        mov r0, v0
        rep i0
        add r0, r0, r1
        mov r1, v0
        endrep
        mov oPos, r0
    )"), Rule::TempInitialized, 3, "add: reads r1"));
}

TEST(ValidatorRule7, SubroutinesAreAnalysedAtTheirCallSites) {
    // call: what the routine writes is written after the call.
    EXPECT_TRUE(Clean(check(R"(
        vs_2_0
        dcl_position v0
        call l0
        mov oPos, r0
        ret
        label l0
        mov r0, v0
        ret
    )")));
    // callnz may not call: not written afterwards.
    EXPECT_TRUE(Only(check(R"(
        vs_2_0
        dcl_position v0
        callnz l0, b0
        mov oPos, r0
        ret
        label l0
        mov r0, v0
        ret
    )"), Rule::TempInitialized, 2, "mov: reads r0"));
    // The routine reads r1, which the (only) call site has not written: reported inside it.
    EXPECT_TRUE(Only(check(R"(
        vs_2_0
        dcl_position v0
        mov r0, v0
        call l3
        mov oPos, r0
        ret
        label l3
        add r0, r0, r1
        ret
    )"), Rule::TempInitialized, 6, "add: reads r1.xyzw before it is written on every path (in a subroutine called at 2)"));
    // Two call sites that both leave r1 unwritten: still one finding.
    EXPECT_TRUE(Only(check(R"(
        vs_2_0
        dcl_position v0
        mov r0, v0
        call l3
        call l3
        mov oPos, r0
        ret
        label l3
        add r0, r0, r1
        ret
    )"), Rule::TempInitialized, 7, "(in a subroutine called at 2)"));
    // Only the first call site leaves r1 unwritten: reported once, naming it.
    EXPECT_TRUE(Only(check(R"(
        vs_2_0
        dcl_position v0
        mov r0, v0
        call l3
        mov r1, v0
        call l3
        mov oPos, r0
        ret
        label l3
        add r0, r0, r1
        ret
    )"), Rule::TempInitialized, 8, "reads r1.xyzw before it is written on every path (in a subroutine called at 2)"));
}

// ===================================================================================
// Rule 8: a0 written by mova before use; aL only inside loops
// ===================================================================================

TEST(ValidatorRule8, AddressComponentNotWritten) {
    EXPECT_TRUE(Only(check(R"(
        vs_2_0
        dcl_position v0
        mova a0.x, v0
        add r0, v0, c[a0.y + 4]
        mov oPos, r0
    )"), Rule::AddressRegister, 2, "add: a0.y is used as an index before mova writes it"));
    EXPECT_TRUE(Only(check(R"(
        vs_2_0
        dcl_position v0
        mov oPos, c[a0.x]
    )"), Rule::AddressRegister, 1, "mov: a0.x is used"));
}

TEST(ValidatorRule8, LoopCounterOutsideLoop) {
    EXPECT_TRUE(Only(check(R"(
        vs_2_0
        dcl_position v0
        add r0, v0, c[aL]
        mov oPos, r0
    )"), Rule::AddressRegister, 1, "add: aL is used outside a loop"));
    // rep does not set aL.
    EXPECT_TRUE(Only(check(R"(
        vs_2_0
        dcl_position v0
        mov r0, v0
        rep i0
        add r0, r0, c[aL]
        endrep
        mov oPos, r0
    )"), Rule::AddressRegister, 3, "add: aL is used outside a loop"));
}

TEST(ValidatorRule8, LoopCounterInSubroutines) {
    // Called only from inside a loop: the caller's aL.
    EXPECT_TRUE(Clean(check(R"(
        vs_2_0
        dcl_position v0
        mov r0, v0
        loop aL, i0
        call l1
        endloop
        mov oPos, r0
        ret
        label l1
        add r0, r0, c[aL + 2]
        ret
    )")));
    // Also called from outside a loop: invalid.
    EXPECT_TRUE(Only(check(R"(
        vs_2_0
        dcl_position v0
        mov r0, v0
        loop aL, i0
        call l1
        endloop
        call l1
        mov oPos, r0
        ret
        label l1
        add r0, r0, c[aL + 2]
        ret
    )"), Rule::AddressRegister, 9, "add: aL is used outside a loop (in a subroutine called at 5)"));
}

// ===================================================================================
// Rule 9: relative addressing
// ===================================================================================

TEST(ValidatorRule9, NotInPixelShaders) {
    Program p = parse_program("ps_2_0\ndef c0, 1, 1, 1, 1\nmov oC0, c0\n");
    p.instructions[1].sources[0].relative = RelativeAddress{RegisterType::Address, 0x00};
    EXPECT_TRUE(Only(validate(p), Rule::RelativeAddressing, 1,
                     "mov: relative addressing is not available in ps_2_0"));
}

TEST(ValidatorRule9, OnlyOnConstants) {
    EXPECT_TRUE(Has(check(R"(
        vs_2_0
        dcl_position v0
        mova a0.x, v0
        mov oPos, v0[a0.x]
    )"), Rule::RelativeAddressing, 2, "mov: relative addressing is only allowed on constant registers c#, got v0[...]"));
}

TEST(ValidatorRule9, IndexMustBeOneComponentOfA0OrAL) {
    const auto v = check(R"(
        vs_2_0
        dcl_position v0
        mova a0, v0
        add r0, v0, c[a0 + 3]
        add r1, r0, c[r0 + 3]
        mov oPos, r1
    )");
    EXPECT_TRUE(Has(v, Rule::RelativeAddressing, 2, "the index a0 must name one component"));
    EXPECT_TRUE(Has(v, Rule::RelativeAddressing, 3, "must be a0.c or aL, got r0"));
}

// ===================================================================================
// Rule 10: source modifiers
// ===================================================================================

TEST(ValidatorRule10, OnlyNegate) {
    EXPECT_TRUE(Only(check(R"(
        vs_2_0
        dcl_position v0
        add r0, v0_abs, c0
        mov oPos, r0
    )"), Rule::SourceModifiers, 1, "add: source modifier _abs on source 0 (v0) is not available in vs_2_0 (only negate)"));
    EXPECT_TRUE(Has(check(R"(
        ps_2_0
        dcl t0
        add r0, t0_bx2, 1-t0
        mov oC0, r0
    )"), Rule::SourceModifiers, 1, "_bx2"));
}

TEST(ValidatorRule10, NoNegateOnMatrixOrTextureOperandsOrColorOutputs) {
    EXPECT_TRUE(Only(check(R"(
        vs_2_0
        dcl_position v0
        m4x4 oPos, -v0, -c0
    )"), Rule::SourceModifiers, 1, "m4x4: the matrix source (source 1) cannot be negated"));
    const auto v = check(R"(
        ps_2_0
        dcl t0
        dcl_2d s0
        texld r0, -t0, s0
        mov oC0, -r0
    )");
    EXPECT_TRUE(Has(v, Rule::SourceModifiers, 2, "texld: texture instruction operands take no modifier"));
    EXPECT_TRUE(Has(v, Rule::SourceModifiers, 3, "mov: the source of a write to oC0 takes no modifier"));
}

TEST(ValidatorRule10, NotOnlyOnBooleanConditions) {
    const auto v = check(R"(
        vs_2_0
        dcl_position v0
        if -b0
        endif
        mov r0, !v0
        mov oPos, v0
    )");
    EXPECT_TRUE(Has(v, Rule::SourceModifiers, 1, "if: source 0 (b0) cannot be negated"));
    EXPECT_TRUE(Has(v, Rule::SourceModifiers, 3, "mov: ! (not) is only allowed on a b# condition"));
}

// ===================================================================================
// Rule 11: destination modifiers
// ===================================================================================

TEST(ValidatorRule11, NoResultModifiersInVertexShaders) {
    const auto v = check(R"(
        vs_2_0
        dcl_position v0
        dcl_pp_texcoord0 v1
        mov_sat r0, v0
        mov_pp oPos, r0
    )");
    EXPECT_TRUE(Has(v, Rule::DestModifiers, 1, "dcl: _pp is not allowed on dcl of v1"));
    EXPECT_TRUE(Has(v, Rule::DestModifiers, 2, "mov: _sat is not available in vs_2_0"));
    EXPECT_TRUE(Has(v, Rule::DestModifiers, 3, "mov: _pp is not available in vs_2_0"));
}

TEST(ValidatorRule11, SaturateRestrictionsInPixelShaders) {
    const auto v = check(std::string(R"(
        ps_2_0
        dcl t0
        dcl_2d s0
    )") + kSinCosDefs + R"(
        texld_sat r0, t0, s0
        frc_sat r1, t0
        sincos_sat r2.xy, r0.x, c1, c2
        mov_sat oC0, r0
        mov_pp oC1, r1
        mov_sat oDepth, r2.x
    )");
    EXPECT_TRUE(Has(v, Rule::DestModifiers, 4, "texld: _sat is not allowed on texld"));
    EXPECT_TRUE(Has(v, Rule::DestModifiers, 5, "frc: _sat is not allowed on frc"));
    EXPECT_TRUE(Has(v, Rule::DestModifiers, 6, "sincos: _sat is not allowed on sincos"));
    EXPECT_TRUE(Has(v, Rule::DestModifiers, 7, "mov: _sat is not allowed on a write to oC0"));
    EXPECT_TRUE(Has(v, Rule::DestModifiers, 8, "mov: _pp is not allowed on a write to oC1"));
    EXPECT_TRUE(Has(v, Rule::DestModifiers, 9, "mov: _sat is not allowed on a write to oDepth"));
    EXPECT_EQ(v.size(), 6u) << dump(v);
}

TEST(ValidatorRule11, ShiftAndCentroid) {
    const auto v = check(R"(
        ps_2_0
        dcl_centroid t0
        dcl_centroid v0
        mul_x2 r0, t0, v0
        add_centroid r1, r0, t0
        mov oC0, r1
    )");
    EXPECT_TRUE(Has(v, Rule::DestModifiers, 1, "dcl: _centroid is not allowed on dcl of v0"));
    EXPECT_TRUE(Has(v, Rule::DestModifiers, 2, "mul: result shifts are not available in ps_2_0"));
    EXPECT_TRUE(Has(v, Rule::DestModifiers, 3, "add: _centroid is only allowed on dcl"));
    EXPECT_EQ(v.size(), 3u) << dump(v);
}

// ===================================================================================
// Rule 12: swizzles
// ===================================================================================

TEST(ValidatorRule12, ReplicateRequired) {
    const auto v = check(R"(
        vs_2_0
        dcl_position v0
        rcp r0, v0
        pow r1, v0.x, v0.xy
        mov oPos, v0
    )");
    EXPECT_TRUE(Has(v, Rule::Swizzle, 1, "rcp: source 0 (v0.xyzw) needs a replicate swizzle"));
    EXPECT_TRUE(Has(v, Rule::Swizzle, 2, "pow: source 1 (v0.xyyy) needs a replicate swizzle"));
    EXPECT_TRUE(Has(check(R"(
        ps_2_0
        dcl t0
        dp2add r0, t0, t0, t0.xy
        mov oC0, r0
    )"), Rule::Swizzle, 1, "dp2add: source 2"));
}

TEST(ValidatorRule12, PixelShaderWhitelist) {
    EXPECT_TRUE(Only(check(R"(
        ps_2_0
        dcl t0
        mov r0, t0.yxzw
        mov oC0, r0
    )"), Rule::Swizzle, 1, "mov: source 0 (t0.yxzw) is not one of the swizzles ps_2_0 allows"));
    EXPECT_TRUE(Clean(check(R"(
        ps_2_0
        dcl t0
        mov r0, t0.yzxw
        add r0, r0, t0.zxyw
        add r0, r0, t0.wzyx
        add r0, r0, t0.w
        mov oC0, r0
    )")));
    // vs_2_0 takes any swizzle.
    EXPECT_TRUE(Clean(check("vs_2_0\ndcl_position v0\nmov oPos, v0.yxwz\n")));
}

TEST(ValidatorRule12, IdentityRequired) {
    const auto v = check(R"(
        ps_2_0
        dcl t0
        dcl_2d s0
        texld r0, t0.yxzw, s0
        crs r1.xyz, r0.yzxw, t0
        m3x3 r2.xyz, r1, c0.yzxw
        mov oC0, r2.x
    )");
    EXPECT_TRUE(Has(v, Rule::Swizzle, 2, "texld: source 0 (t0.yxzw) of a texture instruction takes no swizzle"));
    EXPECT_TRUE(Has(v, Rule::Swizzle, 3, "crs: source 0 (r0.yzxw) of crs takes no swizzle"));
    EXPECT_TRUE(Has(v, Rule::Swizzle, 4, "m3x3: source 1 (c0.yzxw) is the matrix and takes no swizzle"));
    EXPECT_TRUE(Has(v, Rule::Swizzle, 5, "mov: source 0 (r2.xxxx) of a write to oC# takes no swizzle"));

    Program p = parse_program("ps_2_0\ndcl t0\ndcl_2d s0\ntexld r0, t0, s0\nmov oC0, r0\n");
    p.instructions[2].sources[1].swizzle = 0x00;
    EXPECT_TRUE(Only(validate(p), Rule::Swizzle, 2, "texld: source 1 (s0.xxxx) takes no swizzle"));
}

TEST(ValidatorRule12, DepthNeedsReplicate) {
    EXPECT_TRUE(Only(check(R"(
        ps_2_0
        dcl t0
        mov oC0, t0
        mov oDepth, t0
    )"), Rule::Swizzle, 2, "mov: source 0 (t0.xyzw) of a write to oDepth needs a replicate swizzle"));
}

// ===================================================================================
// Rule 13: write masks
// ===================================================================================

TEST(ValidatorRule13, PixelMasks) {
    const auto v = check(std::string(R"(
        ps_2_0
        dcl t0
        dcl_2d s0
    )") + kSinCosDefs + R"(
        texld r0.xy, t0, s0
        sincos r1.xyz, t0.x, c1, c2
        crs r2, t0, c1
        mov oC0.xyz, t0
        mov oDepth.x, t0.x
        texkill t0.xyz
    )");
    EXPECT_TRUE(Has(v, Rule::WriteMask, 4, "texld: the destination needs the full mask .xyzw, got r0.xy"));
    EXPECT_TRUE(Has(v, Rule::WriteMask, 5, "sincos: the mask must be .x, .y or .xy, got r1.xyz"));
    EXPECT_TRUE(Has(v, Rule::WriteMask, 6, "crs: the mask must be one of .x .y .z .xy .xz .yz .xyz, got r2.xyzw"));
    EXPECT_TRUE(Has(v, Rule::WriteMask, 7, "mov: oC# takes the full mask, got oC0.xyz"));
    EXPECT_TRUE(Has(v, Rule::WriteMask, 8, "mov: oDepth takes no write mask, got oDepth.x"));
    EXPECT_TRUE(Has(v, Rule::WriteMask, 9, "texkill: texkill takes the full mask, got t0.xyz"));
}

TEST(ValidatorRule13, MatrixMasks) {
    const auto v = check(R"(
        vs_2_0
        dcl_position v0
        m3x3 r0, v0, c0
        m4x4 r1.xyz, v0, c0
        m3x2 r2.xy, v0, c0
        m4x3 r3.xyz, v0, c0
        mov oPos, v0
    )");
    EXPECT_TRUE(Has(v, Rule::WriteMask, 1, "m3x3: the mask must be .xyz, got r0.xyzw"));
    EXPECT_TRUE(Has(v, Rule::WriteMask, 2, "m4x4: the mask must be .xyzw, got r1.xyz"));
    EXPECT_EQ(v.size(), 2u) << dump(v);
}

TEST(ValidatorRule13, ScalarOutputsTakeNoMask) {
    // The assemblers write oFog/oPts with mask 0xF; anything else is an explicit mask.
    EXPECT_TRUE(Only(check(R"(
        vs_2_0
        dcl_position v0
        mov oPos, v0
        mov oFog.x, v0.x
    )"), Rule::WriteMask, 2, "mov: oFog takes no write mask, got oFog.x"));
}

TEST(ValidatorRule13, DefinitionsAndSamplerDeclarationsTakeTheFullMask) {
    Program p = parse_program(R"(
        ps_2_0
        dcl t0
        dcl_2d s0
        def c0, 1, 1, 1, 1
        texld r0, t0, s0
        mov oC0, r0
    )");
    p.instructions[1].dest->write_mask = 0x3;
    p.instructions[2].dest->write_mask = 0x1;
    const auto v = validate(p);
    EXPECT_TRUE(Has(v, Rule::WriteMask, 1, "dcl: a sampler dcl takes the full mask"));
    EXPECT_TRUE(Has(v, Rule::WriteMask, 2, "def: a constant definition takes the full mask"));
}

TEST(ValidatorRule13, EmptyMask) {
    Program p = parse_program("ps_2_0\ndcl t0\nmov r0, t0\nmov oC0, t0\n");
    p.instructions[1].dest->write_mask = 0;
    EXPECT_TRUE(Has(validate(p), Rule::WriteMask, 1, "mov: empty write mask on r0"));
}

TEST(ValidatorRule13, TexcoordOutputCombinedMasks) {
    // .x then .y: combined .xy is fine.
    EXPECT_TRUE(Clean(check(R"(
        vs_2_0
        dcl_position v0
        mov oPos, v0
        mov oT0.x, v0.x
        mov oT0.y, v0.y
        mov oT1, v0
    )")));
    EXPECT_TRUE(Only(check(R"(
        vs_2_0
        dcl_position v0
        mov oPos, v0
        mov oT0.xz, v0
    )"), Rule::WriteMask, 2, "the combined write mask of oT0 is .xz"));
    EXPECT_TRUE(Only(check(R"(
        vs_2_0
        dcl_position v0
        mov oPos, v0
        mov oT0, v0
        mov oT2.xy, v0
    )"), Rule::WriteMask, 3, "oT2 is written but oT1 is not"));
}

// ===================================================================================
// Rule 14: read ports
// ===================================================================================

TEST(ValidatorRule14, TwoConstantsAtMost) {
    EXPECT_TRUE(Only(check(R"(
        ps_2_0
        mad r0, c1, c2, c3
        mov oC0, r0
    )"), Rule::ReadPorts, 0, "mad: reads 3 different c# registers (c1, c2, c3); at most 2 per instruction"));
    EXPECT_TRUE(Clean(check("ps_2_0\nmad r0, c0, c0, c1\nmov oC0, r0\n")));
}

TEST(ValidatorRule14, OneInputOneTexcoord) {
    EXPECT_TRUE(Only(check(R"(
        vs_2_0
        dcl_position v0
        dcl_normal v1
        add r0, v0, v1
        mov oPos, r0
    )"), Rule::ReadPorts, 2, "add: reads 2 different v# registers (v0, v1); at most 1"));
    // The same v# twice, each with its own swizzle and negate, is one port.
    EXPECT_TRUE(Clean(check("vs_2_0\ndcl_position v0\nmad oPos, v0, -v0.wzyx, v0.x\n")));
    const auto v = check(R"(
        ps_2_0
        dcl t0
        dcl t1
        dcl v0
        dcl v1
        add r0, t0, t1
        add r1, v0, v1
        add r2, r0, r1
        mov oC0, r2
    )");
    EXPECT_TRUE(Has(v, Rule::ReadPorts, 4, "add: reads 2 different t# registers"));
    EXPECT_TRUE(Has(v, Rule::ReadPorts, 5, "add: reads 2 different v# registers"));
}

TEST(ValidatorRule14, IndexReads) {
    EXPECT_TRUE(Has(check(R"(
        vs_2_0
        dcl_position v0
        mova a0, v0
        mad r0, c[a0.x], c[a0.y + 1], c[a0.z + 2]
        mov oPos, r0
    )"), Rule::ReadPorts, 2, "mad: uses a0 as an index 3 times; at most 2"));
}

// ===================================================================================
// Rule 15: instruction-specific operand rules
// ===================================================================================

TEST(ValidatorRule15, SinCosConstants) {
    // The same constant twice.
    EXPECT_TRUE(Only(check(R"(
        vs_2_0
        dcl_position v0
        sincos r0.xy, v0.x, c1, c1
        mov oPos, v0
    )"), Rule::InstructionOperands, 1, "sincos: sources 1 and 2 must be two different constant registers"));
    // Not constants.
    EXPECT_TRUE(Has(check(R"(
        vs_2_0
        dcl_position v0
        mov r1, v0
        sincos r0.xy, v0.x, r1, c2
        mov oPos, v0
    )"), Rule::InstructionOperands, 2, "sincos: sources 1 and 2 must be plain constant registers c#"));
    // Defined in the shader with other values.
    EXPECT_TRUE(Only(check(R"(
        vs_2_0
        dcl_position v0
        def c1, 1, 2, 3, 4
        def c2, 0xBCAAAAAB, 0xBE000000, 0x3F800000, 0x3F000000
        sincos r0.xy, v0.x, c1, c2
        mov oPos, v0
    )"), Rule::InstructionOperands, 3, "sincos: c1 is defined in the shader but does not hold D3DSINCOSCONST1"));
    // Swapped constants.
    EXPECT_TRUE(Has(check(std::string("vs_2_0\ndcl_position v0\n") + kSinCosDefs +
                          "sincos r0.xy, v0.x, c2, c1\nmov oPos, v0\n"),
                    Rule::InstructionOperands, 3, "c2 is defined in the shader but does not hold D3DSINCOSCONST1"));
    // Constants set by the application (not def'ed) are not checked.
    EXPECT_TRUE(Clean(check("vs_2_0\ndcl_position v0\nsincos r0.xy, v0.x, c1, c2\nmov oPos, v0\n")));
}

TEST(ValidatorRule15, SinCosOneSourceFormIsNotPs20) {
    // Wine writes `sincos r0.xy, r1.x` in ps; the documented 2.0 form has three sources.
    EXPECT_TRUE(Only(check(R"(
        ps_2_0
        dcl t0
        sincos r0.xy, t0.x
        mov oC0, t0
    )"), Rule::InstructionOperands, 1, "sincos: the 1-source form is not valid in ps_2_0"));
}

TEST(ValidatorRule15, DestinationMustNotBeASource) {
    const auto v = check(R"(
        vs_2_0
        dcl_position v0
        mov r0, v0
        mov r1, v0
        crs r0.xyz, r0, r1
        nrm r1, r1
        pow r0, r1.x, r0.y
        m4x4 r0, r0, c0
        m3x3 r2.xyz, v0, r1
        pow oD0, r1.x, r1.y
        mov oPos, r0
    )");
    EXPECT_TRUE(Has(v, Rule::InstructionOperands, 3, "crs: the destination r0 must not be source 0"));
    EXPECT_TRUE(Has(v, Rule::InstructionOperands, 4, "nrm: the destination r1 must not be the source"));
    EXPECT_TRUE(Has(v, Rule::InstructionOperands, 5, "pow: the destination r0 must not be source 1 (the exponent)"));
    EXPECT_TRUE(Has(v, Rule::InstructionOperands, 6, "m4x4: the destination r0 must not be source 0"));
    EXPECT_TRUE(Has(v, Rule::InstructionOperands, 7, "m3x3: the destination r2 must not be one of the matrix rows r1..r3"));
    EXPECT_TRUE(Has(v, Rule::InstructionOperands, 8, "pow: the destination must be a temporary register r#, got oD0"));
}

TEST(ValidatorRule15, SgnScratchTemps) {
    const auto v = check(R"(
        vs_2_0
        dcl_position v0
        sgn r0, v0, r1, r1
        sgn r2, v0, c0, r3
        mov oPos, r0
    )");
    EXPECT_TRUE(Has(v, Rule::InstructionOperands, 1, "sgn: the scratch temporaries (sources 1 and 2) must be different, got r1 twice"));
    EXPECT_TRUE(Has(v, Rule::InstructionOperands, 2, "sgn: sources 1 and 2 must be scratch temporaries r#, got c0 and r3"));
}

TEST(ValidatorRule15, TexldCoordinateClass) {
    const auto v = check(R"(
        ps_2_0
        dcl v0
        dcl_2d s0
        texld r0, v0, s0
        texld r1, c0, s0
        add r2, r0, r1
        mov oC0, r2
    )");
    EXPECT_TRUE(Has(v, Rule::InstructionOperands, 2, "texld: the coordinate (source 0) must be t# or r#, got v0"));
    EXPECT_TRUE(Has(v, Rule::InstructionOperands, 3, "texld: the coordinate (source 0) must be t# or r#, got c0"));
}

// ===================================================================================
// Rule 16: slot budgets
// ===================================================================================

std::string ps_arithmetic(int adds) {
    // def (0 slots), mov (1), adds (1 each), mov oC0 (1)
    return "ps_2_0\ndef c0, 1, 1, 1, 1\nmov r0, c0\n" + repeat("add r0, r0, c0", adds) + "mov oC0, r0\n";
}

TEST(ValidatorRule16, PixelArithmeticBudget) {
    EXPECT_TRUE(Clean(check(ps_arithmetic(62))));  // 64 slots
    // 65 slots: the final mov (index 64) is slot 65.
    EXPECT_TRUE(Only(check(ps_arithmetic(63)), Rule::SlotBudget, 65,
                     "mov: uses arithmetic instruction slot 65; the limit is 64"));
}

TEST(ValidatorRule16, PixelArithmeticBudgetUsesTableSlotCosts) {
    // 15 m4x4 (4 each) + lrp (2) + mov oC0 (1) + nop (1) = 64.
    const std::string body = "ps_2_0\ndcl t0\n" + repeat("m4x4 r0, t0, c0", 15) +
                             "lrp r1, t0, r0, c0\nmov oC0, r1\n";
    EXPECT_TRUE(Clean(check(body + "nop\n")));
    EXPECT_TRUE(Only(check(body + "nop\nnop\n"), Rule::SlotBudget, 19, "nop: uses arithmetic instruction slot 65"));
}

std::string ps_texture(int kills) {
    // 8 texld into distinct temps (no dependent reads) + texkill t0 (1 texture slot each).
    std::string s = "ps_2_0\ndcl t0\ndcl_2d s0\n";
    for (int r = 0; r < 8; ++r) s += "texld r" + std::to_string(r) + ", t0, s0\n";
    return s + repeat("texkill t0", kills) + "mov oC0, r7\n";
}

TEST(ValidatorRule16, PixelTextureBudget) {
    EXPECT_TRUE(Clean(check(ps_texture(24))));  // 32 texture slots
    // 33: the last texkill at index 2 + 8 + 24 = 34.
    EXPECT_TRUE(Only(check(ps_texture(25)), Rule::SlotBudget, 34,
                     "texkill: uses texture instruction slot 33; the limit is 32"));
}

std::string vs_slots(int adds) {
    return "vs_2_0\ndcl_position v0\nmov r0, v0\n" + repeat("add r0, r0, c0", adds) + "mov oPos, r0\n";
}

TEST(ValidatorRule16, VertexBudget) {
    EXPECT_TRUE(Clean(check(vs_slots(254))));  // 256 slots
    EXPECT_TRUE(Only(check(vs_slots(255)), Rule::SlotBudget, 257,
                     "mov: uses total instruction slot 257; the limit is 256"));
}

TEST(ValidatorRule16, OptionOverridesTheTotal) {
    ValidationOptions big;
    big.max_instruction_slots = 512;
    EXPECT_TRUE(Clean(check(ps_arithmetic(100), big)));
    ValidationOptions small;
    small.max_instruction_slots = 10;
    EXPECT_TRUE(Only(check(vs_slots(9), small), Rule::SlotBudget, 11,
                     "mov: uses total instruction slot 11; the limit is 10"));
}

// ===================================================================================
// Rule 17: dependent reads
// ===================================================================================

TEST(ValidatorRule17, FourLevelsPassFiveFail) {
    const std::string four = R"(
        ps_2_0
        dcl t0
        dcl_2d s0
        def c0, 0.5, 0.5, 0, 0
        texld r0, t0, s0
        texld r1, r0, s0
        add r1, r1, c0
        texld r2, r1, s0
        texld r3, r2, s0
    )";
    EXPECT_TRUE(Clean(check(four + "mov oC0, r3\n")));
    EXPECT_TRUE(Only(check(four + "texld r4, r3, s0\nmov oC0, r4\n"), Rule::DependentReads, 8,
                     "texld: is a dependent read of order 4; ps_2_0 allows order 3 (4 levels of texture reads)"));
}

TEST(ValidatorRule17, RewritingTheDestinationIsDependent) {
    // A texld whose destination was written earlier is at least first order.
    const std::string base = "ps_2_0\ndcl t0\ndcl_2d s0\n" + repeat("texld r0, t0, s0", 4);
    EXPECT_TRUE(Clean(check(base + "mov oC0, r0\n")));
    EXPECT_TRUE(Only(check(base + "texld r0, t0, s0\nmov oC0, r0\n"), Rule::DependentReads, 6,
                     "order 4"));
}

// ===================================================================================
// Rule 18: flow control
// ===================================================================================

TEST(ValidatorRule18, LoopNesting) {
    EXPECT_TRUE(Only(check(R"(
        vs_2_0
        dcl_position v0
        loop aL, i0
        rep i1
        endrep
        endloop
        mov oPos, v0
    )"), Rule::FlowControl, 2, "rep: loop/rep nesting deeper than 1"));
    // if inside a loop is fine.
    EXPECT_TRUE(Clean(check(R"(
        vs_2_0
        dcl_position v0
        rep i0
        if b0
        endif
        endrep
        mov oPos, v0
    )")));
    // A routine with a loop called from inside a loop nests loops.
    EXPECT_TRUE(Only(check(R"(
        vs_2_0
        dcl_position v0
        rep i0
        call l0
        endrep
        mov oPos, v0
        ret
        label l0
        rep i1
        endrep
        ret
    )"), Rule::FlowControl, 2, "call: calls l0, which has a loop/rep, from inside a loop/rep"));
}

TEST(ValidatorRule18, CallNesting) {
    EXPECT_TRUE(Only(check(R"(
        vs_2_0
        dcl_position v0
        call l0
        mov oPos, v0
        ret
        label l0
        call l1
        ret
        label l1
        ret
    )"), Rule::FlowControl, 5, "call: call nesting deeper than 1 (a subroutine cannot call)"));
}

TEST(ValidatorRule18, StaticFlowCount) {
    // 16 if/else pairs count 16... 8 if + 8 else = 16 is the limit; one more if is 17.
    const std::string eight = repeat("if b0\nelse\nendif", 8);
    EXPECT_TRUE(Clean(check("vs_2_0\ndcl_position v0\n" + eight + "mov oPos, v0\n")));
    EXPECT_TRUE(Only(check("vs_2_0\ndcl_position v0\n" + eight + "if b0\nendif\nmov oPos, v0\n"),
                     Rule::FlowControl, 25, "if: static flow count exceeds 16"));
}

TEST(ValidatorRule18, Labels) {
    const auto v = check(R"(
        vs_2_0
        dcl_position v0
        call l0
        mov oPos, v0
        ret
        label l0
        ret
        label l0
        ret
    )");
    EXPECT_TRUE(Only(v, Rule::FlowControl, 6, "label: l0 is already defined at 4"));
    EXPECT_TRUE(Has(check(R"(
        vs_2_0
        dcl_position v0
        call l0
        mov oPos, v0
        label l0
        ret
    )"), Rule::FlowControl, 3, "label: a label must directly follow a ret"));
    EXPECT_TRUE(Only(check(R"(
        vs_2_0
        dcl_position v0
        call l5
        mov oPos, v0
        ret
        label l0
        ret
    )"), Rule::FlowControl, 1, "call: l5 is not defined"));
}

TEST(ValidatorRule18, CallsGoForward) {
    EXPECT_TRUE(Has(check(R"(
        vs_2_0
        dcl_position v0
        mov oPos, v0
        ret
        label l0
        ret
        label l1
        call l0
        ret
    )"), Rule::FlowControl, 6, "call: calls must go forward; l0 is defined at 3"));
}

TEST(ValidatorRule18, OneRetPerRoutineAndNothingBetweenRoutines) {
    EXPECT_TRUE(Only(check(R"(
        vs_2_0
        dcl_position v0
        mov oPos, v0
        ret
        ret
    )"), Rule::FlowControl, 3, "ret: a routine has one ret; the ret at 2 already ended it"));
    EXPECT_TRUE(Only(check(R"(
        vs_2_0
        dcl_position v0
        mov oPos, v0
        ret
        mov r0, v0
    )"), Rule::FlowControl, 3, "mov: code after a ret must start with a label l#"));
    EXPECT_TRUE(Only(check(R"(
        vs_2_0
        dcl_position v0
        call l0
        mov oPos, v0
        ret
        label l0
        mov r0, v0
    )"), Rule::FlowControl, 4, "label: routine l0 has no ret"));
}

TEST(ValidatorRule18, NestingAndStraddling) {
    EXPECT_TRUE(Has(check(R"(
        vs_2_0
        dcl_position v0
        rep i0
        if b0
        endrep
        endif
        mov oPos, v0
    )"), Rule::FlowControl, 3, "endrep: closes the rep at 1 while the if at 2 is still open"));
    EXPECT_TRUE(Only(check(R"(
        vs_2_0
        dcl_position v0
        if b0
        mov oPos, v0
    )"), Rule::FlowControl, 1, "if: block is not closed"));
    const auto v = check(R"(
        vs_2_0
        dcl_position v0
        else
        endloop
        if b0
        else
        else
        endif
        mov oPos, v0
    )");
    EXPECT_TRUE(Has(v, Rule::FlowControl, 1, "else: has no matching if"));
    EXPECT_TRUE(Has(v, Rule::FlowControl, 2, "endloop: has no matching loop"));
    EXPECT_TRUE(Has(v, Rule::FlowControl, 5, "else: has no matching if"));
    EXPECT_TRUE(Has(check(R"(
        vs_2_0
        dcl_position v0
        mov oPos, v0
        if b0
        ret
        endif
    )"), Rule::FlowControl, 3, "ret: ret inside an open if block (at 2)"));
}

// ===================================================================================
// Rule 19: outputs
// ===================================================================================

TEST(ValidatorRule19, RequiredOutputs) {
    EXPECT_TRUE(Only(check("vs_2_0\ndcl_position v0\nmov oD0, v0\n"), Rule::Outputs, SIZE_MAX,
                     "vs_2_0 shader never writes oPos"));
    const auto v = check("ps_2_0\ndcl t0\nmov oC1, t0\n");
    EXPECT_TRUE(Has(v, Rule::Outputs, SIZE_MAX, "ps_2_0 shader never writes oC0"));
    EXPECT_TRUE(Has(v, Rule::Outputs, 1, "mov: oC1 is written but oC0 is not"));
    EXPECT_EQ(v.size(), 2u) << dump(v);
}

TEST(ValidatorRule19, ColorAndDepthOnlyByMovOnce) {
    const auto v = check(R"(
        ps_2_0
        dcl t0
        dcl t1
        add oC0, t0, c0
        mov oC1, t0
        mov oC1, t1
        mov oDepth, t0.x
        mov oDepth, t1.x
        mov oC3, t0
    )");
    EXPECT_TRUE(Has(v, Rule::Outputs, 2, "add: oC0 can only be written by mov"));
    EXPECT_TRUE(Has(v, Rule::Outputs, 4, "mov: oC1 is written more than once (first at 3)"));
    EXPECT_TRUE(Has(v, Rule::Outputs, 6, "mov: oDepth is written more than once (first at 5)"));
    EXPECT_TRUE(Has(v, Rule::Outputs, 7, "mov: oC3 is written but oC2 is not"));
    EXPECT_EQ(v.size(), 4u) << dump(v);
}

// ===================================================================================
// Robustness: odd hand-built programs never crash
// ===================================================================================

TEST(ValidatorRobustness, OddProgramsDoNotCrash) {
    Program p;
    p.version = {ShaderType::Pixel, 2, 0};
    Instruction texld;
    texld.opcode = Opcode::Tex;
    texld.control = 7;  // no such variant
    p.instructions.push_back(texld);
    Instruction dcl;
    dcl.opcode = Opcode::Dcl;  // no register
    p.instructions.push_back(dcl);
    Instruction def;
    def.opcode = Opcode::Def;
    def.dest = DestinationParameter{RegisterType::Const, 2047, 0xF, false, false, false, 0};
    def.sources.resize(2);
    p.instructions.push_back(def);
    Instruction mov;
    mov.opcode = Opcode::Mov;
    mov.dest = DestinationParameter{static_cast<RegisterType>(31), 2047, 0xF, false, false, false, 0};
    mov.sources.push_back(SourceParameter{static_cast<RegisterType>(19), 2047, 0x1B,
                                          static_cast<SourceModifier>(15),
                                          RelativeAddress{static_cast<RegisterType>(30), 0x12}});
    p.instructions.push_back(mov);
    Instruction m4x4;
    m4x4.opcode = Opcode::M4x4;  // no operands at all
    p.instructions.push_back(m4x4);
    const auto v = validate(p);
    EXPECT_TRUE(Has(v, Rule::OpcodeVersion, 0, "unknown opcode"));
    EXPECT_TRUE(Has(v, Rule::Operands, 1, "dcl: missing the register"));
    EXPECT_TRUE(Has(v, Rule::Operands, 2, "def: takes no source operands"));
    EXPECT_TRUE(Has(v, Rule::Operands, 3, "does not exist in ps_2_0"));
    EXPECT_TRUE(Has(v, Rule::Operands, 4, "m4x4: missing destination"));
}

// Random instructions built from the table rows with random operands: the validator must
// answer (anything) without crashing or reading out of bounds.
TEST(ValidatorRobustness, RandomProgramsDoNotCrash) {
    std::mt19937 rng(12345);
    auto pick = [&](uint32_t n) { return static_cast<uint32_t>(rng() % n); };
    const auto table = opcode_table();
    for (int round = 0; round < 3000; ++round) {
        Program p;
        p.version = {pick(2) ? ShaderType::Vertex : ShaderType::Pixel, 2, 0};
        const uint32_t count = 1 + pick(24);
        for (uint32_t k = 0; k < count; ++k) {
            const OpcodeInfo& row = table[pick(static_cast<uint32_t>(table.size()))];
            Instruction ins;
            ins.opcode = row.opcode;
            ins.control = row.control;
            auto reg_type = [&] { return static_cast<RegisterType>(pick(20)); };
            auto index = [&] { return static_cast<uint16_t>(pick(4) == 0 ? pick(2048) : pick(20)); };
            if (pick(8) != 0 && (row.has_dest() || pick(4) == 0)) {
                DestinationParameter d;
                d.type = pick(3) ? RegisterType::Temp : reg_type();
                d.index = index();
                d.write_mask = static_cast<uint8_t>(pick(16));
                d.saturate = pick(4) == 0;
                d.partial_precision = pick(4) == 0;
                ins.dest = d;
            }
            const uint32_t nsrc = pick(8) ? row.num_sources : pick(5);
            for (uint32_t s = 0; s < nsrc; ++s) {
                SourceParameter src;
                src.type = pick(2) ? RegisterType::Temp : reg_type();
                src.index = index();
                src.swizzle = static_cast<uint8_t>(pick(256));
                src.modifier = static_cast<SourceModifier>(pick(3) ? 0 : pick(16));
                if (pick(6) == 0) src.relative = RelativeAddress{reg_type(), static_cast<uint8_t>(pick(256))};
                ins.sources.push_back(src);
            }
            ins.declaration.texture_type = static_cast<TextureType>(pick(6));
            ins.declaration.usage = static_cast<DeclUsage>(pick(16));
            ins.declaration.usage_index = static_cast<uint8_t>(pick(20));
            if (pick(30) == 0) ins.opcode = Opcode::Comment;
            p.instructions.push_back(ins);
        }
        const auto v = validate(p);
        for (const Violation& x : v) {
            EXPECT_FALSE(x.message.empty());
            EXPECT_TRUE(x.instruction == SIZE_MAX || x.instruction < p.instructions.size());
        }
    }
}

}  // namespace
}  // namespace sm2::isa
