"""Ice-crystal halos: phase functions of hexagonal ice prisms averaged over orientations.

::

    import numpy as np
    import arcus, arcus.halo as halo

    spec = {"kind": "crystal", "shape": "column", "size": 50e-6, "orientation": "random",
            "orientations": 2000, "seed": 1}
    theta = np.arange(0.0, 60.0, 0.05)
    with arcus.Context() as ctx:
        t = halo.crystal_table(spec, 550.0, theta, context=ctx)
    print(t["phase"], t["cross_section"], halo.halo_angle(550.0))   # the 22° halo's edge, 21.92°

Geometric optics without interference or diffraction (crystals of 10-100 µm are many
wavelengths across): a flat-faced :class:`arcus.rainbow.Mesh`'s light leaves as glints
(every ray of one sequence of faces in one direction), traced as beams, exactly, by
:func:`arcus.rainbow.trace_beams` (``method="grid"``: one grid cast of
:func:`arcus.rainbow.phase_function` per orientation, right to O(1/grid) and ~18 times
slower); the glints of all orientations, weighted by their power, are shared linearly
between the θ (and φ) samples asked for around them.
The orientations are quasi-random (a scrambled Halton sequence) and, for randomly
oriented crystals, confined to the prism's symmetry wedge, which leaves the table the
same and makes it converge many times faster than independent draws.  The 22° halo is the light of term p = 1 (two refractions, no internal
reflection: the library's p counts p − 1 internal reflections) through the 60° prisms
of the side faces, the 46° halo p = 1 through the 90° prisms of a side and an end face.

Crystals (:func:`hexagonal_prism`): a regular hexagonal prism, its axis (the c-axis) the
mesh's y, circumscribed radius 1 scaled by ``size``; a "column" has length/diameter 2, a
"plate" 0.2 (the diameter being the corner-to-corner width 2·size).
data/rainbow/make_crystals.py writes the same meshes as OFF files.

Frame: as arcus.rainbow: the light travels along +z, a scattering direction (θ, φ) has
θ from +z and φ from +x toward +y.  For crystals that know "up" (``orientation:
"horizontal"``) +y is the world's up as seen across the light: the sun stands at
elevation e, the light travels down at e, and the world's vertical is, in this frame,
(0, cos e, −sin e); x is horizontal.  The tables hold scattering directions d; an
observer sees that light in the sky at −d, θ from the sun on the opposite side: light
scattered toward φ appears toward φ + 180° around the sun.  So the circumzenithal arc,
above the sun, is at φ ≈ 270° in a table, and the parhelia (sundogs) near φ = 0° and
180° (a few degrees below, φ ≈ 356° and 184° for e = 20°, because they keep the sun's
elevation: :func:`parhelion_angle`).

"horizontal" means the c-axis vertical, as plates fall (sundogs, circumzenithal arc);
columns falling with their axes horizontal (tangent and Parry arcs) are not modelled.
"""

import math
import threading
import time

import numpy as np

from . import rainbow
from ._args import to_float, to_int, to_real_array
from ._errors import ArgumentError
from .context import _owned_context

#: Length over corner-to-corner diameter of each shape.
SHAPES = {"column": 2.0, "plate": 0.2}
ORIENTATIONS = ("random", "horizontal")
#: A spec's keys and their defaults (``shape`` has none).
SPEC_DEFAULTS = {"kind": "crystal", "size": 50e-6, "orientation": "random", "tilt_deg": 1.0,
                 "sun_elevation_deg": 0.0, "orientations": 2000, "seed": 1, "first_orientation": 0}
