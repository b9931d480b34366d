// sm2 compile: vs_2_0 static flow control. An `if` on a uniform bool becomes `if b#`/`else`/`endif`,
// a loop counted by a uniform int becomes `rep i#`/`endrep`; the bytecode's flow instructions are
// checked in `sm2 dis` and the shaders run with `sm2 run --bool/--int` against values worked out
// by hand (in the comments). ps_2_0 has no flow control: the same HLSL is a located error there.
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "cli_support.h"
#include "hlsl_support.h"

using namespace cli_support;
using namespace hlsl_support;

namespace {

// The error text of a compile that must fail (exit status 1).
std::string compile_error(const std::string& name, const std::string& hlsl, const std::string& profile) {
    const std::string source = tmp(name + ".hlsl");
    write_file(source, hlsl);
    const cli_support::Run r = sm2("compile " + source + " -T " + profile);
    EXPECT_EQ(r.status, 1) << r.out;
    return r.err;
}

// The disassembly's lines, and the flow control ones among them (if, else, endif, rep, endrep).
std::vector<std::string> disassembly(const std::string& shader) {
    const cli_support::Run r = sm2("dis " + shader);
    EXPECT_EQ(r.status, 0) << r.err;
    std::vector<std::string> lines;
    std::istringstream text(r.out);
    for (std::string line; std::getline(text, line);) lines.push_back(line);
    return lines;
}

std::vector<std::string> flow_lines(const std::vector<std::string>& lines) {
    std::vector<std::string> flow;
    for (const auto& line : lines)
        for (const char* op : {"if ", "else", "endif", "rep ", "endrep", "loop ", "endloop"})
            if (line.rfind(op, 0) == 0) flow.push_back(line);
    return flow;
}

bool has_line(const std::vector<std::string>& lines, const std::string& wanted) {
    for (const auto& line : lines)
        if (line == wanted) return true;
    return false;
}

constexpr const char* kIfElse =
    "bool useTint;\n"
    "float4 tint;\n"
    "float4 main(float4 pos : POSITION, out float4 col : COLOR0) : POSITION {\n"
    "  if (useTint) col = tint * 2; else col = tint + pos;\n"
    "  return pos;\n"
    "}\n";

constexpr const char* kRep =
    "int count;\n"
    "float4 step;\n"
    "float4 main(float4 pos : POSITION, out float4 col : COLOR0) : POSITION {\n"
    "  float4 acc = pos;\n"
    "  for (int k = 0; k < count; ++k) acc = acc * 0.5 + step;\n"
    "  col = acc;\n"
    "  return pos;\n"
    "}\n";

}  // namespace

TEST(HlslFlow, UniformBoolIfBecomesIfB) {
    const auto vs = compile("flow_if", kIfElse, "vs_2_0");
    ASSERT_FALSE(vs.empty());
    const auto lines = disassembly(vs);
    // useTint is b0 (no c# register), tint the first float register c0.
    EXPECT_TRUE(has_line(lines, "//   useTint  bool    b0        1")) << ::testing::PrintToString(lines);
    EXPECT_TRUE(has_line(lines, "//   tint     float4  c0        1")) << ::testing::PrintToString(lines);
    EXPECT_EQ(flow_lines(lines), (std::vector<std::string>{"if b0", "else", "endif"}));
    // tint (1, 2, 3, 4), pos (1, 1, 1, 1): b0 true -> tint * 2 = (2, 4, 6, 8); false -> tint + pos = (2, 3, 4, 5).
    const std::string args = " --const tint=1,2,3,4 --input v0=1,1,1,1";
    expect_near(run_output(vs, "--bool b0=true" + args, "oD0"), {2, 4, 6, 8});
    expect_near(run_output(vs, "--bool b0=false" + args, "oD0"), {2, 3, 4, 5});
    expect_near(run_output(vs, args, "oD0"), {2, 3, 4, 5});  // b# default FALSE
}

