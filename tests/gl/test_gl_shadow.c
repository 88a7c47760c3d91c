/* The host's transmittance shadow map (sbfx_render_shadow_map, RTR 13.8.1): a known smoke puff
 * against the CPU reference (ref/shadow_ref.h), every channel; what a host makes of it in front
 * of, inside and behind the smoke; the map only where asked for (counters), and bad input
 * refused with nothing changed. Its GL state: test_gl_state's shadow_map_leaves_state. */
#include "gl_fixture.h"
#include "module.h" /* fx->render->shadow */
#include "shadow_ref.h"

#define SIZE 128

static sbfx *module_with_map(gl_fixture *f, int size)
{
    return fixture_module(f, (sbfx_desc){.ignore_timeline = true, .max_particles = 256, .shadow_map_size = size});
}

/* A world point that the map's texel (i, j) covers: the map's rows 0 and 1 are the light view's
 * (orthogonal) rows scaled, so a point a e0 + b e1 in their plane lands where it is asked. */
static void texel_point(const float vp[16], int size, int i, int j, double p[3])
{
    double ndc[2] = {2.0 * (i + 0.5) / size - 1.0, 2.0 * (j + 0.5) / size - 1.0};
    for (int k = 0; k < 3; k++) p[k] = 0.0;
    for (int row = 0; row < 2; row++) {
        double e[3] = {vp[row], vp[4 + row], vp[8 + row]};
        double s2 = e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
        double a = (ndc[row] - vp[12 + row]) / s2; /* (ndc - t) / s along the unit row, over s again */
        for (int k = 0; k < 3; k++) p[k] += a * e[k];
    }
}

/* The map's depth at a world point, as the host computes it: (view_projection x).z * 0.5 + 0.5. */
static void depth_row_of(const float vp[16], double row[4])
{
    for (int k = 0; k < 4; k++) row[k] = 0.5 * vp[k * 4 + 2];
    row[3] += 0.5;
}

/* Six smoke particles overlapping around (0, 1.5, 0), different sizes and intensities. */
static int puff(sbfx *fx, sbfx_view_particle out[], sbfx_ref_particle ref[])
{
    static const float spec[][5] = {
        {0.0f, 1.5f, 0.0f, 1.0f, 1.0f},  {0.6f, 1.8f, 0.2f, 0.7f, 0.8f},  {-0.5f, 1.2f, -0.3f, 0.8f, 0.6f},
        {0.2f, 2.2f, -0.4f, 0.5f, 1.0f}, {-0.3f, 1.9f, 0.5f, 0.6f, 0.4f}, {0.9f, 1.0f, -0.6f, 0.4f, 0.9f},
    };
    float tau = sbfx_media(fx)[SBFX_SMOKE].tau;
    int n = (int)ARRAY_SIZE(spec);
    for (int i = 0; i < n; i++) {
        out[i] = (sbfx_view_particle){.center = {spec[i][0], spec[i][1], spec[i][2]}, .radius = spec[i][3],
                                      .intensity = spec[i][4], .medium = SBFX_SMOKE};
        ref[i] = (sbfx_ref_particle){{spec[i][0], spec[i][1], spec[i][2]}, spec[i][3], (double)tau * spec[i][4]};
    }
    return n;
}

/* The puff's map (SIZE^2) for light travelling along a direction, read back. */
typedef struct puff_case {
    gl_fixture f;
    sbfx *fx;
    sbfx_ref_particle ref[8];
    int n;
    sbfx_shadow_map map;
    float texels[SIZE * SIZE * 4];
} puff_case;

static void puff_open(puff_case *c, const float direction[3])
{
    fixture_open(&c->f, 32, 32);
    c->fx = module_with_map(&c->f, SIZE);
    sbfx_view_particle particles[8];
    c->n = puff(c->fx, particles, c->ref);
    CHECK(sbfx_render_shadow_particles(c->fx, direction, particles, c->n, &c->map) == SBFX_OK, "%s",
          sbfx_last_error(c->fx));
    CHECK(c->map.particles == c->n && c->map.size == SIZE && c->map.texture == c->fx->render->shadow.map.texture[0]);
    CHECK(sbfx_read_shadow_map(c->fx, c->texels, ARRAY_SIZE(c->texels)) == SBFX_OK, "%s", sbfx_last_error(c->fx));
}

