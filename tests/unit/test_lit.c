/* Unit tests of the lit-smoke CPU side (src/tables/smoke_texture.c, ref/lit_ref.c): the procedural
 * smoke textures and the double reference of every lighting term and of the ray march. No GL. */
#include <stdint.h>
#include "check.h"
#include "lit_ref.h"
#include "reference.h"

#define SIZE 64
#define VARIANTS 3

static uint8_t *generate(int size, int variants, uint32_t seed)
{
    uint8_t *t = malloc(sbfx_smoke_texture_bytes(size, variants));
    float *scratch = malloc(sizeof(float) * sbfx_smoke_scratch_floats(size));
    if (!t || !scratch) CHECK_SKIP("out of memory");
    CHECK(sbfx_smoke_texture_generate(size, variants, seed, t, scratch) == 0);
    free(scratch);
    return t;
}

static const uint8_t *texel(const uint8_t *t, int size, int layer, int x, int y)
{
    return t + (((size_t)layer * size + y) * size + x) * 4;
}

/* Distance of texel (x, y)'s centre from the image centre, 1 on the inscribed circle. */
static double rho(int size, int x, int y)
{
    double dx = 2.0 * (x + 0.5) / size - 1.0, dy = 2.0 * (y + 0.5) / size - 1.0;
    return sqrt(dx * dx + dy * dy);
}

CHECK_TEST(texture_is_deterministic_and_seeded)
{
    size_t bytes = sbfx_smoke_texture_bytes(SIZE, VARIANTS), layer = (size_t)SIZE * SIZE * 4;
    uint8_t *a = generate(SIZE, VARIANTS, 7), *b = generate(SIZE, VARIANTS, 7), *c = generate(SIZE, VARIANTS, 8);
    size_t chain = 0;
    for (int side = SIZE; side >= 1; side /= 2) chain += (size_t)side * side * 4 * 2 * VARIANTS;
    CHECK(bytes == chain, "%zu bytes, want %zu with the mip chain", bytes, chain);
    CHECK(memcmp(a, b, bytes) == 0, "same seed, different texels");
    CHECK(memcmp(a, c, bytes) != 0, "different seeds, same texels");
    CHECK(memcmp(a, a + 2 * layer, layer) != 0, "variants 0 and 1 are the same");
    CHECK(sbfx_smoke_texture_seed(1, 0) != sbfx_smoke_texture_seed(1, 1));
    free(a), free(b), free(c);
}

CHECK_TEST(texture_rejects_bad_sizes)
{
    uint8_t out[16];
    float scratch[16];
    CHECK(sbfx_smoke_texture_generate(8, 1, 1, out, scratch) == -1);
    CHECK(sbfx_smoke_texture_generate(SBFX_SMOKE_MAX_SIZE * 2, 1, 1, out, scratch) == -1);
    CHECK(sbfx_smoke_texture_generate(16, 0, 1, out, scratch) == -1);
    CHECK(sbfx_smoke_texture_generate(16, SBFX_SMOKE_MAX_VARIANTS + 1, 1, out, scratch) == -1);
    CHECK(sbfx_smoke_texture_generate(16, 1, 1, NULL, scratch) == -1);
}

/* The height field is a puff: 0 outside the inscribed circle (so CLAMP_TO_EDGE sees no seam),
 * highest in the middle, falling toward the rim ring by ring. */
CHECK_TEST(height_is_a_puff_weighted_by_distance_from_centre)
{
    uint8_t *t = generate(SIZE, VARIANTS, 3);
    for (int v = 0; v < VARIANTS; v++) {
        double ring_sum[5] = {0}, ring_n[5] = {0};
        int outside = 0;
        for (int y = 0; y < SIZE; y++)
            for (int x = 0; x < SIZE; x++) {
                int h = texel(t, SIZE, 2 * v, x, y)[3];
                double r = rho(SIZE, x, y);
                if (r >= 1.0 && h != 0) outside++;
                if (r < 1.0) ring_sum[(int)(r * 5)] += h / 255.0, ring_n[(int)(r * 5)]++;
            }
        CHECK(outside == 0, "variant %d: %d texels outside the circle have height", v, outside);
        for (int i = 0; i < 5; i++) ring_sum[i] /= ring_n[i];
        printf("# variant %d mean height by ring: %.3f %.3f %.3f %.3f %.3f\n", v, ring_sum[0], ring_sum[1],
               ring_sum[2], ring_sum[3], ring_sum[4]);
        CHECK(ring_sum[0] > 0.5, "variant %d: centre only %.3f high", v, ring_sum[0]);
        for (int i = 1; i < 5; i++) CHECK(ring_sum[i] < ring_sum[i - 1], "variant %d: ring %d not lower", v, i);
    }
    free(t);
}

