#!/usr/bin/env bash
# Installs what is missing, builds, and runs the main job on the default device (PoCL's
# CPU when nothing else is there): traces the bundled mirage scene and runs the
# accuracy-vs-time benchmark, then says where the images and tables are.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/bootstrap.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j2

build/arcus_trace scenes/mirage.json --out out/mirage
python3 apps/plot_paths.py out/mirage
build/bench/arcus_bench --out out/bench

echo
echo "Mirage scene:  $(pwd)/out/mirage/  (paths.png, rays.csv, paths.csv, summary.md)"
echo "Benchmark:     $(pwd)/out/bench/   (tables .md and .csv, plots .png)"
