#include "geometry/mesh_scan.h"

#include <cctype>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string_view>
#include <vector>

#include "core/error.h"

namespace arcus::geometry {
namespace {

using std::string_view;

// Counts no mesh of ours comes near; beyond them indices overflow OpenMesh's ints.
constexpr uint64_t kMaxCount = (uint64_t(1) << 31) - 1;
// A PLY header longer than this is no header.
constexpr size_t kMaxHeaderBytes = 64 * 1024;

[[noreturn]] void refuse(const std::string& path, const std::string& what) {
  fail(ARCUS_ERROR_INVALID_ARGUMENT, path + ": " + what);
}

[[noreturn]] void refuse_line(const std::string& path, size_t line, const std::string& what) {
  refuse(path, "line " + std::to_string(line) + ": " + what);
}

// A token for a message: printable, cut short.
std::string shown(string_view token) {
  std::string out;
  for (char c : token.substr(0, 40)) out += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
  return "'" + out + (token.size() > 40 ? "...'" : "'");
}

// Lines of text, numbered from 1, '\r' dropped, comments (from `comment` on) cut.
class Lines {
 public:
  Lines(string_view text, char comment) : text_(text), comment_(comment) {}
  // The next line's tokens (separated by blanks); false at the end.
  bool next(std::vector<string_view>* tokens) {
    if (pos_ >= text_.size()) return false;
    size_t end = text_.find('\n', pos_);
    if (end == string_view::npos) end = text_.size();
    string_view line = text_.substr(pos_, end - pos_);
    pos_ = end + 1;
    ++number_;
    if (comment_) line = line.substr(0, line.find(comment_));
    tokens->clear();
    size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
      size_t j = i;
      while (j < line.size() && !std::isspace(static_cast<unsigned char>(line[j]))) ++j;
      if (j > i) tokens->push_back(line.substr(i, j - i));
      i = j;
    }
    return true;
  }
  size_t number() const { return number_; }
  size_t offset() const { return pos_; }

