// The Python module `sm2emu` (pybind11): the public C++ API for scripts and notebooks.
//
//   assemble / disassemble / validate   shader text <-> bytecode, the validator's violations
//   run                                 one shader over NumPy arrays of lanes -> output registers
//   Device, replay                      command streams replayed; frames as NumPy arrays; the
//                                       device state the C++ Device exposes
//
// docs/python.md documents every function; python/tests/test_sm2emu.py is its test.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "sm2/assembler/assembler.h"
#include "sm2/assembler/disassembler.h"
#include "sm2/emu/engine.h"
#include "sm2/emu/jit.h"
#include "sm2/isa/bytecode.h"
#include "sm2/isa/registers.h"
#include "sm2/isa/validator.h"
#include "sm2/runtime/command_stream.h"
#include "sm2/runtime/d3d9_names.h"
#include "sm2/runtime/device.h"
#include "sm2/runtime/replay.h"
#include "sm2/runtime/sampler.h"
#include "sm2/runtime/stream_assembler.h"

namespace py = pybind11;

namespace sm2::python {

namespace {

// Raised (as sm2emu.Error, a ValueError) for invalid input: shader text that does not assemble,
// bytecode that does not decode, a register that does not exist, a stream that does not parse.
struct Error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// --- shaders ----------------------------------------------------------------------------------

std::vector<std::byte> to_byte_vector(const py::bytes& data) {
    const std::string_view view = data;
    std::vector<std::byte> bytes(view.size());
    std::transform(view.begin(), view.end(), bytes.begin(), [](char c) { return static_cast<std::byte>(c); });
    return bytes;
}

py::bytes to_py_bytes(const std::vector<uint32_t>& tokens) {
    const std::vector<std::byte> bytes = isa::to_bytes(tokens);
    return py::bytes(reinterpret_cast<const char*>(bytes.data()), bytes.size());
}

std::string diagnostics_text(const std::vector<assembler::Diagnostic>& diagnostics) {
    std::string text;
    for (const auto& d : diagnostics) {
        if (d.severity != assembler::Severity::Error) continue;
        text += (text.empty() ? "" : "\n") + d.to_string();
    }
    return text.empty() ? std::string("assembly failed") : text;
}

// Text through the assembler (validation as asked), bytecode through the decoder.
isa::Program load_program(const py::object& source, bool validate, unsigned max_slots, const std::string& file_name) {
    if (py::isinstance<py::str>(source)) {
        assembler::AssembleOptions options;
        options.file_name = file_name;
        options.validate = validate;
        options.validation.max_instruction_slots = max_slots;
        auto result = assembler::assemble(source.cast<std::string>(), options);
        if (!result.ok()) throw Error(diagnostics_text(result.diagnostics));
        return std::move(*result.program);
    }
    isa::DecodeResult decoded;
    if (py::isinstance<py::bytes>(source) || py::isinstance<py::bytearray>(source)) {
        decoded = isa::decode_bytes(to_byte_vector(py::bytes(source)));
    } else {
        auto tokens = py::array_t<uint32_t, py::array::c_style | py::array::forcecast>::ensure(source);
        if (!tokens || tokens.ndim() != 1)
            throw py::type_error("expected shader text (str), bytecode (bytes) or a 1-D array of uint32 tokens");
        decoded = isa::decode({tokens.data(), static_cast<size_t>(tokens.size())});
    }
    if (!decoded.ok()) throw Error(file_name + ": " + decoded.error->to_string());
    if (validate) {
        isa::ValidationOptions options;
        options.max_instruction_slots = max_slots;
        const auto violations = isa::validate(*decoded.program, options);
        if (!violations.empty()) {
            std::string text;
            for (const auto& v : violations)
                text += (text.empty() ? "" : "\n") + file_name + ": error: [" + std::string(isa::rule_name(v.rule)) +
                        "] " + v.message;
            throw Error(text);
        }
    }
    return std::move(*decoded.program);
}

py::bytes assemble(const std::string& text, bool validate, unsigned max_slots, const std::string& file_name) {
    assembler::AssembleOptions options;
    options.file_name = file_name;
    options.validate = validate;
    options.validation.max_instruction_slots = max_slots;
    auto result = assembler::assemble(text, options);
    if (!result.ok()) throw Error(diagnostics_text(result.diagnostics));
    return to_py_bytes(result.tokens);
}

std::string disassemble(const py::object& bytecode) {
    if (py::isinstance<py::str>(bytecode)) throw py::type_error("disassemble takes bytecode (bytes or uint32 tokens), not text");
    return assembler::disassemble(load_program(bytecode, false, 0, "<bytecode>"));
}

// One violation as a dict: rule ("read-ports"), message, instruction (index or None), line
// (1-based in the text; 0 for bytecode).
py::list validate(const py::object& source, unsigned max_slots, const std::string& file_name) {
    const isa::Program program = load_program(source, false, 0, file_name);
    isa::ValidationOptions options;
    options.max_instruction_slots = max_slots;
    py::list out;
    for (const auto& v : isa::validate(program, options)) {
        py::dict d;
        d["rule"] = std::string(isa::rule_name(v.rule));
        d["message"] = v.message;
        d["instruction"] = v.instruction == SIZE_MAX ? py::object(py::none()) : py::object(py::int_(v.instruction));
        d["line"] = v.location.line;
        out.append(std::move(d));
    }
    return out;
}

// --- run: one shader over lanes ---------------------------------------------------------------

std::string output_name(unsigned s) {
    namespace slot = emu::slot;
    if (s == slot::kPosition) return "oPos";
    if (s == slot::kFog) return "oFog";
    if (s == slot::kPointSize) return "oPts";
    if (s == slot::kDepth) return "oDepth";
    if (s >= slot::kColorOutFirst && s < slot::kColorOutFirst + slot::kColorOutCount)
        return "oD" + std::to_string(s - slot::kColorOutFirst);
    if (s >= slot::kTexCoordOutFirst && s < slot::kTexCoordOutFirst + slot::kTexCoordOutCount)
        return "oT" + std::to_string(s - slot::kTexCoordOutFirst);
    if (s >= slot::kRenderTargetFirst && s < slot::kRenderTargetFirst + slot::kRenderTargetCount)
        return "oC" + std::to_string(s - slot::kRenderTargetFirst);
    return "slot" + std::to_string(s);
}

unsigned parse_index(std::string_view text, const std::string& what) {
    if (text.empty() || text.size() > 4 || !std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; }))
        throw Error("bad register number in '" + what + "'");
    return static_cast<unsigned>(std::stoul(std::string(text)));
}

