/*
 * arcus — light transport in participating media, over OpenCL.
 * The one header a user includes (C99, usable from C++).  It gathers one header per
 * topic, as Embree splits rtcore_*.h:
 *   arcus_core.h    status, version, devices, contexts, errors, jobs, features
 *   arcus_scene.h   scene files (JSON), read by the library for every engine
 *   arcus_curved.h  curved light: index-of-refraction fields and advancing rays
 *   arcus_render.h  rendering through curved light
 *   arcus_ocean.h   underwater light: the bio-optical model, spectral photon tracing
 *   arcus_rainbow.h rainbows and halos: phase functions of drops and crystals, Mie, skies
 *   arcus_translucency.h  translucent materials: the dipole model, measured materials
 *   arcus_image.h   reading input images (sky images)
 */
#ifndef ARCUS_ARCUS_H
#define ARCUS_ARCUS_H

#include "arcus_core.h"
#include "arcus_scene.h"
#include "arcus_curved.h"
#include "arcus_render.h"
#include "arcus_ocean.h"
#include "arcus_rainbow.h"
#include "arcus_translucency.h"
#include "arcus_image.h"
#include "arcus_daylight.h"

#endif /* ARCUS_ARCUS_H */
