/* sbfx_set_scene: the scene of a live module replaced. A change of numbers only compiles no
 * shader and makes no target; a change that needs other variants builds them and deletes what
 * the new scene no longer uses; a build that fails leaves the old scene playing; 200 reloads
 * leave GL objects and the heap where they were; the host's GL state is untouched. */
#include <malloc.h>
#include <time.h>
#include "gl_fixture.h"
#include "gl_snapshot.h"
#include "module.h"

/* A smoke column at 4 m in front of the camera (view = identity), optionally with a fire. */
typedef struct edit {
    float grey;        /* the smoke's colour */
    int count;         /* particles of its emitter */
    float detail;      /* detail strength: 0 compiles the smoke without HAS_DETAIL */
    bool fire;         /* a second medium: its own particle program */
    int target_scale;
} edit;

static sbfx_scene *scene_of(edit e)
{
    char text[2048], err[512];
    snprintf(text, sizeof(text),
             "render = { target_scale = %d; max_particles = 512; };\n"
             "media = {\n"
             "  smoke = { albedo = 0.4; density = 0.6; color = [%g, %g, %g];\n"
             "            detail = { source = \"procedural\"; strength = %g; window = 0.8; }; };\n"
             "%s"
             "};\n"
             "effects = { puff = { steps = (\n"
             "  { type = \"emitter\"; medium = \"smoke\"; count = %d; spawn_radius = 0.4; speed = [0.2, 0.5];\n"
             "    lifetime = [3.0, 4.0]; radius = [0.4, 0.9]; intensity = [1.0, 0.2]; }%s\n"
             "); }; };\n"
             "triggers = { timeline = ( { effect = \"puff\"; time = 0.0; position = [0.0, 0.0, -4.0]; } ); };\n",
             e.target_scale ? e.target_scale : 4, e.grey, e.grey, e.grey, e.detail,
             e.fire ? "  fire = { albedo = 0.0; density = 0.8; temperature = [1300.0, 900.0]; };\n" : "", e.count,
             e.fire ? ",\n  { type = \"emitter\"; medium = \"fire\"; count = 20; spawn_radius = 0.2; speed = [0.1, 0.3];\n"
                      "    lifetime = [1.0, 1.5]; radius = [0.3, 0.1]; intensity = [1.0, 0.0]; }"
                    : "");
    sbfx_scene *scene = NULL;
    CHECK(sbfx_scene_parse(text, "edit.cfg", &scene, err, sizeof(err)) == SBFX_OK, "%s", err);
    if (!scene) exit(1);
    return scene;
}

static const edit base = {.grey = 0.8f, .count = 40, .detail = 1.0f};

static sbfx *module_of(gl_fixture *f, edit e)
{
    sbfx_scene *scene = scene_of(e);
    sbfx *fx = fixture_module(f, (sbfx_desc){.scene = scene});
    sbfx_scene_free(scene);
    return fx;
}

static double last_reload_ms; /* printed, never asserted (a wall-clock time) */

static sbfx_result reload(sbfx *fx, edit e)
{
    sbfx_scene *scene = scene_of(e);
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    sbfx_result r = sbfx_set_scene(fx, scene);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    last_reload_ms = (double)(t1.tv_sec - t0.tv_sec) * 1e3 + (double)(t1.tv_nsec - t0.tv_nsec) / 1e6;
    sbfx_scene_free(scene); /* the module keeps nothing of it */
    return r;
}

static void frames(gl_fixture *f, sbfx *fx, int n)
{
    for (int i = 0; i < n; i++) {
        CHECK(sbfx_update(fx, 1.0 / 30.0) == SBFX_OK, "%s", sbfx_last_error(fx));
        CHECK(sbfx_render(fx, &f->frame) == SBFX_OK, "%s", sbfx_last_error(fx));
    }
}

static sbfx_counters stats(const sbfx *fx)
{
    sbfx_counters c;
    sbfx_stats(fx, &c);
    return c;
}

/* GL objects alive in the context, of every kind sbfx makes (the soak's count: Mesa hands out
 * names in increasing order, glIs* is true for the live ones below a fresh name). */
typedef struct gl_census {
    int programs, textures, framebuffers, buffers, vertex_arrays, samplers, queries;
} gl_census;