// "v0" (both shader types) or "t3" (pixel shaders) -> its slot in a batch.
unsigned input_slot(isa::ShaderVersion version, const std::string& name) {
    isa::RegisterType type = isa::RegisterType::Input;
    if (!name.empty() && name[0] == 't' && version.is_pixel()) type = isa::RegisterType::Texture;
    else if (name.empty() || name[0] != 'v')
        throw Error("unknown input register '" + name + "'" +
                    (version.is_pixel() ? " (pixel shaders read v0, v1, t0..t7)" : " (vertex shaders read v0..v15)"));
    const unsigned index = parse_index(std::string_view(name).substr(1), name);
    const isa::RegisterFile* file = isa::find_register_file(version, type, index);
    const auto slot = emu::register_slot(version.type, type, index);
    if (!file || index >= file->count || !slot) throw Error("input register '" + name + "' does not exist in " + version.name());
    return *slot;
}

// A register key of a constants dict: 4 or "c4" (prefix given).
unsigned register_key(const py::handle& key, char prefix, unsigned count) {
    unsigned index = 0;
    std::string what;
    if (py::isinstance<py::int_>(key)) {
        const long v = key.cast<long>();
        what = std::string(1, prefix) + std::to_string(v);
        if (v < 0) throw Error(what + " is out of range");
        index = static_cast<unsigned>(v);
    } else {
        what = py::str(key).cast<std::string>();
        if (what.empty() || what[0] != prefix) throw Error("expected " + std::string(1, prefix) + "N, not '" + what + "'");
        index = parse_index(std::string_view(what).substr(1), what);
    }
    if (index >= count)
        throw Error(what + " is out of range (" + prefix + "0.." + prefix + std::to_string(count - 1) + ")");
    return index;
}

std::vector<double> small_vector(const py::handle& value, const std::string& what) {
    auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
    if (!a || a.ndim() > 1 || a.size() < 1 || a.size() > 4) throw Error("expected 1 to 4 values for " + what);
    return {a.data(), a.data() + a.size()};
}

struct LaneInput {
    unsigned slot;
    py::array_t<double, py::array::c_style | py::array::forcecast> values;  // (k,) all lanes or (N, k)
};

