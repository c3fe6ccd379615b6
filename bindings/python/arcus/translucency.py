"""Translucent materials: the dipole model of subsurface light (thesis §3.1.4, with eq.
3.7 corrected; Jensen et al. 2001), the measured materials, and the inversion from what a
photograph shows to coefficients (Jensen & Buhler 2002).  docs/translucency.md.

Units are the C API's (arcus_translucency.h): coefficients in mm⁻¹, distances in mm,
R_d per mm², three channels R, G, B.

>>> marble = Dipole.from_material("marble")
>>> marble.total_reflectance          # (3,) closed form, = ∫ 2πr R_d(r) dr
>>> marble.Rd([0.5, 1.0, 2.0])        # (3, 3): distances × channels
>>> Dipole.from_reflectance(marble.total_reflectance, marble.diffuse_length, eta=1.5)
"""

import warnings
from ctypes import byref, c_char_p, c_double

import numpy as np

from . import _lib
from ._args import to_float, to_real_array
from ._errors import ArgumentError
from ._lib import lib

__all__ = ["Dipole", "materials", "henyey_greenstein", "fresnel_reflectance"]


def _check(code):
    _lib.check(code)


def _rgb(value, name):
    """``value`` as three floats (one number stands for all three channels)."""
    array = to_real_array(value, name)
    if array.shape == ():
        array = np.repeat(array, 3)
    if array.shape != (3,):
        raise ArgumentError("%s must be one number or three (R, G, B), got shape %s" % (name, array.shape))
    return array


def materials():
    """The names of Jensen et al. 2001's measured materials, for :meth:`Dipole.from_material`."""
    names, name, i = [], c_char_p(), 0
    while lib.arcus_translucency_material_name(i, byref(name)) == 0:
        names.append(_lib.decode(name.value))
        i += 1
    return names


