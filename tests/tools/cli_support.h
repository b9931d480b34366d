// Running the sm2 binary from a test: stdin text in, stdout, stderr and exit status out.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace cli_support {

struct Run {
    int status = -1;
    std::string out, err;
};

inline std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// ctest runs each test in its own process, in parallel: the pid keeps their files apart.
inline std::string tmp(const std::string& name) {
    return std::string(SM2_TEST_TMP) + "/" + std::to_string(getpid()) + "_" + name;
}

inline void write_file(const std::string& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

// Runs `ENV sm2 ARGS` (ENV: "NAME=value ..." or empty) with stdin text.
inline Run sm2_with(const std::string& env, const std::string& args, const std::string& stdin_text = "") {
    static int counter = 0;
    const std::string base = tmp("support_run" + std::to_string(counter++));
    write_file(base + ".in", stdin_text);
    const std::string cmd = env + " " + std::string(SM2_TOOL) + " " + args + " <" + base + ".in >" + base +
                            ".out 2>" + base + ".err";
    const int raw = std::system(cmd.c_str());
    Run r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    r.out = slurp(base + ".out");
    r.err = slurp(base + ".err");
    return r;
}

inline Run sm2(const std::string& args, const std::string& stdin_text = "") { return sm2_with("", args, stdin_text); }

}  // namespace cli_support
