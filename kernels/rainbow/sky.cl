/* A rainbow sky (thesis §4.1.4, §5.5.2): single scattering marched along each view ray
 * through a box of drops lit by the sun.  One pixel per work-item.
 *
 * The sun is at infinity and the drops are the same everywhere in the box, so the
 * scattering angle θ (and the azimuth φ) is the same at every step of a view ray: the
 * march only integrates the attenuation, toward the camera and toward the sun,
 *   I(λ) = ∫ exp(−σ_e(λ)·(t − t0 + ℓ_sun(t))) dt   over the ray's part in the box,
 * by the midpoint rule with `steps` steps, and the radiance is
 *   L(λ) = E_sun(λ)·β(λ, φ, θ)·I(λ) + L_background(λ)·exp(−σ_e(λ)·(t1 − t0)).
 * β has been averaged over the sun's disc by the host.  Drops are grey in geometric
 * optics (σ_e = 2·πr² at every λ), so the march runs once per distinct σ_e, not once per
 * wavelength.  XYZ = Σ_λ L(λ)·w(λ) with the shared module's band weights.
 *
 * beta        [wavelengths × phis × thetas] the disc-averaged volume scattering function
 * extinction  [wavelengths] σ_e [1/m]
 * sun, sky, ground  [wavelengths] irradiance and the background's radiances
 * sky_rgb     [3 per pixel] with s.sky_image: the sky image's linear sRGB behind each
 *             pixel (sampled by the host), which becomes the spectrum Σ_c rgb_c·basis_c
 * sky_basis   [wavelengths × 3] the spectra S_r, S_g, S_b (spectral/srgb.h)
 * weights     [wavelengths × 3] the CIE band weights
 * xyz         [3 per pixel] out;  theta  [per pixel] the scattering angle [deg], out
 *
 * Host prepends: common/real.h, rainbow/rainbow_desc.h.  ARCUS_USE_RAINBOW_AZIMUTH:
 * β depends on φ (bilinear in φ and θ); else on θ alone. */

#define SKY_DEG (RC(180.0) / M_PI)

/* The distances (t0, t1) along x + t·d inside the box, t0 ≥ 0; empty when t1 ≤ t0. */
void sky_box(const REAL* x, const REAL* d, const rainbow_sky_desc* s, REAL* t0, REAL* t1) {
  REAL lo = 0, hi = INFINITY;
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0) {
      if (x[a] < s->box_min[a] || x[a] > s->box_max[a]) hi = -1;
      continue;
    }
    const REAL ta = (s->box_min[a] - x[a]) / d[a], tb = (s->box_max[a] - x[a]) / d[a];
    lo = fmax(lo, fmin(ta, tb));
    hi = fmin(hi, fmax(ta, tb));
  }
  *t0 = lo;
  *t1 = hi;
}

/* β at (φ, θ) of wavelength l: linear in θ (and φ, periodic); 0 outside the θ samples. */
REAL sky_beta(__global const REAL* beta, const rainbow_sky_desc* s, int l, REAL phi_deg, REAL theta_deg) {
  const REAL u = (theta_deg - s->theta_first) / s->theta_step;
  if (!(u >= 0) || u > s->thetas - 1) return 0;
  const int i = min((int)u, s->thetas - 2);
  const REAL fu = u - i;
#ifdef ARCUS_USE_RAINBOW_AZIMUTH
  REAL v = phi_deg / RC(360.0) * s->phis;
  v -= floor(v / s->phis) * s->phis;
  const int j0 = min((int)v, s->phis - 1), j1 = (j0 + 1) % s->phis;
  const REAL fv = v - j0;
  __global const REAL* r0 = beta + ((long)l * s->phis + j0) * s->thetas + i;
  __global const REAL* r1 = beta + ((long)l * s->phis + j1) * s->thetas + i;
  return (1 - fv) * ((1 - fu) * r0[0] + fu * r0[1]) + fv * ((1 - fu) * r1[0] + fu * r1[1]);
#else
  __global const REAL* r = beta + (long)l * s->thetas + i;
  return (1 - fu) * r[0] + fu * r[1];
#endif
}