template <typename BatchType>
py::dict execute_lanes(const emu::Executable& executable, const emu::ConstantFile& constants,
                       const std::vector<LaneInput>& inputs, size_t lanes, bool jit, emu::Sampler& sampler) {
    using Real = std::remove_reference_t<decltype(std::declval<BatchType&>().registers[0][0][0])>;
    const auto& written = executable.components_written();
    std::map<unsigned, py::array_t<Real>> outputs;
    for (unsigned s = 0; s < emu::kSlotCount; ++s)
        if (emu::is_output_slot(s) && written[s] != 0)
            outputs.emplace(s, py::array_t<Real>({static_cast<py::ssize_t>(lanes), py::ssize_t{4}}));
    py::array_t<bool> killed(static_cast<py::ssize_t>(lanes));
    std::shared_ptr<const emu::jit::CompiledShader> compiled;
    if constexpr (std::is_same_v<BatchType, emu::Batch>) {
        if (jit) {
            std::string error;
            compiled = emu::jit::compile(executable, &error);
            if (!compiled) throw Error("engine='jit': " + error);
        }
    }
    auto batch = std::make_unique<BatchType>();
    for (size_t first = 0; first < lanes; first += emu::kBatchLanes) {
        batch->reset();
        const unsigned count = static_cast<unsigned>(std::min<size_t>(emu::kBatchLanes, lanes - first));
        batch->lane_count = count;
        for (const LaneInput& in : inputs) {
            const double* data = in.values.data();
            const bool per_lane = in.values.ndim() == 2;
            const size_t width = static_cast<size_t>(in.values.shape(in.values.ndim() - 1));
            for (unsigned lane = 0; lane < count; ++lane)
                for (size_t c = 0; c < width; ++c)
                    batch->registers[in.slot][c][lane] =
                        static_cast<Real>(per_lane ? data[(first + lane) * width + c] : data[c]);
        }
        {
            py::gil_scoped_release release;
            if constexpr (std::is_same_v<BatchType, emu::Batch>) {
                if (compiled) compiled->run(constants, *batch, &sampler);
                else emu::execute(executable, constants, *batch, &sampler);
            } else {
                emu::execute(executable, constants, *batch, &sampler);
            }
        }
        auto k = killed.mutable_unchecked<1>();
        for (unsigned lane = 0; lane < count; ++lane) k(static_cast<py::ssize_t>(first + lane)) = (batch->killed >> lane) & 1u;
        for (auto& [s, array] : outputs) {
            auto out = array.template mutable_unchecked<2>();
            for (unsigned lane = 0; lane < count; ++lane)
                for (unsigned c = 0; c < 4; ++c)
                    out(static_cast<py::ssize_t>(first + lane), c) = batch->registers[s][c][lane];
        }
    }
    py::dict result;
    for (auto& [s, array] : outputs) result[py::str(output_name(s))] = std::move(array);
    if (executable.version().is_pixel()) result["killed"] = std::move(killed);
    return result;
}

emu::PrecisionOptions precision_options(const std::string& precision, const std::string& transcendentals, bool allow_fp64) {
    emu::PrecisionOptions p;
    if (precision == "fp24" || precision == "fp16") p.precision = emu::Precision::Fp24;
    else if (precision == "fp64" && allow_fp64) p.precision = emu::Precision::Fp64;
    else if (precision != "fp32")
        throw py::value_error("precision must be fp32, fp24, fp16" + std::string(allow_fp64 ? " or fp64" : "") + ", not '" +
                              precision + "'" + (precision == "fp64" ? " (fp64 is run()'s reference; draws do not run it)" : ""));
    p.partial_precision_fp16 = precision == "fp16";
    if (transcendentals == "fast") p.transcendentals = emu::Transcendentals::Fast;
    else if (transcendentals != "exact") throw py::value_error("transcendentals must be exact or fast, not '" + transcendentals + "'");
    return p;
}

bool use_jit(const std::string& engine) {
    if (engine == "interpreter") return false;
    if (engine == "jit") return emu::jit::available();  // a build without the JIT interprets: the same bytes
    throw py::value_error("engine must be jit or interpreter, not '" + engine + "'");
}

