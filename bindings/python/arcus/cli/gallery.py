"""arcus gallery: every engine's showcase on one self-contained page, out/index.html.

Each step is one run of the arcus command (or of an app it ships) at gallery settings
— a preview that still shows the effect — two at a time, since the slowest part on a
CPU is compiling each scene's kernels, which takes one core.  ``--full`` renders at the
scenes' own settings and adds the full benchmarks (about an hour on two cores).
"""

import concurrent.futures
import os
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

from .._scene_file import read
from ..progress import Progress
from . import page, resources


@dataclass
class Step:
    section: str
    title: str
    caption: str           # what it shows, and which thesis figure it reproduces
    argv: list             # arguments of the arcus command, or [app.py, ...] of a shipped app
    out: str               # the folder (under the gallery's) its pictures and tables go to
    docs_image: str = ""   # the picture that stands for the engine in the README (--docs)
    pictures: list = field(default_factory=list)  # what the page shows, if not every PNG of `out`
    expected_seconds: float = 5.0  # with empty caches on two cores: the longest start first
    seconds: float = 0.0
    failed: str = ""


# (scene, title, the thesis figure it reproduces); the caption is the scene's own
# description, which says what it shows.
RENDER_SCENES = [
    ("inferior_mirage", "Inferior mirage", "Thesis Fig. 5.14(a)."),
    ("novaya_zemlya", "Novaya Zemlya effect", "Thesis Fig. 5.14(b)."),
    ("fata_morgana", "Fata Morgana", "Thesis Fig. 5.14(c)."),
    ("cross_room", "Curved photon mapping", "Thesis Fig. 5.14(d)."),
    ("sunset_spectral", "Spectral sunset", "Beyond the thesis' figures (§2.2)."),
]
MIRAGES = ("inferior_mirage", "novaya_zemlya", "fata_morgana")
WATERS = ["atlantic", "mediterranean", "baltic", "north_sea", "cdom_coastal"]
SKIES = [
    ("double_bow", "Primary and secondary bows"),
    ("supernumerary", "Supernumerary bows"),
    ("red_sun", "Red sunset bow"),
    ("cloudbow", "Cloudbow"),
    ("twinned", "Twinned bow"),
    ("halo", "22° halo"),
    ("sundogs", "Sundogs"),
]

BENCH_STEPS = [
    ("curved", "Curved light: error against time",
     "Thesis §5.4.1, Fig. 5.13: the integrators (Euler, RK2, RK4, Dormand–Prince 5(4)) in double and float, "
     "error at the end of a ray against time, beside Boost.Odeint and a native RK4 (docs/benchmarks.md)."),
    ("render", "Rendering: what each optimization costs and saves",
     "Thesis §5.4.2.2, Table 5.2: smart step selection, symmetry, undersampling and the path cache on the "
     "inferior mirage, time against the hit-point error from the exhaustive ground truth."),
    ("ocean", "Underwater light: error against time",
     "Thesis §5.3: photon counts, radiance estimates and estimators (per step, beam) against a converged "
     "reference."),
    ("rainbow", "Rainbows: cast grid against error and time",
     "Thesis §4.4: the ray-cast phase function of a drop against Lorenz–Mie as the grid grows."),
    ("sky", "Rainbow skies: settings against error and time",
     "Thesis §5.5.2: wavelengths, drop-size bins, sun points and march steps against a fine reference."),
    ("translucency", "Translucency: basis, resolution and search against error and time",
     "Thesis Table 3.2 and §5.1: the estimate's resolution, basis count and family, and the genetic search's "
     "population and generations, against recovery error and time per stage."),
]


def description(scene):
    """A bundled scene's own description: what it shows, and the thesis figure."""
    return read(resources.scene(scene), ("render", "ocean", "rainbow", "curved"))[1].get("description", "")