SPEC_KEYS = ("kind", "shape") + tuple(k for k in SPEC_DEFAULTS if k != "kind")
#: Rays per side of each orientation's cast (``method="grid"``).  A glint's power is the cast area of its
#: rays times the Fresnel products of its faces, the same for every ray of a flat face
#: sequence, so the grid enters only through the areas of the faces' regions (cells on
#: their boundaries: O(1/grid)).  At 64 a face's power is within ~1.5%, and the
#: orientation-averaged terms' shares within 1% of grid 384's; 48 is ~1.5x cheaper and
#: ~1.3x less accurate.
GRID = 64
#: How a table's glints are found: traced as beams (exact) or cast as a grid of rays.
METHODS = ("beams", "grid")
#: Orientations per beam trace: ~500 glints each, so a batch's arrays stay near 100 MB.
BEAM_BATCH = 4096
#: Terms p = 0..P traced: at 8 under 1% of the light is still inside a column (3: 9%).
MAX_BOUNCES = 8
#: The cast grid's warp (arcus.rainbow's alpha): uniform, as suits a polygonal shadow.
ALPHA = 1.0


# ---- closed forms -------------------------------------------------------------------


def minimum_deviation(n, apex_deg=60.0):
    """The minimum deviation [deg] of light through a prism of apex ``apex_deg`` and
    refractive index ``n``: D = 2 asin(n sin(A/2)) − A (symmetric passage).  Raises
    :class:`arcus.ArgumentError` where no light passes at minimum deviation
    (n sin(A/2) ≥ 1: total internal reflection)."""
    n = to_float(n, "n")
    a = to_float(apex_deg, "apex_deg")
    if not (n > 1 and math.isfinite(n)):
        raise ArgumentError("n must be a finite number above 1, got %r" % n)
    if not 0 < a < 180:
        raise ArgumentError("apex_deg must lie in (0, 180), got %r" % a)
    s = n * math.sin(math.radians(a) / 2)
    if s >= 1:
        raise ArgumentError("no light passes a %g° prism of index %g at minimum deviation (n sin(A/2) = %g ≥ 1)"
                            % (a, n, s))
    return math.degrees(2 * math.asin(s)) - a


def halo_angle(wavelength=550.0, apex_deg=60.0):
    """The inner edge [deg] of the halo of ice prisms of apex ``apex_deg`` at
    ``wavelength`` nm: the minimum deviation with ice's index (Warren & Brandt 2008);
    60° gives the 22° halo (21.8° at 550 nm), 90° the 46° halo."""
    return minimum_deviation(rainbow.refractive_index("ice", to_float(wavelength, "wavelength")), apex_deg)


def parhelion_angle(n, sun_elevation_deg):
    """The inner edge of a parhelion (sundog) for the sun at ``sun_elevation_deg``: its
    angular distance [deg] from the sun (a scattering angle θ) and its azimuth φ [deg] in
    the light frame above, (θ, φ) for the sundog on the −x side (the other is at 180° − φ).

    Plates with vertical axes refract in their 60° side prisms; projected onto the
    horizontal plane the light sees Bravais' index n' = sqrt(n² − sin² e)/cos e, so it
    turns in azimuth by Δ = 2 asin(n'/2) − 60° and stays at elevation e:
    cos θ = sin² e + cos² e cos Δ."""
    n = to_float(n, "n")
    e = math.radians(to_float(sun_elevation_deg, "sun_elevation_deg"))
    if not abs(e) < math.pi / 2:
        raise ArgumentError("sun_elevation_deg must lie in (-90, 90), got %r" % sun_elevation_deg)
    n_eff = math.sqrt(n * n - math.sin(e) ** 2) / math.cos(e)
    if n_eff / 2 >= 1:
        raise ArgumentError("no parhelion at sun elevation %g° (n' = %g)" % (sun_elevation_deg, n_eff))
    delta = math.radians(minimum_deviation(n_eff, 60.0))
    ce, se = math.cos(e), math.sin(e)
    # the scattered direction in the light frame (x horizontal, y up across the light)
    d = np.array([-ce * math.sin(delta), -se * ce * (1 - math.cos(delta)), se * se + ce * ce * math.cos(delta)])
    theta = math.degrees(math.acos(min(1.0, d[2])))
    phi = math.degrees(math.atan2(d[1], d[0])) % 360.0
    return theta, phi


# ---- crystals -----------------------------------------------------------------------


