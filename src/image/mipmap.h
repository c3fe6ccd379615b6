// A texture's MIP pyramid (Williams 1983, "Pyramidal parametrics") of linear RGB, and
// lookups filtered over a pixel's footprint: a ground seen at grazing angles covers
// thousands of texels with one pixel, and a point sample there is noise.  Every level
// is the box mean of 2×2 texels of the one below (linear light, so colours average as
// light does); a lookup takes trilinear samples along the footprint's long axis at the
// level its short axis asks for, as GPUs' anisotropic filtering does.
//
// OpenImageIO's TextureSystem filters the same way, but from files as they are stored
// (version 2.4 converts no colour: an sRGB PNG would be averaged encoded); arcus's
// textures are decoded to linear light when read (image_io.h), so they are filtered here.
#pragma once

#include <array>
#include <vector>

#include "image/image_io.h"

namespace arcus::image {

class MipPyramid {
 public:
  MipPyramid() = default;
  // Levels of the first three channels of `base`, halving (rounded up) down to 1×1.
  explicit MipPyramid(const Image& base);

  bool empty() const { return levels_.empty(); }
  int width() const { return empty() ? 0 : levels_[0].width; }
  int height() const { return empty() ? 0 : levels_[0].height; }
  size_t level_count() const { return levels_.size(); }

  // The mean over the footprint centred at (u, v), in texture units (1 = the image's
  // width or height; the texture repeats in both), spanned by the vectors (du_x, dv_x)
  // and (du_y, dv_y) (the texture coordinates' change from one pixel to the next,
  // across and down).  A zero footprint is a bilinear sample of the full image.  At
  // most 16 samples: a longer footprint is blurred across to keep the ratio.
  std::array<float, 3> sample(double u, double v, double du_x, double dv_x, double du_y, double dv_y) const;

 private:
  std::array<float, 3> bilinear(size_t level, double u, double v) const;
  std::array<float, 3> trilinear(double level, double u, double v) const;
  std::vector<Image> levels_;
};

}  // namespace arcus::image
