/* Lit smoke on the GPU against the CPU reference (ref/lit_ref.c): random configurations and the
 * hard cases, the sign of the back-light, the plan (smoke textures only for lit media), mixed
 * scenes, orbiting lights and no allocation per frame. */
#include "gl_fixture.h"
#include "lit_ref.h"
#include "module.h"
#include "render/tiles.h"
#include "reference.h"

#define SIZE 48
#define CONFIGS 120
/* |GPU - CPU| of premultiplied radiance relative to the pixel's own reference value (plus 1 %
 * of the configuration's full-light scale, so that nearly black pixels do not divide by ~0).
 * Nearly all of it is the texture fetch: llvmpipe returns filtered RGBA8 at 8-bit precision
 * (measured: about 1/255 at worst, at any lod), so brightness, normal and height each carry up
 * to ~0.5 % (brightness >= 0.6). Float vs double is far below. Mean and worst are printed. */
#define RADIANCE_TOLERANCE 0.03
/* A few pixels may differ by more: where N.V puts n = nMin + N.V (nMax - nMin) at a .5 boundary
 * (float and double round to different step counts), or a steep map meets the 8-bit fetch. */
#define ROUNDING_PIXELS 5e-4

/* A scene whose only medium is lit smoke, detail off (so the CPU needs no detail volume). */
static const char *const lit_scene =
    "media = { smoke = { albedo = 0.7; density = 0.8; lighting = \"lit\"; steps = [4, 16];\n"
    "  texture = { size = 64; variants = 3; }; detail = { strength = 0.0; }; }; };\n"
    "effects = { puff = { steps = ( { type = \"emitter\"; medium = \"smoke\"; count = 4; } ); }; };\n";

static sbfx_scene *parse(const char *text)
{
    char err[512];
    sbfx_scene *scene = NULL;
    CHECK(sbfx_scene_parse(text, "lit-test.cfg", &scene, err, sizeof(err)) == SBFX_OK, "%s", err);
    if (!scene) exit(1);
    return scene;
}

static sbfx *lit_module(gl_fixture *f, const char *text)
{
    sbfx_scene *scene = parse(text);
    /* the CPU side takes alpha from the spherical model (lit media keep any opacity model) */
    sbfx *fx = fixture_module(f, (sbfx_desc){.scene = scene, .target_divisor = 1, .opacity = SBFX_OPACITY_SPHERICAL,
                                             .target_format = SBFX_FORMAT_RGBA32F, .max_particles = 8});
    sbfx_scene_free(scene);
    return fx;
}

/* The module's smoke texture, made again on the CPU from the same seed. */
typedef struct cpu_texture {
    uint8_t *texels;
    sbfx_smoke_texture tex;
} cpu_texture;

static cpu_texture cpu_smoke(sbfx *fx)
{
    const sbfx_medium_params *m = &sbfx_media(fx)[SBFX_SMOKE];
    cpu_texture t = {malloc(sbfx_smoke_texture_bytes(m->texture_size, m->texture_variants)), {0}};
    float *scratch = malloc(sizeof(float) * sbfx_smoke_scratch_floats(m->texture_size));
    CHECK(sbfx_smoke_texture_generate(m->texture_size, m->texture_variants, sbfx_smoke_texture_seed(1, SBFX_SMOKE),
                                      t.texels, scratch) == 0);
    free(scratch);
    t.tex = (sbfx_smoke_texture){m->texture_size, 2 * m->texture_variants, sbfx_smoke_texture_levels(m->texture_size),
                                 t.texels};
    return t;
}

typedef struct lit_config {
    sbfx_view_particle particle;
    double tau, wrap, translucency, dampening, albedo;
    int steps[2], light_count;
    sbfx_view_light lights[SBFX_LIT_MAX_LIGHTS];
    float ambient[3];
} lit_config;

typedef struct comparison {
    double worst;        /* largest relative error under the tolerance */
    double worst_all;    /* largest relative error of all (step-count flips included) */
    double sum;          /* of relative errors, for the mean */
    int pixels, over, bad;
    double max_radiance; /* of the GPU image, to see the test is not comparing zeros */
} comparison;

static void apply(sbfx *fx, const lit_config *c)
{
    sbfx_medium_params *m = &sbfx_media(fx)[SBFX_SMOKE];
    m->tau = (float)c->tau, m->wrap = (float)c->wrap, m->translucency = (float)c->translucency;
    m->dampening = (float)c->dampening, m->albedo = (float)c->albedo;
    m->steps_min = c->steps[0], m->steps_max = c->steps[1];
    sbfx_set_lights(fx, c->lights, c->light_count, c->ambient);
}

