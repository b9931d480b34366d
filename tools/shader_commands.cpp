// sm2 asm / dis / validate / compile.
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <string_view>

#include "commands.h"
#include "io.h"
#include "violations.h"
#include "sm2/assembler/assembler.h"
#include "sm2/assembler/disassembler.h"
#include "sm2/hlsl/compiler.h"
#include "sm2/isa/bytecode.h"
#include "sm2/isa/validator.h"

namespace sm2::tools {

namespace {

std::string hex_word(uint32_t t) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "%08X", t);
    return buf;
}

// Bytecode as hex words, one statement per line (version and END on their own lines).
std::string format_hex(const std::vector<uint32_t>& tokens) {
    std::string out;
    auto decoded = isa::decode(tokens);
    std::vector<size_t> starts;
    if (decoded.ok())
        for (const auto& ins : decoded.program->instructions) starts.push_back(ins.token_offset);
    starts.push_back(tokens.size() - 1);  // END
    size_t next = 0;
    for (size_t i = 0; i < tokens.size(); ++i) {
        if (i > 0) {
            const bool new_line = next < starts.size() && starts[next] == i;
            out += new_line ? '\n' : ' ';
            if (new_line) ++next;
        }
        out += hex_word(tokens[i]);
    }
    return out + '\n';
}

std::string format_c_array(const std::vector<uint32_t>& tokens, const std::string& name) {
    std::string out = "const unsigned int " + name + "[" + std::to_string(tokens.size()) + "] = {\n";
    for (size_t i = 0; i < tokens.size(); ++i) {
        if (i % 6 == 0) out += "   ";
        out += " 0x" + hex_word(tokens[i]) + (i + 1 < tokens.size() ? "," : "");
        if (i % 6 == 5 || i + 1 == tokens.size()) out += '\n';
    }
    return out + "};\n";
}

// Hex words separated by whitespace or commas, with optional 0x prefixes (the `--format hex`
// and `--format c` outputs and hand-written dumps); nullopt if anything else is in the text.
std::optional<std::vector<uint32_t>> parse_hex_words(std::string_view text) {
    std::vector<uint32_t> words;
    size_t i = 0;
    auto skip_separators = [&] {
        while (i < text.size() && (std::isspace(static_cast<unsigned char>(text[i])) || text[i] == ','))
            ++i;
    };
    for (skip_separators(); i < text.size(); skip_separators()) {
        if (text.compare(i, 2, "0x") == 0 || text.compare(i, 2, "0X") == 0) i += 2;
        size_t digits = 0;
        uint32_t value = 0;
        while (i < text.size() && std::isxdigit(static_cast<unsigned char>(text[i]))) {
            if (++digits > 8) return std::nullopt;
            const char c = static_cast<char>(std::tolower(static_cast<unsigned char>(text[i])));
            value = value << 4 | static_cast<uint32_t>(c <= '9' ? c - '0' : c - 'a' + 10);
            ++i;
        }
        if (digits == 0) return std::nullopt;
        words.push_back(value);
    }
    if (words.empty()) return std::nullopt;
    return words;
}

std::string_view as_text(const std::vector<std::byte>& bytes) {
    return {reinterpret_cast<const char*>(bytes.data()), bytes.size()};
}

void print_diagnostics(const std::vector<assembler::Diagnostic>& diagnostics) {
    for (const auto& d : diagnostics) std::cerr << d.to_string() << '\n';
}


// Reads bytecode (binary or hex words); prints the error and returns nullopt on failure.
std::optional<isa::Program> load_bytecode(const std::string& name, const std::vector<std::byte>& bytes) {
    isa::DecodeResult result;
    if (isa::looks_like_bytecode(bytes)) {
        result = isa::decode_bytes(bytes);
    } else if (auto words = parse_hex_words(as_text(bytes))) {
        result = isa::decode(*words);
    } else {
        std::cerr << name << ": error: not shader bytecode (expected a vs/ps version token, "
                             "binary or as hex words)\n";
        return std::nullopt;
    }
    if (!result.ok()) {
        std::cerr << name << ": error: " << result.error->to_string() << '\n';
        return std::nullopt;
    }
    return std::move(*result.program);
}

bool looks_like_assembly(const std::vector<std::byte>& bytes) {
    return !isa::looks_like_bytecode(bytes) && !parse_hex_words(as_text(bytes));
}

