/* What sbfx reads from a frame's projection (docs/design.md §5): any OpenGL perspective — finite far,
 * infinite far (p10 = -1, p14 = -2n), off-axis (p8, p9), reversed-Z (p14 > 0: near -> 1,
 * far -> 0) — and how the host's depth texture turns into view distance.
 *
 * A perspective maps view distance z (along -z) to ndc_z = p14 / z - p10; the clip depth
 * mode maps ndc_z to window depth d: d = (ndc_z + 1) / 2 by default, d = ndc_z with
 * glClipControlEXT(..., GL_ZERO_TO_ONE). Solving the matrix's own row for z, written around
 * the window depth of the far end d_far (1, or 0 when reversed) so that the float shaders
 * subtract no nearly equal numbers (d - d_far is exact for d within a factor 2 of it, and the
 * constant part is formed here in double):
 *     z = p14 / (scale (d - d_far) + offset),  offset = scale d_far + ndc(0) + p10
 * Standard depth: z = p14 / (2 (d - 1) + (1 + p10)); reversed-Z infinite: z = n / d.
 * d = d_far, the clear value, means "no surface". */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "render/render.h"

static bool is_zero(float v) { return v == 0.0f; }

/* NULL, or what is wrong with the matrix, in words naming the entry. */
static const char *shape_error(const float *p, char *buf, size_t size)
{
    for (int i = 0; i < 16; i++)
        if (!isfinite(p[i])) {
            snprintf(buf, size, "frame projection[%d] is %g, not a finite number", i, (double)p[i]);
            return buf;
        }
    if (p[11] == 0.0f && p[15] != 0.0f)
        return "frame projection is orthographic (projection[11] = 0, projection[15] != 0): sbfx needs a "
               "perspective projection (sbfx_perspective, sbfx_frustum)";
    if (p[11] != -1.0f || p[15] != 0.0f) {
        snprintf(buf, size, "frame projection is not an OpenGL perspective: projection[11] must be -1 and "
                 "projection[15] 0 (they are %g and %g)", (double)p[11], (double)p[15]);
        return buf;
    }
    static const int zero[] = {1, 2, 3, 4, 6, 7, 12, 13};
    for (size_t i = 0; i < ARRAY_SIZE(zero); i++)
        if (!is_zero(p[zero[i]])) {
            snprintf(buf, size, "frame projection[%d] is %g: sbfx takes perspectives without skew, shift or "
                     "oblique near plane (non-zero only [0], [5], [8], [9], [10], [14] and [11] = -1)", zero[i],
                     (double)p[zero[i]]);
            return buf;
        }
    if (is_zero(p[0]) || is_zero(p[5])) {
        snprintf(buf, size, "frame projection has a zero scale (projection[0] = %g, projection[5] = %g)",
                 (double)p[0], (double)p[5]);
        return buf;
    }
    if (is_zero(p[14]))
        return "frame projection[14] is 0: its depth row gives every distance the same depth";
    return NULL;
}

static const char *planes_error(const sbfx_depth_model *m, char *buf, size_t size)
{
    if (!(m->near > 0.0) || !isfinite(m->near)) {
        snprintf(buf, size, "frame projection puts the near plane at %g: it must be in front of the camera "
                 "(check projection[10] and [14] and the clip depth mode)", m->near);
        return buf;
    }
    if (!(m->far > m->near)) {
        snprintf(buf, size, "frame projection puts the far plane (%g) not beyond the near plane (%g)", m->far,
                 m->near);
        return buf;
    }
    return NULL;
}

/* The model of a frame, or NULL with `buf` saying what is wrong. */
static const char *depth_model(const sbfx_frame *f, sbfx_depth_model *m, char *buf, size_t size)
{
    const float *p = f->projection;
    *m = (sbfx_depth_model){.window_far = 1.0, .far = INFINITY};
    const char *err = shape_error(p, buf, size);
    if (err) return err;
    if ((unsigned)f->clip_depth_mode >= SBFX_CLIP_DEPTH_COUNT) {
        snprintf(buf, size, "frame clip_depth_mode %d is unknown", (int)f->clip_depth_mode);
        return buf;
    }
    bool zero_to_one = f->clip_depth_mode == SBFX_CLIP_DEPTH_ZERO_TO_ONE, reversed = p[14] > 0.0f;
    double lo = zero_to_one ? 0.0 : -1.0, p10 = p[10], p14 = p[14];
    double ndc_near = reversed ? 1.0 : lo, ndc_far = reversed ? lo : 1.0;
    *m = (sbfx_depth_model){.projection = {p[0], p[5], p[8], p[9]}, .reversed = reversed};
    m->near = p14 / (ndc_near + p10);
    m->far = ndc_far + p10 == 0.0 ? INFINITY : p14 / (ndc_far + p10);
    m->scale = zero_to_one ? 1.0 : 2.0;
    m->window_far = reversed ? 0.0 : 1.0;
    m->offset = m->scale * m->window_far + lo + p10;
    m->p14 = p14;
    m->ndc[0] = (float)m->scale;
    m->ndc[1] = (float)lo;
    return planes_error(m, buf, size);
}

