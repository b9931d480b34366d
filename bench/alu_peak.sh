#!/bin/bash
# ALU-bound pixel shading against the machine's fp32 FMA peak: samples/shaders/alu64.ps.asm (64
# arithmetic slots, no texture) on a full-screen 1024x768 quad, replayed by `sm2 bench`; prints
# the shader's fp32 operations per pixel (counted below), the rate sm2 reaches and its share of
# the peak. A measurement: exit 0 whether or not the 25% goal of issue 9 is met.
#
#   bench/alu_peak.sh [--sm2 PATH] [--threads N] [--repeat R] [--ghz F] [-- SM2-BENCH-FLAGS...]
#   e.g. bench/alu_peak.sh --threads 2 -- --transcendentals fast
#
# Peak = threads x 2 FMA units x fp32 lanes x 2 operations x clock (the formula of issue 9; the
# lanes are the host's vector width, 16 with AVX-512, 8 with AVX2 and FMA, 4 otherwise, from
# /proc/cpuinfo's flags; the clock is its "cpu MHz" unless --ghz is given). Operations per pixel: per
# written component, mad/lrp 2, add/mul/min/max/cmp/frc/abs 1, _sat +1, mov 0; per
# instruction, dp3 5, dp4 7, nrm 9 (dp3, rsq, 3 mul), rcp/rsq/exp/log 1, pow 3 (log, mul, exp).
set -euo pipefail
cd "$(dirname "$0")/.."
usage() { sed -n '2,13p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 2; }
sm2=build/release/tools/sm2 threads=2 repeat=5 ghz=""
while [ $# -gt 0 ]; do
    case "$1" in
        --sm2) sm2=$2; shift 2 ;;
        --threads) threads=$2; shift 2 ;;
        --repeat) repeat=$2; shift 2 ;;
        --ghz) ghz=$2; shift 2 ;;
        --) shift; break ;;
        -h|--help) usage ;;
        *) echo "alu_peak.sh: unknown argument '$1'" >&2; usage ;;
    esac
done
[ -x "$sm2" ] || { echo "alu_peak.sh: no sm2 at $sm2 (build first: scripts/build.sh)" >&2; exit 2; }
if [ -z "$ghz" ]; then
    ghz=$(awk -F: '/^cpu MHz/ { printf "%.3f", $2 / 1000; exit }' /proc/cpuinfo)
    [ -n "$ghz" ] || { echo "alu_peak.sh: no 'cpu MHz' in /proc/cpuinfo; give --ghz" >&2; exit 2; }
fi
flags=$(awk -F: '/^flags/ { print $2; exit }' /proc/cpuinfo)
case " $flags " in
    *" avx512f "*) lanes=16 ;;
    *" avx2 "*) lanes=8 ;;
    *) lanes=4 ;;
esac
shader=samples/shaders/alu64.ps.asm
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
stream=$work/alu64_1024.sm2cs
{
    cat <<'END'
sm2cs 1
# alu64.ps.asm on two triangles covering a 1024x768 target; t0 and t1 vary over the screen.
CreateDevice 1024 768 A8R8G8B8
CreateVertexDeclaration decl { 0 0 FLOAT4 DEFAULT POSITION 0 } { 0 16 FLOAT4 DEFAULT TEXCOORD 0 }
CreateVertexShader vs asm<<END_SHADER
vs_2_0
dcl_position v0
dcl_texcoord v1
mov oPos, v0
mov oT0, v1
mad oT1, v1, c0.x, c0.y
END_SHADER
CreatePixelShader ps asm<<END_SHADER
END
    cat "$shader"
    cat <<'END'
END_SHADER
SetVertexDeclaration decl
SetVertexShader vs
SetPixelShader ps
SetVertexShaderConstantF 0 f32[ 0.5 0.25 0 0 ]
BeginScene
DrawPrimitiveUP TRIANGLESTRIP 2 32 f32[ -1 1 0.5 1  0 0 0.5 1   1 1 0.5 1  1 0 0.25 1   -1 -1 0.5 1  0 1 0.75 1   1 -1 0.5 1  1 1 1 1 ]
EndScene
Present
END
} > "$stream"
operations=$(python3 - "$shader" <<'EOF'
import re, sys
per_component = {"mad": 2, "lrp": 2, "add": 1, "mul": 1, "min": 1, "max": 1, "cmp": 1, "frc": 1, "abs": 1, "mov": 0}
per_instruction = {"dp3": 5, "dp4": 7, "nrm": 9, "rcp": 1, "rsq": 1, "exp": 1, "log": 1, "pow": 3}
total = 0
for line in open(sys.argv[1]):
    line = line.split("//")[0].strip()
    if not line or line.startswith(("ps_", "dcl", "def")):
        continue
    op, _, rest = line.partition(" ")
    base, sat = op.split("_")[0], op.endswith("_sat")
    dest = rest.split(",")[0].strip()
    mask = dest.split(".")[1] if "." in dest else "xyzw"
    if base in per_component:
        total += (per_component[base] + sat) * len(mask)
    elif base in per_instruction:
        total += per_instruction[base] + sat
    else:
        sys.exit("alu_peak.sh: no operation count for '%s'" % base)
print(total)
EOF
)
out=$("$sm2" bench "$stream" --threads "$threads" --repeat "$repeat" "$@")
echo "$out" | grep -E "time per run|pixels shaded/s|engine" || true
pixels_per_second=$(echo "$out" | awk '/^pixels shaded\/s:/ { v = $3; u = $4; if (u == "M") v *= 1e6; else if (u == "k") v *= 1e3; else if (u == "G") v *= 1e9; print v }')
python3 - "$operations" "$pixels_per_second" "$threads" "$ghz" "$lanes" <<'EOF'
import sys
ops, rate, threads, ghz, lanes = int(sys.argv[1]), float(sys.argv[2]), int(sys.argv[3]), float(sys.argv[4]), int(sys.argv[5])
achieved = ops * rate
peak = threads * 2 * lanes * 2 * ghz * 1e9
print("alu64: %d fp32 operations per pixel; %.1f Mpixels/s -> %.2f GFLOP/s" % (ops, rate / 1e6, achieved / 1e9))
print("peak: %d thread(s) x 2 FMA x %d lanes x 2 x %.3f GHz = %.1f GFLOP/s" % (threads, lanes, ghz, peak / 1e9))
print("share of the fp32 FMA peak: %.2f%% (goal >= 25%%)" % (100 * achieved / peak))
EOF