static int live_below(GLuint fresh, GLboolean (*is)(GLuint))
{
    int n = 0;
    for (GLuint id = 1; id < fresh + 64; id++) n += is(id) ? 1 : 0;
    return n;
}

static gl_census census(void)
{
    GLuint t = 0, fb = 0, b = 0, va = 0, s = 0, q = 0;
    glGenTextures(1, &t), glGenFramebuffers(1, &fb), glGenBuffers(1, &b);
    glGenVertexArrays(1, &va), glGenSamplers(1, &s), glGenQueries(1, &q);
    GLuint p = glCreateProgram();
    glDeleteProgram(p);
    glDeleteTextures(1, &t), glDeleteFramebuffers(1, &fb), glDeleteBuffers(1, &b);
    glDeleteVertexArrays(1, &va), glDeleteSamplers(1, &s), glDeleteQueries(1, &q);
    return (gl_census){live_below(p, glIsProgram), live_below(t, glIsTexture), live_below(fb, glIsFramebuffer),
                       live_below(b, glIsBuffer), live_below(va, glIsVertexArray), live_below(s, glIsSampler),
                       live_below(q, glIsQuery)};
}

static bool census_equal(gl_census a, gl_census b, const char *when)
{
    bool same = memcmp(&a, &b, sizeof(a)) == 0;
    CHECK(same, "%s: programs %d -> %d, textures %d -> %d, framebuffers %d -> %d, buffers %d -> %d, vertex arrays "
          "%d -> %d, samplers %d -> %d, queries %d -> %d", when, a.programs, b.programs, a.textures, b.textures,
          a.framebuffers, b.framebuffers, a.buffers, b.buffers, a.vertex_arrays, b.vertex_arrays, a.samplers,
          b.samplers, a.queries, b.queries);
    return same;
}

static int64_t heap_bytes(void)
{
    struct mallinfo2 m = mallinfo2();
    return (int64_t)(m.uordblks + m.hblkhd);
}

/* The programs the module holds now (its object table: every program it built or took over). */
static int programs_of(const sbfx *fx, GLuint *out, int max)
{
    int n = 0;
    for (int i = 0; i < fx->gl->object_count && n < max; i++)
        if (fx->gl->objects[i].kind == SBFX_OBJECT_PROGRAM) out[n++] = fx->gl->objects[i].id;
    return n;
}

static bool holds(const GLuint *ids, int n, GLuint id)
{
    for (int i = 0; i < n; i++)
        if (ids[i] == id) return true;
    return false;
}

CHECK_TEST(number_only_edit_compiles_nothing_and_makes_no_target)
{
    gl_fixture f;
    fixture_open_far(&f, 96, 64);
    sbfx *fx = module_of(&f, base);
    frames(&f, fx, 10);
    sbfx_counters before = stats(fx);
    gl_census objects = census();
    edit e = base;
    e.grey = 0.3f;  /* a colour */
    e.count = 70;   /* a count */
    CHECK(reload(fx, e) == SBFX_OK, "%s", sbfx_last_error(fx));
    printf("# number-only reload: %.1f ms\n", last_reload_ms);
    sbfx_counters after = stats(fx);
    CHECK(after.programs_compiled == before.programs_compiled, "programs compiled %d -> %d",
          before.programs_compiled, after.programs_compiled);
    CHECK(after.targets_created == before.targets_created, "targets created %d -> %d", before.targets_created,
          after.targets_created);
    CHECK(after.programs == before.programs && after.framebuffers == before.framebuffers &&
          after.textures == before.textures && after.gpu_bytes == before.gpu_bytes,
          "programs %d -> %d, framebuffers %d -> %d, textures %d -> %d, bytes %zu -> %zu", before.programs,
          after.programs, before.framebuffers, after.framebuffers, before.textures, after.textures,
          before.gpu_bytes, after.gpu_bytes);
    CHECK(after.scene_reloads == 1, "%d reloads counted", after.scene_reloads);
    /* the clock went on, the timeline starts again now: the new count is fired */
    double clock = sbfx_elapsed(fx);
    CHECK_NEAR(clock, 10.0 / 30.0, 1.0 / 120.0);
    frames(&f, fx, 3); /* (a vertex array exists for glIsVertexArray once it was bound) */
    census_equal(objects, census(), "number-only reload");
    after = stats(fx);
    CHECK(after.particles_alive == 70, "%d particles alive after the reload (70 fired)", after.particles_alive);
    CHECK(after.heap_allocs_after_load == before.heap_allocs_after_load, "frames after the reload allocated %llu",
          (unsigned long long)(after.heap_allocs_after_load - before.heap_allocs_after_load));
    CHECK(after.targets_created == before.targets_created, "the first frames after it made %d targets",
          after.targets_created - before.targets_created);
    sbfx_destroy(fx);
    fixture_close(&f);
}

