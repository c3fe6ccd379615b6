"""Writes storm_sky.png: an equirectangular panorama (1024 × 512, sRGB) of a storm front
ahead and a clear, sunlit sky behind, the backdrop of scenes/rainbow/storm_sky.json.

Procedural and seeded, so it is reproducible: columns are azimuth (u = a/360°, from +z
toward +x, as arcus_rainbow.h maps sky images), rows elevation from the zenith (top)
to the nadir.  Radiances are relative (the scene's "scale" sets them): the clear sky is
Rayleigh blue brightening toward the sun (azimuth 180°, low), the storm a dark blue-grey
cloud over azimuths −75°…75° whose fractal texture comes from filtered noise (periodic
in azimuth, so the seam at u = 0 is invisible).  Run: python3 make_storm_sky.py
"""

from pathlib import Path

import numpy as np

WIDTH, HEIGHT = 1024, 512


def fractal_noise(rng, shape, slope=2.6):
    """Gaussian noise with a power spectrum ∝ f^−slope (clouds), scaled to unit variance."""
    fy = np.fft.fftfreq(shape[0])[:, None]
    fx = np.fft.rfftfreq(shape[1])[None, :]
    f = np.hypot(fy, 2 * fx)  # columns span 360°, rows 180°: the same angle per pixel
    f[0, 0] = 1
    spectrum = (rng.standard_normal(f.shape) + 1j * rng.standard_normal(f.shape)) * f ** (-slope / 2)
    spectrum[0, 0] = 0
    field = np.fft.irfft2(spectrum, s=shape)
    return field / field.std()


def storm_sky(seed=7):
    rng = np.random.default_rng(seed)
    u = (np.arange(WIDTH) + 0.5) / WIDTH
    v = (np.arange(HEIGHT) + 0.5) / HEIGHT
    azimuth = np.radians(u * 360)[None, :]
    elevation = np.radians(90 - v * 180)[:, None]
    up = np.clip(np.sin(elevation), 0, 1)
    # The clear sky: deeper blue overhead, paler at the horizon, a glow around the sun.
    zenith, horizon = np.array([0.16, 0.32, 0.75]), np.array([0.55, 0.65, 0.80])
    t = np.sqrt(up)[..., None]
    clear = (1 - t) * horizon + t * zenith
    sun = np.array([np.cos(np.radians(8)) * np.sin(np.pi), np.sin(np.radians(8)), np.cos(np.radians(8)) * np.cos(np.pi)])
    d = np.stack(np.broadcast_arrays(np.cos(elevation) * np.sin(azimuth), np.sin(elevation),
                                     np.cos(elevation) * np.cos(azimuth)), -1)
    glow = np.exp((d @ sun - 1) / 0.03)[..., None]
    clear = clear + glow * np.array([1.0, 0.85, 0.6])
    # The storm: cloud cover over the azimuths ahead, thinning above 50° and past ±75°.
    ahead = np.cos(azimuth)  # 1 straight ahead (+z), −1 behind
    cover = 1 / (1 + np.exp(-(ahead - np.cos(np.radians(75))) / 0.06))
    cover = cover * 1 / (1 + np.exp((np.degrees(elevation) - 50) / 6))
    texture = fractal_noise(rng, (HEIGHT, WIDTH))
    density = (cover * np.clip(1.6 + 0.4 * texture, 0, 1))[..., None]
    cloud = np.array([0.08, 0.09, 0.12]) * np.clip(1 + 0.4 * texture[..., None], 0.3, None)
    sky = (1 - density) * clear + density * cloud
    ground = np.array([0.05, 0.06, 0.04])
    sky = np.where((elevation < 0)[..., None], ground, sky)
    return np.clip(sky / 1.2, 0, 1)


def write(out):
    """Writes the panorama to ``out`` (PNG)."""
    import matplotlib.image

    linear = storm_sky()
    # PNG holds sRGB code values; readers (arcus_image_read) decode them back to linear.
    encoded = np.where(linear <= 0.0031308, 12.92 * linear, 1.055 * linear ** (1 / 2.4) - 0.055)
    matplotlib.image.imsave(out, encoded)


def main():
    out = Path(__file__).with_name("storm_sky.png")
    write(out)
    print("wrote", out)


if __name__ == "__main__":
    main()
