// Start-up: commands that touch no image must not load OpenImageIO, and commands that run no
// shader natively must not load LLVM. The image I/O module (runtime/src/image_codec.h) is
// dlopen()ed by the first image read or write, the JIT module (emu/src/jit_module) by the first
// use of the JIT; the dynamic loader's own log (LD_DEBUG=files) says which shared objects a
// process opened.
#include <gtest/gtest.h>

#include <string>

#include "cli_support.h"

namespace {

using cli_support::sm2_with;
using cli_support::tmp;

const std::string kTinyScene = "sm2cs 1\nCreateDevice 4 4 A8R8G8B8\nClear TARGET 0xFF00FF00 1 0\nPresent\n";

TEST(CliStartup, AsmAndVersionLoadNoImageLibrary) {
    auto a = sm2_with("LD_DEBUG=files", "asm -", "ps_2_0\nmov oC0, c0\n");
    ASSERT_EQ(a.status, 0) << a.err;
    EXPECT_EQ(a.out, "FFFF0200\n02000001 800F0800 A0E40000\n0000FFFF\n");
    EXPECT_NE(a.err.find("calling init:"), std::string::npos) << "LD_DEBUG gave no log";
    EXPECT_EQ(a.err.find("OpenImageIO"), std::string::npos) << a.err;
    EXPECT_EQ(a.err.find("sm2emu_image_io"), std::string::npos) << a.err;
    EXPECT_EQ(a.err.find("libLLVM"), std::string::npos) << a.err;
    EXPECT_EQ(a.err.find("sm2emu_jit"), std::string::npos) << a.err;
    auto v = sm2_with("LD_DEBUG=files", "--version");
    EXPECT_EQ(v.status, 0);
    EXPECT_EQ(v.err.find("OpenImageIO"), std::string::npos);
    EXPECT_EQ(v.err.find("libLLVM"), std::string::npos);
}

#ifdef SM2_HAS_JIT
TEST(CliStartup, TheJitLoadsLlvmWhenItRunsAShader) {
    const std::string shader = "ps_2_0\ndef c1, 0.5, 0.25, 2, 1\nmul r0, c0, c1\nmov oC0, r0\n";
    auto jit = sm2_with("LD_DEBUG=files", "run - --const c0=1,2,3,4 --engine jit", shader);
    ASSERT_EQ(jit.status, 0) << jit.out;
    EXPECT_EQ(jit.out, "oC0 = 0.5 0.5 6 4\n");
    EXPECT_NE(jit.err.find("sm2emu_jit"), std::string::npos);
    EXPECT_NE(jit.err.find("libLLVM"), std::string::npos);
    auto interpreted = sm2_with("LD_DEBUG=files", "run - --const c0=1,2,3,4 --engine interpreter", shader);
    EXPECT_EQ(interpreted.out, "oC0 = 0.5 0.5 6 4\n");
    EXPECT_EQ(interpreted.err.find("libLLVM"), std::string::npos);
    // Without its module the JIT is unavailable and replay interprets (the same bytes).
    auto missing = sm2_with("SM2EMU_JIT=/nonexistent/sm2emu_jit.so", "bench - --repeat 1 --engine jit", kTinyScene);
    EXPECT_EQ(missing.status, 0) << missing.err;
    EXPECT_NE(missing.out.find("engine: jit (not in this build: interpreter)"), std::string::npos) << missing.out;
}
#endif

TEST(CliStartup, WritingAFrameLoadsTheImageModule) {
    const std::string dir = tmp("frames");
    auto r = sm2_with("LD_DEBUG=files", "replay - --quiet -o " + dir, kTinyScene);
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.err.find("sm2emu_image_io"), std::string::npos);
    EXPECT_NE(r.err.find("libOpenImageIO"), std::string::npos);
    // The frame went through it: sm2 diff reads it back, and it equals itself.
    auto d = sm2_with("", "diff " + dir + "/frame_0000.png " + dir + "/frame_0000.png");
    EXPECT_EQ(d.status, 0) << d.err;
    EXPECT_NE(d.out.find("size: 4x4"), std::string::npos) << d.out;
}

TEST(CliStartup, AMissingModuleIsAnErrorNamingIt) {
    const std::string dir = tmp("nomodule");
    auto r = sm2_with("SM2EMU_IMAGE_IO=/nonexistent/sm2emu_image_io.so", "replay - --quiet -o " + dir, kTinyScene);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("image I/O is not available: cannot load the module"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("/nonexistent/sm2emu_image_io.so"), std::string::npos) << r.err;
    // Commands without images do not notice.
    EXPECT_EQ(sm2_with("SM2EMU_IMAGE_IO=/nonexistent/sm2emu_image_io.so", "asm -", "vs_2_0\ndcl_position v0\nmov oPos, v0\n").status, 0);
}

}  // namespace
