"""Index-of-refraction fields: plain, immutable descriptions of a medium.

A field object holds only its parameters.  The library object behind it
(``arcus_field_create_*``) is made the first time a :class:`arcus.Context` needs it
and cached on that context for as long as both live, so one description can be used
with several contexts (devices) and costs one library object per context.  Because
the cache is keyed by the object itself, the descriptions are frozen: change a
parameter by making a new field.

The library checks the parameters' values (a radius <= 0, a NaN in a grid, ...) when
it creates the field, so such mistakes surface as :class:`arcus.Error` on first use
(``evaluate`` or ``Context.advance``), not here; shapes and types are checked here.
"""

import ctypes
import os
from collections import namedtuple
from dataclasses import dataclass, field

import numpy as np

from . import _lib
from ._args import to_bool, to_float, to_int, to_path, to_real_array, to_vec3
from ._errors import ArgumentError
from ._lib import lib

__all__ = [
    "Field",
    "Constant",
    "Linear",
    "LinearN2",
    "Luneburg",
    "FishEye",
    "Inversion",
    "StandardAtmosphere",
    "Grid",
    "GridFile",
]


def _normalise(obj, **converted):
    # Frozen dataclasses refuse normal assignment, which is the point; __post_init__
    # still has to store the converted values.
    for name, value in converted.items():
        object.__setattr__(obj, name, value)


class Field:
    """Base class of every field description.

    Subclasses implement ``_create(ctx_handle, out)``, calling the matching
    ``arcus_field_create_*`` and returning its status; :class:`arcus.Context` does the
    caching and error handling.  (A scene's field, :class:`arcus.SceneField`, is no
    description but the library object of one context.)
    """

    __slots__ = ()

    def _create(self, ctx_handle, out):
        raise NotImplementedError

    def _handle_on(self, context):
        """The library handle this field always has on ``context``; None: ``context``
        creates one with ``_create`` and caches it (every description does that)."""
        return None

    def evaluate(self, context, positions):
        """n and its gradient at ``positions`` ((N, 3) or (3,)), on the host.

        Uses ``arcus_field_evaluate``: double precision, the same formulas as the
        kernels.  Returns ``(n, gradient)`` with shapes (N,) and (N, 3).
        """
        return context.evaluate(self, positions)


@dataclass(frozen=True, eq=False)
class Constant(Field):
    """A homogeneous medium, n everywhere.  Rays are straight (no integrator runs)."""

    n: float

    def __post_init__(self):
        _normalise(self, n=to_float(self.n, "n"))

    def _create(self, ctx_handle, out):
        return lib.arcus_field_create_constant(ctx_handle, self.n, out)


@dataclass(frozen=True, eq=False)
class Linear(Field):
    """n = n0 + gradient · x: a linear index (rays are catenaries)."""

    n0: float
    gradient: tuple

    def __post_init__(self):
        _normalise(self, n0=to_float(self.n0, "n0"), gradient=to_vec3(self.gradient, "gradient"))

    def _create(self, ctx_handle, out):
        return lib.arcus_field_create_linear(ctx_handle, self.n0, _lib.vec3(self.gradient), out)


@dataclass(frozen=True, eq=False)
class LinearN2(Field):
    """n² = a + k · x: a linear squared index (rays are parabolas)."""

    a: float
    k: tuple

    def __post_init__(self):
        _normalise(self, a=to_float(self.a, "a"), k=to_vec3(self.k, "k"))

    def _create(self, ctx_handle, out):
        return lib.arcus_field_create_linear_n2(ctx_handle, self.a, _lib.vec3(self.k), out)


@dataclass(frozen=True, eq=False)
class Luneburg(Field):
    """Luneburg lens: n = sqrt(2 - (r/R)²) inside radius R about ``center``, 1 outside."""

    center: tuple
    radius: float

    def __post_init__(self):
        _normalise(self, center=to_vec3(self.center, "center"), radius=to_float(self.radius, "radius"))

    def _create(self, ctx_handle, out):
        return lib.arcus_field_create_luneburg(ctx_handle, _lib.vec3(self.center), self.radius, out)


