/* The null engine's kernel arguments, written once for host and kernel (core/launch.h):
 * the kernel's signature and the host's argument names both come from this list. */
#ifndef ARCUS_NULL_DESC_H
#define ARCUS_NULL_DESC_H

#define ARCUS_NULL_FILL_ARGS(X) X(__global const float*, colour) X(__global float*, rgb) X(const uint, pixels)

#endif
