/* Run-time quality and the frame budget (issue 11): a switch to quality Q renders what a module
 * created with Q renders, bit for bit; a level used once costs no allocation and no GL object
 * when switched back to; only the declared levels' variants exist; a budget the top level
 * meets changes nothing; bad names, budgets and ladders are clear errors. */
#include "gl_fixture.h"
#include "budget/ladder_default.h"
#include "module.h"
#include "host/test_scene.h"

#define W 96
#define H 64
#define FRAMES 16

/* Levels over every axis a level names: opacity models, divisors, upsampling, target formats,
 * light per particle, analytic black body, the phase function's table (the built-in explosion has
 * fire, smoke and dust, so each flag changes a program), particle level of detail. */
static const char *const levels[] = {
    "exact/4/nd",   "planar/1/bl",        "soft/2/nd",         "spherical/8/bl/rgba8", "exact/4/nd/lpp",
    "exact/2/bl/abb/tph", "exact/4/nd/rgba32f", "spherical/4/nd/lpp/abb", "exact/8/nd/tph", "planar/4/nd/rgba16f",
    "exact/4/nd/lod40",   "spherical/8/bl/lpp/lod12", "exact/4/mx", "spherical/8/mx/lpp",
};
#define LEVELS ((int)ARRAY_SIZE(levels))

static sbfx_quality level(int i)
{
    sbfx_quality q;
    char err[256];
    CHECK(sbfx_quality_parse(levels[i], &q, err, sizeof(err)) == SBFX_OK, "%s", err);
    return q;
}

static sbfx_desc desc_of(const sbfx_quality *q)
{
    return (sbfx_desc){.ignore_timeline = true, .opacity = q->opacity, .target_divisor = q->target_divisor,
                       .upsample = q->upsample, .target_format = q->target_format,
                       .light_per_particle = q->light_per_particle, .analytic_blackbody = q->analytic_blackbody,
                       .analytic_phase = q->analytic_phase, .table_phase = q->table_phase,
                      .lod_particles = q->lod_particles};
}

typedef struct host {
    gl_fixture f;
    struct test_scene scene;
} host;

static void host_open(host *h)
{
    char err[256];
    fixture_open(&h->f, W, H);
    CHECK(test_scene_create(&h->scene, W, H, err, sizeof(err)) == 0, "%s", err);
}

static void host_close(host *h)
{
    test_scene_destroy(&h->scene);
    fixture_close(&h->f);
}

static sbfx *module(host *h, sbfx_desc d)
{
    sbfx *fx = fixture_module(&h->f, d);
    const float origin[3] = {0, 0, 0};
    CHECK(sbfx_trigger(fx, "explosion", origin) == SBFX_OK);
    return fx;
}

/* Frame i of a module: the host's scene drawn afresh, sbfx over it; the output's bytes and the
 * particle target's floats (the stricter of the two) into out. */
typedef struct picture {
    uint8_t rgba[W * H * 4];
    float target[W * H * 4];
    int tw, th;
} picture;

static void render(host *h, sbfx *fx, int i, picture *out)
{
    test_scene_orbit_camera(i / 30.0, (float)W / H, h->f.frame.view, h->f.frame.projection);
    test_scene_draw(&h->scene, h->f.frame.view, h->f.frame.projection);
    h->f.frame.scene_depth_texture = h->scene.depth_texture;
    h->f.frame.out_framebuffer = h->scene.framebuffer;
    CHECK(sbfx_render(fx, &h->f.frame) == SBFX_OK, "%s", sbfx_last_error(fx));
    if (!out) return;
    glBindFramebuffer(GL_FRAMEBUFFER, h->scene.framebuffer);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, out->rgba);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    memset(out->target, 0, sizeof(out->target));
    CHECK(sbfx_read_particle_target(fx, out->target, ARRAY_SIZE(out->target), &out->tw, &out->th) == SBFX_OK);
}

static bool same(const picture *a, const picture *b)
{
    return a->tw == b->tw && a->th == b->th && memcmp(a->rgba, b->rgba, sizeof(a->rgba)) == 0 &&
           memcmp(a->target, b->target, sizeof(float) * 4 * (size_t)a->tw * (size_t)a->th) == 0;
}

