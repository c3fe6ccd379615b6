#!/usr/bin/env bash
# Installs every system and Python dependency arcus needs; idempotent (a second run
# installs nothing and takes a few seconds).  Debian 12 packages + PyPI only.
# `--test` adds what only the tests use: Mitsuba 3, an external reference for the
# translucency engine (tests/python/mitsuba_slab.py), and pvlib, whose SPCTRAL2 checks
# the shared sun (tests/python/test_daylight.py).
set -euo pipefail
test_deps=0
[ "${1:-}" = "--test" ] && test_deps=1

debs=(
  build-essential cmake pkg-config git
  pocl-opencl-icd ocl-icd-opencl-dev ocl-icd-libopencl1 opencl-c-headers opencl-clhpp-headers clinfo
  libembree-dev libopenimageio-dev libopenmesh-dev libglfw3-dev nlohmann-json3-dev
  libopencv-core-dev libopencv-imgproc-dev
  xvfb xauth libgl1-mesa-dri chromium python3-venv
  libgtest-dev googletest libboost-dev
  clang-14 libclang-rt-14-dev
)
missing=()
for p in "${debs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "bootstrap: installing Debian packages: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

PY=${PYTHON:-python3}
if ! "$PY" -c 'import numpy, scipy, pytest, matplotlib, tqdm, dask.distributed, scikit_build_core' 2>/dev/null; then
  echo "bootstrap: installing Python packages from PyPI (numpy scipy pytest matplotlib tqdm dask[distributed] scikit-build-core)"
  if ! "$PY" -m pip --version > /dev/null 2>&1; then
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends python3-pip
  fi
  pip_install=("$PY" -m pip install -q --disable-pip-version-check numpy scipy pytest matplotlib tqdm "dask[distributed]" scikit-build-core)
  # Debian's own python3 refuses pip installs into it (PEP 668) unless told otherwise.
  "${pip_install[@]}" 2> /dev/null || "${pip_install[@]}" --break-system-packages
fi
if [ $test_deps -eq 1 ] && ! "$PY" -c 'import mitsuba, pvlib' 2>/dev/null; then
  echo "bootstrap: installing the tests' Python references from PyPI (mitsuba pvlib)"
  pip_install=("$PY" -m pip install -q --disable-pip-version-check mitsuba pvlib)
  "${pip_install[@]}" 2> /dev/null || "${pip_install[@]}" --break-system-packages
fi
echo "bootstrap: all dependencies present"