py::dict run(const py::object& shader, const py::dict& inputs, const py::dict& constants, const py::dict& integers,
             const py::dict& booleans, std::optional<size_t> lanes, const std::string& precision,
             const std::string& transcendentals, const std::string& engine) {
    isa::Program program = load_program(shader, true, 0, "<shader>");
    const isa::ShaderVersion version = program.version;
    const isa::RegisterFile* const_file = isa::find_register_file(version, "c");
    const unsigned constant_count = const_file ? const_file->count : 0;

    std::vector<std::array<float, 4>> application(constant_count, {0, 0, 0, 0});
    for (const auto& [key, value] : constants) {
        const unsigned index = register_key(key, 'c', constant_count);
        const auto v = small_vector(value, "c" + std::to_string(index));
        for (size_t c = 0; c < v.size(); ++c) application[index][c] = static_cast<float>(v[c]);
    }
    emu::StaticFlowConstants flow;
    for (const auto& [key, value] : integers) {
        const unsigned index = register_key(key, 'i', emu::kIntConstants);
        const auto v = small_vector(value, "i" + std::to_string(index));
        for (size_t c = 0; c < v.size(); ++c) flow.integers[index][c] = static_cast<int32_t>(v[c]);
    }
    for (const auto& [key, value] : booleans) flow.booleans[register_key(key, 'b', emu::kBoolConstants)] = PyObject_IsTrue(value.ptr()) == 1;

    std::vector<LaneInput> lane_inputs;
    size_t lane_count = lanes.value_or(0);
    for (const auto& [key, value] : inputs) {
        const std::string name = py::str(key);
        LaneInput in{input_slot(version, name), py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value)};
        if (!in.values || in.values.ndim() < 1 || in.values.ndim() > 2 || in.values.shape(in.values.ndim() - 1) < 1 ||
            in.values.shape(in.values.ndim() - 1) > 4)
            throw Error("input " + name + ": expected (k,) for every lane or (lanes, k) per lane, k = 1..4");
        if (in.values.ndim() == 2) {
            const auto n = static_cast<size_t>(in.values.shape(0));
            if (lanes && n != *lanes)
                throw Error("input " + name + " has " + std::to_string(n) + " lanes, lanes=" + std::to_string(*lanes));
            if (!lanes && lane_count != 0 && n != lane_count)
                throw Error("input " + name + " has " + std::to_string(n) + " lanes where another input has " +
                            std::to_string(lane_count));
            lane_count = n;
        }
        lane_inputs.push_back(std::move(in));
    }
    if (lane_count == 0) lane_count = lanes ? 0 : 1;
    if (lane_count == 0) throw Error("lanes must be at least 1");

    emu::LoweringOptions lowering;
    lowering.precision = precision_options(precision, transcendentals, true);
    auto created = emu::Shader::create(std::move(program));
    if (!created.shader) throw Error(created.error);
    auto lowered = emu::lower(*created.shader, flow, lowering);
    if (!lowered.executable) throw Error(lowered.error);
    const emu::ConstantFile bound = lowered.executable->bind_constants(application);
    runtime::TextureSampler sampler;  // no textures bound: texld reads (0, 0, 0, 1)
    if (precision == "fp64")
        return execute_lanes<emu::ReferenceBatch>(*lowered.executable, bound, lane_inputs, lane_count, false, sampler);
    return execute_lanes<emu::Batch>(*lowered.executable, bound, lane_inputs, lane_count, use_jit(engine), sampler);
}

// --- devices and replays ----------------------------------------------------------------------

// A surface as Present writes it to a PNG: RGBA, 8 bits, clamped to [0,1], round(v * 255), NaN 0.
struct Rgba8 {
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> bytes;
};

uint8_t to_unorm8(float v) {
    if (!(v > 0.0f)) return 0;
    if (v >= 1.0f) return 255;
    return static_cast<uint8_t>(std::lround(static_cast<double>(v) * 255.0));
}

Rgba8 to_rgba8(const runtime::Surface& surface) {
    Rgba8 image{surface.width(), surface.height(), {}};
    image.bytes.resize(size_t{image.width} * image.height * 4);
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x) {
            const auto v = surface.read(x, y, 0);
            for (unsigned c = 0; c < 4; ++c) image.bytes[(size_t{y} * image.width + x) * 4 + c] = to_unorm8(v[c]);
        }
    return image;
}

py::array_t<uint8_t> to_array(const Rgba8& image) {
    py::array_t<uint8_t> a({static_cast<py::ssize_t>(image.height), static_cast<py::ssize_t>(image.width), py::ssize_t{4}});
    std::copy(image.bytes.begin(), image.bytes.end(), a.mutable_data());
    return a;
}

