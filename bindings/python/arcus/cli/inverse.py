"""arcus inverse genetic SCENE.json --target PHOTO.exr: genetic inverse rendering (thesis
§3.2, §5.1) — the genes of a dipole (σ_a, σ_s, g, η, b) or an opaque Phong surface
(k_d, k_s, b) whose render of the scene best matches the photo.  Prints the best genes
every tenth generation, as the thesis' Table 5.1, and the result; -o writes the best
render.  docs/translucency.md."""

import time
from pathlib import Path

import numpy as np

from .. import image, inverse
from .._errors import ArgumentError
from ..context import Context
from ..progress import Progress
from .render import FORMATS, _device, _raw


def add(sub):
    p = sub.add_parser("inverse", help="inverse rendering: material genes from a photo of a known scene",
                       description=__doc__, formatter_class=_raw())
    verbs = p.add_subparsers(dest="verb", metavar="VERB", required=True)
    g = verbs.add_parser("genetic", help="genetic search (thesis §3.2)", description=__doc__, formatter_class=_raw(),
                         epilog="example:\n  arcus bssrdf render torus --sigma-a 0.0021 0.0041 0.0071 --sigma-s-prime "
                                "1.095 1.31 1.5 --eta 1.5 --highlight 20 --ortho-height 3.2 --mm-per-unit 20 "
                                "--position 0 2.6 2.6 --light 0.2 1 0.6 --light -0.5 0.3 -1 0.6 --width 64 "
                                "--height 64 -o target.exr\n"
                                "  arcus inverse genetic scenes/translucency/table_5_1.json --target target.exr "
                                "--seed 1")
    g.add_argument("scene", help="a JSON scene: mesh, lights, camera, ortho_height, mm_per_unit")
    g.add_argument("--target", required=True, help="the photo (.exr, .hdr): linear radiance")
    g.add_argument("--model", choices=sorted(inverse.GENES), default="dipole")
    g.add_argument("--population", type=int, default=40, help="individuals (default 40, §5.1)")
    g.add_argument("--generations", type=int, default=50, help="generations (default 50, §5.1)")
    g.add_argument("--seed", type=int, default=0)
    g.add_argument("--polish-steps", type=int, default=20,
                   help="Levenberg–Marquardt steps after the search, from the last population's four best (default 20; 0: the "
                        "thesis' search alone)")
    g.add_argument("--fitness-space", choices=("ycbcr", "rgb"), default="ycbcr")
    g.add_argument("-o", "--output", action="append", metavar="OUT", help="write the best render (.png .exr ...)")
    g.add_argument("--device", help="an OpenCL device: an index or part of its name")
    g.add_argument("--quiet", action="store_true", help="no progress bar")
    g.set_defaults(run=run_genetic)


def _row(generation, fitness, genes):
    cells = []
    for name, value in genes.items():
        cells.append("%s %s" % (name, " ".join("%.4g" % v for v in np.atleast_1d(value))))
    return "%5d  %8.5f  %s" % (generation, fitness, "  ".join(cells))


def run_genetic(args):
    outputs = [Path(o) for o in (args.output or [])]
    for o in outputs:
        if o.suffix.lower() not in FORMATS:
            raise ArgumentError("-o %s: unknown image format %r (expected %s)" % (o, o.suffix, ", ".join(FORMATS)))
    target = Path(args.target)
    if not target.is_file():
        raise ArgumentError("--target %s: no such file" % target)
    rows = []

    def on_generation(generation, best, genes):
        if generation % 10 == 0 or generation == args.generations:
            rows.append(_row(generation, best, genes))

    started = time.monotonic()
    with Context(_device(args.device)) as ctx:
        with Progress("genetic search", quiet=args.quiet) as bar:
            found = inverse.genetic(target, args.scene, model=args.model, population=args.population,
                                    generations=args.generations, seed=args.seed, fitness_space=args.fitness_space,
                                    polish_steps=args.polish_steps,
                                    on_generation=on_generation, progress=bar if bar.shown else None, context=ctx)
    print("generation  best fitness  best genes (every tenth, as Table 5.1)")
    for row in rows:
        print(row)
    if found.polish_steps:
        print("polish: %d Levenberg-Marquardt steps from fitness %.5f to %.5f: %s" % (
            found.polish_steps, found.search_fitness, found.fitness,
            "  ".join("%s %s" % (n, " ".join("%.4g" % v for v in np.atleast_1d(x))) for n, x in found.best.items())))
    print("%s: %s model, %d individuals × %d generations, %d evaluations over %d pixels; cache %.1f s, search "
          "%.1f s, polish %.1f s, %.1f s in all" % (
              target.name, args.model, args.population, len(found.history["best_fitness"]) - 1, found.evaluations,
              found.pixels, found.timings["cache"], found.timings["search"], found.timings["polish"],
              time.monotonic() - started))
    if found.sigma_s_prime is not None:
        print("sigma_s' = (1 - g) sigma_s: %s (what the image determines; sigma_s and g alone are not)"
              % " ".join("%.4g" % v for v in found.sigma_s_prime))
    for o in outputs:
        o.parent.mkdir(parents=True, exist_ok=True)
        eight_bit = o.suffix.lower() in (".png", ".jpg", ".jpeg")
        top = float(found.image.max()) or 1.0
        image.write(o, found.image * (0.9 / top) if eight_bit else found.image)
        print("wrote %s" % o.resolve())
    return 0