// Empty when `name` is a C identifier that is not a keyword (it is written into C source).
std::string c_identifier_error(const std::string& name) {
    static constexpr std::string_view kKeywords[] = {
        "auto", "break", "case", "char", "const", "continue", "default", "do", "double", "else", "enum",
        "extern", "float", "for", "goto", "if", "inline", "int", "long", "register", "restrict", "return",
        "short", "signed", "sizeof", "static", "struct", "switch", "typedef", "union", "unsigned", "void",
        "volatile", "while", "_Bool", "_Complex", "_Imaginary", "bool", "true", "false"};
    const bool ok = !name.empty() && (std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_') &&
                    std::all_of(name.begin(), name.end(), [](char c) {
                        return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
                    });
    if (!ok) return "'" + name + "' is not a C identifier (letters, digits and '_', not starting with a digit)";
    for (std::string_view k : kKeywords)
        if (name == k) return "'" + name + "' is a C keyword";
    return {};
}

struct AsmOptions {
    std::string input;
    std::string output = "-";
    std::string format;
    std::string array_name = "g_shader";
    bool no_validate = false;
    bool wine_order = false;
    unsigned max_slots = 0;
};

// The file stdout is redirected to, when it is a regular file with the extension of a binary
// shader (`sm2 asm x.asm > x.pso`); empty otherwise.
std::string stdout_binary_file() {
    struct stat st {};
    if (fstat(STDOUT_FILENO, &st) != 0 || !S_ISREG(st.st_mode)) return {};
    std::error_code ec;
    const auto target = std::filesystem::read_symlink("/proc/self/fd/1", ec);
    if (ec) return {};
    std::string ext = target.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); });
    constexpr std::array<std::string_view, 8> kBinary = {".bin", ".pso", ".vso", ".fxo", ".cso", ".o", ".obj", ".dxbc"};
    return std::find(kBinary.begin(), kBinary.end(), ext) != kBinary.end() ? target.string() : std::string();
}

int run_asm(const AsmOptions& o) {
    // Binary goes to a file, text to stdout: '-o -' (stdout) takes the text forms only.
    if (o.format == "bin" && o.output == "-") {
        std::cerr << "sm2 asm: binary output goes to a file: use -o FILE (or --format hex or c for text on "
                     "stdout)\n";
        return kBadUsage;
    }
    std::string error;
    auto bytes = read_input(o.input, error);
    if (!bytes) {
        std::cerr << "sm2 asm: " << error << '\n';
        return kInvalidInput;
    }
    assembler::AssembleOptions options;
    options.file_name = display_name(o.input);
    options.validate = !o.no_validate;
    options.wine_order = o.wine_order;
    options.validation.max_instruction_slots = o.max_slots;
    auto result = assembler::assemble(as_text(*bytes), options);
    print_diagnostics(result.diagnostics);
    if (!result.ok()) return kInvalidInput;

    // Without -o the bytes go to stdout as text (hex); with -o FILE, binary.
    const std::string format = !o.format.empty() ? o.format : (o.output == "-" ? "hex" : "bin");
    if (o.format.empty() && o.output == "-")
        if (const std::string file = stdout_binary_file(); !file.empty())
            std::cerr << "sm2 asm: note: stdout is " << file << ": writing hex words (text) there; for the "
                      << "binary bytecode use -o " << file << '\n';
    bool written = false;
    if (format == "bin")
        written = write_output(o.output, isa::to_bytes(result.tokens), error);
    else if (format == "hex")
        written = write_output(o.output, format_hex(result.tokens), error);
    else
        written = write_output(o.output, format_c_array(result.tokens, o.array_name), error);
    if (!written) {
        std::cerr << "sm2 asm: " << error << '\n';
        return kInvalidInput;
    }
    return kOk;
}

int run_dis(const std::string& input, const std::string& output) {
    std::string error;
    auto bytes = read_input(input, error);
    if (!bytes) {
        std::cerr << "sm2 dis: " << error << '\n';
        return kInvalidInput;
    }
    const std::string name = display_name(input);
    auto program = load_bytecode(name, *bytes);
    if (!program) return kInvalidInput;
    // Only text that assembles back to the same bytes is written.
    const assembler::CheckedDisassembly dis = assembler::disassemble_checked(*program);
    if (dis.error) {
        std::cerr << name << ": token " << dis.error->token_offset << " (byte 0x" << std::hex
                  << dis.error->token_offset * 4 << std::dec << "): error: " << dis.error->message << '\n';
        return kInvalidInput;
    }
    if (!write_output(output, dis.text, error)) {
        std::cerr << "sm2 dis: " << error << '\n';
        return kInvalidInput;
    }
    return kOk;
}

