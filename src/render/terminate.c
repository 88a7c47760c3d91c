/* Early termination of the particles (issue 43 item 4; docs/gpus.md "Front to back, and early
 * termination"). The particles are drawn nearest first (particles.c); at a few checkpoints of
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
#include "render/render.h"

/* What a terminated texel may lose at most, in 8-bit levels on the display. */
#define STOP_LEVELS 0.25
/* The checkpoints: after these shares of the particles, nearest first (docs/gpus.md: chosen by
 * counting fragments over the example scenes). */
static const double stop_shares[SBFX_STOPS] = {0.125, 0.25, 0.5};

bool sbfx_terminate_used(const sbfx *fx)
{
    return fx->scene->early_termination && fx->gl->stop_framebuffer && fx->gl->stop_program;
}

/* The largest of a phase function over directions: at cos = +-1 (Cornette-Shanks rises
 * monotonically toward g's side); 1 % over it for the table's interpolation (its error is
 * 4.4e-4 at |g| = 0.95, test_gl_tables). */
static double phase_max(double g)
{
    return 1.01 * fmax(sbfx_phase(1.0, g), sbfx_phase(-1.0, g));
}

/* The brightest a fire particle of this frame emits (pre-exposed): the black body (the table
 * the shader reads, or analytic within its error) at the frame's hottest temperature, T0 + T1
 * at the coordinate's top, 1, times cooled (at most max_cooled), sampled over [0, that] since a
 * channel need not rise monotonically; glow shares are at most 1; then the ceiling. */
static double fire_emission_max(const sbfx *fx, double max_cooled)
{
    const sbfx_medium_params *m = &fx->scene->media[SBFX_FIRE];
    const sbfx_tables *t = fx->tables;
    if (!t->blackbody) return SBFX_RADIANCE_CEILING;
    double hottest = (m->t0 + fmax(m->t1, 0.0f)) * max_cooled, most = 0.0;
    for (int i = 1; i <= 64; i++) {
        double rgb[3];
        sbfx_blackbody_table_lookup(t->blackbody, SBFX_BLACKBODY_SIZE, t->blackbody_lo, t->blackbody_hi,
                                    hottest * i / 64.0, rgb);
        most = fmax(most, fmax(rgb[0], fmax(rgb[1], rgb[2])));
    }
    double scale = (double)m->emission_scale * (1.0 - m->albedo) * fx->scene->desc.exposure;
    return fmin(1.01 * most * scale, SBFX_RADIANCE_CEILING);
}

/* The scattered light's bound of medium m before its albedo: the ambient and every light at
 * its largest falloff (4: no closer than 0.5 m) and phase (lit media: the wrap's largest,
 * |N / (1 + w)| <= sqrt(3) / (1 + w), its bias and the translucency; their maps at most 1). */
static double scattered_max(const sbfx *fx, const frame_lights *lights, sbfx_medium m)
{
    const sbfx_medium_params *mp = &fx->scene->media[m];
    const float *a = fx->scene->ambient;
    double per_light = mp->lit ? (sqrt(3.0) + mp->wrap) / (1.0 + mp->wrap) + mp->translucency
                               : 4.0 * M_PI * phase_max(mp->phase_g);
    double sum = 0.0;
    for (int i = 0; i < lights->count; i++) {
        const float *c = lights->color[i];
        double falloff = lights->vector[i][3] > 0.5f ? 4.0 : 1.0;
        sum += fmax(c[0], fmax(c[1], c[2])) * falloff * per_light;
    }
    double direct = mp->lit ? 1.0 - mp->dampening : 1.0;
    return fmax(a[0], fmax(a[1], a[2])) + direct * sum;
}

/* What multiplies medium m's in-scattered light: the albedo's colour, the exposure, the
 * detail's shading (1 + DETAIL_SHADE (0.5 - detail) x strength, detail >= 0) and for lit media
 * the dampening. */
static double scatter_scale(const sbfx *fx, sbfx_medium m)
{
    const sbfx_medium_params *mp = &fx->scene->media[m];
    double shade = !mp->lit && mp->detail_strength > 0.0f ? 1.0 + 0.9 * mp->detail_strength : 1.0;
    double color = fmax(mp->color[0], fmax(mp->color[1], mp->color[2]));
    return mp->albedo * fx->scene->desc.exposure * color * shade;
}

/* The fire's light in-scattered across a particle: the instance's colour times 1 + e.gradient,
 * e the ray's offset in the centre's plane (at most r |ray| where the sphere is hit) and the
 * gradient at most 1 / r: at most 1 + |ray|, |ray| largest in the frame's corners. */
static double fire_spread(const frame_params *fp)
{
    double x = (1.0 + fabs(fp->projection[2])) / fabs(fp->projection[0]);
    double y = (1.0 + fabs(fp->projection[3])) / fabs(fp->projection[1]);
    return 1.0 + sqrt(1.0 + x * x + y * y);
}

typedef struct stop_media {
    double own[SBFX_MEDIUM_COUNT];   /* emission and scattering of the frame's lights */
    double fire[SBFX_MEDIUM_COUNT];  /* times the instance's fire light */
} stop_media;

static void media_bounds(const sbfx *fx, const frame_lights *lights, const frame_params *fp, double max_cooled,
                         stop_media *b)
{
    double spread = fire_spread(fp);
    for (int m = 0; m < SBFX_MEDIUM_COUNT; m++) {
        const sbfx_medium_params *mp = &fx->scene->media[m];
        bool scatters = m != SBFX_HEAT && mp->albedo > 0.0f;
        double scale = scatters ? scatter_scale(fx, (sbfx_medium)m) : 0.0;
        b->own[m] = scatters ? scale * scattered_max(fx, lights, (sbfx_medium)m) : 0.0;
        if (m == SBFX_FIRE && fx->scene->uses_medium[m]) b->own[m] += fire_emission_max(fx, max_cooled);
        b->fire[m] = scale * (mp->lit ? 1.0 - mp->dampening : spread);
    }
}

/* Particle i's bound (drawn i-th): its medium's, and the fire's light its instance carries. */
static double stop_radiance(const sbfx *fx, const stop_media *b, const sbfx_view_particle *v, int i)
{
    double L = b->own[v->medium];
    int at = fx->scene->instance_fire;
    if (at && b->fire[v->medium] > 0.0) {
        const float *f = &fx->sim->instances[(size_t)fx->scene->instance_floats * i + at];
        L += b->fire[v->medium] * fmax(f[0], fmax(f[1], f[2]));
    }
    return isfinite(L) ? L : SBFX_RADIANCE_CEILING;
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
    media_bounds(fx, lights, fp, max_cooled, &b);
    int n = 0, at[SBFX_STOPS];
    for (int k = 0; k < SBFX_STOPS; k++) {
        int i = (int)(stop_shares[k] * count);
        if (i > 0 && (n == 0 || i > at[n - 1])) at[n++] = i;
    }
    double most = 0.0; /* the brightest of the particles from i on, walked back from the last */
    int k = n - 1;
    for (int i = count - 1; i >= 0 && k >= 0; i--) {
        most = fmax(most, stop_radiance(fx, &b, sbfx_drawn_particle(fx, count, i), i));
        if (i == at[k]) {
            out->at[k] = at[k];
            out->epsilon[k] = (float)(STOP_LEVELS / (255.0 * (most + 1.0)));
            k--;
        }
    }
    out->count = n;
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
