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

# Two lanes, one test at a time in each: the physics and reference suites (their kernels
# use both cores) and then the same once more in the layout GPUs get (one ray per
# work-item, no lane groups), which this CPU-only machine would otherwise never run; beside
# them the api and unit suites, which spend their time starting processes, compiling
# kernels and in host code on one core.  Together, with empty kernel caches, they took
# 602 s against 877 s one after another (2 vCPUs).  The one-ray pass leaves out the estimate's suite (its
# histogram kernel has no lanes: one row a work-group; its photos' renders are the render
# suite's) and of the render suite's comparisons of one technique with another (host
# logic on the same kernels, each a fresh compile of ~10 s) keeps the one with all four.
# Each lane's output is shown when both are done.
physics_lane() {
  (cd build && ctest --output-on-failure -L '^(physics|reference)$') > build/ctest-physics.log 2>&1
  echo $? > build/ctest-physics.rc
  (cd build && ARCUS_LANES=1 ARCUS_GROUPS=1 ctest --output-on-failure -L physics \
     -E '^TranslucencyEstimate\.|^Render\.(SmartStepSelectionFindsExactly|APathCached|CachedPaths|Symmetry|Undersampling)') \
    > build/ctest-one-ray.log 2>&1
  echo $? > build/ctest-one-ray.rc
}
rm -f build/ctest-physics.rc build/ctest-one-ray.rc
(cd build && ctest -N > /dev/null)  # the suites' test lists, once, before two ctests read them
physics_lane &
physics_pid=$!
(cd build && ctest --output-on-failure -LE '^(physics|reference)$')
ctest_rc=$?
wait $physics_pid
cat build/ctest-physics.log build/ctest-one-ray.log
physics_rc=$(cat build/ctest-physics.rc 2>/dev/null || echo 1)
scalar_rc=$(cat build/ctest-one-ray.rc 2>/dev/null || echo 1)
[ "$physics_rc" -eq 0 ] || ctest_rc=1
lap ctest
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