int run_validate(const std::string& input, unsigned max_slots) {
    std::string error;
    auto bytes = read_input(input, error);
    if (!bytes) {
        std::cerr << "sm2 validate: " << error << '\n';
        return kInvalidInput;
    }
    const std::string name = display_name(input);
    isa::ValidationOptions validation;
    validation.max_instruction_slots = max_slots;

    if (looks_like_assembly(*bytes)) {
        assembler::AssembleOptions options;
        options.file_name = name;
        options.validation = validation;
        auto result = assembler::assemble(as_text(*bytes), options);
        print_diagnostics(result.diagnostics);
        if (!result.ok()) return kInvalidInput;
        std::cout << name << ": valid " << result.program->version.name() << ", "
                  << isa::slot_summary(isa::count_slots(*result.program)) << '\n';
        return kOk;
    }
    auto program = load_bytecode(name, *bytes);
    if (!program) return kInvalidInput;
    const auto violations = isa::validate(*program, validation);
    print_violations(std::cerr, name, *program, violations);
    if (!violations.empty()) return kInvalidInput;
    std::cout << name << ": valid " << program->version.name() << ", " << isa::slot_summary(isa::count_slots(*program))
              << '\n';
    return kOk;
}

struct CompileCommandOptions {
    std::string input;
    std::string output = "-";
    std::string format;
    std::string array_name = "g_shader";
    std::string profile;
    std::string entry = "main";
    std::vector<std::string> defines;
    std::vector<std::string> include_dirs;
    bool fxc_errors = false;
    bool debug_info = false;
};

// Empty when `define` is NAME or NAME=VALUE with NAME an identifier.
std::string define_error(const std::string& define) {
    const std::string name = define.substr(0, define.find('='));
    const bool ok = !name.empty() && (std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_') &&
                    std::all_of(name.begin(), name.end(), [](char c) {
                        return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
                    }) && define.find_first_of("\n\r") == std::string::npos;
    return ok ? std::string() : "'" + define + "' is not NAME or NAME=VALUE (NAME an identifier, one line)";
}

// Binary goes to a file, text to stdout, as for asm: hex words on stdout without -o.
bool write_bytecode(const std::string& command, const std::string& output, const std::string& requested_format,
                    const std::string& array_name, const std::vector<uint32_t>& tokens) {
    const std::string format = !requested_format.empty() ? requested_format : (output == "-" ? "hex" : "bin");
    std::string error;
    bool written = false;
    if (format == "bin")
        written = write_output(output, isa::to_bytes(tokens), error);
    else if (format == "hex")
        written = write_output(output, format_hex(tokens), error);
    else
        written = write_output(output, format_c_array(tokens, array_name), error);
    if (!written) std::cerr << "sm2 " << command << ": " << error << '\n';
    return written;
}

int run_compile(const CompileCommandOptions& o) {
    if (o.format == "bin" && o.output == "-") {
        std::cerr << "sm2 compile: binary output goes to a file: use -o FILE (or --format hex or c for text on "
                     "stdout)\n";
        return kBadUsage;
    }
    const auto stage = hlsl::parse_profile(o.profile);
    if (!stage) {
        std::cerr << "sm2 compile: -T " << o.profile << ": the profiles are vs_2_0 and ps_2_0\n";
        return kBadUsage;
    }
    std::string error;
    auto bytes = read_input(o.input, error);
    if (!bytes) {
        std::cerr << "sm2 compile: " << error << '\n';
        return kInvalidInput;
    }
    hlsl::CompileOptions options;
    options.file_name = o.input == "-" ? display_name(o.input) : o.input;
    options.entry_point = o.entry;
    options.stage = *stage;
    options.include_dirs = o.include_dirs;
    options.debug_info = o.debug_info;
    for (const auto& d : o.defines) {
        const size_t eq = d.find('=');
        options.defines.emplace_back(d.substr(0, eq), eq == std::string::npos ? "1" : d.substr(eq + 1));
    }
    const auto result = hlsl::compile(as_text(*bytes), options);
    for (const auto& d : result.diagnostics) {
        if (o.fxc_errors) {
            std::cerr << hlsl::format_fxc(d) << '\n';
            continue;
        }
        // fxc's form without its error number, file(line,col): error: message, which IDEs parse.
        std::cerr << d.file;
        if (d.line > 0) std::cerr << '(' << d.line << ',' << d.column << ')';
        std::cerr << ": " << (d.severity == assembler::Severity::Error ? "error" : d.severity == assembler::Severity::Warning ? "warning" : "note")
                  << ": " << d.message << '\n';
    }
    if (!result.ok()) return kInvalidInput;
    return write_bytecode("compile", o.output, o.format, o.array_name, result.tokens) ? kOk : kInvalidInput;
}

}  // namespace

