"""The binding against the contract: include/arcus/arcus.h and the loaded library.

The constants and struct layouts of the package are hand-written mirrors of the
header; these tests catch any drift between the two.
"""

import ast
import ctypes
import ctypes.util
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import arcus
from arcus import _constants, _lib


@pytest.fixture(scope="module")
def header(repo):
    """Every public header, concatenated (arcus.h includes one per topic); not the
    test-only null engine's, which is not installed."""
    return "\n".join(p.read_text() for p in sorted((repo / "include" / "arcus").glob("*.h"))
                     if p.name != "arcus_null.h")


def enum_values(header, enum_name, prefix):
    """{NAME: value} of `prefix`NAME = value entries inside `typedef enum enum_name {...}`."""
    body = re.search(r"typedef enum %s \{(.*?)\}" % enum_name, header, re.S).group(1)
    return {m.group(1): int(m.group(2)) for m in re.finditer(r"%s(\w+) = (\d+)" % prefix, body)}


def test_library_loaded_and_version_matches_header(header):
    assert os.path.exists(arcus.library_path) or os.sep not in arcus.library_path
    macros = {k: int(v) for k, v in re.findall(r"#define ARCUS_VERSION_(MAJOR|MINOR|PATCH) (\d+)", header)}
    assert arcus.__version__ == "%d.%d.%d" % (macros["MAJOR"], macros["MINOR"], macros["PATCH"])


def test_feature_bits_match_header(header):
    pattern = r"#define ARCUS_FEATURE_(\w+) \(UINT64_C\(1\) << (\d+)\)"
    bits = {name: 1 << int(shift) for name, shift in re.findall(pattern, header)}
    # A library built with the test-only null engine (scripts/sanitize.sh) has its bit too.
    assert bits == {name: bit for name, bit in arcus.FEATURES.items() if not name.startswith("NULL_")}


def test_feature_names_match_library():
    buffer = ctypes.create_string_buffer(1024)
    for name, bit in arcus.FEATURES.items():
        assert _lib.lib.arcus_features_to_string(bit, buffer, len(buffer)) == 0
        assert buffer.value.decode() == name
    every = sum(arcus.FEATURES.values())
    assert _lib.lib.arcus_features_to_string(every, buffer, len(buffer)) == 0
    assert set(buffer.value.decode().split()) == set(arcus.FEATURES)
    assert arcus.feature_names(every) == set(arcus.FEATURES)


def test_enums_match_header(header):
    rays = enum_values(header, "arcus_ray_status", "ARCUS_RAY_")
    assert rays == {name: getattr(arcus, "RAY_" + name) for name in rays}
    assert {v: k for k, v in rays.items()} == arcus.RAY_STATUS_NAMES
    failures = enum_values(header, "arcus_ray_failure", "ARCUS_FAILURE_")
    assert failures == {name: getattr(arcus, "FAILURE_" + name) for name in failures}
    assert {v: k for k, v in failures.items()} == arcus.FAILURE_NAMES and len(failures) == 4
    origins = enum_values(header, "arcus_program_origin", "ARCUS_PROGRAM_")
    assert sorted(origins.values()) == sorted(_constants.PROGRAM_ORIGINS)
    methods = enum_values(header, "arcus_method", "ARCUS_METHOD_")
    assert {k.lower(): v for k, v in methods.items()} == arcus.METHODS
    precisions = enum_values(header, "arcus_precision", "ARCUS_PRECISION_")
    assert {k.lower(): v for k, v in precisions.items()} == arcus.PRECISIONS
    kinds = enum_values(header, "arcus_field_kind", "ARCUS_FIELD_")
    assert {v: k for k, v in kinds.items()} == arcus.FIELD_KINDS
    assert float(re.search(r"#define ARCUS_EARTH_RADIUS ([\d.]+)", header).group(1)) == arcus.EARTH_RADIUS
    assert int(re.search(r"#define ARCUS_DEVICE_DEFAULT \((-?\d+)\)", header).group(1)) == arcus.DEVICE_DEFAULT