static void puff_close(puff_case *c)
{
    sbfx_destroy(c->fx);
    fixture_close(&c->f);
}

CHECK_TEST(smoke_puff_matches_the_reference)
{
    static puff_case c;
    puff_open(&c, (const float[3]){0.4f, -1.0f, 0.3f});
    sbfx *fx = c.fx;
    const sbfx_ref_particle *ref = c.ref;
    const float *texels = c.texels;
    const sbfx_shadow_map map = c.map;
    int n = c.n;
    /* Each blend rounds the product to the map's format, in a rounding mode GL leaves open (llvmpipe
     * truncates): up to one unit in the last place per particle over the texel, at most n, for r,
     * g and b. A unit of a half float is 2^-11 for values in [0.5, 1) and less below; of RGBA8
     * 1/255. a, a MIN, rounds once: half a unit (one where the rounding mode is open) of the
     * front's depth in [0, 1]. The shader's exp, log and sqrt in highp add ~1e-6. */
    bool rgba8 = fx->render->shadow.map.bytes == (size_t)SIZE * SIZE * 4;
    double per_particle = rgba8 ? 1.0 / 255.0 : 1.0 / 2048.0, tol = n * per_particle + 1e-5;
    double tol_front = per_particle + 1e-5;
    double len = sqrt(0.16 + 1.0 + 0.09), unit[3] = {0.4 / len, -1.0 / len, 0.3 / len}, row[4];
    depth_row_of(map.view_projection, row);
    double worst[4] = {0.0, 0.0, 0.0, 0.0}, darkest = 1.0, border_min = 1.0;
    for (int j = 0; j < SIZE; j++)
        for (int i = 0; i < SIZE; i++) {
            double p[3], want[4];
            texel_point(map.view_projection, SIZE, i, j, p);
            sbfx_ref_shadow_texel(ref, (size_t)n, unit, p, row, want);
            CHECK_NEAR(want[0], sbfx_ref_shadow_transmittance(ref, (size_t)n, unit, p), 1e-15);
            const float *got = &texels[(j * SIZE + i) * 4];
            for (int k = 0; k < 4; k++) {
                CHECK_FINITE(got[k]);
                worst[k] = fmax(worst[k], fabs(got[k] - want[k]));
            }
            darkest = fmin(darkest, got[0]);
            if (i < 2 || j < 2 || i >= SIZE - 2 || j >= SIZE - 2) border_min = fmin(border_min, got[0]);
        }
    printf("# %s map: max |map - reference| %.2e %.2e %.2e (r g b, allowed %.2e), front %.2e (allowed %.2e); "
           "darkest %.4f\n", rgba8 ? "RGBA8" : "RGBA16F", worst[0], worst[1], worst[2], tol, worst[3], tol_front,
           darkest);
    CHECK(worst[0] <= tol && worst[1] <= tol && worst[2] <= tol, "max error %g %g %g > %g", worst[0], worst[1],
          worst[2], tol);
    CHECK(worst[3] <= tol_front, "the front's depth is %g off (> %g)", worst[3], tol_front);
    CHECK(darkest < 0.7, "the puff casts no real shadow: darkest %g", darkest);
    CHECK(border_min == 1.0, "the border is shaded (%g): CLAMP_TO_EDGE would smear the shadow", border_min);
    puff_close(&c);
}

