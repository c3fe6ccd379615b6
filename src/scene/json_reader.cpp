#include "scene/json_reader.h"

#include <algorithm>
#include <cctype>
#include <cfloat>
#include <cmath>
#include <nlohmann/json.hpp>
#include <set>

#include "core/error.h"
#include "core/files.h"
#include "core/format.h"
#include "core/limits.h"

namespace arcus::json {

namespace {

// Longest excerpt of nlohmann's own message kept (it quotes the offending token, which
// can be a whole megabyte-long string).
constexpr size_t kMaxDetail = 200;

[[noreturn]] void fail_at(const std::string& file, const std::string& path, const std::string& what) {
  fail(ARCUS_ERROR_INVALID_ARGUMENT, file + ": " + path + ": " + what);
}

// Bytes in the UTF-8 sequence starting at s[i] (RFC 3629: no overlongs, no surrogates,
// nothing above U+10FFFF), or 0 if it is not a valid one.
size_t utf8_length(const std::string& s, size_t i) {
  auto byte = [&](size_t k) { return k < s.size() ? static_cast<unsigned char>(s[k]) : 0u; };
  auto cont = [&](size_t k) { return (byte(k) & 0xC0u) == 0x80u; };
  const unsigned c = byte(i);
  if (c < 0x80) return 1;
  if (c >= 0xC2 && c <= 0xDF) return cont(i + 1) ? 2 : 0;
  if (c >= 0xE0 && c <= 0xEF) {
    const unsigned lo = c == 0xE0 ? 0xA0 : 0x80, hi = c == 0xED ? 0x9F : 0xBF;
    return byte(i + 1) >= lo && byte(i + 1) <= hi && cont(i + 2) ? 3 : 0;
  }
  if (c >= 0xF0 && c <= 0xF4) {
    const unsigned lo = c == 0xF0 ? 0x90 : 0x80, hi = c == 0xF4 ? 0x8F : 0xBF;
    return byte(i + 1) >= lo && byte(i + 1) <= hi && cont(i + 2) && cont(i + 3) ? 4 : 0;
  }
  return 0;
}

// Text from outside (nlohmann's messages quote raw input) made safe for a message:
// valid UTF-8 kept, control characters and invalid bytes written as \xNN, cut short.
std::string printable(const std::string& s, size_t max_bytes) {
  static const char hex[] = "0123456789abcdef";
  std::string out;
  for (size_t i = 0; i < s.size();) {
    if (out.size() >= max_bytes) return out + "...";
    const auto c = static_cast<unsigned char>(s[i]);
    const size_t n = utf8_length(s, i);
    if (n == 0 || c < 0x20 || c == 0x7F) {
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
      ++i;
    } else {
      out.append(s, i, n);
      i += n;
    }
  }
  return out;
}

bool is_identifier(const std::string& key) {
  if (key.empty() || std::isdigit(static_cast<unsigned char>(key[0]))) return false;
  return std::all_of(key.begin(), key.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
  });
}

// nlohmann's what() without its "[json.exception.parse_error.101] " prefix.
std::string detail(const Json::exception& e) {
  std::string what = e.what();
  if (!what.empty() && what[0] == '[') {
    const size_t end = what.find("] ");
    if (end != std::string::npos) what.erase(0, end + 2);
  }
  return printable(what, kMaxDetail);
}

// Tracks where the parser is, for messages, and rejects what nlohmann would accept
// silently (a repeated key: it keeps the last) or dangerously (deep nesting: when an
// ordered_json object grows it copies its members, recursively, so the "b" of
// {"a": [[[... 100 000 deep ...]]], "b": 1} overflowed the stack).  The callback sees
// each container open, so the depth is refused before the DOM gets deep.
class Guard {
 public:
  explicit Guard(const std::string& file) : file_(file) {}