CHECK_TEST(variant_changing_edit_builds_the_new_and_frees_the_old)
{
    gl_fixture f;
    fixture_open_far(&f, 96, 64);
    sbfx *fx = module_of(&f, base);
    frames(&f, fx, 5);
    GLuint old[SBFX_OBJECTS];
    int old_count = programs_of(fx, old, SBFX_OBJECTS);
    sbfx_counters before = stats(fx);
    /* the smoke without detail (a define less) and a fire (a medium more): two new programs */
    edit e = base;
    e.detail = 0.0f;
    e.fire = true;
    CHECK(reload(fx, e) == SBFX_OK, "%s", sbfx_last_error(fx));
    printf("# variant-changing reload (2 programs compiled): %.1f ms\n", last_reload_ms);
    frames(&f, fx, 3);
    sbfx_counters after = stats(fx);
    GLuint now[SBFX_OBJECTS];
    int now_count = programs_of(fx, now, SBFX_OBJECTS);
    CHECK(after.programs_compiled - before.programs_compiled == 2, "%d programs compiled (smoke without detail, fire)",
          after.programs_compiled - before.programs_compiled);
    CHECK(after.programs == before.programs + 1 && now_count == after.programs, "programs %d -> %d (%d held)",
          before.programs, after.programs, now_count);
    int freed = 0;
    for (int i = 0; i < old_count; i++) {
        if (holds(now, now_count, old[i])) continue;
        CHECK(!glIsProgram(old[i]), "program %u of the old scene is neither used nor deleted", old[i]);
        freed++;
    }
    CHECK(freed == 1, "%d programs of the old scene deleted (its smoke with detail)", freed);
    CHECK(after.targets_created == before.targets_created, "same targets: %d made", after.targets_created - before.targets_created);
    /* a coarser target: new targets, and the old ones deleted (counted by GL) */
    gl_census objects = census();
    e.target_scale = 8;
    CHECK(reload(fx, e) == SBFX_OK, "%s", sbfx_last_error(fx));
    sbfx_counters coarse = stats(fx);
    CHECK(coarse.programs_compiled == after.programs_compiled, "a target change compiled %d programs",
          coarse.programs_compiled - after.programs_compiled);
    int targets = 2 + (fx->gl->corners_program ? 1 : 0);
    CHECK(coarse.targets_created - after.targets_created == targets, "%d targets made (particles, low-res depth%s)",
          coarse.targets_created - after.targets_created, fx->gl->corners_program ? ", corners" : "");
    gl_census coarse_objects = census();
    CHECK(coarse_objects.framebuffers == objects.framebuffers && coarse.framebuffers == after.framebuffers,
          "framebuffers in GL %d -> %d, counted %d -> %d", objects.framebuffers, coarse_objects.framebuffers,
          after.framebuffers, coarse.framebuffers);
    sbfx_destroy(fx);
    fixture_close(&f);
}