/* A module switching level every frame against one fresh module per level, in lockstep. */
static void switching_matches_fresh(const char *const *ladder, int ladder_count)
{
    host h;
    host_open(&h);
    sbfx *fresh[LEVELS];
    for (int l = 0; l < LEVELS; l++) {
        sbfx_quality q = level(l);
        fresh[l] = module(&h, desc_of(&q));
    }
    sbfx_desc d = {.ignore_timeline = true, .ladder = ladder, .ladder_count = ladder_count};
    sbfx *sw = module(&h, d);
    static picture a, b, top;
    int compared = 0, identical = 0, other = 0, differs = 0;
    unsigned seen = 0;
    for (int i = 0; i < FRAMES; i++) {
        int l = (i * 5) % LEVELS; /* every level, in an order that is not the ladder's */
        seen |= 1u << l;
        sbfx_quality q = level(l);
        CHECK(sbfx_set_quality(sw, &q) == SBFX_OK, "%s", sbfx_last_error(sw));
        CHECK(sbfx_update(sw, 1.0 / 30) == SBFX_OK);
        for (int k = 0; k < LEVELS; k++) CHECK(sbfx_update(fresh[k], 1.0 / 30) == SBFX_OK);
        render(&h, sw, i, &a);
        render(&h, fresh[l], i, &b);
        sbfx_counters c;
        sbfx_stats(sw, &c);
        compared++;
        if (same(&a, &b)) identical++;
        else printf("#   frame %d at %s (module reports %s): differs from a module created so\n", i, levels[l], c.quality);
        CHECK(strcmp(c.quality, levels[l]) == 0, "quality %s, want %s", c.quality, levels[l]);
        if (l != 0 && c.passes) { /* not vacuous: another level draws another picture */
            render(&h, fresh[0], i, &top);
            other++;
            differs += memcmp(a.rgba, top.rgba, sizeof(a.rgba)) != 0;
        }
    }
    CHECK(other > 0 && differs == other, "%d of %d frames at other levels differ from the default's", differs, other);
    printf("# %d of %d frames over %d levels bit-identical to a fresh module%s\n", identical, compared, LEVELS,
           ladder ? " (levels declared at load)" : " (levels built on first use)");
    CHECK(identical == compared);
    CHECK(seen == (1u << LEVELS) - 1, "levels visited: %#x", seen);
    for (int l = 0; l < LEVELS; l++) sbfx_destroy(fresh[l]);
    sbfx_destroy(sw);
    host_close(&h);
}

CHECK_TEST(switching_equals_a_fresh_module_first_use)
{
    switching_matches_fresh(NULL, 0);
}

CHECK_TEST(switching_equals_a_fresh_module_declared)
{
    switching_matches_fresh(levels, LEVELS);
}

static void counters_of(sbfx *fx, sbfx_counters *c) { sbfx_stats(fx, c); }

static bool same_objects(const sbfx_counters *a, const sbfx_counters *b)
{
    return a->programs == b->programs && a->textures == b->textures && a->framebuffers == b->framebuffers &&
           a->gpu_bytes == b->gpu_bytes;
}

/* A level used once: switching back to it allocates nothing and creates no GL object. With the
 * levels declared at load, not even the first switch does (after the first frame's targets). */
