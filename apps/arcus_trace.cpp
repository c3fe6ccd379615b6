// arcus_trace — runs a scene file through arcus and writes what happened to each ray.
//
//   arcus_trace SCENE.json [--out DIR] [--device N]
//
// Reads the scene, builds its index-of-refraction field, generates its rays, advances
// them with arcus_advance and writes into DIR (default out/<scene name>):
//   rays.csv    ray, origin xyz, initial direction xyz (as given), end position xyz,
//               end direction xyz (unit), arc length travelled, accepted steps, status
//   paths.csv   ray, point, x, y, z          (only when the scene records paths)
//   summary.md  scene, device, compiled kernel features, timings, rays per status
//   scene.json  the scene as read, so that the outputs carry their input (the
//               plotting script apps/plot_paths.py reads it for the plane of the fan)
// Exit status: 0 on success (partial library results are written, with a warning),
// 2 on any error; the message names the JSON path ("$.medium.radius") it concerns.
//
// Scene schema (also in scenes/README.md).  Every key not listed is an error, so that
// typos are caught; so is a key given twice.  Vectors are [x, y, z]; metres throughout.
//   "name":        string of letters, digits, '_', '-', '.' (names the output directory)
//   "description": string, optional (JSON has no comments)
//   "medium":      {"type": one of
//       "constant"   {n}
//       "linear"     {n0, gradient[3]}                     n  = n0 + gradient·x
//       "linear_n2"  {a, k[3]}                             n² = a + k·x
//       "luneburg"   {center[3], radius}
//       "fisheye"    {center[3], radius, n0}
//       "atmosphere" {spherical: bool, wavelength (nm), sea_level_temperature (K),
//                     sea_level_pressure (Pa), inversions: [{base, top, delta_t}]}
//                    every key optional, defaults from arcus_atmosphere_desc_init
//                    (US Standard Atmosphere 1976, flat, 550 nm, no inversions)
//       "grid"       {file, dtype: "float32"|"float64", dims[3] (integers), origin[3],
//                     spacing[3]}   file: raw little-endian values, relative to the scene
//   "rays": either a fan from one point
//       {"origin": [3], "fan": {"direction": [3] (central direction),
//                               "plane_normal": [3] (axis the fan turns about; ⟂ direction),
//                               "min_deg", "max_deg", "count"}}
//     ray i points along direction turned by min + (max − min)·i/(count − 1) degrees
//     about plane_normal (right-handed: direction +x, normal +z, +1° looks up in y);
//     or explicit lists {"origins": [[3], ...], "directions": [[3], ...]} of equal length.
//   "integrator": {"length" (required), "method": "dp45"|"rk4"|"rk2"|"euler", "step",
//                  "rtol", "atol", "min_step", "max_step", "max_rejections", "max_steps",
//                  "precision": "double"|"float"}   defaults from arcus_advance_params_init
//   "box":         {"min": [3], "max": [3]}   optional; rays stop on leaving it
//   "record_path": bool, optional (false)
//   "path_capacity": integer, optional (0: the library's default)
#include <arcus/arcus.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace fs = std::filesystem;
// Ordered, so that scene.json keeps the author's key order.
using json = nlohmann::ordered_json;

