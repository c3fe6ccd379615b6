#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test: the ctest suites (C/C++), the
# physics suite again in the one-ray-per-work-item layout GPUs get, the pytest suite (with
# the arcus command, the gallery in a headless browser and every example of the README
# and docs), `pip install .` into a new virtual environment, then the suites again under
# AddressSanitizer + UndefinedBehaviorSanitizer, and the fuzzers of the scene, image and
# mesh readers for 20 s each.  Exits non-zero when anything fails.  CI runs this.
set -uo pipefail
cd "$(dirname "$0")/.."
start=$SECONDS
stages=""  # "name seconds" of each stage, printed at the end (CI's budget is 40 minutes)
mark=$SECONDS
lap() { stages="$stages $1 $((SECONDS - mark)) s,"; mark=$SECONDS; }
bash scripts/bootstrap.sh --test || exit 1
lap bootstrap
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null || exit 1
cmake --build build -j2 || exit 1
lap build

# PoCL uses every core for each kernel, so the suites run one test at a time.
(cd build && ctest --output-on-failure)
ctest_rc=$?
lap ctest
# Once more in the layout GPUs get (one ray per work-item, no lane groups), which this
# CPU-only machine would otherwise never run.  Not the estimate's suite: its histogram
# kernel has no lanes (one row a work-group), and its photos' renders are the render suite's.
# Of the render suite's comparisons of one technique with another (host logic on the
# same kernels, each a fresh compile of ~10 s) only the one with all four stays.
(cd build && ARCUS_LANES=1 ARCUS_GROUPS=1 ctest --output-on-failure -L physics \
   -E '^TranslucencyEstimate\.|^Render\.(SmartStepSelectionFindsExactly|APathCached|CachedPaths|Symmetry|Undersampling)')
scalar_rc=$?
lap ctest-one-ray
python3 -m pytest -q --durations=30 tests/python  # the slowest 30: where CI's time goes
pytest_rc=$?
lap pytest
# `pip install .` into a new virtual environment; `arcus` from a folder outside the tree.
bash tests/install/pip_install_test.sh
pip_rc=$?
lap pip-install
# The library, its tests and pytest against it, built with ASan + UBSan: any report fails.
bash scripts/sanitize.sh
sanitize_rc=$?
lap sanitizers
# libFuzzer on the readers of untrusted files (scenes, images, meshes): the regression
# inputs, then 20 s of fuzzing each (longer runs: docs/testing.md).
bash tests/fuzz/run_fuzz.sh 20
fuzz_rc=$?
lap fuzzers
echo "stages:${stages%,}"
echo "ctest exit $ctest_rc, ctest (one ray per work-item) exit $scalar_rc, pytest exit $pytest_rc," \
     "pip install exit $pip_rc, sanitizers exit $sanitize_rc, fuzzer exit $fuzz_rc; $((SECONDS - start)) s in all"
[ $ctest_rc -eq 0 ] && [ $scalar_rc -eq 0 ] && [ $pytest_rc -eq 0 ] && [ $pip_rc -eq 0 ] && [ $sanitize_rc -eq 0 ] &&
  [ $fuzz_rc -eq 0 ]
