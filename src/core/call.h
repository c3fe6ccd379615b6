// The C entry points' shared machinery: exceptions become statuses and last-error
// messages, calls on a context take its lock, and handles are checked before use.
// Every api_*.cpp goes through these and nothing else.
#pragma once

#include <algorithm>
#include <mutex>
#include <new>
#include <string>
#include <vector>

#include "core/context.h"
#include "core/error.h"
#include "core/handle.h"
#include "core/job.h"

namespace arcus::api {

// The per-thread message behind arcus_last_error().
void set_thread_error(const std::string& message);

// Runs body (returning an arcus_status, given a message to fill for partial results);
// exceptions become statuses with *message set.
template <class Body>
arcus_status run_catching(Body&& body, std::string* message) {
  try {
    return body(message);
  } catch (const Error& e) {
    *message = e.what();
    return e.status();
  } catch (const std::bad_alloc&) {
    *message = "out of host memory";
    return ARCUS_ERROR_OUT_OF_MEMORY;
  } catch (const std::exception& e) {
    *message = e.what();
    return ARCUS_ERROR_INVALID_ARGUMENT;
  }
}

// A call that needs no context (device queries, creation): body() returns nothing.
template <class Body>
arcus_status without_context(Body&& body) {
  std::string message;
  const arcus_status status = run_catching(
      [&](std::string*) {
        body();
        return ARCUS_SUCCESS;
      },
      &message);
  if (status != ARCUS_SUCCESS) set_thread_error(message);
  return status;
}

// Runs body under ctx's lock, keeps a failure's message on ctx and calls its error
// callback after the lock is released (so the callback may call arcus).
template <class Body>
arcus_status locked(arcus_context_t* ctx, Body&& body) {
  std::string message;
  arcus_status status;
  arcus_error_callback callback;
  void* user;
  {
    ContextLock lock(ctx);
    status = run_catching(body, &message);
    if (status != ARCUS_SUCCESS) ctx->last_error = message;
    callback = ctx->callback;
    user = ctx->callback_user;
  }
  if (status != ARCUS_SUCCESS) {
    set_thread_error(message);
    if (callback) callback(user, status, message.c_str());
  }
  return status;
}

// A handle that could not be used: the message goes to the thread, and to the context
// of the object it points at when that is a live object (of another kind, or one whose
// context this thread is inside of: a re-entry).  Returns `status`.
arcus_status bad_handle(const void* handle, arcus_status status, const std::string& message);

// A reference to `handle`, checked (live, of the right kind, not a re-entry), for a
// call; on failure the status (with the message reported as bad_handle does) and an
// empty reference.
HandleRef hold(const void* handle, const HandleKind& kind, const char* name, arcus_status* status);

// A call on the object `handle` of type T (checked: live, of the right kind), under
// its context's lock, holding a reference to it until the call returns.
// body(T*, std::string* message) returns the status.
template <class T, class Body>
arcus_status on(const void* handle, const HandleKind& kind, const char* name, Body&& body) {
  arcus_status status;
  const HandleRef ref = hold(handle, kind, name, &status);
  if (!ref) return status;
  T* object = static_cast<T*>(ref.get());
  return locked(context_of(object), [&](std::string* msg) { return body(object, msg); });
}

// As `on`, for a body(T*) that returns nothing.
template <class T, class Body>
arcus_status simple(const void* handle, const HandleKind& kind, const char* name, Body&& body) {
  return on<T>(handle, kind, name, [&](T* object, std::string*) {
    body(object);
    return ARCUS_SUCCESS;
  });
}

// Retain and release of any handle of type T (a context's own release frees it when
// its last object is gone).
template <class T>
arcus_status retain(T* handle, const HandleKind& kind, const char* name) {
  arcus_status status;
  HandleRef ref = hold(handle, kind, name, &status);
  if (!ref) return status;
  (void)ref.release_to_caller();  // the reference taken is the caller's new one
  return ARCUS_SUCCESS;
}

template <class T>
arcus_status release(T* handle, const HandleKind& kind, const char* name) {
  arcus_status status;
  const HandleRef ref = hold(handle, kind, name, &status);
  if (!ref) return status;
  // The caller's reference goes now; the object is freed (if that was the last) when
  // `ref`, this call's own, goes too.
  release_handle(ref.get());
  return ARCUS_SUCCESS;
}

// `p` as an object of type T of `ctx`: checked live, of the kind, and of that context.
// For a call holding ctx's lock, which keeps the object from being freed meanwhile.
template <class T>
T* object_of(arcus_context_t* ctx, const void* p, const HandleKind& kind, const char* name) {
  Handle* h = find_handle(p, kind, name);
  if (h->owner() != ctx)
    fail(ARCUS_ERROR_INVALID_ARGUMENT, std::string(name) + " belongs to another context");
  return static_cast<T*>(h);
}

// The job behind a handle as engine job type T (each engine derives its own from
// arcus_job_s); another engine's job is INVALID_ARGUMENT: "job is a render job, not
// <what>".
template <class T>
T* job_as(arcus_job_s* job, const char* what) {
  auto* t = dynamic_cast<T*>(job);
  if (!t) fail(ARCUS_ERROR_INVALID_ARGUMENT, std::string("job is a ") + job->kind + " job, not " + what);
  return t;
}

// A getter on a job of type T: body(T*) under its context's lock.
template <class T, class Body>
arcus_status on_job(arcus_job_t* job, const char* what, Body&& body) {
  return simple<arcus_job_s>(job, arcus::kJobHandle, "job", [&](arcus_job_s* j) { body(job_as<T>(j, what)); });
}

// Copies a result out to a caller's array, which may be NULL (not wanted).
template <class T>
void copy_out(const std::vector<T>& from, T* to) {
  if (to) std::copy(from.begin(), from.end(), to);
}

}  // namespace arcus::api