namespace {

constexpr int kExitError = 2;
constexpr double kPi = 3.14159265358979323846;

// Anything that stops the run: a bad command line, a bad scene, a library failure,
// an unwritable output.  The message is complete; main prints it and exits with 2.
struct Failure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

using Vec3 = std::array<double, 3>;

double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Vec3 scaled(const Vec3& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
Vec3 normalized(const Vec3& a) { return scaled(a, 1.0 / std::sqrt(dot(a, a))); }

// ---- reading JSON with paths ----------------------------------------------------------

// nlohmann keeps the last of repeated keys without a word; a repeated key is as much
// a typo as an unknown one, so the parser callback rejects it, naming where it is.
class RepeatedKeyGuard {
 public:
  bool operator()(int, json::parse_event_t event, json& parsed) {
    using E = json::parse_event_t;
    switch (event) {
      case E::object_start:
      case E::array_start:
        frames_.push_back({event == E::array_start, 0, "", {}});
        break;
      case E::key: {
        Frame& f = frames_.back();
        f.key = parsed.get<std::string>();
        if (!f.keys.insert(f.key).second) throw Failure(path() + ": key given twice");
        break;
      }
      case E::object_end:
      case E::array_end:
        frames_.pop_back();
        count_element();
        break;
      case E::value:
        count_element();
        break;
    }
    return true;
  }

 private:
  struct Frame {
    bool is_array;
    size_t index;  // elements of an array completed so far
    std::string key;
    std::set<std::string> keys;
  };
  void count_element() {
    if (!frames_.empty() && frames_.back().is_array) ++frames_.back().index;
  }
  std::string path() const {
    std::string p = "$";
    for (const Frame& f : frames_) p += f.is_array ? "[" + std::to_string(f.index) + "]" : "." + f.key;
    return p;
  }
  std::vector<Frame> frames_;
};

// A JSON value and its path in the scene ("$.medium.center[1]"): every accessor
// checks the type and every error names the path.
class Node {
 public:
  Node(const json& value, std::string path) : value_(&value), path_(std::move(path)) {}

  [[noreturn]] void fail(const std::string& what) const { throw Failure(path_ + ": " + what); }

  // An object whose keys all come from `allowed`.
  void expect_object(std::initializer_list<const char*> allowed) const {
    if (!value_->is_object()) fail("expected an object");
    for (const auto& item : value_->items()) {
      bool known = std::any_of(allowed.begin(), allowed.end(), [&](const char* k) { return item.key() == k; });
      if (!known) throw Failure(path_ + "." + item.key() + ": unknown key (allowed here: " + join(allowed) + ")");
    }
  }
  std::optional<Node> find(const char* key) const {
    if (!value_->is_object()) fail("expected an object");
    auto it = value_->find(key);
    if (it == value_->end()) return std::nullopt;
    return Node(*it, path_ + "." + key);
  }
  Node member(const char* key) const {
    if (auto node = find(key)) return *node;
    fail(std::string("missing key \"") + key + "\"");
  }
  std::vector<Node> elements() const {
    if (!value_->is_array()) fail("expected an array");
    std::vector<Node> out;
    for (size_t i = 0; i < value_->size(); ++i) out.emplace_back((*value_)[i], path_ + "[" + std::to_string(i) + "]");
    return out;
  }

  double number() const {
    if (!value_->is_number()) fail("expected a number");
    double v = value_->get<double>();
    if (!std::isfinite(v)) fail("expected a finite number");
    return v;
  }
  uint64_t integer(uint64_t max) const {
    // nlohmann reads a literal without sign as unsigned, a negative one as signed.
    bool non_negative = value_->is_number_unsigned() || (value_->is_number_integer() && value_->get<int64_t>() >= 0);
    if (!non_negative) fail("expected a non-negative integer");
    uint64_t v = value_->get<uint64_t>();
    if (v > max) fail("expected an integer no larger than " + std::to_string(max));
    return v;
  }
  bool boolean() const {
    if (!value_->is_boolean()) fail("expected true or false");
    return value_->get<bool>();
  }
  std::string string() const {
    if (!value_->is_string()) fail("expected a string");
    return value_->get<std::string>();
  }
  Vec3 vec3() const {
    std::vector<Node> e = elements();
    if (e.size() != 3) fail("expected [x, y, z]");
    return {e[0].number(), e[1].number(), e[2].number()};
  }
  // One of a fixed set of names, mapped to its value.
  template <class T>
  T choice(const std::vector<std::pair<const char*, T>>& options) const {
    std::string s = string();
    for (const auto& o : options)
      if (s == o.first) return o.second;
    std::vector<const char*> names;
    for (const auto& o : options) names.push_back(o.first);
    fail("\"" + s + "\" is not one of " + join(names));
  }

 private:
  template <class Names>
  static std::string join(const Names& names) {
    std::string s;
    for (const char* n : names) s += (s.empty() ? "" : ", ") + std::string(n);
    return s;
  }

  const json* value_;
  std::string path_;
};

json read_json(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw Failure(file.string() + ": cannot open");
  try {
    return json::parse(in, RepeatedKeyGuard());
  } catch (const json::parse_error& e) {
    throw Failure(file.string() + ": not valid JSON: " + e.what());
  }
}

// ---- the scene ------------------------------------------------------------------------

// Creates the scene's field on a context; kept as a closure so that the whole scene
// is checked before any OpenCL work starts.
using FieldMaker = std::function<arcus_status(arcus_context_t*, arcus_field_t**)>;

struct Scene {
  fs::path file;
  json document;
  std::string name, description, medium_type;
  FieldMaker make_field;
  std::vector<double> origins, directions;  // count × 3
  arcus_advance_params params;
};

FieldMaker parse_constant(const Node& m, const fs::path&) {
  m.expect_object({"type", "n"});
  double n = m.member("n").number();
  return [=](arcus_context_t* ctx, arcus_field_t** out) { return arcus_field_create_constant(ctx, n, out); };
}

FieldMaker parse_linear(const Node& m, const fs::path&) {
  m.expect_object({"type", "n0", "gradient"});
  double n0 = m.member("n0").number();
  Vec3 g = m.member("gradient").vec3();
  return [=](arcus_context_t* ctx, arcus_field_t** out) { return arcus_field_create_linear(ctx, n0, g.data(), out); };
}

FieldMaker parse_linear_n2(const Node& m, const fs::path&) {
  m.expect_object({"type", "a", "k"});
  double a = m.member("a").number();
  Vec3 k = m.member("k").vec3();
  return [=](arcus_context_t* ctx, arcus_field_t** out) { return arcus_field_create_linear_n2(ctx, a, k.data(), out); };
}

FieldMaker parse_luneburg(const Node& m, const fs::path&) {
  m.expect_object({"type", "center", "radius"});
  Vec3 c = m.member("center").vec3();
  double r = m.member("radius").number();
  return [=](arcus_context_t* ctx, arcus_field_t** out) { return arcus_field_create_luneburg(ctx, c.data(), r, out); };
}

FieldMaker parse_fisheye(const Node& m, const fs::path&) {
  m.expect_object({"type", "center", "radius", "n0"});
  Vec3 c = m.member("center").vec3();
  double r = m.member("radius").number();
  double n0 = m.member("n0").number();
  return
      [=](arcus_context_t* ctx, arcus_field_t** out) { return arcus_field_create_fisheye(ctx, c.data(), r, n0, out); };
}

arcus_inversion parse_inversion(const Node& node) {
  node.expect_object({"base", "top", "delta_t"});
  return {node.member("base").number(), node.member("top").number(), node.member("delta_t").number()};
}

FieldMaker parse_atmosphere(const Node& m, const fs::path&) {
  m.expect_object({"type", "spherical", "wavelength", "sea_level_temperature", "sea_level_pressure", "inversions"});
  arcus_atmosphere_desc desc;
  arcus_atmosphere_desc_init(&desc);
  if (auto v = m.find("spherical")) desc.spherical = v->boolean() ? 1 : 0;
  if (auto v = m.find("wavelength")) desc.wavelength = v->number();
  if (auto v = m.find("sea_level_temperature")) desc.sea_level_temperature = v->number();
  if (auto v = m.find("sea_level_pressure")) desc.sea_level_pressure = v->number();
  std::vector<arcus_inversion> inversions;
  if (auto v = m.find("inversions"))
    for (const Node& e : v->elements()) inversions.push_back(parse_inversion(e));
  return [=](arcus_context_t* ctx, arcus_field_t** out) {
    arcus_atmosphere_desc d = desc;  // points into this closure's own copy of the layers
    d.inversion_count = static_cast<uint32_t>(inversions.size());
    d.inversions = inversions.data();
    return arcus_field_create_atmosphere(ctx, &d, out);
  };
}

FieldMaker parse_grid(const Node& m, const fs::path& scene_dir) {
  m.expect_object({"type", "file", "dtype", "dims", "origin", "spacing"});
  Node file_node = m.member("file");
  fs::path file = scene_dir / file_node.string();  // an absolute path stays as it is
  if (!fs::is_regular_file(file)) file_node.fail("no such file: " + file.string());
  arcus_scalar_type dtype =
      m.member("dtype").choice<arcus_scalar_type>({{"float32", ARCUS_FLOAT32}, {"float64", ARCUS_FLOAT64}});
  std::vector<Node> d = m.member("dims").elements();
  if (d.size() != 3) m.member("dims").fail("expected [nx, ny, nz]");
  std::array<uint32_t, 3> dims;
  for (int a = 0; a < 3; ++a) dims[a] = static_cast<uint32_t>(d[a].integer(UINT32_MAX));
  Vec3 origin = m.member("origin").vec3();
  Vec3 spacing = m.member("spacing").vec3();
  return [=](arcus_context_t* ctx, arcus_field_t** out) {
    return arcus_field_create_grid_from_file(ctx, file.c_str(), dtype, dims.data(), origin.data(), spacing.data(), out);
  };
}

using MediumParser = FieldMaker (*)(const Node&, const fs::path&);
const std::vector<std::pair<const char*, MediumParser>> kMedia = {
    {"constant", parse_constant}, {"linear", parse_linear},   {"linear_n2", parse_linear_n2},
    {"luneburg", parse_luneburg}, {"fisheye", parse_fisheye}, {"atmosphere", parse_atmosphere},
    {"grid", parse_grid}};

void parse_medium(const Node& m, const fs::path& scene_dir, Scene* scene) {
  Node type = m.member("type");
  scene->medium_type = type.string();
  scene->make_field = type.choice(kMedia)(m, scene_dir);
}

void append(std::vector<double>* out, const Vec3& v) { out->insert(out->end(), v.begin(), v.end()); }

// Rodrigues' rotation of v about the unit axis k by angle a.
Vec3 rotated(const Vec3& v, const Vec3& k, double a) {
  Vec3 kxv = cross(k, v);
  double c = std::cos(a), s = std::sin(a), kv = dot(k, v) * (1 - c);
  return {v[0] * c + kxv[0] * s + k[0] * kv, v[1] * c + kxv[1] * s + k[1] * kv, v[2] * c + kxv[2] * s + k[2] * kv};
}

Vec3 nonzero_vec3(const Node& node) {
  Vec3 v = node.vec3();
  if (dot(v, v) == 0) node.fail("must not be the zero vector");
  return v;
}

void parse_fan(const Node& fan, const Vec3& origin, Scene* scene) {
  fan.expect_object({"direction", "plane_normal", "min_deg", "max_deg", "count"});
  Vec3 dir = normalized(nonzero_vec3(fan.member("direction")));
  Vec3 axis = normalized(nonzero_vec3(fan.member("plane_normal")));
  // A normal off the perpendicular would sweep a cone instead of a plane.
  if (std::fabs(dot(dir, axis)) > 1e-9) fan.member("plane_normal").fail("must be perpendicular to fan.direction");
  double lo = fan.member("min_deg").number(), hi = fan.member("max_deg").number();
  if (hi < lo) fan.member("max_deg").fail("must be at least min_deg");
  size_t count = fan.member("count").integer(1u << 26);
  if (count == 0) fan.member("count").fail("must be at least 1");
  for (size_t i = 0; i < count; ++i) {
    double deg = count == 1 ? lo : lo + (hi - lo) * double(i) / double(count - 1);
    append(&scene->origins, origin);
    append(&scene->directions, rotated(dir, axis, deg * kPi / 180.0));
  }
}

void parse_ray_lists(const Node& rays, Scene* scene) {
  std::vector<Node> origins = rays.member("origins").elements(), directions = rays.member("directions").elements();
  if (origins.empty()) rays.member("origins").fail("needs at least one ray");
  if (directions.size() != origins.size())
    rays.member("directions")
        .fail("has " + std::to_string(directions.size()) + " entries, origins has " + std::to_string(origins.size()));
  for (const Node& o : origins) append(&scene->origins, o.vec3());
  for (const Node& d : directions) append(&scene->directions, nonzero_vec3(d));
}

void parse_rays(const Node& rays, Scene* scene) {
  rays.expect_object({"origin", "fan", "origins", "directions"});
  bool fan = rays.find("origin") || rays.find("fan"), lists = rays.find("origins") || rays.find("directions");
  if (fan == lists) rays.fail("give either \"origin\" and \"fan\", or \"origins\" and \"directions\"");
  if (fan)
    parse_fan(rays.member("fan"), rays.member("origin").vec3(), scene);
  else
    parse_ray_lists(rays, scene);
}

void parse_integrator(const Node& in, arcus_advance_params* p) {
  in.expect_object(
      {"method", "step", "rtol", "atol", "min_step", "max_step", "max_rejections", "length", "max_steps", "precision"});
  p->length = in.member("length").number();
  if (auto v = in.find("method"))
    p->method = v->choice<arcus_method>({{"dp45", ARCUS_METHOD_DP45},
                                         {"rk4", ARCUS_METHOD_RK4},
                                         {"rk2", ARCUS_METHOD_RK2},
                                         {"euler", ARCUS_METHOD_EULER}});
  if (auto v = in.find("precision"))
    p->precision = v->choice<arcus_precision>({{"double", ARCUS_PRECISION_DOUBLE}, {"float", ARCUS_PRECISION_FLOAT}});
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
  Vec3 lo = box.member("min").vec3(), hi = box.member("max").vec3();
  for (int a = 0; a < 3; ++a)
    if (!(lo[a] < hi[a])) box.member("max").fail("must exceed min on every axis");
  p->use_box = 1;
  std::copy(lo.begin(), lo.end(), p->box_min);
  std::copy(hi.begin(), hi.end(), p->box_max);
}

// The output directory is named after the scene, so the name must be a plain one.
std::string parse_name(const Node& node) {
  std::string name = node.string();
  bool plain = !name.empty() && name != "." && name != ".." && std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
  });
  if (!plain) node.fail("use letters, digits, '_', '-' and '.' only (it names the output directory)");
  return name;
}