static void switching_allocates_nothing(bool declared)
{
    host h;
    host_open(&h);
    sbfx *fx = module(&h, (sbfx_desc){.ignore_timeline = true, .ladder = declared ? levels : NULL,
                                      .ladder_count = declared ? LEVELS : 0});
    render(&h, fx, 0, NULL);
    sbfx_counters first, before, after;
    counters_of(fx, &first);
    for (int l = 0; l < LEVELS; l++) { /* first use */
        sbfx_quality q = level(l);
        CHECK(sbfx_set_quality(fx, &q) == SBFX_OK, "%s", sbfx_last_error(fx));
        CHECK(sbfx_update(fx, 1.0 / 30) == SBFX_OK);
        render(&h, fx, 1 + l, NULL);
    }
    counters_of(fx, &before);
    for (int round = 0; round < 2; round++)
        for (int l = LEVELS - 1; l >= 0; l--) {
            sbfx_quality q = level(l);
            CHECK(sbfx_set_quality(fx, &q) == SBFX_OK, "%s", sbfx_last_error(fx));
            CHECK(sbfx_update(fx, 1.0 / 30) == SBFX_OK);
            render(&h, fx, 20 + l, NULL);
        }
    counters_of(fx, &after);
    printf("# %s: %d programs, %d textures, %d framebuffers, %zu GPU bytes after the first frame; %d, %d, %d, %zu "
           "after every level once; %llu heap allocations after load in all\n", declared ? "declared" : "first use",
           first.programs, first.textures, first.framebuffers, first.gpu_bytes, before.programs, before.textures,
           before.framebuffers, before.gpu_bytes, (unsigned long long)after.heap_allocs_after_load);
    CHECK(after.heap_allocs_after_load == before.heap_allocs_after_load, "%llu allocations switching among used levels",
          (unsigned long long)(after.heap_allocs_after_load - before.heap_allocs_after_load));
    CHECK(same_objects(&before, &after), "GL objects changed switching among used levels: programs %d -> %d, "
          "textures %d -> %d, framebuffers %d -> %d", before.programs, after.programs, before.textures, after.textures,
          before.framebuffers, after.framebuffers);
    if (declared) {
        CHECK(same_objects(&first, &after), "declared levels made GL objects after the first frame");
        CHECK(after.heap_allocs_after_load == 0, "%llu allocations", (unsigned long long)after.heap_allocs_after_load);
    }
    sbfx_destroy(fx);
    host_close(&h);
}

CHECK_TEST(switching_allocates_nothing_after_first_use)
{
    switching_allocates_nothing(false);
}

CHECK_TEST(declared_levels_allocate_nothing_after_load)
{
    switching_allocates_nothing(true);
}

/* Only what the scene and the ladder call for: a module without a ladder has the programs it
 * always had; a ladder adds a program only for what differs in a way the scene's media feel. */
CHECK_TEST(only_declared_variants_exist)
{
    host h;
    host_open(&h);
    static const char *const upsample_only[] = {"exact/4/bl"};
    static const char *const same_programs[] = {"exact/8/nd", "exact/2/nd/rgba32f"};
    sbfx *plain = module(&h, (sbfx_desc){.ignore_timeline = true});
    sbfx *up = module(&h, (sbfx_desc){.ignore_timeline = true, .ladder = upsample_only, .ladder_count = 1});
    sbfx *targets = module(&h, (sbfx_desc){.ignore_timeline = true, .ladder = same_programs, .ladder_count = 2});
    sbfx_counters a, b, c;
    render(&h, plain, 0, NULL);
    render(&h, up, 0, NULL);
    render(&h, targets, 0, NULL);
    counters_of(plain, &a), counters_of(up, &b), counters_of(targets, &c);
    /* nearest-depth levels add the low-res corners' program and target where RGBA32F renders */
    int corners = sbfx_float32_renderable();
    CHECK(a.programs == 5 + corners, "plain module: %d programs (dust, smoke, fire, depth, (corners), composite)",
          a.programs);
    CHECK(b.programs == 6 + corners, "a bilinear level adds its composite only: %d programs", b.programs);
    CHECK(c.programs == 5 + corners, "levels differing in target only add no program: %d", c.programs);
    CHECK(c.framebuffers == a.framebuffers + 4 + 2 * corners, "two more target sets: %d framebuffers, plain %d",
          c.framebuffers, a.framebuffers);
    CHECK(strcmp(a.quality, "exact/4/nd") == 0 && a.budget_ms == 0 && a.quality_changes == 0, "%s", a.quality);
    sbfx_destroy(plain);
    sbfx_destroy(up);
    sbfx_destroy(targets);
    host_close(&h);
}

/* A budget the top level meets: the same frames as without a budget, bit for bit. */
CHECK_TEST(generous_budget_changes_nothing)
{
    host h;
    host_open(&h);
    sbfx *plain = module(&h, (sbfx_desc){.ignore_timeline = true});
    sbfx *budget = module(&h, (sbfx_desc){.ignore_timeline = true, .frame_budget_ms = 10000.0f});
    static picture a, b;
    int identical = 0;
    for (int i = 0; i < FRAMES; i++) {
        CHECK(sbfx_update(plain, 1.0 / 30) == SBFX_OK && sbfx_update(budget, 1.0 / 30) == SBFX_OK);
        render(&h, plain, i, &a);
        render(&h, budget, i, &b);
        identical += same(&a, &b);
    }
    sbfx_counters c;
    sbfx_stats(budget, &c);
    printf("# generous budget: %d of %d frames bit-identical, level %s, %d changes, smoothed GPU %.3f ms\n", identical,
           FRAMES, c.quality, c.quality_changes, (double)c.gpu_ms);
    CHECK(identical == FRAMES);
    CHECK(c.budget_ms == 10000.0f && c.quality_changes == 0 && c.frames_over_budget == 0);
    CHECK(strcmp(c.quality, "exact/4/nd") == 0, "%s", c.quality);
    sbfx_destroy(plain);
    sbfx_destroy(budget);
    host_close(&h);
}

