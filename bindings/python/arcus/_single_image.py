"""The single-image estimate (thesis §3.4): what an uncontrolled photograph gives
without a mesh or lights.  Public through :mod:`arcus.translucency`."""

from ctypes import byref, c_float, c_size_t, c_uint8, c_uint32
from dataclasses import dataclass

import numpy as np

from . import _lib
from ._args import to_choice, to_float
from ._errors import ArgumentError
from ._lib import lib
from ._photos import read_matte, read_photo
from .context import _owned_context


@dataclass
class DetectedLight:
    """A light found in a photograph (:func:`detect_lights`), in the camera's frame (x
    right, y up, z toward the camera): ``azimuth_deg`` θ in the image plane,
    counter-clockwise from +x; ``zenith_deg`` φ from the camera's axis (0: from the
    camera, 90: in the image plane); ``direction`` toward it, (sinφ cosθ, sinφ sinθ,
    cosφ); ``intensity``, relative (the lights' sum is 1); ``azimuth_spread_deg`` and
    ``zenith_spread_deg``, half the range of angles that fit within 5% of the best."""
    azimuth_deg: float
    zenith_deg: float
    direction: np.ndarray
    intensity: float
    azimuth_spread_deg: float
    zenith_spread_deg: float


@dataclass
class LightDetection:
    """What :func:`detect_lights` found: ``lights`` (strongest first), the object's
    ``object_pixels`` and ``contour_pixels``, ``segmented`` (True: no matte was given),
    ``contour_misfit`` (the contour model's RMS residual over the contour's RMS) and
    ``seconds``."""
    lights: list
    object_pixels: int
    contour_pixels: int
    segmented: bool
    contour_misfit: float
    seconds: float


def detect_lights(photo, matte=None, *, context=None):
    """The directional lights of the object in ``photo`` (an HDR file or an (h, w, 3)
    array of linear radiance; 8-bit images are read with a warning) from the photo alone
    (thesis §3.4, after Lopez-Moreno et al. 2009): azimuths from its contour, zeniths from
    the luminance gradients inside it.  ``matte``: an (h, w) array, non-zero on the
    object (default: segmented from the photo).  A :class:`LightDetection`."""
    pixels = read_photo(photo, eight_bit="warn")
    height, width = pixels.shape[:2]
    matte_array = read_matte(matte, height, width)
    result = _lib.LightDetectionStruct()
    with _owned_context(context) as ctx:
        ctx._check(lib.arcus_translucency_detect_lights(
            ctx._handle, width, height, _lib.ptr(pixels, c_float),
            None if matte_array is None else _lib.ptr(matte_array, c_uint8), byref(result)))
    return light_detection(result)


def light_detection(result):
    """An arcus_light_detection as a :class:`LightDetection`."""
    lights = [DetectedLight(azimuth_deg=light.azimuth_deg, zenith_deg=light.zenith_deg,
                            direction=np.array(light.direction[:]), intensity=light.intensity,
                            azimuth_spread_deg=light.azimuth_spread_deg, zenith_spread_deg=light.zenith_spread_deg)
              for light in result.lights[:result.count]]
    return LightDetection(lights=lights, object_pixels=result.object_pixels, contour_pixels=result.contour_pixels,
                          segmented=bool(result.segmented), contour_misfit=result.contour_misfit,
                          seconds=result.seconds)


DEPTH_METHODS = {"base+detail": 0, "base": 1, "luminance": 2}  # arcus_depth_method


@dataclass
class PhotoShape:
    """The object's shape from a photograph (:func:`estimate_shape`): ``depth`` (h, w)
    in pixels toward the camera, ``normals`` (h, w, 3) unit in the camera's frame (x
    right, y up), ``mask`` (h, w) bool: the object; 0 outside it."""
    depth: np.ndarray
    normals: np.ndarray
    mask: np.ndarray


def estimate_shape(photo, matte=None, *, method="base+detail", relief=1.0, sigma_spatial=0.09, sigma_intensity=0.4,
                   base_weight=0.8, detail_weight=0.2, inflation=0.0, context=None):
    """The depth and normals of the object in ``photo`` from the photo alone (thesis
    §3.4, after Khan et al. 2006): ``method`` "base+detail" (the thesis'), "base" or
    "luminance" (the simplest: luminance as depth); ``relief`` scales the depth (the
    bas-relief ambiguity leaves it open); the bilateral filter's ``sigma_spatial`` (over
    the object's diameter) and ``sigma_intensity``; the layers' weights; the inflation
    spline's drop at black (0: off, the default; Khan et al.'s ~0.3 costs 2–5° of normal
    on one-light photos).  arcus_translucency.h says how.  A :class:`PhotoShape`."""
    pixels = read_photo(photo, eight_bit="warn")
    height, width = pixels.shape[:2]
    matte_array = read_matte(matte, height, width)
    params = _lib.PhotoShapeParamsStruct()
    _lib.check(lib.arcus_translucency_photo_shape_params_init(byref(params)))
    params.method = to_choice(method, "method", DEPTH_METHODS)
    for name, value in (("relief", relief), ("sigma_spatial", sigma_spatial), ("sigma_intensity", sigma_intensity),
                        ("base_weight", base_weight), ("detail_weight", detail_weight), ("inflation", inflation)):
        setattr(params, name, to_float(value, name))
    depth, normals = np.empty((height, width)), np.empty((height, width, 3))
    mask = np.empty((height, width), np.uint8)
    with _owned_context(context) as ctx:
        ctx._check(lib.arcus_translucency_estimate_shape(
            ctx._handle, width, height, _lib.ptr(pixels, c_float),
            None if matte_array is None else _lib.ptr(matte_array, c_uint8), byref(params), _lib.ptr(depth),
            _lib.ptr(normals), _lib.ptr(mask, c_uint8)))
    return PhotoShape(depth=depth, normals=normals, mask=mask.astype(bool))


def shape_params_into(params, options):
    """estimate_shape's keyword arguments into an arcus_photo_shape_params."""
    for name, value in options.items():
        if name == "method":
            params.method = to_choice(value, "shape['method']", DEPTH_METHODS)
        elif name in ("relief", "sigma_spatial", "sigma_intensity", "base_weight", "detail_weight", "inflation"):
            setattr(params, name, to_float(value, "shape[%r]" % name))
        else:
            raise ArgumentError("shape: unknown option %r (method, relief, sigma_spatial, sigma_intensity, "
                                "base_weight, detail_weight, inflation)" % (name,))


def automatic_outputs(ctx, job, height, width):
    """What an automatic estimate found: Estimate's lights, shape and relief."""
    found = _lib.LightDetectionStruct()
    vertices, triangles = c_size_t(), c_size_t()
    ctx._check(lib.arcus_job_get_translucency_auto(job, None, None, None, None, byref(vertices), byref(triangles),
                                                   None, None))
    depth, normals = np.empty((height, width)), np.empty((height, width, 3))
    mask = np.empty((height, width), np.uint8)
    positions, faces = np.empty((vertices.value, 3)), np.empty((triangles.value, 3), np.uint32)
    ctx._check(lib.arcus_job_get_translucency_auto(job, byref(found), _lib.ptr(depth), _lib.ptr(normals),
                                                   _lib.ptr(mask, c_uint8), None, None, _lib.ptr(positions),
                                                   _lib.ptr(faces, c_uint32)))
    return {"lights": light_detection(found), "shape": PhotoShape(depth=depth, normals=normals, mask=mask.astype(bool)),
            "relief": (positions, faces)}