Scene parse_scene(const fs::path& file) {
  Scene scene;
  scene.file = file;
  scene.document = read_json(file);
  Node root(scene.document, "$");
  root.expect_object({"name", "description", "medium", "rays", "integrator", "box", "record_path", "path_capacity"});
  scene.name = parse_name(root.member("name"));
  if (auto v = root.find("description")) scene.description = v->string();
  parse_medium(root.member("medium"), file.parent_path(), &scene);
  parse_rays(root.member("rays"), &scene);
  arcus_advance_params_init(&scene.params);
  parse_integrator(root.member("integrator"), &scene.params);
  if (auto v = root.find("box")) parse_box(*v, &scene.params);
  if (auto v = root.find("record_path")) scene.params.record_path = v->boolean() ? 1 : 0;
  if (auto v = root.find("path_capacity")) scene.params.path_capacity = static_cast<uint32_t>(v->integer(UINT32_MAX));
  return scene;
}

// ---- running it -----------------------------------------------------------------------

template <class T, arcus_status (*Release)(T*)>
struct Releaser {
  void operator()(T* handle) const { Release(handle); }
};
using Context = std::unique_ptr<arcus_context_t, Releaser<arcus_context_t, arcus_context_release>>;
using Field = std::unique_ptr<arcus_field_t, Releaser<arcus_field_t, arcus_field_release>>;
using Job = std::unique_ptr<arcus_job_t, Releaser<arcus_job_t, arcus_job_release>>;