/* Scale of a pixel's radiance: what it would be lit by everything at full strength. */
static double radiance_scale(const lit_config *c)
{
    double s = c->ambient[0] + c->ambient[1] + c->ambient[2];
    for (int i = 0; i < c->light_count; i++) {
        double e = c->lights[i].color[0] + c->lights[i].color[1] + c->lights[i].color[2];
        s += e * (1.0 + c->translucency) * (c->lights[i].vector[3] > 0.5f ? 4.0 : 1.0);
    }
    return fmax(s / 3.0, 1e-3);
}

static void cpu_pixel(const gl_fixture *f, const lit_config *c, const sbfx_smoke_texture *tex, int w, int h,
                      int x, int y, double rgba[4])
{
    const sbfx_view_particle *p = &c->particle;
    double tau = c->tau * p->intensity, center[3] = {p->center[0], p->center[1], p->center[2]};
    sbfx_ref_particle rp = {{center[0], center[1], center[2]}, p->radius, tau};
    sbfx_ref_pixel px = {{0}, INFINITY, fixture_near(&f->frame), 0.0};
    fixture_ray(f, &f->frame, w, h, x, y, px.ray);
    double alpha = sbfx_ref_opacity(SBFX_OPACITY_SPHERICAL, &rp, &px);
    sbfx_lit_medium m = {{c->albedo, c->albedo, c->albedo}, tau, c->wrap, c->translucency, c->dampening,
                         c->steps[0], c->steps[1]};
    sbfx_lit_light lights[SBFX_LIT_MAX_LIGHTS];
    for (int i = 0; i < c->light_count; i++)
        for (int k = 0; k < 4; k++) {
            lights[i].vector[k] = c->lights[i].vector[k];
            if (k < 3) lights[i].color[k] = c->lights[i].color[k];
        }
    for (int i = 0; i < c->light_count; i++) { /* directions as the module keeps them: unit floats */
        if (lights[i].vector[3] > 0.5) continue;
        double *v = lights[i].vector;
        float len = sqrtf((float)(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
        for (int k = 0; k < 3; k++) v[k] = (float)v[k] / len;
    }
    const double ambient[3] = {c->ambient[0], c->ambient[1], c->ambient[2]};
    double rgb[3];
    double pixel_slope = 2.0 / (w * f->frame.projection[0]);
    double lod = sbfx_lit_lod(tex->size, p->radius, -center[2], pixel_slope);
    sbfx_lit_radiance(&m, tex, sbfx_lit_variant(p->detail[0], tex->layers / 2), lod, center, p->radius, px.ray,
                      lights, c->light_count, ambient, rgb);
    for (int k = 0; k < 3; k++) rgba[k] = rgb[k] * alpha;
    rgba[3] = alpha;
}

static comparison compare(gl_fixture *f, sbfx *fx, const lit_config *c, const sbfx_smoke_texture *tex)
{
    apply(fx, c);
    CHECK(sbfx_render_view_particles(fx, &f->frame, &c->particle, 1) == SBFX_OK, "%s", sbfx_last_error(fx));
    int w, h;
    float *gpu = fixture_read_target(fx, &w, &h);
    comparison r = {0};
    double scale = radiance_scale(c);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double cpu[4];
            cpu_pixel(f, c, tex, w, h, x, y, cpu);
            const float *g = &gpu[4 * (y * w + x)];
            double e = 0.0;
            for (int k = 0; k < 3; k++) {
                if (!isfinite(g[k])) r.bad++;
                e = fmax(e, fabs(g[k] - cpu[k]) / (fabs(cpu[k]) + 0.01 * scale));
                r.max_radiance = fmax(r.max_radiance, g[k]);
            }
            r.pixels++;
            r.sum += e;
            r.worst_all = fmax(r.worst_all, e);
            if (e > RADIANCE_TOLERANCE) r.over++;
            else r.worst = fmax(r.worst, e);
        }
    free(gpu);
    return r;
}

static void random_light(sbfx_rng *rng, const float center[3], float radius, sbfx_view_light *l)
{
    int kind = (int)(sbfx_rng_u32(rng) % 4);
    for (int k = 0; k < 3; k++) l->color[k] = (float)sbfx_rng_range(rng, 0.2, 3.0);
    if (kind == 0) { /* directional, anywhere */
        l->vector[0] = (float)sbfx_rng_range(rng, -1, 1), l->vector[1] = (float)sbfx_rng_range(rng, -1, 1);
        l->vector[2] = (float)sbfx_rng_range(rng, -1, 1), l->vector[3] = 0.0f;
        if (fabsf(l->vector[0]) + fabsf(l->vector[1]) + fabsf(l->vector[2]) < 0.1f) l->vector[2] = 1.0f;
        return;
    }
    /* point: behind, in front, or inside the particle */
    double reach = kind == 3 ? 0.8 * radius : sbfx_rng_range(rng, 1.2, 4.0) * radius;
    double dz = kind == 1 ? -reach : kind == 2 ? reach : sbfx_rng_range(rng, -1, 1) * reach;
    l->vector[0] = center[0] + (float)sbfx_rng_range(rng, -1, 1) * radius;
    l->vector[1] = center[1] + (float)sbfx_rng_range(rng, -1, 1) * radius;
    l->vector[2] = center[2] + (float)dz;
    l->vector[3] = 1.0f;
}

static lit_config random_config(sbfx_rng *rng)
{
    lit_config c = {0};
    double zc = sbfx_rng_range(rng, 2.0, 12.0);
    c.particle = (sbfx_view_particle){
        .center = {(float)(sbfx_rng_range(rng, -0.15, 0.15) * zc), (float)(sbfx_rng_range(rng, -0.15, 0.15) * zc),
                   (float)-zc},
        .radius = (float)(sbfx_rng_range(rng, 0.15, 0.35) * zc),
        .detail = {(float)sbfx_rng_uniform(rng), 0.0f, 0.0f},
        .intensity = (float)sbfx_rng_range(rng, 0.3, 1.0), .medium = SBFX_SMOKE};
    c.tau = sbfx_rng_range(rng, 0.1, 3.0);
    c.wrap = sbfx_rng_range(rng, 0.0, 1.0);
    c.translucency = sbfx_rng_range(rng, 0.0, 3.0);
    c.dampening = sbfx_rng_range(rng, 0.0, 0.5);
    c.albedo = sbfx_rng_range(rng, 0.2, 1.0);
    c.steps[0] = (int)(sbfx_rng_u32(rng) % 9);
    c.steps[1] = c.steps[0] + (int)(sbfx_rng_u32(rng) % 40);
    c.light_count = (int)(sbfx_rng_u32(rng) % (SBFX_LIT_MAX_LIGHTS + 1));
    for (int i = 0; i < c.light_count; i++) random_light(rng, c.particle.center, c.particle.radius, &c.lights[i]);
    for (int k = 0; k < 3; k++) c.ambient[k] = (float)sbfx_rng_range(rng, 0.0, 0.4);
    return c;
}

static void open_lit(gl_fixture *f)
{
    fixture_open(f, SIZE, SIZE);
    fixture_projection(f, 1.0f, 0.1f, 100.0f);
    fixture_depth(f, depth_far_everywhere, NULL);
}

CHECK_TEST(gpu_matches_cpu_lit)
{
    gl_fixture f;
    open_lit(&f);
    sbfx *fx = lit_module(&f, lit_scene);
    cpu_texture t = cpu_smoke(fx);
    sbfx_rng rng;
    sbfx_rng_seed(&rng, 20261207);
    double worst = 0.0, worst_all = 0.0, sum = 0.0, lit_max = 0.0;
    int over = 0, pixels = 0, bad = 0;
    for (int i = 0; i < CONFIGS; i++) {
        lit_config c = random_config(&rng);
        comparison r = compare(&f, fx, &c, &t.tex);
        worst = fmax(worst, r.worst), lit_max = fmax(lit_max, r.max_radiance);
        worst_all = fmax(worst_all, r.worst_all), sum += r.sum;
        over += r.over, pixels += r.pixels, bad += r.bad;
    }
    printf("# %d configurations x %d pixels: relative |GPU - CPU| radiance mean %.2g, max %.3g under the "
           "tolerance %.0e; %d pixels (%.3f %%) over it, worst %.3g; brightest %.3g\n",
           CONFIGS, SIZE * SIZE, sum / pixels, worst, RADIANCE_TOLERANCE, over, 100.0 * over / pixels, worst_all,
           lit_max);
    CHECK(bad == 0, "%d non-finite pixels", bad);
    CHECK(over <= ROUNDING_PIXELS * pixels, "%d of %d pixels exceed the tolerance", over, pixels);
    CHECK(lit_max > 0.05, "the images are dark: the test compares nothing");
    free(t.texels);
    sbfx_destroy(fx);
    fixture_close(&f);
}

/* Fire lights lit smoke too (issue 27): the frame's fire, gathered into point lights, reaches a lit
 * particle as the phase model's isotropic in-scattering at its centre (src/sim/fire_light.h), per
 * particle like the fill lights, shaded by the brightness map and dampened like the lights
 * (ref/lit_ref.c, sbfx_lit_fire_radiance). A lit puff above a fireball: the light the fire adds
 * (the frame with the fire's emission less the frame with it at 0) against the reference's,
 * pixel by pixel, within the random configurations' tolerance (RADIANCE_TOLERANCE of the pixel's
 * own value plus 1 % of the puff's brightest). */
static const char *const lit_fire_scene =
    "render = { white_luminance = 100.0; };\n"
    "media = { smoke = { albedo = 0.7; density = 0.8; lighting = \"lit\"; steps = [4, 16];\n"
    "  texture = { size = 64; variants = 3; }; detail = { strength = 0.0; }; };\n"
    "  fire = { albedo = 0.0; density = 0.6; temperature = [1500.0, 500.0]; emissivity = 1.0;\n"
    "  detail = { strength = 0.0; }; }; };\n"
    "effects = { puff = { steps = ( { type = \"emitter\"; medium = \"smoke\"; count = 4; },\n"
    "  { type = \"emitter\"; medium = \"fire\"; count = 4; } ); }; };\n";

static float *lit_fire_frame(gl_fixture *f, sbfx *fx, const sbfx_view_particle *p, int count, int *lit_particles)
{
    CHECK(sbfx_render_view_particles(fx, &f->frame, p, count) == SBFX_OK, "%s", sbfx_last_error(fx));
    sbfx_counters c;
    sbfx_stats(fx, &c);
    *lit_particles = c.fire_lit_particles;
    int w, h;
    return fixture_read_target(fx, &w, &h);
}

/* The fire's light on the puff: the module's gathered fire (fx->sim->frame_fire, the frame just
 * rendered) in-scattered at the centre, isotropic. */
static void fire_at_centre(sbfx *fx, const sbfx_view_particle *p, double out[3])
{
    const double c[3] = {p->center[0], p->center[1], p->center[2]};
    sbfx_fire_scatter s;
    sbfx_fire_scatter_at(fx->sim->frame_fire, fx->sim->frame_fire_count, sbfx_get_desc(fx)->exposure, c, 0.0, &s);
    for (int k = 0; k < 3; k++) out[k] = s.rgb[k];
}

CHECK_TEST(fire_lights_lit_smoke_by_the_references_amount)
{
    gl_fixture f;
    open_lit(&f);
    sbfx *fx = lit_module(&f, lit_fire_scene);
    CHECK(sbfx_fire_lit(fx), "a scene of fire and lit smoke: the fire does not light the smoke");
    sbfx_set_lights(fx, (const sbfx_view_light[]){{{-0.3f, -1.0f, -0.2f, 0.0f}, {0.05f, 0.05f, 0.06f}}}, 1,
                    (const float[3]){0.01f, 0.012f, 0.02f});
    cpu_texture t = cpu_smoke(fx);
    const sbfx_view_particle p[] = {
        {.center = {0.0f, 0.6f, -4.5f}, .radius = 1.0f, .detail = {0.4f, 0, 0}, .intensity = 1.0f, .medium = SBFX_SMOKE},
        {.center = {0.0f, -1.2f, -5.0f}, .radius = 0.45f, .detail = {0.2f, 0.5f, 0.1f}, .intensity = 1.0f,
         .medium = SBFX_FIRE},
    };
    int lit_on, lit_off;
    float *on = lit_fire_frame(&f, fx, p, 2, &lit_on);
    double fire_centre[3];
    fire_at_centre(fx, &p[0], fire_centre); /* before the next frame gathers its own */
    sbfx_medium_params *m = &sbfx_media(fx)[SBFX_SMOKE], *fire = &sbfx_media(fx)[SBFX_FIRE];
    float emission = fire->emission_scale;
    fire->emission_scale = 0.0f;
    float *off = lit_fire_frame(&f, fx, p, 2, &lit_off);
    fire->emission_scale = emission;
    CHECK(lit_on == 1 && lit_off == 0, "particles lit by fire: %d, %d without its emission", lit_on, lit_off);
    sbfx_lit_medium lm = {{m->albedo * m->color[0], m->albedo * m->color[1], m->albedo * m->color[2]},
                          m->tau, m->wrap, m->translucency, m->dampening, m->steps_min, m->steps_max};
    double pixel_slope = 2.0 / (SIZE * f.frame.projection[0]), c[3] = {p[0].center[0], p[0].center[1], p[0].center[2]};
    double lod = sbfx_lit_lod(t.tex.size, p[0].radius, -c[2], pixel_slope);
    int variant = sbfx_lit_variant(p[0].detail[0], t.tex.layers / 2), pixels = 0, over = 0;
    double most = 0.0, worst = 0.0, sum_gpu = 0.0, sum_cpu = 0.0, sum_off = 0.0;
    static double want[SIZE * SIZE][3];
    static bool fire_reaches[SIZE * SIZE];
    for (int i = 0; i < SIZE * SIZE; i++) {
        double ray[3], rp_alpha;
        fixture_ray(&f, &f.frame, SIZE, SIZE, i % SIZE, i / SIZE, ray);
        sbfx_ref_particle rp = {{c[0], c[1], c[2]}, p[0].radius, m->tau * p[0].intensity};
        sbfx_ref_particle rf = {{p[1].center[0], p[1].center[1], p[1].center[2]}, p[1].radius, fire->tau};
        sbfx_ref_pixel px = {{ray[0], ray[1], ray[2]}, INFINITY, fixture_near(&f.frame), 0.0};
        rp_alpha = sbfx_ref_opacity(SBFX_OPACITY_SPHERICAL, &rp, &px);
        fire_reaches[i] = sbfx_ref_opacity(SBFX_OPACITY_SPHERICAL, &rf, &px) > 0.0;
        sbfx_lit_fire_radiance(&lm, &t.tex, variant, lod, c, p[0].radius, ray, fire_centre, want[i]);
        for (int k = 0; k < 3; k++) want[i][k] *= rp_alpha, most = fmax(most, want[i][k]);
    }
    for (int i = 0; i < SIZE * SIZE; i++) {
        if (!(1.0 - off[4 * i + 3] > 0.02) || fire_reaches[i]) continue; /* the puff alone */
        for (int k = 0; k < 3; k++) {
            double got = on[4 * i + k] - off[4 * i + k], e = fabs(got - want[i][k]) / (fabs(want[i][k]) + 0.01 * most);
            worst = fmax(worst, e);
            if (e > RADIANCE_TOLERANCE) over++;
            sum_gpu += got, sum_cpu += want[i][k], sum_off += off[4 * i + k];
        }
        pixels++;
    }
    printf("# %d pixels of the lit puff: %.4f without the fire's light, +%.4f with it on the GPU, +%.4f in the "
           "reference (GPU/reference %.4f); worst pixel %.3f, %d channels over %.2f; fire at its centre "
           "%.4f %.4f %.4f\n", pixels, sum_off / pixels, sum_gpu / pixels, sum_cpu / pixels, sum_gpu / sum_cpu, worst,
           over, RADIANCE_TOLERANCE, fire_centre[0], fire_centre[1], fire_centre[2]);
    CHECK(pixels > 200, "%d pixels", pixels);
    CHECK(over <= ROUNDING_PIXELS * 3 * pixels, "%d channels differ from the reference beyond the tolerance", over);
    CHECK(sum_cpu > 0.5 * sum_off, "the fire adds %.4f to %.4f: hardly any light", sum_cpu, sum_off);
    free(on), free(off), free(t.texels);
    sbfx_destroy(fx);
    fixture_close(&f);
}

/* The hard cases, each against the reference: N.V = 0 at the rim (steps nMin), a light exactly
 * behind and exactly in front, zero lights, nMax = nMin, a light inside the particle. */
CHECK_TEST(hard_cases_match_cpu)
{
    gl_fixture f;
    open_lit(&f);
    sbfx *fx = lit_module(&f, lit_scene);
    cpu_texture t = cpu_smoke(fx);
    const sbfx_view_particle p = {.center = {0.0f, 0.0f, -6.0f}, .radius = 2.0f, .detail = {0.5f, 0, 0},
                                  .intensity = 1.0f, .medium = SBFX_SMOKE};
    const sbfx_view_light behind = {{0, 0, 1, 0}, {2, 2, 2}}, front = {{0, 0, -1, 0}, {2, 2, 2}};
    const sbfx_view_light behind_point = {{0, 0, -9, 1}, {20, 20, 20}}, inside = {{0.3f, 0.2f, -6.0f, 1}, {1, 1, 1}};
    const sbfx_view_light at_centre = {{0, 0, -6, 1}, {1, 1, 1}};
    struct { const char *name; lit_config c; } cases[] = {
        {"exactly behind", {p, 0.8, 0.6, 1.5, 0, 0.8, {4, 16}, 1, {behind}, {0.1f, 0.1f, 0.1f}}},
        {"exactly in front", {p, 0.8, 0.6, 1.5, 0, 0.8, {4, 16}, 1, {front}, {0.1f, 0.1f, 0.1f}}},
        {"point exactly behind", {p, 0.8, 0.6, 1.5, 0, 0.8, {4, 16}, 1, {behind_point}, {0, 0, 0}}},
        {"zero lights", {p, 0.8, 0.6, 1.5, 0, 0.8, {4, 16}, 0, {{{0}, {0}}}, {0.3f, 0.2f, 0.1f}}},
        {"nMax = nMin", {p, 0.8, 0.6, 1.5, 0, 0.8, {7, 7}, 2, {behind, front}, {0.1f, 0.1f, 0.1f}}},
        {"no march", {p, 0.8, 0.6, 1.5, 0, 0.8, {0, 0}, 1, {behind}, {0, 0, 0}}},
        {"light inside", {p, 0.8, 0.6, 1.5, 0, 0.8, {4, 16}, 2, {inside, at_centre}, {0, 0, 0}}},
        /* tau = 1e4: exp(-tau 2r sum dt) turns one 8-bit step of height at the puff's thin edge
         * into a large factor, so a few edge pixels differ relatively (not absolutely) */
        {"dense, dampened", {p, 1e4, 1.0, 3.0, 0.5, 1.0, {16, 64}, 4, {behind, front, inside, behind_point}, {0, 0, 0}}},
    };
    for (size_t i = 0; i < ARRAY_SIZE(cases); i++) {
        comparison r = compare(&f, fx, &cases[i].c, &t.tex);
        printf("# %-20s relative error mean %.2g max %.3g, %d pixels over %.0e, brightest %.3g\n", cases[i].name,
               r.sum / r.pixels, r.worst_all, r.over, RADIANCE_TOLERANCE, r.max_radiance);
        CHECK(r.bad == 0, "%s: %d non-finite pixels", cases[i].name, r.bad);
        CHECK(r.over <= 0.01 * r.pixels, "%s: %d pixels exceed the tolerance", cases[i].name, r.over);
    }
    free(t.texels);
    sbfx_destroy(fx);
    fixture_close(&f);
}

/* Radiance (premultiplied / alpha) averaged over a ring d/r in [lo, hi) of a centred particle. */
static double ring_radiance(const float *rgba, int w, int h, double radius_px, double lo, double hi)
{
    double sum = 0.0;
    int n = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double d = hypot(x + 0.5 - w / 2.0, y + 0.5 - h / 2.0) / radius_px;
            const float *g = &rgba[4 * (y * w + x)];
            double alpha = 1.0 - g[3];
            if (d < lo || d >= hi || alpha < 1e-4) continue;
            sum += (g[0] + g[1] + g[2]) / (3.0 * alpha);
            n++;
        }
    return n ? sum / n : 0.0;
}

