// A program built against the installed sm2emu package (tests/package/CMakeLists.txt): it
// assembles a shader, replays a stream whose shaders are asm heredocs (the stream assembler of
// the public headers), writes the frame as a PNG (the image I/O module, dlopen()ed from the
// install), reads it back, and prints what it got and which module file it loaded.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "sm2/assembler/assembler.h"
#include "sm2/emu/jit.h"
#include "sm2/runtime/command_stream.h"
#include "sm2/runtime/device.h"
#include "sm2/runtime/image_io.h"
#include "sm2/runtime/replay.h"
#include "sm2/runtime/stream_assembler.h"

namespace {

const char* const kStream = R"(sm2cs 1
CreateDevice 8 8 A8R8G8B8
CreateVertexBuffer vb0 36
Lock vb0 0 f32[ -1 -1 0.5   -1 3 0.5   3 -1 0.5 ]
CreateVertexDeclaration decl0 { 0 0 FLOAT3 DEFAULT POSITION 0 }
CreateVertexShader vs0 asm<<END
vs_2_0
dcl_position v0
mov oPos, v0
END
CreatePixelShader ps0 asm<<END
ps_2_0
def c0, 1, 0.5, 0, 1
mov oC0, c0
END
SetVertexDeclaration decl0
SetVertexShader vs0
SetPixelShader ps0
SetStreamSource 0 vb0 0 12
SetRenderState CULLMODE NONE
BeginScene
DrawPrimitive TRIANGLELIST 0 1
EndScene
Present
)";

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: consumer OUTPUT_DIR\n");
        return 2;
    }
    const auto assembled = sm2::assembler::assemble("ps_2_0\nmov oC0, c0\n");
    if (!assembled.ok()) return 1;
    std::printf("assembled %zu tokens, version 0x%08X\n", assembled.tokens.size(), assembled.tokens.front());

    auto parsed = sm2::runtime::cs::parse_text(kStream);
    if (!parsed.ok()) {
        std::fprintf(stderr, "%s\n", parsed.error->to_string().c_str());
        return 1;
    }
    std::filesystem::create_directories(argv[1]);
    sm2::runtime::DeviceOptions options;
    options.output_dir = argv[1];
    sm2::runtime::Device device(options);
    sm2::runtime::ReplayOptions replay_options;
    replay_options.assembler = sm2::runtime::stream_assembler();
    const auto result = sm2::runtime::replay(device, *parsed.stream, replay_options);
    for (const auto& d : result.diagnostics) std::fprintf(stderr, "%s\n", d.to_string().c_str());
    if (!result.ok()) return 1;
    std::printf("replayed %zu calls, %zu frame(s), %llu pixels shaded\n", result.calls, result.frames.size(),
                static_cast<unsigned long long>(result.statistics.pixels_shaded));

    const auto image = sm2::runtime::read_image(std::string(argv[1]) + "/frame_0000.png");
    const float* p = &image.rgba[(4 * image.width + 4) * 4];
    std::printf("frame %ux%u, pixel (4,4) = %.5f %.5f %.5f %.5f\n", image.width, image.height, p[0], p[1], p[2], p[3]);

    std::ifstream maps("/proc/self/maps");
    for (std::string line; std::getline(maps, line);)
        if (line.find("sm2emu_image_io") != std::string::npos) {
            std::printf("image module: %s\n", line.substr(line.find('/')).c_str());
            break;
        }
    return 0;
}
