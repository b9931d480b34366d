// Regular files only, with a size limit; stream file names confined to their folder.
#include "sm2/runtime/file_io.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

namespace sm2::runtime {

namespace {

std::string display(const std::string& path) { return path == "-" ? "<stdin>" : path; }

// Why a file of this mode is not read (empty for a regular file).
std::string not_regular(mode_t mode) {
    if (S_ISREG(mode)) return {};
    if (S_ISDIR(mode)) return "is a directory";
    if (S_ISFIFO(mode)) return "is a FIFO (named pipe), not a regular file";
    if (S_ISCHR(mode)) return "is a character device, not a regular file";
    if (S_ISBLK(mode)) return "is a block device, not a regular file";
    if (S_ISSOCK(mode)) return "is a socket, not a regular file";
    return "is not a regular file";
}

std::string too_large(uint64_t max_bytes) {
    return "larger than the " + std::to_string(max_bytes) + "-byte limit for an input file";
}

// Reads `fd` to its end, refusing more than max_bytes.
std::optional<std::vector<std::byte>> read_all(int fd, const std::string& name, uint64_t max_bytes, uint64_t hint,
                                               std::string& error) {
    std::vector<std::byte> bytes;
    bytes.reserve(static_cast<size_t>(std::min<uint64_t>(hint, max_bytes)));
    std::byte chunk[65536];
    while (true) {
        const ssize_t n = ::read(fd, chunk, sizeof chunk);
        if (n < 0) {
            if (errno == EINTR) continue;
            error = name + ": read error: " + std::strerror(errno);
            return std::nullopt;
        }
        if (n == 0) return bytes;
        if (bytes.size() + static_cast<size_t>(n) > max_bytes) {
            error = name + ": " + too_large(max_bytes);
            return std::nullopt;
        }
        bytes.insert(bytes.end(), chunk, chunk + n);
    }
}

}  // namespace

std::optional<std::vector<std::byte>> read_file_limited(const std::string& path, uint64_t max_bytes,
                                                        std::string& error) {
    const std::string name = display(path);
    struct stat st {};
    if (path == "-") {
        // Standard input may be a pipe or a terminal; only a directory is refused outright, and
        // the size limit bounds the rest (/dev/zero as stdin ends at the limit).
        if (::fstat(STDIN_FILENO, &st) == 0 && S_ISDIR(st.st_mode)) {
            error = name + ": is a directory";
            return std::nullopt;
        }
        return read_all(STDIN_FILENO, name, max_bytes, 0, error);
    }
    // O_NONBLOCK: opening a FIFO with no writer must not wait for one.
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (fd < 0) {
        error = name + ": cannot open: " + std::strerror(errno);
        return std::nullopt;
    }
    std::optional<std::vector<std::byte>> bytes;
    if (::fstat(fd, &st) != 0) {
        error = name + ": cannot stat: " + std::strerror(errno);
    } else if (const std::string why = not_regular(st.st_mode); !why.empty()) {
        error = name + ": " + why;
    } else if (static_cast<uint64_t>(st.st_size) > max_bytes) {
        error = name + ": " + too_large(max_bytes) + " (" + std::to_string(st.st_size) + " bytes)";
    } else {
        const int flags = ::fcntl(fd, F_GETFL);
        if (flags >= 0) (void)::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
        bytes = read_all(fd, name, max_bytes, static_cast<uint64_t>(st.st_size), error);
    }
    ::close(fd);
    return bytes;
}

bool check_input_file(const std::string& path, uint64_t max_bytes, std::string& error) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) {
        error = path + ": cannot open: " + std::strerror(errno);
        return false;
    }
    if (const std::string why = not_regular(st.st_mode); !why.empty()) {
        error = path + ": " + why;
        return false;
    }
    if (static_cast<uint64_t>(st.st_size) > max_bytes) {
        error = path + ": " + too_large(max_bytes) + " (" + std::to_string(st.st_size) + " bytes)";
        return false;
    }
    return true;
}

std::optional<std::string> resolve_inside(const std::string& root, const std::string& base, const std::string& path,
                                          std::string& error) {
    namespace fs = std::filesystem;
    if (path.empty()) {
        error = "empty file name";
        return std::nullopt;
    }
    const fs::path p(path);
    if (p.is_absolute() || p.has_root_name()) {
        error = "'" + path + "' is an absolute path; streams may name files only relative to their folder";
        return std::nullopt;
    }
    std::error_code ec;
    const fs::path root_abs = fs::absolute(root.empty() ? fs::path(".") : fs::path(root), ec);
    fs::path root_real = ec ? fs::path() : fs::weakly_canonical(root_abs, ec);
    if (ec || root_real.empty()) {
        error = "cannot resolve the folder '" + root + "'" + (ec ? ": " + ec.message() : std::string());
        return std::nullopt;
    }
    const fs::path full_abs = fs::absolute((base.empty() ? fs::path(".") : fs::path(base)) / p, ec);
    fs::path full_real = ec ? fs::path() : fs::weakly_canonical(full_abs, ec);
    if (ec || full_real.empty()) {
        error = "cannot resolve '" + path + "'" + (ec ? ": " + ec.message() : std::string());
        return std::nullopt;
    }
    // Compare by components, ignoring a trailing separator ("dir/" has an empty last element).
    auto components = [](const fs::path& q) {
        std::vector<fs::path> parts;
        for (const fs::path& part : q)
            if (!part.empty()) parts.push_back(part);
        return parts;
    };
    const auto r = components(root_real), f = components(full_real);
    if (f.size() < r.size() || !std::equal(r.begin(), r.end(), f.begin())) {
        error = "'" + path + "' resolves to " + full_real.string() + ", outside " + root_real.string() +
                " (no '..' or symbolic link may leave it)";
        return std::nullopt;
    }
    return full_real.string();
}

}  // namespace sm2::runtime
