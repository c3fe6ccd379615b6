/*
 * arcus images: reading the image files the library takes as input (sky images), so
 * that C, Python and the command-line tools read them one way.  Include arcus.h.
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
 * (from the file's header alone), then with width × height × 3 floats.  Errors
 * (arcus_last_error() says which): ARCUS_ERROR_IO (missing or unreadable file),
 * ARCUS_ERROR_INVALID_ARGUMENT. */
ARCUS_API arcus_status arcus_image_read(const char* path, uint32_t* width, uint32_t* height, float* rgb);

#ifdef __cplusplus
}
#endif

#endif /* ARCUS_IMAGE_H */