TEST(HlslFlow, UniformIntLoopBecomesRep) {
    const auto vs = compile("flow_rep", kRep, "vs_2_0");
    ASSERT_FALSE(vs.empty());
    const auto lines = disassembly(vs);
    EXPECT_TRUE(has_line(lines, "//   count  int     i0        1")) << ::testing::PrintToString(lines);
    EXPECT_TRUE(has_line(lines, "//   step   float4  c0        1")) << ::testing::PrintToString(lines);
    EXPECT_EQ(flow_lines(lines), (std::vector<std::string>{"rep i0", "endrep"}));
    // acc = acc * 0.5 + step from pos (16, 8, 4, 0), step (1, 1, 1, 1):
    // 0 times: (16, 8, 4, 0); 1: (9, 5, 3, 1); 2: (5.5, 3.5, 2.5, 1.5); 3: (3.75, 2.75, 2.25, 1.75);
    // 5: x5 = (x0 - 2) / 32 + 2 = (2.4375, 2.1875, 2.0625, 1.9375).
    const std::string args = " --const step=1,1,1,1 --input v0=16,8,4,0";
    expect_near(run_output(vs, "--int i0=0" + args, "oD0"), {16, 8, 4, 0});
    expect_near(run_output(vs, "--int i0=1" + args, "oD0"), {9, 5, 3, 1});
    expect_near(run_output(vs, "--int i0=2" + args, "oD0"), {5.5f, 3.5f, 2.5f, 1.5f});
    expect_near(run_output(vs, "--int i0=3" + args, "oD0"), {3.75f, 2.75f, 2.25f, 1.75f});
    expect_near(run_output(vs, "--int i0=5" + args, "oD0"), {2.4375f, 2.1875f, 2.0625f, 1.9375f});
}

TEST(HlslFlow, NestedIfsNegationLoopsAndSelects) {
    // `if (!a)` is `if !b0`; an if inside an if; an if/else inside a rep; a ?: on a uniform bool.
    const auto vs = compile("flow_nested",
                            "bool a;\nbool b;\nint n;\nfloat4 k;\n"
                            "float4 main(float4 pos : POSITION, out float4 col : COLOR0) : POSITION {\n"
                            "  float4 acc = pos;\n"
                            "  if (!a) {\n    acc = acc * 2;\n    if (b) acc += k;\n  }\n"
                            "  for (int i = 0; i < n; i++) {\n    if (b) acc += k; else acc -= 1;\n  }\n"
                            "  col = a ? acc : -acc;\n"
                            "  return pos;\n}\n",
                            "vs_2_0");
    ASSERT_FALSE(vs.empty());
    const auto lines = disassembly(vs);
    EXPECT_TRUE(has_line(lines, "//   a     bool    b0        1")) << ::testing::PrintToString(lines);
    EXPECT_TRUE(has_line(lines, "//   b     bool    b1        1")) << ::testing::PrintToString(lines);
    EXPECT_TRUE(has_line(lines, "//   n     int     i0        1")) << ::testing::PrintToString(lines);
    EXPECT_EQ(flow_lines(lines), (std::vector<std::string>{"if !b0", "if b1", "endif", "endif", "rep i0", "if b1",
                                                           "else", "endif", "endrep", "if b0", "else", "endif"}));
    // pos (1, 2, 3, 4), k (1, 1, 1, 1).
    const std::string args = " --const k=1,1,1,1 --input v0=1,2,3,4";
    // a false, b true, n 2: (2, 4, 6, 8) + 1 = (3, 5, 7, 9); +1 twice = (5, 7, 9, 11); negated.
    expect_near(run_output(vs, "--bool b0=false --bool b1=true --int i0=2" + args, "oD0"), {-5, -7, -9, -11});
    // a false, b false, n 3: (2, 4, 6, 8); -1 three times = (-1, 1, 3, 5); negated.
    expect_near(run_output(vs, "--bool b0=false --bool b1=false --int i0=3" + args, "oD0"), {1, -1, -3, -5});
    // a true, b true, n 1: pos + 1 = (2, 3, 4, 5), kept.
    expect_near(run_output(vs, "--bool b0=true --bool b1=true --int i0=1" + args, "oD0"), {2, 3, 4, 5});
    // a true, b false, n 0: pos, kept.
    expect_near(run_output(vs, "--bool b0=true --bool b1=false --int i0=0" + args, "oD0"), {1, 2, 3, 4});
}

