"""Lorenz–Mie scattering by a sphere and its Debye series (thesis §4.4.1.1, §5.5.1).

::

    import numpy as np
    import arcus.mie as mie

    theta = np.linspace(0.0, 180.0, 3601)                   # degrees
    m = mie.phase_function(250e-6, 650.0, theta)            # water at 20 °C
    print(m.unpolarized, m.q_ext, m.q_sca, m.g)
    d = mie.debye(250e-6, 650.0, theta, max_p=3)            # terms p = 0..3
    print(d.unpolarized[:, 2])                              # the primary rainbow's term

The reference the ray-traced phase functions of :mod:`arcus.rainbow` are checked
against: the Debye term p is the light leaving after p − 1 internal reflections, with
every wave effect (Airy rainbow, supernumeraries, interference).  Host code in the
library (no context, no device).

Units: the radius in metres, the wavelength in nanometres (in vacuum; the air around
the sphere has n = 1), angles in degrees.
``n`` is the sphere's index relative to air, real or complex ``n + iκ`` with κ ≥ 0
(time dependence e^{−iωt}, Bohren & Huffman); None: water's real index at the
wavelength and ``temperature_k`` (:func:`arcus.rainbow.refractive_index`).  Phase
functions are per steradian, normalised so that the whole sphere's ``unpolarized``
integrates to 1; "parallel" is the |S2|² part, "perpendicular" the |S1|² part, for
unpolarised incident light, and unpolarized their sum.
"""

import math
from ctypes import byref
from dataclasses import dataclass

import numpy as np

from . import _lib
from ._args import to_float, to_int
from ._errors import ArgumentError
from ._lib import lib
from .rainbow import _angles, refractive_index, water_temperature_k


@dataclass(frozen=True, eq=False)
class MieResult:
    """Lorenz–Mie for one sphere (:func:`phase_function`).

    Attributes:
        theta: (T,) scattering angles [deg].
        parallel, perpendicular, unpolarized: (T,) phase function per steradian
            (unpolarized = parallel + perpendicular integrates to 1 over the sphere).
        s1, s2: (T,) complex amplitudes (S1 perpendicular, S2 parallel to the
            scattering plane; Bohren & Huffman's convention).
        q_ext, q_sca, q_back, g: extinction, scattering and backscatter efficiencies
            (cross-section / πa²) and the asymmetry parameter.
        n: the relative refractive index used (complex).
        size_parameter: x = 2πa/λ.
        radius [m], wavelength [nm].
    """

    theta: np.ndarray
    parallel: np.ndarray
    perpendicular: np.ndarray
    unpolarized: np.ndarray
    s1: np.ndarray
    s2: np.ndarray
    q_ext: float
    q_sca: float
    q_back: float
    g: float
    n: complex
    size_parameter: float
    radius: float
    wavelength: float


@dataclass(frozen=True, eq=False)
class DebyeResult:
    """The Debye-series terms p = 0..max_p of Lorenz–Mie (:func:`debye`).

    Attributes:
        theta: (T,) scattering angles [deg].
        parallel, perpendicular, unpolarized: (T, max_p + 1): term p's phase function in
            Mie's normalisation (the whole sphere's scattering integrates to 1), so the
            terms compare directly with :class:`MieResult` and with
            :attr:`arcus.rainbow.PhaseResult.per_bounce`.  p = 0 is external reflection
            without diffraction.
        s1, s2: (T, max_p + 1) complex amplitudes of each term.
        n, size_parameter, radius [m], wavelength [nm], max_p.
    """

    theta: np.ndarray
    parallel: np.ndarray
    perpendicular: np.ndarray
    unpolarized: np.ndarray
    s1: np.ndarray
    s2: np.ndarray
    n: complex
    size_parameter: float
    radius: float
    wavelength: float
    max_p: int


def _inputs(radius, wavelength, theta, n, temperature_k):
    radius = to_float(radius, "radius")
    wavelength = to_float(wavelength, "wavelength")
    theta = _angles(theta, "theta", 0.0, 180.0)
    if n is None:
        n = complex(refractive_index("water", wavelength, temperature_k))
    else:
        if isinstance(n, (bool, np.bool_)) or not isinstance(n, (int, float, complex, np.number)):
            raise ArgumentError("n must be a real or complex number (or None for water), got %r" % (n,))
        n = complex(n)
    return radius, wavelength, theta, n


def _size_parameter(radius, wavelength):
    return 2 * math.pi * radius / (wavelength * 1e-9)


def _complex(pairs, shape):
    """(re, im) pairs as a complex array of ``shape``."""
    return (pairs[0::2] + 1j * pairs[1::2]).reshape(shape)


def phase_function(radius, wavelength, theta, n=None, temperature_k=293.15, *, temperature=None):
    """Lorenz–Mie for a sphere of ``radius`` metres at ``wavelength`` nm and angles
    ``theta`` degrees: a :class:`MieResult` (phase functions, amplitudes S1 and S2,
    efficiencies).  ``n``: the relative index (complex allowed; None: water at
    ``temperature_k`` kelvin; ``temperature`` in °C is deprecated)."""
    temperature_k = water_temperature_k(temperature_k, temperature)
    radius, wavelength, theta, n = _inputs(radius, wavelength, theta, n, temperature_k)
    count = theta.size
    s1, s2 = np.zeros(2 * count), np.zeros(2 * count)
    par, perp = np.zeros(count), np.zeros(count)
    eff = _lib.MieEfficienciesStruct()
    _lib.check(lib.arcus_rainbow_mie(radius, wavelength, n.real, n.imag, count, _lib.ptr(theta), _lib.ptr(s1), _lib.ptr(s2),
                             _lib.ptr(par), _lib.ptr(perp), byref(eff)))
    return MieResult(theta=theta.copy(), parallel=par, perpendicular=perp, unpolarized=par + perp,
                     s1=_complex(s1, (count,)), s2=_complex(s2, (count,)), q_ext=eff.q_ext, q_sca=eff.q_sca,
                     q_back=eff.q_back, g=eff.g, n=n, size_parameter=_size_parameter(radius, wavelength),
                     radius=radius, wavelength=wavelength)


def debye(radius, wavelength, theta, n=None, max_p=3, temperature_k=293.15, *, temperature=None):
    """The Debye-series terms p = 0..``max_p`` of Lorenz–Mie for a sphere of ``radius``
    metres at ``wavelength`` nm and angles ``theta`` degrees: a :class:`DebyeResult`
    (arrays of shape (len(theta), max_p + 1))."""
    temperature_k = water_temperature_k(temperature_k, temperature)
    radius, wavelength, theta, n = _inputs(radius, wavelength, theta, n, temperature_k)
    max_p = to_int(max_p, "max_p", 0, 2 ** 32 - 1)
    count, terms = theta.size, max_p + 1
    s1, s2 = np.zeros(2 * count * terms), np.zeros(2 * count * terms)
    par, perp = np.zeros(count * terms), np.zeros(count * terms)
    _lib.check(lib.arcus_rainbow_mie_debye(radius, wavelength, n.real, n.imag, max_p, count, _lib.ptr(theta), _lib.ptr(s1),
                                   _lib.ptr(s2), _lib.ptr(par), _lib.ptr(perp)))
    par, perp = par.reshape(count, terms), perp.reshape(count, terms)
    return DebyeResult(theta=theta.copy(), parallel=par, perpendicular=perp, unpolarized=par + perp,
                       s1=_complex(s1, (count, terms)), s2=_complex(s2, (count, terms)), n=n,
                       size_parameter=_size_parameter(radius, wavelength), radius=radius, wavelength=wavelength,
                       max_p=max_p)
