#!/usr/bin/env python3
"""sweep_bench — what Dask buys and costs for arcus.sweep's phase-table sweeps.

    python3 bench/sweep_bench.py [--out DIR] [--tasks N] [--grid G] [--workers W]

On one task list (N = 16 tables of a 500 µm water sphere at grid G = 300, one per
wavelength, θ = 0..180° in 0.25° steps, p = 0..3) it times:

1. the serial loop (``client="serial"``) and a LocalCluster of W = 2 worker processes,
   both warm (the cluster started and each worker's context made beforehand): tables
   per minute, median of 3 sweeps; and the same cluster sweep cold, start-up and
   shut-down included, as a user's ``phase_tables(..., workers=2)`` runs it;
2. what Dask adds per task: 200 trivial tasks through map_tasks on the cluster and in
   the serial loop, and raw ``client.map`` + ``gather``; the cluster's start-up and
   shut-down;
3. a sweep read entirely from the disk cache.

Writes DIR/sweep.md (the tables, the machine) and prints it.  About a minute on two
cores.  The library is the one ``arcus`` finds (ARCUS_LIBRARY picks one).
"""

import argparse
import os
import statistics
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(ROOT, "bindings", "python"))
sys.path.insert(0, HERE)

import arcus  # noqa: E402
import arcus.sweep as sweep  # noqa: E402

try:
    from ocean_bench import loadavg, machine  # noqa: E402  (one description of the machine)
except ImportError:  # pragma: no cover - ocean_bench needs what arcus needs; keep going without it
    def machine():
        return dict(cpu="unknown CPU", cores=os.cpu_count(), device="see arcus.devices()",
                    arcus=arcus.__version__, library=str(arcus.library_path), date="", python=sys.version.split()[0])

    def loadavg():
        return "n/a"

REPEATS = 3
TRIVIAL_TASKS = 200


def trivial(spec):
    """A task that does nothing: what remains of its time is the machinery's."""
    return {"value": np.array(spec["i"])}


def timed(function, *args, **kwargs):
    start = time.perf_counter()
    result = function(*args, **kwargs)
    return time.perf_counter() - start, result