TEST(HlslFlow, LimitsAndUnsupportedFormsAreLocatedErrors) {
    // ps_2_0 has no flow control: the branch's line, and what vs_2_0 would do.
    std::string err = compile_error("flow_ps_if",
                                    "bool useRed;\nfloat4 main(float2 uv : TEXCOORD0) : COLOR {\n"
                                    "  float4 c = float4(uv, 0, 1);\n  if (useRed) c.x = 1;\n  return c;\n}\n",
                                    "ps_2_0");
    EXPECT_NE(err.find("flow_ps_if.hlsl(4,1): error: ps_2_0 has no flow control"), std::string::npos) << err;
    err = compile_error("flow_ps_rep",
                        "int n;\nfloat4 main(float2 uv : TEXCOORD0) : COLOR {\n  float4 c = 0;\n"
                        "  for (int i = 0; i < n; i++) c += uv.x;\n  return c;\n}\n",
                        "ps_2_0");
    EXPECT_NE(err.find("flow_ps_rep.hlsl(4,1): error: ps_2_0 has no flow control"), std::string::npos) << err;

    // Eight if/else pairs are 16 static flow instructions: they compile; the ninth `if` is the 17th.
    auto ifs = [](int count) {
        std::string hlsl = "bool b;\nfloat4 k;\nfloat4 main(float4 pos : POSITION) : POSITION {\n  float4 acc = pos;\n";
        for (int i = 1; i <= count; ++i) hlsl += "  if (b) acc += k * " + std::to_string(i) + "; else acc -= k;\n";
        return hlsl + "  return acc;\n}\n";
    };
    const auto eight = compile("flow_8", ifs(8), "vs_2_0");
    ASSERT_FALSE(eight.empty());
    // b true: pos + k * (1 + ... + 8) = 1 + 36 = 37 per component.
    expect_near(run_output(eight, "--bool b0=true --const k=1,1,1,1 --input v0=1,1,1,1", "oPos"), {37, 37, 37, 37});
    err = compile_error("flow_9", ifs(9), "vs_2_0");
    EXPECT_NE(err.find("flow_9.hlsl(13,1): error: this `if` is the 17th static flow control instruction"),
              std::string::npos) << err;
    EXPECT_NE(err.find("vs_2_0 allows 16"), std::string::npos) << err;

    // rep inside rep: vs_2_0 nests loops one deep.
    err = compile_error("flow_nested_rep",
                        "int n;\nint m;\nfloat4 k;\nfloat4 main(float4 pos : POSITION) : POSITION {\n"
                        "  float4 acc = pos;\n  for (int i = 0; i < n; i++)\n"
                        "    for (int j = 0; j < m; j++) acc += k;\n  return acc;\n}\n",
                        "vs_2_0");
    EXPECT_NE(err.find("flow_nested_rep.hlsl(7,1): error: a loop counted by a uniform int inside another"),
              std::string::npos) << err;
    // The count read as a value too: it lives in i0 only.
    err = compile_error("flow_count_value",
                        "int n;\nfloat4 main(float4 pos : POSITION) : POSITION {\n  float4 acc = pos;\n"
                        "  for (int i = 0; i < n; i++) acc += 1;\n  return acc * n;\n}\n",
                        "vs_2_0");
    EXPECT_NE(err.find("flow_count_value.hlsl(5,1): error: the uniform 'n' decides an `if` or counts a loop"),
              std::string::npos) << err;
    // Two bools combined: `if b#` tests one.
    err = compile_error("flow_and",
                        "bool b;\nbool e;\nfloat4 k;\nfloat4 main(float4 pos : POSITION) : POSITION {\n"
                        "  float4 a = pos;\n  if (b && e) a = normalize(a * k);\n  return a;\n}\n",
                        "vs_2_0");
    EXPECT_NE(err.find("flow_and.hlsl(6,1): error: a condition on uniform bools other than one bool alone"),
              std::string::npos) << err;
    // break out of a rep.
    err = compile_error("flow_break",
                        "int n;\nbool b;\nfloat4 main(float4 pos : POSITION) : POSITION {\n  float4 acc = pos;\n"
                        "  for (int i = 0; i < n; i++) { if (b) break; acc += 1; }\n  return acc;\n}\n",
                        "vs_2_0");
    EXPECT_NE(err.find("flow_break.hlsl(5,1): error: break, continue or return"), std::string::npos) << err;
}