class Dipole:
    """A homogeneous translucent medium for the dipole: absorption ``sigma_a`` and
    reduced scattering ``sigma_s_prime`` = (1 − g)σ_s (mm⁻¹; one number or R, G, B)
    and the relative refractive index ``eta`` (1 to 3).  Give ``sigma_s`` and ``g``
    instead of ``sigma_s_prime`` if you have them: multiple scattering sees only their
    product (1 − g)σ_s, so the dipole keeps that.

    The derived terms are attributes, each (3,) unless scalar: ``albedo`` (α′),
    ``sigma_t_prime``, ``sigma_tr``, ``diffuse_length`` (ℓ_d = 1/σ_tr, mm),
    ``z_r``/``z_v`` (source depths, mm), ``total_reflectance``, ``diffusive`` (α′ >= 0.5),
    ``f_dr``, ``a``, ``exit_transmittance`` (what eq. 3.6's exit term lets out, 1 − 2·FM1).
    A channel outside diffusion (α′ < 0.5, e.g. ketchup's green and blue) warns.  Bad
    values raise :class:`arcus.ArgumentError` naming them.
    """

    def __init__(self, sigma_a, sigma_s_prime=None, eta=1.3, *, sigma_s=None, g=None):
        if sigma_s_prime is None:
            if sigma_s is None:
                raise ArgumentError("give sigma_s_prime, or sigma_s and g")
            g = 0.0 if g is None else to_float(g, "g")
            if not -1 < g < 1:
                raise ArgumentError("g = %r is not between -1 and 1" % g)
            sigma_s_prime = (1 - g) * _rgb(sigma_s, "sigma_s")
        elif sigma_s is not None or g is not None:
            raise ArgumentError("give sigma_s_prime, or sigma_s and g, not both")
        self._struct = _lib.DipoleStruct()
        self._struct.sigma_a[:] = list(_rgb(sigma_a, "sigma_a"))
        self._struct.sigma_s_prime[:] = list(_rgb(sigma_s_prime, "sigma_s_prime"))
        self._struct.eta = to_float(eta, "eta")
        terms = _lib.DipoleTermsStruct()
        _check(lib.arcus_translucency_dipole_get_terms(byref(self._struct), byref(terms)))
        for name in ("albedo", "sigma_t_prime", "sigma_tr", "diffuse_length", "z_r", "z_v", "total_reflectance"):
            setattr(self, name, np.array(getattr(terms, name)[:]))
        self.diffusive = np.array(terms.diffusive[:], dtype=bool)
        self.f_dr, self.a, self.exit_transmittance = terms.f_dr, terms.a, terms.exit_transmittance
        if not self.diffusive.all():
            channels = ", ".join("RGB"[c] for c in range(3) if not self.diffusive[c])
            warnings.warn("reduced albedo below 0.5 in %s (%s): diffusion describes such a medium poorly"
                          % (channels, np.array2string(self.albedo, precision=3)), stacklevel=2)

    @property
    def sigma_a(self):
        return np.array(self._struct.sigma_a[:])

    @property
    def sigma_s_prime(self):
        return np.array(self._struct.sigma_s_prime[:])

    @property
    def eta(self):
        return self._struct.eta

    @classmethod
    def from_material(cls, name):
        """One of :func:`materials` (Jensen et al. 2001; η = 1.3, marble 1.5)."""
        if not isinstance(name, str):
            raise ArgumentError("name must be a str, got %r" % (name,))
        d = _lib.DipoleStruct()
        _check(lib.arcus_translucency_dipole_from_material(name.encode(), byref(d)))
        return cls(d.sigma_a[:], d.sigma_s_prime[:], d.eta)

    @classmethod
    def from_reflectance(cls, total_reflectance, diffuse_length, eta=1.3):
        """The dipole with total diffuse reflectance 0 < R_total < 1 and diffuse mean free
        path ℓ_d > 0 mm (one number or R, G, B each), at ``eta`` (Jensen & Buhler 2002)."""
        total = np.ascontiguousarray(_rgb(total_reflectance, "total_reflectance"))
        length = np.ascontiguousarray(_rgb(diffuse_length, "diffuse_length"))
        d = _lib.DipoleStruct()
        _check(lib.arcus_translucency_dipole_from_reflectance(_lib.ptr(total), _lib.ptr(length),
                                                              to_float(eta, "eta"), byref(d)))
        return cls(d.sigma_a[:], d.sigma_s_prime[:], d.eta)

    def Rd(self, r, scale=1.0, scaling="energy"):
        """R_d per mm² at distances ``r`` mm (any shape): an array of r's shape + (3,).
        ``scale`` stretches the profile (thesis §5.2): "energy" R_d(r/s)/s² keeps the
        total reflectance, "thesis" R_d(r/s) multiplies it by s²."""
        modes = {"energy": 0, "thesis": 1}
        if scaling not in modes:
            raise ArgumentError("scaling must be 'energy' or 'thesis', got %r" % (scaling,))
        distances = to_real_array(r, "r")
        flat = np.ascontiguousarray(distances.reshape(-1))
        out = np.empty((flat.size, 3))
        _check(lib.arcus_translucency_dipole_profile(byref(self._struct), to_float(scale, "scale"), modes[scaling],
                                                     flat.size, _lib.ptr(flat), _lib.ptr(out)))
        return out.reshape(distances.shape + (3,))

    def __repr__(self):
        return "Dipole(sigma_a=%s, sigma_s_prime=%s, eta=%r)" % (
            np.array2string(self.sigma_a, separator=", "), np.array2string(self.sigma_s_prime, separator=", "),
            self.eta)


def henyey_greenstein(cos_theta, g):
    """The Henyey–Greenstein phase function (per steradian, normalised; thesis eq. 3.5
    corrected) at cosines ``cos_theta`` (any shape, in [-1, 1]), asymmetry -1 < g < 1."""
    mu = to_real_array(cos_theta, "cos_theta")
    flat = np.ascontiguousarray(mu.reshape(-1))
    out = np.empty_like(flat)
    _check(lib.arcus_translucency_henyey_greenstein(to_float(g, "g"), flat.size, _lib.ptr(flat), _lib.ptr(out)))
    return out.reshape(mu.shape)


def fresnel_reflectance(cos_i, n1, n2):
    """The exact unpolarised Fresnel reflectance for light arriving at cos θ = ``cos_i``
    from a medium of index ``n1`` on one of ``n2`` (1 under total internal reflection)."""
    out = c_double()
    _check(lib.arcus_translucency_fresnel_reflectance(to_float(cos_i, "cos_i"), to_float(n1, "n1"),
                                                      to_float(n2, "n2"), byref(out)))
    return out.value