/* The RGBA8 map where half floats are not renderable: the tested fallback. */
CHECK_TEST(rgba8_fallback_matches_the_reference)
{
    static const char hidden[] = "GL_EXT_color_buffer_half_float GL_EXT_color_buffer_float";
    fixture_hide_extensions(hidden);
    gl_fixture f;
    fixture_open(&f, 32, 32);
    fixture_require_hidden(hidden);
    sbfx *fx = module_with_map(&f, 64);
    CHECK(fx->render->shadow.map.bytes == 64 * 64 * 4, "%zu bytes: not RGBA8", fx->render->shadow.map.bytes);
    sbfx_view_particle particles[8];
    sbfx_ref_particle ref[8];
    int n = puff(fx, particles, ref);
    sbfx_shadow_map map;
    const float direction[3] = {0.0f, -1.0f, 0.0f};
    CHECK(sbfx_render_shadow_particles(fx, direction, particles, n, &map) == SBFX_OK, "%s", sbfx_last_error(fx));
    static float texels[64 * 64 * 4];
    CHECK(sbfx_read_shadow_map(fx, texels, ARRAY_SIZE(texels)) == SBFX_OK);
    double unit[3] = {0, -1, 0}, worst = 0.0, front = 0.0, tol = n / 255.0 + 1e-5, row[4]; /* as above */
    depth_row_of(map.view_projection, row);
    for (int j = 0; j < 64; j++)
        for (int i = 0; i < 64; i++) {
            double p[3], want[4];
            texel_point(map.view_projection, 64, i, j, p);
            sbfx_ref_shadow_texel(ref, (size_t)n, unit, p, row, want);
            for (int k = 0; k < 3; k++) worst = fmax(worst, fabs(texels[(j * 64 + i) * 4 + k] - want[k]));
            front = fmax(front, fabs(texels[(j * 64 + i) * 4 + 3] - want[3]));
        }
    printf("# RGBA8 map: max |map - reference| %.2e (allowed %.2e), front %.2e (allowed %.2e)\n", worst, tol, front,
           1.0 / 255.0 + 1e-5);
    CHECK(worst <= tol, "max error %g > %g", worst, tol);
    CHECK(front <= 1.0 / 255.0 + 1e-5, "the front's depth is %g off", front);
    sbfx_destroy(fx);
    fixture_close(&f);
}

/* What a host makes of the map (docs/embedding.md's smoke_visibility, ref/shadow_ref.h's
 * sbfx_ref_shadow_visibility) for receivers on the light's rays through the puff: above where
 * the smoke begins, exactly 1 (a surface over the cloud is not shaded: the map used to shade it
 * like one under it); under all of it, the map's transmittance; inside, the optical depth spread
 * evenly over its mean -+ sqrt(3) standard deviations (from no earlier than the front), against
 * the exact transmittance to the point (each chord as far as the point): within 0.1 (measured
 * 0.058), the spread's approximation. */
CHECK_TEST(the_map_knows_where_the_smoke_is_along_the_light)
{
    static puff_case c;
    puff_open(&c, (const float[3]){0.0f, -1.0f, 0.0f});
    const sbfx_ref_particle *ref = c.ref;
    const float *texels = c.texels;
    const sbfx_shadow_map map = c.map;
    int n = c.n;
    double unit[3] = {0, -1, 0}, row[4], above = 0.0, below = 0.0, inside = 0.0, shaded_above = 1.0;
    depth_row_of(map.view_projection, row);
    int rays = 0;
    for (int j = 0; j < SIZE; j++)
        for (int i = 0; i < SIZE; i++) {
            const float *t = &texels[(j * SIZE + i) * 4];
            if (!(t[0] < 0.95f)) continue; /* rays through the puff */
            double texel[4] = {t[0], t[1], t[2], t[3]}, p[3];
            texel_point(map.view_projection, SIZE, i, j, p);
            rays++;
            for (double y = 3.5; y >= -0.5; y -= 0.05) { /* from above the puff (top 2.7) to below it (0.2) */
                double q[3] = {p[0], y, p[2]}, depth = row[0] * q[0] + row[1] * q[1] + row[2] * q[2] + row[3];
                double host = sbfx_ref_shadow_visibility(texel, depth);
                double exact = sbfx_ref_shadow_transmittance_to(ref, (size_t)n, unit, q);
                if (y > 2.75) above = fmax(above, fabs(host - 1.0)), shaded_above = fmin(shaded_above, host);
                else if (y < 0.15) below = fmax(below, fabs(host - t[0]));
                else inside = fmax(inside, fabs(host - exact));
            }
        }
    printf("# %d rays through the puff: above it visibility 1 within %.1e, below it the map's transmittance "
           "within %.1e, inside the exact transmittance within %.3f\n", rays, above, below, inside);
    CHECK(rays > 200, "%d rays", rays);
    CHECK(above == 0.0, "a surface above the smoke is shaded (%g)", shaded_above);
    CHECK(below <= 1e-12, "under the smoke: %g from the map's transmittance", below);
    CHECK(inside <= 0.1, "inside the smoke: %g from the exact transmittance", inside);
    puff_close(&c);
}

