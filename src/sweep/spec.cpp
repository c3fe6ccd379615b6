#include "sweep/spec.h"

#include <cmath>
#include <string>

#include "core/format.h"
#include "scene/common_keys.h"  // parse_name
#include "scene/scene.h"

namespace arcus::sweep {
namespace {

using json::Node;

// A particle of a phase_tables spec (arcus.sweep.PARTICLE_KEYS, arcus.halo.SPEC_KEYS).
void check_particle(const Node& p) {
  enum class Kind { sphere, raindrop, mesh, crystal };
  const Kind kind = p.member("kind").choice<Kind>(
      {{"sphere", Kind::sphere}, {"raindrop", Kind::raindrop}, {"mesh", Kind::mesh}, {"crystal", Kind::crystal}});
  if (kind == Kind::crystal) {
    p.expect_object({"kind", "shape", "size", "orientation", "tilt_deg", "sun_elevation_deg", "orientations", "seed"});
    p.member("shape").choice<int>({{"column", 0}, {"plate", 1}});
    if (auto v = p.find("orientation")) v->choice<int>({{"random", 0}, {"horizontal", 1}});
    p.check_numbers({"size", "tilt_deg", "sun_elevation_deg"});
    p.check_integers({{"orientations", 100000000}, {"seed", (uint64_t(1) << 63) - 1}});
    return;
  }
  switch (kind) {
    case Kind::sphere:
      p.expect_object({"kind", "radius", "method", "material", "rotation", "temperature_k", "temperature"});
      p.member("radius").number();
      if (auto v = p.find("method")) v->choice<int>({{"rays", 0}, {"mie", 1}});
      break;
    case Kind::raindrop:
      p.expect_object({"kind", "diameter", "material", "rotation", "temperature_k", "temperature"});
      p.member("diameter").number();
      break;
    default:
      p.expect_object({"kind", "path", "scale", "smooth", "material", "rotation", "temperature_k", "temperature"});
      p.member("path").string();
      p.check_numbers({"scale"});
      if (auto v = p.find("smooth")) v->boolean();
  }
  p.check_numbers({"temperature_k", "temperature"});  // temperature: °C, the spelling of 0.9
  if (auto v = p.find("material")) v->choice<int>({{"water", 0}, {"ice", 1}});
  if (auto v = p.find("rotation"); v && !v->is_null()) {
    const std::vector<Node> rows = v->elements();
    if (rows.size() != 3) v->fail("expected a 3x3 matrix (particle -> world): three rows");
    for (const Node& row : rows) row.vec3();
  }
}

void check_spec(const Node& root) {
  enum class Kind { phase_tables, ocean_grid, frames };
  const Kind kind = root.member("kind").choice<Kind>(
      {{"phase_tables", Kind::phase_tables}, {"ocean_grid", Kind::ocean_grid}, {"frames", Kind::frames}});
  switch (kind) {
    case Kind::phase_tables: {
      root.expect_object({"kind", "name", "description", "particles", "wavelengths", "theta", "phi", "grid",
                          "max_bounces"});
      const Node particles = root.member("particles");
      if (particles.array_size() == 0) particles.fail("expected at least one particle");
      for (const Node& p : particles.elements()) check_particle(p);
      check_axis(root.member("wavelengths"));
      check_axis(root.member("theta"));
      if (auto v = root.find("phi"); v && !v->is_null()) check_axis(*v);
      root.check_integers({{"grid", 8192}, {"max_bounces", 15}});
      break;
    }
    case Kind::ocean_grid:
      root.expect_object({"kind", "name", "description", "scene", "chlorophyll", "a_d400", "a_y440", "width", "height",
                          "photons", "k", "steps", "estimator"});
      root.member("scene").string();
      for (const char* axis : {"chlorophyll", "a_d400", "a_y440"}) check_axis(root.member(axis));
      root.check_integers({{"width", 16384}, {"height", 16384}, {"photons", uint64_t(1) << 40}, {"k", uint64_t(1) << 40},
                      {"steps", uint64_t(1) << 40}});
      if (auto v = root.find("estimator")) v->choice<int>({{"per_step", 0}, {"beam", 1}});
      break;
    case Kind::frames:
      root.expect_object({"kind", "name", "description", "scene", "parameter", "values", "width", "height",
                          "techniques"});
      root.member("scene").string();
      root.member("parameter").string();
      check_axis(root.member("values"));
      root.check_integers({{"width", 16384}, {"height", 16384}});
      if (auto v = root.find("techniques")) {
        if (v->is_array())
          for (const Node& t : v->elements()) t.string();
        else
          v->string();
      }
      break;
  }
  if (auto v = root.find("name")) scene::parse_name(*v);
  if (auto v = root.find("description")) v->string();
}

arcus_scene_s* load(arcus_context_t* ctx, const std::string& path, const scene::GivenMeshes&,
                    const scene::Locked& locked) {
  return scene::document_scene(ctx, path, "sweep", check_spec, locked);
}

const scene::LoaderEntry kLoader("sweep", load, "kind");

}  // namespace

void check_axis(const Node& axis) {
  if (axis.is_number()) {
    axis.number();
    return;
  }
  if (axis.is_array()) {
    if (axis.array_size() > kMaxAxisValues)
      axis.fail("more than " + std::to_string(kMaxAxisValues) + " values");
    for (const Node& v : axis.elements()) v.number();
    return;
  }
  axis.expect_object({"linspace", "range"});
  const auto linspace = axis.find("linspace"), range = axis.find("range");
  if (!linspace == !range) axis.fail("expected a list, {\"linspace\": [first, last, count]} or {\"range\": [first, last, step]}");
  const Node form = linspace ? *linspace : *range;
  const std::vector<Node> e = form.elements();
  if (e.size() != 3) form.fail(linspace ? "expected [first, last, count]" : "expected [first, last, step]");
  const double first = e[0].number(), last = e[1].number();
  if (linspace) {
    e[2].integer(kMaxAxisValues);
    return;
  }
  const double step = e[2].number();
  if (!(step > 0) || last < first) form.fail("expected step > 0 and last >= first");
  const double count = std::floor((last - first) / step + 1e-9) + 1;
  if (!(count <= double(kMaxAxisValues)))
    form.fail("makes " + number(count) + " values, more than " + std::to_string(kMaxAxisValues) + " (a larger step?)");
}

}  // namespace arcus::sweep
