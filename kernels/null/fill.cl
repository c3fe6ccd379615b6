// The null engine's one kernel (docs/adding-an-engine.md): every pixel gets the swatch's
// colour.  ARCUS_USE_NULL_FILL comes from the engine's feature table, as every engine's
// -D flags do; without it this program must not build.
#ifndef ARCUS_USE_NULL_FILL
#error "the null engine's kernel is built only with its NULL_FILL feature"
#endif

kernel void arcus_null_fill(ARCUS_PARAMS(ARCUS_NULL_FILL_ARGS)) {
  const uint i = (uint)get_global_id(0);
  if (i >= pixels) return;
  for (int c = 0; c < 3; ++c) rgb[3 * i + c] = colour[c];
}
