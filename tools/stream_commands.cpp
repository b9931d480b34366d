// sm2 cs pack / dump: command streams between their text and binary forms.
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "commands.h"
#include "io.h"
#include "stream_io.h"
#include "sm2/runtime/apitrace_import.h"
#include "sm2/runtime/command_stream.h"

namespace sm2::tools {

namespace {

namespace cs = runtime::cs;

// Binary goes to a file: without -o, IN.sm2cb beside IN; '-o -' (stdout) is refused.
int run_pack(const std::string& input, std::string output, const std::string& read_root) {
    if (output == "-") {
        std::cerr << "sm2 cs pack: the binary form goes to a file: use -o FILE (sm2 cs dump prints text)\n";
        return kBadUsage;
    }
    if (output.empty()) {
        if (input == "-") {
            std::cerr << "sm2 cs pack: reading stdin: name the output with -o FILE\n";
            return kBadUsage;
        }
        output = std::filesystem::path(input).replace_extension(".sm2cb").string();
        if (output == input) {
            std::cerr << "sm2 cs pack: " << input << " is already .sm2cb: name the output with -o FILE\n";
            return kBadUsage;
        }
    }
    auto loaded = load_stream(input, "cs", read_root);
    if (!loaded) return kInvalidInput;
    const cs::Stream& stream = loaded->stream;
    std::string error;
    if (!write_output(output, cs::pack(stream), error)) {
        std::cerr << "sm2 cs pack: " << error << '\n';
        return kInvalidInput;
    }
    return kOk;
}

int run_dump(const std::string& input, const std::string& output, const std::string& read_root) {
    auto loaded = load_stream(input, "cs", read_root);
    if (!loaded) return kInvalidInput;
    const cs::Stream& stream = loaded->stream;
    std::string error;
    if (!write_output(output, cs::to_text(stream), error)) {
        std::cerr << "sm2 cs dump: " << error << '\n';
        return kInvalidInput;
    }
    return kOk;
}

// An apitrace D3D9 trace to a stream: text on stdout (or -o FILE), binary when FILE ends in
// .sm2cb. The report (counts, one line per skipped kind of call) goes to stderr.
int run_import(const std::string& input, const std::string& output, bool quiet) {
    namespace at = runtime::apitrace;
    std::optional<at::Error> error;
    std::unique_ptr<at::Reader> reader;
    std::optional<std::vector<std::byte>> whole;  // stdin: read whole (at most 256 MiB)
    if (input == "-") {
        std::string read_error;
        whole = read_input(input, read_error);
        if (!whole) {
            std::cerr << "sm2 cs import: " << read_error << '\n';
            return kInvalidInput;
        }
        reader = at::Reader::open(*whole, error);
    } else {
        reader = at::Reader::open_file(input, error);
    }
    if (!reader) {
        std::cerr << "sm2 cs import: " << (error->io ? "" : display_name(input) + ": ") << error->to_string() << '\n';
        return kInvalidInput;
    }
    at::ImportResult result = at::import_d3d9(*reader);
    if (result.error) {
        std::cerr << "sm2 cs import: " << display_name(input) << ": " << result.error->to_string() << '\n';
        return kInvalidInput;
    }
    cs::Statement comment;
    comment.kind = cs::Statement::Kind::Comment;
    comment.name = " imported from " + std::filesystem::path(display_name(input)).filename().string() + " by sm2 cs import: " +
                   std::to_string(result.report.imported) + " of " + std::to_string(result.report.calls) + " calls";
    result.stream.statements.insert(result.stream.statements.begin(), std::move(comment));
    const bool binary = output.size() > 6 && output.substr(output.size() - 6) == ".sm2cb";
    std::string write_error;
    const bool written = binary ? write_output(output, cs::pack(result.stream), write_error)
                                : write_output(output, cs::to_text(result.stream), write_error);
    if (!written) {
        std::cerr << "sm2 cs import: " << write_error << '\n';
        return kInvalidInput;
    }
    if (!quiet) std::cerr << "sm2 cs import: " << display_name(input) << ": " << result.report.to_string();
    return kOk;
}

}  // namespace

void add_stream_commands(CLI::App& app, int& status) {
    auto* cs_cmd = app.add_subcommand("cs", "Command streams: convert between the text and binary forms, import apitrace traces");
    cs_cmd->require_subcommand(1);

    auto pack_in = std::make_shared<std::string>();
    auto pack_out = std::make_shared<std::string>();
    auto* pack_cmd = cs_cmd->add_subcommand("pack", "Text (.sm2cs) to binary (.sm2cb)");
    pack_cmd->add_option("input", *pack_in, "Stream, text or binary ('-' for stdin)")->required();
    pack_cmd->add_option("-o,--output", *pack_out, "Binary output file (default: the input's name with .sm2cb)");
    auto pack_root = std::make_shared<std::string>();
    add_read_root_option(*pack_cmd, *pack_root);
    pack_cmd->callback([pack_in, pack_out, pack_root, &status] { status = run_pack(*pack_in, *pack_out, *pack_root); });

    auto dump_in = std::make_shared<std::string>();
    auto dump_out = std::make_shared<std::string>("-");
    auto* dump_cmd = cs_cmd->add_subcommand("dump", "Binary (or text) to canonical text");
    dump_cmd->add_option("input", *dump_in, "Stream, binary or text ('-' for stdin)")->required();
    dump_cmd->add_option("-o,--output", *dump_out, "Text output file ('-' for stdout, the default)");
    auto dump_root = std::make_shared<std::string>();
    add_read_root_option(*dump_cmd, *dump_root);
    dump_cmd->callback([dump_in, dump_out, dump_root, &status] { status = run_dump(*dump_in, *dump_out, *dump_root); });

    auto import_in = std::make_shared<std::string>();
    auto import_out = std::make_shared<std::string>("-");
    auto import_quiet = std::make_shared<bool>(false);
    auto* import_cmd = cs_cmd->add_subcommand("import", "An apitrace D3D9 trace to a stream (docs/apitrace.md)");
    import_cmd->add_option("input", *import_in, "apitrace trace file ('-' for stdin)")->required();
    import_cmd->add_option("-o,--output", *import_out,
                           "Output: text ('-' for stdout, the default), binary when the name ends in .sm2cb");
    import_cmd->add_flag("--quiet", *import_quiet, "No report of imported and skipped calls on stderr");
    import_cmd->callback([import_in, import_out, import_quiet, &status] {
        status = run_import(*import_in, *import_out, *import_quiet);
    });
}

}  // namespace sm2::tools