 private:
  string_view text_;
  char comment_;
  size_t pos_ = 0, number_ = 0;
};

// A decimal number as C++ streams read it into a float (what OpenMesh's text readers
// do): sign, digits with an optional point, optional exponent; finite in single
// precision (a stream fails on overflow, and OpenMesh then skips the whole line).
bool single_number(string_view t) {
  size_t i = 0;
  if (i < t.size() && (t[i] == '+' || t[i] == '-')) ++i;
  size_t digits = 0;
  while (i < t.size() && std::isdigit(static_cast<unsigned char>(t[i]))) ++i, ++digits;
  if (i < t.size() && t[i] == '.') {
    ++i;
    while (i < t.size() && std::isdigit(static_cast<unsigned char>(t[i]))) ++i, ++digits;
  }
  if (digits == 0) return false;
  if (i < t.size() && (t[i] == 'e' || t[i] == 'E')) {
    ++i;
    if (i < t.size() && (t[i] == '+' || t[i] == '-')) ++i;
    size_t exponent = 0;
    while (i < t.size() && std::isdigit(static_cast<unsigned char>(t[i]))) ++i, ++exponent;
    if (exponent == 0) return false;
  }
  if (i != t.size()) return false;
  const float v = std::strtof(std::string(t).c_str(), nullptr);
  return std::isfinite(v);
}

// A decimal integer (optional sign), or false.
bool integer(string_view t, long long* out) {
  if (t.empty() || t.size() > 19) return false;
  size_t i = t[0] == '-' || t[0] == '+' ? 1 : 0;
  if (i == t.size()) return false;
  for (size_t k = i; k < t.size(); ++k)
    if (!std::isdigit(static_cast<unsigned char>(t[k]))) return false;
  *out = std::strtoll(std::string(t).c_str(), nullptr, 10);
  return true;
}

void require_numbers(const std::string& path, const Lines& lines, const std::vector<string_view>& tokens, size_t first,
                     size_t count, const char* what) {
  if (tokens.size() < first + count)
    refuse_line(path, lines.number(), std::string(what) + " needs " + std::to_string(count) + " numbers");
  for (size_t k = first; k < first + count; ++k)
    if (!single_number(tokens[k]))
      refuse_line(path, lines.number(),
                  std::string(what) + ": " + shown(tokens[k]) +
                      " is not a finite number within single precision (OpenMesh would skip the line and "
                      "shift every later index)");
}

// ---- OBJ --------------------------------------------------------------------------------

// An OBJ index (1-based, or negative: counted back from the last defined) into `defined`
// items so far, checked to exist.
void obj_index(const std::string& path, size_t line, string_view token, size_t defined, const char* what) {
  long long i = 0;
  if (!integer(token, &i) || i == 0)
    refuse_line(path, line, std::string("face: ") + shown(token) + " is not a " + what + " index");
  const unsigned long long magnitude = i < 0 ? static_cast<unsigned long long>(-i) : static_cast<unsigned long long>(i);
  if (magnitude > defined)
    refuse_line(path, line, std::string("face: ") + what + " index " + std::string(token) + " names a " + what +
                                " that does not exist (" + std::to_string(defined) + " defined so far)");
}

Declared scan_obj(const std::string& path, string_view text) {
  Lines lines(text, '#');
  std::vector<string_view> t;
  size_t v = 0, vt = 0, vn = 0, faces = 0;
  while (lines.next(&t)) {
    if (t.empty()) continue;
    if (t[0] == "v") {
      require_numbers(path, lines, t, 1, 3, "vertex");
      ++v;
    } else if (t[0] == "vt") {
      require_numbers(path, lines, t, 1, 2, "texture coordinate");
      ++vt;
    } else if (t[0] == "vn") {
      require_numbers(path, lines, t, 1, 3, "normal");
      ++vn;
    } else if (t[0] == "f") {
      if (t.size() < 4) refuse_line(path, lines.number(), "a face needs at least three corners");
      for (size_t k = 1; k < t.size(); ++k) {
        // v, v/vt, v//vn or v/vt/vn
        string_view corner = t[k];
        const size_t a = corner.find('/');
        obj_index(path, lines.number(), corner.substr(0, a), v, "vertex");
        if (a == string_view::npos) continue;
        const size_t b = corner.find('/', a + 1);
        const string_view tex = corner.substr(a + 1, b == string_view::npos ? string_view::npos : b - a - 1);
        if (!tex.empty()) obj_index(path, lines.number(), tex, vt, "texture coordinate");
        if (b != string_view::npos) obj_index(path, lines.number(), corner.substr(b + 1), vn, "normal");
      }
      ++faces;
    }
    if (v > kMaxCount || faces > kMaxCount) refuse_line(path, lines.number(), "more than 2^31 - 1 vertices or faces");
  }
  return {v, faces};
}

// ---- PLY --------------------------------------------------------------------------------

struct PlyElement {
  std::string name;
  uint64_t count;
  uint64_t min_bytes = 0;  // per element: binary bytes, or text tokens
  size_t properties = 0;
};

// Bytes of a PLY scalar type, or 0 for no such type.
unsigned ply_size(string_view type) {
  static const struct {
    const char* name;
    unsigned size;
  } types[] = {{"char", 1},   {"uchar", 1},  {"int8", 1},   {"uint8", 1},  {"short", 2},   {"ushort", 2},
               {"int16", 2},  {"uint16", 2}, {"int", 4},    {"uint", 4},   {"int32", 4},   {"uint32", 4},
               {"float", 4},  {"float32", 4}, {"double", 8}, {"float64", 8}};
  for (const auto& t : types)
    if (type == t.name) return t.size;
  return 0;
}

Declared scan_ply(const std::string& path, string_view text) {
  const size_t end = text.substr(0, kMaxHeaderBytes).find("end_header");
  if (text.substr(0, 4) != "ply\n" && text.substr(0, 5) != "ply\r\n") refuse(path, "not a PLY file (no 'ply' line)");
  if (end == string_view::npos)
    refuse(path, "the PLY header has no 'end_header' line within its first " + std::to_string(kMaxHeaderBytes / 1024) +
                     " KiB");
  size_t body = text.find('\n', end);
  body = body == string_view::npos ? text.size() : body + 1;
  Lines lines(text.substr(0, body), 0);
  std::vector<string_view> t;
  std::vector<PlyElement> elements;
  bool binary = false, format = false;
  while (lines.next(&t)) {
    if (t.empty() || t[0] == "ply" || t[0] == "comment" || t[0] == "obj_info" || t[0] == "end_header") continue;
    if (t[0] == "format") {
      if (t.size() != 3 || (t[1] != "ascii" && t[1] != "binary_little_endian" && t[1] != "binary_big_endian"))
        refuse_line(path, lines.number(), "expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
      binary = t[1] != "ascii";
      format = true;
    } else if (t[0] == "element") {
      long long count = -1;
      if (t.size() != 3 || !integer(t[2], &count) || count < 0 || uint64_t(count) > kMaxCount)
        refuse_line(path, lines.number(), "expected 'element <name> <count>' with a count of 0 to 2^31 - 1");
      elements.push_back({std::string(t[1]), uint64_t(count)});
    } else if (t[0] == "property") {
      if (elements.empty()) refuse_line(path, lines.number(), "a property before any element");
      PlyElement& e = elements.back();
      if (t.size() == 5 && t[1] == "list") {
        const unsigned count_size = ply_size(t[2]);
        if (!count_size || !ply_size(t[3])) refuse_line(path, lines.number(), "unknown list type in " + shown(t[2]));
        e.min_bytes += binary ? count_size : 1;  // a list holds at least its count
      } else if (t.size() == 3 && ply_size(t[1])) {
        e.min_bytes += binary ? ply_size(t[1]) : 1;
      } else {
        refuse_line(path, lines.number(), "expected 'property <type> <name>' or 'property list <type> <type> <name>'");
      }
      ++e.properties;
    } else {
      refuse_line(path, lines.number(), "unknown header keyword " + shown(t[0]));
    }
  }
  if (!format) refuse(path, "the PLY header has no 'format' line");
  // What the declared elements need at least: a text token takes a character and a
  // separator.
  double needed = 0;
  Declared d;
  for (const PlyElement& e : elements) {
    needed += double(e.count) * double(e.min_bytes) * (binary ? 1 : 2);
    if (e.name == "vertex") d.vertices = e.count;
    if (e.name == "face") d.faces = e.count;
  }
  const size_t held = text.size() - body;
  if (needed > double(held))
    refuse(path, "the header declares " + std::to_string(d.vertices) + " vertices and " + std::to_string(d.faces) +
                     " faces, which need at least " + std::to_string(uint64_t(needed)) + " bytes, but " +
                     std::to_string(held) + " follow it");
  return d;
}

// ---- OFF --------------------------------------------------------------------------------

Declared scan_off(const std::string& path, string_view text) {
  Lines lines(text, '#');
  std::vector<string_view> t;
  // The keyword ([ST][C][N][4][n]OFF), on a line of its own or before the counts.
  while (lines.next(&t) && t.empty()) {
  }
  if (t.empty() || t[0].size() < 3 || t[0].substr(t[0].size() - 3) != "OFF") refuse(path, "not an OFF file (no 'OFF')");
  if (t[0].find('n') != string_view::npos || t[0].find('4') != string_view::npos)
    refuse(path, "only 3-D OFF files are read (" + shown(t[0]) + ")");
  const bool binary = t.size() > 1 && t[1] == "BINARY";
  if (binary) refuse(path, "binary OFF files are not read; write it as text");
  size_t skip = 1;
  if (t.size() <= 1) {
    while (lines.next(&t) && t.empty()) {
    }
    skip = 0;
  }
  long long nv = -1, nf = -1, ne = 0;
  if (t.size() < skip + 2 || !integer(t[skip], &nv) || !integer(t[skip + 1], &nf) ||
      (t.size() > skip + 2 && !integer(t[skip + 2], &ne)) || nv < 0 || nf < 0 || uint64_t(nv) > kMaxCount ||
      uint64_t(nf) > kMaxCount)
    refuse_line(path, lines.number(), "expected the counts 'vertices faces edges' (0 to 2^31 - 1)");
  // Every vertex line: three finite coordinates (then optional colour, normal, texture).
  for (long long i = 0; i < nv;) {
    if (!lines.next(&t)) refuse(path, "declares " + std::to_string(nv) + " vertices but ends after " + std::to_string(i));
    if (t.empty()) continue;
    require_numbers(path, lines, t, 0, 3, "vertex");
    ++i;
  }
  // Every face line: k >= 3, then k indices of existing vertices (then an optional colour).
  for (long long i = 0; i < nf;) {
    if (!lines.next(&t)) refuse(path, "declares " + std::to_string(nf) + " faces but ends after " + std::to_string(i));
    if (t.empty()) continue;
    long long k = 0;
    if (!integer(t[0], &k) || k < 3 || t.size() < size_t(k) + 1)
      refuse_line(path, lines.number(), "a face is 'k i1 ... ik' with k >= 3 vertex indices");
    for (long long c = 1; c <= k; ++c) {
      long long index = -1;
      if (!integer(t[c], &index) || index < 0 || index >= nv)
        refuse_line(path, lines.number(), "face: " + shown(t[c]) + " is not the index of one of the " +
                                              std::to_string(nv) + " vertices");
    }
    ++i;
  }
  return {size_t(nv), size_t(nf)};
}

// ---- STL --------------------------------------------------------------------------------

Declared scan_stl(const std::string& path, string_view text) {
  uint32_t count = 0;
  if (text.size() >= 84) std::memcpy(&count, text.data() + 80, 4);
  // Binary exactly when the size matches its count, as OpenMesh decides.
  if (text.size() >= 84 && text.size() == 84 + 50 * uint64_t(count)) {
    for (uint32_t t = 0; t < count; ++t)
      for (int k = 0; k < 9; ++k) {
        float x;
        std::memcpy(&x, text.data() + 84 + 50 * size_t(t) + 12 + 4 * k, 4);
        if (!std::isfinite(x)) refuse(path, "triangle " + std::to_string(t) + " has a non-finite vertex");
      }
    return {3 * size_t(count), count};
  }
  Lines lines(text, 0);
  std::vector<string_view> t;
  size_t vertices = 0, facets = 0;
  while (lines.next(&t)) {
    if (t.empty()) continue;
    if (t[0] == "vertex") {
      require_numbers(path, lines, t, 1, 3, "vertex");
      ++vertices;
    } else if (t[0] == "facet") {
      ++facets;
    }
  }
  if (vertices != 3 * facets)
    refuse(path, std::to_string(facets) + " facets hold " + std::to_string(vertices) + " vertices, not three each");
  return {vertices, facets};
}

}  // namespace

Declared scan_mesh(const std::string& path, const std::string& ext, const std::string& bytes) {
  const string_view text(bytes);
  if (ext == ".obj") return scan_obj(path, text);
  if (ext == ".ply") return scan_ply(path, text);
  if (ext == ".off") return scan_off(path, text);
  return scan_stl(path, text);
}

}  // namespace arcus::geometry
