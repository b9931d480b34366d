#include "frontend.h"

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>
#include <spirv-tools/optimizer.hpp>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <utility>

namespace sm2::hlsl {

namespace {

constexpr size_t kMaxIncludeBytes = 16u << 20;

// #include "x" searches the including file's folder, then the -I folders; <x> only the -I folders.
class FileIncluder : public glslang::TShader::Includer {
public:
    FileIncluder(std::string main_file, std::vector<std::string> dirs)
        : main_file_(std::move(main_file)), dirs_(std::move(dirs)) {}

    IncludeResult* includeLocal(const char* header, const char* includer, size_t depth) override {
        const std::filesystem::path from = (includer && *includer) ? includer : main_file_.c_str();
        return open(from.parent_path() / header, header, depth).value_or(nullptr);
    }
    IncludeResult* includeSystem(const char* header, const char* /*includer*/, size_t depth) override {
        for (const auto& dir : dirs_)
            if (auto found = open(std::filesystem::path(dir) / header, header, depth)) return *found;
        return nullptr;
    }
    void releaseInclude(IncludeResult* result) override {
        if (result == nullptr) return;
        delete static_cast<std::string*>(result->userData);
        delete result;
    }

private:
    // nullopt: not there (try the next folder); a result with an empty name: an error to report.
    std::optional<IncludeResult*> open(const std::filesystem::path& path, const char* header, size_t depth) {
        if (depth > 32) return failure("#include nested more than 32 deep");
        std::error_code ec;
        if (!std::filesystem::is_regular_file(path, ec)) return std::nullopt;
        if (std::filesystem::file_size(path, ec) > kMaxIncludeBytes)
            return failure(std::string("included file '") + header + "' is larger than 16 MiB");
        std::ifstream in(path, std::ios::binary);
        std::stringstream text;
        text << in.rdbuf();
        auto* data = new std::string(text.str());
        return new IncludeResult(path.string(), data->data(), data->size(), data);
    }
    IncludeResult* failure(const std::string& message) {
        auto* data = new std::string(message);
        return new IncludeResult("", data->data(), data->size(), data);
    }

