/* Fire lights its dust and smoke (issue 27): the frame's fire particles gathered into point
 * lights (src/sim/fire_light.h) in-scatter into dust and smoke through the phase model, per particle
 * at its centre, falling off across it from the fire. The GPU against the CPU reference
 * (ref/reference_frame.c, fire_light on): the light the fire adds (the frame with the fire's
 * emission less the frame with it at 0) agrees pixel by pixel within the hard cases' light
 * tolerance (test_gl_hard_cases: 2e-3 relative + 1e-5 absolute) taken for each of the two frames.
 * Only what is asked for: no fire, or nothing for it to light, makes no variant and no work. */
#include "gl_fixture.h"
#include "module.h"
#include "reference_frame.h"

#define SIZE 96
#define RGB_REL 2e-3
#define RGB_ABS 1e-5

static char shader_log[16384];

static void keep_shader_builds(sbfx_log_level level, const char *message, void *user)
{
    (void)level, (void)user;
    if (strstr(message, "shader build begin:") && strlen(shader_log) + strlen(message) + 2 < sizeof(shader_log)) {
        strcat(shader_log, message);
        strcat(shader_log, "\n");
    }
}

/* A fireball under a puff of smoke, a dust cloud beside it: view space, 6 m away. */
static const sbfx_view_particle scene[] = {
    {.center = {0.0f, -0.7f, -6.0f}, .radius = 0.55f, .detail = {0.1f, 0.2f, 0.3f}, .intensity = 1.0f, .medium = SBFX_FIRE},
    {.center = {0.3f, -0.5f, -6.2f}, .radius = 0.45f, .detail = {0.5f, 0.1f, 0.7f}, .intensity = 0.9f, .medium = SBFX_FIRE},
    {.center = {-0.3f, -0.6f, -5.9f}, .radius = 0.5f, .detail = {0.7f, 0.4f, 0.2f}, .intensity = 0.8f, .medium = SBFX_FIRE},
    {.center = {0.0f, 1.0f, -6.0f}, .radius = 1.1f, .detail = {0.3f, 0.6f, 0.1f}, .intensity = 0.9f, .medium = SBFX_SMOKE},
    {.center = {1.9f, -0.5f, -6.5f}, .radius = 0.9f, .detail = {0.8f, 0.3f, 0.5f}, .intensity = 0.9f, .medium = SBFX_DUST},
};
#define COUNT ((int)ARRAY_SIZE(scene))

static float *gpu_layer(gl_fixture *f, sbfx *fx, const sbfx_view_particle *p, int count)
{
    CHECK(sbfx_render_view_particles(fx, &f->frame, p, count) == SBFX_OK, "%s", sbfx_last_error(fx));
    int w, h;
    float *rgba = fixture_read_target(fx, &w, &h);
    CHECK(w == SIZE && h == SIZE, "target %dx%d", w, h);
    return rgba;
}

static float *half_detail(void)
{
    size_t n = 128 * 128 * 32; /* the module's default volume, as R16F holds it */
    float *v = malloc(n * sizeof(float));
    sbfx_detail_generate(128, 32, 1, v);
    for (size_t i = 0; i < n; i++) v[i] = (float)(_Float16)v[i];
    return v;
}

