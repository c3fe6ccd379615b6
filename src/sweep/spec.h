// Sweep specs (scenes/sweeps/*.json, run by bindings/python/arcus/sweep.py on Dask),
// read by the library's strict reader like every scene file: arcus_scene_load gives a
// scene of engine "sweep" whose document Python runs.  The schema is checked here (keys,
// types, integers); what a value means (a mesh file, a scene's contents) is the sweep's.
#pragma once

#include <cstdint>

#include "scene/json_reader.h"

namespace arcus::sweep {

// The most values an axis may have (a sweep of 10^6 tasks is already days of work).
constexpr uint64_t kMaxAxisValues = 1000000;

// An axis as specs and rainbow scenes write them: a number, a list of numbers,
// {"linspace": [first, last, count]} or {"range": [first, last, step]} (last included
// when the steps reach it), with at most kMaxAxisValues values: a step that would make
// more (a range of [100, 180, 1e-9] asked for 596 GiB) is refused naming the axis.
void check_axis(const json::Node& axis);

}  // namespace arcus::sweep
