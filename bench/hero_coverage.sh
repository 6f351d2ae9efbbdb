#!/usr/bin/env bash
# Issue [2/6] item 2 for the heroes (too big for a test): generates every *_hero preset and
# measures it with `forest measure` (leaf coverage, min over 4 orthographic side views at
# 512²; leaf depth below the crown's hull), writing bench/results/hero_coverage.md.
# Usage: bench/hero_coverage.sh [build dir] (default build). Floor: coverage >= 0.55.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
out="$root/bench/results/hero_coverage.md"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
{
  echo "# Hero coverage (bench/hero_coverage.sh)"
  echo
  echo "\`forest measure --species scenes/species/<hero>.toml\`, $(date -u +%Y-%m-%d), commit $(git -C "$root" rev-parse --short HEAD)."
  echo "Floor (issue [2/6]): coverage >= 0.55, >= 15 000 elements."
  echo
  echo "| preset | elements | coverage min | 0° / 90° / 180° / 270° | depth median ÷ half-width | floor met |"
  echo "|---|--:|--:|---|--:|:-:|"
} > "$tmp/table.md"
status=0
for f in "$root"/scenes/species/*_hero.toml; do
  name="$(basename "$f" .toml)"
  "$build/forest" measure --species "$f" --json "$tmp/$name.json" > /dev/null
  python3 - "$tmp/$name.json" "$name" >> "$tmp/table.md" <<'PY' || status=1
import json, sys
j = json.load(open(sys.argv[1])); c = j["coverage"]
views = " / ".join(f'{v["coverage"]:.3f}' for v in c["views"])
ok = c["min"] >= 0.55 and j["leaves"] >= 15000
print(f'| {sys.argv[2]} | {j["leaves"]} | {c["min"]:.3f} | {views} | {j["depth"]["median_rel"]:.3f} | {"yes" if ok else "NO"} |')
sys.exit(0 if ok else 1)
PY
done
mv "$tmp/table.md" "$out"
cat "$out"
exit $status
