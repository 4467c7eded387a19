#!/bin/sh
# Size and load time of the viewer's page for a 20-variable robot with 500 pieces along a
# 1,000-waypoint path (bench/view_bench.cpp writes it). The load time is the page's own
# data-load-ms: milliseconds from navigation start until the first image is drawn, in headless
# Chromium with software WebGL (SwiftShader), read with --dump-dom; frame_ms is the page's
# data-frame-ms: the mean time to show one frame (poses, contact, plot, render) over all frames.
# The same for the shelf demo's page (tests/viewer/shelf_demo_path.txt: 68 frames), for scale.
# RUNS loads of each (default 5), written to bench/results/view_bench.csv and printed: page, bytes,
# run, load_ms, frame_ms, and for view_bench's page the seconds it took to build and write it.
#   bench/run_view_bench.sh BUILD_DIR [RUNS]      (from the repository root)
set -eu
build=${1:?usage: run_view_bench.sh BUILD_DIR [RUNS]}
runs=${2:-5}
csv="$(cd "$(dirname "$0")" && pwd)/results/view_bench.csv"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$build/bench/view_bench" "$out/bench.html" > "$out/written.txt"
made=$(awk 'NR == 2 {print $5 "," $6}' "$out/written.txt")
browser=$(command -v chromium || command -v chromium-headless-shell || true)
if [ -z "$browser" ]; then
  echo "no Chromium: load time not measured" >&2
  exit 1
fi
data=robots/data
"$build/tools/deepcheck" view --robot "$data/deepcheck_arm/urdf/deepcheck_arm.urdf" \
  --srdf "$data/deepcheck_arm/srdf/deepcheck_arm.srdf" --scene "$data/scenes/shelf.urdf" --package-path "$data" \
  --path tests/viewer/shelf_demo_path.txt --out "$out/demo.html" 2>/dev/null
echo "page,bytes,run,load_ms,frame_ms,build_s,write_s" > "$out/view_bench.csv"
for page in bench demo; do
  i=1
  while [ "$i" -le "$runs" ]; do
    root=$("$browser" --headless --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader \
            --window-size=1280,800 --user-data-dir="$out/profile" --dump-dom "file://$out/$page.html#timing" \
            2>/dev/null | grep -o '<html[^>]*>' | head -n 1)
    load=$(echo "$root" | sed -n 's/.*data-load-ms="\([0-9]*\)".*/\1/p')
    frame=$(echo "$root" | sed -n 's/.*data-frame-ms="\([0-9.]*\)".*/\1/p')
    if [ "$page" = bench ]; then written=$made; else written=","; fi
    echo "$page,$(wc -c < "$out/$page.html"),$i,${load:-failed},${frame:-failed},$written" >> "$out/view_bench.csv"
    i=$((i + 1))
  done
done
cp "$out/view_bench.csv" "$csv"
cat "$csv"
