"""An independent Monte Carlo reference for subsurface light, written for the tests and
sharing no code with arcus: a pencil beam enters a homogeneous half-space (z < 0) of
refractive index eta under a smooth dielectric boundary at normal incidence; photons
fly exponential free paths, scatter by Henyey–Greenstein (standard form, sampled
analytically) or are absorbed (analog: with probability σ_a/σ_t at each event), and
at the boundary are reflected back with the exact Fresnel probability or leave.

What it returns is per photon transmitted into the medium (the specular reflection at
entry is excluded, as the dipole's R_total excludes it): the fraction that leaves again
(R_total) and, per annulus of the exit radius, the exitance per unit area (R_d).
Units: the coefficients' inverse (mm⁻¹ → mm)."""

import numpy as np


def fresnel_unpolarized(cos_i, n1, n2):
    """Exact unpolarised reflectance for light from index n1 onto n2 (arrays)."""
    cos_i = np.clip(cos_i, 0.0, 1.0)
    sin_t2 = (n1 / n2) ** 2 * (1 - cos_i**2)
    total = sin_t2 >= 1
    cos_t = np.sqrt(np.where(total, 0.0, 1 - sin_t2))
    rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t)
    rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t)
    return np.where(total, 1.0, 0.5 * (rs**2 + rp**2))


def _scatter(direction, g, rng):
    """New directions after Henyey–Greenstein scattering of unit `direction` (N, 3)."""
    n = len(direction)
    u = rng.random(n)
    if abs(g) < 1e-6:
        cos_t = 1 - 2 * u
    else:
        s = (1 - g * g) / (1 - g + 2 * g * u)
        cos_t = (1 + g * g - s * s) / (2 * g)
    sin_t = np.sqrt(np.maximum(0.0, 1 - cos_t**2))
    phi = 2 * np.pi * rng.random(n)
    # An orthonormal frame around each direction.
    helper = np.where(np.abs(direction[:, :1]) < 0.9, [[1.0, 0.0, 0.0]], [[0.0, 1.0, 0.0]])
    e1 = np.cross(direction, helper)
    e1 /= np.linalg.norm(e1, axis=1, keepdims=True)
    e2 = np.cross(direction, e1)
    return (cos_t[:, None] * direction + (sin_t * np.cos(phi))[:, None] * e1
            + (sin_t * np.sin(phi))[:, None] * e2)


def trace(sigma_a, sigma_s, g, eta, photons, r_edges, seed=1):
    """(R_total, R_d per annulus of `r_edges`, its standard error) for `photons`
    transmitted photons."""
    rng = np.random.default_rng(seed)
    sigma_t = sigma_a + sigma_s
    albedo = sigma_s / sigma_t
    position = np.zeros((photons, 3))
    direction = np.tile([0.0, 0.0, -1.0], (photons, 1))  # normal incidence: no refraction
    exits = []
    while len(position):
        step = -np.log(1 - rng.random(len(position))) / sigma_t
        # Photons whose step would cross z = 0 stop at the boundary instead.
        to_boundary = np.where(direction[:, 2] > 0, -position[:, 2] / np.maximum(direction[:, 2], 1e-300), np.inf)
        crossing = to_boundary < step
        position += np.where(crossing, to_boundary, step)[:, None] * direction
        leaves = np.zeros(len(position), dtype=bool)
        if crossing.any():
            cos_i = direction[crossing, 2]
            reflected = rng.random(crossing.sum()) < fresnel_unpolarized(cos_i, eta, 1.0)
            idx = np.flatnonzero(crossing)
            direction[idx[reflected], 2] *= -1
            position[idx, 2] = 0.0
            leaves[idx[~reflected]] = True
            exits.append(np.hypot(position[idx[~reflected], 0], position[idx[~reflected], 1]))
        # The others interact: absorbed, or scattered.
        interacts = ~crossing
        absorbed = interacts & (rng.random(len(position)) >= albedo)
        scatters = interacts & ~absorbed
        if scatters.any():
            direction[scatters] = _scatter(direction[scatters], g, rng)
        keep = ~(leaves | absorbed)
        position, direction = position[keep], direction[keep]
    radii = np.concatenate(exits) if exits else np.zeros(0)
    counts, _ = np.histogram(radii, bins=r_edges)
    areas = np.pi * (r_edges[1:] ** 2 - r_edges[:-1] ** 2)
    return radii.size / photons, counts / (photons * areas), np.sqrt(np.maximum(counts, 1)) / (photons * areas)


def main():
    """The table of docs/translucency.md: the dipole against this tracer from high
    albedos, where it is asserted, down to low ones, where it is only reported."""
    from arcus.translucency import Dipole  # the thing compared, not used by the tracer

    edges = np.geomspace(2.0, 20.0, 9)
    print("| α′ | R_total, transport | R_total, dipole | dipole / transport | R_d ratio, 2 ≤ rσ′_t ≤ 20 |")
    print("|---|---|---|---|---|")
    for albedo in (0.999, 0.99, 0.9, 0.7, 0.5):
        total, exitance, _ = trace(1 - albedo, albedo, 0.0, 1.3, 200_000, edges, seed=7)
        dipole = Dipole(1 - albedo, albedo, 1.3)
        ratios = []
        for lo, hi, mc in zip(edges[:-1], edges[1:], exitance):
            r = np.linspace(lo, hi, 400)
            flux = np.trapezoid(2 * np.pi * r * dipole.Rd(r)[:, 0], r) / (np.pi * (hi * hi - lo * lo))
            if mc > 0:
                ratios.append(flux / mc)
        print("| %.3f | %.4f | %.4f | %.3f | %.2f to %.2f |" % (albedo, total, dipole.total_reflectance[0],
                                                                dipole.total_reflectance[0] / total,
                                                                min(ratios), max(ratios)))


if __name__ == "__main__":
    main()
