// Loading command streams for the tool's commands (cs pack/dump, replay, bench).
#pragma once

#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "sm2/runtime/command_stream.h"

namespace sm2::tools {

struct LoadedStream {
    runtime::cs::Stream stream;
    std::string file_name;  // for diagnostics ("<stdin>" for "-")
    std::string base_dir;   // side files and LoadTexture paths are relative to it
    std::string root_dir;   // ... and must resolve inside it (--read-root; default base_dir)
};

// Reads a stream in either form (text or binary; "-" is stdin). Side files (@"...") resolve
// inside `read_root` (empty: the stream's folder; runtime/file_io.h resolve_inside). On failure
// prints the error, prefixed with "sm2 COMMAND: " when the file cannot be read, and returns nullopt.
std::optional<LoadedStream> load_stream(const std::string& path, const char* command,
                                        const std::string& read_root = {});

// The --read-root option of the commands that read streams.
void add_read_root_option(CLI::App& command, std::string& read_root);

}  // namespace sm2::tools
