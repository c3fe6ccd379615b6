#!/usr/bin/env bash
# Installs what is missing, builds, and runs the main job on the default device (PoCL's
# CPU when nothing else is there): renders every bundled render scene (the thesis' four
# test scenes and the spectral sunset) to EXR and PNG, runs the Table 5.2 benchmark
# (what each optimization costs and saves, against the ground truth), traces the curved
# mirage scene and runs the integrators' accuracy-vs-time benchmark, renders the five
# waters of the ocean engine with their profiles, energy plots and benchmark, tabulates
# a rainbow phase function against Mie with the rainbow benchmark, renders the rainbow
# skies and halos with their benchmark and the Dask sweep's, then says where the images
# and tables are.
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

# Underwater light: the five waters of Fig. 5.10, the energy by interaction and by
# constituent (Fig. 5.9, 5.12), sunlit irradiance profiles per water, a profile against
# the independent plane-parallel solution, and the ocean benchmark.
mkdir -p out/ocean
for water in atlantic mediterranean baltic north_sea cdom_coastal; do
  python3 apps/ocean/arcus_ocean.py render "scenes/ocean/$water.json" -o "out/ocean/$water.exr" --png "out/ocean/$water.png"
  python3 apps/ocean/arcus_ocean.py profile "scenes/ocean/profiles/${water}_sun.json" --out "out/ocean/profiles/$water"
done
python3 apps/ocean/arcus_ocean.py trace scenes/ocean/fig5_9.json --out out/ocean/fig5_9
python3 apps/ocean/arcus_ocean.py trace scenes/ocean/fig5_11/baltic_inelastic.json --out out/ocean/fig5_12
python3 apps/ocean/plot_profile_check.py --out out/ocean
python3 bench/ocean_bench.py --out out/bench

# Rainbows: a 500 µm sphere's phase function over 33 wavelengths against Lorenz–Mie and,
# per term, the Debye series; the twinned bow of mixed drop shapes; the benchmark.
mkdir -p out/rainbow
python3 apps/rainbow/arcus_rainbow.py table --particle sphere:500um --wavelengths 380 700 33 \
  --theta 120 145 0.01 --plot out/rainbow/sphere.png --per-bounce -o out/rainbow/sphere
python3 apps/rainbow/plot_twinned.py --out out/rainbow
python3 bench/rainbow_bench.py --out out/bench

# Rainbow skies (Fig. 5.21-5.25) and halos: the phase tables are computed once into the
# sweep's cache (~/.cache/arcus/tables), then every later render reads them.
mkdir -p out/rainbow/sky
python3 data/rainbow/sky/make_storm_sky.py  # storm_sky.json's panorama (generated, not in the repository)
for scene in single_bow double_bow supernumerary supernumerary_200um red_sun cloudbow twinned marshall_palmer \
             halo sundogs storm_sky; do
  python3 apps/rainbow/arcus_rainbow_render.py "scenes/rainbow/$scene.json" -o "out/rainbow/sky/$scene.exr" \
    --png "out/rainbow/sky/$scene.png"
done
python3 bench/sky_bench.py --out out/bench
python3 bench/sweep_bench.py --out out/bench

echo
echo "Rendered scenes:  $(pwd)/out/render/  (<scene>.png, <scene>.exr with distance/steps/tests channels, render.md: Table 5.2)"
echo "Mirage rays:      $(pwd)/out/mirage/  (paths.png, rays.csv, paths.csv, summary.md)"
echo "Integrators:      $(pwd)/out/bench/   (tables .md and .csv, plots .png)"
echo "Underwater light: $(pwd)/out/ocean/   (<water>.png/.exr, fig5_9/ and fig5_12/ plots and tallies.json,"
echo "                  profiles/<water>/profile.png and .csv, profile_check.png/.md: against discrete ordinates)"
echo "Ocean benchmark:  $(pwd)/out/bench/ocean.md  (error against time, per stage, both estimators)"
echo "Rainbows:         $(pwd)/out/rainbow/  (sphere.png: against Mie and per term against Debye, sphere.csv/.npz"
echo "                  over 33 wavelengths, twinned.png: the twinned bow)"
echo "Rainbow benchmark: $(pwd)/out/bench/rainbow.md  (grid and drop size against error and time, the targets)"
echo "Rainbow skies:    $(pwd)/out/rainbow/sky/  (<scene>.png and .exr: the thesis' bows, the cloudbow, the twinned"
echo "                  bow, the 22° halo, sundogs and a bow before a sky image)"
echo "Sky benchmark:    $(pwd)/out/bench/sky.md  (wavelengths, size bins, sun points, march steps against error and"
echo "                  time; the five thesis scenes from cached tables), sweep.md (Dask against a plain loop)"
