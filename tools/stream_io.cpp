#include "stream_io.h"

#include <filesystem>
#include <iostream>

#include "io.h"

namespace sm2::tools {

std::optional<LoadedStream> load_stream(const std::string& path, const char* command) {
    namespace cs = runtime::cs;
    std::string error;
    auto bytes = read_input(path, error);
    if (!bytes) {
        std::cerr << "sm2 " << command << ": " << error << '\n';
        return std::nullopt;
    }
    LoadedStream loaded;
    loaded.file_name = display_name(path);
    std::string folder = path == "-" ? std::string() : std::filesystem::path(path).parent_path().string();
    loaded.base_dir = folder.empty() ? std::string(".") : std::move(folder);
    cs::ParseResult result;
    if (cs::looks_packed(*bytes)) {
        result = cs::unpack(*bytes);
        if (result.error) result.error->file = loaded.file_name;
    } else {
        cs::TextOptions options;
        options.file_name = loaded.file_name;
        options.base_dir = loaded.base_dir;
        result = cs::parse_text({reinterpret_cast<const char*>(bytes->data()), bytes->size()}, options);
    }
    if (!result.ok()) {
        std::cerr << result.error->to_string() << '\n';
        return std::nullopt;
    }
    loaded.stream = std::move(*result.stream);
    return loaded;
}

}  // namespace sm2::tools