CHECK_TEST(failed_build_keeps_the_old_scene_playing)
{
    gl_fixture f;
    fixture_open_far(&f, 96, 64);
    gl_census host = census();
    sbfx *fx = module_of(&f, base);
    frames(&f, fx, 5);
    sbfx_counters before = stats(fx);
    gl_census objects = census();
    edit e = base;
    e.grey = 0.2f;     /* numbers that would take over every program... */
    e.fire = true;     /* ...but the fire's new one fails to build */
    setenv("SBFX_INJECT_SHADER_FAILURE", "MEDIUM_EMITS", 1);
    sbfx_result r = reload(fx, e);
    unsetenv("SBFX_INJECT_SHADER_FAILURE");
    CHECK(r == SBFX_ERR_SHADER, "sbfx_set_scene: %s", sbfx_result_string(r));
    CHECK(strstr(sbfx_last_error(fx), "SBFX_INJECT_SHADER_FAILURE") != NULL, "last error: %s", sbfx_last_error(fx));
    sbfx_counters kept = stats(fx);
    CHECK(kept.programs == before.programs && kept.framebuffers == before.framebuffers &&
          kept.textures == before.textures && kept.particles_alive == before.particles_alive &&
          kept.scene_reloads == 0, "the old module changed: programs %d -> %d, particles %d -> %d", before.programs,
          kept.programs, before.particles_alive, kept.particles_alive);
    census_equal(objects, census(), "after a failed reload");
    CHECK(!sbfx_has_effect(fx, "nothing") && sbfx_has_effect(fx, "puff"), "the old effects are gone");
    frames(&f, fx, 3); /* it renders on, and its programs (lent and given back) are its own */
    CHECK(stats(fx).particles_alive == before.particles_alive, "particles %d -> %d", before.particles_alive,
          stats(fx).particles_alive);
    CHECK(reload(fx, e) == SBFX_OK, "the same edit without the failure: %s", sbfx_last_error(fx));
    sbfx_destroy(fx);
    census_equal(host, census(), "destroyed");
    fixture_close(&f);
}

/* n reloads cycling through edits, a frame after each. */
static bool reload_cycle(gl_fixture *f, sbfx *fx, const edit *edits, int count, int n)
{
    for (int i = 0; i < n; i++) {
        sbfx_result r = reload(fx, edits[i % count]);
        CHECK(r == SBFX_OK, "reload %d: %s", i, sbfx_last_error(fx));
        if (r != SBFX_OK) return false;
        frames(f, fx, 1);
    }
    return true;
}

/* 200 reloads of number-only edits: the GL objects are those of the start, exactly. The heap is
 * measured over four blocks of 50 reloads: a leak grows it in every block, while the C library's
 * and Mesa's arenas step once in a while (llvmpipe here: 0 or about 64 KB once in 200). A leak of
 * one block of 41 bytes or more per reload (the scene alone is 40 KB) would grow each block by
 * 2 KiB at least, so the quietest block must stay below that. Then 20 reloads that change
 * variants and targets (each compiles programs): GL objects exactly as before again. (Compiling
 * on Mesa keeps memory of its own, so the heap is checked on the first part; the ASan run of this
 * test checks sbfx's allocations in both.) */
CHECK_TEST(two_hundred_reloads_leak_nothing)
{
    gl_fixture f;
    fixture_open_far(&f, 96, 64);
    sbfx *fx = module_of(&f, base);
    edit numbers[3] = {base, base, base};
    numbers[1].count = 50, numbers[1].grey = 0.5f;
    numbers[2].count = 30, numbers[2].grey = 0.9f;
    if (!reload_cycle(&f, fx, numbers, 3, 6)) goto out; /* a first round: the arenas reach their size */
    gl_census objects = census();
    sbfx_counters start = stats(fx);
    int64_t quietest = INT64_MAX, total = 0;
    for (int block = 0; block < 4; block++) {
        int64_t heap = heap_bytes();
        if (!reload_cycle(&f, fx, numbers, 3, 50)) goto out;
        int64_t grown = heap_bytes() - heap;
        total += grown;
        if (grown < quietest) quietest = grown;
    }
    sbfx_counters end = stats(fx);
    printf("# 200 number-only reloads: heap %+lld bytes (quietest block of 50: %+lld), programs compiled %d, "
           "targets created %d\n", (long long)total, (long long)quietest,
           end.programs_compiled - start.programs_compiled, end.targets_created - start.targets_created);
    census_equal(objects, census(), "after 200 number-only reloads");
    CHECK(end.programs == start.programs && end.textures == start.textures && end.framebuffers == start.framebuffers &&
          end.gpu_bytes == start.gpu_bytes && end.heap_allocs_after_load == start.heap_allocs_after_load,
          "counted objects changed");
    CHECK(end.programs_compiled == start.programs_compiled && end.targets_created == start.targets_created,
          "%d programs compiled, %d targets made", end.programs_compiled - start.programs_compiled,
          end.targets_created - start.targets_created);
    CHECK(end.scene_reloads - start.scene_reloads == 200, "%d reloads", end.scene_reloads - start.scene_reloads);
    CHECK(quietest < 2048, "the heap grew in every block of 50 reloads, %lld bytes in the quietest", (long long)quietest);
    edit variants[4] = {base, base, base, base};
    variants[1].fire = true, variants[1].detail = 0.0f;
    variants[2].target_scale = 2;
    variants[3].fire = true, variants[3].target_scale = 8;
    if (!reload_cycle(&f, fx, variants, 4, 20) || !reload_cycle(&f, fx, variants, 1, 1)) goto out;
    census_equal(objects, census(), "after 20 variant-changing reloads");
    printf("# 20 variant-changing reloads: programs compiled %d, targets created %d\n",
           stats(fx).programs_compiled - end.programs_compiled, stats(fx).targets_created - end.targets_created);
out:
    sbfx_destroy(fx);
    fixture_close(&f);
}

