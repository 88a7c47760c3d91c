/* Effects as functions of identity and time (sbfx_trigger_identified, issue 44): the same
 * (identity, start time, position) gives the same particles whatever the order the triggers
 * arrive in, the frame times, or when the module was made (a late channel catches up); the
 * pictures of two such modules are equal; an instance that has ended is counted, not started;
 * nothing is allocated per frame. The plain calls keep their order-seeded streams. */
#include "gl_fixture.h"
#include "module.h"

#define STEP (1.0 / 120.0)

typedef struct shot {
    const char *effect;
    uint64_t identity;
    double start;
    float at[3];
} shot;

static const shot shots[] = {
    {"explosion", 11, 0.2, {0.0f, 0.0f, 0.0f}},
    {"explosion", 0x0100000100020003ull, 0.5, {4.0f, 0.0f, -2.0f}},
    {"explosion", 7, 0.9, {-3.0f, 0.0f, 1.0f}},
};

/* FNV-1a of one particle; summed over the pool, the hash does not depend on the pool's order. */
static uint64_t particle_hash(const sbfx_pool *p, int i)
{
    uint64_t h = 1469598103934665603ull;
    const struct { const void *data; size_t size; } parts[] = {
        {&p->pos[3 * i], 12}, {&p->vel[3 * i], 12}, {&p->age[i], 4}, {&p->life[i], 4},
        {&p->radius0[i], 4}, {&p->detail[3 * i], 12}, {&p->medium[i], 1}};
    for (size_t k = 0; k < ARRAY_SIZE(parts); k++)
        for (size_t b = 0; b < parts[k].size; b++) h = (h ^ ((const unsigned char *)parts[k].data)[b]) * 1099511628211ull;
    return h;
}

static uint64_t pool_hash(const sbfx *fx)
{
    uint64_t sum = 0;
    for (int i = 0; i < fx->sim->pool.alive; i++) sum += particle_hash(&fx->sim->pool, i);
    return sum ^ (uint64_t)fx->sim->pool.alive;
}

static void fire(sbfx *fx, const shot *s)
{
    sbfx_trigger_desc t = {.version = SBFX_TRIGGER_DESC_VERSION, .effect = s->effect, .identity = s->identity,
                           .start_time = s->start};
    memcpy(t.position, s->at, sizeof(t.position));
    sbfx_result r = sbfx_trigger_identified(fx, &t);
    CHECK(r == SBFX_OK, "trigger %llu: %s", (unsigned long long)s->identity, sbfx_last_error(fx));
}

/* Runs a module from its start to `until` (clock seconds) in updates of dt (the last one cut to
 * land there), firing shot order[k] when the clock passes its start (late: a trigger heard
 * `delay` seconds after its start). */
static void run(sbfx *fx, const int order[3], double dt, double delay, double until)
{
    bool fired[3] = {false, false, false};
    for (;;) {
        double now = sbfx_time(fx);
        for (int k = 0; k < 3; k++) {
            const shot *s = &shots[order[k]];
            if (!fired[order[k]] && now >= s->start + delay) {
                fire(fx, s);
                fired[order[k]] = true;
            }
        }
        if (now >= until - 1e-9) break;
        double step = fmin(dt, until - now);
        CHECK(sbfx_update(fx, step) == SBFX_OK);
        if (step < dt) break;
    }
}

static sbfx *module_at(gl_fixture *f, double start_time)
{
    return fixture_module(f, (sbfx_desc){.ignore_timeline = true, .start_time = start_time});
}

CHECK_TEST(same_identity_and_time_same_particles_in_any_order_and_frame_rate)
{
    gl_fixture f;
    fixture_open(&f, 16, 16);
    static const int orders[][3] = {{0, 1, 2}, {2, 1, 0}, {1, 2, 0}};
    static const double dts[] = {1.0 / 30.0, 1.0 / 144.0, 0.1};
    static const double delays[] = {0.0, 0.05, 0.3}; /* heard late: drawn at its age all the same */
    uint64_t first = 0;
    for (int v = 0; v < 3; v++) {
        sbfx *fx = module_at(&f, 0.0);
        run(fx, orders[v], dts[v], delays[v], 1.5);
        uint64_t h = pool_hash(fx);
        CHECK(fx->sim->pool.alive > 300, "variant %d: %d particles", v, fx->sim->pool.alive);
        if (v == 0) first = h;
        else CHECK(h == first, "variant %d (order %d%d%d, dt %.4f, heard %.2f s late): %llx, want %llx", v,
                   orders[v][0], orders[v][1], orders[v][2], dts[v], delays[v], (unsigned long long)h,
                   (unsigned long long)first);
        sbfx_destroy(fx);
    }
    fixture_close(&f);
}