def test_status_names_come_from_library(header):
    statuses = enum_values(header, "arcus_status", "ARCUS_")
    assert len(statuses) == 13
    for name, code in statuses.items():
        assert _lib.status_name(code) == "ARCUS_" + name
    # The statuses the binding itself tells apart.
    assert (statuses["SUCCESS"], statuses["ERROR_UNSUPPORTED"]) == (_constants.SUCCESS, _constants.ERROR_UNSUPPORTED)
    assert [statuses["ERROR_" + name] for name in ("INVALID_RAYS", "PATH_OVERFLOW", "CANCELLED")] == list(
        _constants.PARTIAL_RESULTS)


def test_every_api_function_has_a_prototype(header):
    """The binding covers the whole C API: every ARCUS_API function has its ctypes prototype
    (the deprecated spellings of arcus 0.9 aside: the binding uses the new names)."""
    current = re.sub(r"#ifndef ARCUS_NO_DEPRECATED.*?#endif", "", header, flags=re.S)
    declared = set(re.findall(r"ARCUS_API\s+[\w\s*]+?\b(arcus_\w+)\s*\(", current))
    assert len(declared) > 40 and "arcus_curved_advance_scene" in declared
    assert declared == set(_lib._PROTOTYPES)


def test_advance_params_defaults():
    """The documented defaults, read through the ctypes struct: a layout error garbles them."""
    params = _lib.AdvanceParamsStruct()
    assert _lib.lib.arcus_advance_params_init(ctypes.byref(params)) == 0
    assert params.method == arcus.METHODS["dp45"]
    assert params.precision == arcus.PRECISIONS["double"]
    assert (params.length, params.step, params.rtol, params.atol) == (1.0, 0.0, 1e-9, 1e-12)
    assert (params.min_step, params.max_step, params.max_rejections) == (1e-12, 0.0, 64)
    assert params.max_steps == 10_000_000
    assert (params.use_box, params.record_path, params.path_capacity) == (0, 0, 0)


def test_atmosphere_defaults_match_library():
    desc = _lib.AtmosphereDescStruct()
    assert _lib.lib.arcus_atmosphere_desc_init(ctypes.byref(desc)) == 0
    python = arcus.fields.StandardAtmosphere()
    assert desc.spherical == int(python.spherical)
    assert desc.wavelength == python.wavelength
    assert desc.sea_level_temperature == python.sea_level_temperature
    assert desc.sea_level_pressure == python.sea_level_pressure
    assert desc.inversion_count == len(python.inversions) == 0