/* Normals are unit, face the eye (z > 0), and follow the height field: on the puff's slopes
 * they lean the way the height falls (outward), as -grad(H) with H = strength x height / 2. */
CHECK_TEST(normals_are_unit_and_follow_the_height)
{
    uint8_t *t = generate(SIZE, 1, 11);
    int bad_length = 0, bad_z = 0, agree = 0, slopes = 0;
    double worst = 0.0;
    for (int y = 1; y < SIZE - 1; y++)
        for (int x = 1; x < SIZE - 1; x++) {
            const uint8_t *n8 = texel(t, SIZE, 0, x, y);
            double n[3] = {n8[0] / 127.5 - 1, n8[1] / 127.5 - 1, n8[2] / 127.5 - 1};
            double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            if (fabs(len - 1.0) > 0.02) bad_length++;
            if (!(n[2] > 0.0)) bad_z++;
            const double slope = SBFX_SMOKE_NORMAL_STRENGTH * 0.25 * SIZE;
            double gx = (texel(t, SIZE, 0, x + 1, y)[3] - texel(t, SIZE, 0, x - 1, y)[3]) / 255.0 * slope;
            double gy = (texel(t, SIZE, 0, x, y + 1)[3] - texel(t, SIZE, 0, x, y - 1)[3]) / 255.0 * slope;
            double want[3] = {-gx, -gy, 1.0}, wl = sqrt(gx * gx + gy * gy + 1.0);
            for (int k = 0; k < 3; k++) worst = fmax(worst, fabs(want[k] / wl - n[k] / len));
            if (fabs(gx) > 0.3 * SBFX_SMOKE_NORMAL_STRENGTH) {
                slopes++;
                if ((gx < 0) == (n[0] > 0)) agree++;
            }
        }
    printf("# normal vs -grad(H) of the stored height: max component difference %.4f\n", worst);
    CHECK(bad_length == 0, "%d normals are not unit", bad_length);
    CHECK(bad_z == 0, "%d normals face away from the eye", bad_z);
    CHECK(slopes > 100 && agree == slopes, "%d of %d slope normals lean the wrong way", slopes - agree, slopes);
    /* the test differentiates 8-bit heights: rounding moves its gradient by up to strength x 0.25 size/255 */
    CHECK(worst < SBFX_SMOKE_NORMAL_STRENGTH * 0.25 * SIZE / 255.0 + 0.02, "normal map differs from the height field's gradient by %.3f", worst);
    free(t);
}

CHECK_TEST(translucency_is_high_where_the_smoke_is_thin)
{
    uint8_t *t = generate(SIZE, VARIANTS, 5);
    double thin = 0, thick = 0, n_thin = 0, n_thick = 0, bright_min = 1, bright_max = 0;
    for (int v = 0; v < VARIANTS; v++)
        for (int y = 0; y < SIZE; y++)
            for (int x = 0; x < SIZE; x++) {
                double h = texel(t, SIZE, 2 * v, x, y)[3] / 255.0;
                const uint8_t *d = texel(t, SIZE, 2 * v + 1, x, y);
                double tr = d[1] / 255.0, b = d[0] / 255.0;
                bright_min = fmin(bright_min, b), bright_max = fmax(bright_max, b);
                if (rho(SIZE, x, y) >= 1.0) continue;
                if (h < 0.25) thin += tr, n_thin++;
                if (h > 0.6) thick += tr, n_thick++;
            }
    printf("# translucency: thin %.3f, thick %.3f; brightness in [%.3f, %.3f]\n", thin / n_thin,
           thick / n_thick, bright_min, bright_max);
    CHECK(thin / n_thin > 2.0 * (thick / n_thick), "thin %.3f vs thick %.3f", thin / n_thin, thick / n_thick);
    CHECK(bright_min >= 0.59 && bright_max <= 1.0 && bright_max - bright_min > 0.2, "brightness [%g, %g]",
          bright_min, bright_max);
    free(t);
}