static double *cpu_layer(gl_fixture *f, sbfx *fx, const float *detail, const sbfx_view_particle *p, int count)
{
    static double distance[SIZE * SIZE];
    for (int i = 0; i < SIZE * SIZE; i++) distance[i] = INFINITY;
    const float *pr = f->frame.projection;
    sbfx_rf_light lights[SBFX_RF_MAX_LIGHTS];
    sbfx_view_light vl[SBFX_RF_MAX_LIGHTS];
    int n = sbfx_frame_lights(fx, f->frame.view, vl, SBFX_RF_MAX_LIGHTS);
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 4; k++) {
            lights[i].vector[k] = vl[i].vector[k];
            if (k < 3) lights[i].color[k] = vl[i].color[k];
        }
    const sbfx_tables *t = sbfx_get_tables(fx);
    sbfx_rf_frame rf = {.width = SIZE, .height = SIZE, .projection = {pr[0], pr[5], pr[8], pr[9]},
                        .near = fixture_near(&f->frame), .opaque_distance = distance, .opacity = SBFX_OPACITY_EXACT,
                        .lights = lights, .light_count = n, .detail = detail, .detail_size = 128, .detail_frames = 32,
                        .detail_time = sbfx_detail_time(fx), .cmf = &sbfx_cie1931_2deg,
                        .blackbody_norm = t->blackbody_norm, .blackbody_table = t->blackbody,
                        .blackbody_table_size = SBFX_BLACKBODY_SIZE, .blackbody_lo = t->blackbody_lo,
                        .blackbody_hi = t->blackbody_hi, .phase_table_size = SBFX_PHASE_SIZE,
                        .exposure = sbfx_get_desc(fx)->exposure, .fire_light = sbfx_fire_lit(fx)};
    float a[3];
    sbfx_frame_ambient(fx, a);
    for (int k = 0; k < 3; k++) rf.ambient[k] = a[k];
    const sbfx_medium_params *m = sbfx_media(fx);
    for (int i = 0; i < SBFX_MEDIUM_COUNT; i++) {
        rf.media[i] = (sbfx_rf_medium){.albedo = m[i].albedo, .tau = m[i].tau, .phase_g = m[i].phase_g,
                                       .color = {m[i].color[0], m[i].color[1], m[i].color[2]},
                                       .detail_strength = m[i].detail_strength, .detail_window = m[i].detail_window,
                                       .t0 = m[i].t0, .t1 = m[i].t1, .cooling = m[i].cooling, .soot = m[i].soot,
                                       .emission_scale = m[i].emission_scale, .has_detail = m[i].detail_strength > 0};
        if (t->phase_table[i]) rf.phase_tables[i] = t->phase + (size_t)i * SBFX_PHASE_SIZE;
    }
    sbfx_rf_particle rp[COUNT];
    for (int i = 0; i < count; i++) {
        rp[i] = (sbfx_rf_particle){.radius = p[i].radius, .intensity = p[i].intensity, .medium = p[i].medium};
        for (int k = 0; k < 3; k++) rp[i].center[k] = p[i].center[k], rp[i].detail[k] = p[i].detail[k];
    }
    double *layer = calloc(SIZE * SIZE * 4, sizeof(double));
    CHECK(sbfx_rf_render_layer(&rf, rp, count, layer, NULL) == 0, "the reference skipped particles");
    return layer;
}

static double luminance_at(const double *v) { return 0.2126 * v[0] + 0.7152 * v[1] + 0.0722 * v[2]; }

static sbfx *night_module(gl_fixture *f)
{
    /* a night's light level: the fire (emissivity 1) is bright against it */
    sbfx *fx = fixture_module(f, (sbfx_desc){.target_divisor = 1, .target_format = SBFX_FORMAT_RGBA32F,
                                             .white_luminance = 100.0f, .ignore_timeline = true});
    sbfx_set_light(fx, (const float[3]){-0.3f, -1.0f, -0.2f}, (const float[3]){0.04f, 0.04f, 0.05f},
                   (const float[3]){0.01f, 0.012f, 0.02f});
    return fx;
}