/* A budget nothing meets walks the ladder down (measured by the module's own timer queries, or
 * where the extension is hidden by the host's reported times), never above the top. */
static void impossible_budget(bool hide_timer)
{
    if (hide_timer) fixture_hide_extensions("GL_EXT_disjoint_timer_query");
    host h;
    host_open(&h);
    if (hide_timer) fixture_require_hidden("GL_EXT_disjoint_timer_query");
    static const char *const ladder[] = {"exact/2/nd", "exact/4/nd", "exact/8/bl", "spherical/8/bl"};
    sbfx *fx = module(&h, (sbfx_desc){.ignore_timeline = true, .target_divisor = 4, .frame_budget_ms = 0.001f,
                                      .ladder = ladder, .ladder_count = 4});
    for (int i = 0; i < 40; i++) {
        CHECK(sbfx_update(fx, 1.0 / 30) == SBFX_OK);
        render(&h, fx, i, NULL);
        if (hide_timer) sbfx_report_frame_time(fx, 5.0);
        else glFinish(); /* results become available */
    }
    sbfx_counters c;
    sbfx_stats(fx, &c);
    printf("# budget 0.001 ms (%s): level %s after 40 frames, %d changes, %d frames over, smoothed %.3f ms\n",
           hide_timer ? "host-reported times" : "timer queries", c.quality, c.quality_changes, c.frames_over_budget,
           (double)c.gpu_ms);
    CHECK(strcmp(c.quality, "spherical/8/bl") == 0, "level %s: the last rung is the one that can go lowest", c.quality);
    CHECK(c.quality_changes >= 1 && c.frames_over_budget > 0);
    sbfx_quality q = level(0);
    CHECK(sbfx_set_quality(fx, &q) == SBFX_ERR_INVALID_ARGUMENT, "set_quality under a budget");
    sbfx_destroy(fx);
    host_close(&h);
}

CHECK_TEST(impossible_budget_walks_down_timer)
{
    impossible_budget(false);
}

CHECK_TEST(impossible_budget_walks_down_host_reported)
{
    impossible_budget(true);
}

/* render.budget_ms and render.ladder reach the module; the desc's own budget wins. The ladder
 * below the top (exact/4/nd, not on it): the levels with a coarser target only. */
CHECK_TEST(scene_budget_and_ladder)
{
    gl_fixture f;
    fixture_open(&f, 8, 8);
    const char *text = "media = { smoke = { albedo = 0.5; density = 0.4; }; };\n"
                       "effects = { puff = { steps = ( { type = \"emitter\"; medium = \"smoke\"; count = 10; } ); }; };\n"
                       "render = { budget_ms = 10000.0; ladder = [ \"exact/2/nd\", \"exact/8/bl\", \"planar/4/bl\" ]; };\n";
    char err[256];
    sbfx_scene *scene = NULL;
    CHECK(sbfx_scene_parse(text, "budget.cfg", &scene, err, sizeof(err)) == SBFX_OK, "%s", err);
    if (!scene) exit(1);
    sbfx *fx = fixture_module(&f, (sbfx_desc){.scene = scene});
    sbfx *own = fixture_module(&f, (sbfx_desc){.scene = scene, .frame_budget_ms = 5.0f});
    sbfx_scene_free(scene);
    sbfx_counters c, d;
    sbfx_stats(fx, &c);
    sbfx_stats(own, &d);
    CHECK(c.budget_ms == 10000.0f && d.budget_ms == 5.0f, "budgets %g, %g", (double)c.budget_ms, (double)d.budget_ms);
    CHECK(strcmp(c.quality, "exact/4/nd") == 0, "%s", c.quality);
    /* smoke + depth + the composites of nd (top) and bl (exact/8/bl) + nd's low-res corners where
     * RGBA32F renders: planar/4/bl and exact/2/nd are not below the top, so not built */
    CHECK(c.programs == 4 + sbfx_float32_renderable(), "%d programs", c.programs);
    sbfx_destroy(fx);
    sbfx_destroy(own);
    fixture_close(&f);
}

