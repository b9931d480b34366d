// glslang 12 crashes (a null dereference in TParseContextBase::growGlobalUniformBlock) on a global
// uniform declared again with a different type; sm2::hlsl::compile runs glslang in a child process
// and must turn that into an error, never a crash of the caller.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include "sm2/hlsl/compiler.h"

namespace {

sm2::hlsl::CompileResult compile_pixel_shader(const std::string& source) {
    sm2::hlsl::CompileOptions options;
    options.file_name = "guard.hlsl";
    options.stage = sm2::isa::ShaderType::Pixel;
    return sm2::hlsl::compile(source, options);
}

// A fuzz corpus input: the first byte picks the profile (P: ps_2_0), the rest is the HLSL.
std::string corpus_text(const std::string& name) {
    std::ifstream in(std::string(SM2_SOURCE_DIR) + "/tests/fuzz/corpus/hlsl/" + name, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_FALSE(bytes.empty()) << name;
    return bytes.empty() ? bytes : bytes.substr(1);
}

void expect_front_end_crash_reported(const sm2::hlsl::CompileResult& result) {
    EXPECT_FALSE(result.ok());
    ASSERT_EQ(result.diagnostics.size(), 1u);
    const auto& d = result.diagnostics[0];
    EXPECT_EQ(d.severity, sm2::assembler::Severity::Error);
    EXPECT_EQ(d.file, "guard.hlsl");
    EXPECT_EQ(d.line, 1u);
    EXPECT_EQ(d.column, 1u);
    EXPECT_NE(d.message.find("the HLSL front end (glslang) crashed on this input (with signal 11)"),
              std::string::npos)
        << d.message;
    EXPECT_EQ(d.fxc_code, 3000u);
}

}  // namespace

TEST(HlslFrontEndGuard, SamplerRedeclaredAsVectorIsAnErrorNotACrash) {
    expect_front_end_crash_reported(compile_pixel_shader("sampler2D tex; float4 tex;\n"));
}

TEST(HlslFrontEndGuard, VectorRedeclaredWithAnotherSizeIsAnErrorNotACrash) {
    expect_front_end_crash_reported(compile_pixel_shader("float4 x; float3 x;\n"));
}

TEST(HlslFrontEndGuard, TheInputsFuzzHlslFoundAreErrors) {
    expect_front_end_crash_reported(compile_pixel_shader(corpus_text("glslang_crash_redeclared_sampler_ps.hlsl")));
    expect_front_end_crash_reported(compile_pixel_shader(corpus_text("glslang_crash_after_syntax_error_ps.hlsl")));
}

TEST(HlslFrontEndGuard, ErrorsAndCodeComeBackFromTheChildProcess) {
    // A syntax error: glslang's message, located, crosses the pipe intact.
    const auto bad = compile_pixel_shader("float4 main() : COLOR {\n  return 1 +;\n}\n");
    EXPECT_FALSE(bad.ok());
    ASSERT_FALSE(bad.diagnostics.empty());
    EXPECT_EQ(bad.diagnostics[0].file, "guard.hlsl");
    EXPECT_EQ(bad.diagnostics[0].line, 2u);
    // A good shader after the failures: the SPIR-V came back whole (mov oC0 of a def).
    const auto good = compile_pixel_shader("float4 main() : COLOR { return float4(1, 0.5, 0.25, 1); }\n");
    ASSERT_TRUE(good.ok());
    EXPECT_NE(good.assembly.find("def c0, 1, 0.5, 0.25, 1"), std::string::npos) << good.assembly;
}

// AddressSanitizer's allocator is not fork-safe while other threads allocate: a child forked
// while another thread holds its lock waits forever (the sanitizer build of this test hung until
// ctest's timeout). The release build runs the test; the sanitizer builds skip it.
#if defined(__SANITIZE_ADDRESS__)
#define SM2_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SM2_TEST_ASAN 1
#endif
#endif

TEST(HlslFrontEndGuard, ThreadsCompilingAtOnceGetTheSameBytecode) {
#ifdef SM2_TEST_ASAN
    GTEST_SKIP() << "fork() from several threads at once deadlocks in AddressSanitizer's allocator";
#endif
    // The front end forks under a mutex: concurrent compiles (a good shader, a crashing one) each
    // get their own answer, and the good one's tokens never differ.
    const std::string good = "float4 tint;\nfloat4 main(float2 uv : TEXCOORD0) : COLOR { return tint * uv.x; }\n";
    const auto reference = compile_pixel_shader(good);
    ASSERT_TRUE(reference.ok());
    std::vector<int> matches(4, 0), crashes_reported(4, 0);
    std::vector<std::thread> threads;
    for (size_t t = 0; t < 4; ++t)
        threads.emplace_back([&, t] {
            for (int k = 0; k < 5; ++k) {
                matches[t] += compile_pixel_shader(good).tokens == reference.tokens ? 1 : 0;
                const auto crashed = compile_pixel_shader("float4 x; float3 x;\n");
                crashes_reported[t] += !crashed.ok() && crashed.diagnostics.size() == 1 ? 1 : 0;
            }
        });
    for (auto& thread : threads) thread.join();
    EXPECT_EQ(matches, std::vector<int>(4, 5));
    EXPECT_EQ(crashes_reported, std::vector<int>(4, 5));
}