__kernel void arcus_rainbow_sky(ARCUS_PARAMS(ARCUS_RAINBOW_SKY_ARGS)) {
  const int item = get_global_id(0);
  if (item >= s.count) return;
  const int pixel = s.first + item;
  const int px = pixel % s.width, py = pixel / s.width;
  const REAL u = (2 * (px + RC(0.5)) / s.width - 1) * s.half_width;
  const REAL v = (1 - 2 * (py + RC(0.5)) / s.height) * s.half_height;
  REAL d[3], x[3];
  REAL norm = 0;
  for (int a = 0; a < 3; ++a) {
    d[a] = s.forward[a] + u * s.right[a] + v * s.up[a];
    norm += d[a] * d[a];
  }
  norm = sqrt(norm);
  for (int a = 0; a < 3; ++a) {
    d[a] /= norm;
    x[a] = s.camera[a];
  }

  /* The light reaching the camera travels along −d; the sun's along −sun. */
  const REAL cos_theta = clamp(d[0] * s.sun[0] + d[1] * s.sun[1] + d[2] * s.sun[2], RC(-1.0), RC(1.0));
  const REAL theta = acos(cos_theta) * SKY_DEG;
  REAL phi = 0;
#ifdef ARCUS_USE_RAINBOW_AZIMUTH
  phi = atan2(-(d[0] * s.y_light[0] + d[1] * s.y_light[1] + d[2] * s.y_light[2]),
              -(d[0] * s.x_light[0] + d[1] * s.x_light[1] + d[2] * s.x_light[2])) * SKY_DEG;
#endif

  /* The rain ahead, cut at the ground; the background is the ground below the horizon. */
  REAL t0, t1;
  sky_box(x, d, &s, &t0, &t1);
  const int below = d[1] < 0;
  if (below && x[1] > 0) t1 = fmin(t1, -x[1] / d[1]);
  const int rain = t1 > t0;
  const int image = !below && s.sky_image;
  __global const REAL* background = below ? ground : sky;
  REAL rgb[3] = {0, 0, 0};
  if (image)
    for (int c = 0; c < 3; ++c) rgb[c] = sky_rgb[3 * (long)pixel + c];

  /* The sun's path out of the box from a point p is min over axes of
   * (bound_a − p_a)/sun_a, with bound_a the face the sun's direction leaves through. */
  REAL bound[3], inv[3];
  for (int a = 0; a < 3; ++a) {
    bound[a] = s.sun[a] > 0 ? s.box_max[a] : s.box_min[a];
    inv[a] = s.sun[a] != 0 ? 1 / s.sun[a] : 0;
  }
  REAL out[3] = {0, 0, 0};
  REAL sigma_done = -1, march = 0;
  for (int l = 0; l < s.wavelengths; ++l) {
    const REAL sigma = extinction[l];
    REAL radiance = image ? rgb[0] * sky_basis[3 * l] + rgb[1] * sky_basis[3 * l + 1] + rgb[2] * sky_basis[3 * l + 2]
                          : background[l];
    if (rain) {
      if (sigma != sigma_done) {
        const REAL dt = (t1 - t0) / s.steps;
        /* Along the ray the exponent is linear in t while the sun leaves through the
         * same face, so the integrand is a geometric sequence there: one exp per face,
         * then a product per step (3 exps a ray rather than one a step). */
        REAL ratio[3];
        for (int a = 0; a < 3; ++a) ratio[a] = exp(-sigma * dt * (1 - d[a] * inv[a]));
        int face = -1;
        REAL term = 0;
        march = 0;
        for (int k = 0; k < s.steps; ++k) {
          const REAL t = t0 + (k + RC(0.5)) * dt;
          REAL path = INFINITY;
          int nearest = 0;
          for (int a = 0; a < 3; ++a) {
            const REAL pa = (bound[a] - x[a] - t * d[a]) * inv[a];
            if (inv[a] != 0 && pa < path) {
              path = pa;
              nearest = a;
            }
          }
          /* The product only while it is exact: in thick rain a ratio overflows (the sun's
           * path shortening faster than the view ray lengthens, exp(+σ·Δt·…)) where the
           * term has underflowed, and 0·∞ made NaN pixels; a term underflowed to 0 would
           * also stay 0 under a finite ratio > 1.  Elsewhere the exp is taken afresh. */
          const int product = nearest == face && term > RC(1e-30) && ratio[nearest] < RC(1e30);
          term = product ? term * ratio[nearest] : exp(-sigma * (t - t0 + fmax(path, RC(0.0))));
          face = nearest;
          march += term;
        }
        march *= dt;
        sigma_done = sigma;
      }
      radiance = sun[l] * sky_beta(beta, &s, l, phi, theta) * march + radiance * exp(-sigma * (t1 - t0));
    }
    for (int c = 0; c < 3; ++c) out[c] += radiance * weights[3 * l + c];
  }
  for (int c = 0; c < 3; ++c) xyz[3 * (long)pixel + c] = (float)out[c];
  theta_out[pixel] = (float)theta;
}
