"""The subcommands that run a tool shipped with arcus: the C++ tracer and live preview,
the ocean, rainbow and sweep apps, and the benchmarks.  Their arguments pass through
unchanged (``arcus ocean --help`` is the app's own help), except that a bundled scene
may be named instead of a path."""

import os
import subprocess
import sys

from .._scene_file import read
from . import resources

# command: (how it runs, words before the scene argument, help)
TOOLS = {
    "trace": ("arcus_trace", 0, "trace a curved-light scene's rays: CSVs, a summary and paths.png"),
    "view": ("arcus_view", 0, "the live, progressive preview of a render scene or a rainbow sky"),
    "ocean": ("apps/ocean/arcus_ocean.py", 1, "underwater light: ocean trace|profile|render SCENE"),
    "rainbow": ("apps/rainbow/arcus_rainbow.py", None, "phase functions: rainbow table|mie (drops, crystals)"),
    "sweep": ("apps/sweep/arcus_sweep.py", 0, "a sweep of independent jobs (on Dask), with its disk cache"),
}


def add(sub):
    for name, (_, _, help_text) in TOOLS.items():
        p = sub.add_parser(name, help=help_text, add_help=False, description=help_text)
        p.set_defaults(run=run_tool, tool=name, passes_arguments=True)
    b = sub.add_parser("bench", help="what accuracy costs in time, engine by engine (docs/benchmarks.md)",
                       description="Runs an engine's benchmark at quick settings (minutes), or the full one "
                       "(--full: up to an hour on two cores); tables and plots go to --out.")
    b.add_argument("engine", nargs="?", choices=sorted(BENCHES), help="one engine (default: all)")
    b.add_argument("--full", action="store_true", help="the full benchmark, as docs/benchmarks.md quotes it")
    b.add_argument("--out", default=os.path.join("out", "bench"), help="output folder (default out/bench)")
    b.set_defaults(run=run_bench)


def command(what):
    """The argv prefix that runs a shipped tool: a C++ binary, or a Python app."""
    if what.endswith(".py"):
        return [sys.executable, str(resources.script(what))]
    return [str(resources.tool(what))]


def _with_scene(extra, before):
    """``extra`` with its scene argument (the first word after ``before`` leading words
    that is not an option) resolved to a file when it names a bundled scene."""
    if before is None:
        return extra
    seen = 0
    for i, word in enumerate(extra):
        if word.startswith("-"):
            return extra
        if seen == before:
            return extra[:i] + [resources.scene_or_word(word)] + extra[i + 1:]
        seen += 1
    return extra


def run_tool(args, extra):
    what, before, _ = TOOLS[args.tool]
    # The Python apps name themselves after this in their usage lines.
    env = dict(os.environ, ARCUS_PROG="arcus " + args.tool)
    extra = _with_scene(extra, before)
    rc = subprocess.call(command(what) + extra, env=env)
    if rc == 0 and args.tool == "trace" and "--help" not in extra and "-h" not in extra:
        rc = subprocess.call(command("apps/plot_paths.py") + [_trace_folder(extra)], env=env)
    return rc


def _trace_folder(extra):
    """Where arcus_trace wrote: --out DIR, else out/<the scene's name>."""
    if "--out" in extra and extra.index("--out") + 1 < len(extra):
        return extra[extra.index("--out") + 1]
    scene = next(w for w in extra if not w.startswith("-"))
    return os.path.join("out", read(scene, ("curved",))[1].get("name", "scene"))


# engine: (quick command, full command); each takes --out.
BENCHES = {
    "curved": (["arcus_bench", "--quick"], ["arcus_bench"]),
    "render": (["arcus_bench_render", "--quick", "--scenes", "{scenes}/inferior_mirage.json"],
               ["arcus_bench_render", "--scenes", ",".join("{scenes}/%s.json" % s for s in
                                                           ("inferior_mirage", "novaya_zemlya", "fata_morgana",
                                                            "cross_room"))]),
    "ocean": (["bench/ocean_bench.py", "--quick"], ["bench/ocean_bench.py"]),
    "rainbow": (["bench/rainbow_bench.py", "--quick"], ["bench/rainbow_bench.py"]),
    "sky": (["bench/sky_bench.py", "--quick"], ["bench/sky_bench.py"]),
    "halo": (["bench/halo_bench.py", "--quick"], ["bench/halo_bench.py"]),
    "fogbow": (["bench/fogbow_bench.py", "--quick"], ["bench/fogbow_bench.py"]),
    "spectral": (["bench/spectral_bench.py", "--quick"], ["bench/spectral_bench.py"]),
    "sweep": (["bench/sweep_bench.py", "--tasks", "4", "--grid", "150"], ["bench/sweep_bench.py"]),
    "translucency": (["bench/translucency_bench.py", "--quick"], ["bench/translucency_bench.py"]),
}


def bench_command(engine, full, out):
    """The command running ``engine``'s benchmark, writing to the folder ``out``."""
    what, *options = BENCHES[engine][1 if full else 0]
    scenes = str(resources.share_dir() / "scenes")
    options = [o.replace("{scenes}", scenes) for o in options]
    # arcus_bench_render takes the Markdown file it writes, the others a folder.
    target = os.path.join(out, "render.md") if engine == "render" else out
    return command(what) + options + ["--out", target]


def bench_env():
    """The environment of a benchmark: an installed arcus_bench is told where its
    plotting script is."""
    env = dict(os.environ)
    script = resources.share_dir() / "bench" / "plot_bench.py"
    if script.is_file():
        env["ARCUS_BENCH_PLOT_SCRIPT"] = str(script)
    return env


def run_bench(args):
    failed = 0
    for engine in [args.engine] if args.engine else list(BENCHES):
        cmd = bench_command(engine, args.full, args.out)
        print("arcus bench %s%s: %s" % (engine, " --full" if args.full else "", " ".join(cmd)), flush=True)
        os.makedirs(args.out, exist_ok=True)
        failed = failed or subprocess.call(cmd, env=bench_env())
    return failed
