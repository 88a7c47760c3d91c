/* The module as a host uses it: fallbacks, errors, idle frames, allocation counts, tables. */
#include "gl_fixture.h"
#include "reference.h"
#include "host/test_scene.h"
#include "module.h"

/* ---- process-wide heap-allocation counter: under ASan, which owns malloc, through its hooks
 * (called for every allocation: malloc, calloc, realloc, the aligned ones, new); otherwise malloc,
 * calloc and realloc taken in front of glibc's ---- */
static volatile int counting;
static volatile long counted;
#if defined(__SANITIZE_ADDRESS__)
/* the sanitizer's allocator interface (sanitizer/allocator_interface.h, which GCC does not install) */
int __sanitizer_install_malloc_and_free_hooks(void (*malloc_hook)(const volatile void *, size_t),
                                              void (*free_hook)(const volatile void *));
static void count_allocation(const volatile void *p, size_t n)
{
    (void)p, (void)n;
    if (counting) counted++;
}
static void ignore_free(const volatile void *p) { (void)p; }
__attribute__((constructor)) static void install_allocation_count(void)
{
    __sanitizer_install_malloc_and_free_hooks(count_allocation, ignore_free);
}
#else
extern void *__libc_malloc(size_t);
extern void *__libc_calloc(size_t, size_t);
extern void *__libc_realloc(void *, size_t);
void *malloc(size_t n)
{
    if (counting) counted++;
    return __libc_malloc(n);
}
void *calloc(size_t a, size_t b)
{
    if (counting) counted++;
    return __libc_calloc(a, b);
}
void *realloc(void *p, size_t n)
{
    if (counting) counted++;
    return __libc_realloc(p, n);
}
#endif

CHECK_TEST(no_context_is_a_clear_error)
{
    sbfx *fx = (sbfx *)1;
    sbfx_result r = sbfx_create(NULL, &fx);
    CHECK(r == SBFX_ERR_NO_GLES3, "got %d (%s)", r, sbfx_result_string(r));
    CHECK(fx == NULL);
}

static char captured[512];
static void capture_log(sbfx_log_level level, const char *message, void *user)
{
    (void)level, (void)user;
    snprintf(captured, sizeof(captured), "%s", message);
}

/* The CIE tables are compiled in: a desc's cmf_path (kept for the struct's layout) is not read. */
CHECK_TEST(fire_needs_no_colour_matching_file)
{
    gl_fixture f;
    fixture_open(&f, 8, 8);
    sbfx *fx = NULL;
    captured[0] = '\0';
    sbfx_desc desc = {.cmf_path = "/nonexistent/CIE1931-2deg-XYZ.cmf", .log = capture_log};
    sbfx_result r = sbfx_create(&desc, &fx);
    CHECK(r == SBFX_OK, "got %d: %s", r, captured);
    CHECK(strstr(captured, "CIE1931") == NULL, "message: %s", captured);
    if (fx) sbfx_destroy(fx);
    fixture_close(&f);
}

static bool logged_mediump;
static void note_mediump(sbfx_log_level level, const char *message, void *user)
{
    (void)level, (void)user;
    logged_mediump = logged_mediump || strstr(message, "mediump as highp") != NULL;
}

/* On Mesa's software rasterisers the shaders' mediump is compiled as highp (half precision is
 * emulated there: the composite ran three times slower with it), and the log says so once; a GPU
 * gets the shaders as written (src/gl/context.c). */
CHECK_TEST(software_rasteriser_compiles_mediump_as_highp)
{
    gl_fixture f;
    fixture_open(&f, 8, 8);
    const char *renderer = (const char *)glGetString(GL_RENDERER);
    bool software = renderer && (strstr(renderer, "llvmpipe") || strstr(renderer, "softpipe"));
    logged_mediump = false;
    sbfx *fx = NULL;
    CHECK(sbfx_create(&(sbfx_desc){.log = note_mediump}, &fx) == SBFX_OK);
    if (fx) {
        CHECK(fx->gl->context.mediump_as_highp == software, "renderer %s: mediump_as_highp %d", renderer, fx->gl->context.mediump_as_highp);
        CHECK(logged_mediump == software, "renderer %s: logged %d", renderer, logged_mediump);
        sbfx_destroy(fx);
    }
    fixture_close(&f);
}

