#!/bin/bash
# Calls from the block kernels (AVX-512 and AVX2 code: sm2::runtime::avx512 and ::avx2, and
# GCC's target clones) into other code with no vzeroupper just before them, in a build's sm2.
# Such a callee's SSE code runs with the registers' upper halves dirty and waits on them: on the
# Intel machine of 2026-12-03, choose_levels() called so from block_sample_anisotropic() was a
# quarter of scene 10's run (docs/performance.md, the twenty-seventh session). Prints one line
# per caller and callee; exit 0 whatever it finds (a diagnostic, like the other bench scripts).
#
#   bench/sse_transitions.sh [SM2]      (default build/release/tools/sm2)
#
# A call through a register (a kernel chosen per draw, itself AVX code) is listed as "*reg".
# Only the instructions before a call within its function are read, not its control flow: a
# vzeroupper on another path counts, so a clean report is necessary, not sufficient.
set -euo pipefail
cd "$(dirname "$0")/.."
sm2=${1:-build/release/tools/sm2}
[ -x "$sm2" ] || { echo "sse_transitions.sh: no $sm2 (build first: scripts/build.sh sm2)" >&2; exit 2; }
command -v objdump >/dev/null || { echo "sse_transitions.sh: needs objdump (binutils)" >&2; exit 2; }
objdump -d --no-show-raw-insn -C "$sm2" | awk '
    # A function header: "0000... <name>:". Kernels: the instruction-set namespaces and clones.
    /^[0-9a-f]+ <.*>:$/ {
        name = substr($0, index($0, "<") + 1); sub(/>:$/, "", name)
        kernel = name ~ /sm2::runtime::(avx512|avx2)::/ || name ~ /\.arch_x86_64_v[34]|\.avx/
        since = 1000; wide = 0; next
    }
    !kernel { next }
    /%[yz]mm/ { wide = 1 }
    /vzeroupper/ { since = 0; next }
    { ++since }
    /\tcall / && wide && since > 6 {
        callee = $0; sub(/.*\tcall +/, "", callee); sub(/^[0-9a-f]+ </, "", callee); sub(/>$/, "", callee)
        if (callee ~ /^\*/) callee = "*reg"
        print short(name) "  ->  " short(callee)
    }
    # A name without "(anonymous namespace)::", its arguments and its return type; a clone keeps
    # its suffix.
    function short(n,    clone) {
        clone = ""
        if (match(n, /\[clone [^]]*\]/)) clone = " " substr(n, RSTART, RLENGTH)
        gsub(/\(anonymous namespace\)::/, "", n)
        sub(/\(.*/, "", n)
        sub(/^[^ <]* /, "", n)
        return n clone
    }' | sort | uniq -c | sort -rn
