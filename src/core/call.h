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
    std::lock_guard<std::mutex> lock(ctx->lock);
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

// A bad handle: the message goes to the thread, and to the context of the object it
// points at when it is a live object of another type.
arcus_status bad_handle(const void* handle, const std::string& message);

// A call on the object `handle` of type T (checked: live, of the right type), under
// its context's lock.  body(T*, std::string* message) returns the status.
template <class T, class Body>
arcus_status on(const void* handle, HandleType type, const char* name, Body&& body) {
  Handle* h = nullptr;
  std::string message;
  const arcus_status found = run_catching(
      [&](std::string*) {
        h = find_handle(handle, type, name);
        return ARCUS_SUCCESS;
      },
      &message);
  if (found != ARCUS_SUCCESS) return bad_handle(handle, message);
  T* object = static_cast<T*>(h);
  return locked(context_of(h), [&](std::string* msg) { return body(object, msg); });
}

// As `on`, for a body(T*) that returns nothing.
template <class T, class Body>
arcus_status simple(const void* handle, HandleType type, const char* name, Body&& body) {
  return on<T>(handle, type, name, [&](T* object, std::string*) {
    body(object);
    return ARCUS_SUCCESS;
  });
}

// Retain and release of any handle of type T (a context's own release frees it when
// its last object is gone).
template <class T>
arcus_status retain(T* handle, HandleType type, const char* name) {
  std::string message;
  const arcus_status st = run_catching(
      [&](std::string*) {
        find_handle(handle, type, name)->retain();
        return ARCUS_SUCCESS;
      },
      &message);
  return st == ARCUS_SUCCESS ? st : bad_handle(handle, message);
}

template <class T>
arcus_status release(T* handle, HandleType type, const char* name) {
  std::string message;
  const arcus_status st = run_catching(
      [&](std::string*) {
        Handle* h = find_handle(handle, type, name);
        if (type == HandleType::Context)
          release_context(static_cast<arcus_context_t*>(h));
        else
          release_object(h);
        return ARCUS_SUCCESS;
      },
      &message);
  return st == ARCUS_SUCCESS ? st : bad_handle(handle, message);
}

// `p` as an object of type T of `ctx`: checked live, of the type, and of that context.
template <class T>
T* object_of(arcus_context_t* ctx, const void* p, HandleType type, const char* name) {
  Handle* h = find_handle(p, type, name);
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
  return simple<arcus_job_s>(job, HandleType::Job, "job", [&](arcus_job_s* j) { body(job_as<T>(j, what)); });
}

// Copies a result out to a caller's array, which may be NULL (not wanted).
template <class T>
void copy_out(const std::vector<T>& from, T* to) {
  if (to) std::copy(from.begin(), from.end(), to);
}

}  // namespace arcus::api