def hexagonal_prism(aspect):
    """A regular hexagonal prism of circumscribed radius 1, axis y, length 2·aspect:
    (vertices (12, 3), triangles (20, 3) int) wound counter-clockwise seen from outside.
    The same triangles as data/rainbow/make_crystals.py."""
    aspect = to_float(aspect, "aspect")
    if not (aspect > 0 and math.isfinite(aspect)):
        raise ArgumentError("aspect must be positive and finite, got %r" % aspect)
    s = math.sqrt(3) / 2
    ring = [(1.0, 0.0), (0.5, -s), (-0.5, -s), (-1.0, 0.0), (-0.5, s), (0.5, s)]
    vertices = [(x, aspect, z) for x, z in ring] + [(x, -aspect, z) for x, z in ring]
    triangles = []
    for k in range(6):
        a, b = k, (k + 1) % 6
        triangles += [(a, 6 + a, 6 + b), (a, 6 + b, b)]
    triangles += [(0, 1 + k, 2 + k) for k in range(4)]
    triangles += [(6, 8 + k, 7 + k) for k in range(4)]
    return np.array(vertices, dtype=float), np.array(triangles, dtype=np.int64)


def off_text(aspect):
    """hexagonal_prism(aspect) as an OFF file (no comment lines: OpenMesh's reader
    takes them for data)."""
    vertices, triangles = hexagonal_prism(aspect)
    lines = ["OFF", "%d %d 0" % (len(vertices), len(triangles))]
    lines += [" ".join(repr(float(c) + 0.0) for c in v) for v in vertices]
    lines += ["3 %d %d %d" % tuple(int(i) for i in t) for t in triangles]
    return "\n".join(lines) + "\n"


_meshes = {}
_mesh_lock = threading.Lock()


def crystal_mesh(shape, size):
    """The flat-faced :class:`arcus.rainbow.Mesh` of ``shape`` ("column", "plate") with
    circumscribed radius ``size`` metres, made from :func:`hexagonal_prism`'s arrays;
    one object per (shape, size), so the library's particle is made once per context.

    Its coordinates are rounded to single precision, as the library reads them from a
    mesh file (OpenMesh reads floats): the crystals are those of
    data/rainbow/crystals/*.off, and their tables those computed from these files."""
    if shape not in SHAPES:
        raise ArgumentError("shape must be one of %s, got %r" % (", ".join(map(repr, SHAPES)), shape))
    size = to_float(size, "size")
    if not (size > 0 and math.isfinite(size)):
        raise ArgumentError("size (the circumscribed radius, m) must be positive and finite, got %r" % size)
    key = (shape, size)
    with _mesh_lock:
        mesh = _meshes.get(key)
        if mesh is None:
            vertices, triangles = hexagonal_prism(SHAPES[shape])
            mesh = _meshes[key] = rainbow.Mesh.from_arrays(vertices.astype(np.float32).astype(np.float64), triangles,
                                                           scale=size, smooth=False)
        return mesh


def projected_areas(vertices, triangles, directions):
    """The areas of the mesh's shadows along unit ``directions`` (K, 3) in its own frame:
    half the sum over triangles of |area vector · direction| (a closed convex mesh)."""
    v = np.asarray(vertices, dtype=float)
    t = np.asarray(triangles)
    area_vectors = 0.5 * np.cross(v[t[:, 1]] - v[t[:, 0]], v[t[:, 2]] - v[t[:, 0]])
    return 0.5 * np.abs(np.asarray(directions, dtype=float) @ area_vectors.T).sum(axis=1)


# ---- orientations -------------------------------------------------------------------


def _axis_angle(axes, angles):
    """Rotations by ``angles`` about unit ``axes`` (K, 3), Rodrigues."""
    k = np.asarray(axes, dtype=float)
    c, s = np.cos(angles)[:, None, None], np.sin(angles)[:, None, None]
    kx = np.zeros((len(k), 3, 3))
    kx[:, 0, 1], kx[:, 0, 2], kx[:, 1, 2] = -k[:, 2], k[:, 1], -k[:, 0]
    kx[:, 1, 0], kx[:, 2, 0], kx[:, 2, 1] = k[:, 2], -k[:, 1], k[:, 0]
    outer = k[:, :, None] * k[:, None, :]
    return c * np.eye(3) + s * kx + (1 - c) * outer


