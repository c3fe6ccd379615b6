#!/usr/bin/env bash
# Builds arcus with AddressSanitizer + UndefinedBehaviorSanitizer into build-asan/ and runs
# the ctest and pytest suites against that build.  Exits non-zero on a build failure, a
# failed test or any sanitizer report.  Re-running rebuilds incrementally.
# Logs: build-asan/logs/.  Needs what scripts/bootstrap.sh installs.
set -uo pipefail
cd "$(dirname "$0")/.."
root=$PWD
build=$root/build-asan
logs=$build/logs
mkdir -p "$logs"

# ---- build.  Flags on the command line, so CMakeLists.txt and build/ stay untouched.
san="-fsanitize=address,undefined -fno-omit-frame-pointer"
# -O1, as AddressSanitizer's documentation advises, and -g1: line tables for the reports
# without the full debug information, which halves the build (json_reader.cpp: 34 s at
# -O2 -g, 14 s at -O1 -g1) that was half of CI's time.
# The test-only null engine is built here (and only here): its suite proves that an engine
# plugs in alone (docs/adding-an-engine.md).
# The physics and reference suites, which this script does not run (below), are not built.
t0=$SECONDS
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" \
  -DARCUS_BUILD_TESTS=ON -DARCUS_BUILD_PHYSICS_TESTS=OFF -DARCUS_BUILD_BENCH=OFF -DARCUS_BUILD_APPS=ON \
  -DARCUS_WITH_NULL_ENGINE=ON \
  "-DCMAKE_C_FLAGS=$san" "-DCMAKE_CXX_FLAGS=$san" \
  "-DCMAKE_EXE_LINKER_FLAGS=$san" "-DCMAKE_SHARED_LINKER_FLAGS=$san" \
  > "$logs/configure.log" 2>&1 || { cat "$logs/configure.log"; echo "sanitize: configure failed"; exit 1; }
cmake --build "$build" -j2 > "$logs/build.log" 2>&1 \
  || { tail -n 40 "$logs/build.log"; echo "sanitize: build failed; log: $logs/build.log"; exit 1; }
build_s=$((SECONDS - t0))

# Uninstrumented programs (python, and the installed-library consumer) must load the ASan
# runtime first; python needs libstdc++ preloaded too, or ASan's __cxa_throw interceptor
# finds nothing to forward to and the first C++ exception in libarcus aborts.
cxx=$(sed -n 's/^CMAKE_CXX_COMPILER:[A-Z]*=//p' "$build/CMakeCache.txt")
preload=""
for name in libasan.so libstdc++.so; do
  file=$("$cxx" -print-file-name=$name)
  [ -f "$file" ] || { echo "sanitize: $cxx cannot find $name"; exit 1; }
  preload="$preload${preload:+:}$(realpath "$file")"
done

# Every report is fatal.  UBSan halts by run-time option rather than -fno-sanitize-recover,
# so that a hand run with UBSAN_OPTIONS=halt_on_error=0 lists all reports at once.
# use_sigaltstack=0: LLVM, inside PoCL's kernel compiler, replaces the alternate signal
# stack of a thread that compiles a kernel with one from malloc when ASan's is smaller
# than SIGSTKSZ + 64 KiB (ASan's is 4 x SIGSTKSZ: too small on CPUs without AMX, whose
# SIGSTKSZ is small); ASan then fails to unmap it when the thread exits ("CHECK failed:
# ... "unable to unmap""), killing every such thread.  Without its own alternate stack
# ASan leaves the thread's alone; what it loses is the report of a stack overflow, which
# still kills the process (SIGSEGV), so the test still fails.  Regression test:
# Threads.AThreadWhoseSignalStackTheKernelCompilerReplacedExitsCleanly.
asan="halt_on_error=1:detect_stack_use_after_return=1:check_initialization_order=1:strict_init_order=1"
asan="$asan:use_sigaltstack=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:report_error_type=1"
export LSAN_OPTIONS="suppressions=$root/tests/sanitizers/lsan.supp:print_suppressions=0"
# A report from a child whose exit status nobody checked still fails the run.
reports() { grep -HnE "ERROR: (AddressSanitizer|LeakSanitizer)|SUMMARY: UndefinedBehaviorSanitizer|: runtime error: " "$@"; }

