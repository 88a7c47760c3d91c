/* Tiles change no pixel (issue 33; src/render/tiles.h): the composite, the depth downsample and
 * the low-res corners draw only the screen tiles the particles can change, where sbfx owns the
 * scene the rest is the scene as the composite reads it, and each particle is drawn as an
 * octagon, its rectangle's empty corners cut (particle.vert). Every frame here is rendered
 * twice, by two modules made and advanced alike: one as it is, one as before (the composite over
 * the whole screen, whole rectangles: sbfx_tiles.full_screen), and the two images must be equal
 * byte for byte — over the life of every example scene from its own camera, and for the cases
 * where a footprint is easiest to get wrong: a particle at a tile's edge, partly off the screen,
 * a huge particle around the eye or across the near plane, heat shimmer at a tile's edge, every
 * kind of projection, every divisor and both upsamplings. The small tiles (8 pixels: two low-res
 * texels at the default divisor) put an edge next to every footprint. Also the counters:
 * composite_tiles and composite_pixels. */
#include "gl_fixture.h"
#include "host/test_scene.h"

#define W 160
#define H 96

/* ---- two modules, one frame each ---------------------------------------------------------- */

typedef struct pair {
    sbfx *tiled, *full;
} pair;

static pair pair_make(gl_fixture *f, sbfx_desc desc, int tile_size)
{
    pair p = {fixture_module(f, desc), fixture_module(f, desc)};
    p.tiled->render->tiles.size_wanted = tile_size;
    p.full->render->tiles.full_screen = true;
    return p;
}

static void pair_destroy(pair *p)
{
    sbfx_destroy(p->tiled);
    sbfx_destroy(p->full);
}

/* The host's picture, its own framebuffer's colour, into the output (as a host composites over
 * its frame), then one sbfx frame: the module's particles, or the n view particles v. */
