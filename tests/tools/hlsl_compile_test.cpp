// sm2 compile: HLSL compiled to vs_2_0/ps_2_0, then executed with `sm2 run` on chosen inputs; the
// expected outputs are worked out by hand in the comments.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "cli_support.h"
#include "hlsl_support.h"

using namespace cli_support;
using namespace hlsl_support;

namespace {

// Per lane of `sm2 run --lanes`: "killed" for a lane texkill discarded, else oC0's values as printed.
std::vector<std::string> lane_results(const std::string& shader, const std::string& csv, const std::string& args = "") {
    static int counter = 0;
    const std::string lanes = tmp("lanes" + std::to_string(counter++) + ".csv");
    write_file(lanes, csv);
    const cli_support::Run r = sm2("run " + shader + " --lanes " + lanes + " " + args);
    EXPECT_EQ(r.status, 0) << r.err;
    std::vector<std::string> out;
    std::istringstream lines(r.out);
    for (std::string line; std::getline(lines, line);) {
        if (line.rfind("lane ", 0) != 0) continue;
        const size_t colon = line.find(": ");
        const std::string rest = colon == std::string::npos ? line : line.substr(colon + 2);
        out.push_back(rest.rfind("killed", 0) == 0 ? "killed" : rest.rfind("oC0 = ", 0) == 0 ? rest.substr(6) : rest);
    }
    return out;
}

bool has_texkill(const std::string& shader) {
    const cli_support::Run r = sm2("dis " + shader);
    return r.status == 0 && r.out.find("texkill r") != std::string::npos;
}

constexpr const char* kMatrixColumns =  // c0..c3 = (1,0,0,0) (0,2,0,0) (0,0,3,0) (1,1,1,1)
    " --const c0=1,0,0,0 --const c1=0,2,0,0 --const c2=0,0,3,0 --const c3=1,1,1,1";

}  // namespace

TEST(HlslCompile, ConstantColourPixelShader) {
    const auto ps = compile("red", "float4 main() : COLOR { return float4(1, 0.5, 0.25, 1); }\n", "ps_2_0");
    ASSERT_FALSE(ps.empty());
    expect_near(run_output(ps, "", "oC0"), {1, 0.5f, 0.25f, 1});
}

TEST(HlslCompile, SplatConstantFillsTheWholeOutput) {
    // A vector of equal literals is one def component seen through a replicate swizzle, here the
    // second one (0.5 comes first): uv.x * 0.5 + 0.25 = 0.75 in every component for uv.x = 1.
    const auto ps = compile("splat",
                            "float4 main(float2 uv : TEXCOORD0) : COLOR {\n"
                            "  return uv.x * 0.5 + float4(0.25, 0.25, 0.25, 0.25);\n}\n", "ps_2_0");
    ASSERT_FALSE(ps.empty());
    expect_near(run_output(ps, "--input t0=1,0", "oC0"), {0.75f, 0.75f, 0.75f, 0.75f});
    // A scalar returned as float4 is the same splat.
    const auto scalar = compile("splat_scalar", "float4 main() : COLOR { return 0.5; }\n", "ps_2_0");
    ASSERT_FALSE(scalar.empty());
    expect_near(run_output(scalar, "", "oC0"), {0.5f, 0.5f, 0.5f, 0.5f});
}

TEST(HlslCompile, VertexShaderTransformsAndPassesTexcoord) {
    // float4x4 is column_major: c0..c3 hold M's columns, so mul(pos, M).j = dot(pos, c_j):
    // pos (1,2,3,1) -> (1, 4, 9, 1+2+3+1 = 7). uv * 2: (0.25, 0.75) -> (0.5, 1.5).
    const auto vs = compile("xform",
                            "float4x4 mvp;\n"
                            "struct VSOut { float4 pos : POSITION; float2 uv : TEXCOORD0; };\n"
                            "VSOut main(float4 pos : POSITION, float2 uv : TEXCOORD0) {\n"
                            "  VSOut o; o.pos = mul(pos, mvp); o.uv = uv * 2; return o;\n}\n",
                            "vs_2_0");
    ASSERT_FALSE(vs.empty());
    const std::string inputs = std::string(" --input v0=1,2,3,1 --input v1=0.25,0.75") + kMatrixColumns;
    expect_near(run_output(vs, inputs, "oPos"), {1, 4, 9, 7});
    expect_near(run_output(vs, inputs, "oT0.xy"), {0.5f, 1.5f});
}

