"""Image files written by the tests themselves, so that what the library reads back is
known exactly."""

import numpy as np


def write_pfm(path, rgb):
    """A PFM file of an (H, W, 3) array: float32, little-endian (negative scale), rows
    stored bottom-up as the format has them.  Returns ``path``."""
    rgb = np.asarray(rgb)
    with open(path, "wb") as f:
        f.write(b"PF\n%d %d\n-1.0\n" % (rgb.shape[1], rgb.shape[0]))
        f.write(np.ascontiguousarray(rgb[::-1], "<f4").tobytes())
    return path
