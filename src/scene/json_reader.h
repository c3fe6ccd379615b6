// Strict JSON for scene files, shared by every engine's schema.  Pure host code (no
// OpenCL).  A Document is read from a file or from text; a Node is a value with its key
// path ("$.medium.center[1]"), and every accessor checks the type.  Every error is an
// arcus::Error whose message starts with the file name and the key path:
//   ARCUS_ERROR_INVALID_ARGUMENT  "<file>: <$.path>: <what>"  (bad JSON, bad schema)
//   ARCUS_ERROR_IO                "<file>: <what>"            (cannot read, not a regular file)
// Reading is strict: a key given twice, nesting deeper than kMaxDepth, a number out of
// the range of a double and (through expect_object) an unknown key are all errors.
#pragma once

#include <array>
#include <cstdint>
#include <initializer_list>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "geometry/vec3.h"

namespace arcus::json {

using Json = nlohmann::ordered_json;  // ordered: the document keeps the author's key order

// Containers nested deeper than this are refused while parsing (nlohmann copies a DOM
// recursively, so a deep document would otherwise overflow the stack).
constexpr int kMaxDepth = 64;

class Node;

class Document {
 public:
  // `file_name` is only used in messages.
  static Document from_text(const std::string& text, const std::string& file_name);
  // Reads a regular file only (a FIFO or a device never blocks the caller) of at most
  // ARCUS_MAX_SCENE_BYTES (64 MiB; core/files.h).
  static Document from_file(const std::string& path);

  Document(Document&&) noexcept;
  Document& operator=(Document&&) noexcept;
  ~Document();

  Node root() const;
  const Json& value() const;
  const std::string& file_name() const;
  // Pretty printed (2 spaces), keys in the author's order.
  std::string dump() const;

 private:
  struct Impl;
  explicit Document(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;  // on the heap: Nodes point into it, and a move keeps them valid
};

// A value of a Document (which must outlive it) and its key path.
class Node {
 public:
  Node(const Json& value, std::string path, const std::string& file_name);

  const std::string& path() const { return path_; }
  const std::string& file_name() const { return *file_; }
  const Json& value() const { return *value_; }

  // Throws ARCUS_ERROR_INVALID_ARGUMENT "<file>: <path>: <what>".
  [[noreturn]] void fail(const std::string& what) const;

  bool is_object() const;
  bool is_array() const;
  bool is_number() const;
  bool is_null() const;

  // An object whose keys all come from `allowed` (else: "<path>.<key>: unknown key").
  void expect_object(std::initializer_list<const char*> allowed) const;
  std::optional<Node> find(const char* key) const;  // this must be an object
  Node member(const char* key) const;               // present, else "missing key"
  std::vector<Node> elements() const;               // this must be an array
  size_t array_size() const;                        // this must be an array

  double number() const;                 // any finite number
  uint64_t integer(uint64_t max) const;  // 0..max, written as an integer
  bool boolean() const;
  std::string string() const;
  Vec3 vec3() const;  // [x, y, z] of numbers

  // Schema checks of an object's optional members: each of `keys` that is present is a
  // number (check_numbers), or an integer 0..max (check_integers).
  void check_numbers(std::initializer_list<const char*> keys) const;
  void check_integers(std::initializer_list<std::pair<const char*, uint64_t>> keys) const;

  // One of a fixed set of names, mapped to its value.
  template <class T>
  T choice(const std::vector<std::pair<const char*, T>>& options) const {
    const std::string s = string();
    std::vector<const char*> names;
    for (const auto& o : options) {
      if (s == o.first) return o.second;
      names.push_back(o.first);
    }
    fail_choice(s, names);
  }

 private:
  [[noreturn]] void fail_choice(const std::string& got, const std::vector<const char*>& names) const;

  const Json* value_;
  std::string path_;
  const std::string* file_;
};

// Helpers for messages, also used by the schemas.
// The path of `key` under `parent`: "$.a.b", or "$.a[\"odd key\"]" when the key is not a
// plain identifier, so that paths stay unambiguous and printable.
std::string child_path(const std::string& parent, const std::string& key);
// A string as a JSON literal for a message: quoted, escaped, cut to `max_bytes`.
std::string quoted(const std::string& s, size_t max_bytes = 64);

}  // namespace arcus::json