TEST(HlslFlow, LoopAttributeKeepsAConstantCountLoopRolled) {
    // Loops with literal bounds are unrolled, except under [loop]: rep on a defi register, numbered
    // after the uniform ints (count is i0, the literal 3 is i1).
    const auto vs = compile("flow_rolled",
                            "int count;\nfloat4 step;\n"
                            "float4 main(float4 pos : POSITION, out float4 col : COLOR0) : POSITION {\n"
                            "  float4 acc = pos;\n"
                            "  [loop] for (int k = 0; k < 3; ++k) acc = acc * 0.5 + step;\n"
                            "  for (int j = 0; j < count; ++j) acc += 1;\n"
                            "  col = acc;\n  return pos;\n}\n",
                            "vs_2_0");
    ASSERT_FALSE(vs.empty());
    const auto lines = disassembly(vs);
    EXPECT_TRUE(has_line(lines, "defi i1, 3, 0, 0, 0")) << ::testing::PrintToString(lines);
    EXPECT_EQ(flow_lines(lines), (std::vector<std::string>{"rep i1", "endrep", "rep i0", "endrep"}));
    // Three halvings towards 2 from (16, 8, 4, 0): (3.75, 2.75, 2.25, 1.75); then + 1 per count.
    const std::string args = " --const step=1,1,1,1 --input v0=16,8,4,0";
    expect_near(run_output(vs, "--int i0=0" + args, "oD0"), {3.75f, 2.75f, 2.25f, 1.75f});
    expect_near(run_output(vs, "--int i0=2" + args, "oD0"), {5.75f, 4.75f, 4.25f, 3.75f});
    // A rolled count past rep's 255.
    const std::string err = compile_error("flow_rolled_300",
                                          "float4 main(float4 pos : POSITION) : POSITION {\n  float4 acc = pos;\n"
                                          "  [loop] for (int k = 0; k < 300; ++k) acc += 1;\n  return acc;\n}\n",
                                          "vs_2_0");
    EXPECT_NE(err.find("flow_rolled_300.hlsl(3,1): error: a rolled loop's count must be 0..255"), std::string::npos)
        << err;
}

// The counter read as a value (rep has none): a float temp counts along, 0 before rep, + 1 before
// endrep. acc = pos + 0 + 1 + 2 for n = 3.
TEST(HlslFlow, LoopCounterReadAsAValueIsAFloatTemp) {
    const auto vs = compile("flow_counter",
                            "int n;\nfloat4 main(float4 pos : POSITION) : POSITION {\n  float4 acc = pos;\n"
                            "  for (int i = 0; i < n; i++) acc += i;\n  return acc;\n}\n",
                            "vs_2_0");
    ASSERT_FALSE(vs.empty());
    EXPECT_TRUE(has_line(disassembly(vs), "rep i0"));
    expect_near(run_output(vs, "--input v0=1,2,3,4 --int i0=3,0,0,0", "oPos"), {4, 5, 6, 7});
    expect_near(run_output(vs, "--input v0=1,2,3,4 --int i0=0,0,0,0", "oPos"), {1, 2, 3, 4});
}