@dataclass(frozen=True, eq=False)
class FishEye(Field):
    """Maxwell's fish-eye: n = n0 / (1 + (r/R)²) about ``center``."""

    center: tuple
    radius: float
    n0: float

    def __post_init__(self):
        _normalise(
            self,
            center=to_vec3(self.center, "center"),
            radius=to_float(self.radius, "radius"),
            n0=to_float(self.n0, "n0"),
        )

    def _create(self, ctx_handle, out):
        return lib.arcus_field_create_fisheye(ctx_handle, _lib.vec3(self.center), self.radius, self.n0, out)


Inversion = namedtuple("Inversion", ["base", "top", "delta_t"])
Inversion.__doc__ = """An inversion layer of a :class:`StandardAtmosphere` (heights in metres, K).

The temperature is offset by ``delta_t`` below ``base``; the offset fades linearly to
zero at ``top`` and the standard profile holds above.  ``delta_t < 0`` puts cold air
under warm (superior mirages, Novaya Zemlya); ``delta_t > 0`` with ``base = 0`` makes a
hot ground layer (inferior mirages).  A plain ``(base, top, delta_t)`` tuple works too.
"""


@dataclass(frozen=True, eq=False)
class StandardAtmosphere(Field):
    """Layered air after the US Standard Atmosphere 1976, with optional inversions.

    Args:
        spherical: False: flat, height is y (y = 0 at sea level).  True: a sphere of
            radius :data:`arcus.EARTH_RADIUS` centred on the origin.  A bool only.
        wavelength: nm, within the range of Ciddor's dispersion formula (300..1690 nm).
            Per-ray wavelengths given to :meth:`arcus.Context.advance` replace it.
        inversions: a sequence of :class:`Inversion` or ``(base, top, delta_t)`` tuples.
        sea_level_temperature: K.
        sea_level_pressure: Pa.

    The defaults are those of ``arcus_atmosphere_desc_init``.
    """

    spherical: bool = False
    wavelength: float = 550.0
    inversions: tuple = ()
    sea_level_temperature: float = 288.15
    sea_level_pressure: float = 101325.0

    def __post_init__(self):
        inversions = []
        for i, layer in enumerate(self.inversions):
            try:
                base, top, delta_t = layer
            except (TypeError, ValueError):
                raise ArgumentError("inversions[%d] must be (base, top, delta_t), got %r" % (i, layer)) from None
            inversions.append(
                Inversion(
                    to_float(base, "inversions[%d].base" % i),
                    to_float(top, "inversions[%d].top" % i),
                    to_float(delta_t, "inversions[%d].delta_t" % i),
                )
            )
        _normalise(
            self,
            spherical=to_bool(self.spherical, "spherical"),
            wavelength=to_float(self.wavelength, "wavelength"),
            inversions=tuple(inversions),
            sea_level_temperature=to_float(self.sea_level_temperature, "sea_level_temperature"),
            sea_level_pressure=to_float(self.sea_level_pressure, "sea_level_pressure"),
        )

    def _create(self, ctx_handle, out):
        desc = _lib.AtmosphereDescStruct()
        # Start from the library's defaults so any field the header adds later keeps
        # a sane value, then state every parameter this description holds.
        status = lib.arcus_atmosphere_desc_init(ctypes.byref(desc))
        if status != 0:
            return status
        layers = (_lib.InversionStruct * len(self.inversions))(*self.inversions)
        desc.spherical = int(self.spherical)
        desc.wavelength = self.wavelength
        desc.sea_level_temperature = self.sea_level_temperature
        desc.sea_level_pressure = self.sea_level_pressure
        desc.inversion_count = len(self.inversions)
        desc.inversions = ctypes.cast(layers, ctypes.POINTER(_lib.InversionStruct)) if self.inversions else None
        return lib.arcus_field_create_atmosphere(ctx_handle, ctypes.byref(desc), out)


def _dims(shape):
    """numpy shape (nz, ny, nx) -> the C API's uint32 dims[3] = (nx, ny, nz)."""
    return (ctypes.c_uint32 * 3)(*reversed(shape))


