#include "render/scene_desc.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/format.h"
#include "curved/params.h"
#include "sky/scattering.h"

namespace arcus::render {
namespace {

namespace fs = std::filesystem;
using json::Document;
using json::Node;

std::string resolved(const Node& node, const std::string& base_dir) {
  const fs::path p(node.string());
  if (p.empty()) node.fail("expected a file name");
  return (p.is_absolute() || base_dir.empty() ? p : fs::path(base_dir) / p).lexically_normal().string();
}

Vec3 colour(const Node& node) {
  const Vec3 c = node.vec3();
  for (int a = 0; a < 3; ++a)
    if (c[a] < 0) node.fail("expected non-negative values");
  return c;
}


double positive(const Node& node) {
  const double v = node.number();
  if (!(v > 0)) node.fail("expected a positive number");
  return v;
}


MaterialDesc parse_material(const Node& m, const std::string& name, const std::string& base_dir) {
  m.expect_object({"diffuse", "texture", "uv_scale", "emission", "blackbody_k"});
  MaterialDesc d;
  d.name = name;
  if (auto v = m.find("diffuse")) d.diffuse = colour(*v);
  if (auto v = m.find("texture")) d.texture = resolved(*v, base_dir);
  if (auto v = m.find("uv_scale")) {
    if (v->array_size() != 2) v->fail("expected [su, sv]");
    const auto e = v->elements();
    d.uv_scale = {e[0].number(), e[1].number()};
  }
  if (auto v = m.find("emission")) d.emission = colour(*v);
  if (auto v = m.find("blackbody_k")) d.blackbody_k = positive(*v);
  return d;
}

ObjectDesc parse_object(const Node& o, const std::map<std::string, int>& materials, const std::string& base_dir) {
  ObjectDesc d;
  d.kind = o.member("type").choice<ObjectKind>(
      {{"mesh", ObjectKind::Mesh}, {"sphere", ObjectKind::Sphere}, {"disc", ObjectKind::Disc}});
  switch (d.kind) {
    case ObjectKind::Mesh:
      o.expect_object({"type", "file", "mesh", "material", "translate", "scale", "rotate_deg"});
      if (o.find("file") && o.find("mesh")) o.member("mesh").fail("give \"file\" or \"mesh\", not both");
      if (auto v = o.find("mesh")) {
        d.mesh_name = v->string();
        if (d.mesh_name.empty()) v->fail("expected the name of a mesh given with the scene");
      } else {
        d.file = resolved(o.member("file"), base_dir);
      }
      if (auto v = o.find("translate")) d.translate = v->vec3();
      if (auto v = o.find("scale")) {
        if (v->is_number()) {
          const double s = positive(*v);
          d.scale = {s, s, s};
        } else {
          d.scale = v->vec3();
          for (int a = 0; a < 3; ++a)
            if (!(d.scale[a] > 0)) v->fail("expected positive scale factors");
        }
      }
      if (auto v = o.find("rotate_deg")) d.rotate_deg = v->vec3();
      break;
    case ObjectKind::Sphere:
      o.expect_object({"type", "center", "radius", "material"});
      d.center = o.member("center").vec3();
      d.radius = positive(o.member("radius"));
      break;
    case ObjectKind::Disc:
      o.expect_object({"type", "center", "normal", "radius", "material"});
      d.center = o.member("center").vec3();
      d.normal = scene::parse_direction(o.member("normal"));
      d.radius = positive(o.member("radius"));
      break;
  }
  const Node m = o.member("material");
  const auto it = materials.find(m.string());
  if (it == materials.end()) m.fail("no material named " + json::quoted(m.string()) + " in $.materials");
  d.material = it->second;
  return d;
}

LightDesc parse_light(const Node& l, const sky::Atmosphere& atmosphere) {
  LightDesc d;
  enum class Type { Sun, DaylightSun, Point };
  const Type type = l.member("type").choice<Type>(
      {{"sun", Type::Sun}, {"daylight_sun", Type::DaylightSun}, {"point", Type::Point}});
  d.kind = type == Type::Point ? LightKind::Point : LightKind::Sun;
  if (type == Type::DaylightSun) {
    // The shared sun: its colour is what the atmosphere lets through at its elevation.
    l.expect_object({"type", "elevation_deg", "azimuth_deg"});
    d.daylight = true;
    d.elevation_deg = l.member("elevation_deg").number();
    if (!(d.elevation_deg >= -10 && d.elevation_deg <= 90))
      l.member("elevation_deg").fail("expected -10 to 90 degrees (below -10 the clear sky's twilight, lit over "
                                     "Earth's shadow, is beyond the sky's model), got " + number(d.elevation_deg));
    d.azimuth_deg = l.member("azimuth_deg").number();
    const double e = d.elevation_deg * M_PI / 180, a = d.azimuth_deg * M_PI / 180;
    d.direction = {std::sin(a) * std::cos(e), std::sin(e), std::cos(a) * std::cos(e)};
    // A sun at or below the horizon lights no surface directly: the ground hides it (a
    // ducted ray that still reaches it, as in a Novaya Zemlya scene, is the visible
    // sun's business, an emissive sphere); it still lights the twilight sky.
    if (e > 0) {
      const auto rgb = sky::sun_linear_srgb(atmosphere, M_PI / 2 - e);
      d.power = {rgb[0], rgb[1], rgb[2]};
    } else {
      d.power = {0, 0, 0};
    }
  } else if (d.kind == LightKind::Sun) {
    l.expect_object({"type", "direction", "irradiance"});
    d.direction = scene::parse_direction(l.member("direction"));
    d.power = colour(l.member("irradiance"));
  } else {
    l.expect_object({"type", "position", "intensity"});
    d.position = l.member("position").vec3();
    d.power = colour(l.member("intensity"));
  }
  return d;
}

SkyDesc parse_sky(const Node& s, const std::string& base_dir) {
  SkyDesc d;
  d.kind = s.member("type").choice<SkyKind>(
      {{"constant", SkyKind::Constant}, {"gradient", SkyKind::Gradient}, {"image", SkyKind::Image},
       {"daylight", SkyKind::Daylight}});
  switch (d.kind) {
    case SkyKind::Constant:
      s.expect_object({"type", "color"});
      d.color = colour(s.member("color"));
      break;
    case SkyKind::Gradient:
      s.expect_object({"type", "horizon", "zenith"});
      d.horizon = colour(s.member("horizon"));
      d.zenith = colour(s.member("zenith"));
      break;
    case SkyKind::Image:
      s.expect_object({"type", "file", "intensity"});
      d.file = resolved(s.member("file"), base_dir);
      if (auto v = s.find("intensity")) d.intensity = positive(*v);
      break;
    case SkyKind::Daylight:
      s.expect_object({"type", "intensity"});
      if (auto v = s.find("intensity")) d.intensity = positive(*v);
      break;
  }
  return d;
}

std::vector<double> parse_spectral(const Node& s) {
  s.expect_object({"wavelengths", "count", "min", "max"});
  std::vector<double> w;
  auto check = [](const Node& n, double v) {
    if (!(v >= ARCUS_MIN_WAVELENGTH && v <= ARCUS_MAX_WAVELENGTH))
      n.fail("expected a wavelength in nm within 300..1690, got " + number(v));
  };
  if (auto list = s.find("wavelengths")) {
    for (const Node& e : list->elements()) {
      w.push_back(e.number());
      check(e, w.back());
    }
    if (w.size() < 2) list->fail("expected at least 2 wavelengths");
    return w;
  }
  const uint64_t count = s.member("count").integer(1024);
  const double lo = s.member("min").number(), hi = s.member("max").number();
  check(s.member("min"), lo);
  check(s.member("max"), hi);
  if (count < 2) s.member("count").fail("expected at least 2 wavelengths");
  if (!(lo < hi)) s.member("max").fail("must exceed min");
  // Band centres: each sample stands for an equal band of [min, max].
  for (uint64_t i = 0; i < count; ++i) w.push_back(lo + (hi - lo) * (i + 0.5) / count);
  return w;
}

PhotonDesc parse_photons(const Node& p) {
  p.expect_object({"count", "estimate", "max_radius"});
  PhotonDesc d;
  d.count = p.member("count").integer(uint64_t(1) << 26);
  if (auto v = p.find("estimate")) d.estimate = static_cast<uint32_t>(v->integer(512));
  if (d.estimate < 1) p.member("estimate").fail("expected at least 1 photon");
  if (auto v = p.find("max_radius")) d.max_radius = positive(*v);
  return d;
}

RenderDesc parse_document(const Document& doc, const std::string& base_dir) {
  RenderDesc s;
  s.file = doc.file_name();
  const Node root = doc.root();
  root.expect_object({"name", "description", "field", "medium", "integrator", "bounds", "camera", "materials", "objects",
                      "lights", "sky", "atmosphere", "spectral", "photons", "techniques", "exposure"});
  s.name = scene::parse_name(root.member("name"));
  if (auto v = root.find("description")) s.description = v->string();
  curved::parse_medium(curved::field_member(root), base_dir, &s.medium);
  curved::default_advance_params(&s.params);
  curved::parse_integrator(root.member("integrator"), &s.params);
  if (auto v = root.find("bounds")) {
    curved::parse_box(*v, &s.params);
    s.has_bounds = true;
  }
  s.camera = scene::parse_camera(root.member("camera"), {0, 1, 0});
  std::map<std::string, int> names;
  if (auto v = root.find("materials")) {
    if (!v->is_object()) v->fail("expected an object of named materials");
    for (auto it = v->value().begin(); it != v->value().end(); ++it) {
      names[it.key()] = static_cast<int>(s.materials.size());
      s.materials.push_back(
          parse_material(Node(it.value(), json::child_path(v->path(), it.key()), s.file), it.key(), base_dir));
    }
  }
  if (auto v = root.find("objects"))
    for (const Node& o : v->elements()) s.objects.push_back(parse_object(o, names, base_dir));
  if (auto v = root.find("atmosphere")) s.atmosphere = scene::parse_atmosphere(*v);
  if (auto v = root.find("lights"))
    for (const Node& l : v->elements()) s.lights.push_back(parse_light(l, s.atmosphere));
  if (auto v = root.find("sky")) {
    s.sky = parse_sky(*v, base_dir);
    if (s.sky.kind == SkyKind::Daylight &&
        std::none_of(s.lights.begin(), s.lights.end(), [](const LightDesc& l) { return l.daylight; }))
      v->fail("a daylight sky needs the sun that lights it: a {\"type\": \"daylight_sun\"} in $.lights");
  }
  if (auto v = root.find("spectral")) s.wavelengths = parse_spectral(*v);
  if (auto v = root.find("photons")) s.photons = parse_photons(*v);
  if (auto v = root.find("techniques")) {
    std::string list;
    for (const Node& t : v->elements()) list += (list.empty() ? "" : ",") + t.string();
    try {
      s.techniques = parse_techniques(list);
    } catch (const Error& e) {
      v->fail(e.what());
    }
  }
  if (auto v = root.find("exposure")) s.exposure = positive(*v);
  s.document = doc.dump();
  return s;
}

}  // namespace

uint32_t parse_techniques(const std::string& list) {
  static const std::pair<const char*, uint32_t> kNames[] = {{"smart_step", ARCUS_TECHNIQUE_SMART_STEP},
                                                            {"symmetry", ARCUS_TECHNIQUE_SYMMETRY},
                                                            {"undersample", ARCUS_TECHNIQUE_UNDERSAMPLE},
                                                            {"path_cache", ARCUS_TECHNIQUE_PATH_CACHE},
                                                            {"all", ARCUS_TECHNIQUE_ALL},
                                                            {"none", 0}};
  uint32_t bits = 0;
  std::stringstream in(list);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (item.empty()) continue;
    bool known = false;
    for (const auto& n : kNames)
      if (item == n.first) {
        bits |= n.second;
        known = true;
      }
    require(known, "unknown technique " + json::quoted(item) +
                       " (expected smart_step, symmetry, undersample, path_cache, all or none)");
  }
  return bits;
}

std::string technique_names(uint32_t t) {
  std::string s;
  if (t & ARCUS_TECHNIQUE_SMART_STEP) s += "smart_step,";
  if (t & ARCUS_TECHNIQUE_SYMMETRY) s += "symmetry,";
  if (t & ARCUS_TECHNIQUE_UNDERSAMPLE) s += "undersample,";
  if (t & ARCUS_TECHNIQUE_PATH_CACHE) s += "path_cache,";
  if (s.empty()) return "none";
  s.pop_back();
  return s;
}

RenderDesc parse_render_text(const std::string& text, const std::string& file_name, const std::string& base_dir) {
  return parse_document(Document::from_text(text, file_name), base_dir);
}

RenderDesc parse_render_file(const std::string& path) {
  const Document doc = Document::from_file(path);
  return parse_document(doc, fs::path(path).parent_path().string());
}

}  // namespace arcus::render