// The source document's Program 2.4 (000 l.1687, samples/shaders/documents): per-vertex Phong
// over n_lights lights, lights[i] indexed by the loop counter: rep i0 with a float counter, each member read at c[a0.x + m] after
// mova a0.x, i * 4 (a T_LIGHT takes 4 registers: pos c0, col_diff c1, col_spec c2, pn c3.x).
// Inputs: pos (0,0,0), n (0,0,1), col (1,1,1); eye_pos (0,0,1): eye = (0,0,1), eye_rfl = (0,0,-1).
// Light 0 at (0,0,-2): light = (0,0,-1), diffuse max(0, -1) = 0, specular pow(1, 2) = 1: + col_spec0
// = (0.25, 0.5, 0.125). Light 1 at (3,0,4): light = (0.6, 0, 0.8), diffuse 0.8 * (0.5, 0.25, 1)
// = (0.4, 0.2, 0.8), col_spec1 = 0. Two lights: (0.65, 0.7, 0.925); one: (0.25, 0.5, 0.125).
TEST(HlslFlow, Program24IndexesTheLightsWithTheLoopCounter) {
    const std::string listing = std::string(SM2_SOURCE_DIR) + "/samples/shaders/documents/000_program_2_4.vs.hlsl";
    const std::string vs = tmp("program24.bin");
    const cli_support::Run compiled = sm2("compile " + listing + " -T vs_2_0 -E vmain -o " + vs);
    ASSERT_EQ(compiled.status, 0) << compiled.err;
    const auto lines = disassembly(vs);
    EXPECT_TRUE(has_line(lines, "rep i0"));
    EXPECT_TRUE(std::any_of(lines.begin(), lines.end(), [](const std::string& l) { return l.find("c[a0.x + 1]") != std::string::npos; }));
    EXPECT_TRUE(std::any_of(lines.begin(), lines.end(), [](const std::string& l) { return l.rfind("mova a0.x", 0) == 0; }));
    const std::string inputs = " --input v0=0,0,0 --input v1=0,0,1 --input v2=1,1,1"
                               " --const c0=0,0,-2,0 --const c1=0,0,0,0 --const c2=0.25,0.5,0.125,0 --const c3=2,0,0,0"
                               " --const c4=3,0,4,0 --const c5=0.5,0.25,1,0 --const c6=0,0,0,0 --const c7=1,0,0,0"
                               " --const c32=1,0,0,0 --const c33=0,1,0,0 --const c34=0,0,1,0 --const c35=0,0,0,1"
                               " --const eye_pos=0,0,1,0";
    expect_near(run_output(vs, "--int i0=2,0,0,0" + inputs, "oD0.xyz"), {0.65f, 0.7f, 0.925f});
    expect_near(run_output(vs, "--int i0=1,0,0,0" + inputs, "oD0.xyz"), {0.25f, 0.5f, 0.125f});
    expect_near(run_output(vs, "--int i0=0,0,0,0" + inputs, "oPos"), {0, 0, 0, 1});
}

// One component of an element indexed by the counter: c[a0.x + n].w. v[k] = (k, 0, 0, 10 k + 1) in
// c0..c3: the sum of .w over 3 iterations is 1 + 11 + 21 = 33; over 4, 33 + 31 = 64.
TEST(HlslFlow, ComponentOfAnElementIndexedByTheCounter) {
    const auto vs = compile("flow_component",
                            "int n;\nfloat4 v[4];\nfloat4 main(float4 pos : POSITION) : POSITION {\n  float acc = 0;\n"
                            "  for (int i = 0; i < n; i++) acc += v[i].w;\n  return float4(acc, pos.yzw);\n}\n",
                            "vs_2_0");
    ASSERT_FALSE(vs.empty());
    const std::string consts = " --input v0=0,1,2,3 --const c0=0,0,0,1 --const c1=1,0,0,11 --const c2=2,0,0,21 --const c3=3,0,0,31";
    expect_near(run_output(vs, "--int i0=3,0,0,0" + consts, "oPos"), {33, 1, 2, 3});
    expect_near(run_output(vs, "--int i0=4,0,0,0" + consts, "oPos"), {64, 1, 2, 3});
}
