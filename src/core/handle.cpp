#include "core/handle.h"

#include <mutex>
#include <string>
#include <unordered_set>
#include <vector>

#include "core/error.h"

namespace arcus {
namespace {

// Registered by address; a mutex suffices: lookups are a hash probe per call.
struct Registry {
  std::mutex mutex;
  std::unordered_set<const void*> live;
};

Registry& registry() {
  static Registry* r = new Registry;  // never destroyed: handles may outlive static destruction
  return *r;
}

// Function-local so that kinds defined in any translation unit register safely at
// static initialisation, in whatever order; never destroyed, as the registry.
std::vector<const HandleKind*>& kind_list() {
  static auto* kinds = new std::vector<const HandleKind*>;
  return *kinds;
}

// The object at `p` checked to be live and of `kind`; the registry's lock is held by the
// caller, so the object cannot finish its destruction meanwhile (~Handle needs the lock).
// `before_kind` (may be null) sees a live object before its kind is checked.
Handle* checked(const Registry& r, const void* p, const HandleKind& kind, const char* name,
                void (*before_kind)(Handle*, void*) = nullptr, void* user = nullptr) {
  if (!p) fail(ARCUS_ERROR_INVALID_ARGUMENT, std::string(name) + " is NULL");
  // Only a registered address is dereferenced, and it is a Handle by construction.
  Handle* h = r.live.count(p) ? static_cast<Handle*>(const_cast<void*>(p)) : nullptr;
  if (!h || !h->alive())
    fail(ARCUS_ERROR_INVALID_ARGUMENT,
         std::string(name) + " is not a live arcus handle (released already, or not an arcus object)");
  if (before_kind) before_kind(h, user);
  if (&h->kind() != &kind)
    fail(ARCUS_ERROR_INVALID_ARGUMENT,
         std::string(name) + " is a " + h->kind().name() + ", not a " + kind.name());
  return h;
}

}  // namespace

HandleKind::HandleKind(const char* name) : name_(name) { kind_list().push_back(this); }

const HandleKind kContextHandle("context");
const HandleKind kJobHandle("job");

std::vector<const HandleKind*> handle_kinds() { return kind_list(); }

Handle::Handle(const HandleKind& kind, arcus_context_t* owner) : kind_(kind), owner_(owner) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  r.live.insert(this);
}

Handle::~Handle() {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  r.live.erase(this);
}

bool Handle::try_retain() {
  int n = refs_.load();
  while (n > 0)
    if (refs_.compare_exchange_weak(n, n + 1)) return true;
  return false;
}

void Handle::retain() {
  if (!try_retain())
    fail(ARCUS_ERROR_INVALID_ARGUMENT,
         std::string("the ") + kind_.name() + " was released by another thread while in use");
}

Handle* retain_handle(const void* p, const HandleKind& kind, const char* name,
                      void (*before_retain)(Handle*, void*), void* user) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  Handle* h = checked(r, p, kind, name, before_retain, user);
  if (!h->try_retain())
    fail(ARCUS_ERROR_INVALID_ARGUMENT, std::string(name) + " is not a live arcus handle (released already)");
  return h;
}

Handle* retain_any_handle(const void* p) {
  if (!p) return nullptr;
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  if (!r.live.count(p)) return nullptr;
  Handle* h = static_cast<Handle*>(const_cast<void*>(p));
  return h->try_retain() ? h : nullptr;
}

Handle* find_handle(const void* p, const HandleKind& kind, const char* name) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  return checked(r, p, kind, name);
}

}  // namespace arcus