// Present and SaveSurface write here instead of files: the Device's output folder is this
// marker, and its write_image keeps the images in memory.
constexpr std::string_view kMemoryDir = "<sm2emu-memory>";

struct PyDevice {
    std::unique_ptr<runtime::Device> device;
    std::vector<Rgba8> frames;                // every Present, in order
    std::map<std::string, Rgba8> saved;       // SaveSurface, by the stream's path

    PyDevice(unsigned threads, const std::string& precision, const std::string& transcendentals,
             const std::string& filter, unsigned max_slots, const std::string& engine) {
        runtime::DeviceOptions o;
        o.output_dir = std::string(kMemoryDir);
        o.threads = std::max(1u, threads);
        o.precision = precision_options(precision, transcendentals, false);
        if (filter == "exact") o.filter_precision = runtime::FilterPrecision::Exact;
        else if (filter != "fixed8") throw py::value_error("filter must be fixed8 or exact, not '" + filter + "'");
        o.max_instruction_slots = max_slots;
        o.engine = use_jit(engine) ? runtime::DeviceOptions::Engine::Jit : runtime::DeviceOptions::Engine::Interpreter;
        o.write_image = [this](const runtime::Surface& surface, const std::string& path) { capture(surface, path); };
        device = std::make_unique<runtime::Device>(o);
    }

    void capture(const runtime::Surface& surface, const std::string& path) {
        std::string name = path;
        const std::string prefix = std::string(kMemoryDir) + "/";
        if (name.rfind(prefix, 0) == 0) name = name.substr(prefix.size());
        char frame[32];
        std::snprintf(frame, sizeof frame, "frame_%04u.png", device->frames_presented());
        if (name == frame) frames.push_back(to_rgba8(surface));
        else saved[name] = to_rgba8(surface);
    }
};

struct PyReplayResult {
    std::shared_ptr<PyDevice> device;
    runtime::ReplayResult result;
    size_t first_frame = 0, frame_count = 0;
};

py::dict statistics_dict(const runtime::DrawStatistics& s) {
    py::dict d;
    d["draws"] = s.draws;
    d["vertices_shaded"] = s.vertices_shaded;
    d["primitives"] = s.primitives;
    d["pixels_shaded"] = s.pixels_shaded;
    d["pixels_rasterized"] = s.pixels_rasterized;
    d["pixels_killed"] = s.pixels_killed;
    d["pixels_written"] = s.pixels_written;
    d["pixels_outside_texture"] = s.pixels_outside_texture;
    d["pipelines_built"] = s.pipelines_built;
    d["pipeline_seconds"] = s.pipeline_seconds;
    d["vertex_seconds"] = s.vertex_seconds;
    d["setup_seconds"] = s.setup_seconds;
    d["pixel_seconds"] = s.pixel_seconds;
    return d;
}

PyReplayResult replay_stream(const std::shared_ptr<PyDevice>& self, const runtime::cs::Stream& stream,
                             const std::string& file_name, const std::string& base_dir) {
    runtime::ReplayOptions options;
    options.file_name = file_name;
    options.base_dir = base_dir;
    options.assembler = runtime::stream_assembler();
    PyReplayResult out;
    out.device = self;
    out.first_frame = self->frames.size();
    {
        py::gil_scoped_release release;
        out.result = runtime::replay(*self->device, stream, options);
    }
    out.frame_count = self->frames.size() - out.first_frame;
    return out;
}

runtime::cs::Stream parse_stream(const std::string& text, const std::string& file_name, const std::string& base_dir) {
    runtime::cs::TextOptions options;
    options.file_name = file_name;
    options.base_dir = base_dir;
    auto parsed = runtime::cs::parse_text(text, options);
    if (!parsed.ok()) throw Error(parsed.error->to_string());
    return std::move(*parsed.stream);
}

PyReplayResult replay_file(const std::shared_ptr<PyDevice>& self, const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    if (!file) throw Error(path + ": cannot open");
    const std::string bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    std::string base_dir = std::filesystem::path(path).parent_path().string();
    if (base_dir.empty()) base_dir = ".";
    const std::span<const std::byte> span(reinterpret_cast<const std::byte*>(bytes.data()), bytes.size());
    if (runtime::cs::looks_packed(span)) {
        auto parsed = runtime::cs::unpack(span);
        if (!parsed.ok()) {
            parsed.error->file = path;
            throw Error(parsed.error->to_string());
        }
        return replay_stream(self, *parsed.stream, path, base_dir);
    }
    return replay_stream(self, parse_stream(bytes, path, base_dir), path, base_dir);
}