    std::string main_file_;
    std::vector<std::string> dirs_;
};

// glslang reports "ERROR: file:line: 'token' : message" (and "file:line:column:" with columns);
// each becomes a located diagnostic. Summary lines ("N compilation errors") are dropped.
void add_glslang_log(const std::string& log, const std::string& file, std::vector<assembler::Diagnostic>& out) {
    std::istringstream lines(log);
    std::string line;
    while (std::getline(lines, line)) {
        assembler::Severity severity;
        std::string rest;
        if (line.rfind("ERROR: ", 0) == 0) {
            severity = assembler::Severity::Error;
            rest = line.substr(7);
        } else if (line.rfind("WARNING: ", 0) == 0) {
            severity = assembler::Severity::Warning;
            rest = line.substr(9);
        } else {
            continue;
        }
        if (rest.find("compilation errors") != std::string::npos || rest.find("No code generated") != std::string::npos)
            continue;
        assembler::Diagnostic d;
        d.severity = severity;
        d.file = file;
        // "name:line: message" or "name:line:column: message"; the name may itself hold ':'.
        size_t pos = rest.find(": ");
        std::string where = pos == std::string::npos ? std::string() : rest.substr(0, pos);
        auto take_number = [&](uint32_t& value) {
            const size_t colon = where.rfind(':');
            if (colon == std::string::npos) return false;
            const std::string digits = where.substr(colon + 1);
            if (digits.empty() || digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos)
                return false;
            value = static_cast<uint32_t>(std::stoul(digits));
            where.resize(colon);
            return true;
        };
        uint32_t a = 0, b = 0;
        if (take_number(a)) {
            if (take_number(b)) {
                d.line = b;
                d.column = a;
            } else {
                d.line = a;
            }
            if (!where.empty() && where != "0") d.file = where;
            d.message = rest.substr(pos + 2);
        } else {
            d.message = rest;
        }
        if (d.line > 0 && d.column == 0) d.column = 1;
        d.message.erase(d.message.find_last_not_of(" \t\r") + 1);  // glslang ends most with a space
        out.push_back(std::move(d));
    }
}

// SPIRV-Tools unrolls only loops whose OpLoopMerge asks for it; SM2 has no loops in ps_2_0 (and
// only i#-counted ones in vs_2_0), so every loop is asked to be unrolled, as with HLSL's [unroll].
void mark_loops_for_unrolling(std::vector<uint32_t>& words) {
    constexpr uint32_t kOpLoopMerge = 246, kUnroll = 0x1, kDontUnroll = 0x2;
    for (size_t i = 5; i < words.size();) {
        const uint32_t count = words[i] >> 16;
        if (count == 0) return;
        if ((words[i] & 0xFFFF) == kOpLoopMerge && count >= 4 && i + 3 < words.size() && !(words[i + 3] & kDontUnroll))
            words[i + 3] |= kUnroll;
        i += count;
    }
}

void initialize_glslang() {
    static std::once_flag once;
    std::call_once(once, [] { glslang::InitializeProcess(); });
}

// The whole front end, in this process; hlsl_to_spirv runs it in a child process (see there).
SpirvModule hlsl_to_spirv_unguarded(std::string_view source, const CompileOptions& options) {
    initialize_glslang();
    SpirvModule result;
    const EShLanguage stage = options.stage == isa::ShaderType::Vertex ? EShLangVertex : EShLangFragment;
    glslang::TShader shader(stage);
    const std::string text(source);
    const char* strings[] = {text.c_str()};
    const int lengths[] = {static_cast<int>(text.size())};
    const char* names[] = {options.file_name.c_str()};
    shader.setStringsWithLengthsAndNames(strings, lengths, names, 1);
    std::string preamble;
    for (const auto& [name, value] : options.defines) preamble += "#define " + name + " " + value + "\n";
    shader.setPreamble(preamble.c_str());
    shader.setEntryPoint(options.entry_point.c_str());
    shader.setEnvInput(glslang::EShSourceHlsl, stage, glslang::EShClientVulkan, 100);
    shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_0);
    shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_0);
    shader.setEnvTargetHlslFunctionality1();  // keeps the semantic strings (UserSemantic)
    shader.setAutoMapLocations(true);
    // DX9 compatibility: sampler2D/tex2D and the DX9 semantics (COLOR, POSITION).
    const auto messages = static_cast<EShMessages>(EShMsgReadHlsl | EShMsgSpvRules | EShMsgVulkanRules |
                                                   EShMsgHlslDX9Compatible | EShMsgDebugInfo |
                                                   EShMsgHlslLegalization | EShMsgHlslOffsets);
    FileIncluder includer(options.file_name, options.include_dirs);
    if (lengths[0] < 0 || !shader.parse(GetDefaultResources(), 100, false, messages, includer)) {
        add_glslang_log(shader.getInfoLog(), options.file_name, result.diagnostics);
        if (result.diagnostics.empty())
            result.diagnostics.push_back({assembler::Severity::Error, options.file_name, 0, 0, "HLSL parse failed"});
        return result;
    }
    glslang::TProgram program;
    program.addShader(&shader);
    if (!program.link(messages) || !program.mapIO()) {
        add_glslang_log(program.getInfoLog(), options.file_name, result.diagnostics);
        if (!has_errors(result.diagnostics))
            result.diagnostics.push_back({assembler::Severity::Error, options.file_name, 0, 0,
                                          "link failed (is the entry point '" + options.entry_point + "' defined?)"});
        return result;
    }
    add_glslang_log(shader.getInfoLog(), options.file_name, result.diagnostics);  // warnings

    std::vector<uint32_t> spirv;
    glslang::SpvOptions spv_options;
    spv_options.generateDebugInfo = true;  // OpLine, so that back-end errors name the HLSL line
    spv_options.disableOptimizer = true;   // we run our own pass list below
    spv::SpvBuildLogger logger;
    glslang::GlslangToSpv(*program.getIntermediate(stage), spirv, &logger, &spv_options);