/* The budget's ladder below a top on the default ladder: the levels after it; below a top that
 * differs from one of them in target format only, the levels after that one. */
static void expect_ladder(gl_fixture *f, const sbfx_quality *top, int from)
{
    sbfx_desc d = desc_of(top);
    d.frame_budget_ms = 16.0f;
    sbfx *fx = fixture_module(f, d);
    const sbfx_budget *b = fx->budget;
    char name[64], want[64];
    CHECK(b->count == 1 + SBFX_LADDER_DEFAULT_COUNT - from, "%d levels below %s, want %d", b->count - 1,
          sbfx_quality_name(top, name, sizeof(name)), SBFX_LADDER_DEFAULT_COUNT - from);
    CHECK(sbfx_quality_equal(&b->ladder[0], top), "the top is level 0");
    for (int i = 1; i < b->count && from + i - 1 < SBFX_LADDER_DEFAULT_COUNT; i++) {
        sbfx_quality_name(&b->ladder[i], name, sizeof(name));
        sbfx_quality q;
        CHECK(sbfx_quality_parse(sbfx_ladder_default[from + i - 1], &q, NULL, 0) == SBFX_OK);
        sbfx_quality_name(&q, want, sizeof(want));
        CHECK(strcmp(name, want) == 0, "level %d: %s, want %s", i, name, want);
    }
    sbfx_destroy(fx);
}

CHECK_TEST(budget_ladder_starts_below_the_top)
{
    gl_fixture f;
    fixture_open(&f, 8, 8);
    for (int k = 0; k < SBFX_LADDER_DEFAULT_COUNT; k++) {
        sbfx_quality q;
        CHECK(sbfx_quality_parse(sbfx_ladder_default[k], &q, NULL, 0) == SBFX_OK);
        expect_ladder(&f, &q, k + 1);
        q.target_format = q.target_format == SBFX_FORMAT_RGBA8 ? SBFX_FORMAT_RGBA32F : SBFX_FORMAT_RGBA8;
        expect_ladder(&f, &q, k + 1);
    }
    /* a top off the ladder: only coarser targets (or fewer particles) below it */
    sbfx_quality top = {.opacity = SBFX_OPACITY_SOFT, .target_divisor = 4, .upsample = SBFX_UPSAMPLE_BILINEAR};
    sbfx *fx = fixture_module(&f, (sbfx_desc){.opacity = top.opacity, .target_divisor = 4,
                                              .upsample = top.upsample, .frame_budget_ms = 16.0f});
    for (int i = 1; i < fx->budget->count; i++)
        CHECK(fx->budget->ladder[i].target_divisor > 4 || fx->budget->ladder[i].lod_particles > 0, "level %d", i);
    sbfx_destroy(fx);
    fixture_close(&f);
}

/* ---- names and bad input (no GL) ---- */

CHECK_TEST(names_are_canonical)
{
    /* aph names the analytic phase, the default since issue 43: accepted, and not written */
    static const char *const in[] = {"exact/4/nd", "spherical/8/bl/lpp/lod256", "planar/1/bl/aph/abb/lpp/rgba32f",
                                     "soft/2/nd/lod1/rgba8", "exact/4/nd/tph/lpp", "exact/4/nd/aph"};
    static const char *const want[] = {"exact/4/nd", "spherical/8/bl/lpp/lod256", "planar/1/bl/rgba32f/lpp/abb",
                                       "soft/2/nd/rgba8/lod1", "exact/4/nd/lpp/tph", "exact/4/nd"};
    for (size_t i = 0; i < ARRAY_SIZE(in); i++) {
        sbfx_quality q, again;
        char err[256], name[64], name2[64];
        CHECK(sbfx_quality_parse(in[i], &q, err, sizeof(err)) == SBFX_OK, "%s", err);
        sbfx_quality_name(&q, name, sizeof(name));
        CHECK(strcmp(name, want[i]) == 0, "%s -> %s, want %s", in[i], name, want[i]);
        CHECK(sbfx_quality_parse(name, &again, err, sizeof(err)) == SBFX_OK, "%s", err);
        CHECK(memcmp(&q, &again, sizeof(q)) == 0, "%s does not parse back to itself", name);
        CHECK(strcmp(sbfx_quality_name(&again, name2, sizeof(name2)), name) == 0);
    }
    sbfx_quality zero = {0};
    char name[64];
    CHECK(strcmp(sbfx_quality_name(&zero, name, sizeof(name)), "exact/4/nd") == 0, "defaults: %s", name);
}

