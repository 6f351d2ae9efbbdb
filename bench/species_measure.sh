#!/usr/bin/env bash
# Every species preset measured with `forest measure` (issue [2/6] items 1-3): elements, leaf
# coverage (min over 4 orthographic side views at 512², leaves alone), leaf depth below the
# crown's hull, and the habit of the generated graph. Writes bench/results/species_measure.md
# (the README's "Crown density and habit" table). Usage: bench/species_measure.sh [build dir]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
out="$root/bench/results/species_measure.md"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
for f in "$root"/scenes/species/*.toml; do
  "$build/forest" measure --species "$f" --json "$tmp/$(basename "$f" .toml).json" > /dev/null
done
python3 - "$tmp" "$(git -C "$root" rev-parse --short HEAD)" > "$tmp/table.md" <<'PY'
import json, sys, glob, os, datetime
dense = {"fagus_sylvatica", "acer_campestre", "quercus_robur", "ulmus_laevis", "populus_trichocarpa",
         "picea_abies", "broadleaf", "conifer"}
open_ = {"betula_pendula", "larix_decidua", "salix_alba", "pinus_sylvestris"}
print("# Species measurements (bench/species_measure.sh)\n")
print(f"`forest measure --species scenes/species/<preset>.toml`, {datetime.date.today()}, commit {sys.argv[2]}, lavapipe.")
print("Floors (issue [2/6]): coverage >= 0.55 dense crowns and heroes, >= 0.35 open crowns; elements >= 4000")
print("(species, demo), >= 15000 (heroes); method demos have none. Depth: leaf distance below the convex")
print("hull of all leaves, quartiles ÷ crown half-width. Habit on the generated graph (generators/tree/habit.h).\n")
print("| preset | elements | coverage min (floor) | depth q1 / median / q3 | crown w ÷ H | clear bole ÷ H | trunk ÷ H | single leader | H (m) |")
print("|---|--:|--:|---|--:|--:|--:|:-:|--:|")
for p in sorted(glob.glob(os.path.join(sys.argv[1], "*.json"))):
    name = os.path.basename(p)[:-5]; j = json.load(open(p)); c = j["coverage"]["min"]; d = j["depth"]; h = j["habit"]
    floor = 0.55 if name in dense or name.endswith("_hero") else 0.35 if name in open_ else None
    mark = "" if floor is None else f" ({floor:.2f}{'' if c >= floor else ' NOT MET'})"
    print(f'| {name} | {j["leaves"]} | {c:.3f}{mark} | {d["q1_rel"]:.2f} / {d["median_rel"]:.2f} / {d["q3_rel"]:.2f} | '
          f'{h["crown_width_over_height"]:.2f} | {h["clear_bole_over_height"]:.2f} | {h["trunk_fraction"]:.2f} | '
          f'{"yes" if h["single_leader"] else "no"} | {h["height_m"]:.1f} |')
PY
mv "$tmp/table.md" "$out"
cat "$out"
