#include "ocean/scene.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/context.h"  // retain_context
#include "core/error.h"
#include "scene/common_keys.h"
#include "scene/json_reader.h"
#include "sky/scattering.h"

namespace arcus::ocean {
namespace {

using json::Document;
using json::Node;

constexpr double kPi = 3.14159265358979323846;
constexpr double kInf = std::numeric_limits<double>::infinity();

double positive(const Node& n) {
  const double v = n.number();
  if (!(v > 0)) n.fail("expected a positive number");
  return v;
}

std::vector<double> numbers(const Node& n) {
  std::vector<double> v;
  for (const Node& e : n.elements()) v.push_back(e.number());
  return v;
}

// A spectrum: one number (flat) or {"nm": [...], "values": [...]}; the values' checks
// (increasing wavelengths, values >= 0) are check_water's and check_light's.
Spectrum parse_spectrum(const Node& n) {
  if (n.is_number()) return {{550}, {n.number()}};
  if (!n.is_object()) n.fail("expected a number or {\"nm\": [...], \"values\": [...]}");
  n.expect_object({"nm", "values"});
  Spectrum s{numbers(n.member("nm")), numbers(n.member("values"))};
  if (s.nm.empty()) n.member("nm").fail("expected at least one wavelength");
  if (s.nm.size() != s.values.size())
    n.member("values").fail("expected as many values as wavelengths (" + std::to_string(s.nm.size()) + ")");
  return s;
}

Phase parse_phase(const Node& n) {
  Phase p;
  p.kind = n.member("kind").choice<Phase::Kind>({{"isotropic", Phase::isotropic},
                                                 {"rayleigh_like", Phase::rayleigh_like},
                                                 {"hg", Phase::hg},
                                                 {"two_term_hg", Phase::two_term_hg},
                                                 {"table", Phase::table}});
  switch (p.kind) {
    case Phase::isotropic:
      n.expect_object({"kind"});
      break;
    case Phase::rayleigh_like:  // pure water's 0.835 unless given (eq. 3.26)
      n.expect_object({"kind", "a"});
      p.a = 0.835;
      if (auto v = n.find("a")) p.a = v->number();
      break;
    case Phase::hg:
      n.expect_object({"kind", "g"});
      p.g_forward = n.member("g").number();
      break;
    case Phase::two_term_hg:  // eq. 3.28–3.29
      n.expect_object({"kind", "g_forward", "g_backward", "forward_weight"});
      p.g_forward = n.member("g_forward").number();
      p.g_backward = n.member("g_backward").number();
      p.forward_weight = n.member("forward_weight").number();
      break;
    case Phase::table:
      n.expect_object({"kind", "cosines", "values"});
      p.cosines = numbers(n.member("cosines"));
      p.values = numbers(n.member("values"));
      if (p.cosines.size() != p.values.size())
        n.member("values").fail("expected as many values as cosines (" + std::to_string(p.cosines.size()) + ")");
      break;
  }
  return p;
}

Iops parse_iops(const Node& n) {
  n.expect_object({"absorption", "scattering", "phase", "raman", "chlorophyll", "chlorophyll_yield", "a_y440", "s_y",
                   "anti_stokes"});
  Iops i;
  i.absorption = parse_spectrum(n.member("absorption"));
  i.scattering = parse_spectrum(n.member("scattering"));
  i.phase = parse_phase(n.member("phase"));
  if (auto v = n.find("raman")) i.raman = v->boolean();
  if (auto v = n.find("anti_stokes")) i.anti_stokes = v->boolean();
  if (auto v = n.find("chlorophyll")) i.chlorophyll = v->number();
  if (auto v = n.find("chlorophyll_yield")) i.chlorophyll_yield = v->number();
  if (auto v = n.find("a_y440")) i.a_y440 = v->number();
  if (auto v = n.find("s_y")) i.s_y = v->number();
  return i;
}

// The bio-optical model from the thesis' values (Table 4.3) or a preset's, with any of
// its parameters overridden; or water by its IOPs.
Water parse_water(const Node& n) {
  Water w;
  if (n.is_object() && n.find("iops")) {
    n.expect_object({"iops"});
    w.kind = Water::kIops;
    w.iops = parse_iops(n.member("iops"));
    return w;
  }
  n.expect_object({"preset", "chlorophyll", "a_d400", "a_y440", "s_d", "s_y", "chlorophyll_yield",
                   "cdom_yield_scale", "raman_scale", "anti_stokes"});
  w.kind = Water::kBioOptical;
  if (auto v = n.find("preset")) {
    try {
      w.bio = preset(v->string());
    } catch (const Error& e) {
      v->fail(e.what());
    }
  }
  const std::pair<const char*, double BioOptical::*> params[] = {
      {"chlorophyll", &BioOptical::chlorophyll},
      {"a_d400", &BioOptical::a_d400},
      {"a_y440", &BioOptical::a_y440},
      {"s_d", &BioOptical::s_d},
      {"s_y", &BioOptical::s_y},
      {"chlorophyll_yield", &BioOptical::chlorophyll_yield},
      {"cdom_yield_scale", &BioOptical::cdom_yield_scale},
      {"raman_scale", &BioOptical::raman_scale}};
  for (const auto& p : params)
    if (auto v = n.find(p.first)) w.bio.*p.second = v->number();
  if (auto v = n.find("anti_stokes")) w.bio.anti_stokes = v->boolean();
  return w;
}

// {"first_nm", "last_nm", "step_nm"}: the grid's count follows from the range.
Grid parse_grid(const Node& n) {
  n.expect_object({"first_nm", "last_nm", "step_nm"});
  Grid g;
  double last = 780;
  if (auto v = n.find("first_nm")) g.first_nm = v->number();
  if (auto v = n.find("last_nm")) last = v->number();
  if (auto v = n.find("step_nm")) g.step_nm = positive(*v);
  if (!(last >= g.first_nm)) n.fail("last_nm (default 780) must be >= first_nm");
  const double steps = (last - g.first_nm) / g.step_nm;
  if (!(steps <= 100000)) n.fail("more than 100000 wavelengths");
  g.count = static_cast<int>(std::lround(steps)) + 1;
  if (std::abs(g.nm(g.count - 1) - last) > 1e-6 * g.step_nm)
    n.fail("last_nm must be first_nm plus a whole number of step_nm");
  return g;
}


// A light's "spectrum": a number, {"nm", "values"}, or "daylight" for a sun or sky (set
// later from the scene's atmosphere: daylight_spectra); *daylight tells which.
Spectrum parse_light_spectrum(const Node& n, bool sun_or_sky, bool* daylight) {
  *daylight = n.value().is_string();
  if (!*daylight) return parse_spectrum(n);
  if (n.string() != "daylight" || !sun_or_sky)
    n.fail(sun_or_sky ? "expected a number, {\"nm\": [...], \"values\": [...]} or \"daylight\""
                      : "\"daylight\" is the spectrum of a sun or a sky only");
  return {};
}

Light parse_light(const Node& n, bool* daylight) {
  enum class Type { point, spot, sun, directional, sky };
  const Type type = n.member("type").choice<Type>({{"point", Type::point},
                                                   {"spot", Type::spot},
                                                   {"sun", Type::sun},
                                                   {"directional", Type::directional},
                                                   {"sky", Type::sky}});
  Light L;
  switch (type) {
    case Type::point:
      n.expect_object({"type", "position", "spectrum"});
      L.kind = Light::point;
      store(n.member("position").vec3(), L.position);
      break;
    case Type::spot:
      n.expect_object({"type", "position", "direction", "half_angle_deg", "spectrum"});
      L.kind = Light::spot;
      store(n.member("position").vec3(), L.position);
      store(scene::parse_direction(n.member("direction")), L.direction);
      L.half_angle_deg = n.member("half_angle_deg").number();
      break;
    case Type::sun: {
      // Sunlight from that zenith and azimuth: a directional light pointing down, as
      // arcus.ocean.Light.sun makes it.
      n.expect_object({"type", "zenith_deg", "azimuth_deg", "radius", "spectrum"});
      L.kind = Light::directional;
      if (auto v = n.find("radius")) L.radius = v->number();  // a lit disc of the surface
      const Node zn = n.member("zenith_deg");
      const double z = zn.number() * kPi / 180;
      if (!(z >= 0 && z < kPi / 2)) zn.fail("expected a zenith angle in [0, 90) degrees");
      double a = 0;
      if (auto v = n.find("azimuth_deg")) a = v->number() * kPi / 180;
      L.direction[0] = -std::sin(z) * std::cos(a);
      L.direction[1] = -std::sin(z) * std::sin(a);
      L.direction[2] = -std::cos(z);
      break;
    }
    case Type::directional:
      n.expect_object({"type", "direction", "position", "radius", "spectrum"});
      L.kind = Light::directional;
      store(scene::parse_direction(n.member("direction")), L.direction);
      if (auto v = n.find("position")) store(v->vec3(), L.position);
      if (auto v = n.find("radius")) L.radius = v->number();
      break;
    case Type::sky:
      n.expect_object({"type", "radius", "spectrum"});
      L.kind = Light::sky;
      if (auto v = n.find("radius")) L.radius = v->number();
      break;
  }
  L.spectrum = parse_light_spectrum(n.member("spectrum"), type == Type::sun || type == Type::sky, daylight);
  return L;
}

// The shared daylight (docs/daylight.md) as the ocean's sun and sky: the direct sun's
// and the clear sky's plane irradiance on the sea surface, sky::ground_irradiance at the
// daylight sun's zenith in the scene's atmosphere, every 5 nm over the daylight's
// 360–830 nm (a light is 0 outside its spectrum's range).  The sky's radiance is taken
// as uniform with that plane irradiance (the ocean's sky light: below the surface the
// sky is squeezed into Snell's window, where its shape matters little).
void daylight_spectra(const Node& lights, const sky::Atmosphere& atmosphere, OceanSceneDesc* s) {
  const auto& daylight = s->daylight_lights;
  if (daylight.empty()) return;
  const Light* sun = nullptr;
  for (size_t l : daylight)
    if (s->lights[l].kind == Light::directional) sun = sun ? sun : &s->lights[l];
  if (!sun)
    lights.elements()[daylight.front()].member("spectrum").fail(
        "a \"daylight\" sky needs the sun that lights it: a {\"type\": \"sun\", \"spectrum\": \"daylight\"}");
  std::vector<double> nm;
  for (double w = 360; w <= 830 + 1e-9; w += 5) nm.push_back(w);
  std::vector<double> direct(nm.size()), diffuse(nm.size());
  sky::ground_irradiance(atmosphere, std::acos(-sun->direction[2]), nm, direct.data(), diffuse.data());
  for (size_t l : daylight)
    s->lights[l].spectrum = {nm, s->lights[l].kind == Light::sky ? diffuse : direct};
}

// A box corner: numbers, or null for "unbounded on that axis" (JSON has no infinity).
void parse_corner(const Node& n, double sign, double* out) {
  if (n.array_size() != 3) n.fail("expected [x, y, z] (null: unbounded)");
  const auto e = n.elements();
  for (int a = 0; a < 3; ++a) out[a] = e[a].value().is_null() ? sign * kInf : e[a].number();
}

Medium parse_medium(const Node& n) {
  n.expect_object({"surface", "n_water", "bottom_depth", "bottom_albedo", "box"});
  Medium m;
  if (auto v = n.find("surface")) m.surface = v->boolean();
  if (auto v = n.find("n_water")) m.n_water = v->number();
  if (auto v = n.find("bottom_depth"); v && !v->value().is_null()) m.bottom_depth = v->number();
  if (auto v = n.find("bottom_albedo")) m.bottom_albedo = v->number();
  if (auto v = n.find("box"); v && !v->value().is_null()) {
    v->expect_object({"min", "max"});
    parse_corner(v->member("min"), -1, m.box_lo);
    parse_corner(v->member("max"), +1, m.box_hi);
  }
  return m;
}

void parse_photons(const Node& n, TraceParams* p) {
  n.expect_object({"count", "max_interactions", "seed", "wavelengths_per_photon"});
  if (auto v = n.find("count")) p->photons = v->integer(uint64_t(1) << 40);
  if (auto v = n.find("max_interactions")) p->max_interactions = static_cast<int>(v->integer(1u << 20));
  if (auto v = n.find("seed")) p->seed = v->integer(uint64_t(1) << 53);  // exact in a double
  if (auto v = n.find("wavelengths_per_photon")) p->wavelengths_per_photon = static_cast<int>(v->integer(1u << 20));
}

void parse_profile(const Node& n, TraceParams* p) {
  n.expect_object({"depths", "layer"});
  p->depths = numbers(n.member("depths"));
  if (auto v = n.find("layer")) p->layer = v->number();
}


MarchParams parse_march(const Node& n) {
  n.expect_object({"steps", "distance", "k", "estimator", "single_scattering", "multiple_scattering", "estimate_stride",
                   "photon_tile", "step_subsample", "exposure"});
  MarchParams m;
  if (auto v = n.find("steps")) {
    m.steps = static_cast<int>(v->integer(1000000));
    if (m.steps < 1) v->fail("expected at least 1 step");
  }
  if (auto v = n.find("distance")) m.distance = positive(*v);
  if (auto v = n.find("k")) {
    m.k = static_cast<int>(v->integer(65536));
    if (m.k < 1) v->fail("expected at least 1 photon");
  }
  if (auto v = n.find("estimator"))
    m.estimator = v->choice<MarchParams::Estimator>({{"per_step", MarchParams::per_step}, {"beam", MarchParams::beam}});
  if (auto v = n.find("single_scattering")) m.single_scattering = v->boolean();
  if (auto v = n.find("multiple_scattering")) m.multiple_scattering = v->boolean();
  if (auto v = n.find("estimate_stride")) {
    m.estimate_stride = static_cast<int>(v->integer(64));
    if (m.estimate_stride < 1) v->fail("expected at least 1 pixel");
  }
  if (auto v = n.find("photon_tile")) m.photon_tile = v->number();
  if (auto v = n.find("step_subsample")) {
    m.step_subsample = static_cast<int>(v->integer(1000000));
    if (m.step_subsample < 1) v->fail("expected at least 1 step");
  }
  if (auto v = n.find("exposure")) m.exposure = positive(*v);
  return m;
}

// The library's checks name parameters as the C API does ("water.bio.chlorophyll",
// "lights[0].position", "setup.depths[2]"); a scene's message names the JSON path.
std::string as_json_paths(std::string message, const std::vector<std::pair<std::string, std::string>>& renames) {
  static const std::pair<const char*, const char*> kPrefixes[] = {
      {"water.bio.", "$.water."},          {"water.iops.", "$.water.iops."},
      {"water.", "$.water."},              {"grid.count", "$.grid"},
      {"grid.", "$.grid."},                {"lights", "$.lights"},
      {"setup.depths", "$.profile.depths"}, {"setup.layer", "$.profile.layer"},
      {"setup.box", "$.medium.box"},       {"setup.", "$.medium."},
      {"params.photons", "$.photons.count"}, {"params.", "$.photons."}};
  for (const auto& p : kPrefixes)
    if (message.rfind(p.first, 0) == 0) {
      message = p.second + message.substr(std::char_traits<char>::length(p.first));
      break;
    }
  // Hints in the body that name the C API's fields.
  static const std::pair<const char*, const char*> kHints[] = {
      {"(setup.surface = 1)", "($.medium.surface: true)"},
      {"(surface = 1, or box_hi z = 0)", "($.medium.surface: true, or $.medium.box.max z = 0)"}};
  for (const auto& h : kHints) {
    const size_t at = message.find(h.first);
    if (at != std::string::npos) message.replace(at, std::char_traits<char>::length(h.first), h.second);
  }
  for (const auto& r : renames)
    if (message.rfind(r.first, 0) == 0) message = r.second + message.substr(r.first.size());
  return message;
}

// Runs one of the library's checks, its message in the scene's terms (`renames`: paths
// whose JSON key differs from the struct's member).
template <class Check>
void checked(const std::string& file, Check&& check,
             const std::vector<std::pair<std::string, std::string>>& renames = {}) {
  try {
    check();
  } catch (const Error& e) {
    fail(e.status(), file + ": " + as_json_paths(e.what(), renames));
  }
}

bool in_water(const Medium& m, const double* p) {
  for (int a = 0; a < 3; ++a)
    if (p[a] < m.box_lo[a] || p[a] > m.box_hi[a]) return false;
  return !(m.surface && p[2] > 0) && p[2] >= -m.bottom_depth;
}

OceanSceneDesc parse_document(const Document& doc) {
  OceanSceneDesc s;
  const std::string& file = doc.file_name();
  const Node root = doc.root();
  root.expect_object(
      {"name", "description", "water", "grid", "lights", "atmosphere", "medium", "photons", "profile", "view"});
  s.name = scene::parse_name(root.member("name"));
  if (auto v = root.find("description")) s.description = v->string();
  s.water = parse_water(root.member("water"));
  if (auto v = root.find("grid")) s.grid = parse_grid(*v);
  const Node lights = root.member("lights");
  for (const Node& l : lights.elements()) {
    bool daylight = false;
    s.lights.push_back(parse_light(l, &daylight));
    if (daylight) s.daylight_lights.push_back(s.lights.size() - 1);
  }
  if (lights.array_size() == 0) lights.fail("expected at least one light");
  sky::Atmosphere atmosphere;
  if (auto v = root.find("atmosphere")) atmosphere = scene::parse_atmosphere(*v);
  daylight_spectra(lights, atmosphere, &s);
  if (auto v = root.find("medium")) s.medium = parse_medium(*v);
  if (auto v = root.find("photons")) parse_photons(*v, &s.trace);
  if (auto v = root.find("profile")) parse_profile(*v, &s.trace);
  if (auto v = root.find("view")) {
    v->expect_object({"camera", "march"});
    s.has_camera = true;
    // The surface is z = 0: the world's up is +z.
    s.camera = scene::camera_struct(scene::parse_camera(v->member("camera"), {0, 0, 1}));
    if (auto m = v->find("march")) s.march = parse_march(*m);
  }
  checked(file, [&] { check_water(s.water); }, {{"$.water.iops.phase.g_forward", "$.water.iops.phase.g"}});
  checked(file, [&] { check_grid(s.grid); });
  checked(file, [&] { check_trace(s.lights, s.medium, s.trace); });
  // Camera rays are marched through the water (thesis §4.2): they start in it.
  if (s.has_camera && !in_water(s.medium, s.camera.position))
    root.member("view").member("camera").member("position").fail(
        "the camera must be in the water (below the surface, inside the box, above the bottom)");
  return s;
}

arcus_scene_s* load(arcus_context_t* ctx, const std::string& path, const scene::GivenMeshes&,
                    const scene::Locked& locked) {
  auto scene = std::make_unique<OceanScene>(ctx);
  const Document doc = Document::from_file(path);
  scene->desc = parse_document(doc);
  scene->name = scene->desc.name;
  scene->description = scene->desc.description;
  // The document as resolved: a daylight light's spectrum as the numbers it became.
  json::Json resolved = doc.value();
  for (size_t l : scene->desc.daylight_lights) {
    const Spectrum& sp = scene->desc.lights[l].spectrum;
    resolved["lights"][l]["spectrum"] = {{"nm", sp.nm}, {"values", sp.values}};
  }
  scene->document = resolved.dump(2, ' ', false, json::Json::error_handler_t::replace);
  locked([&] { retain_context(ctx); });  // the scene's reference
  return scene.release();
}

const scene::LoaderEntry kLoader("ocean", load, "water");

}  // namespace

OceanSceneDesc read_ocean_scene(const std::string& path) { return parse_document(Document::from_file(path)); }

OceanScene* ocean_scene(arcus_scene_s* scene) {
  auto* o = dynamic_cast<OceanScene*>(scene);
  if (!o) fail(ARCUS_ERROR_INVALID_ARGUMENT, std::string("scene is a ") + scene->engine + " scene, not an ocean one");
  return o;
}

}  // namespace arcus::ocean