/* The host's desc is the plan of every reload: its ladder (names copied at create: the host's
 * array is gone) is declared again, so switching to its level after a reload compiles nothing. */
static sbfx *module_with_ladder(gl_fixture *f)
{
    char name[32];
    snprintf(name, sizeof(name), "%s", "spherical/8/bl");
    const char *ladder[] = {name};
    sbfx_scene *scene = scene_of(base);
    sbfx *fx = fixture_module(f, (sbfx_desc){.scene = scene, .ladder = ladder, .ladder_count = 1});
    sbfx_scene_free(scene);
    memset(name, 'x', sizeof(name) - 1); /* the host's names change after create */
    return fx;
}

CHECK_TEST(reload_keeps_the_host_desc)
{
    gl_fixture f;
    fixture_open_far(&f, 96, 64);
    sbfx *fx = module_with_ladder(&f);
    frames(&f, fx, 2);
    edit e = base;
    e.fire = true; /* a new medium: the ladder's level needs its program too */
    CHECK(reload(fx, e) == SBFX_OK, "%s", sbfx_last_error(fx));
    frames(&f, fx, 2);
    sbfx_counters before = stats(fx);
    sbfx_quality q;
    CHECK(sbfx_quality_parse("spherical/8/bl", &q, NULL, 0) == SBFX_OK);
    CHECK(sbfx_set_quality(fx, &q) == SBFX_OK, "%s", sbfx_last_error(fx));
    frames(&f, fx, 2);
    sbfx_counters after = stats(fx);
    CHECK(strcmp(after.quality, "spherical/8/bl") == 0, "quality %s", after.quality);
    CHECK(after.programs_compiled == before.programs_compiled && after.targets_created == before.targets_created,
          "the ladder's level was not declared by the reload: %d programs compiled, %d targets made",
          after.programs_compiled - before.programs_compiled, after.targets_created - before.targets_created);
    sbfx_destroy(fx);
    fixture_close(&f);
}

/* A detail volume taken over on a reload keeps the statistics the fire's light averages over
 * (they were not made again with it, and were all 0 once). */
CHECK_TEST(reload_keeps_the_fire_light_detail_statistics)
{
    gl_fixture f;
    fixture_open_far(&f, 96, 64);
    edit e = base;
    e.fire = true;
    sbfx *fx = module_of(&f, e);
    GLuint volume = fx->gl->detail_texture;
    double before[SBFX_FIRE_DETAIL_LEVELS];
    memcpy(before, fx->sim->fire_detail, sizeof before);
    CHECK(before[SBFX_FIRE_DETAIL_LEVELS - 1] > before[0] && before[0] > 0.0, "quantiles %g .. %g", before[0],
          before[SBFX_FIRE_DETAIL_LEVELS - 1]);
    e.grey = 0.5f;
    CHECK(reload(fx, e) == SBFX_OK, "%s", sbfx_last_error(fx));
    CHECK(fx->gl->detail_texture == volume, "the volume was made again");
    CHECK(memcmp(before, fx->sim->fire_detail, sizeof before) == 0, "the quantiles changed: %g .. %g", fx->sim->fire_detail[0],
          fx->sim->fire_detail[SBFX_FIRE_DETAIL_LEVELS - 1]);
    sbfx_destroy(fx);
    fixture_close(&f);
}

/* A scene without fire does not make the fire's statistics of its volume (65536 samples of it);
 * a reload that adds fire makes the volume again rather than take one without them, and its
 * quantiles are a fresh fire module's, bit for bit. */
