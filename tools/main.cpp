// sm2: the command line of sm2emu.
#include <algorithm>
#include <iostream>
#include <string>
#include <string_view>
#include <vector>

#include "commands.h"

#ifdef __GLIBC__
#include <malloc.h>
#endif

namespace {

// Two or three examples per command, shown at the end of its --help (and `sm2 help CMD`).
struct Examples {
    const char* path;  // "asm", "cs pack"
    const char* text;
};
constexpr Examples kExamples[] = {
    {"asm", "Examples:\n"
            "  sm2 asm shader.asm                     hex words on stdout (text)\n"
            "  sm2 asm shader.asm -o shader.pso       raw DWORDs into a file (binary)\n"
            "  echo 'ps_2_0\n  mov oC0, c0' | sm2 asm - --format c --name g_ps\n"},
    {"dis", "Examples:\n"
            "  sm2 dis shader.pso                     text on stdout\n"
            "  sm2 asm a.asm | sm2 dis -              hex words from a pipe\n"
            "  sm2 dis shader.pso -o shader.asm\n"},
    {"validate", "Examples:\n"
                 "  sm2 validate shader.asm\n"
                 "  sm2 validate shader.pso --max-slots 512\n"},
    {"compile", "Examples:\n"
                "  sm2 compile tint.hlsl -T ps_2_0 -E main      hex words on stdout\n"
                "  sm2 compile sky.hlsl -T vs_2_0 -D FOG=1 -I include -o sky.vso\n"},
    {"run", "Examples:\n"
            "  sm2 run lake.vs.asm --input v0=1,2,3 --const c4=0.5,0.5,0.5,1\n"
            "  sm2 run tex.ps.asm --texture s0=wood.png --input t0=0.25,0.75 --json\n"
            "  sm2 run shader.asm --lanes lanes.csv --precision fp24 --trace\n"},
    {"cs", "Examples:\n"
           "  sm2 cs pack scene.sm2cs                writes scene.sm2cb beside it\n"
           "  sm2 cs dump scene.sm2cb                canonical text on stdout\n"},
    {"cs pack", "Examples:\n"
                "  sm2 cs pack scene.sm2cs                writes scene.sm2cb beside it\n"
                "  sm2 cs pack - -o scene.sm2cb < scene.sm2cs\n"},
    {"cs dump", "Examples:\n"
                "  sm2 cs dump scene.sm2cb\n"
                "  sm2 cs dump scene.sm2cb -o scene.sm2cs\n"},
    {"cs import", "Examples:\n"
                  "  sm2 cs import app.trace -o app.sm2cs   text; the report on stderr\n"
                  "  sm2 cs import app.trace -o app.sm2cb   binary\n"},
    {"trace", "Examples:\n"
              "  sm2 trace dump app.trace               one call per line on stdout\n"},
    {"trace dump", "Examples:\n"
                   "  sm2 trace dump app.trace\n"
                   "  sm2 trace dump app.trace -o app.txt\n"},
    {"replay", "Examples:\n"
               "  sm2 replay samples/scenes/09_lake.sm2cs -o out/lake\n"
               "  sm2 replay scene.sm2cb -o out/scene --overwrite --threads 1 --engine interpreter\n"
               "  sm2 replay - -o out/stdin --quiet < scene.sm2cs\n"
               "  sm2 replay app.trace -o out/app                an apitrace D3D9 capture\n"
               "  sm2 replay scene.sm2cs -o out/scene --overwrite --compare golden/scene --fail 0.004\n"
               "  sm2 replay scene.sm2cs -o out/scene --overwrite --quiet --stats table\n"},
    {"bench", "Examples:\n"
              "  sm2 bench samples/scenes/27_final_combine.sm2cs\n"
              "  sm2 bench scene.sm2cs --repeat 20 --threads 1 --precision fp24\n"
              "  sm2 bench scene.sm2cs --json\n"},
    {"pixel", "Examples:\n"
              "  sm2 pixel scene.sm2cs --frame 0 --pixel 128,100\n"
              "  sm2 pixel scene.sm2cs --frame 0 --pixel 12,40 --target rt1 --json\n"
              "  sm2 pixel capture.trace --frame 2 --pixel 64,64 --target 0x5593a0c0\n"},
    {"debug", "Examples:\n"
              "  sm2 debug scene.sm2cs --frame 0 --pixel 128,100\n"
              "  sm2 debug scene.sm2cs --frame 0 --pixel 128,100 --draw 17 --json\n"
              "  sm2 debug scene.sm2cs --frame 0 --vertex 2 --draw 17\n"},
    {"diff", "Examples:\n"
             "  sm2 diff out/lake/frame_0000.png reference.png\n"
             "  sm2 diff a.exr b.exr --fail 0.004 --warn 0.001 --heatmap diff.png --heatmap-scale 0.01\n"
             "  sm2 diff out/lake golden/lake --failpercent 0.1 --json --html report.html\n"},
};

CLI::App* find_command(CLI::App& app, const std::vector<std::string>& path) {
    CLI::App* cmd = &app;
    for (const auto& name : path) {
        CLI::App* next = nullptr;
        for (CLI::App* sub : cmd->get_subcommands({}))
            if (sub->get_name() == name) next = sub;
        if (next == nullptr) return nullptr;
        cmd = next;
    }
    return cmd;
}

// Edits (insert, delete, substitute, swap two neighbours) from a to b: "dsi" is one from "dis".
size_t edit_distance(std::string_view a, std::string_view b) {
    std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
    for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
    for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
    for (size_t i = 1; i <= a.size(); ++i)
        for (size_t j = 1; j <= b.size(); ++j) {
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
        }
    return d[a.size()][b.size()];
}

// "unknown command 'asn'; did you mean 'asm'?" for a word that is not one of `cmd`'s
// subcommands (a name within two edits, or one that starts with the word).
std::string unknown_command(CLI::App& cmd, const std::string& word) {
    std::string prefix = cmd.get_parent() ? cmd.get_name() + " " : std::string();
    std::string best;
    size_t best_distance = 3;
    for (CLI::App* sub : cmd.get_subcommands({})) {
        const std::string& name = sub->get_name();
        const size_t d = name.rfind(word, 0) == 0 && !word.empty() ? 1 : edit_distance(word, name);
        if (d < best_distance) {
            best_distance = d;
            best = name;
        }
    }
    std::string message = "unknown command '" + prefix + word + "'";
    if (!best.empty()) message += "; did you mean '" + prefix + best + "'?";
    return message + " (sm2 --help lists the commands)";
}

}  // namespace

