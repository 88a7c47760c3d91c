/* Early termination of the particles (issue 43 item 4; docs/gpus.md "Front to back, and early
 * termination"; the scene's render.early_termination, sbfx_set_early_termination, off by
 * default). The particles are drawn nearest first (particles.c); at a few checkpoints of
 * that order a mark (terminate_mark.frag) over the particles' tiles writes depth 0 into the
 * particle target's depth (a DEPTH_COMPONENT16 renderbuffer, cleared to 1 each frame) where the
 * transmittance accumulated so far is below epsilon; the particles after it are drawn at clip
 * z 0 with GL_LESS, so there they fail the early depth test and are never shaded. The window
 * depth of clip z 0 is 0.5 (GL_NEGATIVE_ONE_TO_ONE) or 0 (GL_ZERO_TO_ONE) with the depth range
 * [0, 1], which the frame sets for its passes (SBFX_GL_SAVE_DEPTH_RANGE, as refine.c): under
 * the clear's 1, not under the mark's 0, in both clip depth modes.
 *
 * epsilon is derived, not tuned. Behind a texel whose transmittance is T the particles not
 * drawn would add at most T x L to its light (L: the brightest of them, pre-exposed, as the
 * target holds it) and take at most T from its transmittance, which lets through the host's
 * colour (at most 1: an 8-bit host's, clamped so by the composite where sbfx does not own the
 * scene). The tone map's slope is at most 1 (src/tables/tonemap.c), so the display moves by at
 * most T (L + 1); with T < epsilon = STOP_LEVELS / (255 (L + 1)) that is under STOP_LEVELS of an
 * 8-bit level. L is bounded on the CPU per checkpoint, over the particles drawn after it, from
 * what particle.frag can make of each (stop_radiance below). Every attachment's alpha holds
 * the same transmittance, so the shimmer offsets and the velocities behind lose at most T of
 * theirs too. */
#include <math.h>
#include <string.h>
#include "render/render.h"

/* What a terminated texel may lose at most, in 8-bit levels on the display. */
#define STOP_LEVELS 0.25
/* The checkpoints: after these shares of the particles, nearest first. Chosen by counting the
 * barrage's particle fragments (docs/gpus.md "Front to back, and early termination"): at 1/2 and
 * 3/4 it saves nearly what 1/4, 1/2, 3/4 or six checkpoints save, with fewer marks and
 * framebuffer switches. */
static const double stop_shares[SBFX_STOPS] = {0.5, 0.75};

bool sbfx_terminate_used(const sbfx *fx)
{
    return fx->scene->early_termination && fx->gl->stop_framebuffer && fx->gl->stop_program;
}

/* The brightest a fire particle emits (pre-exposed), per share of cooling: hottest[j] bounds a
 * particle whose cooled factor (1 - cooling (1 - intensity)) is at most (j + 1) / STOP_COOLED
 * (the last entry: any above 1 as well, at the frame's largest). Its temperature is T0 + T1 x
 * the coordinate, at most 1, times cooled; the black body (the table the shader reads, or
 * analytic within its error, 1 % over) is sampled over [0, that] since a channel need not rise
 * monotonically; glow shares are at most 1; then the ceiling. */
#define STOP_COOLED 16
static void fire_emission_max(const sbfx *fx, double max_cooled, double hottest[STOP_COOLED])
{
    const sbfx_medium_params *m = &fx->scene->media[SBFX_FIRE];
    const sbfx_tables *t = fx->tables;
    double scale = (double)m->emission_scale * (1.0 - m->albedo) * fx->scene->desc.exposure, most = 0.0;
    double top = (m->t0 + fmax(m->t1, 0.0f)) * fmax(max_cooled, 1.0);
    for (int j = 0, i = 1; j < STOP_COOLED; j++) {
        double upto = j == STOP_COOLED - 1 ? top : (m->t0 + fmax(m->t1, 0.0f)) * (j + 1) / STOP_COOLED;
        for (; t->blackbody && i <= 8 * STOP_COOLED && top * i / (8.0 * STOP_COOLED) <= upto * (1.0 + 1e-12); i++) {
            double rgb[3];
            sbfx_blackbody_table_lookup(t->blackbody, SBFX_BLACKBODY_SIZE, t->blackbody_lo, t->blackbody_hi,
                                        top * i / (8.0 * STOP_COOLED), rgb);
            most = fmax(most, fmax(rgb[0], fmax(rgb[1], rgb[2])));
        }
        hottest[j] = t->blackbody ? fmin(1.01 * most * scale, SBFX_RADIANCE_CEILING) : SBFX_RADIANCE_CEILING;
    }
}