static float *render_lit(gl_fixture *f, sbfx *fx, const sbfx_view_particle *p, const sbfx_view_light *l,
                         double translucency, int *w, int *h)
{
    sbfx_media(fx)[SBFX_SMOKE].translucency = (float)translucency;
    sbfx_set_lights(fx, l, 1, (const float[3]){0, 0, 0});
    CHECK(sbfx_render_view_particles(fx, &f->frame, p, 1) == SBFX_OK, "%s", sbfx_last_error(fx));
    return fixture_read_target(fx, w, h);
}

/* The sign convention, on the GPU: a light behind the smoke lights its rim more than its
 * middle, and the back-light strength matters; a light in front gets no back-light at all. */
CHECK_TEST(backlight_brightens_the_rim_and_never_a_front_light)
{
    gl_fixture f;
    open_lit(&f);
    sbfx *fx = lit_module(&f, lit_scene);
    const sbfx_view_particle p = {.center = {0.0f, 0.0f, -6.0f}, .radius = 2.0f, .detail = {0.1f, 0, 0},
                                  .intensity = 1.0f, .medium = SBFX_SMOKE};
    const sbfx_view_light behind = {{0, 0, 1, 0}, {1, 1, 1}}, front = {{0.2f, -0.3f, -1, 0}, {1, 1, 1}};
    double radius_px = 2.0 / (6.0 * tan(0.5)) * SIZE / 2.0;
    int w, h;
    float *back0 = render_lit(&f, fx, &p, &behind, 0.0, &w, &h), *back2 = render_lit(&f, fx, &p, &behind, 2.0, &w, &h);
    float *front0 = render_lit(&f, fx, &p, &front, 0.0, &w, &h), *front2 = render_lit(&f, fx, &p, &front, 2.0, &w, &h);
    double rim = ring_radiance(back2, w, h, radius_px, 0.7, 0.95), middle = ring_radiance(back2, w, h, radius_px, 0.0, 0.3);
    double rim0 = ring_radiance(back0, w, h, radius_px, 0.7, 0.95);
    printf("# backlit: rim %.4f middle %.4f (rim without back-light %.4f)\n", rim, middle, rim0);
    CHECK(rim > 2.0 * middle, "backlit rim %.4f is not brighter than the middle %.4f", rim, middle);
    CHECK(rim > 2.0 * rim0, "back-light adds too little at the rim: %.4f vs %.4f", rim, rim0);
    CHECK(memcmp(front0, front2, sizeof(float) * 4 * w * h) == 0, "a light in front got back-light");
    double lit_front = ring_radiance(front2, w, h, radius_px, 0.0, 0.3);
    CHECK(lit_front > middle, "front-lit middle %.4f vs backlit middle %.4f", lit_front, middle);
    free(back0), free(back2), free(front0), free(front2);
    sbfx_destroy(fx);
    fixture_close(&f);
}

