#!/bin/bash
# The long fuzz campaign of docs/fuzzing.md: builds the libFuzzer targets with UBSan (no ASan:
# five to ten times the executions a second) in build/fuzzfast, then runs each target named for
# RUNS executions from its seed corpus, one after the other, with a memory limit and a timeout
# per input. Each target's log and grown corpus go to OUT/TARGET.log and OUT/corpus-TARGET; a
# finding stops that target (its crash-*, leak-*, oom-* or timeout-* file in OUT/work-TARGET)
# and the next one runs. Exit 0 when every target ran its executions without a finding.
#
#   scripts/fuzz_campaign.sh [--runs N] [--out DIR] [TARGET...]
#   e.g. scripts/fuzz_campaign.sh --runs 10000000 --out /tmp/campaign image apitrace
#
# TARGET: decoder assembler command_stream replay image apitrace lanes (default: all seven).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
runs=10000000 out=/tmp/sm2-fuzz-campaign
while [ $# -gt 0 ]; do
    case "$1" in
        --runs) runs=$2; shift 2 ;;
        --out) out=$2; shift 2 ;;
        -h|--help) sed -n '2,12p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;;
        -*) echo "fuzz_campaign.sh: unknown option '$1'" >&2; exit 2 ;;
        *) break ;;
    esac
done
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(decoder assembler command_stream replay image apitrace lanes)
seeds() {
    case "$1" in
        decoder) echo "$root/tests/fuzz/corpus/decoder" ;;
        assembler) echo "$root/tests/assembler/corpus" ;;
        command_stream) echo "$root/tests/fuzz/corpus/command_stream" ;;
        replay) echo "$root/tests/fuzz/corpus/replay $root/tests/fuzz/corpus/command_stream" ;;
        image) echo "$root/tests/fuzz/corpus/images" ;;
        apitrace) echo "$root/tests/fuzz/corpus/apitrace" ;;
        lanes) echo "$root/tests/fuzz/corpus/lanes" ;;
        *) echo "fuzz_campaign.sh: no target '$1'" >&2; exit 2 ;;
    esac
}
for t in "${targets[@]}"; do seeds "$t" > /dev/null; done
flags="-fsanitize=undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
cmake -S . -B build/fuzzfast -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang \
    -DCMAKE_BUILD_TYPE=Release -DSM2_FUZZ=ON "-DCMAKE_CXX_FLAGS=$flags" \
    -DCMAKE_EXE_LINKER_FLAGS=-fsanitize=undefined -DCMAKE_SHARED_LINKER_FLAGS=-fsanitize=undefined > /dev/null
cmake --build build/fuzzfast --target "${targets[@]/#/fuzz_}"
mkdir -p "$out"
failed=0
for t in "${targets[@]}"; do
    rm -rf "$out/corpus-$t" "$out/work-$t"
    mkdir -p "$out/corpus-$t" "$out/work-$t"
    start=$(date +%s)
    # shellcheck disable=SC2046  # the seed folders are separate arguments
    if (cd "$out/work-$t" && "$root/build/fuzzfast/tests/fuzz/fuzz_$t" -runs="$runs" -seed=1 -max_len=16384 \
            -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 "$out/corpus-$t" $(seeds "$t")) > "$out/$t.log" 2>&1; then
        status=ok
    else
        status="FINDING (see $out/$t.log)"
        failed=1
    fi
    echo "fuzz_$t: $status, $(( $(date +%s) - start )) s, $(grep -E '^stat::number_of_executed_units' "$out/$t.log" | awk '{print $2}') executions"
done
exit $failed
