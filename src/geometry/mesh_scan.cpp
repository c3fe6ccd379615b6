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
#include "geometry/mesh.h"

namespace arcus::geometry {
namespace {

using std::string_view;

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
  return {v, faces, false};
}

// ---- PLY --------------------------------------------------------------------------------

struct PlyProperty {
  bool list;
  unsigned count_size;  // a list's count: bytes (binary)
  bool count_float;     // a count type of float or double (nonsense, refused)
  unsigned size;        // the value's (a list's items') bytes
  bool is_float;        // float or double: text tokens are decimals, else integers
};

struct PlyElement {
  std::string name;
  uint64_t count;
  uint64_t min_bytes = 0;  // per element: binary bytes, or text tokens
  size_t properties = 0;
  std::vector<PlyProperty> props;
};

// The most items a list (a face's corners) may have: OpenMesh makes room for a list's
// count before reading it, so a count of 2^31 from a damaged file is 16 GB.
constexpr uint64_t kMaxListItems = 65536;

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

// A text PLY's body, token by token as OpenMesh reads it: every value a number of its
// type, every list's count an integer of at most kMaxListItems.  (OpenMesh read on after
// a token it could not parse, with a list count it had not read: 3 GB for one face.)
void scan_ply_text(const std::string& path, string_view body, const std::vector<PlyElement>& elements) {
  size_t pos = 0;
  auto token = [&](const PlyElement& e, uint64_t item) {
    while (pos < body.size() && std::isspace(static_cast<unsigned char>(body[pos]))) ++pos;
    size_t end = pos;
    while (end < body.size() && !std::isspace(static_cast<unsigned char>(body[end]))) ++end;
    if (end == pos)
      refuse(path, "the body ends inside " + e.name + " " + std::to_string(item) + " of " + std::to_string(e.count));
    const string_view t = body.substr(pos, end - pos);
    pos = end;
    return t;
  };
  auto value = [&](const PlyElement& e, uint64_t item, bool is_float) {
    const string_view t = token(e, item);
    long long ignored;
    if (is_float ? !single_number(t) : !integer(t, &ignored))
      refuse(path, e.name + " " + std::to_string(item) + ": " + shown(t) + " is not " +
                       (is_float ? "a finite number within single precision" : "an integer"));
  };
  for (const PlyElement& e : elements)
    for (uint64_t i = 0; i < e.count; ++i)
      for (const PlyProperty& p : e.props) {
        if (!p.list) {
          value(e, i, p.is_float);
          continue;
        }
        long long n = -1;
        const string_view t = token(e, i);
        if (!integer(t, &n) || n < 0 || uint64_t(n) > kMaxListItems)
          refuse(path, e.name + " " + std::to_string(i) + ": " + shown(t) + " is not a list length of 0 to " +
                           std::to_string(kMaxListItems));
        for (long long k = 0; k < n; ++k) value(e, i, p.is_float);
      }
}

// A binary PLY's body, value by value: lists' counts within kMaxListItems and every
// element within the file.
void scan_ply_binary(const std::string& path, string_view body, const std::vector<PlyElement>& elements,
                     bool big_endian) {
  size_t pos = 0;
  auto need = [&](const PlyElement& e, uint64_t item, uint64_t bytes) {
    if (bytes > body.size() - pos)
      refuse(path, "the body ends inside " + e.name + " " + std::to_string(item) + " of " + std::to_string(e.count));
  };
  for (const PlyElement& e : elements)
    for (uint64_t i = 0; i < e.count; ++i)
      for (const PlyProperty& p : e.props) {
        if (!p.list) {
          need(e, i, p.size);
          pos += p.size;
          continue;
        }
        need(e, i, p.count_size);
        uint64_t n = 0;
        for (unsigned b = 0; b < p.count_size; ++b) {
          const unsigned char byte = static_cast<unsigned char>(body[pos + (big_endian ? b : p.count_size - 1 - b)]);
          n = n << 8 | byte;
        }
        // A signed count with its top bit set is negative: refused like a huge one.
        pos += p.count_size;
        if (n > kMaxListItems)
          refuse(path, e.name + " " + std::to_string(i) + ": a list of " + std::to_string(n) + " items, more than " +
                           std::to_string(kMaxListItems));
        need(e, i, n * p.size);
        pos += n * p.size;
      }
}

Declared scan_ply(const std::string& path, string_view text) {
  if (text.substr(0, 4) != "ply\n" && text.substr(0, 5) != "ply\r\n") refuse(path, "not a PLY file (no 'ply' line)");
  // The header ends at a line whose word is "end_header" (OpenMesh reads it word by word
  // and loops for ever without one), within kMaxHeaderBytes.
  Lines lines(text.substr(0, kMaxHeaderBytes), 0);
  std::vector<string_view> t;
  std::vector<PlyElement> elements;
  bool binary = false, big_endian = false, format = false, ended = false;
  while (!ended && lines.next(&t)) {
    if (t.empty() || t[0] == "ply" || t[0] == "comment" || t[0] == "obj_info") continue;
    if (t[0] == "end_header") {
      if (t.size() != 1) refuse_line(path, lines.number(), "expected 'end_header' alone on its line");
      ended = true;
    } else if (t[0] == "format") {
      // A token OpenMesh cannot read as a number (the version) sends its header loop round for ever.
      if (t.size() != 3 || (t[1] != "ascii" && t[1] != "binary_little_endian" && t[1] != "binary_big_endian") ||
          (t[2] != "1.0" && t[2] != "1"))
        refuse_line(path, lines.number(), "expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
      binary = t[1] != "ascii";
      big_endian = t[1] == "binary_big_endian";
      format = true;
    } else if (t[0] == "element") {
      long long count = -1;
      if (t.size() != 3 || !integer(t[2], &count) || count < 0 || uint64_t(count) > kMaxCount)
        refuse_line(path, lines.number(), "expected 'element <name> <count>' with a count of 0 to 2^31 - 1");
      elements.push_back({std::string(t[1]), uint64_t(count)});
    } else if (t[0] == "property") {
      if (elements.empty()) refuse_line(path, lines.number(), "a property before any element");
      PlyElement& e = elements.back();
      auto is_float = [](string_view type) { return type.find("float") == 0 || type == "double"; };
      if (t.size() == 5 && t[1] == "list") {
        const unsigned count_size = ply_size(t[2]);
        if (!count_size || !ply_size(t[3]) || is_float(t[2]))
          refuse_line(path, lines.number(), "unknown or non-integer list count type in " + shown(t[2]));
        e.min_bytes += binary ? count_size : 1;  // a list holds at least its count
        e.props.push_back({true, count_size, false, ply_size(t[3]), is_float(t[3])});
      } else if (t.size() == 3 && ply_size(t[1])) {
        e.min_bytes += binary ? ply_size(t[1]) : 1;
        e.props.push_back({false, 0, false, ply_size(t[1]), is_float(t[1])});
      } else {
        refuse_line(path, lines.number(), "expected 'property <type> <name>' or 'property list <type> <type> <name>'");
      }
      ++e.properties;
    } else {
      refuse_line(path, lines.number(), "unknown header keyword " + shown(t[0]));
    }
  }
  if (!ended)
    refuse(path, "the PLY header has no 'end_header' line within its first " + std::to_string(kMaxHeaderBytes / 1024) +
                     " KiB");
  const size_t body = lines.offset();
  if (!format) refuse(path, "the PLY header has no 'format' line");
  // Every element takes bytes, so the file's size bounds the counts below; one without
  // properties would take none (OpenMesh looped over a million such vertices).
  for (const PlyElement& e : elements)
    if (e.count > 0 && e.props.empty())
      refuse(path, "element " + e.name + " has " + std::to_string(e.count) + " items but no properties");
  // What the declared elements need at least: a text token takes a character and a
  // separator.
  double needed = 0;
  Declared d;
  for (const PlyElement& e : elements) {
    needed += double(e.count) * double(e.min_bytes) * (binary ? 1 : 2);
    if (e.name == "vertex") d.vertices = e.count;
    if (e.name == "face") d.faces = e.count;
  }
  const size_t held = text.size() > body ? text.size() - body : 0;
  if (needed > double(held))
    refuse(path, "the header declares " + std::to_string(d.vertices) + " vertices and " + std::to_string(d.faces) +
                     " faces, which need at least " + std::to_string(uint64_t(needed)) + " bytes, but " +
                     std::to_string(held) + " follow it");
  if (binary)
    scan_ply_binary(path, text.substr(std::min(body, text.size())), elements, big_endian);
  else
    scan_ply_text(path, text.substr(std::min(body, text.size())), elements);
  return d;
}

// ---- OFF --------------------------------------------------------------------------------

// OFF as OpenMesh reads it: the keyword alone on the first line, the counts on the next,
// then the vertices ("x y z") and the faces ("k i1 ... ik"), no comments, no colours (with
// a colour after a face OpenMesh took the next face's corners wrong).  (It reads counts on the keyword's line,
// comments, colours and normals differently from the format's description: a comment
// before the counts became a count of 32547 faces, counts on the first line were skipped
// and the next line's number taken, one of 3e80 vertices.)
Declared scan_off(const std::string& path, string_view text) {
  Lines lines(text, 0);
  std::vector<string_view> t;
  auto next = [&](const char* what) {
    while (lines.next(&t))
      if (!t.empty()) {
        if (t[0][0] == '#') refuse_line(path, lines.number(), "comments in OFF files are not read (OpenMesh misreads them)");
        return;
      }
    refuse(path, std::string("the file ends before ") + what);
  };
  next("the 'OFF' line");
  if (t.size() != 1 || t[0] != "OFF")
    refuse_line(path, lines.number(),
                "expected 'OFF' alone on the first line (binary, coloured or n-dimensional OFF files are not read)");
  next("the counts");
  long long nv = -1, nf = -1, ne = 0;
  if (t.size() != 3 || !integer(t[0], &nv) || !integer(t[1], &nf) || !integer(t[2], &ne) || nv < 0 || nf < 0 ||
      uint64_t(nv) > kMaxCount || uint64_t(nf) > kMaxCount)
    refuse_line(path, lines.number(), "expected the counts 'vertices faces edges' (0 to 2^31 - 1)");
  // What the counts need at least ("0 0 0" a vertex, "3 0 0 0" a face): a file too short
  // for them is refused before they are read one by one.
  if (double(nv) * 6 + double(nf) * 8 > double(text.size()))
    refuse_line(path, lines.number(), "declares " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
                                          " faces, more than the file can hold");
  for (long long i = 0; i < nv; ++i) {
    next("the last vertex");
    if (t.size() != 3) refuse_line(path, lines.number(), "a vertex is 'x y z'");
    require_numbers(path, lines, t, 0, 3, "vertex");
  }
  for (long long i = 0; i < nf; ++i) {
    next("the last face");
    long long k = 0;
    if (!integer(t[0], &k) || k < 3 || t.size() != size_t(k) + 1)
      refuse_line(path, lines.number(), "a face is 'k i1 ... ik' with k >= 3 vertex indices");
    for (long long c = 1; c <= k; ++c) {
      long long index = -1;
      if (!integer(t[c], &index) || index < 0 || index >= nv)
        refuse_line(path, lines.number(), "face: " + shown(t[c]) + " is not the index of one of the " +
                                              std::to_string(nv) + " vertices");
    }
  }
  return {size_t(nv), size_t(nf), false};
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
    return {3 * size_t(count), count, true};
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
  return {vertices, facets, false};
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
