"""The Novaya Zemlya sun's colour (scenes/novaya_zemlya.json): the sun's disc seen along
the ducted rays of that scene's atmosphere (spherical US 1976 air, 20 K colder at the
ground fading to 0 at 200 m), whose air mass no formula for a standard atmosphere
gives.  Run from anywhere; prints the air masses and the disc's linear sRGB radiance
in W m⁻² sr⁻¹ nm⁻¹ (the daylight sky's unit) for the scene's "sun" material.

Method: rays leave the eye (5 m up) toward the sun's azimuth at the elevations that
reach the sun in the scene (its strip lies 0.013° below to 0.055° above the eye's
horizontal); arcus advances them through the scene's field with every point kept
(steps of at most 200 m), and along each path
  air mass  m_air = ∫ (n − 1) ds / ∫ (n − 1) dh   (refractivity ∝ density; the vertical
            column through the same field, inversion included),
  aerosol   m_aer = ∫ exp(−h/H) ds / H             (the scene's aerosol layer of scale height H),
  ozone     the refracted horizon's (arcus.daylight at 89.9°: the layer at 25 km lies
            above the duct).
The disc's radiance is ASTM G173's sun over its disc's solid angle (the mean over the
limb-darkened disc) times exp(−Σ m τ_vertical) of the vertical depths of the scene's
"atmosphere" (arcus.daylight), integrated over the CIE 1931 observer into linear sRGB.
"""
import json
import pathlib
import sys

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bindings" / "python"))

import arcus  # noqa: E402
import arcus.daylight as daylight  # noqa: E402
from arcus import fields  # noqa: E402

R = arcus.EARTH_RADIUS
EYE = 5.0
SUN_DISC_SR = 6.794e-5  # the sun's disc, 0.533° across, in steradians


def heights(points):
    return np.linalg.norm(points, axis=1) - R


def path_integral(values, points):
    ds = np.linalg.norm(np.diff(points, axis=0), axis=1)
    return float(np.sum(0.5 * (values[1:] + values[:-1]) * ds))


def main():
    scene = json.loads((ROOT / "scenes" / "novaya_zemlya.json").read_text())
    field = fields.StandardAtmosphere(spherical=True, inversions=[tuple(layer.values()) for layer in
                                                                  scene["field"]["inversions"]])
    atmosphere = dict(scene.get("atmosphere", {}))
    scale_height = atmosphere.get("aerosol_scale_height", 1200.0)
    elevations = np.array([-0.013, 0.0, 0.02, 0.04, 0.055])  # degrees: across the strip
    with arcus.Context() as ctx:
        e = np.radians(elevations)
        origins = np.tile([0.0, R + EYE, 0.0], (e.size, 1))
        directions = np.column_stack([np.cos(e), np.sin(e), np.zeros_like(e)])
        result = ctx.advance(field, origins, directions, length=1.5e6, record_path=True, max_step=200.0, path_capacity=20000,
                             rtol=1e-10, atol=1e-6)
        vertical = np.column_stack([np.zeros(2001), R + np.linspace(0.0, 86000.0, 2001), np.zeros(2001)])
        column = path_integral(ctx.evaluate(field, vertical)[0] - 1, vertical)
        air, aerosol = [], []
        for path in result.paths:
            n = ctx.evaluate(field, path)[0]
            air.append(path_integral(n - 1, path) / column)
            aerosol.append(path_integral(np.exp(-heights(path) / scale_height), path) / scale_height)
            if heights(path)[-1] < 80000:
                raise SystemExit("a ray ended %.0f m up: it did not leave the air" % heights(path)[-1])
    air, aerosol = np.array(air), np.array(aerosol)
    for el, m, a in zip(elevations, air, aerosol):
        print("elevation %+.3f°: air mass %.1f, aerosol air mass %.1f" % (el, m, a))
    m_air, m_aer = float(np.median(air)), float(np.median(aerosol))

    nm = np.arange(365.0, 830.0, 10.0)
    up = daylight.optical_depths(nm, 0.0, **atmosphere)
    horizon = daylight.optical_depths(nm, 89.9, **atmosphere)
    tau = up.rayleigh * m_air + up.aerosol * m_aer + horizon.ozone
    radiance = daylight.solar_irradiance(nm, band=10) / SUN_DISC_SR * np.exp(-tau)
    cie = np.loadtxt(ROOT / "data" / "spectra" / "cie1931_2deg_5nm.csv", delimiter=",", skiprows=1)
    bars = np.array([np.interp(nm, cie[:, 0], cie[:, c]) for c in (1, 2, 3)])
    xyz = bars @ radiance / bars[1].sum()
    rgb = np.array([[3.2404542, -1.5371385, -0.4985314], [-0.9692660, 1.8760108, 0.0415560],
                    [0.0556434, -0.2040259, 1.0572252]]) @ xyz
    print("median air mass %.1f, aerosol %.1f; transmittance at 450/550/650 nm: %.3g %.3g %.3g"
          % (m_air, m_aer, *np.exp(-tau[[8, 18, 28]])))
    print("the disc's linear sRGB radiance [W m^-2 sr^-1 nm^-1]: [%.4g, %.4g, %.4g] (negative: outside sRGB; clipped to 0 in the scene)" % tuple(rgb))


if __name__ == "__main__":
    main()
