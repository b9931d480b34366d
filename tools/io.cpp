#include "io.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iostream>
#include <iterator>

namespace sm2::tools {

std::string display_name(const std::string& path) { return path == "-" ? "<stdin>" : path; }

std::optional<std::vector<std::byte>> read_input(const std::string& path, std::string& error) {
    std::vector<char> chars;
    if (path == "-") {
        chars.assign(std::istreambuf_iterator<char>(std::cin), std::istreambuf_iterator<char>());
        if (std::cin.bad()) {
            error = "<stdin>: read error";
            return std::nullopt;
        }
    } else {
        std::ifstream in(path, std::ios::binary);
        if (!in) {
            error = path + ": cannot open: " + std::strerror(errno);
            return std::nullopt;
        }
        chars.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
        if (in.bad()) {
            error = path + ": read error";
            return std::nullopt;
        }
    }
    std::vector<std::byte> bytes(chars.size());
    if (!chars.empty()) std::memcpy(bytes.data(), chars.data(), chars.size());
    return bytes;
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
