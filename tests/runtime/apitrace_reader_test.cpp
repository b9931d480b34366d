// apitrace trace reader: the three real captures of tests/data/traces read call for call as
// `apitrace dump -v` (Debian's apitrace 11.1) printed them, values read back to what the programs
// passed, and every kind of malformed input refused with its byte offset.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <iterator>
#include <regex>

#include <snappy.h>

#include "sm2/runtime/apitrace.h"
#include "trace_event_writer.h"

namespace sm2::runtime::apitrace {
namespace {

std::vector<std::byte> read_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::vector<char> chars((std::istreambuf_iterator<char>(in)), {});
    std::vector<std::byte> out(chars.size());
    if (!chars.empty()) std::memcpy(out.data(), chars.data(), chars.size());
    return out;
}

std::string trace_path(const std::string& name) { return std::string(SM2_SOURCE_DIR) + "/tests/data/traces/" + name; }

std::vector<Call> read_all(std::span<const std::byte> data, std::optional<Error>& error, bool uncompressed = false) {
    std::vector<Call> calls;
    auto reader = Reader::open(data, error, uncompressed);
    if (!reader) return calls;
    while (auto call = reader->next()) calls.push_back(std::move(*call));
    error = reader->error();
    return calls;
}

// The records of an `apitrace dump -v` text: each starts with "N Name(" on a new line; strings
// may span lines (shader disassembly), which our one-line form writes as \n.
std::vector<std::string> reference_records(const std::string& name) {
    std::ifstream in(trace_path(name + ".dump.txt"));
    std::string line;
    std::vector<std::string> records;
    const std::regex start(R"(^\d+ [A-Za-z_][A-Za-z0-9_:]*\()");
    while (std::getline(in, line)) {
        if (std::regex_search(line, start)) {
            records.push_back(line);
        } else if (!records.empty() && !line.empty() && line.rfind("//", 0) != 0) {
            records.back() += "\\n" + line;
        } else if (!records.empty() && line.empty() && records.back().find('"') != std::string::npos &&
                   std::count(records.back().begin(), records.back().end(), '"') % 2 == 1) {
            records.back() += "\\n";  // an empty line inside a string
        }
    }
    return records;
}

struct TraceCase {
    const char* name;
    size_t calls;
};

class RealTraces : public ::testing::TestWithParam<TraceCase> {};

// Every call of every trace, printed by to_text, is the reference dump's line: numbering, names,
// argument names and every value (enums, bitmasks, structs, arrays, floats, blobs as blob(N)).
TEST_P(RealTraces, EveryCallMatchesTheReferenceDump) {
    const auto data = read_bytes(trace_path(std::string(GetParam().name) + ".trace"));
    std::optional<Error> error;
    const auto calls = read_all(data, error);
    ASSERT_FALSE(error) << error->to_string();
    const auto reference = reference_records(GetParam().name);
    ASSERT_EQ(reference.size(), GetParam().calls);
    ASSERT_EQ(calls.size(), GetParam().calls);
    for (size_t i = 0; i < calls.size(); ++i) {
        EXPECT_EQ(calls[i].number, i);
        EXPECT_FALSE(calls[i].incomplete);
        EXPECT_EQ(to_text(calls[i]), reference[i]) << "call " << i;
    }
}

INSTANTIATE_TEST_SUITE_P(Traces, RealTraces,
                         ::testing::Values(TraceCase{"ff_lit_cube", 175}, TraceCase{"shader_scene", 174},
                                           TraceCase{"mixed_states", 268}),
                         [](const auto& test) { return std::string(test.param.name); });

TEST(ApitraceReader, HeaderAndValuesOfShaderScene) {
    const auto data = read_bytes(trace_path("shader_scene.trace"));
    std::optional<Error> error;
    auto reader = Reader::open(data, error);
    ASSERT_TRUE(reader) << error->to_string();
    EXPECT_EQ(reader->header().version, 6u);
    EXPECT_EQ(reader->header().properties.at("process.name"),
              "Z:\\tmp\\d3d9-traces-build\\run_shader_scene\\shader_scene.exe");
    std::vector<Call> calls;
    while (auto c = reader->next()) calls.push_back(std::move(*c));
    ASSERT_FALSE(reader->error());
    ASSERT_EQ(calls.size(), 174u);

    // 1 IDirect3D9::CreateDevice(..., pPresentationParameters = &{BackBufferWidth = 256, ...
    //   AutoDepthStencilFormat = D3DFMT_D24S8, ...}, ppReturnedDeviceInterface = &0x34f900)
    const Call& create = calls[1];
    EXPECT_EQ(create.name(), "IDirect3D9::CreateDevice");
    const Value* pp = create.arg("pPresentationParameters");
    ASSERT_TRUE(pp && pp->kind == Value::Kind::Array && pp->items.size() == 1);
    const Value& params = pp->items[0];
    EXPECT_EQ(params.struct_sig->name, "D3DPRESENT_PARAMETERS");
    EXPECT_EQ(params.member("BackBufferWidth")->as_int(), 256);
    EXPECT_EQ(params.member("BackBufferHeight")->as_int(), 256);
    EXPECT_EQ(to_text(*params.member("BackBufferFormat")), "D3DFMT_X8R8G8B8");
    EXPECT_EQ(params.member("BackBufferFormat")->as_int(), 22);  // D3DFMT_X8R8G8B8
    EXPECT_EQ(params.member("AutoDepthStencilFormat")->as_int(), 75);  // D3DFMT_D24S8
    EXPECT_EQ(create.arg("ppReturnedDeviceInterface")->items.at(0).uint, 0x34f900u);
    EXPECT_EQ(create.ret->kind, Value::Kind::Enum);
    EXPECT_EQ(to_text(*create.ret), "D3D_OK");

    // 2 CreateVertexShader: pFunction is a repr, the disassembly and the token blob.
    const Value* function = calls[2].arg("pFunction");
    ASSERT_TRUE(function && function->kind == Value::Kind::Repr);
    EXPECT_EQ(function->items[0].text.rfind("vs_2_0\ndcl_position0 v0\n", 0), 0u);
    const auto* tokens = function->blob();
    ASSERT_TRUE(tokens);
    ASSERT_GE(tokens->size(), 8u);
    ASSERT_EQ(tokens->size() % 4, 0u);
    uint32_t first = 0, last = 0;
    std::memcpy(&first, tokens->data(), 4);
    std::memcpy(&last, tokens->data() + tokens->size() - 4, 4);
    EXPECT_EQ(first, 0xFFFE0200u);  // vs_2_0
    EXPECT_EQ(last, 0x0000FFFFu);   // end token
    uint32_t ps_version = 0;
    ASSERT_TRUE(calls[3].arg("pFunction")->blob());
    std::memcpy(&ps_version, calls[3].arg("pFunction")->blob()->data(), 4);
    EXPECT_EQ(ps_version, 0xFFFF0200u);  // ps_2_0

    // 13 memcpy(dest = 0x3b6e10, src = blob(432), n = 432) // fake
    EXPECT_EQ(calls[13].name(), "memcpy");
    EXPECT_TRUE(calls[13].fake);
    EXPECT_FALSE(calls[14].fake);
    EXPECT_EQ(calls[13].arg("dest")->uint, 0x3b6e10u);
    EXPECT_EQ(calls[13].arg("src")->bytes.size(), 432u);
    EXPECT_EQ(calls[13].arg("n")->as_int(), 432);

    // 27 Clear(..., Flags = D3DCLEAR_TARGET, Color = 4279246912, Z = 1, Stencil = 0)
    EXPECT_EQ(calls[27].arg("Flags")->kind, Value::Kind::Bitmask);
    EXPECT_EQ(calls[27].arg("Flags")->uint, 1u);
    EXPECT_EQ(calls[27].arg("Color")->uint, 4279246912u);
    EXPECT_EQ(calls[27].arg("Z")->kind, Value::Kind::Float);
    EXPECT_EQ(calls[27].arg("Z")->real, 1.0);
    // 28 SetVertexShaderConstantF(StartRegister = 0, pConstantData = {0.7642692, -0.2364162, ...})
    const Value* constants = calls[28].arg("pConstantData");
    ASSERT_EQ(constants->items.size(), 16u);
    EXPECT_FLOAT_EQ(static_cast<float>(constants->items[0].real), 0.7642692f);
    EXPECT_FLOAT_EQ(static_cast<float>(constants->items[1].real), -0.2364162f);
}

// --- Hand-made event streams (the format before Snappy) ---

using Writer = test::TraceWriter;

std::vector<std::byte> container(const std::vector<std::byte>& stream, size_t chunk = 1 << 20) {
    std::vector<std::byte> out{std::byte{'a'}, std::byte{'t'}};
    for (size_t at = 0; at < stream.size(); at += chunk) {
        std::string compressed;
        snappy::Compress(reinterpret_cast<const char*>(stream.data()) + at, std::min(chunk, stream.size() - at), &compressed);
        const auto n = static_cast<uint32_t>(compressed.size());
        for (int i = 0; i < 4; ++i) out.push_back(std::byte(static_cast<uint8_t>(n >> (8 * i))));
        for (char c : compressed) out.push_back(std::byte(static_cast<uint8_t>(c)));
    }
    return out;
}

TEST(ApitraceReader, EveryValueType) {
    Writer w = Writer::v6();
    w.enter(0, "f", {"a", "b", "c", "d", "e", "f", "g", "h", "i", "j", "k", "l", "m", "n", "o"});
    w.byte(1).uint(0).byte(0);                    // null
    w.byte(1).uint(1).byte(1);                    // false
    w.byte(1).uint(2).byte(2);                    // true
    w.byte(1).uint(3).byte(3).uint(5);            // -5
    w.byte(1).uint(4).byte(4).uint(300);          // 300
    w.byte(1).uint(5).byte(5).byte(0).byte(0).byte(0xC0).byte(0x3F);  // 1.5f
    w.byte(1).uint(6).byte(6);                    // 0.25
    for (uint8_t b : {0, 0, 0, 0, 0, 0, 0xD0, 0x3F}) w.byte(b);
    w.byte(1).uint(7).byte(7).str("hi \"x\"");    // string
    w.byte(1).uint(8).byte(8).uint(3).byte(1).byte(2).byte(3);  // blob(3)
    // enum signature 7: {A = -1, B = 2}, value 2
    w.byte(1).uint(9).byte(9).uint(7).uint(2).str("A").byte(3).uint(1).str("B").byte(4).uint(2).byte(4).uint(2);
    // bitmask signature 3: {NONE = 0, X = 1, Y = 4}, value 5 | 8
    w.byte(1).uint(10).byte(10).uint(3).uint(3).str("NONE").uint(0).str("X").uint(1).str("Y").uint(4).uint(13);
    w.byte(1).uint(11).byte(11).uint(2).byte(4).uint(1).byte(4).uint(2);  // {1, 2}
    // struct signature 1 "S" {p, q}: {p = 9, q = &0x10}
    w.byte(1).uint(12).byte(12).uint(1).str("S").uint(2).str("p").str("q").byte(4).uint(9).byte(11).uint(1).byte(13).uint(16);
    w.byte(1).uint(13).byte(14).byte(7).str("text").byte(8).uint(1).byte(0xAB);  // repr
    w.byte(1).uint(14).byte(15).uint(2).uint(0x48).uint(0x20AC);                // L"H€"
    w.byte(2).byte(9).uint(7).byte(3).uint(1);    // return: enum A, signature by id only
    w.byte(0);
    w.leave(0).byte(5).uint(1).byte(0);           // flags: fake
    std::optional<Error> error;
    const auto calls = read_all(w.out, error, true);
    ASSERT_FALSE(error) << error->to_string();
    ASSERT_EQ(calls.size(), 1u);
    EXPECT_EQ(to_text(calls[0]),
              "0 f(a = NULL, b = false, c = true, d = -5, e = 300, f = 1.5, g = 0.25, h = \"hi \\\"x\\\"\", "
              "i = blob(3), j = B, k = X | Y | 0x8, l = {1, 2}, m = {p = 9, q = &0x10}, n = \"text\", o = L\"H\xE2\x82\xAC\") = A // fake");
    EXPECT_EQ(calls[0].arg("j")->as_int(), 2);
    EXPECT_EQ(calls[0].arg("d")->as_int(), -5);
    EXPECT_EQ(calls[0].arg("n")->blob()->size(), 1u);

    // The same stream in the Snappy container, cut into 7-byte chunks: identical calls.
    std::optional<Error> error2;
    const auto again = read_all(container(w.out, 7), error2);
    ASSERT_FALSE(error2) << error2->to_string();
    ASSERT_EQ(again.size(), 1u);
    EXPECT_EQ(to_text(again[0]), to_text(calls[0]));
}

TEST(ApitraceReader, SignaturesAreDefinedOnceAndCallsComeOutWhenTheyLeave) {
    Writer w = Writer::v6();
    w.enter(3, "Outer", {"x"}).byte(1).uint(0).byte(4).uint(1).byte(0);
    w.enter(5, "Inner", {}).byte(0);
    w.leave(1).byte(0);
    w.leave(0).byte(2).byte(4).uint(7).byte(0);
    w.enter_again(5).byte(0);  // call 2, "Inner" by id
    w.leave(2).byte(0);
    w.enter_again(3).byte(1).uint(0).byte(4).uint(4).byte(0);  // call 3 never leaves
    std::optional<Error> error;
    const auto calls = read_all(w.out, error, true);
    ASSERT_FALSE(error) << error->to_string();
    ASSERT_EQ(calls.size(), 4u);
    EXPECT_EQ(to_text(calls[0]), "1 Inner()");
    EXPECT_EQ(to_text(calls[1]), "0 Outer(x = 1) = 7");
    EXPECT_EQ(to_text(calls[2]), "2 Inner()");
    EXPECT_EQ(to_text(calls[3]), "3 Outer(x = 4) // incomplete");
    EXPECT_TRUE(calls[3].incomplete);
}

std::string first_error(const std::vector<std::byte>& data, bool uncompressed = true) {
    std::optional<Error> error;
    (void)read_all(data, error, uncompressed);
    return error ? error->to_string() : "";
}

TEST(ApitraceReader, MalformedStreamsNameTheByte) {
    // Header.
    EXPECT_EQ(first_error({}), "byte 0: unexpected end of the trace");
    EXPECT_EQ(first_error(Writer().uint(7).out), "byte 1: trace format version 7 (this reader knows up to 6)");
    EXPECT_EQ(first_error(Writer().uint(6).uint(7).out), "byte 2: semantic version 7 above the format version");
    // An integer of 11 bytes.
    Writer big = Writer::v6();
    big.byte(0);
    for (int i = 0; i < 10; ++i) big.byte(0xFF);
    EXPECT_EQ(first_error(big.out), "byte 14: integer longer than 64 bits");
    // Unknown event, detail and value type.
    EXPECT_EQ(first_error(Writer::v6().byte(9).out), "byte 4: unknown event 9 at byte 3");
    EXPECT_EQ(first_error(Writer::v6().enter(0, "f", {}).byte(6).out), "byte 10: unknown call detail 6");
    EXPECT_EQ(first_error(Writer::v6().enter(0, "f", {"a"}).byte(1).uint(0).byte(16).out),
              "byte 14: unknown value type 16 at byte 13");
    // A leave for a call that never entered.
    EXPECT_EQ(first_error(Writer::v6().leave(4).out), "byte 5: leave event for call 4, which has not entered");
    // A blob of 2^40 bytes in a 20-byte stream: refused by the per-call limit before any allocation,
    // and one within it that the data does not back: the end of the data.
    EXPECT_EQ(first_error(Writer::v6().enter(0, "f", {"a"}).byte(1).uint(0).byte(8).uint(uint64_t{1} << 40).out),
              "byte 20: a call holds more than 268435456 bytes of strings and blobs");
    EXPECT_EQ(first_error(Writer::v6().enter(0, "f", {"a"}).byte(1).uint(0).byte(8).uint(1000000).byte(1).out),
              "byte 18: unexpected end of the trace (999999 bytes missing)");
    // An array of 4 billion elements whose data stops: ends at the end of the data.
    EXPECT_EQ(first_error(Writer::v6().enter(0, "f", {"a"}).byte(1).uint(0).byte(11).uint(0xFFFFFFFF).byte(0).byte(0).out),
              "byte 21: unexpected end of the trace");
    // Nesting deeper than 64.
    Writer deep = Writer::v6().enter(0, "f", {"a"});
    deep.byte(1).uint(0);
    for (int i = 0; i < 100; ++i) deep.byte(11).uint(1);
    EXPECT_EQ(first_error(deep.out), "byte 143: values nested deeper than 64");
    // An argument index far past the signature's.
    EXPECT_EQ(first_error(Writer::v6().enter(0, "f", {"a"}).byte(1).uint(1000000).out),
              "byte 15: argument index 1000000 of f is out of range");
}

TEST(ApitraceReader, MalformedContainersNameTheChunk) {
    std::optional<Error> error;
    EXPECT_FALSE(Reader::open(std::vector<std::byte>{std::byte{'x'}, std::byte{'y'}}, error));
    EXPECT_EQ(error->to_string(), "byte 0: not an apitrace file in the Snappy container (it starts with \"at\")");
    EXPECT_FALSE(Reader::open(std::vector<std::byte>{std::byte{0x1f}, std::byte{0x8b}, std::byte{8}}, error));
    EXPECT_NE(error->message.find("gzip"), std::string::npos);

    const auto stream = Writer::v6().enter(0, "f", {}).byte(0).leave(0).byte(0).out;
    auto good = container(stream);
    EXPECT_EQ(first_error(good, false), "");
    // The chunk length past the end of the file.
    auto longer = good;
    longer[2] = std::byte{0xFF};
    EXPECT_EQ(first_error(longer, false),
              "byte 0 (chunk at file offset 2): chunk at file offset 2 declares " + std::to_string(0xFF + (uint32_t(std::to_integer<uint8_t>(good[3])) << 8)) +
                  " compressed bytes, the file has " + std::to_string(good.size() - 6) + " left");
    // A truncated length.
    auto cut = std::vector<std::byte>(good.begin(), good.begin() + 4);
    EXPECT_EQ(first_error(cut, false), "byte 0 (chunk at file offset 2): truncated chunk length at file offset 2");
    // A Snappy header claiming 2^28 bytes from a few.
    std::vector<std::byte> liar{std::byte{'a'}, std::byte{'t'}, std::byte{5}, std::byte{0}, std::byte{0}, std::byte{0},
                                std::byte{0x80}, std::byte{0x80}, std::byte{0x80}, std::byte{0x80}, std::byte{0x01}};
    EXPECT_EQ(first_error(liar, false), "byte 0 (chunk at file offset 2): chunk at file offset 2 claims 268435456 bytes from 5 compressed");
    // Corrupt compressed data.
    auto corrupt = good;
    corrupt.back() = std::byte{0xFF};
    corrupt[corrupt.size() - 2] = std::byte{0xFF};
    EXPECT_NE(first_error(corrupt, false), "");
}

// Version 2's enum signatures hold a value, which may be an enum with a new signature: nested
// that way, the depth limit still holds.
TEST(ApitraceReader, OldEnumSignaturesNestWithinTheDepthLimit) {
    Writer w;
    w.uint(2);                                  // version 2: no properties, thread in a detail
    w.byte(0).uint(0).str("f").uint(1).str("a");  // enter, signature 0 "f"(a)
    w.byte(1).uint(0);
    for (int i = 0; i < 100; ++i) w.byte(9).uint(static_cast<uint64_t>(i)).str("E");  // enum, sig i, name "E", value:
    w.byte(4).uint(7);
    std::optional<Error> error;
    (void)read_all(w.out, error, true);
    ASSERT_TRUE(error);
    EXPECT_EQ(error->message, "values nested deeper than 64");
    // One level: the value is the signature's.
    Writer one;
    one.uint(2).byte(0).uint(0).str("f").uint(1).str("a").byte(1).uint(0).byte(9).uint(0).str("E").byte(4).uint(7).byte(0);
    one.byte(1).uint(0).byte(0);
    const auto calls = read_all(one.out, error, true);
    ASSERT_FALSE(error) << error->to_string();
    ASSERT_EQ(calls.size(), 1u);
    EXPECT_EQ(to_text(calls[0]), "0 f(a = E)");
    EXPECT_EQ(calls[0].arg("a")->as_int(), 7);
}

// A million empty chunks before the data: skipped in a loop (no recursion to overflow the stack).
TEST(ApitraceReader, EmptyChunksAreSkipped) {
    const auto stream = Writer::v6().enter(0, "f", {}).byte(0).leave(0).byte(0).out;
    auto file = container(stream);
    std::string empty;
    snappy::Compress("", 0, &empty);  // one byte: the length 0
    std::vector<std::byte> chunks{std::byte{'a'}, std::byte{'t'}};
    const std::byte empty_chunk[5] = {std::byte{1}, std::byte{0}, std::byte{0}, std::byte{0}, std::byte(static_cast<uint8_t>(empty[0]))};
    ASSERT_EQ(empty.size(), 1u);
    for (int i = 0; i < 1000000; ++i) chunks.insert(chunks.end(), std::begin(empty_chunk), std::end(empty_chunk));
    chunks.insert(chunks.end(), file.begin() + 2, file.end());
    std::optional<Error> error;
    const auto calls = read_all(chunks, error);
    ASSERT_FALSE(error) << error->to_string();
    ASSERT_EQ(calls.size(), 1u);
    EXPECT_EQ(to_text(calls[0]), "0 f()");
}

// Every prefix of a real trace's event stream, and of its container: calls, then either a clean
// end or an error at most at the prefix's end. Never a crash (the sanitizer build runs this too).
TEST(ApitraceReader, EveryPrefixOfARealTraceEndsCleanlyOrWithAnError) {
    const auto file = read_bytes(trace_path("shader_scene.trace"));
    ASSERT_GT(file.size(), 6u);
    size_t n = 0;
    for (int i = 0; i < 4; ++i) n |= size_t(std::to_integer<uint8_t>(file[2 + size_t(i)])) << (8 * i);
    std::string raw;
    ASSERT_TRUE(snappy::Uncompress(reinterpret_cast<const char*>(file.data()) + 6, n, &raw));
    std::vector<std::byte> stream(raw.size());
    std::memcpy(stream.data(), raw.data(), raw.size());
    size_t errors = 0;
    for (size_t len = 0; len < stream.size(); len += 7) {
        std::optional<Error> error;
        const auto calls = read_all(std::span(stream).first(len), error, true);
        if (error) {
            ++errors;
            EXPECT_LE(error->offset, len);
        }
        EXPECT_LE(calls.size(), 174u);
    }
    EXPECT_GT(errors, 0u);
    for (size_t len = 0; len < file.size(); len += 11) {
        std::optional<Error> error;
        (void)read_all(std::span(file).first(len), error);
    }
}

}  // namespace
}  // namespace sm2::runtime::apitrace