/* Nothing of it without the desc or scene asking; one texture, framebuffer and program with it;
 * one pass with live particles, none idle; post.cfg (no host_shadows) has none, a scene with
 * host_shadows a 256 map. */
CHECK_TEST(the_map_exists_only_when_asked_for)
{
    gl_fixture f;
    fixture_open(&f, 32, 32);
    sbfx *plain = module_with_map(&f, 0), *mapped = module_with_map(&f, 64);
    sbfx_counters a, b;
    sbfx_stats(plain, &a);
    sbfx_stats(mapped, &b);
    CHECK(b.textures == a.textures + 1 && b.framebuffers == a.framebuffers + 1 && b.programs == a.programs + 1,
          "textures %d -> %d, framebuffers %d -> %d, programs %d -> %d", a.textures, b.textures, a.framebuffers,
          b.framebuffers, a.programs, b.programs);
    CHECK(plain->render->shadow.size == 0 && !plain->render->shadow.map.framebuffer && !plain->render->shadow.program && !plain->render->shadow.buffer);
    sbfx_shadow_map map;
    const float sun[3] = {0.3f, -1.0f, 0.2f};
    CHECK(sbfx_render_shadow_map(plain, sun, &map) == SBFX_ERR_INVALID_ARGUMENT);
    CHECK(strstr(sbfx_last_error(plain), "shadow_map_size") != NULL, "%s", sbfx_last_error(plain));
    CHECK(sbfx_render_shadow_map(mapped, sun, &map) == SBFX_OK, "%s", sbfx_last_error(mapped));
    sbfx_stats(mapped, &b);
    CHECK(b.shadow_passes == 0 && map.particles == 0, "idle: %d passes, %d particles", b.shadow_passes, map.particles);
    CHECK(sbfx_trigger(mapped, "explosion", (const float[3]){0, 0, 0}) == SBFX_OK);
    CHECK(sbfx_update(mapped, 0.5) == SBFX_OK);
    CHECK(sbfx_render_shadow_map(mapped, sun, &map) == SBFX_OK, "%s", sbfx_last_error(mapped));
    sbfx_stats(mapped, &b);
    CHECK(b.shadow_passes == 1 && map.particles > 0, "live: %d passes, %d particles", b.shadow_passes, map.particles);
    uint64_t allocs = b.heap_allocs_after_load;
    for (int i = 0; i < 5; i++) {
        CHECK(sbfx_update(mapped, 1.0 / 60) == SBFX_OK);
        CHECK(sbfx_render_shadow_map(mapped, sun, &map) == SBFX_OK);
    }
    sbfx_stats(mapped, &b);
    CHECK(b.heap_allocs_after_load == allocs, "%llu heap allocations per map", (unsigned long long)(b.heap_allocs_after_load - allocs));
    sbfx_destroy(plain);
    sbfx_destroy(mapped);

    sbfx_scene *scene = fixture_load_scene("post");
    sbfx *fx = fixture_module(&f, (sbfx_desc){.scene = scene});
    CHECK(fx->render->shadow.size == 0 && !fx->render->shadow.map.framebuffer, "post.cfg has a %d map", fx->render->shadow.size);
    sbfx_destroy(fx);
    sbfx_scene_free(scene);
    char err[512];
    CHECK(sbfx_scene_parse("render = { host_shadows = true; }; media = { smoke = {}; };\n"
                           "effects = { puff = { steps = ( { type = \"emitter\"; medium = \"smoke\"; count = 4; } ); }; };",
                           "inline", &scene, err, sizeof(err)) == SBFX_OK, "%s", err);
    if (scene) {
        sbfx_scene_host host;
        sbfx_scene_host_get(scene, &host);
        CHECK(host.host_shadows && !host.host_lights && !host.has_sky && host.has_sun);
        fx = fixture_module(&f, (sbfx_desc){.scene = scene});
        CHECK(fx->render->shadow.size == 256, "host_shadows made a %d map", fx->render->shadow.size);
        sbfx_destroy(fx);
        sbfx_scene_free(scene);
    }
    fixture_close(&f);
}

static char last_error[512];