std::string library_failure(arcus_status status, const char* message) {
  return std::string(arcus_status_string(status)) + ": " + message;
}

// Throws unless status is a success; `what` says which step (and JSON path) failed.
void check(arcus_status status, arcus_context_t* ctx, const std::string& what) {
  if (status == ARCUS_SUCCESS) return;
  throw Failure(what + ": " + library_failure(status, ctx ? arcus_context_last_error(ctx) : arcus_last_error()));
}

Context create_context(int32_t device) {
  arcus_context_t* ctx = nullptr;
  check(arcus_context_create(device, &ctx), nullptr, "creating the OpenCL context");
  return Context(ctx);
}

struct Results {
  size_t count = 0;
  arcus_status status = ARCUS_SUCCESS;  // or a partial-result status, with its message
  std::string message;
  std::vector<double> end_positions, end_directions, lengths;
  std::vector<uint64_t> steps;
  std::vector<int32_t> ray_status;
  std::vector<uint64_t> path_offsets, path_needed;  // empty without record_path
  std::vector<double> path_points;
  arcus_features features = 0;
  arcus_job_stats stats{};
};

bool partial_result(arcus_status s) { return s == ARCUS_ERROR_INVALID_RAYS || s == ARCUS_ERROR_PATH_OVERFLOW; }

