#!/usr/bin/env bash
# arcus_view's screenshot of a small render scene, taken in a real (Xvfb) window, must
# be arcus_render's PNG of the same scene.
#   tests/view/test_view.sh BUILD_DIR SOURCE_DIR
# Exit 77 (ctest: skipped) only when xvfb-run is missing.
set -euo pipefail

build=$(cd "$1" && pwd)
source=$(cd "$2" && pwd)
if ! command -v xvfb-run > /dev/null; then
  echo "xvfb-run not found: skipped (scripts/bootstrap.sh installs xvfb)"
  exit 77
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# The inferior mirage at 160x80 (fast on a CPU), its mesh's and texture's paths made
# absolute since the scene now lives in the temporary directory.
python3 - "$source/scenes/inferior_mirage.json" "$work/scene.json" <<'EOF'
import json, os, sys
src, dst = sys.argv[1], sys.argv[2]
scene = json.load(open(src))
scene["name"] = "view_test"
scene["camera"]["width"], scene["camera"]["height"] = 160, 80
here = os.path.dirname(os.path.abspath(src))
for entry, key in [(o, "file") for o in scene["objects"]] + [(m, "texture") for m in scene["materials"].values()]:
    if key in entry:
        entry[key] = os.path.normpath(os.path.join(here, entry[key]))
json.dump(scene, open(dst, "w"), indent=2)
EOF

# Both render two frames with the camera at rest (the second predicts its hit steps
# from the first), so they run the same frames.
"$build/arcus_render" "$work/scene.json" -o "$work/render.exr" --png "$work/render.png" --frames 2 --quiet
# Under the sanitizers (scripts/sanitize.sh) the X and GL libraries the window needs
# leave a few blocks at exit that LeakSanitizer cannot attribute (their stacks end in
# its own allocator); the library's own leaks are checked by every other test, so leak
# detection is off for this one process only.
ASAN_OPTIONS="${ASAN_OPTIONS:-}${ASAN_OPTIONS:+:}detect_leaks=0" xvfb-run -a -s "-screen 0 1280x1024x24" \
  "$build/arcus_view" "$work/scene.json" --frames 2 --screenshot "$work/view.png"

# Tolerance: both PNGs are the same float image rounded by the same sRGB transfer
# function, and Mesa's glDrawPixels of RGB8 into a 24-bit window at 1:1 is exact, so
# they should agree byte for byte; 1/255 on 99.9 % of the pixels leaves room only for a
# last-bit difference in pow() between builds, never for a shifted, flipped, scaled or
# re-encoded image.
python3 - "$work/render.png" "$work/view.png" <<'EOF'
import sys
import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.image as mpimg

def load(path):
    img = mpimg.imread(path)  # PNG: floats in [0, 1]
    return np.rint(img[..., :3] * 255).astype(int)

render, view = load(sys.argv[1]), load(sys.argv[2])
assert render.shape == view.shape == (80, 160, 3), f"shapes: render {render.shape}, view {view.shape}"
# Not blank (nor one flat colour): sky, ground and the shaded tower give a few dozen
# colours (flat shading: 26 at this size).
colours = len(np.unique(view.reshape(-1, 3), axis=0))
assert colours >= 10 and view.std() > 10, f"the screenshot looks blank: {colours} colours, std {view.std():.1f}"
diff = np.abs(render - view).max(axis=2)
close = (diff <= 1).mean()
print(f"screenshot vs arcus_render: {100 * close:.3f} % of pixels within 1/255, "
      f"{100 * (diff == 0).mean():.3f} % equal, largest difference {diff.max()}/255; {colours} colours")
assert close >= 0.999, "the screenshot differs from arcus_render's PNG"
EOF
echo "arcus_view screenshot matches arcus_render"
