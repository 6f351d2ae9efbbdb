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
print("Habit ranges: the preset's [habit] table (cited in its `# habit:` comments); a cell shows measured")
print("[range], and OUT where the value is outside it.\n")
print("| preset | elements | coverage min (floor) | depth q1 / median / q3 | crown w ÷ H [range] | clear bole ÷ H [range] | trunk ÷ H [min] | single leader [required] | H (m) |")
print("|---|--:|--:|---|--:|--:|--:|:-:|--:|")
def cell(h, r, key, fmt="{:.2f}"):
    v = h[key]
    txt = "yes" if v is True else "no" if v is False else fmt.format(v)
    x = r.get(key)
    if x is None: return txt
    if "range" in x: txt += f" [{x['range'][0]:.2f}–{x['range'][1]:.2f}]"
    elif "min" in x: txt += f" [≥ {x['min']:.2f}]"
    elif "required" in x: txt += " [required]" if x["required"] else ""
    return txt + ("" if x["in_range"] else " OUT")
for p in sorted(glob.glob(os.path.join(sys.argv[1], "*.json"))):
    name = os.path.basename(p)[:-5]; j = json.load(open(p)); c = j["coverage"]["min"]; d = j["depth"]; h = j["habit"]
    r = j.get("habit_ranges") or {}
    if "trunk_fraction" in r or "trunk_fraction_min" in r: r["trunk_fraction"] = r.get("trunk_fraction", r.get("trunk_fraction_min"))
    floor = 0.55 if name in dense or name.endswith("_hero") else 0.35 if name in open_ else None
    mark = "" if floor is None else f" ({floor:.2f}{'' if c >= floor else ' NOT MET'})"
    print(f'| {name} | {j["leaves"]} | {c:.3f}{mark} | {d["q1_rel"]:.2f} / {d["median_rel"]:.2f} / {d["q3_rel"]:.2f} | '
          f'{cell(h, r, "crown_width_over_height")} | {cell(h, r, "clear_bole_over_height")} | {cell(h, r, "trunk_fraction")} | '
          f'{cell(h, r, "single_leader")} | {h["height_m"]:.1f} |')
PY
mv "$tmp/table.md" "$out"
cat "$out"
