#!/usr/bin/env bash
# `pip install .` as a new user does it: into a new virtual environment, then from a
# folder outside the repository `arcus` must be on PATH, say its version and render a
# bundled scene by name.  The venv sees the system's packages (numpy, ...; bootstrap.sh
# installed them) so that nothing but arcus is fetched; the build reuses build/wheel.
set -euo pipefail
src=$(cd "$(dirname "$0")/../.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
start=$SECONDS
"${PYTHON:-python3}" -m venv --system-site-packages "$work/venv"
# The benchmarks stay out of this wheel (the quick start's has them): they add a minute
# of compiling and nothing to what is tested here.
"$work/venv/bin/pip" install -q --disable-pip-version-check --no-build-isolation \
  --config-settings=cmake.define.ARCUS_BUILD_BENCH=OFF "$src"
echo "pip install .: $((SECONDS - start)) s"
cd "$work"
export PATH="$work/venv/bin:$PATH"
[ "$(command -v arcus)" = "$work/venv/bin/arcus" ] || { echo "arcus is not on PATH"; exit 1; }
# The version is written once, in the header.
header=$(sed -n 's/^#define ARCUS_VERSION_\(MAJOR\|MINOR\|PATCH\) \([0-9]*\)$/\2/p' \
           "$src/include/arcus/arcus_core.h" | paste -sd.)
version=$(arcus --version)
[ "$version" = "arcus $header" ] || { echo "arcus --version says '$version', the header $header"; exit 1; }
arcus render inferior_mirage -o m.png --quiet
arcus info > /dev/null
# The installed package loads its own library, not the source tree's build.
python3 -c 'import arcus, sys; sys.exit(0 if "/venv/" in arcus.library_path else "loaded " + arcus.library_path)'
[ -s m.png ] && echo "pip install test: $version renders from $work ($((SECONDS - start)) s)"