/* Only the lighting variants a scene uses: the smoke texture array exists only for lit media,
 * the phase table (asked for: the analytic phase is the default) only for phase media, one array
 * per lit medium. */
#define PLAN_EFFECT(medium) "{ type = \"emitter\"; medium = \"" medium "\"; count = 2; }"
#define NO_DETAIL "detail = { strength = 0.0; };"

CHECK_TEST(plan_makes_smoke_textures_only_for_lit_media)
{
    gl_fixture f;
    fixture_open(&f, 16, 16);
    const size_t smoke64 = sbfx_smoke_texture_bytes(64, 2), phase = SBFX_PHASE_SIZE * SBFX_MEDIUM_COUNT * 4;
    struct {
        const char *name, *media, *steps;
        int textures;
        size_t bytes;
        bool lit[SBFX_MEDIUM_COUNT];
    } plans[] = {
        {"phase smoke", "smoke = { " NO_DETAIL " };", PLAN_EFFECT("smoke"), 1, phase, {false}},
        {"lit smoke", "smoke = { lighting = \"lit\"; texture = { size = 64; variants = 2; }; " NO_DETAIL " };",
         PLAN_EFFECT("smoke"), 1, smoke64, {false, true, false}},
        {"lit smoke, phase dust",
         "smoke = { lighting = \"lit\"; texture = { size = 64; variants = 2; }; " NO_DETAIL " };"
         "dust = { " NO_DETAIL " };",
         PLAN_EFFECT("smoke") "," PLAN_EFFECT("dust"), 2, smoke64 + phase, {false, true, false}},
        {"lit smoke and dust",
         "smoke = { lighting = \"lit\"; texture = { size = 64; variants = 2; }; " NO_DETAIL " };"
         "dust = { lighting = \"lit\"; texture = { size = 64; variants = 2; }; " NO_DETAIL " };",
         PLAN_EFFECT("smoke") "," PLAN_EFFECT("dust"), 2, 2 * smoke64, {true, true, false}},
        {"lit smoke defined, unused", "smoke = { lighting = \"lit\"; " NO_DETAIL " }; dust = { " NO_DETAIL " };",
         PLAN_EFFECT("dust"), 1, phase, {false}},
    };
    for (size_t i = 0; i < ARRAY_SIZE(plans); i++) {
        char text[1024];
        snprintf(text, sizeof(text), "media = { %s };\neffects = { e = { steps = ( %s ); }; };\n", plans[i].media,
                 plans[i].steps);
        sbfx_scene *scene = parse(text);
        sbfx *fx = fixture_module(&f, (sbfx_desc){.scene = scene, .max_particles = 16, .table_phase = true});
        sbfx_scene_free(scene);
        sbfx_counters c;
        sbfx_stats(fx, &c);
        printf("# %-26s programs %d textures %d gpu_bytes %zu\n", plans[i].name, c.programs, c.textures, c.gpu_bytes);
        CHECK(c.textures == plans[i].textures, "%s: %d textures, want %d", plans[i].name, c.textures, plans[i].textures);
        size_t bytes = plans[i].bytes + 16 * 32 + sizeof(((sbfx_tiles *)0)->rects); /* + instances, tiles */
        CHECK(c.gpu_bytes == bytes, "%s: %zu GPU bytes, want %zu", plans[i].name, c.gpu_bytes, bytes);
        for (int m = 0; m < SBFX_MEDIUM_COUNT; m++) {
            bool has_texture = fx->gl->smoke_texture[m] != 0;
            bool lit_program = fx->gl->particle[m].id && fx->gl->particle[m].smoke >= 0;
            CHECK(has_texture == plans[i].lit[m] && lit_program == plans[i].lit[m],
                  "%s: medium %d texture %d lit program %d", plans[i].name, m, has_texture, lit_program);
        }
        sbfx_destroy(fx);
    }
    fixture_close(&f);
}

