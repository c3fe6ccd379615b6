// Light directions from one uncontrolled photograph (thesis §3.4, after Lopez-Moreno,
// Hadap, Reinhard & Gutierrez 2009, "Light source detection in photographs", CEIG):
// the object found in the photo, its outer contour with the normals there, the lights'
// azimuths from the contour (k-means on the luminance-weighted normals, the count from
// a clamped-cosine model of the contour's luminance) and their zeniths from the
// luminance gradients inside the object.  arcus_translucency.h states the conventions.
#pragma once

#include <cstdint>
#include <vector>

#include "arcus/arcus_translucency.h"

namespace arcus::translucency {

// The side the single-image steps work at, at most: a larger photo is box-filtered by a
// whole factor first (the steps' cost grows with the pixels, the relief solve's as their
// square; the estimate itself works at 200 a side, as the thesis).
constexpr uint32_t kWorkingSide = 512;

// The object in a photograph, at the working resolution: a mask of its pixels (the
// matte's largest region, or one segmented from the photo, small holes filled) and
// every pixel's luminance.
struct PhotoObject {
  uint32_t width = 0, height = 0;              // the working resolution's
  uint32_t scale = 1;                          // the photo's pixels a working pixel spans, a side
  uint32_t photo_width = 0, photo_height = 0;  // the photo's own size
  std::vector<uint8_t> mask;      // 1: the object
  std::vector<double> luminance;  // Rec. 709 weights, every pixel
  size_t pixels = 0;              // the mask's
  bool segmented = false;
};

// Checks the photo (finite, >= 0) and finds the object; errors name "photo" or "matte":
// no object, or one touching the border.
PhotoObject find_object(uint32_t width, uint32_t height, const float* photo, const uint8_t* matte);

// A working-resolution map (`channels` values a pixel) read back at the photo's size
// (each photo pixel takes its working pixel's values, times `multiply`).
std::vector<double> at_photo_size(const PhotoObject& object, const std::vector<double>& values, int channels,
                                  double multiply);
std::vector<uint8_t> at_photo_size(const PhotoObject& object, const std::vector<uint8_t>& values);

// A pixel of the outer contour: where (pixel centres, x right, y down), the outward
// normal there in the camera's frame (x right, y up; the surface faces across the view
// at a contour), and the luminance just inside.
struct ContourSample {
  double x = 0, y = 0;
  double nx = 0, ny = 0;
  double luminance = 0;
};
std::vector<ContourSample> outer_contour(const PhotoObject& object);

// The depth (pixels, 0 outside) of a globally convex stand-in for the object, inflated
// from its contour as Johnston 2002 ("Lumo", the thesis' Joh02) and Teddy do: u solving
// ∇²u = −1 inside, 0 outside, then Z = sqrt(4u).  A disc of radius R gives a sphere of
// radius R exactly and an ellipse of semi-axes a, b an ellipsoid (of depth
// sqrt(2 / (1/a² + 1/b²))), whose cross-sections the distance to the contour misses.
std::vector<double> convex_depth(const PhotoObject& object);

// Unit normals of a depth map (pixels toward the camera), 3 per pixel in the camera's
// frame (x right, y up), by central differences with 0 outside; 0 outside the object.
std::vector<double> depth_normals(const PhotoObject& object, const std::vector<double>& depth);

arcus_light_detection detect_lights(uint32_t width, uint32_t height, const float* photo, const uint8_t* matte);
arcus_light_detection detect_lights(const PhotoObject& object);

}  // namespace arcus::translucency
