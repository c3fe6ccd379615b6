#!/usr/bin/env bash
# Fuzzes the readers of untrusted files with libFuzzer: scene files (src/scene/json_reader,
# src/curved/scene_desc), images (src/image/image_io over OpenImageIO) and meshes
# (src/geometry: the scan, then OpenMesh).
#
#   tests/fuzz/run_fuzz.sh [SECONDS] [TARGET...]     (default 60 s each; scene image mesh)
#
# For each target (fuzz_TARGET.cpp, inputs in tests/fuzz/TARGET/):
# 1. builds build-fuzz/fuzz_TARGET with clang++ -fsanitize=fuzzer,address,undefined;
# 2. replays every file of TARGET/regressions/ (inputs that once crashed, hung or were
#    misread): a failure there stops the script;
# 3. fuzzes for SECONDS from a temporary corpus seeded with TARGET/seeds/ (images and
#    meshes: small files of every format, written by make_seeds.py) and the regressions
#    (with TARGET/TARGET.dict if there is one).
# Exits non-zero on any finding; libFuzzer saves the input as
# build-fuzz/artifacts/TARGET-crash-* (or leak-*, timeout-*, oom-*): fix the bug, then add
# the input to TARGET/regressions/.  Image and mesh inputs start with one byte that picks
# the file's extension (fuzz_image.cpp, fuzz_mesh.cpp).
# Environment: CXX (default clang++-14, else clang++), ARCUS_FUZZ_BUILD (build-fuzz).
set -euo pipefail

root=$(cd "$(dirname "$0")/../.." && pwd)
seconds=${1:-60}
shift || true
targets=("$@")
((${#targets[@]})) || targets=(scene image mesh)
build=${ARCUS_FUZZ_BUILD:-$root/build-fuzz}
if [[ -z ${CXX:-} ]]; then
  if command -v clang++-14 >/dev/null; then CXX=clang++-14; else CXX=clang++; fi
fi
mkdir -p "$build/artifacts"
# Leaks are findings, but for the third-party ones listed there (each with its reason).
export LSAN_OPTIONS="suppressions=$root/tests/sanitizers/lsan.supp:print_suppressions=0"
# Whole stacks for every allocation: the suppressions name frames inside uninstrumented
# libraries (OpenImageIO), which the fast unwinder does not reach.
export ASAN_OPTIONS="fast_unwind_on_malloc=0${ASAN_OPTIONS:+:$ASAN_OPTIONS}"

status=0
for target in "${targets[@]}"; do
  bin=$build/fuzz_$target
  data=$root/tests/fuzz/$target
  # The library's sources the target needs (beside the file reader every one uses), and
  # what it links.
  case $target in
    scene) sources=(src/scene/json_reader.cpp src/scene/common_keys.cpp src/curved/scene_desc.cpp src/curved/params.cpp
                    src/sky/atmosphere.cpp src/sky/paths.cpp src/sky/rayleigh.cpp src/sky/us1976.cpp)
           libs=() ;;
    image) sources=(src/image/image_io.cpp src/spectral/srgb.cpp src/spectral/cie.cpp)
           read -r -a libs <<< "$(pkg-config --libs OpenImageIO)" ;;
    mesh) sources=(src/geometry/mesh.cpp src/geometry/mesh_scan.cpp) libs=(-lOpenMeshCore) ;;
    *) echo "run_fuzz: no target '$target' (scene, image, mesh)" >&2; exit 2 ;;
  esac
  sources+=(src/core/files.cpp src/core/limits.cpp)
  echo "run_fuzz: building $bin with $CXX"
  # -fno-sanitize-recover: a UBSan report must stop the run, or libFuzzer never sees it.
  "$CXX" -std=c++17 -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all \
    -I"$root/src" -I"$root/include" -I"$root/kernels" "$root/tests/fuzz/fuzz_$target.cpp" "${sources[@]/#/$root/}" "${libs[@]}" \
    -o "$bin"

  shopt -s nullglob
  regressions=("$data"/regressions/*)
  if ((${#regressions[@]})); then
    echo "run_fuzz: $target: replaying ${#regressions[@]} regression inputs"
    "$bin" -timeout=10 -rss_limit_mb=2048 "${regressions[@]}" >"$build/replay-$target.log" 2>&1 || {
      tail -n 40 "$build/replay-$target.log"
      echo "run_fuzz: $target: a regression input fails again (log: $build/replay-$target.log)" >&2
      exit 1
    }
  fi

  corpus=$(mktemp -d "${TMPDIR:-/tmp}/arcus_fuzz_$target.XXXXXX")
  for f in "$data"/seeds/*; do cp "$f" "$corpus/seed_$(basename "$f")"; done
  [[ $target == scene ]] || python3 "$root/tests/fuzz/make_seeds.py" "$target" "$corpus"
  for f in "${regressions[@]}"; do cp "$f" "$corpus/regression_$(basename "$f")"; done
  [[ $target == scene ]] && cp "$root"/scenes/*.json "$corpus/"
  dict=()
  [[ -f $data/$target.dict ]] && dict=(-dict="$data/$target.dict")

  echo "run_fuzz: $target: fuzzing for ${seconds}s"
  rc=0
  "$bin" "$corpus" "${dict[@]}" -max_total_time="$seconds" -max_len=8192 -timeout=10 -rss_limit_mb=2048 \
    -print_final_stats=1 -artifact_prefix="$build/artifacts/$target-" || rc=$?
  rm -rf "$corpus"
  if ((rc != 0)); then
    echo "run_fuzz: $target: finding (exit $rc); the input is in $build/artifacts/:" >&2
    ls -t "$build/artifacts/" | head -n 5 >&2
    status=1
  fi
done
((status == 0)) && echo "run_fuzz: no finding"
exit $status
