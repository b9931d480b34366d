#!/usr/bin/env bash
# ctest demo_two_scenes: scripts/demo.sh on two small scenes with a built sm2, into WORK:
# the summary's totals, the per-scene lines, index.html's relative links to every frame.
#   tests/demo/check_demo.sh SOURCE_DIR SM2 WORK
set -euo pipefail
source_dir="$1"; sm2="$2"; work="$3"
rm -rf "$work"
fail() { echo "check_demo: $*" >&2; exit 1; }

summary=$(bash "$source_dir/scripts/demo.sh" --scenes '0[12]_*' --out "$work" --sm2 "$sm2") \
  || fail "demo.sh exited with $?: $summary"
echo "$summary"
grep -q '^demo: 2 scenes (0 failed), 3 frames, [0-9.]* s replaying; probes 20/20 passed; 6 shaders validated' <<<"$summary" \
  || fail "summary totals: expected 2 scenes, 3 frames, probes 20/20, 6 shaders"
grep -Eq '^01_gouraud_triangle +1 +[0-9]+\.[0-9]{3} +9/9$' <<<"$summary" || fail "no summary line for scene 01"
grep -Eq '^02_shared_edges_stencil +2 +[0-9]+\.[0-9]{3} +11/11$' <<<"$summary" || fail "no summary line for scene 02"
for n in 0 1 2; do
  grep -q "^ok    trace ff_lit_cube frame $n matches Wine's" <<<"$summary" || fail "no trace line for ff_lit_cube frame $n"
done
grep -q "contact sheet $work/index.html" <<<"$summary" || fail "summary does not say where index.html is"
[ -z "$(ls "$work/scenes" | grep -v -e '^01_gouraud_triangle$' -e '^02_shared_edges_stencil$' -e '^runs.tsv$')" ] \
  || fail "scenes outside the pattern were replayed: $(ls "$work/scenes")"

index="$work/index.html"
[ -f "$index" ] || fail "no $index"
mapfile -t images < <(grep -o '<img src="[^"]*"' "$index" | sed 's/<img src="\(.*\)"/\1/')
[ "${images[*]}" = "scenes/01_gouraud_triangle/frame_0000.png scenes/02_shared_edges_stencil/frame_0000.png scenes/02_shared_edges_stencil/frame_0001.png" ] \
  || fail "index.html images: ${images[*]}"
for image in "${images[@]}"; do
  cmp -s <(head -c 8 "$work/$image") <(printf '\x89PNG\r\n\x1a\n') || fail "$image is not a PNG beside index.html"
done
! grep -Eiq '(src|href)="(https?:|//|/)' "$index" || fail "index.html links outside its folder"
! grep -qi '<script\|<link\|@import\|url(' "$index" || fail "index.html loads external resources"

# A pattern that matches nothing is bad usage.
status=0
bash "$source_dir/scripts/demo.sh" --scenes 'no_such_scene' --out "$work/none" --sm2 "$sm2" 2>/dev/null || status=$?
[ "$status" = 2 ] || fail "--scenes matching nothing: exit $status, expected 2"
echo "check_demo: ok"