static void render_one(gl_fixture *f, GLuint host_fbo, sbfx *fx, const sbfx_view_particle *v, int n, uint8_t *out,
                       sbfx_counters *c)
{
    glBindFramebuffer(GL_READ_FRAMEBUFFER, host_fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, f->out_fbo);
    if (fx->scene->plan.owns_scene) { /* sbfx writes every pixel: what it misses stays magenta */
        glClearColor(1.0f, 0.0f, 1.0f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
    } else {
        glBlitFramebuffer(0, 0, f->width, f->height, 0, 0, f->width, f->height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    sbfx_result r = v ? sbfx_render_view_particles(fx, &f->frame, v, n) : sbfx_render(fx, &f->frame);
    CHECK(r == SBFX_OK, "%s", sbfx_last_error(fx));
    sbfx_stats(fx, c);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, f->out_fbo);
    glReadPixels(0, 0, f->width, f->height, GL_RGBA, GL_UNSIGNED_BYTE, out);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
}

typedef struct comparison {
    int differing;          /* bytes that differ */
    int first;              /* the first differing pixel, -1: none */
    sbfx_counters tiled, full;
} comparison;

static comparison pair_render(gl_fixture *f, GLuint host_fbo, pair *p, const sbfx_view_particle *v, int n)
{
    static uint8_t a[W * H * 4], b[W * H * 4];
    comparison c = {.first = -1};
    render_one(f, host_fbo, p->tiled, v, n, a, &c.tiled);
    render_one(f, host_fbo, p->full, v, n, b, &c.full);
    for (int i = 0; i < f->width * f->height * 4; i++)
        if (a[i] != b[i]) {
            if (c.first < 0) c.first = i / 4;
            c.differing++;
        }
    return c;
}

static void check_same(const comparison *c, const char *what)
{
    CHECK(c->differing == 0, "%s: %d bytes differ from the full-screen composite, the first at pixel (%d, %d); "
          "%d tiles", what, c->differing, c->first % W, c->first / W, c->tiled.composite_tiles);
}

/* ---- the example scenes over their life --------------------------------------------------- */

#define STEP (1.0 / 30.0)
#define SAMPLE 10 /* steps between compared frames: a third of a second */

/* Every compared frame of scenes/NAME.cfg from its camera over the test scene, until its last
 * particle died (at most 8 s); returns the share of the screen the tiles covered, on average. */
static double scene_over_its_life(const char *name)
{
    gl_fixture f;
    fixture_open(&f, W, H);
    char err[256];
    struct test_scene host;
    CHECK(test_scene_create(&host, W, H, err, sizeof(err)) == 0, "%s", err);
    sbfx_scene *scene = fixture_load_scene(name);
    sbfx_scene_camera camera;
    bool has_camera = sbfx_scene_camera_get(scene, &camera);
    pair p = pair_make(&f, (sbfx_desc){.scene = scene}, 8);
    sbfx_scene_free(scene);
    f.frame.scene_color_texture = host.color_texture;
    f.frame.scene_depth_texture = host.depth_texture;
    int frames = 0, differing = 0;
    double covered = 0.0;
    for (int step = 1; step <= 8 * 30; step++) {
        CHECK(sbfx_update(p.tiled, STEP) == SBFX_OK && sbfx_update(p.full, STEP) == SBFX_OK);
        if (step % SAMPLE) continue;
        double t = sbfx_time(p.tiled);
        if (has_camera) test_scene_camera(&camera, t, (float)W / H, f.frame.view, f.frame.projection);
        else test_scene_orbit_camera(t, (float)W / H, f.frame.view, f.frame.projection);
        CHECK(test_scene_draw(&host, f.frame.view, f.frame.projection) == 0);
        comparison c = pair_render(&f, host.framebuffer, &p, NULL, 0);
        if (c.differing && !differing) {
            char what[96];
            snprintf(what, sizeof(what), "%s at %.2f s", name, t);
            check_same(&c, what);
        }
        differing += c.differing;
        frames++;
        covered += (double)c.tiled.composite_pixels / (W * H);
        if (t > 1.0 && c.tiled.particles_alive == 0) break;
    }
    printf("# %s: %d frames over its life, %d bytes differ; the tiles covered %.0f %% of the screen on "
           "average\n", name, frames, differing, 100.0 * covered / frames);
    CHECK(differing == 0, "%s: %d bytes differ over %d frames", name, differing, frames);
    CHECK(glGetError() == GL_NO_ERROR);
    pair_destroy(&p);
    test_scene_destroy(&host);
    fixture_close(&f);
    return covered / frames;
}

CHECK_TEST(explosion_over_its_life) { CHECK(scene_over_its_life("explosion") < 0.9); }
CHECK_TEST(barrage_over_its_life) { scene_over_its_life("barrage"); }
CHECK_TEST(campfire_over_its_life) { CHECK(scene_over_its_life("campfire") < 0.9); }
CHECK_TEST(dust_storm_over_its_life) { scene_over_its_life("dust-storm"); }
CHECK_TEST(lit_smoke_over_its_life) { scene_over_its_life("lit-smoke"); }
CHECK_TEST(night_over_its_life) { scene_over_its_life("night"); }
CHECK_TEST(post_over_its_life) { CHECK(scene_over_its_life("post") < 0.9); }
CHECK_TEST(smoke_over_its_life) { scene_over_its_life("smoke"); }

/* ---- particles placed where a footprint is easiest to get wrong --------------------------- */

/* A host picture with edges everywhere: colour checks, and opaque distances in narrow bands
 * (5.8 m, among the particles, 9 m and nothing), so nearest-depth upsampling picks texels by
 * depth all over; the bands trade places from one set of particles to the next, so that a
 * low-res depth the tiles failed to update is the last frame's, not this one's. */
static double banded_distance(int x, int y, void *user)
{
    int set = *(const int *)user, band = (x / 3 + y / 5 + set) % 3;
    return band == 0 ? 5.8 : band == 1 ? 9.0 : INFINITY;
}

typedef struct host_picture {
    GLuint texture, fbo;
} host_picture;

static host_picture host_open(gl_fixture *f)
{
    host_picture h;
    fixture_rgba8_target(f->width, f->height, &h.texture, &h.fbo);
    static uint8_t rgba[W * H * 4];
    for (int y = 0; y < f->height; y++)
        for (int x = 0; x < f->width; x++) {
            uint8_t *p = &rgba[4 * (y * f->width + x)];
            bool check = ((x / 5) ^ (y / 5)) & 1;
            p[0] = (uint8_t)(40 + 3 * x % 200), p[1] = check ? 200 : 60, p[2] = (uint8_t)(30 + 2 * y), p[3] = 255;
        }
    glBindTexture(GL_TEXTURE_2D, h.texture);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, f->width, f->height, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    glBindTexture(GL_TEXTURE_2D, 0);
    int shift = 0;
    fixture_depth(f, banded_distance, &shift);
    f->frame.scene_color_texture = h.texture;
    return h;
}

static void host_close(host_picture *h)
{
    glDeleteFramebuffers(1, &h->fbo);
    glDeleteTextures(1, &h->texture);
}

/* A particle of `medium` whose centre projects to output pixel (x, y), `distance` m in front of
 * the eye along -z, with radius r. */
static sbfx_view_particle particle_at(const gl_fixture *f, double x, double y, double distance, double r,
                                      sbfx_medium medium)
{
    double ray[3];
    const float *p = f->frame.projection;
    double ndc_x = x / f->width * 2.0 - 1.0, ndc_y = y / f->height * 2.0 - 1.0;
    ray[0] = (ndc_x + p[8]) / p[0], ray[1] = (ndc_y + p[9]) / p[5], ray[2] = -1.0;
    return (sbfx_view_particle){.center = {(float)(ray[0] * distance), (float)(ray[1] * distance), (float)-distance},
                                .radius = (float)r, .detail = {0.3f, 0.6f, 0.1f}, .intensity = 1.0f,
                                .medium = medium};
}

/* A case: its index-th set of view particles. */
typedef void (*case_fn)(const gl_fixture *f, int index, sbfx_view_particle *out, int *n);

/* The sets of a case through a pair of modules; those whose tiles left part of the screen out. */
static int run_sets(gl_fixture *f, const host_picture *h, pair *p, int tile_size, case_fn make, int sets,
                    const char *what, bool hard)
{
    int partial = 0;
    for (int i = 0; i < sets; i++) {
        sbfx_view_particle v[16];
        int n = 0;
        make(f, i, v, &n);
        fixture_depth(f, banded_distance, &i);
        comparison c = pair_render(f, h->fbo, p, v, n);
        char name[128];
        snprintf(name, sizeof(name), "%s, tiles of %d px, set %d%s", what, tile_size, i, hard ? ", hard rims" : "");
        check_same(&c, name);
        CHECK(c.tiled.composite_pixels <= f->width * f->height && c.full.composite_pixels == f->width * f->height,
              "%s: %d pixels composited (full screen: %d)", name, c.tiled.composite_pixels, c.full.composite_pixels);
        partial += c.tiled.composite_pixels < f->width * f->height;
    }
    CHECK(glGetError() == GL_NO_ERROR);
    return partial;
}

/* Media with hard rims: a density that makes a particle opaque to its silhouette's last texel,
 * and a stronger shimmer, so that a pixel the tiles miss shows (a rim of the scene's media is
 * below an 8-bit level). */
static void pair_harden(pair *p)
{
    sbfx *both[2] = {p->tiled, p->full};
    for (int k = 0; k < 2; k++)
        for (int m = 0; m < SBFX_MEDIUM_COUNT; m++) {
            sbfx_media(both[k])[m].tau = 1e5f;
            sbfx_media(both[k])[m].heat_strength = 0.05f;
        }
}

/* Every view-particle set of a case, through a pair of modules made from desc (tiles of
 * `tile_size`), over the banded host picture, with the scene's media and with hard rims;
 * returns the sets whose tiles left part of the screen out. */
static int run_case(gl_fixture *f, sbfx_desc desc, int tile_size, case_fn make, int sets, const char *what)
{
    int partial = 0;
    for (int hard = 0; hard < 2; hard++) {
        host_picture h = host_open(f);
        pair p = pair_make(f, desc, tile_size);
        if (hard) pair_harden(&p);
        partial += run_sets(f, &h, &p, tile_size, make, sets, what, hard);
        pair_destroy(&p);
        host_close(&h);
    }
    return partial / 2;
}

/* Small puffs swept across tiles' edges a quarter of a pixel at a time, in x and in y (their
 * rims cross the edges at every phase of the low-res texels). */
#define SWEEP 32
static void sweep_across_an_edge(const gl_fixture *f, int i, sbfx_view_particle *out, int *n)
{
    double s = 60.0 + (i % SWEEP) / 4.0;
    out[0] = i < SWEEP ? particle_at(f, s, 40.0, 6.0, 0.25, SBFX_SMOKE) : particle_at(f, 90.0, s - 16.0, 6.0, 0.25, SBFX_FIRE);
    out[1] = particle_at(f, 40.0 + (i % SWEEP) * 0.37, 72.0 - (i % SWEEP) * 0.29, 5.0, 0.12, SBFX_DUST);
    out[2] = particle_at(f, 120.0 - (i % SWEEP) * 0.23, 20.0 + (i % SWEEP) * 0.27, 7.0, 0.2, SBFX_SMOKE);
    /* past a tile's corner along the diagonals, where the octagon's cut edges lie */
    double k = (i % SWEEP) / 4.0;
    out[3] = particle_at(f, 28.0 + k, 28.0 + k, 6.0, 0.25, SBFX_FIRE);
    out[4] = particle_at(f, 140.0 - k, 36.0 + k, 6.0, 0.25, SBFX_SMOKE);
    *n = 5;
}

CHECK_TEST(a_particle_at_a_tile_edge)
{
    gl_fixture f;
    fixture_open(&f, W, H);
    fixture_projection(&f, 1.0f, 0.1f, 100.0f);
    int sizes[] = {8, SBFX_TILE_SIZE}; /* the smallest (an edge by every footprint) and the default */
    for (size_t k = 0; k < ARRAY_SIZE(sizes); k++)
        for (int d = 1; d <= 4; d *= 4) {
            sbfx_desc desc = {.max_particles = 16, .target_divisor = d};
            CHECK(run_case(&f, desc, sizes[k], sweep_across_an_edge, 2 * SWEEP, d == 1 ? "edge sweep at 1/1" : "edge sweep") ==
                  2 * SWEEP, "the tiles covered the whole screen");
        }
    fixture_close(&f);
}

/* Puffs centred beyond each side and corner of the screen, reaching into it. */
static void off_screen(const gl_fixture *f, int i, sbfx_view_particle *out, int *n)
{
    static const double at[8][2] = {{-6, 48}, {166, 40}, {80, -7}, {70, 103}, {-5, -5}, {165, 101}, {-4, 100}, {163, -3}};
    out[0] = particle_at(f, at[i][0], at[i][1], 6.0, 0.5 + 0.1 * i, i % 2 ? SBFX_FIRE : SBFX_SMOKE);
    out[1] = particle_at(f, at[i][0] * 0.97 + 2.0, at[i][1] * 0.97 + 1.5, 7.0, 0.3, SBFX_DUST);
    *n = 2;
}

CHECK_TEST(a_particle_partly_off_screen)
{
    gl_fixture f;
    fixture_open(&f, W, H);
    fixture_projection(&f, 1.0f, 0.1f, 100.0f);
    CHECK(run_case(&f, (sbfx_desc){.max_particles = 16}, 8, off_screen, 8, "off screen") == 8);
    CHECK(run_case(&f, (sbfx_desc){.max_particles = 16}, SBFX_TILE_SIZE, off_screen, 8, "off screen") > 0);
    fixture_close(&f);
}

/* The eye inside a huge particle; one reaching across the near plane; one just in front of it;
 * one wholly behind it (drawn by nobody): with small puffs around. */
static void around_the_eye(const gl_fixture *f, int i, sbfx_view_particle *out, int *n)
{
    const double near = 0.1;
    double distance[4] = {1.0, 2.0, 3.0 + near + 1e-5, -0.5};
    double radius[4] = {2.5, 2.0 - 0.5 * near, 3.0, 0.3};
    out[0] = particle_at(f, 70.0, 50.0, distance[i], radius[i], SBFX_SMOKE);
    out[1] = particle_at(f, 20.0, 20.0, 6.0, 0.2, SBFX_FIRE);
    *n = 2;
}

CHECK_TEST(a_huge_particle_around_the_eye)
{
    gl_fixture f;
    fixture_open(&f, W, H);
    fixture_projection(&f, 1.0f, 0.1f, 100.0f);
    int partial = run_case(&f, (sbfx_desc){.max_particles = 16}, 8, around_the_eye, 4, "around the eye");
    CHECK(partial == 1, "%d of 4 sets composited part of the screen: only the one whose big particle is behind "
          "the eye may", partial);
    fixture_close(&f);
}

/* Heat beside smoke at tile edges (campfire's media: sbfx owns the scene for its shimmer, so the
 * pixels outside the tiles are the scene copied). */
static void heat_at_an_edge(const gl_fixture *f, int i, sbfx_view_particle *out, int *n)
{
    double s = 48.0 + i * 0.7;
    out[0] = particle_at(f, s, 48.0, 5.0, 0.35, SBFX_HEAT);
    out[1] = particle_at(f, 110.0, s, 5.0, 0.3, SBFX_HEAT);
    out[2] = particle_at(f, s + 30.0, 70.0, 6.0, 0.25, SBFX_SMOKE);
    *n = 3;
}

CHECK_TEST(shimmer_near_a_tile_edge)
{
    gl_fixture f;
    fixture_open(&f, W, H);
    fixture_projection(&f, 1.0f, 0.1f, 100.0f);
    sbfx_scene *scene = fixture_load_scene("campfire");
    sbfx_desc desc = {.scene = scene, .ignore_timeline = true};
    CHECK(run_case(&f, desc, 8, heat_at_an_edge, 12, "shimmer") == 12);
    CHECK(run_case(&f, desc, SBFX_TILE_SIZE, heat_at_an_edge, 12, "shimmer") > 0);
    sbfx_scene_free(scene);
    fixture_close(&f);
}

/* A handful of puffs near the edges and corners, for the projections and levels below. */
static void scattered(const gl_fixture *f, int i, sbfx_view_particle *out, int *n)
{
    static const double at[6][2] = {{3, 50}, {157, 44}, {81, 2}, {77, 94}, {40, 30}, {120, 70}};
    for (int k = 0; k < 6; k++)
        out[k] = particle_at(f, at[k][0] + i * 0.45, at[k][1] - i * 0.3, 4.0 + k, 0.15 + 0.05 * k, (sbfx_medium)(k % 3));
    *n = 6;
}

CHECK_TEST(every_projection)
{
    gl_fixture f;
    fixture_open(&f, W, H);
    for (int v = 0; v < 3; v++) {
        f.frame.clip_depth_mode = SBFX_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE;
        if (v == 0) sbfx_frustum(f.frame.projection, -0.03f, 0.09f, -0.05f, 0.02f, 0.1f, 100.0f); /* off-axis */
        if (v == 1) sbfx_perspective(f.frame.projection, 1.1f, (float)W / H, 0.1f, INFINITY);
        if (v == 2) { /* reversed-Z, infinite far, [0, 1] */
            sbfx_perspective(f.frame.projection, 0.9f, (float)W / H, 0.1f, INFINITY);
            sbfx_reverse_z(f.frame.projection, 0.1f, INFINITY);
            f.frame.clip_depth_mode = SBFX_CLIP_DEPTH_ZERO_TO_ONE;
        }
        const char *names[3] = {"off-axis", "infinite far", "reversed-Z"};
        CHECK(run_case(&f, (sbfx_desc){.max_particles = 16}, 8, scattered, 4, names[v]) == 4);
    }
    fixture_close(&f);
}

CHECK_TEST(every_divisor_and_upsampling)
{
    gl_fixture f;
    fixture_open(&f, W, H);
    fixture_projection(&f, 1.0f, 0.1f, 100.0f);
    int divisors[] = {1, 2, 4, 8};
    for (size_t d = 0; d < ARRAY_SIZE(divisors); d++)
        for (int u = 0; u < 2; u++) {
            sbfx_desc desc = {.max_particles = 16, .target_divisor = divisors[d],
                              .upsample = u ? SBFX_UPSAMPLE_BILINEAR : SBFX_UPSAMPLE_NEAREST_DEPTH};
            char what[64];
            snprintf(what, sizeof(what), "divisor %d, %s", divisors[d], u ? "bilinear" : "nearest-depth");
            CHECK(run_case(&f, desc, 8, scattered, 3, what) == 3);
        }
    fixture_close(&f);
}

/* The bench's floor writes every fragment it draws: it keeps its rectangles (the bench's floor
 * row as before tiles), which no diagonal of the tiles' footprint may cut. */
static void large_puffs(const gl_fixture *f, int i, sbfx_view_particle *out, int *n)
{
    out[0] = particle_at(f, 40.0 + 3.3 * i, 50.0 - 2.1 * i, 5.0, 0.5 + 0.1 * i, SBFX_SMOKE);
    out[1] = particle_at(f, 120.0 - 2.7 * i, 30.0 + 1.9 * i, 7.0, 0.9, SBFX_FIRE);
    *n = 2;
}

CHECK_TEST(the_benchs_floor_keeps_its_rectangles)
{
    gl_fixture f;
    fixture_open(&f, W, H);
    fixture_projection(&f, 1.0f, 0.1f, 100.0f);
    for (int d = 1; d <= 4; d *= 4) {
        sbfx_desc desc = {.max_particles = 16, .opacity = SBFX_OPACITY_FLOOR, .target_divisor = d};
        CHECK(run_case(&f, desc, 8, large_puffs, 4, "the bench's floor") == 4);
        CHECK(run_case(&f, desc, 8, scattered, 3, "the bench's floor") == 3);
    }
    fixture_close(&f);
}

/* ---- the counters --------------------------------------------------------------------------- */

CHECK_TEST(counters_say_what_was_composited)
{
    gl_fixture f;
    fixture_open(&f, W, H);
    fixture_projection(&f, 1.0f, 0.1f, 100.0f);
    host_picture h = host_open(&f);
    pair p = pair_make(&f, (sbfx_desc){.max_particles = 16}, 0);
    /* idle: nothing drawn, nothing counted */
    comparison idle = pair_render(&f, h.fbo, &p, NULL, 0);
    CHECK(idle.tiled.passes == 0 && idle.tiled.composite_tiles == 0 && idle.tiled.composite_pixels == 0,
          "idle: %d passes, %d tiles, %d pixels", idle.tiled.passes, idle.tiled.composite_tiles,
          idle.tiled.composite_pixels);
    /* one small puff in the middle of a tile: one tile (the upsampling's footprint stays inside it) */
    int t = SBFX_TILE_SIZE;
    sbfx_view_particle small = particle_at(&f, 2.5 * t, 1.5 * t, 10.0, 0.5, SBFX_SMOKE);
    comparison one = pair_render(&f, h.fbo, &p, &small, 1);
    check_same(&one, "one small puff");
    CHECK(one.tiled.composite_tiles == 1 && one.tiled.composite_pixels == t * t, "one small puff: %d tiles, %d pixels",
          one.tiled.composite_tiles, one.tiled.composite_pixels);
    CHECK(one.full.composite_pixels == W * H && one.full.composite_tiles == ((W + t - 1) / t) * ((H + t - 1) / t),
          "full screen: %d tiles, %d pixels", one.full.composite_tiles, one.full.composite_pixels);
    CHECK(one.tiled.passes == one.full.passes && one.tiled.draw_calls == one.full.draw_calls,
          "passes %d / %d, draw calls %d / %d", one.tiled.passes, one.full.passes, one.tiled.draw_calls,
          one.full.draw_calls);
    /* wholly behind the eye: the particle pass runs (its target is cleared), nothing is composited */
    sbfx_view_particle behind = small;
    behind.center[2] = 5.0f;
    comparison none = pair_render(&f, h.fbo, &p, &behind, 1);
    check_same(&none, "a puff behind the eye");
    CHECK(none.tiled.composite_tiles == 0 && none.tiled.composite_pixels == 0 && none.tiled.passes == 1,
          "behind the eye: %d tiles, %d pixels, %d passes", none.tiled.composite_tiles, none.tiled.composite_pixels,
          none.tiled.passes);
    pair_destroy(&p);
    host_close(&h);
    fixture_close(&f);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
