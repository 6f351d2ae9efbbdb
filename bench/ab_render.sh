#!/usr/bin/env bash
# A/B of two forest builds on one frame: renders the same scene and camera with each binary,
# alternating A B A B ... (so that a busy machine slows both alike), and prints per run the
# GPU frame, draw and shadow-pass times, input-assembly primitives and fragment invocations,
# then the median GPU frame and draw times of each and their ratios. For an engine change that has no switch to
# compare within one `forest bench` run (e.g. leaves as one triangle instead of a quad:
# results/leaf_triangles.md). Scenes of unbaked models (`model = "x.glb"`) need no bake, so
# the two builds' different species-cache keys cost nothing.
# Usage: bench/ab_render.sh BIN_A BIN_B SCENE REPEATS [forest render options...]
set -euo pipefail
[[ $# -ge 4 ]] || { echo "usage: bench/ab_render.sh BIN_A BIN_B SCENE REPEATS [render options]" >&2; exit 2; }
a="$1" b="$2" scene="$3" repeats="$4"
shift 4
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
declare -A draws frames
for ((r = 0; r < repeats; ++r)); do
  for side in A B; do
    bin=$a; [[ $side == B ]] && bin=$b
    "$bin" render "$scene" --out "$tmp/$side.png" --stats "$@" >"$tmp/$side.txt" 2>&1 ||
      { cat "$tmp/$side.txt" >&2; exit 1; }
    draw=$(sed -n 's/.*GPU cull [0-9.]* ms, draw \([0-9.]*\) ms.*/\1/p' "$tmp/$side.txt")
    frame=$(sed -n 's/.*GPU cull [0-9.]* ms, draw [0-9.]* ms, frame \([0-9.]*\) ms.*/\1/p' "$tmp/$side.txt")
    shadow=$(sed -n 's/^shadows: GPU \([0-9.]*\) ms.*/\1/p' "$tmp/$side.txt")
    ia=$(sed -n 's/.*IA primitives \([0-9]*\).*/\1/p' "$tmp/$side.txt")
    fs=$(sed -n 's/.*FS invocations \([0-9]*\).*/\1/p' "$tmp/$side.txt")
    echo "$side run $r: GPU frame $frame ms, draw $draw ms, shadow pass ${shadow:-0} ms, IA primitives $ia, FS invocations $fs"
    draws[$side]+="$draw "
    frames[$side]+="$frame "
  done
done
median() { tr ' ' '\n' <<<"$1" | sed '/^$/d' | sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
ratio() { awk -v a="$1" -v b="$2" 'BEGIN {printf "%.2f", a / b}'; }
fa=$(median "${frames[A]}") fb=$(median "${frames[B]}") da=$(median "${draws[A]}") db=$(median "${draws[B]}")
echo "median GPU frame: A $fa ms, B $fb ms, A / B = $(ratio "$fa" "$fb"); median draw: A $da ms, B $db ms, A / B = $(ratio "$da" "$db")"
