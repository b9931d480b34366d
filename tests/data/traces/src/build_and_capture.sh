#!/bin/bash
# Build the D3D9 test programs with mingw-w64, run each under Wine + Xvfb with
# apitrace's d3d9.dll wrapper, and collect NAME.trace, NAME/frame_N.png and
# (when Debian's `apitrace` is installed) NAME.dump.txt.
#
#   build_and_capture.sh APITRACE_D3D9_DLL [OUTDIR] [PROGRAM...]
#
#   APITRACE_D3D9_DLL  the apitrace d3d9 wrapper (a 64-bit d3d9.dll built for x86_64-w64-mingw32)
#   OUTDIR             where the results go (default: the folder above this script)
#   PROGRAM            any of ff_texops ff_lighting ff_fog_texgen ff_sprites_blend locks_reset
#                      (default: all five)
#
# Environment (optional):
#   BUILD_DIR    build + run folder           (default /tmp/d3d9-traces-build)
#   WINEPREFIX   Wine prefix to use            (default /tmp/d3d9-traces-wineprefix; created if missing)
#   WINE         Wine loader                   (default: wine64 on PATH, else /usr/lib/wine/wine64)
#   MINGW_CC     C compiler                    (default x86_64-w64-mingw32-gcc)
#   DISPLAY_NUM  X display to use; if unset a private Xvfb is started on the first free
#                display from :120 up and stopped at the end
#
# Needs: wine64 (tested with Wine 8.0, Debian), gcc-mingw-w64-x86-64, xvfb, python3,
# Mesa llvmpipe (software OpenGL used by Wine's wined3d); optional: apitrace (Linux CLI).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
if [ $# -lt 1 ]; then sed -n '2,23p' "$0" | sed 's/^# \{0,1\}//'; exit 2; fi
dll=$(realpath "$1"); shift
[ -f "$dll" ] || { echo "no such file: $dll" >&2; exit 2; }
out=${1:-$(dirname "$here")}; [ $# -gt 0 ] && shift
mkdir -p "$out"; out=$(cd "$out" && pwd)
programs=("$@"); [ ${#programs[@]} -gt 0 ] || programs=(ff_texops ff_lighting ff_fog_texgen ff_sprites_blend locks_reset)

build=${BUILD_DIR:-/tmp/d3d9-traces-build}
cc=${MINGW_CC:-x86_64-w64-mingw32-gcc}
wine=${WINE:-$(command -v wine64 || echo /usr/lib/wine/wine64)}
export WINEPREFIX=${WINEPREFIX:-/tmp/d3d9-traces-wineprefix}
export WINEDEBUG=${WINEDEBUG:--all}
export GALLIUM_DRIVER=${GALLIUM_DRIVER:-llvmpipe}
mkdir -p "$build"

# ---- build ----
for p in "${programs[@]}"; do
    libs=(-ld3d9)
    [ "$p" = shader_scene ] && libs=(-ld3d9 -ld3dx9_43)
    "$cc" -std=gnu11 -O2 -Wall -Wextra -Wno-unused-parameter -Wno-missing-field-initializers \
        -o "$build/$p.exe" "$here/$p.c" "${libs[@]}" -lm
    echo "built $build/$p.exe"
done

# ---- X server + Wine prefix ----
xvfb_pid=
cleanup() {
    "$(dirname "$wine")/wineserver" -k 2>/dev/null || wineserver -k 2>/dev/null || true
    if [ -n "$xvfb_pid" ]; then kill "$xvfb_pid" 2>/dev/null || true; wait "$xvfb_pid" 2>/dev/null || true; fi
}
trap cleanup EXIT
if [ -n "${DISPLAY_NUM:-}" ]; then
    export DISPLAY=":$DISPLAY_NUM"
else
    n=120
    while [ -e "/tmp/.X11-unix/X$n" ] || [ -e "/tmp/.X$n-lock" ]; do n=$((n + 1)); done
    Xvfb ":$n" -screen 0 1024x768x24 -nolisten tcp >/dev/null 2>&1 &
    xvfb_pid=$!
    for _ in $(seq 100); do [ -e "/tmp/.X11-unix/X$n" ] && break; sleep 0.05; done
    [ -e "/tmp/.X11-unix/X$n" ] || { echo "Xvfb :$n did not start" >&2; exit 1; }
    export DISPLAY=":$n"
fi
if [ ! -f "$WINEPREFIX/system.reg" ]; then
    WINEDLLOVERRIDES="mscoree,mshtml=" "$wine" wineboot -i >/dev/null 2>&1
fi

# ---- capture ----
# The wrapper d3d9.dll sits next to the .exe; "d3d9=n,b" makes Wine load it (native) instead of
# its builtin d3d9, and the wrapper then loads the real one from GetSystemDirectory()
# (C:\windows\system32\d3d9.dll = Wine's builtin).  TRACE_FILE names the output.
status=0
for p in "${programs[@]}"; do
    run="$build/run_$p"
    rm -rf "$run"; mkdir -p "$run"
    cp "$build/$p.exe" "$run/"
    cp "$dll" "$run/d3d9.dll"
    echo "== $p"
    rc=0
    (cd "$run" && WINEDLLOVERRIDES="mscoree,mshtml=;d3d9=n,b" TRACE_FILE="$p.trace" \
        timeout 300 "$wine" "$p.exe" . >"$run/run.log" 2>&1) || rc=$?
    sed 's/^/   /' "$run/run.log"
    if [ $rc -ne 0 ] || [ ! -s "$run/$p.trace" ]; then echo "   FAILED (exit $rc)"; status=1; continue; fi
    rm -rf "${out:?}/$p"; mkdir -p "$out/$p"
    for f in "$run"/frame_*.bmp; do
        python3 "$here/bmp2png.py" "$f" "$out/$p/$(basename "${f%.bmp}").png"
    done
    cp "$run/$p.trace" "$out/$p.trace"
    [ -f "$run/depth.txt" ] && cp "$run/depth.txt" "$out/$p/depth.txt"
    if command -v apitrace >/dev/null 2>&1; then
        apitrace dump -v --color=never "$out/$p.trace" >"$out/$p.dump.txt"
    fi
    echo "   -> $out/$p.trace ($(stat -c %s "$out/$p.trace") bytes), $(ls "$out/$p" | wc -l) frames"
done
exit $status
