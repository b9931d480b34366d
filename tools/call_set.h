// apitrace's call sets (`sm2 replay --snapshot`): which calls of a replay to act on.
//
//   10            one call
//   10,20-30      a list (commas or blanks between items)
//   20-           call 20 and every later one
//   0-100/5       every fifth call from 0 (0, 5, ..., 100)
//   */draw        every draw call (DrawPrimitive, DrawIndexedPrimitive and their UP forms)
//   1-1000/draw   the draw calls among 1..1000
//   frame         every Present (the call that ends a frame); `draw` alone is `*/draw`
//   @FILE         the items written in FILE, with the same syntax
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace sm2::tools {

class CallSet {
public:
    // nullopt with `error` set ("call set '1-x': column 3: expected a call number after '-'")
    // when `text` is not a call set.
    [[nodiscard]] static std::optional<CallSet> parse(std::string_view text, std::string& error);

    // Whether call `call` (named `name`: "Present", "DrawPrimitive", ...) is in the set.
    [[nodiscard]] bool contains(uint64_t call, std::string_view name) const;

private:
    struct Range {
        uint64_t first = 0, last = UINT64_MAX;
        uint64_t step = 1;
        bool draws_only = false, frames_only = false;
    };
    std::vector<Range> ranges_;
};

[[nodiscard]] bool is_draw_call(std::string_view name);

}  // namespace sm2::tools