    mark_loops_for_unrolling(spirv);
    spvtools::Optimizer optimizer(SPV_ENV_UNIVERSAL_1_0);
    std::string optimizer_errors;
    optimizer.SetMessageConsumer([&](spv_message_level_t level, const char*, const spv_position_t&, const char* m) {
        if (level <= SPV_MSG_ERROR) optimizer_errors += std::string(m) + "\n";
    });
    optimizer.RegisterLegalizationPasses();
    optimizer.RegisterPerformancePasses();
    // SM2 has no dynamic loops in ps_2_0 and only constant-count ones in vs_2_0: unroll them all.
    optimizer.RegisterPass(spvtools::CreateLoopUnrollPass(true));
    optimizer.RegisterPerformancePasses();
    optimizer.RegisterPass(spvtools::CreateIfConversionPass());
    optimizer.RegisterPass(spvtools::CreateBlockMergePass());
    optimizer.RegisterPass(spvtools::CreateSimplificationPass());
    optimizer.RegisterPass(spvtools::CreateAggressiveDCEPass());
    spvtools::OptimizerOptions run_options;
    run_options.set_run_validator(false);
    if (!optimizer.Run(spirv.data(), spirv.size(), &result.words, run_options)) {
        result.words.clear();
        result.diagnostics.push_back({assembler::Severity::Error, options.file_name, 0, 0,
                                      "SPIR-V optimizer failed: " + optimizer_errors});
    }
    return result;
}

// The child's answer on the pipe: the SPIR-V words, then each diagnostic. Native byte order:
// the reader is the same program.
class ModuleWriter {
public:
    void u32(uint32_t value) { bytes_.append(reinterpret_cast<const char*>(&value), sizeof value); }
    void text(const std::string& value) {
        u32(static_cast<uint32_t>(value.size()));
        bytes_ += value;
    }
    [[nodiscard]] const std::string& bytes() const { return bytes_; }

private:
    std::string bytes_;
};

class ModuleReader {
public:
    explicit ModuleReader(std::string_view bytes) : bytes_(bytes) {}
    bool u32(uint32_t& value) {
        if (bytes_.size() - pos_ < sizeof value) return false;
        std::memcpy(&value, bytes_.data() + pos_, sizeof value);
        pos_ += sizeof value;
        return true;
    }
    bool text(std::string& value) {
        uint32_t size = 0;
        if (!u32(size) || bytes_.size() - pos_ < size) return false;
        value.assign(bytes_.substr(pos_, size));
        pos_ += size;
        return true;
    }
    [[nodiscard]] bool at_end() const { return pos_ == bytes_.size(); }

private:
    std::string_view bytes_;
    size_t pos_ = 0;
};

std::string serialize_module(const SpirvModule& module) {
    ModuleWriter out;
    out.u32(static_cast<uint32_t>(module.words.size()));
    for (uint32_t word : module.words) out.u32(word);
    out.u32(static_cast<uint32_t>(module.diagnostics.size()));
    for (const auto& d : module.diagnostics) {
        out.u32(static_cast<uint32_t>(d.severity));
        out.text(d.file);
        out.u32(d.line);
        out.u32(d.column);
        out.text(d.message);
    }
    return out.bytes();
}

std::optional<SpirvModule> deserialize_module(std::string_view bytes) {
    ModuleReader in(bytes);
    SpirvModule module;
    uint32_t count = 0;
    if (!in.u32(count) || count > bytes.size() / 4) return std::nullopt;
    module.words.resize(count);
    for (uint32_t& word : module.words)
        if (!in.u32(word)) return std::nullopt;
    if (!in.u32(count) || count > bytes.size()) return std::nullopt;
    for (uint32_t i = 0; i < count; ++i) {
        assembler::Diagnostic d;
        uint32_t severity = 0;
        if (!in.u32(severity) || severity > static_cast<uint32_t>(assembler::Severity::Note) || !in.text(d.file) ||
            !in.u32(d.line) || !in.u32(d.column) || !in.text(d.message))
            return std::nullopt;
        d.severity = static_cast<assembler::Severity>(severity);
        module.diagnostics.push_back(std::move(d));
    }
    if (!in.at_end()) return std::nullopt;
    return module;
}

