"""The angles a phase-table task is computed on (arcus.sweep.phase_tables): the grid
ray-cast tables share, and how a task's key names a uniform grid."""

import numpy as np


# A ray-cast phase function (spheres, raindrops, smooth meshes) is read off the cast at
# any direction for the cast's cost alone, so its table is computed on one shared grid,
# 0-180 degrees every 0.01 degrees, and each caller takes its own angles out of it.
# Scenes whose theta grids are subsets of it share their tables exactly: a slice of the
# same point samples, never an interpolation (double_bow's 100-180 every 0.05 degrees
# and supernumerary's 120-180 every 0.02 are).  Other grids, Lorenz-Mie (whose cost
# grows with the angles), crystals (binned glints) and tables over azimuths too (18 001
# angles times every azimuth made the twinned bow's raindrop tables 26 MB each and its
# first render 181 s instead of 26) are computed on the grid asked.
SHARED_THETA_STEP = 0.01
SHARED_THETA = np.arange(18001) * SHARED_THETA_STEP


def _shared_theta_index(spec, theta, phi):
    """Where ``theta`` sits in SHARED_THETA, if ``spec``'s table is computed there; else None."""
    if spec["kind"] == "crystal" or (spec["kind"] == "sphere" and spec["method"] == "mie") or \
            (spec["kind"] == "mesh" and not spec["smooth"]) or isinstance(phi, np.ndarray):
        return None
    steps = theta / SHARED_THETA_STEP
    index = np.rint(steps)
    return index.astype(np.int64) if np.all(np.abs(steps - index) < 1e-6) else None


def _theta_task(theta):
    """The angles as a task holds them: a uniform grid as its first angle, step and count
    (a task's key is JSON: thousands of angles, written out, cost more to key and check
    than a cached table costs to read), when those give back exactly these angles; else
    the list."""
    if theta.size >= 2:
        diff = float(theta[1] - theta[0])
        for step in (float("%.12g" % diff), diff):  # the step a spec wrote (0.05), or the one apart
            grid = dict(first_deg=float(theta[0]), step_deg=step, count=int(theta.size))
            if np.array_equal(_theta_values(grid), theta):
                return grid
    return theta.tolist()


def _theta_values(theta):
    """The angles of a task's ``theta`` (see _theta_task)."""
    if isinstance(theta, dict):
        return theta["first_deg"] + theta["step_deg"] * np.arange(theta["count"])
    return np.array(theta, dtype=np.float64)
