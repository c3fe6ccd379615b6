"""The second, external reference for subsurface light: Mitsuba 3 (PyPI `mitsuba`, its
`scalar_rgb` variant, which runs on any CPU) rendering a deep slab of a homogeneous
medium under a smooth dielectric boundary with its `volpath` integrator.

A directional light through a smooth dielectric is black in Mitsuba (a delta light
through a delta interface), so the slab is lit by a constant environment of radiance 1
and looked at straight down by an orthographic camera: by reciprocity the radiance seen
is the slab's albedo for light arriving along the normal.  The specular part (the same
render with a non-scattering medium) is taken off and the rest divided by the
transmittance, which gives R_total as the dipole defines it: the fraction of the
transmitted flux that leaves again.  `python3 tests/python/mitsuba_slab.py` prints it."""

import numpy as np


def _radiance(mi, albedo, eta, samples):
    scene = mi.load_dict({
        "type": "scene",
        "integrator": {"type": "volpath", "max_depth": -1, "rr_depth": 1_000_000},  # no roulette bias
        "sensor": {
            "type": "orthographic",
            "to_world": mi.ScalarTransform4f().look_at(origin=[0, 0, 10], target=[0, 0, 0], up=[0, 1, 0])
            @ mi.ScalarTransform4f().scale([0.5, 0.5, 1]),
            "film": {"type": "hdrfilm", "width": 4, "height": 4, "rfilter": {"type": "box"}},
            "sampler": {"type": "independent", "sample_count": max(1, samples // 16)},
        },
        "environment": {"type": "constant", "radiance": {"type": "rgb", "value": 1.0}},
        # 1000 mean free paths deep and 2000 wide: a half-space for these albedos.
        "slab": {
            "type": "cube",
            "to_world": mi.ScalarTransform4f().translate([0, 0, -500]) @ mi.ScalarTransform4f().scale([1000, 1000, 500]),
            "bsdf": {"type": "dielectric", "int_ior": eta, "ext_ior": 1.0},
            "interior": {"type": "homogeneous", "sigma_t": 1.0, "albedo": albedo, "phase": {"type": "isotropic"}},
        },
    })
    return float(np.mean(np.array(mi.render(scene))[..., 0]))


def total_reflectance(albedo, eta=1.3, samples=65_536):
    """R_total of a half-space of single-scattering albedo `albedo` (σ_t = 1, g = 0)
    under a boundary of index `eta`, by Mitsuba 3."""
    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    specular = ((eta - 1) / (eta + 1)) ** 2  # normal incidence: what a non-scattering slab returns
    return (_radiance(mi, albedo, eta, samples) - specular) / (1 - specular)


if __name__ == "__main__":
    for a in (0.9, 0.99):
        print("albedo %.2f: R_total %.4f (Mitsuba 3, volpath, scalar_rgb)" % (a, total_reflectance(a, samples=524_288)))