LAYOUT_PROGRAM = r"""
#include <stdio.h>
#include <stddef.h>
#include "arcus/arcus.h"
#define F(T, m) printf(#T "." #m " %zu %zu\n", offsetof(T, m), sizeof(((T*)0)->m));
int main(void) {
  printf("arcus_device_info %zu\n", sizeof(arcus_device_info));
  F(arcus_device_info, index) F(arcus_device_info, name) F(arcus_device_info, platform)
  F(arcus_device_info, version) F(arcus_device_info, is_gpu) F(arcus_device_info, fp64)
  F(arcus_device_info, compute_units) F(arcus_device_info, global_memory) F(arcus_device_info, lanes)
  printf("arcus_inversion %zu\n", sizeof(arcus_inversion));
  F(arcus_inversion, base) F(arcus_inversion, top) F(arcus_inversion, delta_t)
  printf("arcus_atmosphere_desc %zu\n", sizeof(arcus_atmosphere_desc));
  F(arcus_atmosphere_desc, spherical) F(arcus_atmosphere_desc, wavelength)
  F(arcus_atmosphere_desc, sea_level_temperature) F(arcus_atmosphere_desc, sea_level_pressure)
  F(arcus_atmosphere_desc, inversion_count) F(arcus_atmosphere_desc, inversions)
  printf("arcus_advance_params %zu\n", sizeof(arcus_advance_params));
  F(arcus_advance_params, method) F(arcus_advance_params, precision) F(arcus_advance_params, length)
  F(arcus_advance_params, step) F(arcus_advance_params, rtol) F(arcus_advance_params, atol)
  F(arcus_advance_params, min_step) F(arcus_advance_params, max_step) F(arcus_advance_params, max_rejections)
  F(arcus_advance_params, max_steps) F(arcus_advance_params, use_box) F(arcus_advance_params, box_min)
  F(arcus_advance_params, box_max) F(arcus_advance_params, record_path) F(arcus_advance_params, path_capacity)
  F(arcus_advance_params, progress) F(arcus_advance_params, progress_user)
  printf("arcus_job_stats %zu\n", sizeof(arcus_job_stats));
  F(arcus_job_stats, build_seconds) F(arcus_job_stats, kernel_seconds) F(arcus_job_stats, total_seconds)
  F(arcus_job_stats, program_origin) F(arcus_job_stats, lanes) F(arcus_job_stats, groups)
  F(arcus_job_stats, launches)
  printf("arcus_particle_info %zu\n", sizeof(arcus_particle_info));
  F(arcus_particle_info, kind) F(arcus_particle_info, equivalent_radius) F(arcus_particle_info, volume)
  F(arcus_particle_info, bound_radius) F(arcus_particle_info, triangles)
  printf("arcus_rainbow_params %zu\n", sizeof(arcus_rainbow_params));
  F(arcus_rainbow_params, wavelength_nm) F(arcus_rainbow_params, material) F(arcus_rainbow_params, temperature_k)
  F(arcus_rainbow_params, refractive_index) F(arcus_rainbow_params, grid) F(arcus_rainbow_params, alpha)
  F(arcus_rainbow_params, max_bounces) F(arcus_rainbow_params, edge_rays) F(arcus_rainbow_params, rotation)
  F(arcus_rainbow_params, query_phi_deg) F(arcus_rainbow_params, progress) F(arcus_rainbow_params, progress_user)
  F(arcus_rainbow_params, temperature_c)
  printf("arcus_rainbow_stats %zu\n", sizeof(arcus_rainbow_stats));
  F(arcus_rainbow_stats, refractive_index) F(arcus_rainbow_stats, rays) F(arcus_rainbow_stats, hits)
  F(arcus_rainbow_stats, edge_rays) F(arcus_rainbow_stats, patches) F(arcus_rainbow_stats, patches_rejected)
  F(arcus_rainbow_stats, patches_folded) F(arcus_rainbow_stats, intercepted) F(arcus_rainbow_stats, scattered)
  F(arcus_rainbow_stats, remaining) F(arcus_rainbow_stats, cast_seconds) F(arcus_rainbow_stats, patch_seconds)
  F(arcus_rainbow_stats, bvh_seconds) F(arcus_rainbow_stats, query_seconds)
  printf("arcus_mie_efficiencies %zu\n", sizeof(arcus_mie_efficiencies));
  F(arcus_mie_efficiencies, q_ext) F(arcus_mie_efficiencies, q_sca) F(arcus_mie_efficiencies, q_back)
  F(arcus_mie_efficiencies, g)
  printf("arcus_dipole %zu\n", sizeof(arcus_dipole));
  F(arcus_dipole, sigma_a) F(arcus_dipole, sigma_s_prime) F(arcus_dipole, eta)
  printf("arcus_dipole_terms %zu\n", sizeof(arcus_dipole_terms));
  F(arcus_dipole_terms, albedo) F(arcus_dipole_terms, sigma_t_prime) F(arcus_dipole_terms, sigma_tr)
  F(arcus_dipole_terms, diffuse_length) F(arcus_dipole_terms, z_r) F(arcus_dipole_terms, z_v)
  F(arcus_dipole_terms, total_reflectance) F(arcus_dipole_terms, diffusive) F(arcus_dipole_terms, f_dr)
  F(arcus_dipole_terms, a) F(arcus_dipole_terms, exit_transmittance)
  printf("arcus_detected_light %zu\n", sizeof(arcus_detected_light));
  F(arcus_detected_light, azimuth_deg) F(arcus_detected_light, zenith_deg) F(arcus_detected_light, direction)
  F(arcus_detected_light, intensity) F(arcus_detected_light, azimuth_spread_deg)
  F(arcus_detected_light, zenith_spread_deg)
  printf("arcus_light_detection %zu\n", sizeof(arcus_light_detection));
  F(arcus_light_detection, count) F(arcus_light_detection, lights) F(arcus_light_detection, object_pixels)
  F(arcus_light_detection, contour_pixels) F(arcus_light_detection, segmented)
  F(arcus_light_detection, contour_misfit) F(arcus_light_detection, seconds)
  printf("arcus_photo_shape_params %zu\n", sizeof(arcus_photo_shape_params));
  F(arcus_photo_shape_params, method) F(arcus_photo_shape_params, sigma_spatial)
  F(arcus_photo_shape_params, sigma_intensity) F(arcus_photo_shape_params, base_weight)
  F(arcus_photo_shape_params, detail_weight) F(arcus_photo_shape_params, inflation)
  F(arcus_photo_shape_params, relief)
  printf("arcus_translucency_auto_params %zu\n", sizeof(arcus_translucency_auto_params));
  F(arcus_translucency_auto_params, estimate) F(arcus_translucency_auto_params, shape)
  F(arcus_translucency_auto_params, mm_per_pixel) F(arcus_translucency_auto_params, irradiance)
  printf("arcus_daylight_desc %zu\n", sizeof(arcus_daylight_desc));
  F(arcus_daylight_desc, site_height) F(arcus_daylight_desc, ozone_du) F(arcus_daylight_desc, aerosol_depth_500)
  F(arcus_daylight_desc, angstrom_exponent) F(arcus_daylight_desc, aerosol_scale_height) F(arcus_daylight_desc, co2_ppm)
  F(arcus_daylight_desc, aerosol_albedo) F(arcus_daylight_desc, aerosol_asymmetry) F(arcus_daylight_desc, ground_albedo)
  printf("arcus_optical_depths %zu\n", sizeof(arcus_optical_depths));
  F(arcus_optical_depths, rayleigh) F(arcus_optical_depths, ozone) F(arcus_optical_depths, aerosol)
  return 0;
}
"""