Job advance(arcus_context_t* ctx, arcus_field_t* field, const Scene& scene, Results* results) {
  results->count = scene.origins.size() / 3;
  arcus_job_t* job = nullptr;
  arcus_status s =
      arcus_advance(ctx, field, &scene.params, results->count, scene.origins.data(), scene.directions.data(), nullptr, &job);
  if (partial_result(s)) {
    results->status = s;
    results->message = arcus_context_last_error(ctx);
  } else {
    check(s, ctx, "arcus_advance ($.integrator, $.rays)");
  }
  return Job(job);
}

void read_paths(arcus_context_t* ctx, arcus_job_t* job, Results* r) {
  size_t total = 0;
  check(arcus_job_get_path_size(job, &total), ctx, "reading the path size");
  r->path_offsets.resize(r->count + 1);
  r->path_needed.resize(r->count);
  r->path_points.resize(total * 3);
  check(arcus_job_get_paths(job, r->path_offsets.data(), r->path_points.data(), r->path_needed.data()), ctx,
        "reading the paths");
}

void read_results(arcus_context_t* ctx, arcus_job_t* job, bool with_paths, Results* r) {
  size_t n = r->count;
  r->end_positions.resize(n * 3);
  r->end_directions.resize(n * 3);
  r->lengths.resize(n);
  r->steps.resize(n);
  r->ray_status.resize(n);
  check(arcus_job_get_end_states(job, r->end_positions.data(), r->end_directions.data(), r->steps.data(),
                                 r->ray_status.data(), r->lengths.data()),
        ctx, "reading the end states");
  check(arcus_job_get_features(job, &r->features), ctx, "reading the job's features");
  check(arcus_job_get_stats(job, &r->stats), ctx, "reading the job's statistics");
  if (with_paths) read_paths(ctx, job, r);
}

