/* The plan: only what a scene uses is created; idle costs nothing; the simulation is
 * deterministic whatever the frame times; a full pool refuses triggers cleanly. */
#include "gl_fixture.h"
#include "module.h"
#include "render/tiles.h"

#define BLACKBODY_BYTES (SBFX_BLACKBODY_SIZE * 16)
#define PHASE_BYTES (SBFX_PHASE_SIZE * SBFX_MEDIUM_COUNT * 4)
#define DETAIL_BYTES (128 * 128 * 32 * 2) /* the default R16F detail volume (docs/look.md) */

typedef struct plan {
    const char *scene;
    int particle_programs; /* one per medium used */
    int post_programs;     /* copy (+ 6 velocity blur: tile max, neighbour max, blocks, gather, its fast path, copy; + the velocity
                              pass without depth of field, whose composite writes them; + 5 depth of field:
                              blur, setup and composite inside and outside the tiles; + 1 history blur) */
    bool blackbody, phase;
    int max_particles;
    int shadow_map;        /* render.host_shadows: the host's shadow map, texels per side (0: none) */
    bool fire_light;       /* emitting fire lights dust or smoke: + its light per particle */
} plan;

static const plan plans[] = {
    /* no phase table: the analytic phase is the default (issue 43), a scene asks for the table */
    {"explosion", 3, 0, true, false, 2048, 256, true},
    {"smoke", 1, 0, false, false, 512, 256, false},
    {"campfire", 3, 1, true, false, 1024, 256, true},   /* heat: shimmer owns the scene, a copy program */
    {"dust-storm", 1, 0, false, false, 1024, 256, false},
    {"barrage", 3, 0, true, false, 4096, 256, true},
    {"post", 4, 1 + 6 + 5, true, false, 2048, 0, true},
};

CHECK_TEST(plan_holds_only_what_each_scene_uses)
{
    gl_fixture f;
    fixture_open(&f, 64, 64);
    for (size_t i = 0; i < ARRAY_SIZE(plans); i++) {
        const plan *want = &plans[i];
        sbfx_scene *scene = fixture_load_scene(want->scene);
        sbfx *fx = fixture_module(&f, (sbfx_desc){.scene = scene});
        sbfx_scene_free(scene);
        sbfx_counters c;
        sbfx_stats(fx, &c);
        int textures = want->blackbody + want->phase + 1 + (want->shadow_map > 0); /* + the detail volume */
        int instance_bytes = (strcmp(want->scene, "post") == 0 ? 48 : 32) /* + previous centre */
                             + (want->fire_light ? 32 : 0);                 /* + the fire's light */
        size_t bytes = (want->blackbody ? BLACKBODY_BYTES : 0) + (want->phase ? PHASE_BYTES : 0) +
                       DETAIL_BYTES + (size_t)want->max_particles * instance_bytes +
                       sizeof(((sbfx_tiles *)0)->rects); /* the tiles' rectangles (render/tiles.h) */
        /* the shadow map (made at load: RGBA16F, or RGBA8 where half floats do not render) and its
         * instance buffer of 5 floats per particle */
        if (want->shadow_map)
            bytes += (size_t)want->shadow_map * want->shadow_map * (sbfx_half_float_renderable() ? 8 : 4) +
                     (size_t)want->max_particles * 20;
        printf("# %-10s programs %d textures %d framebuffers %d gpu_bytes %zu\n", want->scene, c.programs,
               c.textures, c.framebuffers, c.gpu_bytes);
        /* + depth, composite and (where RGBA32F renders) the low-res corners; with post effects the
         * composite's scene outside the tiles (composite.frag SCENE_ONLY) */
        CHECK(c.programs == want->particle_programs + 2 + sbfx_float32_renderable() + want->post_programs +
                                (want->post_programs > 0) + (want->shadow_map > 0), "%s: %d programs", want->scene,
              c.programs);
        CHECK(c.textures == textures, "%s: %d textures, want %d", want->scene, c.textures, textures);
        CHECK(c.framebuffers == (want->shadow_map > 0), "%s: targets exist before the first frame", want->scene);
        CHECK(c.gpu_bytes == bytes, "%s: %zu GPU bytes, want %zu", want->scene, c.gpu_bytes, bytes);
        CHECK(sbfx_fire_lit(fx) == want->fire_light, "%s: fire light %d", want->scene, sbfx_fire_lit(fx));
        sbfx_destroy(fx);
    }
    fixture_close(&f);
}