CHECK_TEST(smoke_next_to_fire_is_brighter_by_the_references_amount)
{
    gl_fixture f;
    fixture_open_far(&f, SIZE, SIZE);
    fixture_projection(&f, 0.8f, 0.1f, 100.0f);
    fixture_depth(&f, depth_far_everywhere, NULL);
    sbfx *fx = night_module(&f);
    CHECK(sbfx_fire_lit(fx), "the built-in explosion's fire does not light its smoke");
    float *detail = half_detail();
    sbfx_medium_params *fire = &sbfx_media(fx)[SBFX_FIRE];
    float emission = fire->emission_scale;
    float *gpu_on = gpu_layer(&f, fx, scene, COUNT);
    sbfx_counters c;
    sbfx_stats(fx, &c);
    CHECK(c.fire_lit_particles == 2, "%d particles lit by fire (the smoke and the dust)", c.fire_lit_particles);
    double *cpu_on = cpu_layer(&f, fx, detail, scene, COUNT);
    fire->emission_scale = 0.0f;   /* emissivity 0: the fire neither shows nor lights */
    float *gpu_off = gpu_layer(&f, fx, scene, COUNT);
    sbfx_stats(fx, &c);
    CHECK(c.fire_lit_particles == 0, "%d particles lit by a fire that emits nothing", c.fire_lit_particles);
    double *cpu_off = cpu_layer(&f, fx, detail, scene, COUNT);
    fire->emission_scale = emission;
    /* where the fire itself does not reach: what changes there is the fire's light on the rest */
    double *fire_only = cpu_layer(&f, fx, detail, scene, 3);
    double sum_gpu = 0.0, sum_cpu = 0.0, sum_off = 0.0, below = 0.0, above = 0.0, worst = 0.0;
    int pixels = 0, n_below = 0, n_above = 0, over = 0;
    for (int i = 0; i < SIZE * SIZE; i++) {
        if (fire_only[4 * i + 3] < 1.0 || cpu_on[4 * i + 3] >= 1.0) continue;
        double g_on[3] = {gpu_on[4 * i], gpu_on[4 * i + 1], gpu_on[4 * i + 2]};
        double g_off[3] = {gpu_off[4 * i], gpu_off[4 * i + 1], gpu_off[4 * i + 2]};
        for (int k = 0; k < 3; k++) {
            double dg = g_on[k] - g_off[k], dc = cpu_on[4 * i + k] - cpu_off[4 * i + k];
            double tol = RGB_REL * (fabs(cpu_on[4 * i + k]) + fabs(cpu_off[4 * i + k])) + 2.0 * RGB_ABS;
            worst = fmax(worst, fabs(dg - dc) / tol);
            if (!(fabs(dg - dc) <= tol)) over++;
        }
        double dg = luminance_at(g_on) - luminance_at(g_off), dc = luminance_at(&cpu_on[4 * i]) - luminance_at(&cpu_off[4 * i]);
        sum_gpu += dg, sum_cpu += dc, sum_off += luminance_at(&cpu_off[4 * i]), pixels++;
        int y = i / SIZE;
        if (i % SIZE > SIZE / 2 - 8 && i % SIZE < SIZE / 2 + 8) { /* the smoke's column */
            if (y > SIZE / 2 + 2 && y < SIZE / 2 + 10) below += dc, n_below++;
            if (y > SIZE / 2 + 20 && y < SIZE / 2 + 28) above += dc, n_above++;
        }
    }
    printf("# %d pixels of smoke and dust the fire does not cover: mean luminance %.5f without the fire's light, "
           "+%.5f with it on the GPU, +%.5f in the reference (GPU/reference %.5f); worst pixel %.3f of the "
           "tolerance\n", pixels, sum_off / pixels, sum_gpu / pixels, sum_cpu / pixels, sum_gpu / sum_cpu, worst);
    printf("# the smoke's column: +%.5f just above the fire, +%.5f higher up\n", below / n_below, above / n_above);
    CHECK(pixels > 500, "%d pixels", pixels);
    CHECK(over == 0, "%d channels differ from the reference by more than the tolerance (worst %.2f of it)", over, worst);
    CHECK(sum_cpu > 0.5 * sum_off, "the fire adds %.4f to %.4f: hardly any light", sum_cpu / pixels, sum_off / pixels);
    CHECK(below > 1.5 * above * n_below / n_above, "smoke above the fire does not glow from below");
    free(gpu_on), free(gpu_off), free(cpu_on), free(cpu_off), free(fire_only), free(detail);
    sbfx_destroy(fx);
    fixture_close(&f);
}

