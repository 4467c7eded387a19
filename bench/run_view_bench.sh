#!/bin/sh
# Size and load time of the viewer's page for a 20-variable robot with 500 pieces along a
# 1,000-waypoint path (bench/view_bench.cpp writes it). The load time is the page's own
# data-load-ms: milliseconds from navigation start until the first image is drawn, in headless
# Chromium with software WebGL (SwiftShader), read with --dump-dom; RUNS loads, each printed.
#   bench/run_view_bench.sh BUILD_DIR [RUNS]
set -eu
build=${1:?usage: run_view_bench.sh BUILD_DIR [RUNS]}
runs=${2:-5}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$build/bench/view_bench" "$out/bench.html"
browser=$(command -v chromium || command -v chromium-headless-shell || true)
if [ -z "$browser" ]; then
  echo "no Chromium: load time not measured" >&2
  exit 1
fi
echo "run load_ms"
i=1
while [ "$i" -le "$runs" ]; do
  ms=$("$browser" --headless --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader \
        --window-size=1280,800 --user-data-dir="$out/profile" --dump-dom "file://$out/bench.html" 2>/dev/null |
       sed -n 's/.*data-load-ms="\([0-9]*\)".*/\1/p' | head -n 1)
  echo "$i ${ms:-failed}"
  i=$((i + 1))
done