STRUCTS = {
    "arcus_device_info": _lib.DeviceInfoStruct,
    "arcus_inversion": _lib.InversionStruct,
    "arcus_atmosphere_desc": _lib.AtmosphereDescStruct,
    "arcus_advance_params": _lib.AdvanceParamsStruct,
    "arcus_job_stats": _lib.JobStatsStruct,
    "arcus_particle_info": _lib.ParticleInfoStruct,
    "arcus_rainbow_params": _lib.RainbowParamsStruct,
    "arcus_rainbow_stats": _lib.RainbowStatsStruct,
    "arcus_mie_efficiencies": _lib.MieEfficienciesStruct,
    "arcus_dipole": _lib.DipoleStruct,
    "arcus_dipole_terms": _lib.DipoleTermsStruct,
    "arcus_daylight_desc": _lib.DaylightDescStruct,
    "arcus_optical_depths": _lib.OpticalDepthsStruct,
    "arcus_detected_light": _lib.DetectedLightStruct,
    "arcus_light_detection": _lib.LightDetectionStruct,
    "arcus_photo_shape_params": _lib.PhotoShapeParamsStruct,
    "arcus_translucency_auto_params": _lib.TranslucencyAutoParamsStruct,
}


def test_struct_layouts_match_c_compiler(repo, tmp_path):
    """Every ctypes struct has the C compiler's size and member offsets and sizes."""
    compiler = shutil.which("cc") or shutil.which("gcc") or shutil.which("clang")
    if compiler is None:
        pytest.skip("no C compiler to measure the C layouts with")
    source = tmp_path / "layout.c"
    source.write_text(LAYOUT_PROGRAM)
    program = tmp_path / "layout"
    subprocess.run([compiler, "-std=c99", "-I", str(repo / "include"), str(source), "-o", str(program)], check=True)
    lines = subprocess.run([str(program)], check=True, capture_output=True, text=True).stdout.splitlines()
    checked = 0
    for line in lines:
        words = line.split()
        if len(words) == 2:
            assert ctypes.sizeof(STRUCTS[words[0]]) == int(words[1]), line
        else:
            struct_name, member = words[0].split(".")
            descriptor = getattr(STRUCTS[struct_name], member)
            assert (descriptor.offset, descriptor.size) == (int(words[1]), int(words[2])), line
        checked += 1
    assert checked == len(STRUCTS) + sum(len(s._fields_) for s in STRUCTS.values())