  bool on_event(Json::parse_event_t event, Json& parsed) {
    using E = Json::parse_event_t;
    switch (event) {
      case E::object_start:
      case E::array_start:
        if (frames_.size() >= static_cast<size_t>(kMaxDepth))
          fail_at(file_, path(), "nesting deeper than " + std::to_string(kMaxDepth) + " levels");
        frames_.push_back({event == E::array_start, 0, "", {}});
        break;
      case E::key: {
        Frame& f = frames_.back();
        f.key = parsed.get<std::string>();
        if (!f.keys.insert(f.key).second) fail_at(file_, path(), "key given twice");
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

  // The value being read: "$.medium.center[1]".
  std::string path() const {
    std::string p = "$";
    for (const Frame& f : frames_) {
      if (f.is_array)
        p += "[" + std::to_string(f.index) + "]";
      else if (!f.keys.empty())  // before the first key there is no member to name
        p = child_path(p, f.key);
    }
    return p;
  }

 private:
  struct Frame {
    bool is_array;
    size_t index;     // elements of an array completed so far
    std::string key;  // the object's latest key
    std::set<std::string> keys;
  };
  void count_element() {
    if (!frames_.empty() && frames_.back().is_array) ++frames_.back().index;
  }

  const std::string& file_;
  std::vector<Frame> frames_;
};

bool only_whitespace(const std::string& text) {
  return text.find_first_not_of(" \t\r\n") == std::string::npos;
}

}  // namespace

// ---- Document -----------------------------------------------------------------------

struct Document::Impl {
  Json value;
  std::string file;
};

Document::Document(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Document::Document(Document&&) noexcept = default;
Document& Document::operator=(Document&&) noexcept = default;
Document::~Document() = default;

Document Document::from_text(const std::string& text, const std::string& file_name) {
  auto impl = std::make_unique<Impl>();
  impl->file = file_name;
  if (only_whitespace(text)) fail_at(file_name, "$", "empty document (expected a JSON object)");
  Guard guard(impl->file);
  try {
    impl->value = Json::parse(text, [&guard](int, Json::parse_event_t event, Json& parsed) {
      return guard.on_event(event, parsed);
    });
  } catch (const Json::out_of_range& e) {
    // 406: a literal beyond a double, e.g. 1e400 (nlohmann's message lacks the file).
    if (e.id == 406)
      fail_at(file_name, guard.path(),
              "number out of range (the largest magnitude is " + number(DBL_MAX) + "): " + detail(e));
    fail_at(file_name, guard.path(), "not valid JSON: " + detail(e));
  } catch (const Json::exception& e) {
    // The path is where the parser had got to, which may lie before the error.
    fail(ARCUS_ERROR_INVALID_ARGUMENT, file_name + ": not valid JSON (after " + guard.path() + "): " + detail(e));
  }
  return Document(std::move(impl));
}

Document Document::from_file(const std::string& path) {
  return from_text(files::read_all(path, limits::scene_file_bytes(), "ARCUS_MAX_SCENE_BYTES"), path);
}

Node Document::root() const { return Node(impl_->value, "$", impl_->file); }
const Json& Document::value() const { return impl_->value; }
const std::string& Document::file_name() const { return impl_->file; }
std::string Document::dump() const { return impl_->value.dump(2, ' ', false, Json::error_handler_t::replace); }

// ---- Node ---------------------------------------------------------------------------

Node::Node(const Json& value, std::string path, const std::string& file_name)
    : value_(&value), path_(std::move(path)), file_(&file_name) {}

void Node::fail(const std::string& what) const { fail_at(*file_, path_, what); }

bool Node::is_object() const { return value_->is_object(); }
bool Node::is_array() const { return value_->is_array(); }
bool Node::is_number() const { return value_->is_number(); }
bool Node::is_null() const { return value_->is_null(); }

namespace {
std::string join(const std::vector<const char*>& names) {
  std::string s;
  for (const char* n : names) s += (s.empty() ? "" : ", ") + std::string(n);
  return s;
}
}  // namespace

void Node::expect_object(std::initializer_list<const char*> allowed) const {
  if (!value_->is_object()) fail("expected an object");
  for (const auto& item : value_->items()) {
    const bool known = std::any_of(allowed.begin(), allowed.end(), [&](const char* k) { return item.key() == k; });
    if (!known)
      fail_at(*file_, child_path(path_, item.key()),
              "unknown key (allowed here: " + join(std::vector<const char*>(allowed)) + ")");
  }
}

std::optional<Node> Node::find(const char* key) const {
  if (!value_->is_object()) fail("expected an object");
  const auto it = value_->find(key);
  if (it == value_->end()) return std::nullopt;
  return Node(*it, child_path(path_, key), *file_);
}

Node Node::member(const char* key) const {
  if (auto node = find(key)) return *node;
  fail(std::string("missing key \"") + key + "\"");
}

std::vector<Node> Node::elements() const {
  if (!value_->is_array()) fail("expected an array");
  std::vector<Node> out;
  out.reserve(value_->size());
  for (size_t i = 0; i < value_->size(); ++i) out.emplace_back((*value_)[i], path_ + "[" + std::to_string(i) + "]", *file_);
  return out;
}

size_t Node::array_size() const {
  if (!value_->is_array()) fail("expected an array");
  return value_->size();
}

double Node::number() const {
  if (!value_->is_number()) fail("expected a number");
  const double v = value_->get<double>();
  if (!std::isfinite(v)) fail("expected a finite number");  // the parser refuses 1e400; kept as a guard
  return v;
}

uint64_t Node::integer(uint64_t max) const {
  // nlohmann reads a literal without sign as unsigned, a negative one as signed, and one
  // with a fraction or exponent (or beyond 64 bits) as a double.
  if (value_->is_number_float()) fail("expected a non-negative integer, got " + arcus::number(value_->get<double>()));
  if (value_->is_number_integer() && !value_->is_number_unsigned() && value_->get<int64_t>() < 0)
    fail("expected a non-negative integer, got " + std::to_string(value_->get<int64_t>()));
  if (!value_->is_number_integer()) fail("expected a non-negative integer");
  const uint64_t v = value_->get<uint64_t>();
  if (v > max) fail("expected an integer no larger than " + std::to_string(max));
  return v;
}

bool Node::boolean() const {
  if (!value_->is_boolean()) fail("expected true or false");
  return value_->get<bool>();
}

std::string Node::string() const {
  if (!value_->is_string()) fail("expected a string");
  return value_->get<std::string>();
}

Vec3 Node::vec3() const {
  const std::vector<Node> e = elements();
  if (e.size() != 3) fail("expected [x, y, z]");
  return {e[0].number(), e[1].number(), e[2].number()};
}

void Node::check_numbers(std::initializer_list<const char*> keys) const {
  for (const char* k : keys)
    if (auto v = find(k)) v->number();
}

void Node::check_integers(std::initializer_list<std::pair<const char*, uint64_t>> keys) const {
  for (const auto& [k, max] : keys)
    if (auto v = find(k)) v->integer(max);
}

void Node::fail_choice(const std::string& got, const std::vector<const char*>& names) const {
  fail(quoted(got) + " is not one of " + join(names));
}

// ---- message helpers ------------------------------------------------------------------

std::string child_path(const std::string& parent, const std::string& key) {
  return is_identifier(key) ? parent + "." + key : parent + "[" + quoted(key) + "]";
}

std::string quoted(const std::string& s, size_t max_bytes) {
  if (s.size() <= max_bytes) return Json(s).dump(-1, ' ', false, Json::error_handler_t::replace);
  size_t cut = max_bytes;
  while (cut > 0 && (static_cast<unsigned char>(s[cut]) & 0xC0u) == 0x80u) --cut;  // whole code points
  return Json(s.substr(0, cut)).dump(-1, ' ', false, Json::error_handler_t::replace) + "...";
}

}  // namespace arcus::json
