#!/usr/bin/env bash
# The "C API linkage" users will do: install arcus into a fresh prefix, build a C
# program against that copy both with find_package(arcus) and with pkg-config, run
# both, and check that libarcus.so exports the C API and nothing else.
set -euo pipefail
build=$1 src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cmake --install "$build" --prefix "$work/prefix" > /dev/null
lib=$(dirname "$(find "$work/prefix" -name 'libarcus.so' | head -n 1)")
export LD_LIBRARY_PATH="$lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"

echo "== find_package(arcus)"
cmake -S "$src/tests/install" -B "$work/cmake" -DCMAKE_PREFIX_PATH="$work/prefix" > /dev/null
cmake --build "$work/cmake" > /dev/null
"$work/cmake/consumer"

echo "== pkg-config arcus"
export PKG_CONFIG_PATH="$lib/pkgconfig"
cc -std=c99 -Wall -Werror "$src/tests/install/consumer.c" $(pkg-config --cflags --libs arcus) -lm -o "$work/consumer_pc"
"$work/consumer_pc"

echo "== exported symbols"
others=$(nm -D --defined-only "$lib/libarcus.so" | awk '{print $3}' | grep -v '^arcus_' || true)
if [ -n "$others" ]; then
  echo "libarcus.so exports symbols outside the C API:"; echo "$others" | head; exit 1
fi
echo "only arcus_* symbols exported ($(nm -D --defined-only "$lib/libarcus.so" | grep -c ' arcus_'))"