// ---- writing --------------------------------------------------------------------------

const char* ray_status_name(int32_t s) {
  static const char* const names[] = {"DONE", "LEFT_BOX", "STEP_LIMIT", "FAILED", "INVALID_INPUT"};
  return s >= 0 && s < 5 ? names[s] : "UNKNOWN";
}

// Full round-trip precision: the CSVs are data for analysis, not for reading.
std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

void write_triple(std::ostream& out, const double* v) {
  out << ',' << num(v[0]) << ',' << num(v[1]) << ',' << num(v[2]);
}

std::ofstream open_output(const fs::path& file) {
  std::ofstream out(file);
  if (!out) throw Failure(file.string() + ": cannot write");
  return out;
}

void close_output(std::ofstream& out, const fs::path& file) {
  out.close();
  if (!out) throw Failure(file.string() + ": writing failed");
}

void write_rays_csv(const fs::path& file, const Scene& scene, const Results& r) {
  std::ofstream out = open_output(file);
  out << "ray,origin_x,origin_y,origin_z,dir_x,dir_y,dir_z,end_x,end_y,end_z,end_dir_x,end_dir_y,end_dir_z,"
         "length,steps,status\n";
  for (size_t i = 0; i < r.count; ++i) {
    out << i;
    write_triple(out, &scene.origins[3 * i]);
    write_triple(out, &scene.directions[3 * i]);
    write_triple(out, &r.end_positions[3 * i]);
    write_triple(out, &r.end_directions[3 * i]);
    out << ',' << num(r.lengths[i]) << ',' << r.steps[i] << ',' << ray_status_name(r.ray_status[i]) << '\n';
  }
  close_output(out, file);
}