/* A channel made 1.2 s into the exercise hears of the three at once and shows them at their age. */
CHECK_TEST(late_start_catches_up_to_the_same_particles_and_pixels)
{
    gl_fixture f;
    fixture_open(&f, 96, 64);
    sbfx_perspective(f.frame.projection, 1.0f, 1.5f, 0.5f, 200.0f);
    const float eye[3] = {0, 3, 18}, target[3] = {0, 2, 0}, up[3] = {0, 1, 0};
    sbfx_look_at(f.frame.view, eye, target, up);
    fixture_depth(&f, depth_far_everywhere, NULL);
    static const int order[3] = {0, 1, 2}, reverse[3] = {2, 0, 1};
    sbfx *early = module_at(&f, 0.0), *late = module_at(&f, 1.2);
    run(early, order, 1.0 / 60.0, 0.0, 2.0);
    run(late, reverse, 1.0 / 24.0, 0.0, 2.0);
    CHECK(pool_hash(early) == pool_hash(late), "late %llx, early %llx", (unsigned long long)pool_hash(late),
          (unsigned long long)pool_hash(early));
    uint8_t *a = malloc(96 * 64 * 4), *b = malloc(96 * 64 * 4);
    int lit = 0, differ = 0, maxd = 0;
    sbfx *mods[2] = {early, late};
    uint8_t *px[2] = {a, b};
    for (int m = 0; m < 2; m++) {
        glBindFramebuffer(GL_FRAMEBUFFER, f.out_fbo);
        glClearColor(0, 0, 0, 0);
        glClear(GL_COLOR_BUFFER_BIT);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        CHECK(sbfx_render(mods[m], &f.frame) == SBFX_OK, "%s", sbfx_last_error(mods[m]));
        glBindFramebuffer(GL_FRAMEBUFFER, f.out_fbo);
        glReadPixels(0, 0, 96, 64, GL_RGBA, GL_UNSIGNED_BYTE, px[m]);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }
    for (int i = 0; i < 96 * 64 * 4; i++) {
        lit += a[i] != 0;
        differ += a[i] != b[i];
        if (abs(a[i] - b[i]) > maxd) maxd = abs(a[i] - b[i]);
    }
    printf("# %d lit channel values, largest difference %d\n", lit, maxd);
    CHECK(lit > 500, "only %d lit channels: the explosion is not in view", lit);
    CHECK(differ == 0, "%d channel values differ between the early and the late module", differ);
    free(a);
    free(b);
    sbfx_destroy(early);
    sbfx_destroy(late);
    fixture_close(&f);
}

/* Another identity is another explosion; the plain sbfx_trigger's stream depends on the order
 * (what the identity is for), and the identity's does not depend on desc.seed. */
CHECK_TEST(identity_alone_chooses_the_particles)
{
    gl_fixture f;
    fixture_open(&f, 16, 16);
    sbfx *a = module_at(&f, 0.0), *b = module_at(&f, 0.0);
    sbfx *c = fixture_module(&f, (sbfx_desc){.ignore_timeline = true, .seed = 77});
    shot s = shots[0];
    fire(a, &s);
    fire(c, &s);
    s.identity = 12;
    fire(b, &s);
    CHECK(sbfx_update(a, 0.5) == SBFX_OK && sbfx_update(b, 0.5) == SBFX_OK && sbfx_update(c, 0.5) == SBFX_OK);
    CHECK(pool_hash(a) != pool_hash(b), "identities 11 and 12 gave the same particles");
    CHECK(pool_hash(a) == pool_hash(c), "desc.seed changed an identified instance");
    sbfx_destroy(a), sbfx_destroy(b), sbfx_destroy(c);
    /* plain triggers: order-seeded as before */
    sbfx *p = module_at(&f, 0.0), *q = module_at(&f, 0.0);
    const float o[3] = {0, 0, 0}, x[3] = {5, 0, 0};
    CHECK(sbfx_trigger(p, "explosion", o) == SBFX_OK && sbfx_trigger(p, "explosion", x) == SBFX_OK);
    CHECK(sbfx_trigger(q, "explosion", x) == SBFX_OK && sbfx_trigger(q, "explosion", o) == SBFX_OK);
    CHECK(sbfx_update(p, 0.5) == SBFX_OK && sbfx_update(q, 0.5) == SBFX_OK);
    CHECK(pool_hash(p) != pool_hash(q), "plain triggers in another order gave the same particles");
    sbfx_destroy(p), sbfx_destroy(q);
    fixture_close(&f);
}