const runtime::StateInfo& render_state_info(const py::object& state) {
    const runtime::StateInfo* info = py::isinstance<py::int_>(state) ? runtime::find_render_state(state.cast<uint32_t>())
                                                                       : runtime::find_render_state(state.cast<std::string>());
    if (!info) throw Error("unknown render state '" + py::str(state).cast<std::string>() + "'");
    return *info;
}

const runtime::StateInfo& sampler_state_info(const py::object& state) {
    const runtime::StateInfo* info = py::isinstance<py::int_>(state) ? runtime::find_sampler_state(state.cast<uint32_t>())
                                                                       : runtime::find_sampler_state(state.cast<std::string>());
    if (!info) throw Error("unknown sampler state '" + py::str(state).cast<std::string>() + "'");
    return *info;
}

py::array_t<float> constants_array(const runtime::Device& d, bool pixel, unsigned start, std::optional<unsigned> count) {
    const unsigned total = pixel ? runtime::kMaxPixelShaderConstantsF : runtime::kMaxVertexShaderConstantsF;
    if (start > total) throw Error("constant c" + std::to_string(start) + " is out of range (c0..c" + std::to_string(total - 1) + ")");
    const unsigned n = count.value_or(total - start);
    if (start + n > total) throw Error("constants c" + std::to_string(start) + "..c" + std::to_string(start + n - 1) + " are out of range (c0..c" + std::to_string(total - 1) + ")");
    py::array_t<float> a({static_cast<py::ssize_t>(n), py::ssize_t{4}});
    auto out = a.mutable_unchecked<2>();
    for (unsigned i = 0; i < n; ++i) {
        const auto& v = pixel ? d.pixel_shader_constant_f(start + i) : d.vertex_shader_constant_f(start + i);
        for (unsigned c = 0; c < 4; ++c) out(i, c) = v[c];
    }
    return a;
}

py::dict flow_dict(const emu::StaticFlowConstants& flow) {
    py::dict d;
    py::list booleans;
    for (bool b : flow.booleans) booleans.append(b);
    py::array_t<int32_t> integers({py::ssize_t{emu::kIntConstants}, py::ssize_t{4}});
    auto out = integers.mutable_unchecked<2>();
    for (unsigned i = 0; i < emu::kIntConstants; ++i)
        for (unsigned c = 0; c < 4; ++c) out(i, c) = flow.integers[i][c];
    d["booleans"] = booleans;
    d["integers"] = integers;
    return d;
}

py::array_t<float> surface_floats(const runtime::Surface& s) {
    py::array_t<float> a({static_cast<py::ssize_t>(s.height()), static_cast<py::ssize_t>(s.width()), py::ssize_t{4}});
    auto out = a.mutable_unchecked<3>();
    for (uint32_t y = 0; y < s.height(); ++y)
        for (uint32_t x = 0; x < s.width(); ++x) {
            const auto v = s.read(x, y, 0);
            for (unsigned c = 0; c < 4; ++c) out(y, x, c) = v[c];
        }
    return a;
}

}  // namespace

}  // namespace sm2::python