def light_frame(sun_elevation_deg):
    """The rotation world -> light frame (world: x horizontal, y up, z horizontal away
    from the sun; light frame: the light along +z, tilted down by the elevation)."""
    e = math.radians(sun_elevation_deg)
    return np.array([[1.0, 0.0, 0.0], [0.0, math.cos(e), math.sin(e)], [0.0, -math.sin(e), math.cos(e)]])


#: The hexagonal prism's symmetries (D6h, 24 of them, mirrors included) map light
#: arriving from any direction to light arriving within one wedge of the crystal's frame:
#: its azimuth about the axis (y) within 30° of a corner (x), its polar angle from the
#: axis within 90°.  A mirror image of a crystal and its light scatters the same power
#: through the same angle θ, so for randomly oriented crystals sampling this wedge is
#: sampling every direction, 24 times more densely.
WEDGE_DEG = 30.0
#: Turning a prism by 60° about its axis leaves it unchanged: horizontal crystals (whose
#: φ-tables mirrors would change) need spins within 60° only.
SPIN_PERIOD_DEG = 60.0


def _scrambled_halton(dimensions, first, count, seed):
    """Points first .. first + count - 1 of a scrambled Halton sequence in [0, 1)^dimensions
    (scipy.stats.qmc), the same for one seed: any run of them is spread evenly in every
    dimension and pair, which the histogram of a few hundred orientations needs and
    independent draws do not give, and successive runs fill in between each other."""
    from scipy.stats import qmc
    sequence = qmc.Halton(d=dimensions, scramble=True, seed=np.random.default_rng(seed))
    sequence.fast_forward(first)
    return sequence.random(count)


def orientations(spec):
    """The spec's crystal -> light-frame rotations, (N, 3, 3), quasi-random from its
    ``seed``: "random": the light's direction in the crystal's frame (the rotation's last
    row) spread evenly over the prism's symmetry wedge (:data:`WEDGE_DEG`; uniform on
    SO(3) up to the prism's symmetries), a uniformly random turn about the light;
    "horizontal": the crystal's axis (its y) vertical, tilted by |N(0, tilt_deg)|
    toward a uniform azimuth, turned about the axis uniformly within
    :data:`SPIN_PERIOD_DEG`, then seen from the light frame of the sun's elevation.
    Both take the N points from ``first_orientation`` on of a scrambled Halton sequence,
    so a table's noise falls faster than independent draws' 1/√N (as N^-0.66 for the
    halo: bench/halo_bench.py), and tables that take successive runs of it (the sky's
    wavelengths: :func:`arcus.sweep.phase_tables`) average as one of all their points."""
    spec = normalise_spec(spec)
    count = spec["orientations"]
    u = _scrambled_halton(3, spec["first_orientation"], count, spec["seed"])
    if spec["orientation"] == "random":
        cos_polar, azimuth = u[:, 0], np.radians(WEDGE_DEG) * u[:, 1]
        sin_polar = np.sqrt(1 - cos_polar ** 2)
        light = np.stack([sin_polar * np.cos(azimuth), cos_polar, sin_polar * np.sin(azimuth)], axis=1)
        # two more rows, a and b = light × a, so that a × b = light: a proper rotation
        # whose last row is the light, then turned by u[:, 2] of a turn about it
        a = np.cross(light, [0.0, 0.0, 1.0])  # light never lies along z: sin_polar·sin(azimuth) < 0.5
        a /= np.linalg.norm(a, axis=1, keepdims=True)
        b = np.cross(light, a)
        turn = 2 * math.pi * u[:, 2:3]
        return np.stack([np.cos(turn) * a + np.sin(turn) * b, -np.sin(turn) * a + np.cos(turn) * b, light], axis=1)
    from scipy.special import erfinv
    spin = np.radians(SPIN_PERIOD_DEG) * u[:, 0]
    tilt = math.radians(spec["tilt_deg"]) * math.sqrt(2) * erfinv(u[:, 1])  # |N(0, σ)| by its inverse CDF
    toward = 2 * math.pi * u[:, 2]
    about_axis = _axis_angle(np.tile([0.0, 1.0, 0.0], (count, 1)), spin)
    tilt_axes = np.stack([np.cos(toward), np.zeros(count), np.sin(toward)], axis=1)
    return light_frame(spec["sun_elevation_deg"]) @ _axis_angle(tilt_axes, tilt) @ about_axis


