// Precision modes of the numeric policy (numerics.h has the rounding functions, inline).
#include "numerics.h"

namespace sm2::emu::numerics {

ResultRounding result_rounding(const PrecisionOptions& options, bool pixel_shader,
                               bool partial_precision) {
    if (options.precision == Precision::Fp64) return ResultRounding::None;
    if (partial_precision && options.partial_precision_fp16 && pixel_shader)
        return ResultRounding::Fp16;
    if (options.precision == Precision::Fp24 && pixel_shader) return ResultRounding::Fp24;
    return ResultRounding::None;
}

}  // namespace sm2::emu::numerics