TEST(HlslCompile, RowMajorMatrixHoldsRowsInRegisters) {
    // row_major: c0..c3 are M's rows. mul(pos, M) = sum_i pos_i * row_i
    // = 1*(1,0,0,0) + 2*(0,2,0,0) + 3*(0,0,3,0) + 1*(1,1,1,1) = (2, 5, 10, 1);
    // mul(M, pos).i = dot(row_i, pos) = (1, 4, 9, 7).
    const auto vs = compile("rowmajor",
                            "row_major float4x4 m;\n"
                            "void main(float4 pos : POSITION, out float4 o : POSITION, out float4 c : COLOR0) {\n"
                            "  o = mul(pos, m); c = mul(m, pos);\n}\n",
                            "vs_2_0");
    ASSERT_FALSE(vs.empty());
    const std::string inputs = std::string(" --input v0=1,2,3,1") + kMatrixColumns;
    expect_near(run_output(vs, inputs, "oPos"), {2, 5, 10, 1});
    expect_near(run_output(vs, inputs, "oD0"), {1, 4, 9, 7});
}

TEST(HlslCompile, SwizzlesAndArithmetic) {
    // k = (1,2,3,4): k.wzyx * 2 + k.yzwx = (8,6,4,2) + (2,3,4,1) = (10, 9, 8, 3);
    // ps_2_0 has no .yzwx swizzle, so this also checks the per-component moves.
    const auto ps = compile("swizzle", "float4 k;\nfloat4 main() : COLOR { return k.wzyx * 2 + k.yzwx; }\n", "ps_2_0");
    ASSERT_FALSE(ps.empty());
    expect_near(run_output(ps, "--const c0=1,2,3,4", "oC0"), {10, 9, 8, 3});
}

TEST(HlslCompile, AssigningOneComponentOfAVector) {
    // c = tex (here the constant k = (0.5, 0.25, 1, 0.8)) with c.w scaled by s = 0.5 and c.y set
    // to 2: (0.5, 2, 1, 0.4). glslang writes these as OpCompositeInsert.
    const auto ps = compile("insert",
                            "float4 k : register(c1);\nfloat s : register(c0);\n"
                            "float4 main() : COLOR { float4 c = k; c.w *= s; c.y = 2; return c; }\n", "ps_2_0");
    ASSERT_FALSE(ps.empty());
    expect_near(run_output(ps, "--const c0=0.5,0,0,0 --const c1=0.5,0.25,1,0.8", "oC0"), {0.5f, 2, 1, 0.4f});
}

TEST(HlslCompile, ReflectAndArraysOfStructs) {
    // reflect(i, n) = i - 2 dot(n, i) n: i = (1, -1, 0.5), n = (0, 1, 0): dot = -1,
    // i + 2 n = (1, 1, 0.5). The struct L takes 2 registers (pos, pn), so lights[0] is c0..c1 and
    // lights[1] c2..c3: lights[1].pos = c2 = (0, 0, 1), lights[0].pn = c1.x = 3;
    // (1, 1, 0.5) + (0, 0, 1) * 3 = (1, 1, 3.5).
    const auto ps = compile("reflect",
                            "struct L { float3 pos; float pn; };\nL lights[2];\n"
                            "float4 main(float3 i : TEXCOORD0, float3 n : TEXCOORD1) : COLOR {\n"
                            "  return float4(reflect(i, n) + lights[1].pos * lights[0].pn, 1);\n}\n", "ps_2_0");
    ASSERT_FALSE(ps.empty());
    expect_near(run_output(ps, "--input t0=1,-1,0.5 --input t1=0,1,0 --const c1=3,0,0,0 --const c2=0,0,1,0", "oC0"),
                {1, 1, 3.5f, 1});
}

