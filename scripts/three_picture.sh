#!/usr/bin/env bash
# One picture from tests/tools/three_render.html (three.js, WebGL 2 on SwiftShader in headless
# Chromium), written to PNG; prints the tree's triangle count. One `--dump-dom` run gives both,
# from the same finished page (?dump=1 puts the picture into the page); a run whose page had
# not finished (no title) is tried again, twice at most. Needs build/npm (scripts/test.sh).
# Usage: scripts/three_picture.sh 'file=/abs/x.glb' | 'eztree=Oak%20Medium&seed=1'  OUT.png  SIZE
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
[[ $# -eq 3 ]] || { echo "usage: scripts/three_picture.sh QUERY OUT.png SIZE" >&2; exit 2; }
query="$1" png="$2" size="$3"
cp "$root/tests/tools/three_render.html" "$root/build/npm/three_render.html"
page="file://$root/build/npm/three_render.html"
for attempt in 1 2 3; do
  dom=$(chromium --headless --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader \
    --allow-file-access-from-files --virtual-time-budget=60000 --window-size="$size,$size" \
    --dump-dom "$page?$query&size=$size&dump=1" 2>/dev/null || true)
  if [[ "$dom" == *"<title>rendered: "* && "$dom" == *'<pre id="png">data:image/png;base64,'* ]]; then
    sed -n 's/.*<pre id="png">data:image\/png;base64,\([^<]*\)<\/pre>.*/\1/p' <<<"$dom" | base64 -d >"$png"
    sed -n 's/.*<title>rendered: \([0-9]*\) triangles<\/title>.*/\1/p' <<<"$dom"
    exit 0
  fi
done
echo "three_picture: three.js did not finish $query" >&2
exit 1
