#include "lanes.h"

#include "sm2/emu/engine.h"
#include "sm2/isa/registers.h"

namespace sm2::tools {

std::vector<std::string_view> split(std::string_view s, char sep) {
    std::vector<std::string_view> parts;
    size_t start = 0;
    while (true) {
        const size_t at = s.find(sep, start);
        parts.push_back(s.substr(start, at == std::string_view::npos ? std::string_view::npos : at - start));
        if (at == std::string_view::npos) return parts;
        start = at + 1;
    }
}

template <typename Error>
unsigned input_slot(isa::ShaderVersion version, std::string_view name, const std::string& what) {
    isa::RegisterType type = isa::RegisterType::Input;
    std::string_view number = name;
    if (!name.empty() && name[0] == 'v') {
        number.remove_prefix(1);
    } else if (!name.empty() && name[0] == 't' && version.is_pixel()) {
        type = isa::RegisterType::Texture;
        number.remove_prefix(1);
    } else {
        throw Error{"unknown input register '" + std::string(name) + "' in " + what +
                    (version.is_pixel() ? " (pixel shaders read v0, v1, t0..t7)" : " (vertex shaders read v0..v15)")};
    }
    const auto index = parse_number<unsigned, Error>(number, what);
    const isa::RegisterFile* file = isa::find_register_file(version, type, index);
    const auto slot = emu::register_slot(version.type, type, index);
    if (!file || index >= file->count || !slot)
        throw Error{"input register '" + std::string(name) + "' does not exist in " + version.name()};
    return *slot;
}

template unsigned input_slot<UsageError>(isa::ShaderVersion, std::string_view, const std::string&);
template unsigned input_slot<InputError>(isa::ShaderVersion, std::string_view, const std::string&);

namespace {

std::string_view trim(std::string_view s) {
    while (!s.empty() && (s.back() == '\r' || s.back() == ' ')) s.remove_suffix(1);
    while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
    return s;
}

}  // namespace

std::vector<std::vector<LaneValue>> parse_lanes_csv(std::string_view text, const std::string& name,
                                                    isa::ShaderVersion version) {
    const std::vector<std::string_view> lines = split(text, '\n');
    if (lines.empty() || trim(lines[0]).empty()) throw InputError{name + ":1: empty file, expected a header"};
    std::vector<std::pair<unsigned, unsigned>> columns;  // slot, component
    for (std::string_view column : split(lines[0], ',')) {
        column = trim(column);
        const size_t dot = column.find('.');
        const std::string what = name + ":1: column '" + std::string(column) + "'";
        if (dot == std::string_view::npos || column.size() != dot + 2)
            throw InputError{what + ": expected REGISTER.COMPONENT, e.g. v0.x"};
        const std::string_view letters = "xyzw";
        const size_t component = letters.find(column[dot + 1]);
        if (component == std::string_view::npos) throw InputError{what + ": component must be x, y, z or w"};
        columns.emplace_back(input_slot<InputError>(version, column.substr(0, dot), what),
                             static_cast<unsigned>(component));
    }
    std::vector<std::vector<LaneValue>> lanes;
    for (size_t row = 1; row < lines.size(); ++row) {
        const std::string_view line = lines[row];
        if (line.empty() || line == "\r") continue;
        const auto cells = split(line, ',');
        const std::string where = name + ":" + std::to_string(row + 1);
        if (cells.size() != columns.size())
            throw InputError{where + ": " + std::to_string(cells.size()) + " values for " +
                             std::to_string(columns.size()) + " columns"};
        std::vector<LaneValue> lane;
        for (size_t k = 0; k < cells.size(); ++k)
            lane.push_back({columns[k].first, columns[k].second, parse_number<double, InputError>(trim(cells[k]), where)});
        lanes.push_back(std::move(lane));
    }
    if (lanes.empty()) throw InputError{name + ": no lanes after the header"};
    return lanes;
}

}  // namespace sm2::tools