/* The example scene: lit smoke and phase dust side by side, two programs, the orbiting light
 * where the simulation time puts it, nothing allocated per frame. */
CHECK_TEST(example_scene_mixes_models_and_orbits_its_light)
{
    gl_fixture f;
    fixture_open(&f, 96, 64);
    fixture_projection(&f, 0.9f, 0.1f, 100.0f);
    fixture_depth(&f, depth_far_everywhere, NULL);
    char err[512];
    sbfx_scene *scene = NULL;
    CHECK(sbfx_scene_load("scenes/lit-smoke.cfg", &scene, err, sizeof(err)) == SBFX_OK, "%s", err);
    if (!scene) exit(1);
    sbfx *fx = fixture_module(&f, (sbfx_desc){.scene = scene});
    sbfx_scene_free(scene);
    sbfx_counters c;
    sbfx_stats(fx, &c);
    int corners = sbfx_float32_renderable(); /* the low-res corners' program and pass (passes.c) */
    /* the detail volume and the lit smoke's array (the phase dust is analytic: no table) */
    CHECK(c.programs == 4 + corners && c.textures == 2, "programs %d textures %d", c.programs, c.textures);
    /* orbit: centre (0, 2, 0), radius 3.6, period 4 s, counter-clockwise seen from above:
     * +x at t = 0, -z a quarter turn later, -x at half a turn */
    const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    for (int q = 0; q < 3; q++) {
        sbfx_view_light lights[8];
        double a = 2.0 * M_PI * sbfx_time(fx) / 4.0;
        const double want[3] = {3.6 * cos(a), 2.0, -3.6 * sin(a)};
        CHECK(sbfx_frame_lights(fx, identity, lights, 8) >= 2);
        CHECK(lights[0].vector[3] == 1.0f);
        for (int k = 0; k < 3; k++) CHECK_NEAR(lights[0].vector[k], want[k], 1e-4);
        if (q == 1) CHECK(lights[0].vector[2] < -3.5f, "not a quarter turn toward -z at t = %g", sbfx_time(fx));
        for (int s = 0; s < 7; s++) sbfx_update(fx, 1.0 / 7); /* about 1 s in uneven frames */
    }
    float view[16];
    sbfx_look_at(view, (const float[3]){0, 2, 9}, (const float[3]){0, 1.5f, 0}, (const float[3]){0, 1, 0});
    memcpy(f.frame.view, view, sizeof(view));
    uint64_t before = 0;
    for (int i = 0; i < 8; i++) {
        sbfx_update(fx, 1.0 / 12);
        CHECK(sbfx_render(fx, &f.frame) == SBFX_OK, "%s", sbfx_last_error(fx));
        sbfx_stats(fx, &c);
        if (i == 0) before = c.heap_allocs_after_load;
    }
    CHECK(c.heap_allocs_after_load == before && before == 0, "%llu allocations after load",
          (unsigned long long)c.heap_allocs_after_load);
    CHECK(c.passes == 3 + corners && c.draw_calls >= 4, "passes %d draws %d", c.passes, c.draw_calls);
    int w, h;
    float *rgba = fixture_read_target(fx, &w, &h);
    CHECK(all_finite(rgba, 4u * w * h), "non-finite pixel");
    free(rgba);
    sbfx_destroy(fx);
    fixture_close(&f);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