def normalise_spec(spec):
    """``spec`` checked, with defaults filled in (a new dict); raises
    :class:`arcus.ArgumentError` naming what is wrong."""
    if not isinstance(spec, dict):
        raise ArgumentError("spec must be a dict, got %r" % (spec,))
    unknown = sorted(set(spec) - set(SPEC_KEYS), key=str)
    if unknown:
        raise ArgumentError("spec has unknown keys %s (known: %s)" % (unknown, ", ".join(SPEC_KEYS)))
    out = dict(SPEC_DEFAULTS)
    out.update(spec)
    if out["kind"] != "crystal":
        raise ArgumentError("spec['kind'] must be 'crystal', got %r" % (out["kind"],))
    if "shape" not in spec:
        raise ArgumentError("spec needs a 'shape': one of %s" % ", ".join(map(repr, SHAPES)))
    if out["shape"] not in SHAPES:
        raise ArgumentError("spec['shape'] must be one of %s, got %r" % (", ".join(map(repr, SHAPES)), out["shape"]))
    size = to_float(out["size"], "spec['size']")
    if not (size > 0 and math.isfinite(size)):
        raise ArgumentError("spec['size'] (the circumscribed radius, m) must be positive and finite, got %r" % size)
    out["size"] = size
    if out["orientation"] not in ORIENTATIONS:
        raise ArgumentError("spec['orientation'] must be one of %s, got %r"
                            % (", ".join(map(repr, ORIENTATIONS)), out["orientation"]))
    tilt = to_float(out["tilt_deg"], "spec['tilt_deg']")
    if not 0 <= tilt <= 90:
        raise ArgumentError("spec['tilt_deg'] must lie in [0, 90], got %r" % tilt)
    out["tilt_deg"] = tilt
    elevation = to_float(out["sun_elevation_deg"], "spec['sun_elevation_deg']")
    if not -90 < elevation < 90:
        raise ArgumentError("spec['sun_elevation_deg'] must lie in (-90, 90), got %r" % elevation)
    out["sun_elevation_deg"] = elevation
    out["orientations"] = to_int(out["orientations"], "spec['orientations']", 1, 10 ** 8)
    out["seed"] = to_int(out["seed"], "spec['seed']", 0, 2 ** 63 - 1)
    out["first_orientation"] = to_int(out["first_orientation"], "spec['first_orientation']", 0, 10 ** 12)
    return out


# ---- the table ----------------------------------------------------------------------


def _uniform(values, name, low, high, periodic=False):
    """(first bin's lower edge, step) of bins centred on uniformly spaced ``values``."""
    a = to_real_array(values, name)
    if a.ndim != 1 or a.size < 2:
        raise ArgumentError("%s must be a 1-D array of at least 2 uniformly spaced angles [deg], got shape %s"
                            % (name, a.shape))
    bad = ~np.isfinite(a) if periodic else ~((a >= low) & (a <= high))
    if bad.any():
        raise ArgumentError("%s[%d] must be %s, got %r" % (name, int(np.flatnonzero(bad)[0]),
                                                           "finite" if periodic else "within [%g, %g]" % (low, high),
                                                           float(a[bad][0])))
    step = (a[-1] - a[0]) / (a.size - 1)
    if not step > 0 or np.max(np.abs(np.diff(a) - step)) > 1e-9 * max(1.0, abs(step)):
        raise ArgumentError("%s must increase in uniform steps (bins are centred on them)" % name)
    if periodic and step * a.size > 360 + 1e-9:
        raise ArgumentError("%s spans more than 360° (%d bins of %g°)" % (name, a.size, step))
    return a, a[0] - step / 2, step


