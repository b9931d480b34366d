#include "call_walk.h"

#include <algorithm>
#include <iostream>
#include <thread>

#include "io.h"
#include "sm2/runtime/apitrace_import.h"
#include "sm2/runtime/replay.h"
#include "sm2/runtime/stream_assembler.h"
#include "sm2/runtime/stream_hlsl_compiler.h"
#include "stream_io.h"

namespace sm2::tools {

namespace cs = runtime::cs;

runtime::DeviceOptions inspection_device_options() {
    runtime::DeviceOptions options;
    options.threads = std::max(1u, std::thread::hardware_concurrency());
    options.engine = runtime::DeviceOptions::Engine::Jit;
    options.write_image = [](const runtime::Surface&, const std::string&) {};
    return options;
}

std::string CallWalk::range_text() const {
    if (last_call < first_call) return "no calls";
    return "calls " + std::to_string(first_call) + ".." + std::to_string(last_call);
}

std::optional<CallWalk> walk_calls(const std::string& path, const std::string& read_root, const char* command,
                                   runtime::Device& device,
                                   const std::function<bool(uint64_t call, const cs::Statement&)>& keep_going) {
    CallWalk walk;
    runtime::ReplayOptions options;
    options.assembler = runtime::stream_assembler();
    options.hlsl_compiler = runtime::stream_hlsl_compiler();
    if (path.ends_with(".trace")) {
        namespace at = runtime::apitrace;
        walk.trace = true;
        walk.file_name = display_name(path);
        std::optional<at::Error> error;
        auto reader = at::Reader::open_file(path, error);
        if (!reader) {
            std::cerr << "sm2 " << command << ": " << (error->io ? "" : walk.file_name + ": ") << error->to_string() << '\n';
            return std::nullopt;
        }
        options.file_name = walk.file_name;
        runtime::Replayer replayer(device, options);
        bool stopped = false;
        const at::ImportResult imported = at::import_d3d9(*reader, [&](const cs::Statement& st, uint64_t call) {
            if (st.kind != cs::Statement::Kind::Call || stopped) return;
            if (!keep_going(call, st)) {
                stopped = true;
                return;
            }
            if (!replayer.execute(st, static_cast<size_t>(call))) ++walk.refused;
            replayer.clear_diagnostics();
        });
        if (imported.error) {
            std::cerr << "sm2 " << command << ": " << walk.file_name << ": " << imported.error->to_string() << '\n';
            return std::nullopt;
        }
        walk.first_call = 0;
        walk.last_call = imported.report.calls == 0 ? 0 : imported.report.calls - 1;
        if (imported.report.calls == 0) walk.first_call = 1;  // empty: no number is in range
        return walk;
    }
    auto loaded = load_stream(path, command, read_root);
    if (!loaded) return std::nullopt;
    walk.file_name = loaded->file_name;
    options.file_name = loaded->file_name;
    options.base_dir = loaded->base_dir;
    options.root_dir = loaded->root_dir;
    for (const auto& st : loaded->stream.statements) walk.last_call += st.kind == cs::Statement::Kind::Call;
    runtime::Replayer replayer(device, options);
    uint64_t call = 0;
    for (size_t i = 0; i < loaded->stream.statements.size(); ++i) {
        const cs::Statement& st = loaded->stream.statements[i];
        if (st.kind != cs::Statement::Kind::Call) continue;
        if (!keep_going(++call, st)) break;
        if (!replayer.execute(st, i + 1)) ++walk.refused;
    }
    for (const auto& d : replayer.diagnostics()) std::cerr << d.to_string() << '\n';
    return walk;
}

}  // namespace sm2::tools