def _grid_shape(shape):
    """(nz, ny, nx) as three ints that fit the C API's uint32 dims."""
    try:
        items = tuple(shape)
    except TypeError:
        items = ()
    if len(items) != 3:
        raise ArgumentError("shape must be three integers (nz, ny, nx), got %r" % (shape,))
    return tuple(to_int(s, "shape[%d]" % axis, 1, 2**32 - 1) for axis, s in enumerate(items))


@dataclass(frozen=True, eq=False)
class Grid(Field):
    """A 3D voxel grid of n, interpolated trilinearly.

    Args:
        values: a 3D array indexed ``values[k, j, i]`` = ``[z][y][x]``: n at
            ``origin + (i, j, k) * spacing``.  Its C-order flattening is exactly the C
            API's layout ``values[(k*ny + j)*nx + i]``.  Copied (and made read-only).
        origin: (x, y, z) position of ``values[0, 0, 0]``.
        spacing: (x, y, z) distance between neighbouring samples.

    Outside the grid the face values extend outwards (zero gradient across the face).
    """

    values: np.ndarray = field(repr=False)
    origin: tuple
    spacing: tuple

    def __post_init__(self):
        values = np.array(to_real_array(self.values, "values"), order="C", copy=True)
        if values.ndim != 3:
            raise ArgumentError("values must be a 3D array indexed [z][y][x], got shape %s" % (values.shape,))
        values.flags.writeable = False
        _normalise(
            self,
            values=values,
            origin=to_vec3(self.origin, "origin"),
            spacing=to_vec3(self.spacing, "spacing"),
        )

    @property
    def dims(self):
        """(nx, ny, nz), the order the C API takes them in."""
        return tuple(reversed(self.values.shape))

    def __repr__(self):
        return "Grid(shape=%s, origin=%s, spacing=%s)" % (self.values.shape, self.origin, self.spacing)

    def _create(self, ctx_handle, out):
        return lib.arcus_field_create_grid(
            ctx_handle,
            _lib.ptr(self.values),
            _dims(self.values.shape),
            _lib.vec3(self.origin),
            _lib.vec3(self.spacing),
            out,
        )

    @staticmethod
    def from_file(path, shape, origin, spacing, dtype="float32"):
        """A grid read by the library from a raw little-endian file.

        Args:
            path: the file (str, bytes or os.PathLike): nx*ny*nz little-endian values,
                in the order of ``values`` above.
            shape: (nz, ny, nx), i.e. the numpy shape the data would have as ``values``
                (so ``Grid.from_file(p, grid.values.shape, ...)`` round-trips).
            origin, spacing: as for :class:`Grid`.
            dtype: ``"float32"`` or ``"float64"``.

        Returns a :class:`GridFile`; the file is read when the field is first used.
        """
        return GridFile(path, shape, origin, spacing, dtype)


_SCALAR_TYPES = {"float32": 0, "float64": 1}  # arcus_scalar_type


@dataclass(frozen=True, eq=False)
class GridFile(Field):
    """A :class:`Grid` whose values the library reads from a raw file; see :meth:`Grid.from_file`."""

    path: str
    shape: tuple
    origin: tuple
    spacing: tuple
    dtype: str = "float32"

    def __post_init__(self):
        try:
            dtype = np.dtype(self.dtype)
        except TypeError:
            dtype = None
        # The file is little-endian: a big-endian dtype (">f4") would be misread.
        if dtype is None or dtype.name not in _SCALAR_TYPES or dtype != dtype.newbyteorder("<"):
            raise ArgumentError("dtype must be 'float32' or 'float64' (little-endian), got %r" % (self.dtype,))
        to_path(self.path, "path")  # refused here, not truncated at a NUL by ctypes later
        _normalise(
            self,
            path=os.fspath(self.path),
            shape=_grid_shape(self.shape),
            origin=to_vec3(self.origin, "origin"),
            spacing=to_vec3(self.spacing, "spacing"),
            dtype=dtype.name,
        )

    def _create(self, ctx_handle, out):
        return lib.arcus_field_create_grid_from_file(
            ctx_handle,
            to_path(self.path, "path"),
            _SCALAR_TYPES[self.dtype],
            _dims(self.shape),
            _lib.vec3(self.origin),
            _lib.vec3(self.spacing),
            out,
        )