TEST(HlslCompile, ScalarConditionSelectsAVector) {
    // flag > 0 ? k.xyz : 0, the comparison splat over three components: k = (0.25, 0.5, 0.75)
    // where flag = 1, zeros where flag = 0.
    const auto ps = compile("select_splat",
                            "float4 k;\nfloat flag;\n"
                            "float4 main() : COLOR { return float4(flag > 0 ? k.xyz : 0, 1); }\n", "ps_2_0");
    ASSERT_FALSE(ps.empty());
    expect_near(run_output(ps, "--const c0=0.25,0.5,0.75,1 --const c1=1,0,0,0", "oC0"), {0.25f, 0.5f, 0.75f, 1});
    expect_near(run_output(ps, "--const c0=0.25,0.5,0.75,1 --const c1=0,0,0,0", "oC0"), {0, 0, 0, 1});
}

TEST(HlslCompile, Intrinsics) {
    // u = (4, 16, 0.25, 3): sqrt(4) = 2, rsqrt(16) = 0.25, lerp(2, 6, 0.25) = 3, max(3, 1) - min(3, 1) = 2.
    const auto ps = compile("intrinsics",
                            "float4 u;\n"
                            "float4 main() : COLOR {\n"
                            "  return float4(sqrt(u.x), rsqrt(u.y), lerp(2.0, 6.0, u.z), max(u.w, 1) - min(u.w, 1));\n}\n",
                            "ps_2_0");
    ASSERT_FALSE(ps.empty());
    expect_near(run_output(ps, "--const c0=4,16,0.25,3", "oC0"), {2, 0.25f, 3, 2}, 1e-4f);
    // normalize(a), dot, saturate and abs:
    const auto ps2 = compile("intrinsics2",
                             "float3 a; float3 b;\n"
                             "float4 main() : COLOR {\n"
                             "  float3 n = normalize(a);\n"
                             "  return float4(n.x, n.z, dot(b, b.zyx), saturate(b.z) + abs(-b.x));\n}\n",
                             "ps_2_0");
    ASSERT_FALSE(ps2.empty());
    // a = (3,0,4) in c0, b = (1,2,3) in c1: dot((1,2,3),(3,2,1)) = 10; saturate(3) + abs(-1) = 2.
    expect_near(run_output(ps2, "--const c0=3,0,4,0 --const c1=1,2,3,0", "oC0"), {0.6f, 0.8f, 10, 2}, 1e-4f);
}

TEST(HlslCompile, SelectBecomesCmp) {
    // x > 0.5 ? 1 : 0.25 on t0.x, and a static branch folded by -D.
    const std::string hlsl =
        "float4 main(float2 uv : TEXCOORD0) : COLOR {\n"
        "  float x = uv.x > 0.5 ? 1.0 : 0.25;\n"
        "#if MODE == 1\n  x = x * 4;\n#endif\n"
        "  return float4(x, uv.y, 0, 1);\n}\n";
    const auto ps = compile("select", hlsl, "ps_2_0");
    ASSERT_FALSE(ps.empty());
    expect_near(run_output(ps, "--input t0=0.75,0.5", "oC0"), {1, 0.5f, 0, 1});
    expect_near(run_output(ps, "--input t0=0.25,0.5", "oC0"), {0.25f, 0.5f, 0, 1});
    const auto ps4 = compile("select4", hlsl, "ps_2_0", "-D MODE=1");
    ASSERT_FALSE(ps4.empty());
    expect_near(run_output(ps4, "--input t0=0.25,0.5", "oC0"), {1, 0.5f, 0, 1});
}

TEST(HlslCompile, SelectInVertexShader) {
    // vs_2_0 has no cmp: sge and lrp. c0.x = 2: (2 >= 1) -> 5, else 7.
    const auto vs = compile("vselect",
                            "float4 k;\n"
                            "float4 main(float4 p : POSITION) : POSITION { return float4(k.x >= 1 ? 5 : 7, p.yzw); }\n",
                            "vs_2_0");
    ASSERT_FALSE(vs.empty());
    expect_near(run_output(vs, "--input v0=0,1,2,3 --const c0=2,0,0,0", "oPos"), {5, 1, 2, 3});
    expect_near(run_output(vs, "--input v0=0,1,2,3 --const c0=0.5,0,0,0", "oPos"), {7, 1, 2, 3});
}

