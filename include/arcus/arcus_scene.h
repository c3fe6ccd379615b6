/*
 * arcus scenes: JSON scene files, read by the library for every engine, the
 * command-line tools and Python.  Schema: scenes/README.md.  Include arcus.h.
 *
 * Reading is strict: an unknown key, a key given twice, a wrong type, a non-finite or
 * out-of-range number, nesting deeper than 64 levels, or a file that is not a regular
 * file is an error whose message names the file and the key path ("scene.json:
 * $.medium.radius: expected a number").  The engine a scene is for follows from its
 * keys; each engine's header has the calls that use a scene (arcus_curved.h:
 * arcus_scene_get_field, arcus_curved_advance_scene, ...).
 *
 * Meshes (arcus_mesh_t) are geometry handed over in memory, as Embree takes it, where
 * a call would otherwise read a mesh file: a scene names them (arcus_scene_load_with_meshes)
 * and each engine's header says which of its calls take one (arcus_rainbow.h:
 * arcus_particle_create_from_mesh).
 */
#ifndef ARCUS_SCENE_H
#define ARCUS_SCENE_H

#include "arcus_core.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct arcus_scene_s arcus_scene_t;
typedef struct arcus_mesh_s arcus_mesh_t; /* below: "meshes from memory" */

/* A pinhole camera, shared by every engine that makes a view (arcus_render.h,
 * arcus_ocean.h): the image's rows run top to bottom, y up along `up`; positions in
 * the scene's units.  Scene files give it as "camera" with the same member names. */
typedef struct arcus_camera {
  double position[3];
  double look_at[3];
  double up[3];
  double vfov_deg; /* vertical field of view, 0 < vfov < 180 */
  uint32_t width, height; /* 1..16384 pixels a side */
} arcus_camera;

/* Reads and checks the scene file at `path` and creates what it describes on ctx
 * (its medium, ...).  Relative file names inside the scene are relative to the scene
 * file's directory.  Errors: ARCUS_ERROR_IO (the file cannot be read),
 * ARCUS_ERROR_INVALID_ARGUMENT (not valid JSON, or not a valid scene).            */
ARCUS_API arcus_status arcus_scene_load(arcus_context_t* ctx, const char* path, arcus_scene_t** out);

/* As arcus_scene_load, for a scene whose objects take meshes from memory rather than
 * files: where a render scene's object says {"type": "mesh", "mesh": "bunny"} (instead
 * of "file"), the mesh is meshes[i] for the i with mesh_names[i] equal to "bunny".  The
 * scene copies what it needs: the meshes may be released once the call returns.
 * mesh_count may be 0 (then both arrays may be NULL).  Errors name the argument:
 * mesh_names[i] NULL, empty, longer than 1024 bytes or repeated; meshes[i] not a live
 * mesh of ctx; mesh_count over 65536; a name the file uses that is not given
 * ("scene.json: $.objects[2].mesh: no mesh named \"bunny\" was given ..."); and a given
 * mesh the scene does not use (a misspelt name, or an engine that takes no meshes). */
ARCUS_API arcus_status arcus_scene_load_with_meshes(arcus_context_t* ctx, const char* path, size_t mesh_count,
                                                    const char* const* mesh_names, arcus_mesh_t* const* meshes,
                                                    arcus_scene_t** out);
ARCUS_API arcus_status arcus_scene_retain(arcus_scene_t* scene);
ARCUS_API arcus_status arcus_scene_release(arcus_scene_t* scene);

/* Strings owned by the scene, valid while it lives: its "name" (letters, digits,
 * '_', '-', '.'), its "description" ("" if none), the document as read (pretty
 * printed JSON, keys in the author's order), and the engine it is for ("curved"). */
ARCUS_API arcus_status arcus_scene_get_name(arcus_scene_t* scene, const char** name);
ARCUS_API arcus_status arcus_scene_get_description(arcus_scene_t* scene, const char** description);
ARCUS_API arcus_status arcus_scene_get_document(arcus_scene_t* scene, const char** json);
ARCUS_API arcus_status arcus_scene_get_engine(arcus_scene_t* scene, const char** engine);

/* ---- meshes from memory ------------------------------------------------------- */

/* A triangle mesh of `vertex_count` vertices (`vertices`: x y z each, tightly packed, in
 * metres or in the units a `scale` later turns into metres) and `triangle_count`
 * triangles (`indices`: 3 vertex indices each, from 0; either array may be NULL when its
 * count is 0), copied: the arrays may be freed once the call returns.  It is the same
 * mesh a file with these vertices and triangles gives (arcus_particle_create_mesh),
 * checked the same way: at least one triangle, every coordinate finite, every index
 * below vertex_count, counts of at most 2^31 - 1 and within the host's memory
 * (ARCUS_ERROR_OUT_OF_MEMORY).  How far from the origin it may lie (1e18 m) is
 * checked, in metres, where it is used.  Errors name the argument:
 * "indices[7] = 12 is not below vertex_count 10", "vertices[4] = nan is not finite". */
ARCUS_API arcus_status arcus_mesh_create(arcus_context_t* ctx, size_t vertex_count, const double* vertices,
                                         size_t triangle_count, const uint32_t* indices, arcus_mesh_t** out);
ARCUS_API arcus_status arcus_mesh_retain(arcus_mesh_t* mesh);
ARCUS_API arcus_status arcus_mesh_release(arcus_mesh_t* mesh);
/* Its counts; either pointer may be NULL (not wanted). */
ARCUS_API arcus_status arcus_mesh_get_counts(arcus_mesh_t* mesh, size_t* vertex_count, size_t* triangle_count);
/* The mesh file at `path` (OBJ, PLY, OFF or STL, as every engine reads them): the same
 * mesh as arcus_mesh_create on its arrays.  A missing or unreadable file is
 * ARCUS_ERROR_IO, a malformed one ARCUS_ERROR_INVALID_ARGUMENT; both name the file. */
ARCUS_API arcus_status arcus_mesh_load(arcus_context_t* ctx, const char* path, arcus_mesh_t** out);
/* Its arrays: vertex_count × 3 doubles and triangle_count × 3 indices (counts from
 * arcus_mesh_get_counts); either pointer may be NULL (not wanted). */
ARCUS_API arcus_status arcus_mesh_get_arrays(arcus_mesh_t* mesh, double* vertices, uint32_t* indices);

#ifdef __cplusplus
}
#endif
#endif /* ARCUS_SCENE_H */