/* The mip chain: log2(size) + 1 levels down to 1 x 1, each the rounded 2x2 box average of the
 * level above, layer by layer. */
CHECK_TEST(mip_chain_is_the_box_average)
{
    uint8_t *t = generate(SIZE, 2, 13);
    const int layers = 4, levels = sbfx_smoke_texture_levels(SIZE);
    CHECK(levels == 7 && sbfx_smoke_texture_levels(16) == 5 && sbfx_smoke_texture_levels(512) == 10);
    CHECK(sbfx_smoke_level_offset(SIZE, layers, 1) == (size_t)SIZE * SIZE * 4 * layers);
    int wrong = 0;
    for (int level = 1; level < levels; level++) {
        int side = SIZE >> level, above = side * 2;
        const uint8_t *src = t + sbfx_smoke_level_offset(SIZE, layers, level - 1);
        const uint8_t *dst = t + sbfx_smoke_level_offset(SIZE, layers, level);
        for (int l = 0; l < layers; l++)
            for (int y = 0; y < side; y++)
                for (int x = 0; x < side; x++)
                    for (int c = 0; c < 4; c++) {
                        int sum = 0;
                        for (int k = 0; k < 4; k++)
                            sum += src[(((size_t)l * above + 2 * y + k / 2) * above + 2 * x + k % 2) * 4 + c];
                        if (dst[(((size_t)l * side + y) * side + x) * 4 + c] != (sum + 2) / 4) wrong++;
                    }
    }
    CHECK(wrong == 0, "%d mip texels are not the box average", wrong);
    /* trilinear: halfway between two levels is the mean of the two bilinear fetches */
    sbfx_smoke_texture tex = {SIZE, layers, levels, t};
    double a[4], b[4], mid[4];
    sbfx_smoke_sample(&tex, 1, 0.37, 0.61, 2.0, a);
    sbfx_smoke_sample(&tex, 1, 0.37, 0.61, 3.0, b);
    sbfx_smoke_sample(&tex, 1, 0.37, 0.61, 2.5, mid);
    for (int c = 0; c < 4; c++) CHECK_NEAR(mid[c], 0.5 * (a[c] + b[c]), 1e-12);
    sbfx_smoke_sample(&tex, 1, 0.37, 0.61, 99.0, a); /* clamped to the 1 x 1 level */
    const uint8_t *last = t + sbfx_smoke_level_offset(SIZE, layers, levels - 1) + 4;
    CHECK_NEAR(a[0], last[0] / 255.0, 1e-12);
    free(t);
}

/* One lod per particle: log2 of texels per pixel, 0 when magnified. */
CHECK_TEST(lod_follows_the_particles_footprint)
{
    CHECK_NEAR(sbfx_lit_lod(128, 1.0, 10.0, 0.01), log2(128 * 0.01 * 10.0 / 2.0), 1e-12); /* 6.4 texels */
    CHECK_NEAR(sbfx_lit_lod(128, 1.0, 2.0, 0.01), log2(1.28), 1e-12);
    CHECK_NEAR(sbfx_lit_lod(128, 5.0, 2.0, 0.01), 0.0, 1e-15);  /* magnified */
    CHECK_NEAR(sbfx_lit_lod(128, 1.0, 20.0, 0.01), sbfx_lit_lod(128, 1.0, 10.0, 0.01) + 1.0, 1e-12);
    CHECK(sbfx_lit_lod(128, 0.0, 10.0, 0.01) == 30.0); /* radius 0: the coarsest level, finite */
    CHECK(sbfx_lit_lod(128, 1.0, NAN, 0.01) == 0.0);
    double rgba[4];
    uint8_t one[4 * 4] = {10, 20, 30, 40};
    sbfx_smoke_texture tiny = {1, 1, 1, one};
    sbfx_smoke_sample(&tiny, 0, 0.5, 0.5, INFINITY, rgba);
    CHECK_NEAR(rgba[3], 40 / 255.0, 1e-12);
}

/* ---- a synthetic texture of constant maps, for terms with closed forms ---- */
typedef struct flat_texture {
    uint8_t texels[16 * 16 * 4 * 2];
    sbfx_smoke_texture tex;
} flat_texture;

