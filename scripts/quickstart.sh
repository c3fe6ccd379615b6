#!/usr/bin/env bash
# Installs what is missing, builds, and runs the main job on the default device (PoCL's
# CPU when nothing else is there): renders every bundled render scene (the thesis' four
# test scenes and the spectral sunset) to EXR and PNG, runs the Table 5.2 benchmark
# (what each optimization costs and saves, against the ground truth), traces the curved
# mirage scene and runs the integrators' accuracy-vs-time benchmark, then says where the
# images and tables are.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/bootstrap.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j2

mkdir -p out/render
for scene in inferior_mirage novaya_zemlya fata_morgana cross_room sunset_spectral; do
  build/arcus_render "scenes/$scene.json" -o "out/render/$scene.exr" --png "out/render/$scene.png"
done
build/bench/arcus_bench_render --out out/render/render.md
build/arcus_trace scenes/mirage.json --out out/mirage
python3 apps/plot_paths.py out/mirage
build/bench/arcus_bench --out out/bench

echo
echo "Rendered scenes:  $(pwd)/out/render/  (<scene>.png, <scene>.exr with distance/steps/tests channels, render.md: Table 5.2)"
echo "Mirage rays:      $(pwd)/out/mirage/  (paths.png, rays.csv, paths.csv, summary.md)"
echo "Integrators:      $(pwd)/out/bench/   (tables .md and .csv, plots .png)"