CHECK_TEST(idle_scene_simulates_and_draws_nothing)
{
    gl_fixture f;
    fixture_open_far(&f, 64, 64);
    sbfx_scene *scene = fixture_load_scene("barrage");
    sbfx *fx = fixture_module(&f, (sbfx_desc){.scene = scene, .ignore_timeline = true});
    sbfx_scene_free(scene);
    for (int i = 0; i < 30; i++) {
        CHECK(sbfx_update(fx, 1.0 / 30) == SBFX_OK);
        CHECK(sbfx_render(fx, &f.frame) == SBFX_OK);
        sbfx_counters c;
        sbfx_stats(fx, &c);
        /* barrage.cfg asks for host_shadows: its shadow map's framebuffer is made at load */
        CHECK(c.passes == 0 && c.draw_calls == 0 && c.particles_simulated == 0 && c.framebuffers == 1,
              "frame %d: %d passes %d draws %d simulated", i, c.passes, c.draw_calls, c.particles_simulated);
    }
    sbfx_destroy(fx);
    fixture_close(&f);
}

/* Advances to exactly `steps` simulation steps with frame times from `next_dt`. */
static uint64_t run_to_step(sbfx *fx, int steps, double (*next_dt)(sbfx_rng *), sbfx_rng *rng)
{
    const double step = 1.0 / 120.0;
    while (sbfx_time(fx) < steps * step - 1e-6) CHECK(sbfx_update(fx, next_dt(rng)) == SBFX_OK);
    CHECK(fabs(sbfx_time(fx) - steps * step) < 1e-6, "overshot to %.6f s", sbfx_time(fx));
    return sbfx_state_hash(fx);
}

static double steady_dt(sbfx_rng *rng) { (void)rng; return 1.0 / 120.0; }
static double jittery_dt(sbfx_rng *rng) { return sbfx_rng_range(rng, 0.0, 1.0 / 120.0); }
static double tiny_dt(sbfx_rng *rng) { (void)rng; return 1.0 / 1000.0; }

CHECK_TEST(simulation_is_deterministic_across_frame_times)
{
    gl_fixture f;
    fixture_open(&f, 16, 16);
    sbfx_scene *scene = fixture_load_scene("barrage");
    double (*sequences[])(sbfx_rng *) = {steady_dt, jittery_dt, tiny_dt};
    uint64_t hashes[3];
    for (int s = 0; s < 3; s++) {
        sbfx *fx = fixture_module(&f, (sbfx_desc){.scene = scene});
        sbfx_rng rng;
        sbfx_rng_seed(&rng, 99 + s);
        hashes[s] = run_to_step(fx, 300, sequences[s], &rng); /* 2.5 s: many instances live */
        sbfx_counters c;
        sbfx_stats(fx, &c);
        CHECK(c.particles_alive > 1000, "only %d particles alive", c.particles_alive);
        sbfx_destroy(fx);
    }
    CHECK(hashes[0] == hashes[1] && hashes[1] == hashes[2], "states differ: %llx %llx %llx",
          (unsigned long long)hashes[0], (unsigned long long)hashes[1], (unsigned long long)hashes[2]);
    sbfx *other_seed = fixture_module(&f, (sbfx_desc){.scene = scene, .seed = 2});
    sbfx_rng rng;
    sbfx_rng_seed(&rng, 1);
    CHECK(run_to_step(other_seed, 300, steady_dt, &rng) != hashes[0], "a different seed gave the same state");
    sbfx_destroy(other_seed);
    sbfx_scene_free(scene);
    fixture_close(&f);
}

/* Pool full: the trigger is refused and counted, live instances keep going, and room made by
 * dying particles is used again. */
CHECK_TEST(full_pool_refuses_triggers_without_harm)
{
    gl_fixture f;
    fixture_open(&f, 16, 16);
    sbfx *fx = fixture_module(&f, (sbfx_desc){.max_particles = 200, .ignore_timeline = true});
    const float at[3] = {0, 0, 0};
    CHECK(sbfx_trigger(fx, "explosion", at) == SBFX_OK);
    CHECK(sbfx_trigger(fx, "explosion", at) == SBFX_ERR_POOL_FULL);
    CHECK(strstr(sbfx_last_error(fx), "refused") != NULL, "%s", sbfx_last_error(fx));
    CHECK(sbfx_schedule(fx, "explosion", 0.5, at) == SBFX_OK);
    for (int i = 0; i < 60; i++) sbfx_update(fx, 1.0 / 60);
    sbfx_counters c;
    sbfx_stats(fx, &c);
    CHECK(c.triggers_fired == 1 && c.triggers_refused == 2, "fired %d refused %d", c.triggers_fired,
          c.triggers_refused);
    CHECK(c.particles_alive == 159, "%d alive", c.particles_alive);
    for (int i = 0; i < 240; i++) sbfx_update(fx, 1.0 / 60); /* the first instance dies out */
    CHECK(sbfx_trigger(fx, "explosion", at) == SBFX_OK, "%s", sbfx_last_error(fx));
    CHECK(sbfx_trigger(fx, "no-such-effect", at) == SBFX_ERR_UNKNOWN_EFFECT);
    sbfx_destroy(fx);
    fixture_close(&f);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