# ---- finding the library ---------------------------------------------------------------


def import_in_tree(tree, environment):
    """Imports the package copied into `tree` in a fresh interpreter; (ok, output)."""
    env = {k: v for k, v in os.environ.items() if k != "ARCUS_LIBRARY"}
    env.update(environment)
    env["PYTHONPATH"] = str(tree / "bindings" / "python")
    run = subprocess.run(
        [sys.executable, "-c", "import arcus; print(arcus.library_path)"],
        cwd=tree, env=env, capture_output=True, text=True, timeout=60,
    )
    return run.returncode == 0, (run.stdout + run.stderr).strip()


@pytest.fixture
def tree(repo, tmp_path):
    """A copy of the source tree's layout, with the package but no library."""
    (tmp_path / "include" / "arcus").mkdir(parents=True)
    shutil.copy(repo / "include" / "arcus" / "arcus.h", tmp_path / "include" / "arcus")
    shutil.copytree(repo / "bindings" / "python" / "arcus", tmp_path / "bindings" / "python" / "arcus",
                    ignore=shutil.ignore_patterns("__pycache__"))
    return tmp_path


def add_build(tree, name):
    build = tree / name
    build.mkdir()
    shutil.copy(os.path.realpath(arcus.library_path), build / "libarcus.so")
    return str(build / "libarcus.so")


def test_loader_prefers_build_then_other_build_dirs(tree):
    second = add_build(tree, "build-z")
    first = add_build(tree, "build-a")
    assert import_in_tree(tree, {}) == (True, first)
    default = add_build(tree, "build")
    assert import_in_tree(tree, {}) == (True, default)
    # ARCUS_LIBRARY wins over everything.
    assert import_in_tree(tree, {"ARCUS_LIBRARY": second}) == (True, second)


def test_loader_error_lists_every_place(tree):
    ok, output = import_in_tree(tree, {"ARCUS_LIBRARY": str(tree / "missing" / "libarcus.so")})
    assert not ok
    assert "ImportError" in output or "LibraryNotFoundError" in output
    assert str(tree / "missing" / "libarcus.so") in output

    if ctypes.util.find_library("arcus"):
        pytest.skip("an installed libarcus would be found; the not-found message cannot be produced")
    ok, output = import_in_tree(tree, {})
    assert not ok
    assert "LibraryNotFoundError" in output
    for place in ("ARCUS_LIBRARY", str(tree / "build" / "libarcus.so"), "find_library", sys.prefix):
        assert place in output
    assert "cmake" in output


def public_names():
    for module in (arcus, arcus.fields):
        for name in module.__all__:
            yield "%s.%s" % (module.__name__, name), getattr(module, name)


def test_every_public_name_has_a_docstring():
    undocumented = []
    for qualified, obj in public_names():
        if isinstance(obj, (int, float, str, dict, frozenset)):
            continue  # constants are documented in the module (#: comments) and the header
        if not (obj.__doc__ or "").strip():
            undocumented.append(qualified)
        if isinstance(obj, type):
            for member, value in vars(obj).items():
                if member.startswith("_"):
                    continue
                target = value.fget if isinstance(value, property) else getattr(value, "__func__", value)
                if callable(target) and not (target.__doc__ or "").strip():
                    undocumented.append("%s.%s" % (qualified, member))
    assert not undocumented


# ---- the package's layering: no import circle ---------------------------------------


