// sm2 replay --snapshot: the images of what a call left in the bound render targets and depth-stencil
// surface.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "sm2/runtime/device_inspection.h"

namespace sm2::tools {

// Writes into `folder`, for call `call` of frame `frame`:
//   call_NNNNNN_frame_F_rtI.png   each bound render target I (0..3), 8-bit RGBA; .exr (32-bit
//                                 float RGBA) for float formats (R16F ... A32B32G32R32F)
//   call_NNNNNN_frame_F_depth.exr the depth as 32-bit float in R, G and B (alpha 1)
//   call_NNNNNN_frame_F_stencil.png the stencil value s as s/255 in R, G and B (alpha 1), when the
//                                 format has stencil bits
// and returns the paths written. Throws runtime::ImageIoError when a file cannot be written.
std::vector<std::string> write_snapshot(const runtime::DeviceInspection& state, const std::string& folder,
                                        uint64_t call, uint32_t frame);

// "call_000042_frame_0" (the prefix of the snapshot's files).
[[nodiscard]] std::string snapshot_prefix(uint64_t call, uint32_t frame);

}  // namespace sm2::tools