TEST(HlslCompile, TextureSampling) {
    // A 2x2 TGA, top row red then green, bottom row blue then white; POINT sampling at
    // (0.75, 0.25) reads the green texel: (0,1,0,1) * 0.5 + (0,0,0.25,0) = (0, 0.5, 0.25, 0.5).
    const std::string tga = tmp("texture.tga");
    std::string bytes(18, '\0');
    bytes[2] = 2;                     // uncompressed true colour
    bytes[12] = 2;                    // width
    bytes[14] = 2;                    // height
    bytes[16] = 32;                   // bits per pixel
    bytes[17] = 0x28;                 // top-left origin, 8 alpha bits
    const unsigned char pixels[] = {0, 0, 255, 255, 0, 255, 0, 255,         // red, green (BGRA)
                                    255, 0, 0, 255, 255, 255, 255, 255};   // blue, white
    bytes.append(reinterpret_cast<const char*>(pixels), sizeof pixels);
    write_file(tga, bytes);
    const auto ps = compile("texture",
                            "sampler2D tex;\n"
                            "float4 main(float2 uv : TEXCOORD0) : COLOR { return tex2D(tex, uv) * 0.5 + float4(0, 0, 0.25, 0); }\n",
                            "ps_2_0");
    ASSERT_FALSE(ps.empty());
    expect_near(run_output(ps, "--texture s0=" + tga + " --input t0=0.75,0.25", "oC0"), {0, 0.5f, 0.25f, 0.5f});
}

TEST(HlslCompile, ErrorsAreLocatedInTheHlsl) {
    const std::string bad = tmp("bad.hlsl");
    write_file(bad, "float4 main() : COLOR {\n  return undefined_thing;\n}\n");
    cli_support::Run r = sm2("compile " + bad + " -T ps_2_0");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("bad.hlsl(2,"), std::string::npos) << r.err;

    // Sampling in vs_2_0: no texld there; the error names the line of the tex2D.
    const std::string vs = tmp("vstex.hlsl");
    write_file(vs, "sampler2D s;\nfloat4 main(float2 uv : TEXCOORD0) : POSITION {\n  return tex2D(s, uv);\n}\n");
    r = sm2("compile " + vs + " -T vs_2_0");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("vstex.hlsl(3,"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("vs_3_0"), std::string::npos) << r.err;

    // A loop on a run-time value that needs real flow control.
    const std::string branch = tmp("branch.hlsl");
    write_file(branch, "float4 main(float2 uv : TEXCOORD0) : COLOR {\n  float x = uv.x;\n  while (x < 1) x = x * 2;\n"
                       "  return x;\n}\n");
    r = sm2("compile " + branch + " -T ps_2_0");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("branch.hlsl("), std::string::npos) << r.err;

    EXPECT_EQ(sm2("compile " + bad + " -T ps_3_0").status, 2);
    EXPECT_EQ(sm2("compile " + bad + " -T ps_2_0 -D 1X=2").status, 2);
}

TEST(HlslCompile, StructsAndNamedEntryPoint) {
    // The source document's Program 3.1 (Gouraud pass-through), entry point PShader.
    const auto ps = compile("gouraud",
                            "struct T_PIN { float4 col : COLOR0; };\n"
                            "struct T_POUT { float4 col : COLOR0; };\n"
                            "T_POUT PShader(T_PIN pin) { T_POUT pout; pout.col = pin.col; return pout; }\n",
                            "ps_2_0", "-E PShader");
    ASSERT_FALSE(ps.empty());
    expect_near(run_output(ps, "--input v0=0.1,0.2,0.3,0.4", "oC0"), {0.1f, 0.2f, 0.3f, 0.4f});
}

