// Loading command streams for the tool's commands (cs pack/dump, replay, bench).
#pragma once

#include <optional>
#include <string>

#include "sm2/runtime/command_stream.h"

namespace sm2::tools {

struct LoadedStream {
    runtime::cs::Stream stream;
    std::string file_name;  // for diagnostics ("<stdin>" for "-")
    std::string base_dir;   // side files and LoadTexture paths are relative to it
};

// Reads a stream in either form (text or binary; "-" is stdin). On failure prints the error,
// prefixed with "sm2 COMMAND: " when the file cannot be read, and returns nullopt.
std::optional<LoadedStream> load_stream(const std::string& path, const char* command);

}  // namespace sm2::tools