def steps(full):
    size = [] if full else ["--width", "400", "--height", "200"]
    s = []
    for name, title, figure in RENDER_SCENES:
        square = [] if full else ["--width", "200", "--height", "200"]
        dims = square if name in ("novaya_zemlya", "cross_room") else size
        # the mirages beside their rays (arcus.mirage_profile): the fan with and without the inversions
        fan = ["--profile", "{out}/%s_rays.png" % name] if name in MIRAGES else []
        s.append(Step("Curved light and rendering through it", title, figure + " " + description(name),
                      ["render", name, "-o", "{out}/%s.png" % name, "--quiet"] + dims + fan, "render",
                      docs_image="render/inferior_mirage.png" if name == "inferior_mirage" else "",
                      expected_seconds=35.0))
    s.append(Step("Curved light and rendering through it", "Ray paths of a mirage",
                  "Thesis §5.4.1: the rays of scenes/mirage.json, integrated with Dormand–Prince 5(4). "
                  + description("mirage"),
                  ["trace", "mirage", "--out", "{out}", "--quiet"], "mirage",
                  docs_image="mirage/paths.png", pictures=["paths.png"]))
    quick_water = [] if full else ["--width", "256", "--height", "192", "--photons", "1000000"]
    for w in WATERS:
        s.append(Step("Underwater light", "%s water" % w.replace("_", " ").title(), description("ocean/" + w),
                      ["render", "ocean/" + w, "-o", "{out}/%s.png" % w, "--quiet"] + quick_water, "ocean",
                      docs_image="ocean/mediterranean.png" if w == "mediterranean" else ""))
        s.append(Step("Underwater light", "%s water in daylight" % w.replace("_", " ").title(),
                      description("ocean/sunlit/" + w),
                      ["render", "ocean/sunlit/" + w, "-o", "{out}/sunlit_%s.png" % w, "--quiet"] + quick_water,
                      "ocean"))
        # beside it the same water's vertical profile under the sun and a sky, and its reference
        s.append(Step("Underwater light", "%s water under the sun: depth profiles" % w.replace("_", " ").title(),
                      description("ocean/profiles/%s_sun" % w) + " Photons (markers) beside discrete ordinates "
                      "with elastic scattering only (lines): where the photons rise above the lines is Raman "
                      "and fluorescence light.",
                      ["ocean", "profile", "ocean/profiles/%s_sun" % w, "--out", "{out}", "--quiet"]
                      + ([] if full else ["--photons", "100000"]), "ocean/%s_profile" % w,
                      pictures=["profile.png"]))
    photons = [] if full else ["--photons", "100000"]
    s.append(Step("Underwater light", "Where the energy goes (Fig. 5.9)",
                  "The energy absorbed per interaction. " + description("ocean/fig5_9"),
                  ["ocean", "trace", "ocean/fig5_9", "--out", "{out}", "--quiet"] + photons, "ocean/fig5_9",
                  pictures=["fig5_9.png"]))
    s.append(Step("Underwater light", "Inelastic scattering in Baltic water (Fig. 5.12)",
                  "Thesis Fig. 5.12: the energy per event and constituent. "
                  + description("ocean/fig5_11/baltic_inelastic"),
                  ["ocean", "trace", "ocean/fig5_11/baltic_inelastic", "--out", "{out}", "--quiet"] + photons,
                  "ocean/fig5_12", pictures=["fig5_12.png"]))
    s.append(Step("Underwater light", "A sunlit profile against discrete ordinates",
                  "Thesis §4.2: downwelling, upwelling and scalar irradiance from the photon tracer against an "
                  "independent plane-parallel discrete-ordinates solution (arcus.discrete_ordinates).",
                  ["apps/ocean/plot_profile_check.py", "--out", "{out}"]
                  + ([] if full else ["--photons", "50000", "--batches", "4"]), "ocean/profile"))
    wl = ["--wavelengths", "380", "700", "33" if full else "9"]
    s.append(Step("Rainbows", "A drop's phase function against Mie and Debye",
                  "Thesis §4.4, Fig. 5.16–5.20: a 500 µm drop's phase function by ray casting with interference, "
                  "against Lorenz–Mie (Fig. 5.20), and term by term against the Debye series (Fig. 5.16–5.19).",
                  ["rainbow", "table", "--particle", "sphere:500um"] + wl
                  + ["--theta", "120", "145", "0.01", "--plot", "{out}/sphere.png", "--per-bounce", "-o",
                     "{out}/sphere", "--quiet"] + ([] if full else ["--grid", "500"]), "rainbow",
                  docs_image="rainbow/sphere.png"))
    for name, title in SKIES:
        # Gallery tables: 17 wavelengths (9 for the crystals, whose colours are a red
        # edge), the crystals at their scenes' orientations (traced as beams:
        # bench/halo_bench.py).
        tables = {"halo": ["--wavelengths", "9"],
                  "sundogs": ["--wavelengths", "9"]}.get(name, ["--wavelengths", "17"])
        s.append(Step("Rainbow skies and halos", title, description("rainbow/" + name),
                      ["render", "rainbow/" + name, "-o", "{out}/%s.png" % name,
                       "--profile", "{out}/%s_profile.png" % name, "--quiet"]
                      + ([] if full else ["--quick", "--width", "400", "--height", "300"] + tables), "sky",
                      docs_image="sky/%s.png" % name if name in ("double_bow", "supernumerary") else "",
                      expected_seconds={"halo": 20.0, "sundogs": 15.0, "twinned": 26.0, "cloudbow": 10.0}.get(name, 3.0)))
    s.append(Step("Translucency", "Marble through the dipole",
                  "Thesis eq. 3.6–3.8: a marble torus 54 mm across (Jensen et al. 2001's coefficients) by the "
                  "hierarchical gather of Jensen & Buhler 2002, with a Fresnel-weighted highlight.",
                  ["bssrdf", "render", "torus", "--material", "marble", "--mm-per-unit", "20", "--position", "0",
                   "2.6", "2.6", "--ortho-height", "3.2", "--light", "0.2", "1", "0.6", "--light", "-0.5", "0.3", "-1", "0.6",
                   "-o", "{out}/marble.png", "--quiet"] + ([] if full else ["--width", "200", "--height", "200"]),
                  "translucency/render", expected_seconds=8.0))
    s.append(Step("Translucency", "A photograph and its estimated BSSRDF",
                  "Thesis §3.3.1, Fig. 3.8: a synthetic photograph of an apple sphere, its profile estimated by "
                  "QMR on the distance histograms and fitted by the dipole; photo | re-render | difference, and "
                  "the profile against the dipole and §3.4's Hermite curve.",
                  ["apps/translucency/showcase.py", "estimate", "--out", "{out}"]
                  + ([] if full else ["--side", "128"]), "translucency/estimate",
                  pictures=["compare.png", "profile.png"], expected_seconds=12.0))
    s.append(Step("Translucency", "From an uncontrolled photograph",
                  "Thesis §3.4, §5.2: a synthetic photograph of an apple lumpy sphere, with no mesh and no light "
                  "given: the light found on its contour and inside it, the shape inflated from its contour, and "
                  "§3.4's Hermite profile estimated on that shape; photograph | estimated normals | re-render.",
                  ["apps/translucency/showcase.py", "photo", "--out", "{out}"]
                  + ([] if full else ["--side", "128"]), "translucency/photo", expected_seconds=8.0))
    s.append(Step("Translucency", "Table 3.3: six materials estimated back",
                  "Thesis §3.3.1, Table 3.3: Jensen et al. 2001's apple, cream, marble, potato, skim and whole "
                  "milk on a torus lit from the front and from behind, each photo estimated back; reduced albedo "
                  "and extinction beside the measured values and the thesis' estimates, the photos above their "
                  "re-renders.  At 200² in the quick gallery too: coarser photos lose the short profiles.",
                  ["apps/translucency/showcase.py", "table_3_3", "--out", "{out}"], "translucency/table_3_3",
                  expected_seconds=65.0))
    s.append(Step("Translucency", "Table 5.1: genetic inverse rendering",
                  "Thesis §3.2, §5.1: 40 individuals × 50 generations from Table 3.1's genes toward Table 5.1's "
                  "medium; the target beside the best render, and the best genes every tenth generation.",
                  ["apps/translucency/showcase.py", "genetic", "--out", "{out}"]
                  + ([] if full else ["--side", "48"]), "translucency/genetic", expected_seconds=10.0))
    for engine, title, caption in BENCH_STEPS:
        s.append(Step("What accuracy costs in time", title, caption,
                      ["bench", engine, "--out", "{out}"] + (["--full"] if full else []), "bench/" + engine,
                      expected_seconds={"render": 65.0, "curved": 32.0}.get(engine, 15.0)))
    return s