/* Each light's largest contribution per unit of a medium's phase (or lit) factor at a particle:
 * its colour's largest channel times its falloff at the sphere's nearest point, 1 / max(d², 1/4)
 * as particle.frag computes it per pixel (d at least the centre's distance less the radius). */
static double lights_at(const frame_lights *lights, const sbfx_view_particle *v)
{
    double sum = 0.0;
    for (int i = 0; i < lights->count; i++) {
        const float *c = lights->color[i], *l = lights->vector[i];
        double falloff = 1.0;
        if (l[3] > 0.5f) {
            double d[3] = {v->center[0] - l[0], v->center[1] - l[1], v->center[2] - l[2]};
            double near = fmax(sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) - v->radius, 0.0);
            falloff = 1.0 / fmax(near * near, 0.25);
        }
        sum += fmax(c[0], fmax(c[1], c[2])) * falloff;
    }
    return sum;
}

/* A medium's factors: what multiplies its in-scattered light (the albedo's colour, the exposure,
 * the detail's shading 1 + DETAIL_SHADE (0.5 - detail) x strength, detail >= 0), each light's
 * largest phase (4 pi p at cos = +-1: Cornette-Shanks rises toward g's side; 1 % over it for
 * the table's interpolation, whose error is 4.4e-4 at |g| = 0.95, test_gl_tables) or for lit
 * media the wrap's largest, |N / (1 + w)| <= sqrt(3) / (1 + w), its bias and the translucency
 * (their maps at most 1) with the dampening; the fire's light across the particle: 1 + e.grad,
 * e the ray's offset in the centre's plane (at most r |ray| where the sphere is hit), the
 * gradient at most 1 / r: at most 1 + |ray|, |ray| largest in the frame's corners. */
typedef struct stop_media {
    double scale[SBFX_MEDIUM_COUNT];     /* 0: the medium scatters nothing */
    double per_light[SBFX_MEDIUM_COUNT];
    double fire[SBFX_MEDIUM_COUNT];      /* times the instance's fire light */
    double ambient;
    double hottest[STOP_COOLED];         /* fire's emission (fire_emission_max) */
} stop_media;

static double fire_spread(const frame_params *fp)
{
    double x = (1.0 + fabs(fp->projection[2])) / fabs(fp->projection[0]);
    double y = (1.0 + fabs(fp->projection[3])) / fabs(fp->projection[1]);
    return 1.0 + sqrt(1.0 + x * x + y * y);
}

static void media_bounds(const sbfx *fx, const frame_params *fp, double max_cooled, stop_media *b)
{
    const float *a = fx->scene->ambient;
    b->ambient = fmax(a[0], fmax(a[1], a[2]));
    double spread = fire_spread(fp);
    for (int m = 0; m < SBFX_MEDIUM_COUNT; m++) {
        const sbfx_medium_params *mp = &fx->scene->media[m];
        bool scatters = m != SBFX_HEAT && mp->albedo > 0.0f;
        double shade = !mp->lit && mp->detail_strength > 0.0f ? 1.0 + 0.9 * mp->detail_strength : 1.0;
        double color = fmax(mp->color[0], fmax(mp->color[1], mp->color[2]));
        double direct = mp->lit ? 1.0 - mp->dampening : 1.0;
        b->scale[m] = scatters ? mp->albedo * fx->scene->desc.exposure * color * shade : 0.0;
        b->per_light[m] = mp->lit ? direct * ((sqrt(3.0) + mp->wrap) / (1.0 + mp->wrap) + mp->translucency)
                                  : 4.0 * M_PI * 1.01 * fmax(sbfx_phase(1.0, mp->phase_g), sbfx_phase(-1.0, mp->phase_g));
        b->fire[m] = mp->lit ? direct : spread;
    }
    if (fx->scene->uses_medium[SBFX_FIRE]) fire_emission_max(fx, max_cooled, b->hottest);
}

