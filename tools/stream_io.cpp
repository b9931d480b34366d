#include "stream_io.h"

#include <filesystem>
#include <iostream>

#include "io.h"

namespace sm2::tools {

void add_read_root_option(CLI::App& command, std::string& read_root) {
    command.add_option("--read-root", read_root,
                       "Folder that side files (@\"...\") and LoadTexture paths must stay inside (default: the "
                       "stream's folder); they are still relative to the stream's folder");
}

std::optional<LoadedStream> load_stream(const std::string& path, const char* command, const std::string& read_root) {
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
    loaded.root_dir = read_root.empty() ? loaded.base_dir : read_root;
    cs::ParseResult result;
    if (cs::looks_packed(*bytes)) {
        result = cs::unpack(*bytes);
        if (result.error) result.error->file = loaded.file_name;
    } else {
        cs::TextOptions options;
        options.file_name = loaded.file_name;
        options.base_dir = loaded.base_dir;
        options.root_dir = loaded.root_dir;
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