void write_paths_csv(const fs::path& file, const Results& r) {
  std::ofstream out = open_output(file);
  out << "ray,point,x,y,z\n";
  for (size_t i = 0; i < r.count; ++i)
    for (uint64_t k = r.path_offsets[i]; k < r.path_offsets[i + 1]; ++k) {
      out << i << ',' << k - r.path_offsets[i];
      write_triple(out, &r.path_points[3 * k]);
      out << '\n';
    }
  close_output(out, file);
}

void write_scene_copy(const fs::path& file, const Scene& scene) {
  std::ofstream out = open_output(file);
  out << scene.document.dump(2) << '\n';
  close_output(out, file);
}

std::string features_string(arcus_features features) {
  char buf[512];
  if (arcus_features_to_string(features, buf, sizeof buf) != ARCUS_SUCCESS) return "(unavailable)";
  return buf;
}

size_t truncated_paths(const Results& r) {
  size_t n = 0;
  for (size_t i = 0; i < r.path_needed.size(); ++i) n += r.path_needed[i] > r.path_offsets[i + 1] - r.path_offsets[i];
  return n;
}

void write_status_table(std::ostream& out, const Results& r) {
  std::map<int32_t, size_t> counts;
  for (int32_t s : r.ray_status) ++counts[s];
  out << "| status | rays |\n|---|---|\n";
  for (const auto& c : counts) out << "| " << ray_status_name(c.first) << " | " << c.second << " |\n";
}

void write_summary(const fs::path& file, const Scene& scene, const arcus_device_info& device, const Results& r) {
  std::ofstream out = open_output(file);
  out << "# " << scene.name << "\n\n";
  if (!scene.description.empty()) out << scene.description << "\n\n";
  out << "- scene: `" << scene.file.string() << "` (medium: " << scene.medium_type << ")\n"
      << "- device: " << device.name << " (" << device.platform << ", " << device.version << ")\n"
      << "- features compiled: " << features_string(r.features) << "\n"
      << "- rays: " << r.count << "\n";
  if (!r.path_offsets.empty())
    out << "- path points kept: " << r.path_offsets.back() << " (" << truncated_paths(r)
        << " paths cut short by path_capacity)\n";
  if (r.status != ARCUS_SUCCESS) out << "- library result: " << library_failure(r.status, r.message.c_str()) << "\n";
  out << "\n## Timing\n\n"
      << "| program build | kernel | total (arcus_advance) | program cache hit | lanes | groups |\n"
      << "|---|---|---|---|---|---|\n"
      << "| " << r.stats.build_seconds << " s | " << r.stats.kernel_seconds << " s | " << r.stats.total_seconds
      << " s | " << (r.stats.program_origin != ARCUS_PROGRAM_BUILT ? "yes" : "no") << " | " << r.stats.lanes << " | " << r.stats.groups
      << " |\n\n## Rays per status\n\n";
  write_status_table(out, r);
  close_output(out, file);
}