/* Particle i's bound (drawn i-th): what its medium scatters of the ambient, the lights and the
 * fire's light its instance carries, and what fire emits. */
static double stop_radiance(const sbfx *fx, const stop_media *b, const frame_lights *lights,
                            const sbfx_view_particle *v, int i)
{
    sbfx_medium m = v->medium;
    double L = 0.0;
    if (b->scale[m] > 0.0) {
        double fire = 0.0;
        int at = fx->scene->instance_fire;
        if (at) {
            const float *f = &fx->sim->instances[(size_t)fx->scene->instance_floats * i + at];
            fire = b->fire[m] * fmax(f[0], fmax(f[1], f[2]));
        }
        L = b->scale[m] * (b->ambient + b->per_light[m] * lights_at(lights, v) + fire);
    }
    if (m == SBFX_FIRE) {
        double cooled = 1.0 - fx->scene->media[SBFX_FIRE].cooling * (1.0 - v->intensity);
        int j = (int)ceil(cooled * STOP_COOLED) - 1;
        L += b->hottest[j < 0 ? 0 : j >= STOP_COOLED ? STOP_COOLED - 1 : j];
    }
    return isfinite(L) ? L : SBFX_RADIANCE_CEILING;
}

/* The largest optical depth particle v gives any ray, of what it covers with: every opacity
 * model's is at most tau x tau_scale x the chord, at most 2r (optical_depth: the exact model's
 * integral, the paper's (1 - d/r) ds, the flat profile's 2w), tau_scale = intensity x the
 * detail's erosion (mix(1, at most EROSION_GAIN 2.2, strength)); fire covers with its soot on
 * top, depth (1 + soot) + strength FIRE_SOOT (at most 16) tau tau_scale chord^2 / 2r; heat covers
 * nothing; the bench's floor 0.05 a fragment. */
static double depth_max(const sbfx *fx, const sbfx_view_particle *v)
{
    if (fx->scene->desc.opacity == SBFX_OPACITY_FLOOR) return -log(0.95);
    if (v->medium == SBFX_HEAT) return 0.0;
    const sbfx_medium_params *mp = &fx->scene->media[v->medium];
    double strength = mp->detail_strength > 0.0f ? mp->detail_strength : 0.0;
    double column = mp->tau * fmax(v->intensity, 0.0) * (1.0 + 1.2 * strength) * 2.0 * v->radius;
    if (v->medium == SBFX_FIRE) column = column * (1.0 + fmax(mp->soot, 0.0f)) + 16.0 * strength * column;
    return column;
}

/* Leaves out the checkpoints where no texel can be below its epsilon: a texel's transmittance
 * after the first at[k] particles is at least exp(-(the sum of depth_max over those whose
 * region's box holds its tile)), so where that sum stays under -ln(epsilon) on every tile the
 * mark would write nothing (and cost a pass and two framebuffer switches). */
static void keep_useful(sbfx *fx, const frame_params *fp, int count, sbfx_stops *s)
{
    const sbfx_tiles *t = &fx->render->tiles;
    float *sum = fx->render->stop_depth;
    memset(sum, 0, sizeof(float) * (size_t)(t->columns * t->rows));
    double deepest = 0.0;
    int kept = 0;
    for (int i = 0, k = 0; k < s->count && i < count; i++) {
        int box[4];
        const sbfx_view_particle *v = sbfx_drawn_particle(fx, count, i);
        double d = depth_max(fx, v);
        if (d > 0.0 && sbfx_tiles_box(fx, fp, v, box))
            for (int row = box[1]; row <= box[3]; row++)
                for (int col = box[0]; col <= box[2]; col++) {
                    float *at = &sum[row * t->columns + col];
                    *at += (float)d;
                    deepest = fmax(deepest, *at);
                }
        if (i + 1 < s->at[k]) continue;
        if (deepest > -log(s->epsilon[k]) * (1.0 - 1e-6)) { /* float sums: a millionth's margin */
            s->at[kept] = s->at[k];
            s->epsilon[kept++] = s->epsilon[k];
        } else
            fx->render->stops_skipped++;
        k++;
    }
    s->count = kept;
}

