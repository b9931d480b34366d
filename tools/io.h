// File and stdin/stdout access for the tool; "-" means the standard stream.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace sm2::tools {

// Reads the whole file (or stdin for "-"): a regular file of at most runtime::kMaxInputFileBytes
// (runtime/file_io.h); nullopt and a message in `error` on failure.
std::optional<std::vector<std::byte>> read_input(const std::string& path, std::string& error);
// Writes (or stdout for "-"); false and a message in `error` on failure.
bool write_output(const std::string& path, const std::vector<std::byte>& data, std::string& error);
bool write_output(const std::string& path, const std::string& text, std::string& error);
// "<stdin>" for "-", else the path.
std::string display_name(const std::string& path);

}  // namespace sm2::tools