TEST(HlslCompile, SinCosWithRangeReduction) {
    // The waving lake: h = sin(2x + t) * 0.5 + cos(z + t) * 0.25 at x = 0.5, z = 0.25, t = 0.3:
    // sin(1.3) = 0.963558, cos(0.55) = 0.852525 -> h = 0.481779 + 0.213131 = 0.694910.
    // With the identity in c0..c3, oPos = (x, h, z, 1).
    const auto vs = compile("lake",
                            "float4x4 mvp; float time;\n"
                            "struct VOut { float4 pos : POSITION; float4 col : COLOR0; };\n"
                            "VOut main(float4 p : POSITION) {\n"
                            "  VOut o;\n"
                            "  float h = sin(p.x * 2 + time) * 0.5 + cos(p.z + time) * 0.25;\n"
                            "  o.pos = mul(float4(p.x, h, p.z, 1), mvp);\n"
                            "  o.col = float4(h, h, 1, 1);\n"
                            "  return o;\n}\n",
                            "vs_2_0");
    ASSERT_FALSE(vs.empty());
    const std::string args = "--input v0=0.5,0,0.25,1 --const c0=1,0,0,0 --const c1=0,1,0,0 --const c2=0,0,1,0 "
                             "--const c3=0,0,0,1 --const c4=0.3,0,0,0";
    expect_near(run_output(vs, args, "oPos"), {0.5f, 0.69491f, 0.25f, 1}, 1e-4f);
}

TEST(HlslCompile, IncludeFolderAndDefines) {
    // #include <scale.h> from -I; SCALE from -D: 0.5 * 3 = 1.5.
    const std::string dir = tmp("include_dir");
    std::filesystem::create_directories(dir);
    write_file(dir + "/scale.h", "float scaled(float x) { return x * SCALE; }\n");
    const auto ps = compile("include", "#include <scale.h>\nfloat4 main() : COLOR { return float4(scaled(0.5), 0, 0, 1); }\n",
                            "ps_2_0", "-I " + dir + " -D SCALE=3");
    ASSERT_FALSE(ps.empty());
    expect_near(run_output(ps, "", "oC0"), {1.5f, 0, 0, 1});
}

TEST(HlslCompile, LoopsAreUnrolledAndTheSlotLimitIsLocated) {
    // x = x * x + 0.5 three times from 0.5: 0.75, 1.0625, 1.62890625.
    const std::string loop = "float4 main(float2 uv : TEXCOORD0) : COLOR {\n  float x = uv.x;\n"
                             "  for (int i = 0; i < COUNT; i++) x = x * x + 0.5;\n  return x;\n}\n";
    const auto ps = compile("loop3", loop, "ps_2_0", "-D COUNT=3");
    ASSERT_FALSE(ps.empty());
    expect_near(run_output(ps, "--input t0=0.5,0", "oC0"), {1.62890625f, 1.62890625f, 1.62890625f, 1.62890625f});
    // 70 mads do not fit ps_2_0's 64 arithmetic slots: the error names the limit and the loop's line.
    const std::string source = tmp("loop70.hlsl");
    write_file(source, loop);
    const cli_support::Run r = sm2("compile " + source + " -T ps_2_0 -D COUNT=70");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("loop70.hlsl(3,"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("the limit is 64"), std::string::npos) << r.err;
}

