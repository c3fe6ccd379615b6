"""Independent references the tests compare arcus with: closed-form ray paths, and
Ciddor's refractivity of air, written out here rather than taken from the library."""

import numpy as np


def fan(count, spread=0.2):
    """A fan of rays in the x-y plane: origins (0, 0.1 i, 0), directions (1, 0.05 i - spread, 0).

    This is the job of the C program tests/c_api_dump (for count = 8, spread = 0.2).
    """
    i = np.arange(count)
    origins = np.stack([np.zeros(count), 0.1 * i, np.zeros(count)], axis=1)
    directions = np.stack([np.ones(count), 0.05 * i - spread, np.zeros(count)], axis=1)
    return origins, directions


def catenary(n0, g, origins, directions, length):
    """End position and unit direction of rays in n = n0 + g*y, after arc length `length`.

    The rays lie in the x-y plane.  v = n dr/ds has a conserved x component A (the
    field does not vary in x) and dv_y/ds = g.  Writing n = A cosh u, v_y = A sinh u:
    sinh u grows linearly, sinh u(s) = sinh u0 + g s / A; dx = A du / g, so
    x = C + A u / g, and y = (A cosh u - n0) / g.
    """
    origins = np.asarray(origins, dtype=float)
    d = np.asarray(directions, dtype=float)
    d = d / np.linalg.norm(d, axis=1, keepdims=True)
    n_start = n0 + g * origins[:, 1]
    A = n_start * d[:, 0]
    u0 = np.arcsinh(n_start * d[:, 1] / A)
    C = origins[:, 0] - A * u0 / g
    u = np.arcsinh(np.sinh(u0) + g * length / A)
    end = np.stack([C + A * u / g, (A * np.cosh(u) - n0) / g, origins[:, 2]], axis=1)
    direction = np.stack([1.0 / np.cosh(u), np.tanh(u), np.zeros_like(u)], axis=1)
    return end, direction


def catenary_height(n0, g, origin, direction, x):
    """y at abscissa x on the catenary through `origin` with `direction` (one ray)."""
    n_start = n0 + g * origin[1]
    d = np.asarray(direction, dtype=float) / np.linalg.norm(direction)
    A = n_start * d[0]
    u0 = np.arcsinh(n_start * d[1] / A)
    C = origin[0] - A * u0 / g
    return (A * np.cosh((np.asarray(x) - C) * g / A) - n0) / g


def ciddor(nm):
    """n - 1 of standard dry air (288.15 K, 101325 Pa) at a vacuum wavelength in nm.

    Ciddor (1996), eq. 1: (n - 1) 1e8 = 5792105 / (238.0185 - s2) + 167917 / (57.362 - s2),
    s2 = (1 / lambda[um])^2.
    """
    s2 = (1000.0 / np.asarray(nm, dtype=float)) ** 2
    return 1e-8 * (5792105.0 / (238.0185 - s2) + 167917.0 / (57.362 - s2))
