// The base of every object behind a public handle (context, field, job, scene): a
// reference count, the owning context and a type tag.  Every live object is registered,
// so a call can tell a live handle of the right type from NULL, a released handle, a
// handle of another type or a pointer that is no arcus object at all, and answer each
// with ARCUS_ERROR_INVALID_ARGUMENT instead of undefined behaviour.
#pragma once

#include <atomic>
#include <cstdint>

#include "arcus/arcus_core.h"

namespace arcus {

enum class HandleType : uint32_t { Context, Field, Job, Scene, Renderer, Water, Particle };

// "context", "field", "job", "scene", "renderer", "water".
const char* handle_type_name(HandleType type);

class Handle {
 public:
  // owner: the context this object belongs to (its creator retains it for the object);
  // null for a context itself.
  Handle(HandleType type, arcus_context_t* owner);
  virtual ~Handle();
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;

  HandleType type() const { return type_; }
  arcus_context_t* owner() const { return owner_; }
  void retain() { refs_.fetch_add(1); }
  // Drops one reference; true when it was the last (the caller then deletes).
  bool drop() { return refs_.fetch_sub(1) == 1; }

 private:
  const HandleType type_;
  arcus_context_t* const owner_;
  std::atomic<int> refs_{1};
};

// The live object at `p`, checked to be of `type`; throws ARCUS_ERROR_INVALID_ARGUMENT
// naming `name` ("field is NULL", "field is not a live arcus handle", "field is a job,
// not a field").
Handle* find_handle(const void* p, HandleType type, const char* name);

// The live object at `p` of any type, or null.
Handle* find_any_handle(const void* p);

}  // namespace arcus
