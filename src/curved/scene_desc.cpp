#include "curved/scene_desc.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <system_error>
#include <utility>

#include "core/format.h"
#include "core/limits.h"
#include "curved/params.h"
#include "scene/common_keys.h"
#include "scene/json_reader.h"

namespace arcus::curved {

namespace {

namespace fs = std::filesystem;
using json::Document;
using json::Node;

constexpr double kPi = 3.14159265358979323846;
constexpr double kMaxFanDegrees = 360.0;  // beyond a full turn a fan only repeats itself

double max_abs(const Vec3& v) { return std::max({std::fabs(v[0]), std::fabs(v[1]), std::fabs(v[2])}); }
// The unit vector along v, scaled by the largest component first, so that neither 1e200
// (v·v overflows) nor 1e-200 (v·v underflows) loses the direction.
Vec3 direction_of(const Vec3& v) {
  const double m = max_abs(v);
  const Vec3 w{v[0] / m, v[1] / m, v[2] / m};
  const double inv = 1.0 / std::sqrt(dot(w, w));
  return {w[0] * inv, w[1] * inv, w[2] * inv};
}

// Rodrigues' rotation of v about the unit axis k by angle a.
Vec3 rotated(const Vec3& v, const Vec3& k, double a) {
  const Vec3 kxv = cross(k, v);
  const double c = std::cos(a), s = std::sin(a), kv = dot(k, v) * (1 - c);
  return {v[0] * c + kxv[0] * s + k[0] * kv, v[1] * c + kxv[1] * s + k[1] * kv, v[2] * c + kxv[2] * s + k[2] * kv};
}

void append(std::vector<double>* out, const Vec3& v) { out->insert(out->end(), {v.x, v.y, v.z}); }

Vec3 nonzero_vec3(const Node& node) {
  const Vec3 v = node.vec3();
  if (max_abs(v) == 0) node.fail("must not be the zero vector");
  return v;
}

// ---- medium -----------------------------------------------------------------------------

void parse_constant(const Node& m, const std::string&, MediumDesc* d) {
  m.expect_object({"type", "n"});
  d->n = m.member("n").number();
}

void parse_linear(const Node& m, const std::string&, MediumDesc* d) {
  m.expect_object({"type", "n0", "gradient"});
  d->n0 = m.member("n0").number();
  d->gradient = m.member("gradient").vec3();
}

void parse_linear_n2(const Node& m, const std::string&, MediumDesc* d) {
  m.expect_object({"type", "a", "k"});
  d->a = m.member("a").number();
  d->k = m.member("k").vec3();
}

void parse_luneburg(const Node& m, const std::string&, MediumDesc* d) {
  m.expect_object({"type", "center", "radius"});
  d->center = m.member("center").vec3();
  d->radius = m.member("radius").number();
}

void parse_fisheye(const Node& m, const std::string&, MediumDesc* d) {
  m.expect_object({"type", "center", "radius", "n0"});
  d->center = m.member("center").vec3();
  d->radius = m.member("radius").number();
  d->n0 = m.member("n0").number();
}

arcus_inversion parse_inversion(const Node& node) {
  node.expect_object({"base", "top", "delta_t"});
  return {node.member("base").number(), node.member("top").number(), node.member("delta_t").number()};
}

void parse_atmosphere(const Node& m, const std::string&, MediumDesc* d) {
  m.expect_object({"type", "spherical", "wavelength", "sea_level_temperature", "sea_level_pressure", "inversions"});
  AtmosphereDesc& a = d->atmosphere;
  if (auto v = m.find("spherical")) a.spherical = v->boolean();
  if (auto v = m.find("wavelength")) a.wavelength = v->number();
  if (auto v = m.find("sea_level_temperature")) a.sea_level_temperature = v->number();
  if (auto v = m.find("sea_level_pressure")) a.sea_level_pressure = v->number();
  if (auto v = m.find("inversions")) {
    // Counted before the elements are visited: the limit is the library's.
    if (v->array_size() > ARCUS_MAX_INVERSIONS)
      v->fail("at most " + std::to_string(ARCUS_MAX_INVERSIONS) + " layers");
    for (const Node& e : v->elements()) a.inversions.push_back(parse_inversion(e));
  }
}

// Resolves the file name only: the field creation opens it (and says what is wrong).
std::string grid_file(const Node& node, const std::string& base_dir) {
  const std::string name = node.string();
  if (name.empty()) node.fail("must not be empty");
  // A NUL would end the name early when it reaches the C API.
  if (name.find('\0') != std::string::npos) node.fail("must not contain a NUL character");
  std::error_code ec;
  const fs::path path = fs::absolute(fs::path(base_dir) / name, ec);  // an absolute name stays as it is
  if (ec) node.fail("cannot resolve " + json::quoted(name) + ": " + ec.message());
  return path.string();
}

void parse_grid(const Node& m, const std::string& base_dir, MediumDesc* d) {
  m.expect_object({"type", "file", "dtype", "dims", "origin", "spacing"});
  GridDesc& g = d->grid;
  g.file = grid_file(m.member("file"), base_dir);
  g.dtype = m.member("dtype").choice<int32_t>({{"float32", ARCUS_FLOAT32}, {"float64", ARCUS_FLOAT64}});
  const Node dims = m.member("dims");
  const std::vector<Node> e = dims.elements();
  if (e.size() != 3) dims.fail("expected [nx, ny, nz]");
  for (size_t a = 0; a < 3; ++a) g.dims[a] = static_cast<uint32_t>(e[a].integer(UINT32_MAX));
  g.origin = m.member("origin").vec3();
  g.spacing = m.member("spacing").vec3();
}

using MediumParser = void (*)(const Node&, const std::string&, MediumDesc*);
struct MediumType {
  const char* name;
  arcus_field_kind kind;
  MediumParser parse;
};
const MediumType kMedia[] = {
    {"constant", ARCUS_FIELD_CONSTANT, parse_constant},       {"linear", ARCUS_FIELD_LINEAR, parse_linear},
    {"linear_n2", ARCUS_FIELD_LINEAR_N2, parse_linear_n2},    {"luneburg", ARCUS_FIELD_LUNEBURG, parse_luneburg},
    {"fisheye", ARCUS_FIELD_FISHEYE, parse_fisheye},          {"atmosphere", ARCUS_FIELD_ATMOSPHERE, parse_atmosphere},
    {"grid", ARCUS_FIELD_GRID, parse_grid}};

}  // namespace

void parse_medium(const Node& m, const std::string& base_dir, MediumDesc* d) {
  std::vector<std::pair<const char*, const MediumType*>> options;
  for (const MediumType& t : kMedia) options.emplace_back(t.name, &t);
  const MediumType* type = m.member("type").choice(options);
  d->key_path = m.path();
  d->kind = type->kind;
  type->parse(m, base_dir, d);
}

namespace {

// ---- rays -------------------------------------------------------------------------------

double wavelength(const Node& node) {
  const double w = node.number();
  // Ciddor's dispersion covers these; arcus_curved_advance would flag the ray otherwise.
  if (!(w >= ARCUS_MIN_WAVELENGTH && w <= ARCUS_MAX_WAVELENGTH))
    node.fail("expected a wavelength in nm within 300..1690, got " + number(w));
  return w;
}

double fan_angle(const Node& node) {
  const double deg = node.number();
  if (std::fabs(deg) > kMaxFanDegrees)
    node.fail("must be within -360..360 degrees, got " + number(deg));
  return deg;
}

std::vector<Vec3> fan_directions(const Node& fan, const SceneLimits& limits) {
  fan.expect_object({"direction", "plane_normal", "min_deg", "max_deg", "count"});
  const Vec3 dir = direction_of(nonzero_vec3(fan.member("direction")));
  const Vec3 axis = direction_of(nonzero_vec3(fan.member("plane_normal")));
  // A normal off the perpendicular would sweep a cone instead of a plane.
  if (std::fabs(dot(dir, axis)) > 1e-9) fan.member("plane_normal").fail("must be perpendicular to fan.direction");
  const double lo = fan_angle(fan.member("min_deg")), hi = fan_angle(fan.member("max_deg"));
  if (hi < lo) fan.member("max_deg").fail("must be at least min_deg");
  const size_t count = fan.member("count").integer(limits.max_rays);
  if (count == 0) fan.member("count").fail("must be at least 1");
  std::vector<Vec3> dirs;
  dirs.reserve(count);
  for (size_t i = 0; i < count; ++i) {
    const double deg = count == 1 ? lo : lo + (hi - lo) * double(i) / double(count - 1);
    dirs.push_back(rotated(dir, axis, deg * kPi / 180.0));
  }
  return dirs;
}

// The fan once per wavelength, wavelength-major: ray w·count + i is fan ray i at
// wavelength w, so each wavelength's rays are one whole fan, in order.
void parse_fan_rays(const Node& rays, const SceneLimits& limits, SceneDesc* s) {
  const Vec3 origin = rays.member("origin").vec3();
  const std::vector<Vec3> dirs = fan_directions(rays.member("fan"), limits);
  std::vector<double> per_fan;  // the wavelengths, one fan each; empty: none given
  if (auto w = rays.find("wavelengths")) {
    if (w->is_number()) {
      per_fan.push_back(wavelength(*w));
    } else {
      const std::vector<Node> e = w->elements();
      if (e.empty()) w->fail("needs at least one wavelength");
      if (e.size() > limits.max_rays / dirs.size())
        w->fail(std::to_string(e.size()) + " wavelengths times " + std::to_string(dirs.size()) +
                " fan rays exceed the limit of " + std::to_string(limits.max_rays) + " rays");
      for (const Node& n : e) per_fan.push_back(wavelength(n));
    }
  }
  const size_t fans = std::max<size_t>(per_fan.size(), 1);
  arcus::limits::require_host_memory(48.0 * double(fans) * double(dirs.size()),
                              rays.path() + ": " + std::to_string(fans * dirs.size()) + " rays");
  s->origins.reserve(3 * fans * dirs.size());
  s->directions.reserve(3 * fans * dirs.size());
  for (size_t f = 0; f < fans; ++f)
    for (const Vec3& d : dirs) {
      append(&s->origins, origin);
      append(&s->directions, d);
    }
  for (double w : per_fan) s->wavelengths.insert(s->wavelengths.end(), dirs.size(), w);
}

void parse_ray_lists(const Node& rays, const SceneLimits& limits, SceneDesc* s) {
  const Node origins_node = rays.member("origins"), directions_node = rays.member("directions");
  const std::vector<Node> origins = origins_node.elements(), directions = directions_node.elements();
  if (origins.empty()) origins_node.fail("needs at least one ray");
  if (origins.size() > limits.max_rays)
    origins_node.fail("has " + std::to_string(origins.size()) + " rays, more than the limit of " +
                      std::to_string(limits.max_rays));
  if (directions.size() != origins.size())
    directions_node.fail("has " + std::to_string(directions.size()) + " entries, origins has " +
                         std::to_string(origins.size()));
  s->origins.reserve(3 * origins.size());
  s->directions.reserve(3 * origins.size());
  for (const Node& o : origins) append(&s->origins, o.vec3());
  for (const Node& d : directions) append(&s->directions, nonzero_vec3(d));
  if (auto w = rays.find("wavelengths")) {
    if (w->is_number()) {
      s->wavelengths.assign(origins.size(), wavelength(*w));
    } else {
      const std::vector<Node> e = w->elements();
      if (e.size() != origins.size())
        w->fail("has " + std::to_string(e.size()) + " entries, origins has " + std::to_string(origins.size()));
      s->wavelengths.reserve(e.size());
      for (const Node& n : e) s->wavelengths.push_back(wavelength(n));
    }
  }
}

void parse_rays(const Node& rays, const SceneLimits& limits, SceneDesc* s) {
  rays.expect_object({"origin", "fan", "origins", "directions", "wavelengths"});
  const bool fan = rays.find("origin") || rays.find("fan");
  const bool lists = rays.find("origins") || rays.find("directions");
  if (fan == lists) rays.fail("give either \"origin\" and \"fan\", or \"origins\" and \"directions\"");
  if (fan)
    parse_fan_rays(rays, limits, s);
  else
    parse_ray_lists(rays, limits, s);
}

// ---- integrator, box, name --------------------------------------------------------------

}  // namespace

void parse_integrator(const Node& in, arcus_advance_params* p) {
  in.expect_object(
      {"method", "step", "rtol", "atol", "min_step", "max_step", "max_rejections", "length", "max_steps", "precision"});
  p->length = in.member("length").number();
  if (auto v = in.find("method"))
    p->method = v->choice<int32_t>({{"dp45", ARCUS_METHOD_DP45},
                                    {"rk4", ARCUS_METHOD_RK4},
                                    {"rk2", ARCUS_METHOD_RK2},
                                    {"euler", ARCUS_METHOD_EULER}});
  if (auto v = in.find("precision"))
    p->precision = v->choice<int32_t>({{"double", ARCUS_PRECISION_DOUBLE}, {"float", ARCUS_PRECISION_FLOAT}});
  if (auto v = in.find("step")) p->step = v->number();
  if (auto v = in.find("rtol")) p->rtol = v->number();
  if (auto v = in.find("atol")) p->atol = v->number();
  if (auto v = in.find("min_step")) p->min_step = v->number();
  if (auto v = in.find("max_step")) p->max_step = v->number();
  if (auto v = in.find("max_rejections")) p->max_rejections = static_cast<uint32_t>(v->integer(UINT32_MAX));
  if (auto v = in.find("max_steps")) p->max_steps = v->integer(UINT64_MAX);
}

void parse_box(const Node& box, arcus_advance_params* p) {
  box.expect_object({"min", "max"});
  const Vec3 lo = box.member("min").vec3(), hi = box.member("max").vec3();
  for (int a = 0; a < 3; ++a)
    if (!(lo[a] < hi[a])) box.member("max").fail("must exceed min on every axis");
  p->use_box = 1;
  store(lo, p->box_min);
  store(hi, p->box_max);
}

Node field_member(const Node& root) {
  const std::optional<Node> field = root.find("field"), medium = root.find("medium");
  if (field && medium) medium->fail("\"medium\" is the arcus 0.9 spelling of \"field\": give one of them");
  return medium ? *medium : root.member("field");
}

namespace {

SceneDesc parse_document(const Document& doc, const std::string& base_dir, const SceneLimits& limits) {
  SceneDesc s;
  s.file = doc.file_name();
  const Node root = doc.root();
  root.expect_object(
      {"name", "description", "field", "medium", "rays", "integrator", "box", "record_path", "path_capacity"});
  s.name = scene::parse_name(root.member("name"));
  if (auto v = root.find("description")) s.description = v->string();
  parse_medium(field_member(root), base_dir, &s.medium);
  parse_rays(root.member("rays"), limits, &s);
  default_advance_params(&s.params);
  parse_integrator(root.member("integrator"), &s.params);
  if (auto v = root.find("box")) parse_box(*v, &s.params);
  if (auto v = root.find("record_path")) s.params.record_path = v->boolean() ? 1 : 0;
  if (auto v = root.find("path_capacity")) s.params.path_capacity = static_cast<uint32_t>(v->integer(UINT32_MAX));
  s.document = doc.dump();
  return s;
}

}  // namespace

const char* medium_type_name(arcus_field_kind kind) {
  for (const MediumType& t : kMedia)
    if (t.kind == kind) return t.name;
  return "unknown";
}

SceneDesc parse_scene_text(const std::string& text, const std::string& file_name, const std::string& base_dir,
                           const SceneLimits& limits) {
  return parse_document(Document::from_text(text, file_name), base_dir, limits);
}

SceneDesc parse_scene_file(const std::string& path, const SceneLimits& limits) {
  const Document doc = Document::from_file(path);
  return parse_document(doc, fs::path(path).parent_path().string(), limits);
}

}  // namespace arcus::curved