static void flat_init(flat_texture *f, const uint8_t surface[4], const uint8_t diffuse[4])
{
    for (int i = 0; i < 16 * 16; i++) {
        memcpy(f->texels + 4 * i, surface, 4);
        memcpy(f->texels + 16 * 16 * 4 + 4 * i, diffuse, 4);
    }
    f->tex = (sbfx_smoke_texture){16, 2, 1, f->texels};
}

CHECK_TEST(sampler_filters_like_the_gpu)
{
    flat_texture f;
    flat_init(&f, (const uint8_t[4]){0, 0, 0, 0}, (const uint8_t[4]){0, 0, 0, 255});
    f.texels[(3 * 16 + 4) * 4] = 255; /* texel (4, 3) of layer 0, red */
    double rgba[4];
    sbfx_smoke_sample(&f.tex, 0, 4.5 / 16, 3.5 / 16, 0.0, rgba);
    CHECK_NEAR(rgba[0], 1.0, 1e-12);
    sbfx_smoke_sample(&f.tex, 0, 5.0 / 16, 3.5 / 16, 0.0, rgba);
    CHECK_NEAR(rgba[0], 0.5, 1e-12);
    sbfx_smoke_sample(&f.tex, 0, 5.0 / 16, 4.0 / 16, 0.0, rgba);
    CHECK_NEAR(rgba[0], 0.25, 1e-12);
    sbfx_smoke_sample(&f.tex, 0, 5.0 / 16, 4.0 / 16, 3.0, rgba); /* one level: lod clamped to it */
    CHECK_NEAR(rgba[0], 0.25, 1e-12);
    f.texels[0] = 255; /* texel (0, 0): clamped beyond the edge */
    sbfx_smoke_sample(&f.tex, 0, -3.0, -0.5, 0.0, rgba);
    CHECK_NEAR(rgba[0], 1.0, 1e-12);
    sbfx_smoke_sample(&f.tex, 1, NAN, INFINITY, NAN, rgba);
    CHECK_FINITE(rgba[0]);
    CHECK_NEAR(rgba[3], 1.0, 1e-12);
}

CHECK_TEST(variant_comes_from_detail_u)
{
    CHECK(sbfx_lit_variant(0.0, 4) == 0);
    CHECK(sbfx_lit_variant(0.26, 4) == 1);
    CHECK(sbfx_lit_variant(0.9999, 4) == 3);
    CHECK(sbfx_lit_variant(1.0, 4) == 3);
    CHECK(sbfx_lit_variant(-2.0, 4) == 0);
    CHECK(sbfx_lit_variant(NAN, 4) == 0);
    CHECK(sbfx_lit_variant(0.7, 1) == 0);
}

/* Seed eq. 5.2.3-5.2.4: (N.L) / (1+w) + w / (1+w), clamped at 0. */
CHECK_TEST(wrap_is_the_seeds_scale_and_bias)
{
    CHECK_NEAR(sbfx_lit_wrap(0.7, 0.0), 0.7, 1e-15);
    CHECK_NEAR(sbfx_lit_wrap(-0.3, 0.0), 0.0, 1e-15);
    CHECK_NEAR(sbfx_lit_wrap(1.0, 0.6), 1.0, 1e-15);
    CHECK_NEAR(sbfx_lit_wrap(0.0, 0.6), 0.375, 1e-15);
    CHECK_NEAR(sbfx_lit_wrap(-0.6, 0.6), 0.0, 1e-15);
    CHECK_NEAR(sbfx_lit_wrap(-1.0, 0.6), 0.0, 1e-15);
    CHECK_NEAR(sbfx_lit_wrap(-1.0, 1.0), 0.0, 1e-15);
    CHECK_NEAR(sbfx_lit_wrap(-0.5, 1.0), 0.25, 1e-15);
}

/* The sign convention: only a light behind the particle (V.L < 0) adds back-light, the more
 * the more directly behind; the seed's printed min(0, E.L) x map would subtract it. */
CHECK_TEST(backlight_only_for_lights_behind)
{
    CHECK_NEAR(sbfx_lit_backlight(-1.0, 0.8, 1.5), 1.2, 1e-15);   /* exactly behind */
    CHECK_NEAR(sbfx_lit_backlight(1.0, 0.8, 1.5), 0.0, 1e-15);    /* exactly in front */
    CHECK_NEAR(sbfx_lit_backlight(0.0, 0.8, 1.5), 0.0, 1e-15);    /* to the side */
    CHECK_NEAR(sbfx_lit_backlight(-0.5, 0.8, 1.0), 0.4, 1e-15);
    double seed_printed = fmin(0.0, -1.0) * 0.8;
    CHECK(seed_printed < 0.0 && sbfx_lit_backlight(-1.0, 0.8, 1.0) == -seed_printed);
}

