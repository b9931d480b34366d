// Reading input files safely, and keeping a stream's file names inside their folder.
//
// Every file the project reads from a user (shaders, streams, side files, lane CSVs, textures,
// images to compare) goes through read_file_limited() or check_input_file(): only regular files
// (a directory, /dev/zero, a FIFO or a socket is refused before anything is read, and a FIFO is
// opened without blocking), and at most a size limit.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace sm2::runtime {

// The default size limit for one input file: 256 MiB (shaders and streams are far smaller; the
// largest texture, 4096x4096 of 128-bit texels with its mip chain, is 341 MiB as DDS, so loaders
// of images pass kMaxImageFileBytes).
constexpr uint64_t kMaxInputFileBytes = uint64_t{256} << 20;
constexpr uint64_t kMaxImageFileBytes = uint64_t{1} << 30;

// Reads the whole regular file `path` ("-": standard input, which may be a pipe) of at most
// `max_bytes`. On failure: nullopt and `error` = "PATH: reason" (is a directory, is not a regular
// file, larger than the limit, cannot open: strerror).
[[nodiscard]] std::optional<std::vector<std::byte>> read_file_limited(const std::string& path, uint64_t max_bytes,
                                                                      std::string& error);

// The same checks without reading, for readers that open the file themselves (OpenImageIO):
// `path` exists, is a regular file (after symlinks) and has at most `max_bytes`.
[[nodiscard]] bool check_input_file(const std::string& path, uint64_t max_bytes, std::string& error);

// Resolves `path`, a file name written in a command stream, inside the folder `root`: relative
// paths are taken from `base` (a folder inside root, usually root itself), absolute paths are
// refused, and the result (with `..` and every symbolic link of its existing part resolved) must
// lie inside root. nullopt and a reason in `error` otherwise.
[[nodiscard]] std::optional<std::string> resolve_inside(const std::string& root, const std::string& base,
                                                        const std::string& path, std::string& error);

}  // namespace sm2::runtime