static sbfx *module_of_text(gl_fixture *f, const char *text)
{
    sbfx_scene *parsed = NULL;
    char err[512];
    CHECK(sbfx_scene_parse(text, "test", &parsed, err, sizeof(err)) == SBFX_OK, "%s", err);
    if (!parsed) exit(1);
    sbfx *fx = NULL;
    sbfx_desc d = {.scene = parsed, .log = keep_shader_builds, .log_user = f, .ignore_timeline = true};
    CHECK(sbfx_create(&d, &fx) == SBFX_OK, "%s", fx ? sbfx_last_error(fx) : "no module");
    sbfx_scene_free(parsed);
    if (!fx) exit(1);
    return fx;
}

#define MEDIA "lights = ( { type = \"directional\"; direction = [0.0, -1.0, 0.0]; color = [1.0, 1.0, 1.0]; } ); " \
              "ambient = [0.1, 0.1, 0.1]; media = { smoke = { albedo = 0.2; density = 0.4; }; " \
              "fire = { albedo = 0.0; density = 0.4; temperature = [1100.0, 900.0]; emissivity = 1.0; }; " \
              "heat = { strength = 0.01; }; };"
#define EMITTER(medium) "{ type = \"emitter\"; medium = \"" medium "\"; count = 20; speed = [1.0, 2.0]; " \
                        "lifetime = [1.0, 2.0]; radius = [0.4, 0.8]; intensity = [1.0, 0.0]; }"

/* No extra variant, instance data or work where there is no fire, or nothing for it to light. */
CHECK_TEST(only_what_is_asked_for)
{
    gl_fixture f;
    fixture_open_far(&f, 64, 64);
    GLuint color, color_fbo; /* heat shimmer reads the scene's colour */
    fixture_rgba8_target(64, 64, &color, &color_fbo);
    f.frame.scene_color_texture = color;
    setenv("SBFX_SHADER_LOG", "1", 1);
    static const struct { const char *name, *steps; bool lit; } cases[] = {
        {"smoke only", EMITTER("smoke"), false},
        {"fire only", EMITTER("fire"), false},
        {"fire and heat", EMITTER("fire") "," EMITTER("heat"), false},
        {"fire and smoke", EMITTER("fire") "," EMITTER("smoke"), true},
    };
    for (size_t i = 0; i < ARRAY_SIZE(cases); i++) {
        char text[2048];
        snprintf(text, sizeof(text), "%s effects = { boom = { steps = ( %s ); }; };", MEDIA, cases[i].steps);
        shader_log[0] = '\0';
        sbfx *fx = module_of_text(&f, text);
        bool has_define = strstr(shader_log, "FIRE_LIGHT") != NULL;
        CHECK(sbfx_fire_lit(fx) == cases[i].lit && has_define == cases[i].lit && (fx->scene->instance_fire > 0) == cases[i].lit,
              "%s: fire light %d, FIRE_LIGHT variant %d, instance data %d", cases[i].name, sbfx_fire_lit(fx),
              has_define, fx->scene->instance_fire);
        CHECK(sbfx_trigger(fx, "boom", (const float[3]){0.0f, 0.0f, -5.0f}) == SBFX_OK);
        sbfx_update(fx, 0.2);
        CHECK(sbfx_render(fx, &f.frame) == SBFX_OK, "%s", sbfx_last_error(fx));
        sbfx_counters c;
        sbfx_stats(fx, &c);
        CHECK((c.fire_lit_particles > 0) == cases[i].lit, "%s: %d particles lit by fire", cases[i].name,
              c.fire_lit_particles);
        CHECK(c.heap_allocs_after_load == 0, "%s: allocated while rendering", cases[i].name);
        sbfx_destroy(fx);
    }
    glDeleteFramebuffers(1, &color_fbo);
    glDeleteTextures(1, &color);
    fixture_close(&f);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
