// Rainbow scenes (scenes/rainbow/*.json, scenes/README.md "Rainbow scenes"), read by the
// library's strict reader like every scene file: arcus_scene_load gives a scene of
// engine "rainbow", whose document arcus.rainbow.render turns into tables and a sky.
// The schema is checked here (keys, types, integers); the physics' ranges (a sun above
// the horizon, positive sizes) are checked where the values are used.
#include <string>

#include "scene/common_keys.h"  // parse_name
#include "scene/json_reader.h"
#include "scene/scene.h"
#include "sweep/spec.h"  // check_axis: tables' axes are written as sweep specs write them

namespace arcus::rainbow {
namespace {

using json::Node;

void pair_of_numbers(const Node& n) {
  const std::vector<Node> e = n.elements();
  if (e.size() != 2) n.fail("expected [low, high]");
  e[0].number();
  e[1].number();
}

// One population of drops or crystals (arcus.sky.populations).
void check_population(const Node& p) {
  enum class Shape { sphere, raindrop, crystal };
  Shape shape = Shape::sphere;
  if (auto v = p.find("shape"))
    shape = v->choice<Shape>({{"sphere", Shape::sphere}, {"raindrop", Shape::raindrop}, {"crystal", Shape::crystal}});
  if (shape == Shape::crystal) {
    p.expect_object({"shape", "crystal", "size", "orientation", "tilt_deg", "orientations", "seed", "density"});
    if (auto v = p.find("crystal")) v->choice<int>({{"column", 0}, {"plate", 1}});
    if (auto v = p.find("orientation")) v->choice<int>({{"random", 0}, {"horizontal", 1}});
    p.member("size").number();
    p.member("density").number();
    p.check_numbers({"tilt_deg"});
    p.check_integers({{"orientations", 10000000}, {"seed", uint64_t(1) << 31}});
    return;
  }
  const auto distribution = p.find("distribution");
  if (!distribution) {
    if (shape == Shape::sphere) {
      p.expect_object({"shape", "radius", "density", "method", "nonspherical_above_mm"});
      p.member("radius").number();
      p.check_numbers({"nonspherical_above_mm"});
    } else {
      p.expect_object({"shape", "diameter", "density"});
      p.member("diameter").number();
    }
    p.member("density").number();
  } else {
    enum class Kind { marshall_palmer, gamma, lognormal };
    const Kind kind = distribution->choice<Kind>(
        {{"marshall_palmer", Kind::marshall_palmer}, {"gamma", Kind::gamma}, {"lognormal", Kind::lognormal}});
    if (kind == Kind::marshall_palmer) {
      p.expect_object({"shape", "distribution", "rain_rate_mm_h", "diameter_range_mm", "bins", "method",
                       "nonspherical_above_mm"});
      p.member("rain_rate_mm_h").number();
      if (auto v = p.find("diameter_range_mm")) pair_of_numbers(*v);
    } else {
      // Cloud droplets by their effective radius and variance (Hansen & Travis 1974), or
      // a gamma by its mode and μ (arcus.sky says which combinations go together).
      p.expect_object({"shape", "distribution", "effective_radius", "effective_variance", "mode_radius", "mu",
                       "total_density", "radius_range", "bins", "method", "nonspherical_above_mm"});
      if (kind == Kind::lognormal || !p.find("mode_radius")) p.member("effective_radius").number();
      p.member("total_density").number();
      p.check_numbers({"effective_radius", "effective_variance", "mode_radius", "mu"});
      if (auto v = p.find("radius_range")) pair_of_numbers(*v);
    }
    p.check_integers({{"bins", 200}});
    p.check_numbers({"nonspherical_above_mm"});
  }
  if (auto v = p.find("method")) v->choice<int>({{"rays", 0}, {"mie", 1}});
}

// A background: a spectrum, the shared daylight (the ground with an albedo), or (the
// sky only) an image.
void check_background(const Node& b, bool image_allowed) {
  if (b.find("type")) {
    if (image_allowed) {
      b.expect_object({"type"});
    } else {
      b.expect_object({"type", "albedo"});
      b.check_numbers({"albedo"});
    }
    b.member("type").choice<int>({{"daylight", 0}});
    return;
  }
  if (image_allowed && b.find("image")) {
    b.expect_object({"image", "scale"});
    if (b.member("image").string().empty()) b.member("image").fail("expected a file name");
    b.check_numbers({"scale"});
    return;
  }
  b.expect_object({"spectrum", "radiance"});
  if (auto v = b.find("spectrum")) v->choice<int>({{"flat", 0}, {"rayleigh", 1}});
  b.check_numbers({"radiance"});
}

void check_scene(const Node& root) {
  root.expect_object({"name", "description", "image", "camera", "sun", "atmosphere", "rain", "background", "tables"});
  if (auto v = root.find("atmosphere")) scene::parse_atmosphere(*v);
  if (auto v = root.find("name")) scene::parse_name(*v);
  if (auto v = root.find("description")) v->string();
  if (auto img = root.find("image")) {
    img->expect_object({"width", "height", "fov_deg", "exposure"});
    img->check_integers({{"width", 16384}, {"height", 16384}});
    img->check_numbers({"fov_deg", "exposure"});
  }
  if (auto cam = root.find("camera")) {
    cam->expect_object({"position", "look_azimuth_deg", "look_elevation_deg"});
    if (auto v = cam->find("position")) v->vec3();
    cam->check_numbers({"look_azimuth_deg", "look_elevation_deg"});
  }
  if (auto sun = root.find("sun")) {
    sun->expect_object({"elevation_deg", "azimuth_deg", "diameter_deg", "samples", "spectrum", "temperature_k",
                        "irradiance", "airmass"});
    sun->check_numbers({"elevation_deg", "azimuth_deg", "diameter_deg", "temperature_k", "irradiance", "airmass"});
    sun->check_integers({{"samples", 4096}});
    if (auto v = sun->find("spectrum")) v->choice<int>({{"blackbody", 0}, {"flat", 1}, {"daylight", 2}});
  }
  const Node rain = root.member("rain");
  rain.expect_object({"box_min", "box_max", "march_steps", "populations"});
  rain.member("box_min").vec3();
  rain.member("box_max").vec3();
  rain.check_integers({{"march_steps", 100000}});
  const Node populations = rain.member("populations");
  if (populations.array_size() == 0) populations.fail("expected at least one population");
  for (const Node& p : populations.elements()) check_population(p);
  if (auto bg = root.find("background")) {
    bg->expect_object({"sky", "ground"});
    if (auto v = bg->find("sky")) check_background(*v, true);
    if (auto v = bg->find("ground")) check_background(*v, false);
  }
  if (auto tables = root.find("tables")) {
    tables->expect_object({"wavelengths", "theta", "phi_step_deg", "grid", "max_bounces", "band_samples"});
    if (auto v = tables->find("wavelengths")) sweep::check_axis(*v);
    if (auto v = tables->find("theta")) sweep::check_axis(*v);
    tables->check_numbers({"phi_step_deg"});
    tables->check_integers({{"grid", 8192}, {"max_bounces", 15}, {"band_samples", 64}});
  }
}

arcus_scene_s* load(arcus_context_t* ctx, const std::string& path, const scene::GivenMeshes&,
                    const scene::Locked& locked) {
  return scene::document_scene(ctx, path, "rainbow", check_scene, locked);
}

// "rain" before "camera": rainbow scenes have a camera too (render scenes never rain).
const scene::LoaderEntry kLoader("rainbow", load, "rain", /*precedence=*/1);

}  // namespace
}  // namespace arcus::rainbow