def _linear_deposit(x, first, step, count, periodic):
    """The two samples (first + k·step) bracketing each x and their weights, as
    [(k0, w0), (k1, w1)]: a glint's power shared linearly between them, a tent kernel
    one step wide each side instead of a bin's box, so that where a glint falls inside
    its bin no longer shows (the box's aliasing is a halo's rings of noise).  An axis
    covers x within half a step of its first and last samples, whose outer halves
    fold onto them (power stays in the table); a periodic axis (a whole circle of φ)
    wraps round instead.  x that no sample covers gets k = -1 and weight 0."""
    u = (np.asarray(x, dtype=float) - first) / step
    k0 = np.floor(u).astype(np.int64)
    w1 = u - k0
    k1 = k0 + 1
    if periodic:
        return [(np.mod(k0, count), 1.0 - w1), (np.mod(k1, count), w1)]
    covered = (u >= -0.5) & (u < count - 0.5)
    k0, k1 = np.clip(k0, 0, count - 1), np.clip(k1, 0, count - 1)
    return [(np.where(covered, k0, -1), np.where(covered, 1.0 - w1, 0.0)),
            (np.where(covered, k1, -1), np.where(covered, w1, 0.0))]


def crystal_table(spec, wavelength, theta, phi=None, *, method="beams", grid=GRID, max_bounces=MAX_BOUNCES,
                  edge_rays=True, rotations=None, context=None):
    """The orientation-averaged phase function and cross-sections of the ice crystals of
    ``spec`` at ``wavelength`` nm (one number, within ice's 199-1100 nm), in geometric
    optics (no diffraction, no interference).

    Args:
        spec: a dict (JSON-serialisable) with keys ``kind`` ("crystal"), ``shape``
            ("column": length/diameter 2, "plate": 0.2), ``size`` (circumscribed radius,
            m; 50e-6), ``orientation`` ("random": uniform on SO(3); "horizontal": the axis
            vertical with a tilt of |N(0, tilt_deg)| toward a uniform azimuth and a
            uniform turn about the axis), ``tilt_deg`` (1.0), ``sun_elevation_deg`` (0.0;
            horizontal crystals only), ``orientations`` (2000), ``seed`` (1) and
            ``first_orientation`` (0): the orientations, points first_orientation ..
            first_orientation + orientations - 1 of a quasi-random sequence
            (:func:`orientations`), identical for one seed.
        theta: uniformly spaced scattering angles [deg] (at least 2) on which the bins are
            centred (bin edges halfway between; the first and last bins half a step out,
            clipped to [0, 180]).  Each glint's power is shared linearly between the
            two samples around it (:func:`_linear_deposit`; in φ too), which smooths
            the table by a tent one step wide each side: keep the step within the
            sun's radius (0.27°), which smooths it as much in the sky anyway.
        phi: None: a 1-D table in θ (for horizontal crystals the average over azimuth);
            else uniformly spaced azimuths [deg] spanning at most 360°, bins centred on
            them (periodic): a 2-D table (F, T).  Randomly oriented crystals have no
            preferred azimuth: their 1-D table is repeated over φ.
        method: "beams" (the default): each orientation's glints traced as beams,
            exactly (:func:`arcus.rainbow.trace_beams`); "grid": cast as a grid of
            rays (:func:`arcus.rainbow.phase_function`), whose faces' shares are right
            to O(1/grid), about 10 times slower at grid 32 (docs/benchmarks.md).
        grid: "grid" only: rays per side of each orientation's cast (see :data:`GRID`).
        max_bounces: P, terms p = 0..P (p − 1 internal reflections).
        edge_rays: "grid" only, arcus.rainbow's: grid points just outside the shadow move onto its
            edge (on flat faces a thousandth of a cell inside it).  On (the default) the
            shares of the faces' light are right to about 1% at grid 64 and the books
            close; off, the cells along the silhouette are left out, which biases the
            terms' shares by a few % (p = 1 +2.6% for columns at grid 64).
        rotations: (N, 3, 3) crystal -> light-frame rotations to average over instead
            of the spec's (its ``orientations`` and ``seed`` are then not used), e.g.
            another distribution of orientations.
        context: an arcus.Context, reused for every orientation (else a new one).

    Returns a dict:
        phase: (T,) or (F, T) per steradian: the power of the glints falling in each
            bin over the bin's solid angle, normalised by all the scattered power of
            p = 0..P (light outside the table's bins counts toward the normalisation,
            so the phase integrates to 1 over the whole sphere, to less over a partial
            table).
        per_term: (P+1, T) or (P+1, F, T): the same for each term p alone (they sum to
            ``phase``).
        cross_section: [m²] the orientation-averaged power scattered in p = 0..P per unit
            irradiance (the glints' sum; a flat crystal has no other light).
        intercepted: [m²] the mean projected area (exact, from the geometry).
        extinction: [m²] 2 × intercepted (the other half is diffraction, not in ``phase``).
        remaining: the fraction of the intercepted power still inside after P (weighted by
            projected area).
        lost: the fraction of the intercepted power the cast's books miss (rounding:
            below 1e-5): cross_section + (remaining + lost) · intercepted = intercepted.
        theta, phi, wavelength, refractive_index, spec (normalised), grid, max_bounces,
        seconds, and cast_area_ratio: the cast's intercepted area over the exact one
        (the grid's silhouette loss, corrected for: see below).

    Each orientation's glint cross-sections are scaled by exact/cast projected area, so
    the absolute cross-sections do not depend on the grid's resolution of the silhouette;
    the fractions per glint are the cast's.
    """
    spec = normalise_spec(spec)
    if np.ndim(wavelength) != 0:
        raise ArgumentError("wavelength must be one number (nm); call once per wavelength, got %r" % (wavelength,))
    wavelength = to_float(wavelength.item() if isinstance(wavelength, np.ndarray) else wavelength, "wavelength")
    n = rainbow.refractive_index("ice", wavelength)  # raises outside ice's range
    theta, theta0, dtheta = _uniform(theta, "theta", 0.0, 180.0)
    two_d = phi is not None
    if two_d:
        phi, phi0, dphi = _uniform(phi, "phi", None, None, periodic=True)
    if method not in METHODS:
        raise ArgumentError("method must be one of %s, got %r" % (", ".join(map(repr, METHODS)), method))
    grid = to_int(grid, "grid", 4, 8192)
    max_bounces = to_int(max_bounces, "max_bounces", 0, rainbow.MAX_BOUNCES)
    t_start = time.perf_counter()

    mesh = crystal_mesh(spec["shape"], spec["size"])
    if rotations is None:
        rotations = orientations(spec)
    else:
        rotations = to_real_array(rotations, "rotations")
        if rotations.ndim != 3 or rotations.shape[1:] != (3, 3) or len(rotations) == 0:
            raise ArgumentError("rotations must be an array of shape (N, 3, 3), got %s" % (rotations.shape,))
        if not (np.allclose(rotations @ rotations.transpose(0, 2, 1), np.eye(3), atol=1e-9)
                and np.all(np.linalg.det(rotations) > 0)):
            raise ArgumentError("rotations must be proper rotation matrices (R Rᵀ = 1, det R = +1)")
    vertices, triangles = hexagonal_prism(SHAPES[spec["shape"]])
    # the light (+z) in each crystal's frame: Rᵀ z
    exact = projected_areas(vertices, triangles, rotations[:, 2, :]) * spec["size"] ** 2

    # θ from +z, φ from +x toward +y; each glint's power shared between the two samples
    # that bracket it (in φ too, for 2-D tables of horizontal crystals)
    edges = np.clip(theta0 + dtheta * np.arange(theta.size + 1), 0.0, 180.0)
    ring = np.cos(np.radians(edges[:-1])) - np.cos(np.radians(edges[1:]))  # solid angle / Δφ
    terms_n = max_bounces + 1
    by_phi = two_d and spec["orientation"] != "random"
    hist = np.zeros(terms_n * (phi.size if by_phi else 1) * theta.size)

    def deposit(d, p, w):
        p = p.astype(np.int64)
        th = np.degrees(np.arccos(np.clip(d[:, 2], -1.0, 1.0)))
        th_cells = _linear_deposit(th, theta[0], dtheta, theta.size, periodic=False)
        if not by_phi:
            for ti, tw in th_cells:
                ok = ti >= 0
                hist[:] += np.bincount(p[ok] * theta.size + ti[ok], weights=(w * tw)[ok], minlength=hist.size)
            return
        ph = np.degrees(np.arctan2(d[:, 1], d[:, 0]))
        whole_circle = abs(phi.size * dphi - 360.0) < 1e-9
        ph_cells = _linear_deposit(np.mod(ph - phi0, 360.0) + phi0, phi[0], dphi, phi.size, whole_circle)
        for ti, tw in th_cells:
            for fi, fw in ph_cells:
                ok = (ti >= 0) & (fi >= 0)
                flat = (p[ok] * phi.size + fi[ok]) * theta.size + ti[ok]
                hist[:] += np.bincount(flat, weights=(w * tw * fw)[ok], minlength=hist.size)

    total = remaining = lost = cast_area = 0.0
    with _owned_context(context) as ctx:
        if method == "beams":
            for first in range(0, len(rotations), BEAM_BATCH):
                batch = rotations[first:first + BEAM_BATCH]
                g = rainbow.trace_beams(mesh, wavelength, batch, max_bounces=max_bounces, material="ice", context=ctx)
                deposit(g["direction"], g["term"], g["cross_section"])
                shadows = g["stats"]["intercepted"] * len(batch)
                total += float(g["cross_section"].sum())
                cast_area += shadows
                remaining += g["stats"]["remaining"] * shadows
                lost += (1 - float(np.sum(g["stats"]["scattered"])) - g["stats"]["remaining"]) * shadows
        else:
            query = np.zeros(1)
            pending = []  # glints deposited a few hundred orientations at a time

            def flush():
                if pending:
                    deposit(*(np.concatenate(column) for column in zip(*pending)))
                    pending.clear()

            for rotation, area in zip(rotations, exact):
                r = rainbow.phase_function(mesh, wavelength, query, grid=grid, max_bounces=max_bounces,
                                           material="ice", rotation=rotation, coherent=False, alpha=ALPHA,
                                           edge_rays=edge_rays, context=ctx)
                cast = r.stats["intercepted"]
                if not cast > 0:
                    raise ArgumentError("grid %d is too coarse: a cast missed the crystal" % grid)
                cast_area += cast
                remaining += r.stats["remaining"] * area
                lost += (1 - float(np.sum(r.stats["scattered"])) - r.stats["remaining"]) * area
                g = r.glints
                if g is not None:
                    power = g["cross_section"] * (area / cast)
                    pending.append((g["direction"], g["term"], power))
                    total += float(power.sum())
                    if len(pending) == 256:
                        flush()
            flush()
    count = len(rotations)
    intercepted = float(exact.mean())
    if by_phi:
        per_term = hist.reshape(terms_n, phi.size, theta.size) / (ring * math.radians(dphi))
    else:
        per_term = hist.reshape(terms_n, theta.size) / (ring * 2 * math.pi)
        if two_d:  # random orientation: no preferred azimuth
            per_term = np.repeat(per_term[:, None, :], phi.size, axis=1)
    if total > 0:
        per_term /= total
    return {
        "phase": per_term.sum(axis=0),
        "per_term": per_term,
        "cross_section": total / count,  # per crystal, averaged over orientations
        "intercepted": intercepted,
        "extinction": 2 * intercepted,
        "remaining": float(remaining / exact.sum()),
        "lost": float(lost / exact.sum()),
        "theta": theta,
        "phi": phi if two_d else None,
        "wavelength": wavelength,
        "refractive_index": n,
        "spec": spec,
        "method": method,
        "grid": grid,
        "max_bounces": max_bounces,
        "cast_area_ratio": float(cast_area / exact.sum()),
        "seconds": time.perf_counter() - t_start,
    }
