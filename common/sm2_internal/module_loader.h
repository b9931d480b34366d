// Finding and dlopen()ing one of sm2emu's own modules (the image I/O module, the JIT), which
// are loaded only when first needed so that a process that does not use them does not pay for
// the shared libraries behind them (OpenImageIO, LLVM). Header-only and private: compiled into
// the runtime and emu libraries, never installed.
//
// Where a module NAME is looked for, first found wins (docs/embedding.md):
//   1. $ENV_VAR, a path to the module (then only there);
//   2. <folder of the running executable>/<bindir-to-module-dir path of the install layout>
//      (an installed `sm2`: PREFIX/bin -> PREFIX/lib/sm2emu; the build tree has the same
//      layout: build/tools/sm2, build/tests/*, build/bench/* -> build/lib/sm2emu);
//   3. the same relative path, and ./sm2emu/, from the file that holds the caller's code (a
//      shared library in PREFIX/lib);
//   4. the install folder chosen at configure time (CMAKE_INSTALL_FULL_LIBDIR/sm2emu);
//   5. the build tree's folder.
#pragma once

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

namespace sm2::internal {

struct ModuleLocation {
    const char* name;          // file name, e.g. "sm2emu_jit.so"
    const char* env_var;       // e.g. "SM2EMU_JIT"
    const char* relative_dir;  // from PREFIX/bin to the module folder, e.g. "../lib/sm2emu"
    const char* install_dir;   // absolute
    const char* build_dir;     // absolute
};

// dlopen()s the module and returns dlsym(symbol) from it, or nullptr with `why` saying where it
// looked and what failed. `anchor`: an address in the caller's own code (for dladdr).
inline void* load_module_symbol(const ModuleLocation& where, const char* symbol, const void* anchor,
                                std::string& why) {
    namespace fs = std::filesystem;
    std::vector<fs::path> list;
    auto add = [&list](const fs::path& p) {
        std::error_code ec;
        fs::path normal = fs::weakly_canonical(p, ec);
        if (ec) normal = p.lexically_normal();
        for (const auto& q : list)
            if (q == normal) return;
        list.push_back(normal);
    };
    if (const char* env = std::getenv(where.env_var); env != nullptr && *env != '\0') {
        list.emplace_back(env);
    } else {
        std::error_code ec;
        const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
        if (!ec) add(exe.parent_path() / where.relative_dir / where.name);
        Dl_info info{};
        if (dladdr(anchor, &info) != 0 && info.dli_fname != nullptr) {
            const fs::path self = info.dli_fname;
            if (self.has_parent_path()) {
                add(self.parent_path() / where.relative_dir / where.name);
                add(self.parent_path() / "sm2emu" / where.name);
            }
        }
        add(fs::path(where.install_dir) / where.name);
        add(fs::path(where.build_dir) / where.name);
    }
    why.clear();
    for (const auto& path : list) {
        std::error_code ec;
        if (!fs::exists(path, ec)) {
            why += "\n  " + path.string() + ": not found";
            continue;
        }
        void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) {
            const char* e = dlerror();
            why += "\n  " + path.string() + ": " + (e ? e : "cannot load");
            continue;
        }
        if (void* entry = dlsym(handle, symbol)) return entry;  // never unloaded
        why += "\n  " + path.string() + ": has no " + symbol + " (another version of sm2emu?)";
        dlclose(handle);
    }
    why = std::string("cannot load the module ") + where.name + " (set " + where.env_var + " to its path):" + why;
    return nullptr;
}

}  // namespace sm2::internal