# ---- ctest: instrumented programs, leak detection on.  The api and unit suites: the
# physics suites spend their time in kernels, which are not instrumented, make the calls
# the api suites make, and run twice uninstrumented already (scripts/test.sh); CI's 40
# minutes are the limit.  One test at a time, but beside the pytest run below: both
# spend their time in instrumented host code on one core each (a test's kernels are
# small), so on two cores the two together take about as long as the longer alone.
# Output goes to the logs and is shown when both are done.
ctest_stage() {
  local t0=$SECONDS rc install_rc
  (cd "$build" && ASAN_OPTIONS="$asan:detect_leaks=1" \
    ctest -j1 --output-on-failure -LE '^(physics|reference)$' -E '^c_api_linkage_installed$') > "$logs/ctest.log" 2>&1
  rc=$?
  cp "$build/Testing/Temporary/LastTest.log" "$logs/ctest-full.log" 2>/dev/null  # every test's output
  # c_api_linkage_installed builds an uninstrumented C consumer against the installed
  # sanitized library: the runtime is preloaded, for cmake, cc and nm too, so leak
  # detection is off (those tools do not free at exit; the consumer makes c_api_dump's
  # calls, checked above).
  (cd "$build" && LD_PRELOAD="$preload" ASAN_OPTIONS="$asan:detect_leaks=0" \
    ctest --output-on-failure -R '^c_api_linkage_installed$') > "$logs/ctest-install.log" 2>&1
  install_rc=$?
  cat "$build/Testing/Temporary/LastTest.log" >> "$logs/ctest-full.log" 2>/dev/null
  if reports "$logs/ctest-full.log"; then [ $rc -ne 0 ] || rc=1; fi
  echo "$rc $install_rc $((SECONDS - t0))" > "$logs/ctest.status"
}
rm -f "$logs/ctest.status"
ctest_stage &
ctest_pid=$!

# ---- pytest against the sanitized library.  Leak detection off: CPython keeps pointers
# to malloc'd objects in mmap'd pymalloc arenas that LSan does not scan, so live
# interpreter objects are reported as leaks, and the preload reaches the pyenv shim and
# the tests' cc runs too; arcus's own leaks are the ctest run's job.  --capture=sys: a
# sanitizer writes to fd 2 and exits, which pytest's default fd capture would swallow.
# The end-to-end tests (the command, the gallery, the docs' examples) repeat in
# subprocesses library calls the suites already make, at several times their plain cost
# under the sanitizer: they run in the plain pass only, as do the full-size reproductions
# of thesis tables (marker full_size: Table 3.3, Table 5.1's five seeds) and the heavy
# physics checks (marker heavy: their calls run instrumented in the modules' other tests).
t0=$SECONDS
LD_PRELOAD="$preload" ASAN_OPTIONS="$asan:detect_leaks=0" ARCUS_LIBRARY="$build/libarcus.so" \
  python3 -m pytest -v --durations=15 --capture=sys -p no:cacheprovider -m "not end_to_end and not external_reference and not full_size and not heavy" tests/python 2>&1 | tee "$logs/pytest.log"
pytest_rc=$?
pytest_s=$((SECONDS - t0))
if reports "$logs/pytest.log"; then [ $pytest_rc -ne 0 ] || pytest_rc=1; fi

wait $ctest_pid
cat "$logs/ctest.log" "$logs/ctest-install.log"
read -r ctest_rc install_rc ctest_s < "$logs/ctest.status" 2>/dev/null || { ctest_rc=1; install_rc=1; ctest_s=0; }

echo "sanitize: build ${build_s}s, ctest ${ctest_s}s (exit $ctest_rc; install test exit $install_rc)," \
     "pytest ${pytest_s}s (exit $pytest_rc).  Logs: $logs (ctest-full.log: every test's output)"
[ $ctest_rc -eq 0 ] && [ $install_rc -eq 0 ] && [ $pytest_rc -eq 0 ]