CHECK_TEST(ended_instances_are_counted_bad_ones_refused_nothing_allocated)
{
    gl_fixture f;
    fixture_open(&f, 16, 16);
    sbfx_perspective(f.frame.projection, 1.0f, 1.0f, 0.5f, 200.0f);
    sbfx *fx = module_at(&f, 100.0);
    int seen = 0;
    shot old = shots[0];
    fire(fx, &old); /* started at 0.2, the module's clock is at 100: long over */
    sbfx_counters c;
    sbfx_stats(fx, &c);
    CHECK(sbfx_triggers_expired(fx) == 1 && c.triggers_fired == 0 && c.particles_alive == 0,
          "expired %d fired %d alive %d", sbfx_triggers_expired(fx), c.triggers_fired, c.particles_alive);
    sbfx_trigger_desc t = {.version = 2, .effect = "explosion", .identity = 1, .start_time = 100.0};
    CHECK(sbfx_trigger_identified(fx, &t) == SBFX_ERR_INVALID_ARGUMENT, "version 2 accepted");
    t.version = SBFX_TRIGGER_DESC_VERSION;
    t.identity = 0;
    CHECK(sbfx_trigger_identified(fx, &t) == SBFX_ERR_INVALID_ARGUMENT, "identity 0 accepted");
    t.identity = UINT64_C(1) << 63;
    CHECK(sbfx_trigger_identified(fx, &t) == SBFX_ERR_INVALID_ARGUMENT, "identity 2^63 accepted");
    t.identity = 5;
    t.start_time = NAN;
    CHECK(sbfx_trigger_identified(fx, &t) == SBFX_ERR_INVALID_ARGUMENT, "a NaN start accepted");
    t.start_time = 100.5;
    t.effect = "nothing";
    CHECK(sbfx_trigger_identified(fx, &t) == SBFX_ERR_UNKNOWN_EFFECT, "an unknown effect accepted");
    t.effect = "explosion";
    sbfx_stats(fx, &c);
    uint64_t allocs = c.heap_allocs_after_load;
    CHECK(sbfx_trigger_identified(fx, &t) == SBFX_OK, "%s", sbfx_last_error(fx)); /* ahead: waits */
    sbfx_stats(fx, &c);
    CHECK(c.particles_alive > 0, "a trigger ahead of the clock was not kept");
    for (int i = 0; i < 120; i++) {
        CHECK(sbfx_update(fx, 1.0 / 60.0) == SBFX_OK);
        CHECK(sbfx_render(fx, &f.frame) == SBFX_OK);
        sbfx_stats(fx, &c);
        seen += c.particles_alive;
    }
    CHECK(seen > 0);
    sbfx_stats(fx, &c);
    CHECK(c.heap_allocs_after_load == allocs, "%llu allocations in 120 frames",
          (unsigned long long)(c.heap_allocs_after_load - allocs));
    sbfx_destroy(fx);
    fixture_close(&f);
}

/* CIGI's Destroyed: sbfx_stop_identified ends one instance, the others go on. */
CHECK_TEST(stop_ends_one_instance)
{
    gl_fixture f;
    fixture_open(&f, 16, 16);
    sbfx *fx = module_at(&f, 0.0);
    fire(fx, &shots[0]);
    fire(fx, &shots[1]);
    CHECK(sbfx_update(fx, 1.0) == SBFX_OK);
    int before = fx->sim->pool.alive;
    int removed = sbfx_stop_identified(fx, shots[0].identity);
    CHECK(removed > 0 && fx->sim->pool.alive == before - removed, "removed %d of %d", removed, before);
    for (int i = 0; i < fx->sim->pool.alive; i++)
        CHECK(fx->sim->pool.identity[i] == shots[1].identity, "a particle of %llu is left",
              (unsigned long long)fx->sim->pool.identity[i]);
    CHECK(sbfx_stop_identified(fx, shots[0].identity) == 0, "stopped twice");
    CHECK(sbfx_stop_identified(fx, 0) == SBFX_ERR_INVALID_ARGUMENT);
    sbfx_destroy(fx);
    fixture_close(&f);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
