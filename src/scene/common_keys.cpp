#include "scene/common_keys.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "core/error.h"
#include "core/format.h"

namespace arcus::scene {

sky::Atmosphere parse_atmosphere(const json::Node& node) {
  node.expect_object({"site_height", "ozone_du", "aerosol_depth_500", "angstrom_exponent", "aerosol_scale_height",
                      "co2_ppm", "aerosol_albedo", "aerosol_asymmetry", "ground_albedo"});
  sky::Atmosphere a;
  const std::pair<const char*, double*> fields[] = {
      {"site_height", &a.site_height_m},         {"ozone_du", &a.ozone_du},
      {"aerosol_depth_500", &a.aerosol_depth_500}, {"angstrom_exponent", &a.angstrom_exponent},
      {"aerosol_scale_height", &a.aerosol_scale_height_m}, {"co2_ppm", &a.co2_ppm},
      {"aerosol_albedo", &a.aerosol_albedo},     {"aerosol_asymmetry", &a.aerosol_asymmetry},
      {"ground_albedo", &a.ground_albedo}};
  for (const auto& [name, value] : fields)
    if (auto v = node.find(name)) {
      *value = v->number();
      try {
        sky::check_atmosphere(a, "");
      } catch (const Error& e) {
        v->fail(e.what());
      }
    }
  return a;
}

std::string parse_name(const json::Node& node) {
  const std::string name = node.string();
  const bool plain = !name.empty() && name != "." && name != ".." && std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
  });
  if (!plain) node.fail("use letters, digits, '_', '-' and '.' only (it names the output directory)");
  return name;
}

Vec3 parse_direction(const json::Node& node) {
  const Vec3 v = node.vec3();
  const double len = std::hypot(v.x, v.y, v.z);
  if (!(len > 0) || !std::isfinite(len)) node.fail("expected a non-zero direction");
  return {v.x / len, v.y / len, v.z / len};
}

void check_camera(const CameraDesc& c, const std::string& what) {
  for (int a = 0; a < 3; ++a)
    require(std::isfinite(c.position[a]) && std::isfinite(c.look_at[a]) && std::isfinite(c.up[a]),
            what + ": position, look_at and up must be finite");
  const Vec3 forward = c.look_at - c.position;
  require(length(forward) > 0, what + ": look_at must differ from position");
  require(length(cross(forward, c.up)) > 1e-9 * length(forward) * length(c.up),
          what + ": up must not be zero or along the view direction");
  require(std::isfinite(c.vfov_deg) && c.vfov_deg > 0 && c.vfov_deg < 180,
          what + ": vfov_deg = " + number(c.vfov_deg) + " must lie strictly between 0 and 180");
  require(c.width >= 1 && c.height >= 1 && c.width <= kMaxSide && c.height <= kMaxSide,
          what + ": width and height must be 1.." + std::to_string(kMaxSide) + " pixels");
}

CameraDesc camera_desc(const arcus_camera& c) {
  return {vec3(c.position), vec3(c.look_at), vec3(c.up), c.vfov_deg, c.width, c.height};
}

arcus_camera camera_struct(const CameraDesc& d) {
  arcus_camera c{};
  store(d.position, c.position);
  store(d.look_at, c.look_at);
  store(d.up, c.up);
  c.vfov_deg = d.vfov_deg;
  c.width = d.width;
  c.height = d.height;
  return c;
}

Frame camera_frame(const CameraDesc& c) {
  Frame f;
  f.origin = c.position;
  f.forward = normalized(c.look_at - f.origin);
  f.right = normalized(cross(f.forward, c.up));
  f.up = cross(f.right, f.forward);
  f.tan_half = std::tan(0.5 * c.vfov_deg * M_PI / 180.0);
  f.aspect = static_cast<double>(c.width) / c.height;
  return f;
}

Vec3 pixel_direction(const Frame& f, const CameraDesc& c, uint32_t i, uint32_t j) {
  const double px = (2.0 * (i + 0.5) / c.width - 1.0) * f.tan_half * f.aspect;
  const double py = (1.0 - 2.0 * (j + 0.5) / c.height) * f.tan_half;
  return f.forward + px * f.right + py * f.up;
}

void orthographic_ray(const Frame& f, const CameraDesc& c, double height, uint32_t i, uint32_t j, Vec3* origin,
                      Vec3* direction) {
  const double px = (2.0 * (i + 0.5) / c.width - 1.0) * 0.5 * height * f.aspect;
  const double py = (1.0 - 2.0 * (j + 0.5) / c.height) * 0.5 * height;
  *origin = f.origin + px * f.right + py * f.up;
  *direction = f.forward;
}

CameraDesc parse_camera(const json::Node& n, Vec3 default_up) {
  n.expect_object({"position", "look_at", "up", "vfov_deg", "width", "height"});
  CameraDesc d;
  d.position = n.member("position").vec3();
  d.look_at = n.member("look_at").vec3();
  d.up = default_up;
  if (auto v = n.find("up")) d.up = v->vec3();
  d.vfov_deg = n.member("vfov_deg").number();
  d.width = static_cast<uint32_t>(n.member("width").integer(kMaxSide));
  d.height = static_cast<uint32_t>(n.member("height").integer(kMaxSide));
  try {
    check_camera(d, "camera");
  } catch (const Error& e) {
    n.fail(e.what());
  }
  return d;
}

}  // namespace arcus::scene