TEST(HlslCompile, FxcErrorsCarryFxcNumbers) {
    // Each line is fxc's `file(line,col): error X####: message`; glslang gives no columns (1).
    auto errors_of = [](const std::string& name, const std::string& hlsl, const std::string& profile) {
        const std::string source = tmp(name);
        write_file(source, hlsl);
        const cli_support::Run r = sm2("compile " + source + " -T " + profile + " --fxc-errors");
        EXPECT_EQ(r.status, 1);
        return r.err;
    };
    const std::string syntax = errors_of("fxc_syntax.hlsl", "float4 main() : COLOR {\n  return 1 +;\n}\n", "ps_2_0");
    EXPECT_EQ(syntax.rfind(tmp("fxc_syntax.hlsl") + "(2,1): error X3000: 'expression' : Expected\n", 0), 0u) << syntax;
    const std::string undeclared =
        errors_of("fxc_undeclared.hlsl", "float4 main() : COLOR {\n  return undefined_thing;\n}\n", "ps_2_0");
    EXPECT_NE(undeclared.find("fxc_undeclared.hlsl(2,1): error X3004: 'undefined_thing' : unknown variable"),
              std::string::npos) << undeclared;
    const std::string redefined =
        errors_of("fxc_redefined.hlsl", "float4 main() : COLOR {\n  float a;\n  float a;\n  return a;\n}\n", "ps_2_0");
    EXPECT_NE(redefined.find("fxc_redefined.hlsl(3,1): error X3003: 'a' : redefinition"), std::string::npos) << redefined;
    const std::string no_entry = errors_of("fxc_entry.hlsl", "float4 other() : COLOR { return 1; }\n", "ps_2_0");
    EXPECT_NE(no_entry.find("fxc_entry.hlsl: error X3501: link failed (is the entry point 'main' defined?)"),
              std::string::npos) << no_entry;
    // 65 dependent mads: the 65th passes ps_2_0's 64 arithmetic slots (fxc's X5608), at the loop's line.
    const std::string slots = errors_of("fxc_slots.hlsl",
                                        "float4 main(float2 uv : TEXCOORD0) : COLOR {\n  float x = uv.x;\n"
                                        "  for (int i = 0; i < 70; i++) x = x * x + 0.5;\n  return x;\n}\n",
                                        "ps_2_0");
    EXPECT_NE(slots.find("fxc_slots.hlsl(3,1): error X5608: [slot-budget] mad: uses arithmetic instruction slot 65; "
                         "the limit is 64"),
              std::string::npos) << slots;
    // What the profile cannot express: X4532, fxc's "cannot map expression to vs_2_0 instruction set".
    const std::string vs_texture = errors_of(
        "fxc_vstex.hlsl", "sampler2D s;\nfloat4 main(float2 uv : TEXCOORD0) : POSITION {\n  return tex2D(s, uv);\n}\n",
        "vs_2_0");
    EXPECT_NE(vs_texture.find("fxc_vstex.hlsl(3,1): error X4532: texture sampling in a vertex shader needs vs_3_0"),
              std::string::npos) << vs_texture;
    // The glslang crash sm2 guards against (a global declared again with another type).
    const std::string crash = errors_of("fxc_crash.hlsl", "sampler2D tex; float4 tex;\n", "ps_2_0");
    EXPECT_NE(crash.find("fxc_crash.hlsl(1,1): error X3000: the HLSL front end (glslang) crashed on this input"),
              std::string::npos) << crash;
}