// Writes every output file; returns their names, for the closing message.
std::vector<std::string> write_outputs(const fs::path& dir, const Scene& scene, const arcus_device_info& device,
                                       const Results& r) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw Failure(dir.string() + ": cannot create the output directory: " + ec.message());
  std::vector<std::string> written{"rays.csv"};
  write_rays_csv(dir / "rays.csv", scene, r);
  if (!r.path_offsets.empty()) {
    write_paths_csv(dir / "paths.csv", r);
    written.push_back("paths.csv");
  }
  write_summary(dir / "summary.md", scene, device, r);
  write_scene_copy(dir / "scene.json", scene);
  written.insert(written.end(), {"summary.md", "scene.json"});
  return written;
}

// ---- command line ---------------------------------------------------------------------

struct Options {
  fs::path scene;
  std::optional<fs::path> out;
  int32_t device = ARCUS_DEVICE_DEFAULT;
};

const char* const kUsage =
    "usage: arcus_trace SCENE.json [--out DIR] [--device N]\n"
    "  --out DIR    where to write rays.csv, paths.csv, summary.md (default out/<scene name>)\n"
    "  --device N   OpenCL device index (default: ARCUS_DEVICE, else the first GPU, else CPU)\n"
    "The scene schema is described in scenes/README.md.\n";

int32_t parse_device(const std::string& s) {
  char* end = nullptr;
  long v = std::strtol(s.c_str(), &end, 10);
  if (s.empty() || *end != '\0' || v < 0 || v > INT32_MAX)
    throw Failure("--device: expected a device index, got \"" + s + "\"");
  return static_cast<int32_t>(v);
}

// Returns nullopt when the usage was asked for.
std::optional<Options> parse_options(int argc, char** argv) {
  Options o;
  std::vector<std::string> args(argv + 1, argv + argc);
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "-h" || a == "--help") return std::nullopt;
    if (a == "--out" || a == "--device") {
      if (i + 1 == args.size()) throw Failure(a + ": missing value\n" + kUsage);
      const std::string& value = args[++i];
      if (a == "--out")
        o.out = value;
      else
        o.device = parse_device(value);
    } else if (!a.empty() && a[0] == '-') {
      throw Failure("unknown option " + a + "\n" + kUsage);
    } else if (o.scene.empty()) {
      o.scene = a;
    } else {
      throw Failure(std::string("more than one scene file given\n") + kUsage);
    }
  }
  if (o.scene.empty()) throw Failure(std::string("no scene file given\n") + kUsage);
  return o;
}

void run(const Options& options) {
  Scene scene = parse_scene(options.scene);
  Context ctx = create_context(options.device);
  arcus_device_info device{};
  check(arcus_context_get_device(ctx.get(), &device), ctx.get(), "querying the device");

  arcus_field_t* raw_field = nullptr;
  check(scene.make_field(ctx.get(), &raw_field), ctx.get(), "creating the medium ($.medium)");
  Field field(raw_field);

  std::cout << "arcus_trace: " << scene.name << ": " << scene.origins.size() / 3 << " rays through "
            << scene.medium_type << " on " << device.name << std::endl;
  Results results;
  Job job = advance(ctx.get(), field.get(), scene, &results);
  read_results(ctx.get(), job.get(), scene.params.record_path != 0, &results);
  if (results.status != ARCUS_SUCCESS)
    std::cerr << "arcus_trace: warning: partial results: " << library_failure(results.status, results.message.c_str())
              << "\n";

  fs::path dir = options.out ? *options.out : fs::path("out") / scene.name;
  std::vector<std::string> written = write_outputs(dir, scene, device, results);
  std::cout << "arcus_trace: wrote";
  for (const std::string& f : written) std::cout << ' ' << (dir / f).string();
  std::cout << std::endl;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    std::optional<Options> options = parse_options(argc, argv);
    if (!options) {
      std::cout << kUsage;
      return 0;
    }
    run(*options);
    return 0;
  } catch (const Failure& e) {
    std::cerr << "arcus_trace: " << e.what() << "\n";
  } catch (const std::exception& e) {  // e.g. out of memory, filesystem errors
    std::cerr << "arcus_trace: unexpected error: " << e.what() << "\n";
  }
  return kExitError;
}
