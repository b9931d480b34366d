// sm2 trace dump: an apitrace trace file as text, one call per line (docs/apitrace.md).
#include <fstream>
#include <iostream>
#include <memory>
#include <string>

#include "commands.h"
#include "io.h"
#include "sm2/runtime/apitrace.h"

namespace sm2::tools {

namespace {

namespace at = runtime::apitrace;

std::string escape(const std::string& text) {
    at::Value v;
    v.kind = at::Value::Kind::String;
    v.text = text;
    return at::to_text(v);
}

// Streams the calls as they are read: memory stays that of the largest call.
int run_trace_dump(const std::string& input, const std::string& output) {
    std::optional<at::Error> error;
    std::unique_ptr<at::Reader> reader;
    std::optional<std::vector<std::byte>> whole;  // stdin only: read whole (at most 256 MiB)
    if (input == "-") {
        std::string read_error;
        whole = read_input(input, read_error);
        if (!whole) {
            std::cerr << "sm2 trace dump: " << read_error << '\n';
            return kInvalidInput;
        }
        reader = at::Reader::open(*whole, error);
    } else {
        reader = at::Reader::open_file(input, error);
    }
    if (!reader) {
        std::cerr << "sm2 trace dump: " << (error->io ? "" : display_name(input) + ": ") << error->to_string() << '\n';
        return kInvalidInput;
    }
    std::ofstream file;
    if (output != "-") {
        file.open(output, std::ios::binary | std::ios::trunc);
        if (!file) {
            std::cerr << "sm2 trace dump: " << output << ": cannot write\n";
            return kInvalidInput;
        }
    }
    std::ostream& out = output == "-" ? std::cout : file;
    for (const auto& [name, value] : reader->header().properties) out << "// " << name << " = " << escape(value) << '\n';
    while (auto call = reader->next()) out << at::to_text(*call) << '\n';
    out.flush();
    if (!out) {
        std::cerr << "sm2 trace dump: " << (output == "-" ? std::string("<stdout>") : output) << ": write error\n";
        return kInvalidInput;
    }
    if (reader->error()) {
        std::cerr << "sm2 trace dump: " << display_name(input) << ": " << reader->error()->to_string() << '\n';
        return kInvalidInput;
    }
    return kOk;
}

}  // namespace

void add_trace_commands(CLI::App& app, int& status) {
    auto* trace_cmd = app.add_subcommand("trace", "apitrace trace files (D3D9 captures)");
    trace_cmd->require_subcommand(1);

    auto dump_in = std::make_shared<std::string>();
    auto dump_out = std::make_shared<std::string>("-");
    auto* dump_cmd = trace_cmd->add_subcommand("dump", "A trace as text, one call per line (as apitrace dump prints it)");
    dump_cmd->add_option("input", *dump_in, "apitrace trace file ('-' for stdin)")->required();
    dump_cmd->add_option("-o,--output", *dump_out, "Text output file ('-' for stdout, the default)");
    dump_cmd->callback([dump_in, dump_out, &status] { status = run_trace_dump(*dump_in, *dump_out); });
}

}  // namespace sm2::tools