bool sbfx_depth_model_from(sbfx *fx, const sbfx_frame *f, sbfx_depth_model *out)
{
    char buf[320];
    const char *err = depth_model(f, out, buf, sizeof(buf));
    if (err) sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "%s", err);
    return !err;
}

void sbfx_depth_model_uniform(const sbfx_depth_model *m, float out[4])
{
    out[0] = (float)m->scale;
    out[1] = (float)m->window_far;
    out[2] = (float)m->offset;
    out[3] = (float)m->p14;
}

void sbfx_near_model_uniform(const sbfx_depth_model *m, float out[3])
{
    out[0] = (float)(m->near * m->scale / m->p14);
    out[1] = (float)m->window_far;
    out[2] = (float)(m->near * m->offset / m->p14);
}

float sbfx_window_depth(const sbfx_frame *f, double distance)
{
    char buf[320];
    sbfx_depth_model m;
    if (depth_model(f, &m, buf, sizeof(buf)) || !(distance < m.far)) return (float)(m.window_far);
    /* d - d_far = (p14 / z - offset) / scale: no cancellation for the far end either */
    double d = m.window_far + (m.p14 / distance - m.offset) / m.scale;
    return (float)fmin(1.0, fmax(0.0, d));
}

double sbfx_window_distance(const sbfx_frame *f, float window)
{
    char buf[320];
    sbfx_depth_model m;
    if (depth_model(f, &m, buf, sizeof(buf)) || window == (float)m.window_far) return INFINITY;
    return m.p14 / (m.scale * ((double)window - m.window_far) + m.offset);
}

/* ---- host helpers: column-major projection matrices ---- */

/* The depth row of a standard perspective ([-1, 1] clip depth), far = INFINITY: its limit. */
static void depth_row(float m[16], float n, float f)
{
    m[11] = -1.0f;
    if (isinf(f)) {
        m[10] = -1.0f;
        m[14] = -2.0f * n;
    } else {
        m[10] = -(f + n) / (f - n);
        m[14] = -2.0f * f * n / (f - n);
    }
}

void sbfx_frustum(float m[16], float left, float right, float bottom, float top, float n, float f)
{
    memset(m, 0, 16 * sizeof(float));
    m[0] = 2.0f * n / (right - left);
    m[5] = 2.0f * n / (top - bottom);
    m[8] = (right + left) / (right - left);
    m[9] = (top + bottom) / (top - bottom);
    depth_row(m, n, f);
}

void sbfx_perspective(float m[16], float fov_y, float aspect, float n, float f)
{
    float t = 1.0f / tanf(fov_y * 0.5f);
    memset(m, 0, 16 * sizeof(float));
    m[0] = t / aspect;
    m[5] = t;
    depth_row(m, n, f);
}

void sbfx_reverse_z(float m[16], float n, float f)
{
    if (isinf(f)) {
        m[10] = 0.0f;
        m[14] = n;
    } else {
        m[10] = n / (f - n);
        m[14] = f * n / (f - n);
    }
}

/* ---- the look-at matrix (the host's camera, the shadow map's light view) ---- */
static void cross3(const float a[3], const float b[3], float out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

void sbfx_look_at(float m[16], const float eye[3], const float target[3], const float up[3])
{
    float f[3] = {target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]}, s[3], u[3];
    sbfx_normalize3(f);
    cross3(f, up, s);
    sbfx_normalize3(s);
    cross3(s, f, u);
    const float rows[3][3] = {{s[0], s[1], s[2]}, {u[0], u[1], u[2]}, {-f[0], -f[1], -f[2]}};
    memset(m, 0, 16 * sizeof(float));
    for (int r = 0; r < 3; r++) {
        for (int c = 0; c < 3; c++) m[c * 4 + r] = rows[r][c];
        m[12 + r] = -(rows[r][0] * eye[0] + rows[r][1] * eye[1] + rows[r][2] * eye[2]);
    }
    m[15] = 1.0f;
}