CHECK_TEST(step_count_is_view_dependent)
{
    CHECK(sbfx_lit_steps(0.0, 4, 16) == 4);   /* N.V = 0: nMin */
    CHECK(sbfx_lit_steps(1.0, 4, 16) == 16);
    CHECK(sbfx_lit_steps(0.5, 4, 16) == 10);
    CHECK(sbfx_lit_steps(0.125, 4, 16) == 6); /* 5.5 rounds up */
    CHECK(sbfx_lit_steps(2.0, 4, 16) == 16);
    CHECK(sbfx_lit_steps(-1.0, 4, 16) == 4);
    CHECK(sbfx_lit_steps(NAN, 4, 16) == 4);
    for (double nv = 0.0; nv <= 1.0; nv += 0.05) CHECK(sbfx_lit_steps(nv, 8, 8) == 8); /* nMax = nMin */
    CHECK(sbfx_lit_steps(0.7, 0, 0) == 0);
}

/* A slab of height 1 everywhere: straight through, the density 1 - 2|z| integrates to 1/2 of the
 * diameter, so the transmittance is exp(-tau r) — exactly for an even number of midpoint steps
 * (the kink at z = 0 falls on a step boundary). In front or grazing along the surface: 1. */
CHECK_TEST(shadow_through_a_flat_slab_is_analytic)
{
    flat_texture f;
    flat_init(&f, (const uint8_t[4]){128, 128, 255, 255}, (const uint8_t[4]){255, 255, 0, 255});
    const double st[2] = {0.5, 0.5}, behind[3] = {0, 0, -1}, front[3] = {0, 0, 1}, side[3] = {1, 0, 0};
    const double tau = 0.7, r = 1.3, want = exp(-tau * r);
    for (int n = 2; n <= 64; n *= 2) CHECK_NEAR(sbfx_lit_shadow(&f.tex, 0, 0.0, st, 1.0, behind, r, tau, n), want, 1e-12);
    double odd = sbfx_lit_shadow(&f.tex, 0, 0.0, st, 1.0, behind, r, tau, 3);
    CHECK(fabs(odd - want) > 1e-6 && fabs(odd - want) < 0.05, "3 steps: %g vs %g", odd, want);
    CHECK_NEAR(sbfx_lit_shadow(&f.tex, 0, 0.0, st, 1.0, front, r, tau, 16), 1.0, 1e-15);
    CHECK_NEAR(sbfx_lit_shadow(&f.tex, 0, 0.0, st, 1.0, side, r, tau, 16), 1.0, 1e-15);
    CHECK_NEAR(sbfx_lit_shadow(&f.tex, 0, 0.0, st, 1.0, behind, r, tau, 0), 1.0, 1e-15); /* no march */
    CHECK_NEAR(sbfx_lit_shadow(&f.tex, 0, 0.0, st, 1.0, behind, r, 0.0, 16), 1.0, 1e-15);
    double big = sbfx_lit_shadow(&f.tex, 0, 0.0, st, 1.0, behind, r, 1e6, 16);
    CHECK(big >= 0.0 && big < 1e-100, "tau 1e6: %g", big);
}

