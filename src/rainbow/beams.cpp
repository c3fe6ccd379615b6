#include "rainbow/beams.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <thread>

#include "core/error.h"
#include "core/format.h"

// Fresnel and polarisation at a flat interface: the cast's own code (host and device).
#define ARCUS_USE_RAINBOW_MESH
#include "rainbow/optics.h"

namespace arcus::rainbow {
namespace {

// A convex polygon's corners.  Every piece of a beam is the intersection of the
// shadows of a few faces, so its edges lie on the particle's edges' projections: a
// hexagonal prism's pieces have at most 18; the room left covers near-duplicates.
constexpr int kMaxCorners = 40;
struct Polygon {
  int n = 0;
  double v[kMaxCorners][3];
};

double dot(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// out = r · x, r a row-major 3 × 3 rotation (particle → world).
void rotate(const double* r, const double* x, double* out) {
  for (int i = 0; i < 3; ++i) out[i] = r[3 * i] * x[0] + r[3 * i + 1] * x[1] + r[3 * i + 2] * x[2];
}

// The polygon's area, on a plane of unit normal `normal`.
double area(const Polygon& p, const double* normal) {
  double s = 0;
  for (int i = 0; i < p.n; ++i) {
    const double* a = p.v[i];
    const double* b = p.v[(i + 1) % p.n];
    const double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    s += dot(c, normal);
  }
  return std::fabs(s) / 2;
}

// A face in one orientation: its plane and, per edge, the in-plane inward normal m and
// m · (a corner of the edge), so that x is inside the edge where m · x ≥ that.
struct PlacedFace {
  double normal[3], offset;
  std::vector<double> edge_normal, edge_offset;
};

PlacedFace place_face(const ConvexFace& f, const double* r) {
  PlacedFace p;
  rotate(r, f.normal, p.normal);
  p.offset = f.offset;
  const size_t corners = f.vertices.size() / 3;
  for (size_t i = 0; i < corners; ++i) {
    double a[3], b[3];
    rotate(r, &f.vertices[3 * i], a);
    rotate(r, &f.vertices[3 * ((i + 1) % corners)], b);
    const double e[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    // normal × edge points into a counter-clockwise polygon seen from outside
    double m[3] = {p.normal[1] * e[2] - p.normal[2] * e[1], p.normal[2] * e[0] - p.normal[0] * e[2],
                   p.normal[0] * e[1] - p.normal[1] * e[0]};
    const double l = std::sqrt(dot(m, m));
    for (double& x : m) x /= l;
    p.edge_normal.insert(p.edge_normal.end(), m, m + 3);
    p.edge_offset.push_back(dot(m, a));
  }
  return p;
}

// Sutherland–Hodgman: `p` (on the face's plane) cut to the face's inside.
Polygon clip(const Polygon& p, const PlacedFace& f) {
  Polygon in = p, out;
  for (size_t e = 0; e < f.edge_offset.size() && in.n > 0; ++e) {
    const double* m = &f.edge_normal[3 * e];
    out.n = 0;
    for (int i = 0; i < in.n; ++i) {
      const double* a = in.v[(i + in.n - 1) % in.n];
      const double* b = in.v[i];
      const double sa = dot(m, a) - f.edge_offset[e], sb = dot(m, b) - f.edge_offset[e];
      if ((sa >= 0) != (sb >= 0) && out.n < kMaxCorners) {
        const double t = sa / (sa - sb);
        for (int c = 0; c < 3; ++c) out.v[out.n][c] = a[c] + t * (b[c] - a[c]);
        ++out.n;
      }
      if (sb >= 0 && out.n < kMaxCorners) {
        std::copy(b, b + 3, out.v[out.n]);
        ++out.n;
      }
    }
    in = out;
  }
  return in;
}

struct Beam {
  Polygon polygon;  // on the face it last met
  double k[3];      // its direction
  rb_field field;   // per incident polarisation, power-normalised (rb_interface)
  double area;      // the incident cross-section it carries [m²]
  int p, face;
};

double power(const rb_field& f) { return (rb_power(&f, 0) + rb_power(&f, 1)) / 2; }

void add_glint(std::vector<Glint>& out, int p, const double* k, double area, double cross_section) {
  Glint g;
  g.p = p;
  std::copy(k, k + 3, g.direction);
  g.area = area;
  g.cross_section = cross_section;
  out.push_back(g);
}

// One orientation's beams, depth first.
void trace_orientation(const std::vector<ConvexFace>& faces, double n, int bounces, const double* rotation,
                       std::vector<Beam>& stack, std::vector<Glint>& glints, BeamTotals& totals) {
  std::vector<PlacedFace> placed;
  placed.reserve(faces.size());
  for (const ConvexFace& f : faces) placed.push_back(place_face(f, rotation));
  // Pieces below this share of the shadow are rounding (an edge seen exactly edge-on).
  double shadow = 0;
  for (const PlacedFace& f : placed) shadow += std::max(0.0, -f.normal[2]);
  const double k0[3] = {0, 0, 1};
  rb_field unit;
  for (int pol = 0; pol < 2; ++pol)
    for (int a = 0; a < 3; ++a) unit.e[pol][a] = rb_c(pol == a ? 1.0 : 0.0, 0.0);
  double intercepted = 0;
  for (size_t i = 0; i < faces.size(); ++i) {
    const PlacedFace& f = placed[i];
    if (!(f.normal[2] < 0)) continue;  // faces away from the light or edge-on
    Beam b;
    b.polygon.n = static_cast<int>(faces[i].vertices.size() / 3);
    for (int c = 0; c < b.polygon.n; ++c) rotate(rotation, &faces[i].vertices[3 * c], b.polygon.v[c]);
    b.area = area(b.polygon, f.normal) * -f.normal[2];
    intercepted += b.area;
    double kr[3], kt[3];
    rb_field fr, ft;
    rb_fresnel fres;
    rb_interface(k0, f.normal, 1.0, n, &unit, kr, &fr, kt, &ft, &fres);
    add_glint(glints, 0, kr, b.area, b.area * power(fr));
    totals.scattered[0] += b.area * power(fr);
    std::copy(kt, kt + 3, b.k);
    b.field = ft;
    b.p = 1;
    b.face = static_cast<int>(i);
    stack.push_back(b);
  }
  totals.intercepted += intercepted;
  const double smallest = 1e-12 * intercepted;
  while (!stack.empty()) {
    const Beam b = stack.back();
    stack.pop_back();
    ++totals.beams;
    const double b_area_on_face = area(b.polygon, placed[b.face].normal);
    for (size_t g = 0; g < placed.size(); ++g) {
      const PlacedFace& f = placed[g];
      const double c = dot(f.normal, b.k);
      if (static_cast<int>(g) == b.face || !(c > 0)) continue;
      // the beam's polygon carried along k onto the plane of face g
      Polygon projected;
      projected.n = b.polygon.n;
      for (int v = 0; v < b.polygon.n; ++v) {
        const double t = (f.offset - dot(f.normal, b.polygon.v[v])) / c;
        for (int a = 0; a < 3; ++a) projected.v[v][a] = b.polygon.v[v][a] + t * b.k[a];
      }
      const Polygon piece = clip(projected, f);
      if (piece.n < 3) continue;
      // areas along parallel rays scale alike on any plane: the piece's share of the
      // beam is its share of the projection, the projection's area A·|cos| / cos
      const double whole = b_area_on_face * std::fabs(dot(placed[b.face].normal, b.k)) / c;
      const double share = whole > 0 ? area(piece, f.normal) / whole : 0;
      const double a = b.area * std::min(1.0, share);
      if (!(a > smallest)) {
        totals.dropped += a * power(b.field);
        continue;
      }
      const double inward[3] = {-f.normal[0], -f.normal[1], -f.normal[2]};
      Beam r;
      rb_fresnel fres;
      double kt[3];
      rb_field ft;
      if (rb_interface(b.k, inward, n, 1.0, &b.field, r.k, &r.field, kt, &ft, &fres)) {
        add_glint(glints, b.p, kt, a, a * power(ft));
        if (b.p < 16) totals.scattered[b.p] += a * power(ft);
      }
      if (b.p >= bounces) {
        totals.remaining += a * power(r.field);
        continue;
      }
      r.polygon = piece;
      r.area = a;
      r.p = b.p + 1;
      r.face = static_cast<int>(g);
      stack.push_back(r);
    }
  }
}

}  // namespace

std::vector<ConvexFace> convex_faces(const Particle& particle) {
  require(particle.kind == ARCUS_RAINBOW_SHAPE_MESH && !particle.smooth,
          "beam tracing needs a flat-faced mesh particle (arcus_particle_create_mesh with smooth = 0)");
  const geometry::Mesh& m = particle.mesh;
  const double tolerance = 1e-9 * particle.bound;
  std::vector<ConvexFace> faces;
  std::vector<std::vector<uint32_t>> corners;  // vertex indices per face
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    const double* a = &m.positions[3 * m.triangles[3 * t]];
    const double* b = &m.positions[3 * m.triangles[3 * t + 1]];
    const double* c = &m.positions[3 * m.triangles[3 * t + 2]];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double nrm[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double l = std::sqrt(dot(nrm, nrm));
    if (!(l > tolerance * particle.bound)) continue;  // a degenerate triangle adds no face
    for (double& x : nrm) x /= l;
    const double offset = dot(nrm, a);
    auto same_plane = [&](const ConvexFace& face) {
      return dot(face.normal, nrm) > 1 - 1e-9 && std::fabs(face.offset - offset) < tolerance;
    };
    size_t f = 0;
    while (f < faces.size() && !same_plane(faces[f])) ++f;
    if (f == faces.size()) {
      faces.push_back(ConvexFace{{nrm[0], nrm[1], nrm[2]}, offset, {}});
      corners.emplace_back();
    }
    for (int k = 0; k < 3; ++k) {
      const uint32_t i = m.triangles[3 * t + k];
      if (std::find(corners[f].begin(), corners[f].end(), i) == corners[f].end()) corners[f].push_back(i);
    }
  }
  for (size_t f = 0; f < faces.size(); ++f) {
    ConvexFace& face = faces[f];
    // convex: every vertex on or behind every face's plane
    for (size_t v = 0; v < m.vertex_count(); ++v) {
      const double above = dot(face.normal, &m.positions[3 * v]) - face.offset;
      require(above <= tolerance, "beam tracing needs a convex particle: vertex " + std::to_string(v) + " lies " +
                                      number(above) + " m outside the plane of face " + std::to_string(f));
    }
    // the face's corners counter-clockwise seen from outside, by angle about their mean
    double centre[3] = {0, 0, 0};
    for (uint32_t i : corners[f])
      for (int a = 0; a < 3; ++a) centre[a] += m.positions[3 * i + a] / corners[f].size();
    const double* first = &m.positions[3 * corners[f][0]];
    double x[3] = {first[0] - centre[0], first[1] - centre[1], first[2] - centre[2]};
    const double lx = std::sqrt(dot(x, x));
    for (double& c : x) c /= lx;
    const double y[3] = {face.normal[1] * x[2] - face.normal[2] * x[1], face.normal[2] * x[0] - face.normal[0] * x[2],
                         face.normal[0] * x[1] - face.normal[1] * x[0]};
    std::vector<std::pair<double, uint32_t>> by_angle;
    for (uint32_t i : corners[f]) {
      const double d[3] = {m.positions[3 * i] - centre[0], m.positions[3 * i + 1] - centre[1],
                           m.positions[3 * i + 2] - centre[2]};
      by_angle.emplace_back(std::atan2(dot(d, y), dot(d, x)), i);
    }
    std::sort(by_angle.begin(), by_angle.end());
    require(by_angle.size() + 1 < kMaxCorners, "beam tracing takes faces of at most " +
                                                   std::to_string(kMaxCorners - 2) + " corners; face " +
                                                   std::to_string(f) + " has " + std::to_string(by_angle.size()));
    for (const auto& entry : by_angle)
      face.vertices.insert(face.vertices.end(), &m.positions[3 * entry.second], &m.positions[3 * entry.second] + 3);
  }
  return faces;
}

bool trace_beams(const std::vector<ConvexFace>& faces, double n, int bounces, size_t count, const double* rotations,
                 std::vector<Glint>& glints, BeamTotals& totals, arcus_progress_callback progress,
                 void* progress_user) {
  // Orientations in chunks, each cut into one run per host core, the runs' glints joined
  // in order (the same list for any number of cores); progress between chunks on the
  // caller's thread.
  const size_t chunk = 512;
  const unsigned workers = std::max(1u, std::min(std::thread::hardware_concurrency(), 8u));
  for (size_t first = 0; first < count; first += chunk) {
    const size_t end = std::min(count, first + chunk);
    const unsigned used = static_cast<unsigned>(std::min<size_t>(workers, end - first));
    std::vector<std::vector<Glint>> out(used);
    std::vector<BeamTotals> books(used);
    auto work = [&](unsigned w) {
      std::vector<Beam> stack;
      const size_t from = first + (end - first) * w / used, to = first + (end - first) * (w + 1) / used;
      for (size_t o = from; o < to; ++o)
        trace_orientation(faces, n, bounces, rotations + 9 * o, stack, out[w], books[w]);
    };
    std::vector<std::thread> threads;
    for (unsigned w = 1; w < used; ++w) threads.emplace_back(work, w);
    work(0);
    for (std::thread& t : threads) t.join();
    for (unsigned w = 0; w < used; ++w) {
      glints.insert(glints.end(), out[w].begin(), out[w].end());
      totals.intercepted += books[w].intercepted;
      for (int p = 0; p < 16; ++p) totals.scattered[p] += books[w].scattered[p];
      totals.remaining += books[w].remaining;
      totals.dropped += books[w].dropped;
      totals.beams += books[w].beams;
    }
    if (progress && progress(progress_user, double(end) / count) != 0) return true;
  }
  return false;
}

}  // namespace arcus::rainbow