def add(sub):
    p = sub.add_parser("gallery", help="every engine's showcase on one page, out/index.html", description=__doc__)
    p.add_argument("--out", default="out", help="output folder (default out)")
    p.add_argument("--full", action="store_true", help="the scenes' own settings and the full benchmarks (slow)")
    p.add_argument("--docs", action="store_true", help="also copy the README's pictures to docs/images/")
    p.add_argument("--jobs", type=int, default=2, help="steps run at once (default 2)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(run=run)


def _command(argv):
    first = argv[0]
    if first.endswith(".py"):
        return [sys.executable, str(resources.script(os.path.normpath(first)))] + argv[1:]
    return [sys.executable, "-m", "arcus.cli"] + argv


def _env():
    env = dict(os.environ)
    # The package this command runs from, for the steps' own processes.
    package_parent = str(resources.PACKAGE.parent)
    env["PYTHONPATH"] = package_parent + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    env.setdefault("MPLBACKEND", "Agg")
    return env


def run_step(step, root, log):
    out = root / step.out
    out.mkdir(parents=True, exist_ok=True)
    started = time.monotonic()
    cmd = _command([a.replace("{out}", str(out)) for a in step.argv])
    with open(log, "a") as f:
        f.write("$ %s\n" % " ".join(cmd))
        f.flush()
        rc = subprocess.call(cmd, stdout=f, stderr=subprocess.STDOUT, env=_env(), cwd=str(root))
    if rc != 0:
        step.failed = "exit status %d (see %s)" % (rc, log)
    step.seconds = time.monotonic() - started
    return step


def run(args):
    root = Path(args.out).resolve()
    root.mkdir(parents=True, exist_ok=True)
    log = root / "gallery.log"
    log.write_text("")
    planned = steps(args.full)
    started = time.monotonic()
    with Progress("gallery", total=len(planned), unit="steps", quiet=args.quiet) as bar, \
            concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        # Longest first, so that no long step starts last (the page keeps its own order).
        order = sorted(planned, key=lambda s: -s.expected_seconds)
        for step in concurrent.futures.as_completed([pool.submit(run_step, s, root, log) for s in order]):
            step = step.result()
            bar.set_stage("gallery: %s (%.0f s)" % (step.title, step.seconds))
            bar.advance()
    seconds = time.monotonic() - started
    index = page.write(root, planned, seconds, full=args.full)
    if args.docs:
        page.copy_docs_images(root, planned)
    failed = [s for s in planned if s.failed]
    for s in failed:
        print("arcus gallery: %s failed: %s" % (s.title, s.failed), file=sys.stderr)
    print("arcus gallery: %d of %d steps in %.0f s; open %s" % (len(planned) - len(failed), len(planned), seconds, index))
    return 1 if failed else 0
