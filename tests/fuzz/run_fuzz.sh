#!/usr/bin/env bash
# Fuzzes the scene reader (src/scene/json_reader, src/curved/scene_desc) with libFuzzer.
#
#   tests/fuzz/run_fuzz.sh [SECONDS]        (default 60)
#
# 1. builds build-fuzz/fuzz_scene with clang++ -fsanitize=fuzzer,address,undefined;
# 2. replays every file of tests/fuzz/regressions/ (inputs that once crashed): a failure
#    there stops the script;
# 3. fuzzes for SECONDS from a temporary corpus seeded with scenes/*.json, seeds/ (the
#    forms the bundled scenes lack) and the regressions, with the schema's dictionary.
# Exits non-zero on any finding; libFuzzer saves the input as
# build-fuzz/artifacts/crash-* (or leak-*, timeout-*, oom-*): fix the bug, then add the
# input to tests/fuzz/regressions/.
# Environment: CXX (default clang++-14, else clang++), ARCUS_FUZZ_BUILD (build-fuzz).
set -euo pipefail

root=$(cd "$(dirname "$0")/../.." && pwd)
seconds=${1:-60}
build=${ARCUS_FUZZ_BUILD:-$root/build-fuzz}
if [[ -z ${CXX:-} ]]; then
  if command -v clang++-14 >/dev/null; then CXX=clang++-14; else CXX=clang++; fi
fi

mkdir -p "$build/artifacts"
bin=$build/fuzz_scene
echo "run_fuzz: building $bin with $CXX"
# -fno-sanitize-recover: a UBSan report must stop the run, or libFuzzer never sees it.
"$CXX" -std=c++17 -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all \
  -I"$root/src" -I"$root/include" \
  "$root/tests/fuzz/fuzz_scene.cpp" "$root/src/scene/json_reader.cpp" "$root/src/curved/scene_desc.cpp" \
  "$root/src/curved/params.cpp" "$root/src/core/files.cpp" "$root/src/core/limits.cpp" \
  -o "$bin"

shopt -s nullglob
regressions=("$root"/tests/fuzz/regressions/*)
if ((${#regressions[@]})); then
  echo "run_fuzz: replaying ${#regressions[@]} regression inputs"
  "$bin" -timeout=10 -rss_limit_mb=2048 "${regressions[@]}" >"$build/replay.log" 2>&1 || {
    tail -n 40 "$build/replay.log"
    echo "run_fuzz: a regression input fails again (log: $build/replay.log)" >&2
    exit 1
  }
fi

corpus=$(mktemp -d "${TMPDIR:-/tmp}/arcus_fuzz_corpus.XXXXXX")
trap 'rm -rf "$corpus"' EXIT
cp "$root"/scenes/*.json "$corpus/"
for f in "$root"/tests/fuzz/seeds/*; do cp "$f" "$corpus/seed_$(basename "$f")"; done
for f in "${regressions[@]}"; do cp "$f" "$corpus/regression_$(basename "$f")"; done

echo "run_fuzz: fuzzing for ${seconds}s"
status=0
"$bin" "$corpus" -dict="$root/tests/fuzz/scene.dict" -max_total_time="$seconds" -max_len=8192 \
  -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$build/artifacts/" || status=$?
if ((status != 0)); then
  echo "run_fuzz: finding (exit $status); the input is in $build/artifacts/:" >&2
  ls -t "$build/artifacts/" | head -n 5 >&2
  exit 1
fi
echo "run_fuzz: no finding"