TEST(HlslCompile, DisassemblyShowsTheConstantTable) {
    const auto ps = compile("ctab",
                            "float4 tint = float4(1, 0.5, 0.25, 1);\nrow_major float4x4 world;\nsampler2D diffuse;\n"
                            "float4 main(float2 uv : TEXCOORD0) : COLOR { return tex2D(diffuse, uv) * tint + world[2]; }\n",
                            "ps_2_0");
    ASSERT_FALSE(ps.empty());
    const cli_support::Run r = sm2("dis " + ps);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("target ps_2_0, creator \"sm2emu sm2 compile (glslang HLSL, SPIRV-Tools, sm2 back end)\""),
              std::string::npos) << r.out;
    // name, type, first register, count (and defaults): tint c0, world c1..c4 (rows), diffuse s0.
    EXPECT_NE(r.out.find("tint     float4              c0        1  default {1, 0.5, 0.25, 1}"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("world    row_major float4x4  c1        4"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("diffuse  sampler2D           s0        1"), std::string::npos) << r.out;
}

TEST(HlslCompile, RunSetsUniformsByTheirNames) {
    // --const NAME fills the named registers four values at a time: tint = c0, world = c1..c4 (rows),
    // so world[2] is c3 = (10, 20, 30, 40); tint + world[2] = (11, 22, 33, 44).
    const auto ps = compile("named", "float4 tint;\nrow_major float4x4 world;\n"
                                     "float4 main() : COLOR { return tint + world[2]; }\n", "ps_2_0");
    ASSERT_FALSE(ps.empty());
    expect_near(run_output(ps, "--const tint=1,2,3,4 --const world=0,0,0,0,0,0,0,0,10,20,30,40,0,0,0,0", "oC0"),
                {11, 22, 33, 44});
}

TEST(HlslCompile, DebugInfoAddsTheLineTableThatDisAndAsmRoundTrip) {
    const std::string hlsl = "float3 light;\n"                                   // 1
                             "float4 main(float3 n : TEXCOORD0) : COLOR\n"        // 2
                             "{\n"                                                 // 3
                             "    float d = dot(n, light);\n"                     // 4: dp3
                             "    return d;\n"                                    // 5: mov oC0
                             "}\n";
    const auto plain = compile("lines_plain", hlsl, "ps_2_0");
    const auto with = compile("lines_g", hlsl, "ps_2_0", "--debug-info");
    ASSERT_FALSE(plain.empty() || with.empty());
    const std::string plain_bytes = slurp(plain), with_bytes = slurp(with);
    EXPECT_GT(with_bytes.size(), plain_bytes.size());
    const cli_support::Run plain_dis = sm2("dis " + plain);
    EXPECT_EQ(plain_dis.out.find("SM2L"), std::string::npos) << plain_dis.out;
    const cli_support::Run dis = sm2("dis " + with);
    ASSERT_EQ(dis.status, 0) << dis.err;
    EXPECT_NE(dis.out.find("// SM2L HLSL line table, "), std::string::npos) << dis.out;
    const std::string source = tmp("lines_g.hlsl");
    EXPECT_NE(dis.out.find("//   " + source + ":4 (instructions "), std::string::npos) << dis.out;
    EXPECT_NE(dis.out.find("):     float d = dot(n, light);\n"), std::string::npos) << dis.out;
    // sm2 asm of sm2 dis's text: the same bytes, the block included.
    const std::string text = tmp("lines_g.asm"), again = tmp("lines_g_again.bin");
    write_file(text, dis.out);
    ASSERT_EQ(sm2("asm " + text + " -o " + again).status, 0);
    EXPECT_EQ(slurp(again), with_bytes);
    // The short -g too; and the shader runs the same with the table: d = 1*1 + 2*0.5 + 3*0 = 2.
    const auto g = compile("lines_short_g", hlsl, "ps_2_0", "-g");
    ASSERT_FALSE(g.empty());
    for (const auto& shader : {plain, with, g})
        expect_near(run_output(shader, "--input t0=1,2,3,0 --const light=1,0.5,0", "oC0"), {2, 2, 2, 2});
}

TEST(HlslCompile, DiscardInAnIfBecomesTexkill) {
    // if (uv.x > 0.5) discard: texkill of 0.5 - uv.x, negative exactly when uv.x > 0.5 (0.5 itself lives).
    const auto ps = compile("discard_if",
                            "float4 main(float2 uv : TEXCOORD0) : COLOR {\n  if (uv.x > 0.5) discard;\n"
                            "  return float4(uv, 0, 1);\n}\n", "ps_2_0");
    ASSERT_FALSE(ps.empty());
    EXPECT_TRUE(has_texkill(ps));
    EXPECT_EQ(lane_results(ps, "t0.x,t0.y\n0.75,0.5\n0.25,0.5\n0.5,0.125\n0.625,0\n"),
              (std::vector<std::string>{"killed", "0.25 0.5 0 1", "0.5 0.125 0 1", "killed"}));
    // <= and == against uniforms need cmp (texkill kills on < 0 only): k = (0.25, 2).
    // Lane 0 (y 0.5, z 0) lives; lane 1 (y 0.25 <= 0.25) dies; lane 2 (z 2 == 2) dies; lane 3 lives.
    const auto ps2 = compile("discard_cmp",
                             "float2 k;\n"
                             "float4 main(float4 a : TEXCOORD0) : COLOR {\n  if (a.y <= k.x) discard;\n"
                             "  if (a.z == k.y) discard;\n  return a;\n}\n", "ps_2_0");
    ASSERT_FALSE(ps2.empty());
    EXPECT_EQ(lane_results(ps2, "t0.x,t0.y,t0.z,t0.w\n1,0.5,0,1\n1,0.25,0,1\n1,0.5,2,1\n1,0.5,2.5,1\n",
                           "--const k=0.25,2,0,0"),
              (std::vector<std::string>{"1 0.5 0 1", "killed", "killed", "1 0.5 2.5 1"}));
    // `else discard`: the kill on the branch's false arm, negative exactly when a.x < 0.5 fails.
    const auto ps3 = compile("discard_else",
                             "float4 main(float4 a : TEXCOORD0) : COLOR {\n  float4 c = a;\n"
                             "  if (a.x < 0.5) c = a * 2; else discard;\n  return c;\n}\n", "ps_2_0");
    ASSERT_FALSE(ps3.empty());
    EXPECT_EQ(lane_results(ps3, "t0.x,t0.y\n0.25,1\n0.5,1\n0.75,1\n0,0\n"),
              (std::vector<std::string>{"0.5 2 0 2", "killed", "killed", "0 0 0 2"}));
}

TEST(HlslCompile, ClipBecomesTexkill) {
    // clip(a.xy - 0.25): dies where a.x or a.y is below 0.25; a.z (not clipped) negative does not kill.
    const auto ps = compile("clip2",
                            "float4 main(float4 a : TEXCOORD0) : COLOR {\n  clip(a.xy - 0.25);\n  return a * 2;\n}\n",
                            "ps_2_0");
    ASSERT_FALSE(ps.empty());
    EXPECT_TRUE(has_texkill(ps));
    EXPECT_EQ(lane_results(ps, "t0.x,t0.y,t0.z,t0.w\n0.5,0.5,-1,1\n0.125,0.5,0,1\n0.5,0.125,0,1\n0.25,0.25,0,1\n"),
              (std::vector<std::string>{"1 1 -2 2", "killed", "killed", "0.5 0.5 0 2"}));
    // A scalar: clip(a.z) dies below 0 only (0 lives); a float3 with its w beyond: clip(a.xyz).
    const auto ps1 = compile("clip1", "float4 main(float4 a : TEXCOORD0) : COLOR {\n  clip(a.z);\n  return a;\n}\n",
                             "ps_2_0");
    ASSERT_FALSE(ps1.empty());
    EXPECT_EQ(lane_results(ps1, "t0.x,t0.y,t0.z,t0.w\n-1,-1,-0.125,1\n-1,-1,0,-1\n"),
              (std::vector<std::string>{"killed", "-1 -1 0 -1"}));
    const auto ps3 = compile("clip3", "float4 main(float4 a : TEXCOORD0) : COLOR {\n  clip(a.xyz);\n  return a;\n}\n",
                             "ps_2_0");
    ASSERT_FALSE(ps3.empty());
    EXPECT_EQ(lane_results(ps3, "t0.x,t0.y,t0.z,t0.w\n0,0,0,-1\n0,0,-0.5,1\n"),
              (std::vector<std::string>{"0 0 0 -1", "killed"}));
}

TEST(HlslCompile, UnconditionalDiscardKillsEveryPixel) {
    const auto ps = compile("discard_all", "float4 main(float4 a : TEXCOORD0) : COLOR {\n  discard;\n  return a;\n}\n",
                            "ps_2_0");
    ASSERT_FALSE(ps.empty());
    EXPECT_TRUE(has_texkill(ps));
    EXPECT_EQ(lane_results(ps, "t0.x\n1\n-1\n"), (std::vector<std::string>{"killed", "killed"}));
    // vs_2_0 has no texkill: a discard there stays an error (glslang or the back end).
    const std::string vs = tmp("vs_discard.hlsl");
    write_file(vs, "float4 main(float4 p : POSITION) : POSITION {\n  if (p.x > 0) discard;\n  return p;\n}\n");
    EXPECT_EQ(sm2("compile " + vs + " -T vs_2_0").status, 1);
}

TEST(HlslCompile, SaturateFoldsIntoTheInstructionAndOneOverXIsRcp) {
    // saturate(dot(a, b)) of a value nothing else reads: dp3_sat; 1 / x: rcp alone.
    // a = (1, 2, 2), b = (0.5, 0.5, 0) in c0, c1: dot = 1.5 -> 1; 1 / a.z = 0.5; dot(a, a) = 9, not saturated.
    const auto ps = compile("sat_fold",
                            "float3 a; float3 b;\n"
                            "float4 main() : COLOR {\n  return float4(saturate(dot(a, b)), 1 / a.z, dot(a, a), 0);\n}\n",
                            "ps_2_0");
    ASSERT_FALSE(ps.empty());
    const cli_support::Run dis = sm2("dis " + ps);
    EXPECT_NE(dis.out.find("dp3_sat"), std::string::npos) << dis.out;
    EXPECT_EQ(dis.out.find("mov_sat"), std::string::npos) << dis.out;
    EXPECT_EQ(dis.out.find("\nmul"), std::string::npos) << dis.out;
    expect_near(run_output(ps, "--const c0=1,2,2,0 --const c1=0.5,0.5,0,0", "oC0"), {1, 0.5f, 9, 0});
}
