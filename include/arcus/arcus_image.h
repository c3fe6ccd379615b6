/*
 * arcus images: reading the image files the library takes as input (sky images) and
 * writing images in the format their file name asks for, so that C, Python and the
 * command-line tools read and write them one way.  Include arcus.h.
 */
#ifndef ARCUS_IMAGE_H
#define ARCUS_IMAGE_H

#include "arcus_core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Reads the first image of any file OpenImageIO reads (EXR, HDR, PNG, JPEG, TIFF, PFM,
 * ...) as linear RGB, 3 floats a pixel, top row first: integer files are taken as sRGB
 * encoded and decoded unless they declare themselves linear, float files are read as
 * they are; grey becomes grey, alpha is dropped.  Call with rgb NULL to learn the size
 * (from the file's header alone), then with rgb holding rgb_count floats (width ×
 * height × 3); width and height, when given, receive the size of what was read.  An
 * image that does not fit rgb_count (the file changed between the calls) writes
 * nothing and is ARCUS_ERROR_INVALID_ARGUMENT naming rgb_count.
 * Errors (arcus_last_error() says which): ARCUS_ERROR_IO (missing, unreadable, not a
 * regular file, more than ARCUS_MAX_IMAGE_PIXELS pixels: 2^28 unless set),
 * ARCUS_ERROR_INVALID_ARGUMENT (a NaN or infinite value, naming the pixel),
 * ARCUS_ERROR_OUT_OF_MEMORY (more than the host has available). */
ARCUS_API arcus_status arcus_image_read(const char* path, uint32_t* width, uint32_t* height, float* rgb,
                                        size_t rgb_count);

/* Writes width × height linear RGB pixels (3 floats a pixel, top row first) to `path`
 * in the format its extension names: .exr and .hdr keep the floats as they are; .png
 * and .jpg/.jpeg are 8-bit, sRGB-encoded and clamped to [0, 1] (JPEG at quality 92).
 * Errors: ARCUS_ERROR_INVALID_ARGUMENT (another extension, naming the path; a zero
 * size), ARCUS_ERROR_NOT_FINITE (a NaN or infinite value, naming the pixel),
 * ARCUS_ERROR_IO (the file cannot be written). */
ARCUS_API arcus_status arcus_image_write(const char* path, uint32_t width, uint32_t height, const float* rgb);

#ifdef __cplusplus
}
#endif

#endif /* ARCUS_IMAGE_H */
