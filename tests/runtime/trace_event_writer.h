// Hand-made apitrace event streams (the trace format before Snappy compression) for the reader's
// and the importer's tests: what a capture cannot produce (malformed events, calls Wine refuses).
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string_view>
#include <vector>

namespace sm2::runtime::apitrace::test {

struct TraceWriter {
    std::vector<std::byte> out;
    TraceWriter& byte(uint8_t b) {
        out.push_back(std::byte{b});
        return *this;
    }
    TraceWriter& uint(uint64_t v) {
        do {
            uint8_t b = v & 0x7F;
            v >>= 7;
            if (v) b |= 0x80;
            byte(b);
        } while (v);
        return *this;
    }
    TraceWriter& str(std::string_view text) {
        uint(text.size());
        for (char c : text) byte(static_cast<uint8_t>(c));
        return *this;
    }
    // version 6 header with no properties
    static TraceWriter v6() {
        TraceWriter w;
        w.uint(6).uint(6).str("");
        return w;
    }
    // enter of a new function signature `id` named `name` with args, thread 0
    TraceWriter& enter(uint64_t id, std::string_view name, std::initializer_list<std::string_view> args) {
        byte(0).uint(0).uint(id).str(name).uint(args.size());
        for (auto a : args) str(a);
        return *this;
    }
    TraceWriter& enter_again(uint64_t id) { return byte(0).uint(0).uint(id); }
    TraceWriter& leave(uint64_t call) { return byte(1).uint(call); }
    // argument `index`, then its value
    TraceWriter& arg(uint64_t index) { return byte(1).uint(index); }
    TraceWriter& u(uint64_t v) { return byte(4).uint(v); }
    TraceWriter& ptr(uint64_t p) { return byte(13).uint(p); }
    TraceWriter& one() { return byte(11).uint(1); }  // a pointer to one value: an array of one
    TraceWriter& floats(std::initializer_list<float> values) {
        byte(8).uint(values.size() * 4);
        for (float f : values) {
            const auto bits = std::bit_cast<uint32_t>(f);
            for (int i = 0; i < 4; ++i) byte(static_cast<uint8_t>(bits >> (8 * i)));
        }
        return *this;
    }
};

}  // namespace sm2::runtime::apitrace::test