CHECK_TEST(fire_statistics_only_with_fire)
{
    gl_fixture f;
    fixture_open_far(&f, 96, 64);
    edit e = base;
    e.fire = true;
    sbfx *fresh = module_of(&f, e);
    double want[SBFX_FIRE_DETAIL_LEVELS];
    memcpy(want, fresh->sim->fire_detail, sizeof want);
    CHECK(fresh->sim->fire_detail_made && want[0] > 0.0, "a fire module: made %d, quantiles %g ..",
          fresh->sim->fire_detail_made, want[0]);
    sbfx_destroy(fresh);
    sbfx *fx = module_of(&f, base);
    CHECK(fx->gl->detail_texture != 0, "the smoke's detail volume was not made");
    CHECK(!fx->sim->fire_detail_made && fx->sim->fire_detail[SBFX_FIRE_DETAIL_LEVELS - 1] == 0.0,
          "a scene without fire made the fire's statistics");
    CHECK(reload(fx, e) == SBFX_OK, "%s", sbfx_last_error(fx));
    CHECK(fx->sim->fire_detail_made, "the reload with fire took a volume without the fire's statistics");
    CHECK(memcmp(want, fx->sim->fire_detail, sizeof want) == 0, "the quantiles differ from a fresh module's: %g .. %g",
          fx->sim->fire_detail[0], fx->sim->fire_detail[SBFX_FIRE_DETAIL_LEVELS - 1]);
    sbfx_destroy(fx);
    fixture_close(&f);
}

/* The procedural detail volume is taken over while it holds what it was made with; once a host
 * pushed a slice into it, a reload makes a procedural one again (the host pushes again). */
CHECK_TEST(pushed_detail_is_not_taken_over)
{
    gl_fixture f;
    fixture_open_far(&f, 96, 64);
    sbfx *fx = module_of(&f, base);
    GLuint volume = fx->gl->detail_texture;
    CHECK(reload(fx, base) == SBFX_OK, "%s", sbfx_last_error(fx));
    CHECK(fx->gl->detail_texture == volume, "an untouched procedural volume was made again");
    int size = 0, slices = 0;
    sbfx_detail_dimensions(fx, &size, &slices);
    uint16_t *slice = calloc((size_t)size * size, sizeof(uint16_t));
    CHECK(sbfx_detail_push_slice(fx, slice, size) == SBFX_OK, "%s", sbfx_last_error(fx));
    free(slice);
    sbfx_counters before = stats(fx);
    CHECK(reload(fx, base) == SBFX_OK, "%s", sbfx_last_error(fx));
    sbfx_counters after = stats(fx);
    CHECK(fx->gl->detail_texture != volume && !glIsTexture(volume), "the pushed volume %u was kept (now %u)", volume,
          fx->gl->detail_texture);
    CHECK(after.textures == before.textures && after.programs_compiled == before.programs_compiled,
          "textures %d -> %d, %d programs compiled", before.textures, after.textures,
          after.programs_compiled - before.programs_compiled);
    sbfx_destroy(fx);
    fixture_close(&f);
}

CHECK_TEST(reload_leaves_the_host_gl_state_alone)
{
    gl_fixture f;
    fixture_open_far(&f, 96, 64);
    sbfx *fx = module_of(&f, base);
    frames(&f, fx, 3);
    edit e = base;
    e.fire = true;
    e.target_scale = 2;
    /* a host's state: a program, bindings, a viewport and blending of its own */
    GLuint tex = 0, fbo = 0;
    fixture_rgba8_target(8, 8, &tex, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glActiveTexture(GL_TEXTURE3);
    glBindTexture(GL_TEXTURE_2D, tex);
    glViewport(1, 2, 5, 6);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 8);
    snapshot a, b;
    snapshot_take(&a, false);
    CHECK(reload(fx, e) == SBFX_OK, "%s", sbfx_last_error(fx));
    snapshot_take(&b, false);
    char first[128] = "";
    CHECK(snapshot_diff(&a, &b, "sbfx_set_scene", first, sizeof(first)) == 0, "state changed: %s", first);
    CHECK(glGetError() == GL_NO_ERROR, "a GL error left pending");
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &tex);
    sbfx_destroy(fx);
    fixture_close(&f);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
