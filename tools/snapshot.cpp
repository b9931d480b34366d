#include "snapshot.h"

#include <cstdio>
#include <filesystem>

#include "sm2/runtime/formats.h"
#include "sm2/runtime/image_io.h"

namespace sm2::tools {

namespace {

// The float colour formats (R16F, G32R32F, ...): an 8-bit PNG would clamp them.
bool is_float_format(runtime::Format format) {
    const runtime::FormatInfo* info = runtime::format_info(format);
    return info && info->kind == runtime::FormatKind::Color && info->name.ends_with('F');
}

}  // namespace

std::string snapshot_prefix(uint64_t call, uint32_t frame) {
    char name[64];
    std::snprintf(name, sizeof name, "call_%06llu_frame_%u", static_cast<unsigned long long>(call), frame);
    return name;
}

std::vector<std::string> write_snapshot(const runtime::DeviceInspection& state, const std::string& folder,
                                        uint64_t call, uint32_t frame) {
    std::vector<std::string> written;
    const std::string base = (std::filesystem::path(folder) / snapshot_prefix(call, frame)).string();
    for (unsigned i = 0; i < state.render_targets.size(); ++i) {
        const runtime::Surface* target = state.render_targets[i];
        if (!target) continue;
        const std::string path = base + "_rt" + std::to_string(i) + (is_float_format(target->format()) ? ".exr" : ".png");
        runtime::write_surface(*target, path);
        written.push_back(path);
    }
    if (const runtime::DepthStencilSurface* ds = state.depth_stencil) {
        runtime::write_surface(runtime::depth_as_surface(*ds), base + "_depth.exr");
        written.push_back(base + "_depth.exr");
        if (ds->info().stencil_bits > 0) {
            runtime::write_surface(runtime::stencil_as_surface(*ds), base + "_stencil.png");
            written.push_back(base + "_stencil.png");
        }
    }
    return written;
}

}  // namespace sm2::tools
