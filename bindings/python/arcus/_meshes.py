"""Meshes from memory (``arcus_mesh_t``, arcus_scene.h): numpy arrays checked here and
handed to the library, for rainbow particles (:meth:`arcus.rainbow.Mesh.from_arrays`)
and for the meshes a render scene names (``Context.render(scene, meshes=...)``)."""

import os
from ctypes import byref, c_char_p, c_size_t, c_uint32, c_void_p

import numpy as np

from . import _lib
from ._args import to_path, to_real_array
from ._errors import ArgumentError
from ._lib import lib


def mesh_arrays(vertices, triangles, prefix=""):
    """``vertices`` ((N, 3) real numbers) and ``triangles`` ((M, 3) integers: vertex
    indices from 0) as read-only C arrays of float64 and uint32, copied.  Shapes and
    types are checked here; the values (finite coordinates, indices below N, at least
    one triangle) by the library, whose messages name the C API's flat arrays
    ("indices[7] = 12 is not below vertex_count 10": row 7 // 3, column 7 % 3).
    ``prefix`` begins each message ("meshes['ball'] ")."""
    v = to_real_array(vertices, prefix + "vertices")
    if v.ndim != 2 or v.shape[1] != 3:
        raise ArgumentError("%svertices must have shape (N, 3), got %s" % (prefix, v.shape))
    t = np.asarray(triangles)
    if t.dtype.kind not in "iu" or t.ndim != 2 or t.shape[1] != 3:
        raise ArgumentError("%striangles must be an (M, 3) array of integers (vertex indices), got %s of %s"
                            % (prefix, t.shape, t.dtype))
    outside = (t < 0) | (t > 0xFFFFFFFF)
    if outside.any():
        row, col = np.argwhere(outside)[0]
        raise ArgumentError("%striangles[%d, %d] = %d is not a vertex index (0 to 2**32 - 1)"
                            % (prefix, row, col, t[row, col]))
    v = v.copy()
    t = np.array(t, dtype=np.uint32, order="C")
    v.flags.writeable = t.flags.writeable = False
    return v, t


def create(ctx_handle, vertices, triangles, out):
    """``arcus_mesh_create`` on arrays from :func:`mesh_arrays`: its status."""
    return lib.arcus_mesh_create(ctx_handle, len(vertices), _lib.ptr(vertices), len(triangles),
                                 _lib.ptr(triangles, c_uint32), out)


def named(meshes):
    """A scene's meshes, ``{name: (vertices, triangles)}``, as [(name, vertices,
    triangles)] checked; None or {} gives []."""
    if meshes is None:
        return []
    if not isinstance(meshes, dict):
        raise ArgumentError("meshes must be a dict {name: (vertices, triangles)}, got %r" % (meshes,))
    checked = []
    for name, mesh in meshes.items():
        if not isinstance(name, str) or not name or "\0" in name:
            raise ArgumentError("meshes: a mesh's name must be a non-empty str without NUL, got %r" % (name,))
        if not isinstance(mesh, (tuple, list)) or len(mesh) != 2:
            raise ArgumentError("meshes[%r] must be a pair (vertices, triangles), e.g. (mesh.vertices, mesh.faces)"
                                % name)
        checked.append((name,) + mesh_arrays(mesh[0], mesh[1], "meshes[%r] " % name))
    return checked


def load_scene(ctx, encoded_path, meshes, out):
    """``arcus_scene_load_with_meshes`` of the file at ``encoded_path`` on ``ctx`` (a
    Context) with ``meshes`` from :func:`named`; raises arcus.Error on failure.  The
    library copies what the scene needs, so the mesh handles go when it returns."""
    handles = []
    try:
        for _, vertices, triangles in meshes:
            handle = c_void_p()
            ctx._check(create(ctx._handle, vertices, triangles, byref(handle)))
            handles.append(handle)
        names = (c_char_p * len(meshes))(*[name.encode() for name, _, _ in meshes])
        array = (c_void_p * len(meshes))(*[h.value for h in handles])
        ctx._check(lib.arcus_scene_load_with_meshes(ctx._handle, encoded_path, len(meshes), names, array, out))
    finally:
        for handle in handles:
            lib.arcus_mesh_release(handle)


def read_mesh(path, context=None):
    """The mesh file at ``path`` (OBJ, PLY, OFF, STL) as ``(vertices (N, 3) float64,
    triangles (M, 3) uint32)``, read as every engine reads it."""
    from .context import _owned_context  # the context module loads this one
    with _owned_context(context) as ctx:
        handle = c_void_p()
        ctx._check(lib.arcus_mesh_load(ctx._handle, to_path(path, "path"), byref(handle)))
        try:
            nv, nt = c_size_t(), c_size_t()
            ctx._check(lib.arcus_mesh_get_counts(handle, byref(nv), byref(nt)))
            vertices = np.empty((nv.value, 3))
            triangles = np.empty((nt.value, 3), np.uint32)
            ctx._check(lib.arcus_mesh_get_arrays(handle, _lib.ptr(vertices), _lib.ptr(triangles, c_uint32)))
        finally:
            lib.arcus_mesh_release(handle)
    return vertices, triangles


def handle_of(ctx, mesh):
    """An arcus_mesh_t of ``mesh`` (a file path or (vertices, triangles)) on ctx; the
    caller releases it."""
    handle = c_void_p()
    if isinstance(mesh, (str, os.PathLike)):
        ctx._check(lib.arcus_mesh_load(ctx._handle, to_path(mesh, "mesh"), byref(handle)))
    elif isinstance(mesh, (tuple, list)) and len(mesh) == 2:
        vertices, triangles = mesh_arrays(mesh[0], mesh[1], "mesh ")
        ctx._check(create(ctx._handle, vertices, triangles, byref(handle)))
    else:
        raise ArgumentError("mesh must be a file path or a (vertices, triangles) pair, got %r" % (mesh,))
    return handle