CHECK_TEST(bad_desc_is_rejected)
{
    gl_fixture f;
    fixture_open(&f, 8, 8);
    sbfx *fx = NULL;
    CHECK(sbfx_create(&(sbfx_desc){.target_divisor = 3}, &fx) == SBFX_ERR_INVALID_ARGUMENT);
    CHECK(sbfx_create(&(sbfx_desc){.detail_size = 63}, &fx) == SBFX_ERR_INVALID_ARGUMENT);
    CHECK(sbfx_create(&(sbfx_desc){.max_particles = -5}, &fx) == SBFX_ERR_INVALID_ARGUMENT);
    CHECK(fx == NULL);
    fixture_close(&f);
}

/* Without any live particle, sbfx_render issues no pass and leaves the host framebuffer alone. */
CHECK_TEST(idle_frame_runs_no_pass)
{
    gl_fixture f;
    fixture_open_far(&f, 64, 48);
    sbfx *fx = fixture_module(&f, (sbfx_desc){.ignore_timeline = true});
    glBindFramebuffer(GL_FRAMEBUFFER, f.out_fbo);
    glClearColor(0.25f, 0.5f, 0.75f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    uint8_t cleared[4];
    glReadPixels(10, 10, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, cleared);
    CHECK(fixture_unorm8_is(cleared[0], 0.25f) && fixture_unorm8_is(cleared[1], 0.5f) &&
              fixture_unorm8_is(cleared[2], 0.75f),
          "cleared to %d %d %d", cleared[0], cleared[1], cleared[2]);
    for (int i = 0; i < 10; i++) {
        CHECK(sbfx_update(fx, 1.0 / 30) == SBFX_OK);
        CHECK(sbfx_render(fx, &f.frame) == SBFX_OK);
    }
    sbfx_counters c;
    sbfx_stats(fx, &c);
    CHECK(c.passes == 0 && c.draw_calls == 0 && c.particles_simulated == 0,
          "idle: %d passes, %d draws, %d simulated", c.passes, c.draw_calls, c.particles_simulated);
    uint8_t px[4];
    glBindFramebuffer(GL_FRAMEBUFFER, f.out_fbo);
    glReadPixels(10, 10, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
    CHECK(memcmp(px, cleared, 4) == 0, "host pixel changed from %d %d %d to %d %d %d", cleared[0], cleared[1],
          cleared[2], px[0], px[1], px[2]);
    sbfx_destroy(fx);
    fixture_close(&f);
}

typedef struct run_result {
    long mallocs;
    uint64_t module_allocs;
    int max_passes, max_draws, frames_with_particles;
    bool finite;
} run_result;

/* The built-in explosion over the test scene for `frames` frames at 30 fps. */
static run_result run_explosion(gl_fixture *f, sbfx *fx, struct test_scene *scene, int frames, int warmup)
{
    run_result out = {.finite = true};
    const float origin[3] = {0, 0, 0};
    CHECK(sbfx_trigger(fx, "explosion", origin) == SBFX_OK);
    float *target = malloc(sizeof(float) * 4 * f->width * f->height);
    for (int i = 0; i < frames; i++) {
        test_scene_orbit_camera(i / 30.0, (float)f->width / f->height, f->frame.view, f->frame.projection);
        test_scene_draw(scene, f->frame.view, f->frame.projection);
        f->frame.scene_depth_texture = scene->depth_texture;
        f->frame.out_framebuffer = scene->framebuffer;
        counting = i >= warmup;
        CHECK(sbfx_update(fx, 1.0 / 30) == SBFX_OK);
        counting = 0;
        out.mallocs = counted;
        CHECK(sbfx_render(fx, &f->frame) == SBFX_OK, "%s", sbfx_last_error(fx));
        sbfx_counters c;
        sbfx_stats(fx, &c);
        if (i == warmup - 1) out.module_allocs = c.heap_allocs_after_load;
        if (i >= warmup) out.module_allocs = c.heap_allocs_after_load - out.module_allocs;
        out.max_passes = c.passes > out.max_passes ? c.passes : out.max_passes;
        out.max_draws = c.draw_calls > out.max_draws ? c.draw_calls : out.max_draws;
        if (c.passes) {
            out.frames_with_particles++;
            int w, h;
            sbfx_read_particle_target(fx, target, 4u * f->width * f->height, &w, &h);
            if (!all_finite(target, 4u * w * h)) out.finite = false;
        }
    }
    free(target);
    return out;
}

CHECK_TEST(no_heap_allocation_per_frame_after_warmup)
{
    gl_fixture f;
    fixture_open(&f, 160, 90);
    struct test_scene scene;
    char err[256];
    CHECK(test_scene_create(&scene, 160, 90, err, sizeof(err)) == 0, "%s", err);
    sbfx *fx = fixture_module(&f, (sbfx_desc){.ignore_timeline = true});
    /* Warm up across the first frames (targets are made on the first render). */
    uint64_t before = 0;
    for (int i = 0; i < 3; i++) {
        test_scene_orbit_camera(0, 160.0f / 90, f.frame.view, f.frame.projection);
        f.frame.scene_depth_texture = scene.depth_texture;
        f.frame.out_framebuffer = scene.framebuffer;
        sbfx_render(fx, &f.frame);
    }
    sbfx_counters c;
    sbfx_stats(fx, &c);
    before = c.heap_allocs_after_load;
    run_result r = run_explosion(&f, fx, &scene, 60, 5);
    sbfx_stats(fx, &c);
    /* sbfx_render's own allocations are counted by the module (every allocation of sbfx goes
     * through sbfx_calloc); the process-wide count covers sbfx_update only, because the GL
     * driver (llvmpipe) allocates inside draw calls, which is not ours to control. */
    printf("# heap allocations after warm-up: module %llu, whole process during sbfx_update %ld\n",
           (unsigned long long)(c.heap_allocs_after_load - before), r.mallocs);
    CHECK(c.heap_allocs_after_load == before, "module allocated %llu times per run",
          (unsigned long long)(c.heap_allocs_after_load - before));
    CHECK(r.mallocs == 0, "%ld heap allocations during 55 frames of sbfx_update", r.mallocs);
    sbfx_destroy(fx);
    test_scene_destroy(&scene);
    fixture_close(&f);
}

CHECK_TEST(explosion_renders_three_passes_and_finite_pixels)
{
    gl_fixture f;
    fixture_open(&f, 160, 90);
    struct test_scene scene;
    char err[256];
    CHECK(test_scene_create(&scene, 160, 90, err, sizeof(err)) == 0, "%s", err);
    sbfx *fx = fixture_module(&f, (sbfx_desc){.ignore_timeline = true});
    run_result r = run_explosion(&f, fx, &scene, 90, 0);
    CHECK(r.finite, "a particle-target pixel is NaN or Inf");
    int corners = sbfx_float32_renderable(); /* the low-res corners' program and pass (passes.c) */
    CHECK(r.max_passes == 3 + corners, "passes %d, want depth + (corners) + particles + composite", r.max_passes);
    CHECK(r.frames_with_particles >= 80, "only %d of 90 frames had particles", r.frames_with_particles);
    sbfx_counters c;
    sbfx_stats(fx, &c);
    CHECK(c.programs == 5 + corners, "programs %d: dust, smoke, fire, depth, (corners), composite", c.programs);
    sbfx_destroy(fx);
    test_scene_destroy(&scene);
    fixture_close(&f);
}

/* With the half-float colour-buffer extensions hidden, the target falls back to RGBA8, says so
 * once, and still renders the same picture within 8-bit precision. */
CHECK_TEST(rgba8_fallback_when_half_float_not_renderable)
{
    static const char hidden[] = "GL_EXT_color_buffer_half_float GL_EXT_color_buffer_float";
    fixture_hide_extensions(hidden);
    gl_fixture f;
    fixture_open_far(&f, 64, 64);
    fixture_require_hidden(hidden);
    sbfx *fx = fixture_module(&f, (sbfx_desc){.target_divisor = 1});
    sbfx_view_particle p = {.center = {0, 0, -6}, .radius = 2.0f, .intensity = 1, .medium = SBFX_SMOKE};
    CHECK(sbfx_render_view_particles(fx, &f.frame, &p, 1) == SBFX_OK, "%s", sbfx_last_error(fx));
    f.frame.width = 32, f.frame.height = 32; /* a resize remakes the target: no second warning */
    CHECK(sbfx_render_view_particles(fx, &f.frame, &p, 1) == SBFX_OK);
    f.frame.width = 64, f.frame.height = 64;
    CHECK(sbfx_render_view_particles(fx, &f.frame, &p, 1) == SBFX_OK);
    sbfx_counters c;
    sbfx_stats(fx, &c);
    CHECK(c.target_format == SBFX_FORMAT_RGBA8, "format %d", c.target_format);
    CHECK(f.warnings == 1, "%d warnings (want exactly one)", f.warnings);
    CHECK(strstr(f.last_warning, "RGBA8") != NULL, "warning: %s", f.last_warning);
    int w, h;
    float *rgba = fixture_read_target(fx, &w, &h);
    sbfx_media(fx)[SBFX_SMOKE].detail_strength = 0.0f;
    double worst = 0;
    CHECK(sbfx_render_view_particles(fx, &f.frame, &p, 1) == SBFX_OK);
    free(rgba);
    rgba = fixture_read_target(fx, &w, &h);
    sbfx_ref_particle rp = {{0, 0, -6}, 2.0, sbfx_media(fx)[SBFX_SMOKE].tau};
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            sbfx_ref_pixel px = {{0}, INFINITY, fixture_near(&f.frame), 0};
            fixture_ray(&f, &f.frame, w, h, x, y, px.ray);
            double cpu = sbfx_ref_opacity(SBFX_OPACITY_DEFAULT, &rp, &px); /* the module's default */
            worst = fmax(worst, fabs(cpu - (1.0 - rgba[4 * (y * w + x) + 3])));
        }
    printf("# RGBA8 fallback: max alpha error %.4f (8-bit step %.4f)\n", worst, 1.0 / 255);
    CHECK(worst <= 1.0 / 255, "RGBA8 alpha off by %g", worst);
    free(rgba);
    sbfx_destroy(fx);
    fixture_close(&f);
}

/* The GPU's lookups are the CPU lookups of the same float tables (src/tables/blackbody.c, phase.c), up
 * to the shader's float arithmetic: what SBFX_TABLE_GPU_ALLOWANCE allows for. */
CHECK_TEST(gpu_tables_match_cpu_tables)
{
    gl_fixture f;
    fixture_open(&f, 8, 8);
    sbfx *fx = fixture_module(&f, (sbfx_desc){.table_phase = true});
    double bb_worst = 0, phase_worst = 0;
    sbfx_rng rng;
    sbfx_rng_seed(&rng, 7);
    for (int pass = 0; pass < 2; pass++) {
        if (pass == 1) { /* a forward-scattering smoke: a warped table */
            sbfx_media(fx)[SBFX_SMOKE].phase_g = 0.7f;
            CHECK(sbfx_reload(fx) == SBFX_OK, "%s", sbfx_last_error(fx));
        }
        const sbfx_tables *t = sbfx_get_tables(fx);
        double g = sbfx_media(fx)[SBFX_SMOKE].phase_g;
        for (int i = 0; i < 200; i++) {
            double k = 1.0 / sbfx_rng_range(&rng, 1.0 / t->blackbody_hi, 1.0 / t->blackbody_lo);
            double c = sbfx_rng_range(&rng, -1.0, 1.0), cpu[3];
            float gpu[3], phase;
            sbfx_blackbody_table_lookup(t->blackbody, SBFX_BLACKBODY_SIZE, t->blackbody_lo, t->blackbody_hi,
                                        (float)k, cpu);
            CHECK(sbfx_fetch_luts(fx, SBFX_SMOKE, (float)k, (float)c, gpu, &phase) == SBFX_OK);
            double top = fmax(cpu[0], fmax(cpu[1], cpu[2]));
            for (int j = 0; j < 3; j++) bb_worst = fmax(bb_worst, fabs(gpu[j] - cpu[j]) / top);
            double p = sbfx_phase_table_lookup(t->phase + SBFX_SMOKE * SBFX_PHASE_SIZE, SBFX_PHASE_SIZE, g, (float)c);
            phase_worst = fmax(phase_worst, fabs(phase - p) / p);
        }
    }
    printf("# GPU tables vs the CPU lookup of the same tables: black body %.2e, phase %.2e\n", bb_worst, phase_worst);
    CHECK(bb_worst < SBFX_TABLE_GPU_ALLOWANCE, "black body %g", bb_worst);
    CHECK(phase_worst < SBFX_TABLE_GPU_ALLOWANCE, "phase %g", phase_worst);
    sbfx_destroy(fx);
    fixture_close(&f);
}

/* Renders one fire and one dust particle; returns the particle target (malloc'ed). */
static float *render_pair(gl_fixture *f, sbfx_desc desc, int *w, int *h)
{
    desc.target_divisor = 1;
    desc.target_format = SBFX_FORMAT_RGBA32F;
    desc.ignore_timeline = true;
    sbfx *fx = fixture_module(f, desc);
    sbfx_view_particle p[2] = {
        {.center = {-0.8f, 0, -6}, .radius = 1.2f, .detail = {0.2f, 0.4f, 0.1f}, .intensity = 1, .medium = SBFX_FIRE},
        {.center = {0.8f, 0.2f, -5}, .radius = 1.0f, .detail = {0.6f, 0.1f, 0.5f}, .intensity = 1, .medium = SBFX_DUST}};
    CHECK(sbfx_render_view_particles(fx, &f->frame, p, 2) == SBFX_OK, "%s", sbfx_last_error(fx));
    float *rgba = fixture_read_target(fx, w, h);
    sbfx_destroy(fx);
    return rgba;
}

/* The analytic alternatives agree with the tables (the tables' error is what the benchmark
 * reports); R32F detail renders too, at the price of nearest sampling. */
CHECK_TEST(analytic_blackbody_and_phase_agree_with_tables)
{
    gl_fixture f;
    fixture_open_far(&f, 48, 48);
    int w, h;
    float *lut = render_pair(&f, (sbfx_desc){0}, &w, &h);
    float *analytic = render_pair(&f, (sbfx_desc){.analytic_blackbody = true, .analytic_phase = true}, &w, &h);
    float *r32 = render_pair(&f, (sbfx_desc){.detail_format = SBFX_DETAIL_R32F}, &w, &h);
    double worst = 0, peak = 0, detail_diff = 0;
    for (int i = 0; i < 4 * w * h; i++) {
        worst = fmax(worst, fabs(lut[i] - analytic[i]));
        peak = fmax(peak, fabs(lut[i]));
        detail_diff = fmax(detail_diff, fabs(lut[i] - r32[i]));
    }
    printf("# analytic vs LUT: max abs diff %.3g of peak %.3g; R32F nearest vs R16F linear detail: %.3g\n",
           worst, peak, detail_diff);
    CHECK(peak > 0.1, "nothing rendered");
    CHECK(worst < 0.01 * peak, "analytic differs from the tables by %g", worst);
    CHECK(all_finite(analytic, 4u * w * h) && all_finite(r32, 4u * w * h));
    CHECK(detail_diff > 0, "R32F detail should differ from R16F (nearest vs linear sampling)");
    free(lut);
    free(analytic);
    free(r32);
    fixture_close(&f);
}
/* In-scattering once per particle (on the CPU, at the centre) against per fragment: close for
 * particles of ordinary size, and only scattering media change. */
CHECK_TEST(light_per_particle_close_to_per_pixel)
{
    gl_fixture f;
    fixture_open_far(&f, 48, 48);
    int w, h;
    float *pixel = render_pair(&f, (sbfx_desc){0}, &w, &h);
    float *particle = render_pair(&f, (sbfx_desc){.light_per_particle = true}, &w, &h);
    double worst = 0, peak = 0;
    for (int i = 0; i < 4 * w * h; i++) {
        worst = fmax(worst, fabs(pixel[i] - particle[i]));
        peak = fmax(peak, fabs(pixel[i]));
    }
    printf("# light per particle vs per pixel: max abs diff %.4f of peak %.3f\n", worst, peak);
    CHECK(worst > 0, "the per-particle variant changed nothing");
    CHECK(worst < 0.02 * peak, "per-particle light differs by %g", worst);
    free(pixel);
    free(particle);
    fixture_close(&f);
}

/* ---- sbfx_set_trigger_listener: told of every instance started, by whom, when ---- */
typedef struct told {
    int count;
    char effect[8][32];
    double time[8];
    sbfx_trigger_origin origin[8];
    float x[8];
} told;

static void tell(const char *effect, const float position[3], double time, sbfx_trigger_origin origin, void *user)
{
    told *t = user;
    if (t->count == 8) return;
    snprintf(t->effect[t->count], sizeof(t->effect[0]), "%s", effect);
    t->time[t->count] = time, t->origin[t->count] = origin, t->x[t->count] = position[0];
    t->count++;
}

CHECK_TEST(trigger_listener_is_told_of_every_start)
{
    gl_fixture f;
    fixture_open(&f, 16, 16);
    /* room for one explosion at a time: a second one while the first lives is refused */
    sbfx *fx = fixture_module(&f, (sbfx_desc){.max_particles = 200, .start_time = 100.0});
    told t = {0};
    sbfx_set_trigger_listener(fx, tell, &t);
    const float here[3] = {1, 0, 0}, there[3] = {2, 0, 0};
    CHECK(sbfx_trigger(fx, "explosion", here) == SBFX_OK);
    CHECK(t.count == 1 && t.origin[0] == SBFX_TRIGGER_CALL && t.time[0] == 100.0 && t.x[0] == 1.0f,
          "sbfx_trigger: told %d, origin %d at %g", t.count, t.origin[0], t.time[0]);
    CHECK(sbfx_update(fx, 0.1) == SBFX_OK); /* the timeline's explosion at 0: the pool is full */
    CHECK(t.count == 1, "a refused timeline trigger was told (%d)", t.count);
    sbfx_destroy(fx);

    t = (told){0};
    fx = fixture_module(&f, (sbfx_desc){.start_time = 100.0});
    sbfx_set_trigger_listener(fx, tell, &t);
    CHECK(sbfx_schedule(fx, "explosion", 0.5, there) == SBFX_OK);
    CHECK(sbfx_update(fx, 0.25) == SBFX_OK && sbfx_update(fx, 0.25) == SBFX_OK && sbfx_update(fx, 0.1) == SBFX_OK);
    double step = 1.0 / 120.0;
    CHECK(t.count == 2, "told %d times", t.count);
    CHECK(t.origin[0] == SBFX_TRIGGER_TIMELINE && t.time[0] == 100.0 && strcmp(t.effect[0], "explosion") == 0,
          "the timeline: origin %d at %g (%s)", t.origin[0], t.time[0], t.effect[0]);
    CHECK(t.origin[1] == SBFX_TRIGGER_SCHEDULE && t.time[1] >= 100.5 - 1e-9 && t.time[1] < 100.5 + step && t.x[1] == 2.0f,
          "sbfx_schedule: origin %d at %.6f", t.origin[1], t.time[1]);
    /* a reload keeps the listener; its timeline starts again from now */
    double now = sbfx_time(fx);
    CHECK(sbfx_set_scene(fx, NULL) == SBFX_OK);
    CHECK(sbfx_update(fx, 0.02) == SBFX_OK);
    CHECK(t.count == 3 && t.origin[2] == SBFX_TRIGGER_TIMELINE && t.time[2] == now,
          "after a reload: told %d, origin %d at %g (now %g)", t.count, t.origin[2], t.time[2], now);
    sbfx_set_trigger_listener(fx, NULL, NULL);
    CHECK(sbfx_trigger(fx, "explosion", here) == SBFX_OK);
    CHECK(t.count == 3, "told after the listener was cleared");
    sbfx_destroy(fx);
    fixture_close(&f);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
