// hlsl<<TAG heredocs in command streams: text and binary round trip, replay through
// stream_hlsl_compiler (a drawn pixel checked by hand), a compile error at its line in the stream,
// and the refusal when no HLSL compiler is handed in.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "sm2/runtime/command_stream.h"
#include "sm2/runtime/replay.h"
#include "sm2/runtime/stream_assembler.h"
#include "sm2/runtime/stream_hlsl_compiler.h"

namespace sm2::runtime {
namespace {

// A full-screen quad (two triangles, clip-space positions) and a pixel shader returning a
// constant: (0.25, 0.5, 0.75, 1) -> A8R8G8B8 bytes B G R A = round(0.75*255)=191,
// round(0.5*255)=128, round(0.25*255)=64, 255 (0.5*255 = 127.5 rounds to 128).
const char* const kQuad =
    "sm2cs 1\n"
    "CreateDevice 4 4 A8R8G8B8\n"
    "CreateVertexBuffer vb 72\n"
    "Lock vb 0 f32[ -1 -1 0.5  -1 1 0.5  1 1 0.5   -1 -1 0.5  1 1 0.5  1 -1 0.5 ]\n"
    "CreateVertexDeclaration decl { 0 0 FLOAT3 DEFAULT POSITION 0 }\n"
    "CreateVertexShader vs hlsl<<END\n"
    "float4 main(float4 p : POSITION) : POSITION { return p; }\n"
    "END\n"
    "CreatePixelShader ps hlsl<<END\n"
    "float4 main() : COLOR { return float4(0.25, 0.5, 0.75, 1.0); }\n"
    "END\n"
    "SetVertexDeclaration decl\n"
    "SetVertexShader vs\n"
    "SetPixelShader ps\n"
    "SetRenderState CULLMODE NONE\n"
    "SetStreamSource 0 vb 0 12\n"
    "Clear TARGET 0xFF000000 1 0\n"
    "BeginScene\n"
    "DrawPrimitive TRIANGLELIST 0 2\n"
    "EndScene\n";

cs::Stream parse(const std::string& text) {
    auto parsed = cs::parse_text(text, {});
    EXPECT_TRUE(parsed.ok()) << (parsed.error ? parsed.error->to_string() : "");
    return parsed.ok() ? *parsed.stream : cs::Stream{};
}

ReplayOptions options_with_compilers() {
    ReplayOptions options;
    options.file_name = "t.sm2cs";
    options.assembler = stream_assembler();
    options.hlsl_compiler = stream_hlsl_compiler();
    return options;
}

TEST(StreamHlsl, TextRoundTripIsCanonicalAndKeepsTheLanguage) {
    const cs::Stream stream = parse(kQuad);
    const cs::Value& shader = stream.statements[5].arguments.at(1);
    ASSERT_EQ(shader.kind, cs::Value::Kind::Heredoc);
    EXPECT_EQ(shader.language, cs::Value::Language::Hlsl);
    const std::string canonical = cs::to_text(stream);
    EXPECT_NE(canonical.find("CreatePixelShader ps hlsl<<END\nfloat4 main() : COLOR { return float4(0.25, 0.5, "
                             "0.75, 1.0); }\nEND\n"),
              std::string::npos)
        << canonical;
    EXPECT_EQ(cs::to_text(parse(canonical)), canonical);
    EXPECT_EQ(parse(canonical).statements[5].arguments.at(1), shader);
}

TEST(StreamHlsl, BinaryRoundTripIsExact) {
    const cs::Stream stream = parse(kQuad);
    const auto packed = cs::pack(stream);
    auto unpacked = cs::unpack(packed);
    ASSERT_TRUE(unpacked.ok());
    EXPECT_EQ(cs::to_text(*unpacked.stream), cs::to_text(stream));
    EXPECT_EQ(unpacked.stream->statements[4].arguments.at(1).language, cs::Value::Language::Hlsl);
    EXPECT_EQ(cs::pack(*unpacked.stream), packed);
}

TEST(StreamHlsl, ConstantColourPixelShaderFillsTheQuad) {
    Device device{DeviceOptions{}};
    Replayer replayer(device, options_with_compilers());
    const ReplayResult r = replayer.replay(parse(kQuad));
    for (const auto& d : r.diagnostics) ADD_FAILURE() << d.to_string();
    const Surface* back = device.surface("backbuffer");
    ASSERT_NE(back, nullptr);
    const auto bytes = back->bytes();
    ASSERT_EQ(bytes.size(), 4u * 4u * 4u);
    for (size_t px = 0; px < 16; ++px) {
        EXPECT_EQ(static_cast<int>(bytes[px * 4 + 0]), 191) << px;
        EXPECT_EQ(static_cast<int>(bytes[px * 4 + 1]), 128) << px;
        EXPECT_EQ(static_cast<int>(bytes[px * 4 + 2]), 64) << px;
        EXPECT_EQ(static_cast<int>(bytes[px * 4 + 3]), 255) << px;
    }
}

TEST(StreamHlsl, CompileErrorNamesTheLineInsideTheHeredoc) {
    Device device{DeviceOptions{}};
    Replayer replayer(device, options_with_compilers());
    const ReplayResult r = replayer.replay(parse("sm2cs 1\n"
                                                 "CreateDevice 2 2 A8R8G8B8\n"    // line 2
                                                 "CreatePixelShader ps hlsl<<END\n"  // line 3
                                                 "float4 main() : COLOR {\n"     // line 4: HLSL line 1
                                                 "  return undefined_thing;\n"   // line 5: HLSL line 2
                                                 "}\n"
                                                 "END\n"));
    ASSERT_EQ(r.diagnostics.size(), 1u);
    const std::string text = r.diagnostics[0].to_string();
    EXPECT_EQ(text.rfind("t.sm2cs:5: D3DERR_INVALIDCALL: CreatePixelShader: HLSL line 2: ", 0), 0u) << text;
    EXPECT_FALSE(device.has_resource("ps"));
}

// The device's instruction-slot limit applies to HLSL heredocs as to assembly ones: 70 chained
// mads on uniforms (unrolled: 70 arithmetic slots plus the output's mov) are over ps_2_0's 64,
// refused at the HLSL line of the loop, and accepted once the stream raises the limit to 96.
TEST(StreamHlsl, TheDeviceSlotLimitAppliesToHlsl) {
    const std::string shader = "CreatePixelShader ps_NAME hlsl<<END\n"
                               "float4 a;\n"                                          // HLSL line 1
                               "float4 b;\n"                                          // 2
                               "float4 main() : COLOR {\n"                            // 3
                               "  float4 x = a;\n"                                    // 4
                               "  [unroll] for (int i = 0; i < 70; ++i) x = x * a + b;\n"  // 5
                               "  return x;\n"
                               "}\n"
                               "END\n";
    auto named = [&](const std::string& name) {
        std::string text = shader;
        text.replace(text.find("NAME"), 4, name);
        return text;
    };
    Device device{DeviceOptions{}};
    Replayer replayer(device, options_with_compilers());
    const ReplayResult r = replayer.replay(parse("sm2cs 1\nCreateDevice 2 2 A8R8G8B8\n" + named("first") +
                                                 "SetDeviceLimits INSTRUCTIONSLOTS 96\n" + named("second")));
    ASSERT_EQ(r.diagnostics.size(), 1u);
    const std::string text = r.diagnostics[0].to_string();
    EXPECT_NE(text.find("CreatePixelShader"), std::string::npos) << text;
    EXPECT_NE(text.find("slot"), std::string::npos) << text;
    EXPECT_FALSE(device.has_resource("ps_first"));
    EXPECT_TRUE(device.has_resource("ps_second"));
}

TEST(StreamHlsl, WithoutACompilerHlslIsRefused) {
    Device device{DeviceOptions{}};
    ReplayOptions options;
    options.file_name = "t.sm2cs";
    Replayer replayer(device, options);
    const ReplayResult r = replayer.replay(parse("sm2cs 1\nCreateDevice 2 2 A8R8G8B8\n"
                                                 "CreatePixelShader ps hlsl<<END\n"
                                                 "float4 main() : COLOR { return 1; }\nEND\n"));
    ASSERT_EQ(r.diagnostics.size(), 1u);
    EXPECT_NE(r.diagnostics[0].to_string().find("HLSL needs sm2 compile support"), std::string::npos)
        << r.diagnostics[0].to_string();
}

}  // namespace
}  // namespace sm2::runtime