def module_level_imports(package_dir):
    """{module: set of modules}: what each module of the package at ``package_dir``
    imports while it is itself imported, read from the source with ``ast`` (the package is
    not imported).  Modules are dotted names within the package ("rainbow", "cli.render";
    "" is the package's __init__).  Imports inside functions run later, when called, and
    cannot close a circle at import time, so they are left out; those in class bodies and
    under module-level ``if``/``try``/``with`` run at import and count."""
    package_dir = Path(package_dir)
    files = {}
    for path in sorted(package_dir.rglob("*.py")):
        parts = list(path.relative_to(package_dir).with_suffix("").parts)
        is_package = parts[-1] == "__init__"
        if is_package:
            parts = parts[:-1]
        files[".".join(parts)] = (path, is_package)

    def walk(node):
        """The statements run at import: everything but function bodies (and lambdas)."""
        for child in ast.iter_child_nodes(node):
            if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
                continue
            yield child
            yield from walk(child)

    top = package_dir.name
    graph = {}
    for module, (path, is_package) in files.items():
        parts = module.split(".") if module else []
        package = parts if is_package else parts[:-1]  # the package a relative import starts from
        edges = set()
        for node in walk(ast.parse(path.read_text(), str(path))):
            if isinstance(node, ast.Import):
                for alias in node.names:
                    names = alias.name.split(".")
                    if names[0] != top:
                        continue  # another package
                    if len(names) == 1:  # import arcus: its __init__
                        edges.add("")
                    # import arcus.x.y: x, then x.y (the package itself is importing already)
                    edges.update(m for m in (".".join(names[1:k]) for k in range(2, len(names) + 1)) if m in files)
            elif isinstance(node, ast.ImportFrom):
                if node.level:
                    if node.level - 1 > len(package):
                        continue
                    base = package[:len(package) - (node.level - 1)]
                    rest = node.module.split(".") if node.module else []
                elif node.module.split(".")[0] == top:
                    base, rest = [], node.module.split(".")[1:]
                else:
                    continue  # another package
                target = base + rest
                # from .x.y import z: the packages and module on the way (x, x.y), then z
                # if it is a submodule, else the module z is read from
                edges.update(m for m in (".".join(target[:k]) for k in range(len(base) + 1, len(target) + 1))
                             if m in files)
                for alias in node.names:
                    sub = ".".join(target + [alias.name])
                    if sub in files:
                        edges.add(sub)
                    elif ".".join(target) in files:
                        edges.add(".".join(target))
        edges.discard(module)
        graph[module] = edges
    return graph


def import_circle(graph):
    """An import circle of ``graph`` as a list of modules (first == last), or None."""
    state = {}  # module -> 1 on the current path, 2 done
    path = []

    def visit(module):
        state[module] = 1
        path.append(module)
        for target in sorted(graph.get(module, ())):
            if state.get(target) == 1:
                return path[path.index(target):] + [target]
            if target not in state:
                found = visit(target)
                if found:
                    return found
        path.pop()
        state[module] = 2
        return None

    for module in sorted(graph):
        if module not in state:
            found = visit(module)
            if found:
                return found
    return None


def test_import_graph_reader_sees_a_circle(tmp_path):
    """The checker below finds a circle through module-level imports, and none through
    imports inside functions."""
    pkg = tmp_path / "arcus"
    (pkg / "cli").mkdir(parents=True)
    (pkg / "__init__.py").write_text("from . import a\n")
    (pkg / "a.py").write_text("from .b import thing\n")
    (pkg / "b.py").write_text("def f():\n    from . import a\n")
    (pkg / "cli" / "__init__.py").write_text("")
    (pkg / "cli" / "tool.py").write_text("from ..a import x\nimport arcus.b\n")
    graph = module_level_imports(pkg)
    assert graph == {"": {"a"}, "a": {"b"}, "b": set(), "cli": set(), "cli.tool": {"a", "b"}}
    assert import_circle(graph) is None
    (pkg / "b.py").write_text("try:\n    from .cli.tool import y\nexcept ImportError:\n    pass\n")
    assert import_circle(module_level_imports(pkg)) == ["a", "b", "cli.tool", "a"]


def test_the_package_has_no_import_circle():
    """bindings/python/arcus is layered: low-level modules (_lib, _args, _errors, image,
    fields, progress, ...) → context (Context, _owned_context) → engines (rainbow, mie,
    halo, ocean) → sweep → sky (its tables come from sweep) → cli.  Every module-level
    import points down, so no module sees another half initialised.  Read from the
    source, so a circle anyone adds fails here; an import that must stay inside a
    function says why in a comment.  (arcus.rainbow.render, the deprecated name of
    sky.render, is found by name when used, not imported.)"""
    graph = module_level_imports(Path(arcus.__file__).resolve().parent)
    assert {"context", "rainbow", "sky", "sweep", "cli.render"} <= set(graph)  # the reader found the package
    assert import_circle(graph) is None