/* On a generated puff the march converges as the steps grow (against 1024 steps). */
CHECK_TEST(shadow_converges_with_steps)
{
    uint8_t *t = generate(SIZE, 1, 9);
    sbfx_smoke_texture tex = {SIZE, 2, sbfx_smoke_texture_levels(SIZE), t};
    sbfx_rng rng;
    sbfx_rng_seed(&rng, 42);
    const int counts[] = {2, 4, 8, 16, 32, 64};
    double err[6] = {0};
    for (int i = 0; i < 400; i++) {
        double st[2] = {sbfx_rng_range(&rng, 0.15, 0.85), sbfx_rng_range(&rng, 0.15, 0.85)}, rgba[4];
        sbfx_smoke_sample(&tex, 0, st[0], st[1], 0.0, rgba);
        double l[3] = {sbfx_rng_range(&rng, -1, 1), sbfx_rng_range(&rng, -1, 1), sbfx_rng_range(&rng, -1, 0.3)};
        double len = sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
        for (int k = 0; k < 3; k++) l[k] /= len;
        double ref = sbfx_lit_shadow(&tex, 0, 0.0, st, rgba[3], l, 1.0, 1.5, 1024);
        for (int c = 0; c < 6; c++)
            err[c] += fabs(sbfx_lit_shadow(&tex, 0, 0.0, st, rgba[3], l, 1.0, 1.5, counts[c]) - ref) / 400;
    }
    printf("# mean |S(n) - S(1024)|: n=2 %.4f, 4 %.4f, 8 %.4f, 16 %.4f, 32 %.5f, 64 %.5f\n", err[0], err[1],
           err[2], err[3], err[4], err[5]);
    for (int c = 1; c < 6; c++) CHECK(err[c] < err[c - 1], "%d steps no better than %d", counts[c], counts[c - 1]);
    CHECK(err[5] < 0.01, "64 steps still %.4f off", err[5]);
    free(t);
}

/* ---- the whole fragment ---- */
static const double centre[3] = {0.0, 0.0, -5.0}, ray_centre[3] = {0.0, 0.0, -1.0};

static sbfx_lit_medium medium(double wrap, double translucency, int n)
{
    return (sbfx_lit_medium){{0.5, 0.4, 0.3}, 0.8, wrap, translucency, 0.0, n, n};
}

CHECK_TEST(zero_lights_give_ambient_only)
{
    flat_texture f;
    flat_init(&f, (const uint8_t[4]){128, 128, 255, 200}, (const uint8_t[4]){204, 255, 0, 255});
    sbfx_lit_medium m = medium(0.6, 1.0, 8);
    const double ambient[3] = {0.2, 0.3, 0.4};
    double rgb[3];
    sbfx_lit_radiance(&m, &f.tex, 0, 0.0, centre, 1.0, ray_centre, NULL, 0, ambient, rgb);
    for (int k = 0; k < 3; k++) CHECK_NEAR(rgb[k], m.albedo_color[k] * 0.8 * ambient[k], 1e-12);
    m.dampening = 1.0; /* dampening removes the lights, never the ambient */
    sbfx_lit_light sun = {{0, 0, -1, 0}, {5, 5, 5}};
    sbfx_lit_radiance(&m, &f.tex, 0, 0.0, centre, 1.0, ray_centre, &sun, 1, ambient, rgb);
    for (int k = 0; k < 3; k++) CHECK_NEAR(rgb[k], m.albedo_color[k] * 0.8 * ambient[k], 1e-12);
}

/* A flat puff facing the eye: a light exactly in front gives Lambert 1 and no back-light; a
 * light exactly behind gives no diffuse (w = 0) and the full back-light, shadowed by the slab. */
CHECK_TEST(light_in_front_and_light_behind)
{
    flat_texture f;
    flat_init(&f, (const uint8_t[4]){128, 128, 255, 255}, (const uint8_t[4]){255, 153, 0, 255});
    sbfx_lit_medium m = medium(0.0, 2.0, 8);
    m.albedo_color[0] = m.albedo_color[1] = m.albedo_color[2] = 1.0;
    const double none[3] = {0, 0, 0};
    sbfx_lit_light front = {{0, 0, -1, 0}, {1, 1, 1}}, behind = {{0, 0, 1, 0}, {1, 1, 1}};
    double rgb[3];
    sbfx_lit_radiance(&m, &f.tex, 0, 0.0, centre, 1.0, ray_centre, &front, 1, none, rgb);
    double n_dot_l = 255 / 127.5 - 1; /* the filtered normal as it is, not renormalised */
    CHECK_NEAR(rgb[0], n_dot_l, 1e-12);
    sbfx_lit_radiance(&m, &f.tex, 0, 0.0, centre, 1.0, ray_centre, &behind, 1, none, rgb);
    CHECK_NEAR(rgb[0], 2.0 * 0.6 * exp(-0.8 * 1.0), 1e-9);
    /* the seed's wrap lets some front light round the edge of a backlit normal */
    m.wrap = 0.6;
    sbfx_lit_radiance(&m, &f.tex, 0, 0.0, centre, 1.0, ray_centre, &behind, 1, none, rgb);
    CHECK_NEAR(rgb[0], 2.0 * 0.6 * exp(-0.8), 1e-9); /* N.L = -1: wrap gives 0 still */
}

