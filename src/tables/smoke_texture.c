/* Procedural smoke textures (the lit-smoke seed's appendix): fBm and turbulence weighted by the
 * distance from the centre of the image. Per variant, three independent fBm fields f1..f3 in
 * (0,1) (the detail volume's lattice, one frame: f1, f2 the smooth fBm of gain 1/2,
 * sbfx_detail_generate_smooth; f3 gain BRIGHTNESS_GAIN, finer veins) give
 *   edge   = 0.7 + 0.3 f1                  the puff's ragged outline (inside the unit circle)
 *   height = sqrt(1 - (rho/edge)^2) * (0.55 + 0.45 f2)   rho = distance from the centre, 1 at
 *            the inscribed circle: a sphere where f = 1, so lit normals read as a round puff
 *   brightness   = 1 - 0.4 |2 f3 - 1|      turbulence: dark veins, little pre-lighting
 *   translucency = (1 - height)(0.6 + 0.4 f3)   thin smoke lets light through: the rim glows
 *   normal = normalize(-dH/ds, -dH/dt, 1) with H = SBFX_SMOKE_NORMAL_STRENGTH x height / 2 (slab
 *            half-thickness in units of the particle's diameter, the relief shaded as 0.35 as
 *            deep: docs/look.md), central differences.
 * The height is 0 outside the outline, so CLAMP_TO_EDGE sampling sees no seam. The mip chain is
 * the rounded 2x2 box average of the level above, layer by layer. */
#include <math.h>
#include <string.h>
#include "tables/tables.h"

/* The brightness veins' fBm gain (with the normal strength, docs/look.md: the rendered lit
 * smoke's spectrum within the turbulent range in every view measured). */
#define BRIGHTNESS_GAIN 0.65

int sbfx_smoke_texture_levels(int size)
{
    int levels = 1;
    while (size > 1) size >>= 1, levels++;
    return levels;
}

size_t sbfx_smoke_level_offset(int size, int layers, int level)
{
    size_t offset = 0;
    for (int l = 0; l < level; l++) {
        size_t side = (size_t)(size >> l > 0 ? size >> l : 1);
        offset += side * side * 4u * (size_t)layers;
    }
    return offset;
}

size_t sbfx_smoke_texture_bytes(int size, int variants)
{
    int layers = SBFX_SMOKE_LAYERS_PER_VARIANT * variants;
    return sbfx_smoke_level_offset(size, layers, sbfx_smoke_texture_levels(size));
}

size_t sbfx_smoke_scratch_floats(int size) { return 3u * (size_t)size * (size_t)size; }

uint32_t sbfx_smoke_texture_seed(uint32_t seed, int medium)
{
    return seed * 0x9E3779B1u + 0x5A17u * (uint32_t)(medium + 1);
}

static uint8_t unorm8(double v)
{
    v = v < 0.0 ? 0.0 : v > 1.0 ? 1.0 : v;
    return (uint8_t)lrint(v * 255.0);
}

static double height_at(double s, double t, double f1, double f2)
{
    double dx = 2.0 * s - 1.0, dy = 2.0 * t - 1.0;
    double rho = sqrt(dx * dx + dy * dy) / (0.7 + 0.3 * f1);
    return rho >= 1.0 ? 0.0 : sqrt((1.0 - rho) * (1.0 + rho)) * (0.55 + 0.45 * f2);
}

/* dH/ds by central differences over the clamped neighbours (one-sided at the border). */
static void height_gradient(const float *h, int size, int x, int y, double grad[2])
{
    int xm = x > 0 ? x - 1 : x, xp = x < size - 1 ? x + 1 : x;
    int ym = y > 0 ? y - 1 : y, yp = y < size - 1 ? y + 1 : y;
    grad[0] = 0.5 * (h[y * size + xp] - h[y * size + xm]) * size / (xp - xm);
    grad[1] = 0.5 * (h[yp * size + x] - h[ym * size + x]) * size / (yp - ym);
}