// Sanitizer build only: LeakSanitizer's scan of dynamic TLS (clang 14's runtime, glibc 2.36) reads
// a garbage block for the TLS of the dlopen()ed modules at some layouts of the initial stack (the
// lengths of argv), and crashes at exit ("Tracer caught signal 11", "DTLS 5 at 0xfc3-0x18000020c5"):
// `sm2 replay` of samples/scenes/14 packed, with paths of 27 to 31 characters, exit 1 with no
// leak. Not intercepting __tls_get_addr leaves dynamic TLS unscanned; leaks elsewhere are still
// found.
#if defined(__SANITIZE_ADDRESS__)
#define SM2_TOOL_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SM2_TOOL_ASAN 1
#endif
#endif
#ifdef SM2_TOOL_ASAN
extern "C" const char* __asan_default_options();
extern "C" const char* __asan_default_options() { return "intercept_tls_get_addr=0"; }
#endif

int main(int argc, char** argv) {
#ifdef __GLIBC__
    // glibc hands blocks of 128 KiB and more straight back to the kernel when they are freed, so
    // a surface created again after one was freed (every run of `sm2 bench`, textures a trace
    // creates per frame, a device reset) faults in each of its pages anew: in a virtual machine
    // that cost a fifth of a 27_final_combine run, more than drawing into the pages. Keep freed
    // blocks in the heap for reuse; a single block of 32 MiB or more is still mapped by itself.
    constexpr int kMib = 1 << 20;
    mallopt(M_MMAP_THRESHOLD, 32 * kMib);
    mallopt(M_TRIM_THRESHOLD, 512 * kMib);
#endif
    CLI::App app{"sm2emu: a software Shader Model 2.0 GPU (vs_2_0 / ps_2_0)", "sm2"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "sm2emu 0.1.0");
    app.footer("Run 'sm2 help COMMAND' or 'sm2 COMMAND --help' for a command's options and examples.");
    int status = sm2::tools::kOk;
    sm2::tools::add_shader_commands(app, status);
    sm2::tools::add_run_command(app, status);
    sm2::tools::add_stream_commands(app, status);
    sm2::tools::add_trace_commands(app, status);
    sm2::tools::add_replay_commands(app, status);
    sm2::tools::add_state_command(app, status);
    sm2::tools::add_pixel_command(app, status);
    sm2::tools::add_debug_command(app, status);
    sm2::tools::add_diff_command(app, status);
    for (const auto& e : kExamples)
        if (CLI::App* cmd = find_command(app, CLI::detail::split(e.path, ' '))) cmd->footer(e.text);

    // sm2 help [COMMAND [SUBCOMMAND]]: that command's --help.
    std::vector<std::string> args(argv + 1, argv + argc);
    if (!args.empty() && args[0] == "help") {
        const std::vector<std::string> path(args.begin() + 1, args.end());
        CLI::App* cmd = find_command(app, path);
        if (cmd == nullptr) {
            CLI::App* parent = &app;
            for (const auto& word : path) {
                CLI::App* next = find_command(*parent, {word});
                if (next == nullptr) {
                    std::cerr << "sm2 help: " << unknown_command(*parent, word) << '\n';
                    return sm2::tools::kBadUsage;
                }
                parent = next;
            }
        }
        std::string prev;  // "sm2 cs" for `sm2 help cs pack`: the usage line names the whole command
        for (CLI::App* p = cmd->get_parent(); p != nullptr; p = p->get_parent())
            prev = p->get_name() + (prev.empty() ? "" : " " + prev);
        std::cout << cmd->help(prev);
        return sm2::tools::kOk;
    }
    // A mistyped command: say what was meant instead of "A subcommand is required".
    {
        CLI::App* cmd = &app;
        for (const auto& word : args) {
            if (word.empty() || word[0] == '-') break;
            if (CLI::App* next = find_command(*cmd, {word})) {
                cmd = next;
                continue;
            }
            if (!cmd->get_subcommands({}).empty() && cmd->get_require_subcommand_min() > 0) {
                std::cerr << "sm2: " << unknown_command(*cmd, word) << '\n';
                return sm2::tools::kBadUsage;
            }
            break;
        }
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        app.exit(e);
        return sm2::tools::kBadUsage;
    }
    return status;
}