void add_shader_commands(CLI::App& app, int& status) {
    auto asm_options = std::make_shared<AsmOptions>();
    auto* asm_cmd = app.add_subcommand("asm", "Assemble vs_2_0/ps_2_0 text into D3D9 bytecode");
    asm_cmd->add_option("input", asm_options->input, "Assembly file ('-' for stdin)")->required();
    asm_cmd->add_option("-o,--output", asm_options->output,
                        "Output file (default: stdout, '-', which takes the text forms hex and c only)");
    asm_cmd->add_option("--format", asm_options->format,
                        "bin (raw little-endian DWORDs, the default with -o FILE), hex (words as text, the default on "
                        "stdout) or c (a C array)")
        ->check(CLI::IsMember({"bin", "hex", "c"}));
    asm_cmd->add_option("--name", asm_options->array_name, "Array name for --format c (a C identifier)")
        ->check(CLI::Validator(c_identifier_error, "C identifier", "C identifier"));
    asm_cmd->add_flag("--no-validate", asm_options->no_validate,
                      "Encode without running the validator (as Wine's assembler does)");
    asm_cmd->add_flag("--wine-order", asm_options->wine_order,
                      "Write Wine's statement order (every dcl, then every def, defb, defi, then the rest) instead "
                      "of the source order (what Microsoft's assemblers keep)");
    asm_cmd->add_option("--max-slots", asm_options->max_slots,
                        "Raise the instruction-slot limit (e.g. 512 for ps_2_x-size shaders)");
    asm_cmd->callback([asm_options, &status] { status = run_asm(*asm_options); });

    auto dis_input = std::make_shared<std::string>();
    auto dis_output = std::make_shared<std::string>("-");
    auto* dis_cmd = app.add_subcommand("dis", "Disassemble D3D9 shader bytecode (binary or hex words)");
    dis_cmd->add_option("input", *dis_input, "Bytecode file ('-' for stdin)")->required();
    dis_cmd->add_option("-o,--output", *dis_output, "Output file ('-' for stdout, the default)");
    dis_cmd->callback([dis_input, dis_output, &status] { status = run_dis(*dis_input, *dis_output); });

    auto val_input = std::make_shared<std::string>();
    auto val_slots = std::make_shared<unsigned>(0);
    auto* val_cmd = app.add_subcommand(
        "validate", "Check a shader (text or bytecode) against the documented vs_2_0/ps_2_0 rules");
    val_cmd->add_option("input", *val_input, "Shader file ('-' for stdin)")->required();
    val_cmd->add_option("--max-slots", *val_slots, "Raise the instruction-slot limit");
    val_cmd->callback([val_input, val_slots, &status] { status = run_validate(*val_input, *val_slots); });

    auto compile_options = std::make_shared<CompileCommandOptions>();
    auto* compile_cmd = app.add_subcommand("compile", "Compile HLSL to vs_2_0/ps_2_0 bytecode (docs/hlsl.md)");
    compile_cmd->add_option("input", compile_options->input, "HLSL file ('-' for stdin)")->required();
    compile_cmd->add_option("-T,--profile", compile_options->profile, "vs_2_0 or ps_2_0")->required();
    compile_cmd->add_option("-E,--entry", compile_options->entry, "Entry point function (default main)");
    compile_cmd->add_option("-D,--define", compile_options->defines, "Preprocessor macro NAME or NAME=VALUE")
        ->check(CLI::Validator(define_error, "NAME[=VALUE]", "NAME[=VALUE]"));
    compile_cmd->add_option("-I,--include", compile_options->include_dirs, "Folder searched by #include");
    compile_cmd->add_option("-o,--output", compile_options->output,
                            "Output file (default: stdout, '-', which takes the text forms hex and c only)");
    compile_cmd->add_option("--format", compile_options->format, "bin, hex or c, as for asm")
        ->check(CLI::IsMember({"bin", "hex", "c"}));
    compile_cmd->add_option("--name", compile_options->array_name, "Array name for --format c (a C identifier)")
        ->check(CLI::Validator(c_identifier_error, "C identifier", "C identifier"));
    compile_cmd->add_flag("--fxc-errors", compile_options->fxc_errors,
                          "Print errors with fxc's numbers: file(line,col): error X3000: message");
    compile_cmd->add_flag("-g,--debug-info", compile_options->debug_info,
                          "Add the HLSL line table (a comment block 'SM2L', as fxc /Zi adds its debug block): each "
                          "instruction's HLSL file and line, for sm2 debug");
    compile_cmd->callback([compile_options, &status] { status = run_compile(*compile_options); });
}

}  // namespace sm2::tools