static void write_variant(int size, const float *f1, const float *f2, const float *f3, float *h,
                          uint8_t *surface, uint8_t *diffuse)
{
    for (int y = 0; y < size; y++)
        for (int x = 0; x < size; x++) {
            int i = y * size + x; /* f1 is read before h overwrites it: h may alias f1 */
            h[i] = (float)height_at((x + 0.5) / size, (y + 0.5) / size, f1[i], f2[i]);
        }
    for (int y = 0; y < size; y++)
        for (int x = 0; x < size; x++) {
            int i = y * size + x;
            double g[2];
            height_gradient(h, size, x, y, g);
            double n[3] = {-SBFX_SMOKE_NORMAL_STRENGTH * g[0], -SBFX_SMOKE_NORMAL_STRENGTH * g[1], 1.0};
            double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            for (int k = 0; k < 3; k++) surface[4 * i + k] = unorm8(n[k] / len * 0.5 + 0.5);
            surface[4 * i + 3] = unorm8(h[i]);
            double turbulence = fabs(2.0 * f3[i] - 1.0);
            diffuse[4 * i + 0] = unorm8(1.0 - 0.4 * turbulence);
            diffuse[4 * i + 1] = unorm8((1.0 - h[i]) * (0.6 + 0.4 * f3[i]));
            diffuse[4 * i + 2] = 0;
            diffuse[4 * i + 3] = 255;
        }
}

/* Level `level` (side `side`) of every layer from the level above. */
static void downsample(uint8_t *texels, int size, int layers, int level)
{
    int side = size >> level, above = side * 2;
    const uint8_t *src = texels + sbfx_smoke_level_offset(size, layers, level - 1);
    uint8_t *dst = texels + sbfx_smoke_level_offset(size, layers, level);
    for (int l = 0; l < layers; l++)
        for (int y = 0; y < side; y++)
            for (int x = 0; x < side; x++)
                for (int c = 0; c < 4; c++) {
                    const uint8_t *a = src + (((size_t)l * above + 2 * y) * above + 2 * x) * 4 + c;
                    size_t row = (size_t)above * 4;
                    dst[(((size_t)l * side + y) * side + x) * 4 + c] = (uint8_t)((a[0] + a[4] + a[row] + a[row + 4] + 2) / 4);
                }
}

int sbfx_smoke_texture_generate(int size, int variants, uint32_t seed, uint8_t *out, float *scratch)
{
    if (size < SBFX_SMOKE_MIN_SIZE || size > SBFX_SMOKE_MAX_SIZE || (size & (size - 1)) || variants < 1 ||
        variants > SBFX_SMOKE_MAX_VARIANTS || !out || !scratch)
        return -1;
    size_t texels = (size_t)size * size, layer_bytes = texels * 4;
    float *f1 = scratch, *f2 = scratch + texels, *f3 = scratch + 2 * texels;
    sbfx_rng rng;
    sbfx_rng_seed(&rng, ((uint64_t)seed << 20) ^ UINT64_C(0x6c69742d736d6f6b));
    for (int v = 0; v < variants; v++) {
        sbfx_detail_generate_smooth(size, 1, sbfx_rng_u32(&rng), f1);
        sbfx_detail_generate_smooth(size, 1, sbfx_rng_u32(&rng), f2);
        sbfx_detail_generate_fbm(size, 1, sbfx_rng_u32(&rng), BRIGHTNESS_GAIN, 5, f3);
        uint8_t *surface = out + (size_t)(SBFX_SMOKE_LAYERS_PER_VARIANT * v) * layer_bytes;
        write_variant(size, f1, f2, f3, f1, surface, surface + layer_bytes);
    }
    for (int level = 1; level < sbfx_smoke_texture_levels(size); level++)
        downsample(out, size, SBFX_SMOKE_LAYERS_PER_VARIANT * variants, level);
    return 0;
}
