// sm2 pixel --target and its shader inputs, and sm2 debug (pixel and vertex shaders stepped one
// source instruction at a time), on small streams whose values are worked out by hand below and
// checked against sm2 run on the same inputs.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_support.h"

namespace {

using Result = cli_support::Run;
using cli_support::sm2;
using cli_support::tmp;
using cli_support::write_file;

const std::string kSource = SM2_SOURCE_DIR;
const std::string kShaderTrace = "/work/shared/traces/shader_scene.trace";

void expect_vec(const nlohmann::json& v, double x, double y, double z, double w, const std::string& what,
                double tolerance = 1e-5) {
    ASSERT_TRUE(v.is_array() && v.size() == 4) << what << ": " << v.dump();
    EXPECT_NEAR(v[0].get<double>(), x, tolerance) << what;
    EXPECT_NEAR(v[1].get<double>(), y, tolerance) << what;
    EXPECT_NEAR(v[2].get<double>(), z, tolerance) << what;
    EXPECT_NEAR(v[3].get<double>(), w, tolerance) << what;
}

nlohmann::json run_json(const std::string& args) {
    const Result r = sm2(args + " --json");
    EXPECT_EQ(r.status, 0) << args << ": " << r.err;
    return nlohmann::json::parse(r.out, nullptr, false);
}

// The write of `reg` in a debug step ({"register", "mask", "lanes"}), or null.
nlohmann::json write_of(const nlohmann::json& step, const std::string& reg) {
    for (const auto& w : step["writes"])
        if (w["register"] == reg) return w;
    return nullptr;
}

// ---------------------------------------------------------------------------------------------
// A 4x4 target, one full-screen quad (a two-triangle strip). The vertex shader scales the
// positions (+-0.5) by 2 with an m4x4 and passes the texture coordinate through; t0 runs from
// (0, 0) at the left and top edges (x, y = -1) to (4, 4) at the right and bottom ones. D3D9
// maps x = -1 to pixel coordinate 0 and samples pixel (x, y) at (x, y) (the half-pixel offset),
// so t0 = (x, y, 0, 1) there. The pixel shader at pixel (1, 2), t0 = (1, 2, 0, 1):
//   mad r0, t0, c1.x, c0   r0 = 2 t0 + (0.25, 0.5, -1, 0)          = (2.25, 4.5, -1, 2)
//   m4x4 r1, r0, c2        rows (1,0,0,0) (0,1,0,0) (1,1,1,0) (0,0,0,0.5)
//                          r1 = (2.25, 4.5, 2.25 + 4.5 - 1, 2 * 0.5) = (2.25, 4.5, 5.75, 1)
//   mul r2, r1, c1.y       r2 = r1 / 2                              = (1.125, 2.25, 2.875, 0.5)
//   mov oC0, r2
// Its quad's lane 0 is pixel (0, 2): t0 = (0, 2), r0 = (0.25, 4.5, -1, 2), r1.z = 3.75.
const std::string kPixelShader =
    "ps_2_0\n"
    "def c1, 2, 0.5, 0, 1\n"
    "dcl t0\n"
    "mad r0, t0, c1.x, c0\n"
    "m4x4 r1, r0, c2\n"
    "mul r2, r1, c1.y\n"
    "mov oC0, r2\n";

const std::string kGradient =
    "sm2cs 1\n"
    "CreateDevice 4 4 A8R8G8B8\n"
    "CreateVertexDeclaration decl { 0 0 FLOAT3 DEFAULT POSITION 0 } { 0 12 FLOAT4 DEFAULT TEXCOORD 0 }\n"
    "CreateVertexShader vs asm<<END\nvs_2_0\ndcl_position v0\ndcl_texcoord v1\nm4x4 r0, v0, c0\nmov oPos, r0\n"
    "mov oT0, v1\nEND\n"
    "CreatePixelShader ps asm<<END\n" + kPixelShader + "END\n"
    "SetVertexDeclaration decl\n"
    "SetVertexShader vs\n"
    "SetPixelShader ps\n"
    "SetVertexShaderConstantF 0 f32[ 2 0 0 0   0 2 0 0   0 0 1 0   0 0 0 1 ]\n"
    "SetPixelShaderConstantF 0 f32[ 0.25 0.5 -1 0 ]\n"
    "SetPixelShaderConstantF 2 f32[ 1 0 0 0   0 1 0 0   1 1 1 0   0 0 0 0.5 ]\n"
    "BeginScene\n"
    "DrawPrimitiveUP TRIANGLESTRIP 2 28 f32[ -0.5 0.5 0.5  0 0 0 1   0.5 0.5 0.5  4 0 0 1"
    "   -0.5 -0.5 0.5  0 4 0 1   0.5 -0.5 0.5  4 4 0 1 ]\n"
    "EndScene\n"
    "Present\n";
constexpr int kGradientDraw = 12;

std::string gradient_stream() {
    const std::string stream = tmp("gradient.sm2cs");
    write_file(stream, kGradient);
    return stream;
}

TEST(CliPixelInputs, TheInterpolatedTexcoordOfTheWatchedPixel) {
    const auto j = run_json("pixel " + gradient_stream() + " --frame 0 --pixel 1,2");
    ASSERT_EQ(j["draws"].size(), 1u) << j.dump();
    const auto& f = j["draws"][0]["fragments"][0];
    ASSERT_TRUE(f["inputs"].contains("t0")) << f.dump();
    expect_vec(f["inputs"]["t0"], 1, 2, 0, 1, "t0 at (1, 2)");
    EXPECT_FALSE(f["inputs"].contains("v0"));  // not read by the shader
    expect_vec(f["shader_color"], 1.125, 2.25, 2.875, 0.5, "oC0");
    const Result text = sm2("pixel " + gradient_stream() + " --frame 0 --pixel 1,2");
    EXPECT_NE(text.out.find("  inputs: t0 (1, 2, 0, 1)\n"), std::string::npos) << text.out;
}

TEST(CliDebug, PixelShaderStepsWorkedOutByHand) {
    const auto j = run_json("debug " + gradient_stream() + " --frame 0 --pixel 1,2");
    ASSERT_TRUE(j.is_object()) << j.dump();
    EXPECT_EQ(j["stage"], "pixel");
    EXPECT_EQ(j["call"], kGradientDraw);
    EXPECT_EQ(j["watched_lane"], 1);  // (1, 2) in the quad at (0, 2)
    ASSERT_EQ(j["lanes"].size(), 4u);
    EXPECT_EQ(j["lanes"][3]["x"], 1);
    EXPECT_EQ(j["lanes"][3]["y"], 3);
    expect_vec(j["inputs"]["t0"][1], 1, 2, 0, 1, "t0, lane 1");
    expect_vec(j["inputs"]["t0"][2], 0, 3, 0, 1, "t0, lane 2 (0, 3)");
    // Primitive 0 is the top-left half: x + y < 3 at pixel centres, and the diagonal x + y = 3 by
    // the fill rule; (1, 3) belongs to primitive 1 and is a helper lane here.
    for (unsigned lane = 0; lane < 4; ++lane) EXPECT_EQ(j["lanes"][lane]["covered"], lane != 3) << lane;
    EXPECT_EQ(j["primitive"], 0);
    expect_vec(j["constants"]["c0"], 0.25, 0.5, -1, 0, "c0");
    expect_vec(j["constants"]["c1"], 2, 0.5, 0, 1, "c1 (def)");
    // One step per source instruction: the m4x4 is one step, not four dp4.
    ASSERT_EQ(j["steps"].size(), 4u) << j.dump();
    const std::vector<std::string> texts = {"mad r0, t0, c1.x, c0", "m4x4 r1, r0, c2", "mul r2, r1, c1.y", "mov oC0, r2"};
    for (size_t i = 0; i < texts.size(); ++i) {
        EXPECT_EQ(j["steps"][i]["text"], texts[i]);
        EXPECT_EQ(j["steps"][i]["line"], i + 4) << "line in sm2 dis: after ps_2_0, def and dcl";
    }
    const auto r0 = write_of(j["steps"][0], "r0");
    ASSERT_FALSE(r0.is_null());
    EXPECT_EQ(r0["mask"], "xyzw");
    expect_vec(r0["lanes"][1], 2.25, 4.5, -1, 2, "r0 at the pixel");
    expect_vec(r0["lanes"][0], 0.25, 4.5, -1, 2, "r0 at (0, 2)");
    const auto r1 = write_of(j["steps"][1], "r1");
    ASSERT_FALSE(r1.is_null());
    EXPECT_EQ(r1["mask"], "xyzw");
    ASSERT_EQ(j["steps"][1]["writes"].size(), 1u);
    expect_vec(r1["lanes"][1], 2.25, 4.5, 5.75, 1, "r1 at the pixel");
    EXPECT_NEAR(r1["lanes"][0][2].get<double>(), 3.75, 1e-5);
    expect_vec(write_of(j["steps"][2], "r2")["lanes"][1], 1.125, 2.25, 2.875, 0.5, "r2");
    expect_vec(write_of(j["steps"][3], "oC0")["lanes"][1], 1.125, 2.25, 2.875, 0.5, "oC0");
}

TEST(CliDebug, PixelStepsEqualSmRunOnTheSameInputs) {
    const auto j = run_json("debug " + gradient_stream() + " --frame 0 --pixel 1,2");
    ASSERT_TRUE(j.is_object());
    const std::string shader = tmp("gradient_ps.asm");
    write_file(shader, kPixelShader);
    // sm2 dis of the same shader: each step's line is its text.
    const std::string bytecode = tmp("gradient_ps.bin");
    ASSERT_EQ(sm2("asm " + shader + " -o " + bytecode).status, 0);
    const Result dis = sm2("dis " + bytecode);
    ASSERT_EQ(dis.status, 0) << dis.err;
    std::vector<std::string> lines;
    for (size_t at = 0, next; at < dis.out.size(); at = next + 1) {
        next = dis.out.find('\n', at);
        if (next == std::string::npos) next = dis.out.size();
        lines.push_back(dis.out.substr(at, next - at));
    }
    for (const auto& step : j["steps"]) {
        const size_t line = step["line"].get<size_t>();
        ASSERT_LE(line, lines.size());
        EXPECT_EQ(lines[line - 1], step["text"].get<std::string>());
    }
    // sm2 run on every lane's interpolated t0, with the draw's constants: the same oC0, bit for bit.
    for (unsigned lane = 0; lane < 4; ++lane) {
        const auto& t0 = j["inputs"]["t0"][lane];
        char input[160];
        std::snprintf(input, sizeof input, "t0=%.9g,%.9g,%.9g,%.9g", t0[0].get<double>(), t0[1].get<double>(),
                      t0[2].get<double>(), t0[3].get<double>());
        const auto run = run_json("run " + shader + " --input " + input +
                                  " --const c0=0.25,0.5,-1,0 --const c2=1,0,0,0 --const c3=0,1,0,0"
                                  " --const c4=1,1,1,0 --const c5=0,0,0,0.5");
        ASSERT_TRUE(run.contains("lanes")) << run.dump();
        const auto& oc0 = run["lanes"][0]["oC0"];
        const auto debug = write_of(j["steps"][3], "oC0")["lanes"][lane];
        EXPECT_EQ(oc0["x"].get<double>(), debug[0].get<double>()) << lane;
        EXPECT_EQ(oc0["y"].get<double>(), debug[1].get<double>()) << lane;
        EXPECT_EQ(oc0["z"].get<double>(), debug[2].get<double>()) << lane;
        EXPECT_EQ(oc0["w"].get<double>(), debug[3].get<double>()) << lane;
    }
}

TEST(CliDebug, PixelTextShowsLanesAndSteps) {
    const Result r = sm2("debug " + gradient_stream() + " --frame 0 --pixel 1,2");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("pixel shader of call 12 DrawPrimitiveUP, primitive"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("carries no HLSL line table"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("step 2, line 5: m4x4 r1, r0, c2\n  r1 (xyzw)\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("    lane 1 (1, 2): (2.25, 4.5, 5.75, 1)  <- the pixel\n"), std::string::npos) << r.out;
}

// ---------------------------------------------------------------------------------------------
// The same quad with an hlsl<< pixel shader: the stream's HLSL compiler writes the HLSL line
// table, so sm2 debug steps by HLSL line. The compiler's code, line by line (its def c2 = (2, 1,
// 0, 0); light = c0 = (1, 2, 3), tint = c1 = (0.5, 0.25, 1, 2)); at pixel (1, 2), t0 = (1, 2, 0, 1):
//   line 6  mad r0.xyz, t0, c2.x, -c2.y   n = 2 t - 1                 = (1, 3, -1)
//   line 7  dp3 r1.x, r0, c0              d = 1*1 + 3*2 - 1*3         = 4
//   line 8  (tint * d is fused into line 9's mad: no instruction of its own)
//   line 9  mad r0, c1, r1.x, t0.w        tint * 4 + 1                = (3, 2, 5, 9)
//           mov oC0, r0                   (the output's copy: the line of the value returned)
// Lane 0, pixel (0, 2): n = (-1, 3, -1), d = 2, r0 = (2, 1.5, 3, 5).
const std::string kHlslPixelShader =
    "float3 light;\n"                     // 1
    "float4 tint;\n"                      // 2
    "\n"                                  // 3
    "float4 main(float4 t : TEXCOORD0) : COLOR\n"  // 4
    "{\n"                                 // 5
    "    float3 n = t.xyz * 2 - 1;\n"     // 6
    "    float d = dot(n, light);\n"      // 7
    "    float4 c = tint * d;\n"          // 8
    "    return c + t.w;\n"               // 9
    "}\n";

std::string hlsl_stream() {
    std::string text = kGradient;
    text.replace(text.find("CreatePixelShader ps asm<<END\n" + kPixelShader + "END\n"),
                 ("CreatePixelShader ps asm<<END\n" + kPixelShader + "END\n").size(),
                 "CreatePixelShader ps hlsl<<END\n" + kHlslPixelShader + "END\n");
    text.replace(text.find("SetPixelShaderConstantF 0 f32[ 0.25 0.5 -1 0 ]\n"),
                 std::string("SetPixelShaderConstantF 0 f32[ 0.25 0.5 -1 0 ]\n").size(),
                 "SetPixelShaderConstantF 0 f32[ 1 2 3 0   0.5 0.25 1 2 ]\n");
    const std::string stream = tmp("hlsl_gradient.sm2cs");
    write_file(stream, text);
    return stream;
}

TEST(CliDebug, HlslPixelShaderStepsByHlslLine) {
    const auto j = run_json("debug " + hlsl_stream() + " --frame 0 --pixel 1,2");
    ASSERT_TRUE(j.is_object()) << j.dump();
    EXPECT_NE(j["source"].get<std::string>().find("HLSL"), std::string::npos) << j["source"];
    ASSERT_EQ(j["steps"].size(), 4u) << j.dump();
    // r2 for the result: ps_2_0 temps are taken by dependent-read level, one never written first.
    const std::vector<std::string> texts = {"mad r0.xyz, t0, c2.x, -c2.y", "dp3 r1.x, r0, c0", "mad r2, c1, r1.x, t0.w",
                                            "mov oC0, r2"};
    const std::vector<unsigned> lines = {6, 7, 9, 9};
    for (size_t i = 0; i < texts.size(); ++i) {
        EXPECT_EQ(j["steps"][i]["text"], texts[i]) << i;
        ASSERT_TRUE(j["steps"][i]["hlsl"].is_object()) << j["steps"][i].dump();
        EXPECT_EQ(j["steps"][i]["hlsl"]["file"], "hlsl");
        EXPECT_EQ(j["steps"][i]["hlsl"]["line"], lines[i]) << texts[i];
    }
    EXPECT_EQ(j["steps"][1]["hlsl"]["text"], "    float d = dot(n, light);");
    // Grouped by line: 6 (step 1), 7 (step 2), 9 (steps 3 and 4).
    ASSERT_EQ(j["hlsl_lines"].size(), 3u) << j["hlsl_lines"].dump();
    EXPECT_EQ(j["hlsl_lines"][0]["line"], 6);
    EXPECT_EQ(j["hlsl_lines"][2]["line"], 9);
    EXPECT_EQ(j["hlsl_lines"][2]["text"], "    return c + t.w;");
    EXPECT_EQ(j["hlsl_lines"][2]["steps"], nlohmann::json::parse("[3, 4]"));
    // The values, worked out above.
    const auto n = write_of(j["steps"][0], "r0");
    ASSERT_FALSE(n.is_null());
    EXPECT_EQ(n["mask"], "xyz");
    EXPECT_NEAR(n["lanes"][1][0].get<double>(), 1, 1e-6);
    EXPECT_NEAR(n["lanes"][1][1].get<double>(), 3, 1e-6);
    EXPECT_NEAR(n["lanes"][1][2].get<double>(), -1, 1e-6);
    EXPECT_NEAR(write_of(j["steps"][1], "r1")["lanes"][1][0].get<double>(), 4, 1e-6);
    EXPECT_NEAR(write_of(j["steps"][1], "r1")["lanes"][0][0].get<double>(), 2, 1e-6);
    expect_vec(write_of(j["steps"][2], "r2")["lanes"][1], 3, 2, 5, 9, "r2 at the pixel");
    expect_vec(write_of(j["steps"][2], "r2")["lanes"][0], 2, 1.5, 3, 5, "r2 at (0, 2)");
    expect_vec(write_of(j["steps"][3], "oC0")["lanes"][1], 3, 2, 5, 9, "oC0");
}

TEST(CliDebug, HlslPixelShaderTextListsEachLinesInstructionsUnderIt) {
    const Result r = sm2("debug " + hlsl_stream() + " --frame 0 --pixel 1,2");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out.find("carries no HLSL line table"), std::string::npos) << r.out;
    const size_t line7 = r.out.find("hlsl:7: float d = dot(n, light);\n  step 2, line ");
    ASSERT_NE(line7, std::string::npos) << r.out;
    EXPECT_NE(r.out.find(": dp3 r1.x, r0, c0\n    r1 (x)\n      lane 0 (0, 2): (2, 0, 0, 0)\n"
                         "      lane 1 (1, 2): (4, 0, 0, 0)  <- the pixel\n",
                         line7),
              std::string::npos)
        << r.out;
    const size_t line9 = r.out.find("hlsl:9: return c + t.w;\n  step 3, line ");
    ASSERT_NE(line9, std::string::npos) << r.out;
    EXPECT_NE(r.out.find("  step 4, line ", line9), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("hlsl:8:"), std::string::npos) << "line 8 has no instruction of its own";
    EXPECT_EQ(r.out.find("hlsl:9:", line9 + 1), std::string::npos) << "one group for line 9";
    EXPECT_NE(r.out.find("      lane 1 (1, 2): (3, 2, 5, 9)  <- the pixel\n", line9), std::string::npos) << r.out;
}

TEST(CliDebug, BytecodeFromSm2CompileDebugInfoStepsByHlslLine) {
    // The same HLSL compiled by sm2 compile, with and without -g, read by the stream as a side
    // file: with the line table the steps are grouped under ps_lines.hlsl's lines, without it they
    // are the assembly's.
    const std::string source = tmp("ps_lines.hlsl");
    write_file(source, kHlslPixelShader);
    const std::string with_table = tmp("ps_lines_g.bin"), without_table = tmp("ps_lines.bin");
    ASSERT_EQ(sm2("compile " + source + " -T ps_2_0 -g -o " + with_table).status, 0);
    ASSERT_EQ(sm2("compile " + source + " -T ps_2_0 -o " + without_table).status, 0);
    const std::string with_name = std::filesystem::path(with_table).filename().string();
    const std::string without_name = std::filesystem::path(without_table).filename().string();
    std::string text = kGradient;
    const std::string asm_shader = "CreatePixelShader ps asm<<END\n" + kPixelShader + "END\n";
    text.replace(text.find(asm_shader), asm_shader.size(), "CreatePixelShader ps @\"" + with_name + "\"\n");
    const std::string constants = "SetPixelShaderConstantF 0 f32[ 0.25 0.5 -1 0 ]\n";
    text.replace(text.find(constants), constants.size(), "SetPixelShaderConstantF 0 f32[ 1 2 3 0   0.5 0.25 1 2 ]\n");
    const std::string stream = tmp("hlsl_bytecode.sm2cs");
    write_file(stream, text);
    const Result with = sm2("debug " + stream + " --frame 0 --pixel 1,2");
    ASSERT_EQ(with.status, 0) << with.err;
    const size_t line7 = with.out.find(source + ":7: float d = dot(n, light);\n  step 2, line ");
    ASSERT_NE(line7, std::string::npos) << with.out;
    EXPECT_NE(with.out.find("      lane 1 (1, 2): (4, 0, 0, 0)  <- the pixel\n", line7), std::string::npos) << with.out;
    text.replace(text.find(with_name), with_name.size(), without_name);
    write_file(stream, text);
    const Result without = sm2("debug " + stream + " --frame 0 --pixel 1,2");
    ASSERT_EQ(without.status, 0) << without.err;
    EXPECT_NE(without.out.find("carries no HLSL line table"), std::string::npos) << without.out;
    EXPECT_EQ(without.out.find(":7: float d"), std::string::npos) << without.out;
    EXPECT_NE(without.out.find("step 2, line "), std::string::npos) << without.out;
    EXPECT_NE(without.out.find(": dp3 r1.x, r0, c0\n  r1 (x)\n"), std::string::npos) << without.out;
}

TEST(CliDebug, VertexShaderOfAKnownVertex) {
    // Vertex 1: v0 = (0.5, 0.5, 0.5, 1) (FLOAT3, w = 1), v1 = (4, 0, 0, 1); m4x4 by diag(2, 2, 1, 1).
    const auto j = run_json("debug " + gradient_stream() + " --frame 0 --vertex 1");
    ASSERT_TRUE(j.is_object()) << j.dump();
    EXPECT_EQ(j["stage"], "vertex");
    EXPECT_EQ(j["call"], kGradientDraw);
    expect_vec(j["inputs"]["v0"][0], 0.5, 0.5, 0.5, 1, "v0");
    expect_vec(j["inputs"]["v1"][0], 4, 0, 0, 1, "v1");
    ASSERT_EQ(j["steps"].size(), 3u) << j.dump();
    EXPECT_EQ(j["steps"][0]["text"], "m4x4 r0, v0, c0");
    expect_vec(write_of(j["steps"][0], "r0")["lanes"][0], 1, 1, 0.5, 1, "r0");
    expect_vec(write_of(j["steps"][1], "oPos")["lanes"][0], 1, 1, 0.5, 1, "oPos");
    expect_vec(write_of(j["steps"][2], "oT0")["lanes"][0], 4, 0, 0, 1, "oT0");
    const Result text = sm2("debug " + gradient_stream() + " --frame 0 --vertex 2 --draw 12");
    ASSERT_EQ(text.status, 0) << text.err;
    EXPECT_NE(text.out.find("vertex shader of call 12 DrawPrimitiveUP for vertex 2"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("  r0 (xyzw) (-1, -1, 0.5, 1)\n"), std::string::npos) << text.out;
}

// The gradient's vertex shader written in HLSL (an hlsl<< heredoc): vertex 1 has p = (0.5, 0.5,
// 0.5, 1) and t = (4, 0, 0, 1); world = diag(2, 2, 1, 1) in c0..c3, so mul(p, world) = (1, 1,
// 0.5, 1) (four dp4 under line 6) and t * 2 = (8, 0, 0, 2) (line 7); the output copies carry the
// lines of the values they store.
TEST(CliDebug, HlslVertexShaderStepsByHlslLine) {
    std::string text = kGradient;
    const std::string asm_vs = "CreateVertexShader vs asm<<END\nvs_2_0\ndcl_position v0\ndcl_texcoord v1\nm4x4 r0, v0, c0\n"
                               "mov oPos, r0\nmov oT0, v1\nEND\n";
    ASSERT_NE(text.find(asm_vs), std::string::npos);
    text.replace(text.find(asm_vs), asm_vs.size(),
                 "CreateVertexShader vs hlsl<<END\n"
                 "float4x4 world;\n"                                             // 1
                 "struct Out { float4 pos : POSITION; float4 t : TEXCOORD0; };\n"  // 2
                 "Out main(float4 p : POSITION, float4 t : TEXCOORD0)\n"          // 3
                 "{\n"                                                           // 4
                 "    Out o;\n"                                                  // 5
                 "    o.pos = mul(p, world);\n"                                  // 6
                 "    o.t = t * 2;\n"                                            // 7
                 "    return o;\n"                                               // 8
                 "}\nEND\n");
    const std::string stream = tmp("hlsl_vertex_gradient.sm2cs");
    write_file(stream, text);
    const Result r = sm2("debug " + stream + " --frame 0 --vertex 1");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("HLSL, stepped by source line"), std::string::npos) << r.out;
    const size_t line6 = r.out.find("hlsl:6: o.pos = mul(p, world);\n  step 1, line ");
    ASSERT_NE(line6, std::string::npos) << r.out;
    const size_t line7 = r.out.find("hlsl:7: o.t = t * 2;\n", line6);
    ASSERT_NE(line7, std::string::npos) << r.out;
    const std::string group6 = r.out.substr(line6, line7 - line6);
    size_t dp4 = 0;
    for (size_t at = group6.find(": dp4 "); at != std::string::npos; at = group6.find(": dp4 ", at + 1)) ++dp4;
    EXPECT_EQ(dp4, 4u) << group6;
    EXPECT_NE(group6.find("(1, 1, 0.5, 1)\n"), std::string::npos) << group6;
    EXPECT_NE(r.out.find("(8, 0, 0, 2)\n", line7), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("    oPos (xyzw) (1, 1, 0.5, 1)\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("    oT0 (xyzw) (8, 0, 0, 2)\n"), std::string::npos) << r.out;
}

TEST(CliDebug, ATexturedDrawOfATraceEndsAtThePixelsShaderColour) {
    // shader_scene.trace, pixel (128, 128) of frame 0: the debugged shader's last oC0 at the pixel
    // is the colour the draw's own pass gave it (sm2 pixel), texture samples included.
    const auto history = run_json("pixel " + kShaderTrace + " --frame 0 --pixel 128,128");
    ASSERT_FALSE(history["draws"].empty()) << history.dump();
    for (const auto& draw : history["draws"]) {
        const auto& fragment = draw["fragments"].back();
        // Call 64 draws with COLORWRITEENABLE 0: the draw does not compute oC0 (it reads the
        // default (0, 0, 0, 1)); the debugger, which runs every instruction, does.
        if (!fragment["shaded"].get<bool>() || draw["call"] == 64) continue;
        const auto j = run_json("debug " + kShaderTrace + " --frame 0 --pixel 128,128 --draw " + draw["call"].dump());
        ASSERT_TRUE(j.is_object()) << draw["call"];
        nlohmann::json last = nullptr;
        for (const auto& step : j["steps"])
            if (auto w = write_of(step, "oC0"); !w.is_null()) last = w;
        ASSERT_FALSE(last.is_null()) << draw["call"];
        EXPECT_EQ(last["lanes"][j["watched_lane"].get<size_t>()], fragment["shader_color"]) << "call " << draw["call"];
    }
}

TEST(CliDebug, BadArgumentsAreRefused) {
    const std::string stream = gradient_stream();
    const auto expect = [&](const std::string& args, int status, const std::string& message) {
        const Result r = sm2(args);
        EXPECT_EQ(r.status, status) << args << ": " << r.err;
        EXPECT_NE(r.err.find(message), std::string::npos) << args << ": " << r.err;
    };
    expect("debug " + stream + " --frame 0", 2, "give one of --pixel X,Y and --vertex I");
    expect("debug " + stream + " --frame 0 --pixel 1,1 --vertex 0", 2, "give one of");
    expect("debug " + stream + " --frame 0 --pixel 1", 2, "expected X,Y");
    expect("debug " + stream + " --frame 0 --pixel 4,0", 1, "--pixel 4,0: outside the 4x4 back buffer");
    expect("debug " + stream + " --frame 1 --pixel 1,1", 1, "--frame 1: out of range");
    expect("debug " + stream + " --frame 0 --pixel 1,1 --draw 5", 1,
           "--draw 5: no draw at that call covered pixel 1,1 of frame 0 (draws that did: calls 12)");
    expect("debug " + stream + " --frame 0 --vertex 4", 1, "no draw fetched vertex 4 in frame 0 (none did)");
    expect("debug " + stream + " --frame 0 --vertex 0 --draw 11", 1, "--draw 11: no draw at that call fetched");
    expect("pixel " + stream + " --frame 0 --pixel 1,1 --target ''", 2, "--target ''");
    // Scene 02, pixel (128, 128): the last draw over it, call 38, fails the early depth test there.
    expect("debug " + kSource + "/samples/scenes/02_shared_edges_stencil.sm2cs --frame 0 --pixel 128,128", 1,
           "call 38 covered pixel 128,128 but its pixel shader did not run there");
}

// ---------------------------------------------------------------------------------------------
// Render to texture: a 4x4 texture `rtt` cleared to (0, 128/255, 0, 1), then
//   call 14 (into rtt):        oC0 = (1, 0, 0, 1)                          -> (1, 0, 0, 1)
//   call 19 (into rtt):        oC0 = (0, 0, 0.5, 0), blend ONE + ONE        -> (1, 0, 128/255, 1)
//   call 23 (into the back buffer, cleared to (0, 0, 128/255, 1)): oC0 = (0, 0, 1, 1), no blend
const std::string kQuad = "DrawPrimitiveUP TRIANGLESTRIP 2 12 f32[ -1 1 0.5   1 1 0.5   -1 -1 0.5   1 -1 0.5 ]\n";
const std::string kRenderToTexture =
    "sm2cs 1\n"
    "CreateDevice 4 4 A8R8G8B8\n"
    "CreateTexture rtt 4 4 1 A8R8G8B8 RENDERTARGET\n"
    "CreateVertexDeclaration decl { 0 0 FLOAT3 DEFAULT POSITION 0 }\n"
    "CreateVertexShader vs asm<<END\nvs_2_0\ndcl_position v0\nmov oPos, v0\nEND\n"
    "CreatePixelShader ps asm<<END\nps_2_0\nmov oC0, c0\nEND\n"
    "SetVertexDeclaration decl\n"
    "SetVertexShader vs\n"
    "SetPixelShader ps\n"
    "Clear TARGET 0xFF000080 1 0\n"
    "SetRenderTarget 0 rtt\n"
    "Clear TARGET 0xFF008000 1 0\n"
    "BeginScene\n"
    "SetPixelShaderConstantF 0 f32[ 1 0 0 1 ]\n" + kQuad +
    "SetRenderState ALPHABLENDENABLE TRUE\n"
    "SetRenderState SRCBLEND ONE\n"
    "SetRenderState DESTBLEND ONE\n"
    "SetPixelShaderConstantF 0 f32[ 0 0 0.5 0 ]\n" + kQuad +
    "SetRenderTarget 0 backbuffer\n"
    "SetRenderState ALPHABLENDENABLE FALSE\n"
    "SetPixelShaderConstantF 0 f32[ 0 0 1 1 ]\n" + kQuad +
    "EndScene\n"
    "Present\n";

TEST(CliPixelTarget, TwoDrawsIntoATexture) {
    const std::string stream = tmp("rtt.sm2cs");
    write_file(stream, kRenderToTexture);
    const double half = 128.0 / 255.0;
    const auto j = run_json("pixel " + stream + " --frame 0 --pixel 2,1 --target rtt");
    ASSERT_EQ(j["draws"].size(), 2u) << j.dump();
    EXPECT_EQ(j["target"], "rtt");
    EXPECT_EQ(j["draws"][0]["call"], 14);
    EXPECT_EQ(j["draws"][0]["surface"], "rtt");
    EXPECT_EQ(j["draws"][0]["render_target"], 0);
    const auto& first = j["draws"][0]["fragments"][0];
    expect_vec(first["before"]["color"], 0, half, 0, 1, "call 14 before: rtt's clear", 1e-6);
    expect_vec(first["shader_color"], 1, 0, 0, 1, "call 14 shader", 1e-6);
    expect_vec(first["after"]["color"], 1, 0, 0, 1, "call 14 after", 1e-6);
    EXPECT_EQ(j["draws"][1]["call"], 19);
    const auto& second = j["draws"][1]["fragments"][0];
    expect_vec(second["before"]["color"], 1, 0, 0, 1, "call 19 before", 1e-6);
    expect_vec(second["after"]["color"], 1, 0, half, 1, "call 19 after: red + 0.5 blue", 1e-6);
    EXPECT_TRUE(j["final"].is_null());  // only the back buffer's final value is the frame's
    EXPECT_EQ(j["consistent"], true);

    const auto back = run_json("pixel " + stream + " --frame 0 --pixel 2,1");
    ASSERT_EQ(back["draws"].size(), 1u) << back.dump();
    EXPECT_EQ(back["draws"][0]["call"], 23);
    expect_vec(back["draws"][0]["fragments"][0]["before"]["color"], 0, 0, half, 1, "call 23 before", 1e-6);
    expect_vec(back["final"], 0, 0, 1, 1, "final", 1e-6);

    const auto slot = run_json("pixel " + stream + " --frame 0 --pixel 2,1 --target rt0");
    ASSERT_EQ(slot["draws"].size(), 3u) << slot.dump();
    EXPECT_EQ(slot["draws"][1]["surface"], "rtt");
    EXPECT_EQ(slot["draws"][2]["surface"], "backbuffer");

    EXPECT_TRUE(run_json("pixel " + stream + " --frame 0 --pixel 2,1 --target rt1")["draws"].empty());
    const Result text = sm2("pixel " + stream + " --frame 0 --pixel 2,1 --target rtt");
    EXPECT_NE(text.out.find("target rtt: 2 draws covered it"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("call 19 DrawPrimitiveUP, primitive 0, into rt0 (rtt):"), std::string::npos) << text.out;
}

// Two render targets: the back buffer in slot 0, the texture `second` in slot 1; call 12 writes
// oC0 = (1, 0, 0, 1) and oC1 = (0, 0.5, 1, 1).
const std::string kTwoTargets =
    "sm2cs 1\n"
    "CreateDevice 4 4 A8R8G8B8\n"
    "CreateTexture second 4 4 1 A8R8G8B8 RENDERTARGET\n"
    "CreateVertexDeclaration decl { 0 0 FLOAT3 DEFAULT POSITION 0 }\n"
    "CreateVertexShader vs asm<<END\nvs_2_0\ndcl_position v0\nmov oPos, v0\nEND\n"
    "CreatePixelShader ps asm<<END\nps_2_0\nmov oC0, c0\nmov oC1, c1\nEND\n"
    "SetVertexDeclaration decl\n"
    "SetVertexShader vs\n"
    "SetPixelShader ps\n"
    "SetRenderTarget 1 second\n"
    "BeginScene\n"
    "SetPixelShaderConstantF 0 f32[ 1 0 0 1   0 0.5 1 1 ]\n" + kQuad +
    "EndScene\n"
    "Present\n";

TEST(CliPixelTarget, TheSecondRenderTargetShowsOC1) {
    const std::string stream = tmp("two_targets.sm2cs");
    write_file(stream, kTwoTargets);
    for (const std::string target : {"rt1", "second"}) {
        const auto j = run_json("pixel " + stream + " --frame 0 --pixel 3,3 --target " + target);
        ASSERT_EQ(j["draws"].size(), 1u) << target << ": " << j.dump();
        EXPECT_EQ(j["draws"][0]["call"], 12);
        EXPECT_EQ(j["draws"][0]["render_target"], 1);
        EXPECT_EQ(j["draws"][0]["surface"], "second");
        const auto& f = j["draws"][0]["fragments"][0];
        expect_vec(f["shader_color"], 0, 0.5, 1, 1, target + ": oC1", 1e-6);
        expect_vec(f["after"]["color"], 0, 128.0 / 255.0, 1, 1, target + ": written", 1e-6);
    }
    const auto back = run_json("pixel " + stream + " --frame 0 --pixel 3,3");
    ASSERT_EQ(back["draws"].size(), 1u);
    EXPECT_EQ(back["draws"][0]["render_target"], 0);
    expect_vec(back["draws"][0]["fragments"][0]["shader_color"], 1, 0, 0, 1, "oC0", 1e-6);
}

TEST(CliDebug, AFixedFunctionVertexProgram) {
    // ff_lit_cube.trace draws without shaders: the debugger steps the program the device generated
    // for the fixed-function state. Its first instruction transforms the position by the combined
    // matrix in c0..c3; the test does that dot product itself from the inputs and constants shown.
    const std::string trace = "/work/shared/traces/ff_lit_cube.trace";
    const auto j = run_json("debug " + trace + " --frame 0 --vertex 0");
    ASSERT_TRUE(j.is_object()) << j.dump();
    EXPECT_EQ(j["fixed_function"], true);
    EXPECT_NE(j["source"].get<std::string>().find("fixed-function"), std::string::npos);
    ASSERT_FALSE(j["steps"].empty());
    EXPECT_EQ(j["steps"][0]["text"], "m4x4 oPos, v0, c0");
    const auto& v0 = j["inputs"]["v0"][0];
    const auto position = write_of(j["steps"][0], "oPos");
    ASSERT_FALSE(position.is_null());
    for (int row = 0; row < 4; ++row) {
        const auto& c = j["constants"]["c" + std::to_string(row)];
        double dot = 0;
        for (int k = 0; k < 4; ++k) dot += v0[k].get<double>() * c[k].get<double>();
        EXPECT_NEAR(position["lanes"][0][row].get<double>(), dot, 1e-4 * (1 + std::abs(dot))) << row;
    }
}

TEST(CliInspectSideEffects, SaveSurfaceWritesNothingWhenLookingInside) {
    // sm2 state, pixel and debug replay a stream to look at it: its SaveSurface calls succeed
    // without writing into the working folder.
    const std::string image = "inspect_side_effect_" + std::to_string(getpid()) + ".png";
    std::string text = kTwoTargets;
    text.insert(text.find("Present\n"), "SaveSurface second \"" + image + "\"\n");
    const std::string stream = tmp("save_surface.sm2cs");
    write_file(stream, text);
    for (const std::string& args : {"state " + stream + " --call 14", "pixel " + stream + " --frame 0 --pixel 1,1",
                                   "debug " + stream + " --frame 0 --pixel 1,1"}) {
        const Result r = sm2(args);
        EXPECT_EQ(r.status, 0) << args << ": " << r.err;
        EXPECT_FALSE(std::filesystem::exists(image)) << args;
        std::filesystem::remove(image);
    }
}

}  // namespace