static void keep_error(sbfx_log_level level, const char *message, void *user)
{
    (void)user;
    if (level == SBFX_LOG_ERROR) snprintf(last_error, sizeof(last_error), "%s", message);
}

/* A zero-length or non-finite direction: an error naming it, *out and the map untouched, no GL
 * call; sizes that are not renderable refused at create (and in the scene file). */
CHECK_TEST(bad_input_is_refused_and_changes_nothing)
{
    gl_fixture f;
    fixture_open(&f, 32, 32);
    sbfx *fx = module_with_map(&f, 64);
    CHECK(sbfx_trigger(fx, "explosion", (const float[3]){0, 0, 0}) == SBFX_OK);
    CHECK(sbfx_update(fx, 0.5) == SBFX_OK);
    sbfx_shadow_map map;
    CHECK(sbfx_render_shadow_map(fx, (const float[3]){0.3f, -1.0f, 0.2f}, &map) == SBFX_OK);
    static float before[64 * 64 * 4], after[64 * 64 * 4];
    CHECK(sbfx_read_shadow_map(fx, before, ARRAY_SIZE(before)) == SBFX_OK);
    sbfx_counters c0, c1;
    sbfx_stats(fx, &c0);
    const float bad[][3] = {{0, 0, 0}, {NAN, -1, 0}, {0, INFINITY, 0}, {1e-30f, 0, 0}};
    for (size_t i = 0; i < ARRAY_SIZE(bad); i++) {
        sbfx_shadow_map out, sentinel;
        memset(&out, 0xa5, sizeof(out));
        memcpy(&sentinel, &out, sizeof(out));
        CHECK(sbfx_render_shadow_map(fx, bad[i], &out) == SBFX_ERR_INVALID_ARGUMENT, "direction %zu accepted", i);
        CHECK(memcmp(&out, &sentinel, sizeof(out)) == 0, "direction %zu wrote *out", i);
        const char *e = sbfx_last_error(fx);
        CHECK(strstr(e, i == 0 || i == 3 ? "zero length" : "not finite") != NULL, "%s", e);
    }
    CHECK(sbfx_render_shadow_map(fx, (const float[3]){0, -1, 0}, NULL) == SBFX_ERR_INVALID_ARGUMENT);
    CHECK(sbfx_render_shadow_map(NULL, (const float[3]){0, -1, 0}, &map) == SBFX_ERR_INVALID_ARGUMENT);
    sbfx_stats(fx, &c1);
    CHECK(c1.shadow_passes == c0.shadow_passes && c1.textures == c0.textures);
    CHECK(sbfx_read_shadow_map(fx, after, ARRAY_SIZE(after)) == SBFX_OK);
    CHECK(memcmp(before, after, sizeof(before)) == 0, "a refused call changed the map");
    sbfx_destroy(fx);

    GLint max_size = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    const int sizes[] = {-1, 1, 15, max_size + 1, 1 << 30};
    for (size_t i = 0; i < ARRAY_SIZE(sizes); i++) {
        sbfx *none = NULL;
        last_error[0] = '\0';
        sbfx_desc d = {.shadow_map_size = sizes[i], .log = keep_error};
        sbfx_result r = sbfx_create(&d, &none);
        CHECK(r == SBFX_ERR_INVALID_ARGUMENT && none == NULL, "size %d: %s", sizes[i], sbfx_result_string(r));
        CHECK(strstr(last_error, "shadow_map_size") != NULL, "size %d: \"%s\"", sizes[i], last_error);
    }
    sbfx_scene *scene = NULL;
    char err[512] = "";
    CHECK(sbfx_scene_parse("render = { shadow_map_size = 8; };", "inline", &scene, err, sizeof(err)) != SBFX_OK);
    CHECK(strstr(err, "shadow_map_size") != NULL, "%s", err);
    CHECK(sbfx_scene_parse("render = { host_shadows = 1; };", "inline", &scene, err, sizeof(err)) != SBFX_OK);
    CHECK(strstr(err, "host_shadows") != NULL && strstr(err, "true or false") != NULL, "%s", err);
    CHECK(sbfx_scene_parse("sky = [0.1, 0.2];", "inline", &scene, err, sizeof(err)) != SBFX_OK);
    fixture_close(&f);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
