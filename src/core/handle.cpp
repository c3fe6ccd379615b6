#include "core/handle.h"

#include <mutex>
#include <string>
#include <unordered_set>

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

}  // namespace

const char* handle_type_name(HandleType type) {
  switch (type) {
    case HandleType::Context: return "context";
    case HandleType::Field: return "field";
    case HandleType::Job: return "job";
    case HandleType::Scene: return "scene";
    case HandleType::Renderer: return "renderer";
    case HandleType::Water: return "water";
    case HandleType::Particle: return "particle";
  }
  return "object";
}

Handle::Handle(HandleType type, arcus_context_t* owner) : type_(type), owner_(owner) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  r.live.insert(this);
}

Handle::~Handle() {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  r.live.erase(this);
}

Handle* find_any_handle(const void* p) {
  if (!p) return nullptr;
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  // Only a registered address is dereferenced, and it is a Handle by construction.
  return r.live.count(p) ? static_cast<Handle*>(const_cast<void*>(p)) : nullptr;
}

Handle* find_handle(const void* p, HandleType type, const char* name) {
  if (!p) fail(ARCUS_ERROR_INVALID_ARGUMENT, std::string(name) + " is NULL");
  Handle* h = find_any_handle(p);
  if (!h)
    fail(ARCUS_ERROR_INVALID_ARGUMENT,
         std::string(name) + " is not a live arcus handle (released already, or not an arcus object)");
  if (h->type() != type)
    fail(ARCUS_ERROR_INVALID_ARGUMENT, std::string(name) + " is a " + handle_type_name(h->type()) + ", not a " +
                                           handle_type_name(type));
  return h;
}

}  // namespace arcus
