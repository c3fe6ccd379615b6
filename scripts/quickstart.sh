#!/usr/bin/env bash
# The main job: installs what is missing (scripts/bootstrap.sh), builds and installs
# arcus with `pip install .` (libarcus, the Python package, the C++ tools, the bundled
# scenes, and the `arcus` command on PATH), then runs `arcus gallery`: every engine's
# showcase at gallery settings on one page, out/index.html, whose path it prints.
# `arcus gallery --full` renders at the scenes' own settings (docs/cli.md).
set -euo pipefail
cd "$(dirname "$0")/.."
start=$SECONDS
bash scripts/bootstrap.sh
PY=${PYTHON:-python3}
install=("$PY" -m pip install -q --disable-pip-version-check .)
# Debian's own python3 refuses pip installs into it (PEP 668) unless told otherwise.
"${install[@]}" 2> /dev/null || "${install[@]}" --break-system-packages
echo "quickstart: installed $("$PY" -m arcus.cli --version) ($((SECONDS - start)) s so far); the arcus command:" \
     "$(command -v arcus || echo "$PY -m arcus.cli")"
"$PY" -m arcus.cli gallery --out out
echo "quickstart: done in $((SECONDS - start)) s"