CHECK_TEST(bad_names_name_the_token)
{
    static const char *const bad[][2] = {
        {"fuzzy/4/nd", "'fuzzy'"}, {"exact/3/nd", "'3'"},       {"exact/4/xx", "'xx'"},
        {"exact/4/nd/foo", "'foo'"}, {"exact/4", "<opacity>"},  {"exact/4/nd/lpp/lpp", "'lpp'"},
        {"exact/4/nd/lod0", "'lod0'"}, {"exact//nd", "''"},     {"exact/4/nd/rgba8/rgba16f", "'rgba16f'"},
        {"floor/4/nd", "'floor'"}, {"exact/4/nd/lod12x", "'lod12x'"}, {"", "''"},
        {"exact/4/nd/aph/tph", "'tph'"}, {"exact/4/nd/tph/tph", "'tph'"},
    };
    for (size_t i = 0; i < ARRAY_SIZE(bad); i++) {
        sbfx_quality q;
        char err[256] = "";
        CHECK(sbfx_quality_parse(bad[i][0], &q, err, sizeof(err)) == SBFX_ERR_INVALID_ARGUMENT, "%s parsed", bad[i][0]);
        CHECK(strstr(err, bad[i][1]) != NULL, "\"%s\": message \"%s\" does not name %s", bad[i][0], err, bad[i][1]);
    }
}

static char logged[512];
static void capture(sbfx_log_level level, const char *message, void *user)
{
    (void)level, (void)user;
    snprintf(logged, sizeof(logged), "%s", message);
}

CHECK_TEST(bad_budget_and_ladder_are_rejected)
{
    gl_fixture f;
    fixture_open(&f, 8, 8);
    sbfx *fx = NULL;
    static const char *const bad_ladder[] = {"exact/4/nd", "exact/8/zz"};
    CHECK(sbfx_create(&(sbfx_desc){.frame_budget_ms = -1.0f, .log = capture}, &fx) == SBFX_ERR_INVALID_ARGUMENT);
    CHECK(strstr(logged, "frame_budget_ms -1") != NULL, "%s", logged);
    CHECK(sbfx_create(&(sbfx_desc){.frame_budget_ms = NAN, .log = capture}, &fx) == SBFX_ERR_INVALID_ARGUMENT);
    CHECK(strstr(logged, "frame_budget_ms nan") != NULL, "%s", logged);
    CHECK(sbfx_create(&(sbfx_desc){.ladder_count = 2}, &fx) == SBFX_ERR_INVALID_ARGUMENT);
    sbfx_desc d = {.frame_budget_ms = 16.0f, .ladder = bad_ladder, .ladder_count = 2, .log = capture};
    CHECK(sbfx_create(&d, &fx) == SBFX_ERR_INVALID_ARGUMENT);
    CHECK(strstr(logged, "ladder[1]") && strstr(logged, "'zz'"), "message: %s", logged);
    CHECK(fx == NULL);
    fx = fixture_module(&f, (sbfx_desc){.ignore_timeline = true});
    sbfx_quality q = {.target_divisor = 3};
    CHECK(sbfx_set_quality(fx, &q) == SBFX_ERR_INVALID_ARGUMENT);
    CHECK(strstr(sbfx_last_error(fx), "divisor") != NULL, "%s", sbfx_last_error(fx));
    q = (sbfx_quality){.lod_particles = -1};
    CHECK(sbfx_set_quality(fx, &q) == SBFX_ERR_INVALID_ARGUMENT);
    CHECK(sbfx_set_quality(fx, NULL) == SBFX_ERR_INVALID_ARGUMENT);
    sbfx_destroy(fx);
    fixture_close(&f);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