/* Only the key light (the first) is marched: the same light behind the puff a second time
 * adds its back-light unshadowed, and swapping the two lights' colours moves the shadow. */
CHECK_TEST(only_the_key_light_is_shadowed)
{
    flat_texture f;
    flat_init(&f, (const uint8_t[4]){128, 128, 255, 255}, (const uint8_t[4]){255, 153, 0, 255});
    sbfx_lit_medium m = medium(0.0, 2.0, 8);
    m.albedo_color[0] = m.albedo_color[1] = m.albedo_color[2] = 1.0;
    const double none[3] = {0, 0, 0};
    sbfx_lit_light two[2] = {{{0, 0, 1, 0}, {1, 1, 1}}, {{0, 0, 1, 0}, {1, 1, 1}}};
    double rgb[3];
    sbfx_lit_radiance(&m, &f.tex, 0, 0.0, centre, 1.0, ray_centre, two, 2, none, rgb);
    CHECK_NEAR(rgb[0], 2.0 * 0.6 * exp(-0.8) + 2.0 * 0.6, 1e-9);
    two[0].color[1] = 3.0; /* green from the key light: shadowed; red from both */
    sbfx_lit_radiance(&m, &f.tex, 0, 0.0, centre, 1.0, ray_centre, two, 2, none, rgb);
    CHECK_NEAR(rgb[1], 3.0 * 2.0 * 0.6 * exp(-0.8) + 2.0 * 0.6, 1e-9);
    sbfx_lit_light swapped[2] = {two[1], two[0]};
    sbfx_lit_radiance(&m, &f.tex, 0, 0.0, centre, 1.0, ray_centre, swapped, 2, none, rgb);
    CHECK_NEAR(rgb[1], 2.0 * 0.6 * exp(-0.8) + 3.0 * 2.0 * 0.6, 1e-9);
}

/* N.V = 0 (normals in the screen plane), a point light inside the particle and one exactly at
 * the shaded point: finite, and the last one has no direction (only the wrap's bias lights it). */
CHECK_TEST(degenerate_geometry_stays_finite)
{
    flat_texture f;
    flat_init(&f, (const uint8_t[4]){255, 128, 128, 128}, (const uint8_t[4]){255, 255, 0, 255});
    sbfx_lit_medium m = medium(0.6, 1.0, 0);
    m.steps_min = 2, m.steps_max = 32;
    const double ambient[3] = {0.1, 0.1, 0.1};
    sbfx_lit_light lights[4] = {
        {{0, 0, -5, 1}, {3, 3, 3}},                  /* at the centre: inside the particle */
        {{0, 0, -5.0 + 128 / 255.0, 1}, {2, 2, 2}},  /* exactly at the shaded point */
        {{0, 0, 1, 0}, {1, 1, 1}},                   /* exactly behind */
        {{0, 0, -1, 0}, {1, 1, 1}}};                 /* exactly in front */
    double rgb[3];
    sbfx_lit_radiance(&m, &f.tex, 0, 0.0, centre, 1.0, ray_centre, lights, 4, ambient, rgb);
    for (int k = 0; k < 3; k++) CHECK(isfinite(rgb[k]) && rgb[k] > 0.0, "rgb[%d] = %g", k, rgb[k]);
    double at_point[3];
    sbfx_lit_radiance(&m, &f.tex, 0, 0.0, centre, 1.0, ray_centre, &lights[1], 1, (const double[3]){0, 0, 0}, at_point);
    /* no direction: the wrap's bias w/(1+w), falloff 4, the march stays where the density is 0 */
    CHECK_NEAR(at_point[0], 0.5 * 2 * 4 * (0.6 / 1.6), 1e-9);
    /* a fifth light is ignored: lit media take four */
    sbfx_lit_light five[5] = {lights[0], lights[1], lights[2], lights[3], {{0, 1, 0, 0}, {100, 100, 100}}};
    double rgb5[3];
    sbfx_lit_radiance(&m, &f.tex, 0, 0.0, centre, 1.0, ray_centre, five, 5, ambient, rgb5);
    CHECK(rgb5[0] == rgb[0]);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