bool write_all(int fd, std::string_view bytes) {
    while (!bytes.empty()) {
        const ssize_t written = ::write(fd, bytes.data(), bytes.size());
        if (written < 0 && errno == EINTR) continue;
        if (written <= 0) return false;
        bytes.remove_prefix(static_cast<size_t>(written));
    }
    return true;
}

std::string read_all(int fd) {
    std::string bytes;
    char buffer[65536];
    for (;;) {
        const ssize_t got = ::read(fd, buffer, sizeof buffer);
        if (got < 0 && errno == EINTR) continue;
        if (got <= 0) return bytes;
        bytes.append(buffer, static_cast<size_t>(got));
    }
}

SpirvModule front_end_failure(const CompileOptions& options, const std::string& message) {
    SpirvModule module;
    module.diagnostics.push_back({assembler::Severity::Error, options.file_name, 1, 1, message});
    return module;
}

}  // namespace

// glslang 12 dereferences a null pointer when a global uniform is declared again with a different
// type (`sampler2D t; float4 t;`, `float4 x; float3 x;`, also reached after syntax errors):
// TParseContextBase::growGlobalUniformBlock builds its "Types must match" error from the new
// member's field name, which is set only on the copy it made. That library, and whatever else
// malformed input finds in it, is not ours to fix, so the front end runs in a forked child
// process; a child that dies becomes an error at the top of the file instead of killing sm2.
// A mutex keeps other threads of this process out of glslang (and its global locks) while forking.
SpirvModule hlsl_to_spirv(std::string_view source, const CompileOptions& options) {
    static std::mutex front_end_mutex;
    const std::lock_guard lock(front_end_mutex);
    // glslang builds its table of HLSL built-ins on a stage's first parse and keeps it for the
    // process; built once here from a fixed shader, every child inherits it instead of rebuilding
    // it (the bulk of a compile's time).
    static bool warm[2] = {false, false};
    if (!std::exchange(warm[options.stage == isa::ShaderType::Vertex], true)) {
        CompileOptions warm_up = options;
        warm_up.entry_point = "main";
        warm_up.defines.clear();
        (void)hlsl_to_spirv_unguarded("float4 main() : POSITION { return 0; }\n", warm_up);
    }
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0)  // not inherited by programs other threads start
        return front_end_failure(options, std::string("cannot start the HLSL front end: pipe: ") + std::strerror(errno));
    const pid_t child = ::fork();
    if (child < 0) {
        const int error = errno;
        ::close(fds[0]);
        ::close(fds[1]);
        return front_end_failure(options, std::string("cannot start the HLSL front end: fork: ") + std::strerror(error));
    }
    if (child == 0) {
        ::close(fds[0]);
        // Die by the signal, quietly: no sanitizer or fuzzer crash handler, the parent reports it.
        for (const int crash_signal : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) std::signal(crash_signal, SIG_DFL);
        const bool sent = write_all(fds[1], serialize_module(hlsl_to_spirv_unguarded(source, options)));
        ::_exit(sent ? 0 : 1);  // no exit handlers: they belong to the parent (leak checks, files)
    }
    ::close(fds[1]);
    const std::string answer = read_all(fds[0]);
    ::close(fds[0]);
    int status = 0;
    while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
    }
    std::optional<SpirvModule> module;
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) module = deserialize_module(answer);
    if (module) return std::move(*module);
    const std::string how = WIFSIGNALED(status) ? "with signal " + std::to_string(WTERMSIG(status))
                                                : "with exit status " + std::to_string(WEXITSTATUS(status));
    return front_end_failure(options, "the HLSL front end (glslang) crashed on this input (" + how +
                                          "); glslang 12 does on a global declared twice with different "
                                          "types, as in `float4 x; float3 x;`");
}

}  // namespace sm2::hlsl