def median_time(function, *args, **kwargs):
    return statistics.median(timed(function, *args, **kwargs)[0] for _ in range(REPEATS))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default=os.path.join("out", "bench"), help="output directory (default out/bench)")
    ap.add_argument("--tasks", type=int, default=16, help="tables in the sweep (default 16)")
    ap.add_argument("--grid", type=int, default=300, help="rays per side of each cast (default 300)")
    ap.add_argument("--workers", type=int, default=2, help="the LocalCluster's worker processes (default 2)")
    args = ap.parse_args(argv)
    import distributed

    os.makedirs(args.out, exist_ok=True)
    load0 = loadavg()
    m = machine()
    particles = [{"kind": "sphere", "radius": 5e-4}]
    wavelengths = np.linspace(400.0, 700.0, args.tasks)
    theta = np.arange(0.0, 180.001, 0.25)
    sweep_args = (particles, wavelengths, theta)
    options = dict(grid=args.grid, max_bounces=3, cache_dir=False)
    n = args.tasks
    print("sweep_bench: %d tables of a 500 µm sphere at grid %d, %d angles; %d workers"
          % (n, args.grid, theta.size, args.workers), flush=True)

    # 1. throughput
    sweep.phase_tables(particles, wavelengths[:1], theta, client="serial", **options)  # kernels built, context made
    serial_s = median_time(sweep.phase_tables, *sweep_args, client="serial", **options)
    start_s, cluster = timed(distributed.LocalCluster, n_workers=args.workers, threads_per_worker=1, processes=True,
                             dashboard_address=":0")
    client_s, client = timed(distributed.Client, cluster, set_as_default=False)
    try:
        sweep.phase_tables(particles, wavelengths[:2 * args.workers], theta, client=client, **options)  # warm workers
        cluster_s = median_time(sweep.phase_tables, *sweep_args, client=client, **options)

        # 2. the overhead per task
        specs = [{"i": i} for i in range(TRIVIAL_TASKS)]
        trivial_cluster_s = median_time(sweep.map_tasks, trivial, specs, client=client, cache_dir=False)
        trivial_serial_s = median_time(sweep.map_tasks, trivial, specs, client="serial", cache_dir=False)

        def raw_dask():
            return client.gather(client.map(trivial, specs, pure=False))

        raw_s = median_time(raw_dask)
    finally:
        close_s, _ = timed(lambda: (client.close(), cluster.close()))
    cold_s, _ = timed(sweep.phase_tables, *sweep_args, workers=args.workers, **options)

    # 3. the cache
    with tempfile.TemporaryDirectory() as cache:
        write_s, _ = timed(sweep.phase_tables, *sweep_args, client="serial", **dict(options, cache_dir=cache))
        read_s, again = timed(sweep.phase_tables, *sweep_args, client="serial", **dict(options, cache_dir=cache))
        assert again.cached == n and again.computed == 0

    def per_minute(seconds):
        return 60.0 * n / seconds

    rows = [
        ("serial loop (this process)", serial_s, per_minute(serial_s), "1.00×"),
        ("LocalCluster, %d workers, warm" % args.workers, cluster_s, per_minute(cluster_s),
         "%.2f×" % (serial_s / cluster_s)),
        ("LocalCluster, %d workers, cold (start + sweep + close)" % args.workers, cold_s, per_minute(cold_s),
         "%.2f×" % (serial_s / cold_s)),
        ("serial loop, writing the cache", write_s, per_minute(write_s), "%.2f×" % (serial_s / write_s)),
        ("everything read from the cache", read_s, per_minute(read_s), "%.0f×" % (serial_s / read_s)),
    ]
    overhead = [
        ("map_tasks on the cluster, per trivial task", 1e3 * trivial_cluster_s / TRIVIAL_TASKS),
        ("map_tasks in the serial loop, per trivial task", 1e3 * trivial_serial_s / TRIVIAL_TASKS),
        ("raw client.map + gather, per trivial task", 1e3 * raw_s / TRIVIAL_TASKS),
        ("LocalCluster(%d workers) start-up" % args.workers, 1e3 * (start_s + client_s)),
        ("LocalCluster shut-down", 1e3 * close_s),
        ("one table at grid %d, serial (for scale)" % args.grid, 1e3 * serial_s / n),
    ]
    lines = [
        "# sweep_bench — arcus.sweep on Dask",
        "",
        "Machine: %s, %d cores; %s; arcus %s (%s); Python %s; %s; load average %s before, %s after."
        % (m["cpu"], m["cores"], m["device"], m["arcus"], m["library"], m["python"], m["date"], load0, loadavg()),
        "",
        "Task list: %d phase tables (`phase_tables`) of a 500 µm water sphere, one per wavelength 400–700 nm, "
        "grid %d, p = 0..3, %d angles (0–180° by 0.25°); no cache unless stated.  Median of %d sweeps."
        % (n, args.grid, theta.size, REPEATS),
        "",
        "| run | seconds | tables / minute | speed-up |",
        "|---|---:|---:|---:|",
    ] + ["| %s | %.2f | %.0f | %s |" % row for row in rows] + [
        "",
        "| Dask's cost | ms |",
        "|---|---:|",
    ] + ["| %s | %.2f |" % row for row in overhead] + [
        "",
        "Every worker runs its tasks on the same OpenCL device as the serial loop: on a CPU "
        "device (PoCL) each cast already uses every core, so workers overlap only the casts' "
        "host-side parts (patches, queries) with one another's kernels; on a machine of "
        "GPUs, or a cluster of machines, each worker brings its own device.",
    ]
    text = "\n".join(lines) + "\n"
    path = os.path.join(args.out, "sweep.md")
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)
    print(text)
    print("sweep_bench: wrote %s" % path)
    return 0


if __name__ == "__main__":  # the guard also keeps Dask's spawned workers from running it again
    sys.exit(main())