void sbfx_terminate_plan(sbfx *fx, const frame_lights *lights, const frame_params *fp, int count, sbfx_stops *out)
{
    *out = (sbfx_stops){0};
    if (!sbfx_terminate_used(fx) || count < 2) return;
    double max_cooled = 0.0;
    const float cooling = fx->scene->media[SBFX_FIRE].cooling;
    for (int i = 0; i < count; i++) {
        const sbfx_view_particle *v = sbfx_drawn_particle(fx, count, i);
        if (v->medium == SBFX_FIRE) max_cooled = fmax(max_cooled, 1.0 - cooling * (1.0 - v->intensity));
    }
    stop_media b;
    media_bounds(fx, fp, max_cooled, &b);
    int n = 0, at[SBFX_STOPS];
    for (int k = 0; k < SBFX_STOPS; k++) {
        int i = (int)(stop_shares[k] * count);
        if (i > 0 && (n == 0 || i > at[n - 1])) at[n++] = i;
    }
    double most = 0.0; /* the brightest of the particles from i on, walked back from the last */
    int k = n - 1;
    for (int i = count - 1; i >= 0 && k >= 0; i--) {
        most = fmax(most, stop_radiance(fx, &b, lights, sbfx_drawn_particle(fx, count, i), i));
        if (i == at[k]) {
            out->at[k] = at[k];
            out->epsilon[k] = (float)(STOP_LEVELS / (255.0 * (most + 1.0)));
            k--;
        }
    }
    out->count = n;
    fx->render->stops_skipped = 0;
    keep_useful(fx, fp, count, out);
}

/* The target's depth cleared to 1 and the test on (GL_LESS, no writes) for the particles. */
void sbfx_terminate_begin(sbfx *fx)
{
    const GLfloat open = 1.0f;
    glDepthMask(GL_TRUE);
    glClearBufferfv(GL_DEPTH, 0, &open);
    glDepthMask(GL_FALSE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    fx->render->stops_marked = 0;
}

/* The mark at one checkpoint; the particle target bound again after it with its draw state,
 * its opaque depth back on UNIT_DEPTH and the particles' vertex array. */
void sbfx_terminate_mark(sbfx *fx, float epsilon, GLuint depth_texture)
{
    sbfx_gl *gl = fx->gl;
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, gl->stop_framebuffer);
    glDepthFunc(GL_ALWAYS);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glUseProgram(gl->stop_program);
    sbfx_bind_texture(UNIT_DEPTH, GL_TEXTURE_2D, gl->particles.texture[0], 0);
    glUniform1i(gl->stop_u.particles, UNIT_DEPTH);
    glUniform1f(gl->stop_u.epsilon, epsilon);
    sbfx_tiles_draw(fx, &gl->stop_u, true, gl->low_width, gl->low_height, fx->scene->desc.target_divisor);
    glDepthMask(GL_FALSE);
    glDepthFunc(GL_LESS);
    glEnable(GL_BLEND);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, gl->particles.framebuffer);
    sbfx_bind_texture(UNIT_DEPTH, GL_TEXTURE_2D, depth_texture, 0);
    glBindVertexArray(gl->particle_vao);
    glBindBuffer(GL_ARRAY_BUFFER, gl->instance_buffer);
    fx->counters.passes++;
    fx->render->stops_marked++;
}

void sbfx_terminate_end(void)
{
    glDisable(GL_DEPTH_TEST);
}

sbfx_result sbfx_set_early_termination(sbfx *fx, bool on)
{
    if (!fx) return SBFX_ERR_INVALID_ARGUMENT;
    if (on == fx->scene->early_termination) return SBFX_OK;
    fx->scene->early_termination = on;
    if (!on) return SBFX_OK; /* the targets keep their depth, untested */
    sbfx_gl_enter(fx);
    sbfx_result r = sbfx_stop_program_build(fx);
    /* targets made without the depth: made again, with it, by the next render */
    if (r == SBFX_OK && fx->gl->out_width && !fx->gl->stop_framebuffer) sbfx_targets_destroy(fx);
    if (r == SBFX_OK && !sbfx_gl_check(fx, "turning early termination on")) r = SBFX_ERR_GL;
    sbfx_gl_leave(fx, "sbfx_set_early_termination");
    return r;
}