PYBIND11_MODULE(sm2emu, m) {
    using namespace sm2;
    using namespace sm2::python;
    m.doc() = "sm2emu: a Direct3D 9 Shader Model 2.0 GPU in software (docs/python.md)";
    m.attr("__version__") = SM2_VERSION;
    py::register_exception<Error>(m, "Error", PyExc_ValueError);

    m.def("assemble", &assemble, py::arg("text"), py::arg("validate") = true, py::arg("max_slots") = 0u,
          py::arg("file_name") = "<input>",
          "Assemble vs_2_0/ps_2_0 text to bytecode (bytes, little-endian DWORDs), byte for byte as Wine's "
          "D3DAssemble. Raises sm2emu.Error with file:line:column diagnostics.");
    m.def("disassemble", &disassemble, py::arg("bytecode"),
          "Bytecode (bytes or uint32 tokens) to text that assembles back to the same bytes.");
    m.def("validate", &validate, py::arg("source"), py::arg("max_slots") = 0u, py::arg("file_name") = "<input>",
          "Every violated vs_2_0/ps_2_0 rule of shader text or bytecode, as dicts (rule, message, instruction, "
          "line); an empty list when the shader is valid. Syntax errors raise sm2emu.Error.");
    m.def("run", &run, py::arg("shader"), py::arg("inputs") = py::dict(), py::arg("constants") = py::dict(),
          py::arg("integers") = py::dict(), py::arg("booleans") = py::dict(), py::arg("lanes") = py::none(),
          py::arg("precision") = "fp32", py::arg("transcendentals") = "exact", py::arg("engine") = "jit",
          "Run one shader over lanes. inputs: {'v0': (lanes, k) or (k,) array}; constants: {'c4' or 4: up to 4 "
          "floats}; integers: {'i0': 4 ints}; booleans: {'b0': bool}. Returns {'oPos': (lanes, 4) array, ...} for "
          "every output register the shader writes (float32; float64 with precision='fp64'), plus 'killed' "
          "(bool per lane) for pixel shaders, whose lanes run as 2x2 quads.");
    m.def("jit_available", &emu::jit::available, "True when this build's JIT module is found (engine='jit').");

    py::class_<PyReplayResult>(m, "ReplayResult", "What one replay did (Device.replay, sm2emu.replay).")
        .def_property_readonly("device", [](const PyReplayResult& r) { return r.device; })
        .def_property_readonly("frames",
                               [](const PyReplayResult& r) {
                                   py::list frames;
                                   for (size_t i = 0; i < r.frame_count; ++i)
                                       frames.append(to_array(r.device->frames[r.first_frame + i]));
                                   return frames;
                               },
                               "This replay's frames, one (height, width, 4) uint8 RGBA array per Present: the "
                               "bytes `sm2 replay` writes to frame_NNNN.png.")
        .def_property_readonly("frame_stats",
                               [](const PyReplayResult& r) {
                                   py::list out;
                                   for (const auto& f : r.result.frames) {
                                       py::dict d = statistics_dict(f.statistics);
                                       d["seconds"] = f.seconds;
                                       d["calls"] = f.calls;
                                       out.append(std::move(d));
                                   }
                                   return out;
                               })
        .def_property_readonly("diagnostics",
                               [](const PyReplayResult& r) {
                                   std::vector<std::string> out;
                                   for (const auto& d : r.result.diagnostics) out.push_back(d.to_string());
                                   return out;
                               },
                               "Refused calls, as 'file:line: D3DERR_INVALIDCALL: Call: message'.")
        .def_property_readonly("ok", [](const PyReplayResult& r) { return r.result.ok(); })
        .def_property_readonly("calls", [](const PyReplayResult& r) { return r.result.calls; })
        .def_property_readonly("refused", [](const PyReplayResult& r) { return r.result.refused; })
        .def_property_readonly("seconds", [](const PyReplayResult& r) { return r.result.seconds; })
        .def_property_readonly("statistics", [](const PyReplayResult& r) { return statistics_dict(r.result.statistics); });

    py::class_<PyDevice, std::shared_ptr<PyDevice>>(m, "Device",
                                                    "The emulated device: replays streams and shows its state.")
        .def(py::init<unsigned, const std::string&, const std::string&, const std::string&, unsigned, const std::string&>(),
             py::arg("threads") = 1u, py::arg("precision") = "fp32", py::arg("transcendentals") = "exact",
             py::arg("filter") = "fixed8", py::arg("max_slots") = 0u, py::arg("engine") = "jit")
        .def("replay", &replay_file, py::arg("path"),
             "Replay a command stream file (.sm2cs text or .sm2cb binary); side files are relative to its folder.")
        .def("replay_text",
             [](const std::shared_ptr<PyDevice>& self, const std::string& text, const std::string& base_dir,
                const std::string& file_name) { return replay_stream(self, parse_stream(text, file_name, base_dir), file_name, base_dir); },
             py::arg("text"), py::arg("base_dir") = ".", py::arg("file_name") = "<text>")
        .def_property_readonly("frames",
                               [](const PyDevice& d) {
                                   py::list frames;
                                   for (const auto& f : d.frames) frames.append(to_array(f));
                                   return frames;
                               },
                               "Every frame presented on this device, (height, width, 4) uint8 RGBA arrays.")
        .def_property_readonly("saved",
                               [](const PyDevice& d) {
                                   py::dict out;
                                   for (const auto& [name, image] : d.saved) out[py::str(name)] = to_array(image);
                                   return out;
                               },
                               "SaveSurface images by the stream's path, as uint8 RGBA arrays.")
        .def_property_readonly("frames_presented", [](const PyDevice& d) { return d.device->frames_presented(); })
        .def_property_readonly("statistics", [](const PyDevice& d) { return statistics_dict(d.device->statistics()); })
        .def_property_readonly("max_instruction_slots", [](const PyDevice& d) { return d.device->max_instruction_slots(); })
        .def("has_resource", [](const PyDevice& d, const std::string& name) { return d.device->has_resource(name); })
        .def("render_state",
             [](const PyDevice& d, const py::object& state) -> py::object {
                 const auto& info = render_state_info(state);
                 const auto v = runtime::get_render_state(d.device->render_state(), info.id);
                 return v ? py::object(py::int_(*v)) : py::object(py::none());
             },
             py::arg("state"),
             "A render state's DWORD by name ('CULLMODE' or 'D3DRS_CULLMODE') or number (float states as their "
             "bits); None for a state sm2emu does not model.")
        .def("render_states",
             [](const PyDevice& d) {
                 py::dict out;
                 for (const auto& info : runtime::render_states())
                     if (const auto v = runtime::get_render_state(d.device->render_state(), info.id))
                         out[py::str(std::string(info.name))] = *v;
                 return out;
             },
             "Every modelled render state, name -> DWORD.")
        .def("sampler_state",
             [](const PyDevice& d, uint32_t sampler, const py::object& state) -> py::object {
                 if (sampler >= runtime::kMaxSamplers) throw Error("sampler " + std::to_string(sampler) + " is out of range (0..15)");
                 const auto v = d.device->sampler_state(sampler).get(sampler_state_info(state).id);
                 return v ? py::object(py::int_(*v)) : py::object(py::none());
             },
             py::arg("sampler"), py::arg("state"))
        .def_property_readonly("viewport",
                               [](const PyDevice& d) {
                                   const auto& v = d.device->viewport();
                                   py::dict out;
                                   out["x"] = v.x;
                                   out["y"] = v.y;
                                   out["width"] = v.width;
                                   out["height"] = v.height;
                                   out["min_z"] = v.min_z;
                                   out["max_z"] = v.max_z;
                                   return out;
                               })
        .def_property_readonly("scissor_rect",
                               [](const PyDevice& d) {
                                   const auto& r = d.device->scissor_rect();
                                   return py::make_tuple(r.left, r.top, r.right, r.bottom);
                               },
                               "(left, top, right, bottom)")
        .def("clip_plane",
             [](const PyDevice& d, uint32_t index) {
                 if (index >= 6) throw Error("clip plane " + std::to_string(index) + " is out of range (0..5)");
                 const auto& p = d.device->clip_plane(index);
                 return py::array_t<float>(4, p.data());
             })
        .def("vs_constants",
             [](const PyDevice& d, unsigned start, std::optional<unsigned> count) { return constants_array(*d.device, false, start, count); },
             py::arg("start") = 0u, py::arg("count") = py::none(), "Vertex shader float constants as a (count, 4) array.")
        .def("ps_constants",
             [](const PyDevice& d, unsigned start, std::optional<unsigned> count) { return constants_array(*d.device, true, start, count); },
             py::arg("start") = 0u, py::arg("count") = py::none(), "Pixel shader float constants as a (count, 4) array.")
        .def_property_readonly("vs_flow_constants", [](const PyDevice& d) { return flow_dict(d.device->vertex_shader_flow_constants()); })
        .def_property_readonly("ps_flow_constants", [](const PyDevice& d) { return flow_dict(d.device->pixel_shader_flow_constants()); })
        .def("surface",
             [](const PyDevice& d, const std::string& name) {
                 const runtime::Surface* s = d.device->surface(name);
                 if (!s) throw Error("'" + name + "' is not a surface or texture");
                 return surface_floats(*s);
             },
             py::arg("name"),
             "A render target's (or texture's level 0) values as the sampler reads them, (height, width, 4) float32.");

    m.def("replay",
          [](const std::string& path, unsigned threads, const std::string& precision, const std::string& transcendentals,
             const std::string& filter, unsigned max_slots, const std::string& engine) {
              auto device = std::make_shared<PyDevice>(threads, precision, transcendentals, filter, max_slots, engine);
              return replay_file(device, path);
          },
          py::arg("path"), py::arg("threads") = 1u, py::arg("precision") = "fp32", py::arg("transcendentals") = "exact",
          py::arg("filter") = "fixed8", py::arg("max_slots") = 0u, py::arg("engine") = "jit",
          "Replay a stream file on a new Device; the result holds the frames and the device.");
}
