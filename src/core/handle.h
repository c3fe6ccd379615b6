// The base of every object behind a public handle (context, job, and each engine's: a
// scene, a field, ...): a reference count, the owning context and its kind.  Every live object is registered,
// so a call can tell a live handle of the right type from NULL, a released handle, a
// handle of another type or a pointer that is no arcus object at all, and answer each
// with ARCUS_ERROR_INVALID_ARGUMENT instead of undefined behaviour.
//
// A call holds a reference to the object it was handed for as long as it runs
// (HandleRef, core/context.h), taken under the registry's lock: another thread's release
// of the last user reference then only drops the count, and the object is freed when
// the call ends, never while it is in use.
#pragma once

#include <atomic>
#include <vector>

#include "arcus/arcus_core.h"

namespace arcus {

// What an object behind a handle is, by the name error messages give it ("field is a job,
// not a field").  The core defines the two kinds it owns (context, job); every other
// module defines its own as a static HandleKind beside its object type, which registers
// it, as feature tables and scene loaders are registered: the core never names an
// engine's kind.  Kinds compare by address.  An object is freed through Handle's virtual
// destructor, so a kind needs no release function.
class HandleKind {
 public:
  explicit HandleKind(const char* name);
  HandleKind(const HandleKind&) = delete;
  HandleKind& operator=(const HandleKind&) = delete;
  const char* name() const { return name_; }

 private:
  const char* const name_;
};

extern const HandleKind kContextHandle;  // "context"
extern const HandleKind kJobHandle;      // "job"

// Every registered kind, in registration order (for tests and diagnostics).
std::vector<const HandleKind*> handle_kinds();

class Handle {
 public:
  // owner: the context this object belongs to (its creator retains it for the object);
  // null for a context itself.
  Handle(const HandleKind& kind, arcus_context_t* owner);
  virtual ~Handle();
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;

  const HandleKind& kind() const { return kind_; }
  arcus_context_t* owner() const { return owner_; }
  // One more reference.  An object whose count has reached 0 is being freed and is
  // never revived: retaining it is ARCUS_ERROR_INVALID_ARGUMENT ("... was released").
  void retain();
  // As retain, but false instead of throwing.
  bool try_retain();
  // Drops one reference; true when it was the last (the caller then deletes).
  bool drop() { return refs_.fetch_sub(1) == 1; }
  // False once the last reference is gone (the object awaits deletion).
  bool alive() const { return refs_.load() > 0; }

 private:
  const HandleKind& kind_;
  arcus_context_t* const owner_;
  std::atomic<int> refs_{1};
};

// What a handle is, checked under the registry's lock: `p` must be a live object
// (registered, count above 0) of `kind`, else ARCUS_ERROR_INVALID_ARGUMENT naming
// `name` ("field is NULL", "field is not a live arcus handle", "field is a job, not a
// field").  `before_retain` (may be null) sees a live object and `user` before its kind
// is checked, still under the lock, and may throw to refuse it; then a reference is
// taken for the caller, who must drop it.
Handle* retain_handle(const void* p, const HandleKind& kind, const char* name,
                      void (*before_retain)(Handle*, void* user) = nullptr, void* user = nullptr);

// The live object at `p` of any kind, retained for the caller, or null.
Handle* retain_any_handle(const void* p);

// The live object at `p`, checked as retain_handle does, without a reference: only for
// a caller that holds the lock of the object's context, which keeps it from being freed.
Handle* find_handle(const void* p, const HandleKind& kind, const char* name);

}  // namespace arcus
