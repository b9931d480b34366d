#include "io.h"

#include "sm2/runtime/file_io.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iostream>

namespace sm2::tools {

std::string display_name(const std::string& path) { return path == "-" ? "<stdin>" : path; }

std::optional<std::vector<std::byte>> read_input(const std::string& path, std::string& error) {
    return runtime::read_file_limited(path, runtime::kMaxInputFileBytes, error);
}

bool write_output(const std::string& path, const std::vector<std::byte>& data, std::string& error) {
    if (path == "-") {
        std::cout.write(reinterpret_cast<const char*>(data.data()),
                        static_cast<std::streamsize>(data.size()));
        std::cout.flush();
        if (!std::cout) {
            error = "<stdout>: write error";
            return false;
        }
        return true;
    }
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (!out) {
        error = path + ": cannot open for writing: " + std::strerror(errno);
        return false;
    }
    out.write(reinterpret_cast<const char*>(data.data()), static_cast<std::streamsize>(data.size()));
    if (!out) {
        error = path + ": write error";
        return false;
    }
    return true;
}

bool write_output(const std::string& path, const std::string& text, std::string& error) {
    std::vector<std::byte> bytes(text.size());
    if (!text.empty()) std::memcpy(bytes.data(), text.data(), text.size());
    return write_output(path, bytes, error);
}

}  // namespace sm2::tools
