/* The screen tiles a frame's particles can change (tiles.h says why and what is kept), marked on
 * the CPU each frame from the particles the frame draws, merged into rectangles of tiles and drawn
 * as instances of tiles.vert by the composite, the depth downsample and the low-res corners
 * (passes.c). Fixed arrays in the render room's state and a buffer made at load: nothing is
 * allocated per frame. */
#include <math.h>
#include <string.h>
#include "render/render.h"

sbfx_result sbfx_tiles_create(sbfx *fx)
{
    sbfx_tiles *t = &fx->render->tiles;
    glGenVertexArrays(1, &t->vao);
    glGenBuffers(1, &t->buffer);
    glBindVertexArray(t->vao);
    glBindBuffer(GL_ARRAY_BUFFER, t->buffer);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)sizeof(t->rects), NULL, GL_DYNAMIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribDivisor(0, 1);
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    fx->counters.gpu_bytes += sizeof(t->rects);
    return sbfx_gl_check(fx, "creating the tile rectangles' buffer") ? SBFX_OK : SBFX_ERR_GL;
}

void sbfx_tiles_destroy(sbfx *fx)
{
    sbfx_tiles *t = &fx->render->tiles;
    if (t->buffer) glDeleteBuffers(1, &t->buffer);
    if (t->vao) glDeleteVertexArrays(1, &t->vao);
    t->buffer = t->vao = 0;
}

/* ---- where a particle can change the picture ----------------------------------------------- */

/* One direction the region is bounded along (in the particle target's pixels): a view-space unit
 * direction n, the pixels per unit of slope along it, the pixels' offset, how much to grow. */
typedef struct region_axis {
    double n[2], scale, shift, grow;
} region_axis;

#define WHOLE_TARGET 1e9 /* a region's bound when it is the whole target */

/* Where a particle changes the picture, in the particle target's pixels (texel i spans [i, i + 1)):
 * a box and two diagonal slabs (u = x + y, v = x - y), grown to what the composite reads; the
 * axes in that order (x, y, u, v). */
typedef struct particle_region {
    double range[4][2];
} particle_region;

/* The frame's four axes: x and y (pixels = p0 or p5 times the slope, times half the target),
 * their sum and difference. A pixel at q (its centre, in low-res pixels) reads the texels whose
 * centres lie within 1 of q on each axis (composite.frag: base and base + 1): the box grows by 1,
 * the diagonal slabs by 2. The bench's floor writes every fragment of the rectangle particle.vert
 * draws for it (its picture as before the octagons: particles.c): the box grows by that
 * rectangle's pixel more, and no slab bounds it. */
static void region_axes(const frame_params *fp, int lw, int lh, bool floor_mode, region_axis axes[4])
{
    const float *p = fp->projection;
    double ax = p[0] * 0.5 * lw, ay = p[1] * 0.5 * lh, sx = (1.0 - p[2]) * 0.5 * lw, sy = (1.0 - p[3]) * 0.5 * lh;
    double box = floor_mode ? 2.0 : 1.0, slab = floor_mode ? WHOLE_TARGET : 2.0, diagonal = sqrt(ax * ax + ay * ay);
    axes[0] = (region_axis){{ax > 0.0 ? 1.0 : -1.0, 0.0}, fabs(ax), sx, box};
    axes[1] = (region_axis){{0.0, ay > 0.0 ? 1.0 : -1.0}, fabs(ay), sy, box};
    axes[2] = (region_axis){{ax / diagonal, ay / diagonal}, diagonal, sx + sy, slab};
    axes[3] = (region_axis){{ax / diagonal, -ay / diagonal}, diagonal, sx - sy, slab};
}

/* The region of the pixels whose composite particle v can change, in low-res pixels, or false
 * for none. Where no ray meets its sphere the particle shader adds nothing (optical_depth is 0:
 * no light, no opacity, no shimmer offset, no motion), so the sphere's outline bounds the texels
 * it changes (the texel centres inside it), not the octagon particle.vert draws around it. Along
 * each axis the outline spans particle.vert's slope_range (the tangents from the eye, in double),
 * widened by the axis' growth and by what the GPU's float may be off by. A sphere that reaches
 * the near plane or holds the eye gets the whole target, as particle.vert gives it; one wholly
 * behind the near plane none. */
static bool particle_region_of(const sbfx_view_particle *v, const frame_params *fp, const region_axis axes[4],
                               int lw, int lh, particle_region *out)
{
    double zc = -(double)v->center[2], r = v->radius, near = fp->near, c[2] = {v->center[0], v->center[1]};
    if (!(r > 0.0) || !isfinite(zc) || !isfinite(r) || !isfinite(c[0]) || !isfinite(c[1])) return false;
    if (zc + r <= near) return false;
    /* close to the near plane, or to holding the eye (then the slopes lose their precision):
     * the whole target, which is what particle.vert draws at or before that point */
    if (zc - r <= near * (1.0 + 1e-4) || zc - r <= 1e-3 * zc) {
        for (int k = 0; k < 4; k++) out->range[k][0] = -WHOLE_TARGET, out->range[k][1] = WHOLE_TARGET;
        return true;
    }
    /* the vertex shader's float: a few units of 2^-24 of every magnitude it meets, scaled by
     * how nearly the sphere touches the eye's plane; 2^-12 of it is far more than that */
    double margin = ldexp(1.0, -12) * zc / (zc - r), denom = (zc - r) * (zc + r), inverse = 1.0 / denom;
    for (int k = 0; k < 4; k++) {
        const region_axis *a = &axes[k];
        double along = a->n[0] * c[0] + a->n[1] * c[1], root = r * sqrt(fmax(along * along + denom, 0.0));
        double err = margin * ((fabs(along) * zc + root) * inverse * a->scale + fabs(a->shift) + 1.0) + a->grow;
        out->range[k][0] = (along * zc - root) * inverse * a->scale + a->shift - err;
        out->range[k][1] = (along * zc + root) * inverse * a->scale + a->shift + err;
    }
    return out->range[0][1] >= 0.0 && out->range[0][0] <= lw && out->range[1][1] >= 0.0 && out->range[1][0] <= lh;
}

/* ---- the mask and its rectangles ------------------------------------------------------------ */

/* fmax and fmin for the finite values here, without their calls (the inner loop's) */
static inline double larger(double a, double b) { return a > b ? a : b; }
static inline double smaller(double a, double b) { return a < b ? a : b; }

/* Marks the tiles holding a pixel of the region: row by row of tiles, the region's columns over
 * the row's pixel centres (q = (pixel + 1/2) / d in low-res pixels). The depth passes, over the
 * same tiles, then compute every low-res depth the composite compares (the texels beside one a
 * particle changed): at d >= 2 each of them holds a marked pixel (the pixels of texel m read
 * from m - 1 or from m on, each way); at d = 1 a pixel reads its own texel and the next, and the
 * region reaches a texel beyond on both sides. True for the whole target (nothing left to mark). */
static bool mark_particle(sbfx_tiles *t, const particle_region *g, int divisor, int width, int height)
{
    if (g->range[0][0] <= -WHOLE_TARGET) return true;
    /* in output pixels (pixel p's centre is at q = (p + 1/2) / d): x, y, u = x + y, v = x - y */
    const double d = divisor;
    double x0 = d * g->range[0][0] - 0.5, x1 = d * g->range[0][1] - 0.5;
    double y0 = larger(ceil(d * g->range[1][0] - 0.5), 0.0), y1 = smaller(floor(d * g->range[1][1] - 0.5), height - 1.0);
    double u0 = d * g->range[2][0] - 1.0, u1 = d * g->range[2][1] - 1.0, v0 = d * g->range[3][0], v1 = d * g->range[3][1];
    if (y0 > y1) return false;
    int shift = t->shift, last = (int)y1 >> shift;
    for (int row = (int)y0 >> shift; row <= last; row++) {
        double top = larger(row << shift, y0), bottom = smaller(((row + 1) << shift) - 1, y1); /* its pixel rows */
        double from = larger(ceil(larger(x0, larger(u0 - bottom, v0 + top))), 0.0);
        double to = smaller(floor(smaller(x1, smaller(u1 - top, v1 + bottom))), width - 1.0);
        if (from > to) continue;
        int c0 = (int)from >> shift, c1 = (int)to >> shift;
        memset(&t->mask[row * t->columns + c0], 1, (size_t)(c1 - c0 + 1));
    }
    return false;
}

/* Runs of `value` along each row, merged down the rows where a run spans the same columns as the
 * one above it, appended to t->rects from `first`; the count, or -1 when they do not fit. */
static int build_rects(sbfx_tiles *t, uint8_t value, int first)
{
    int open[2][SBFX_TILE_GRID / 2 + 1], open_count[2] = {0, 0}; /* the previous row's rects */
    int n = first;
    for (int y = 0; y < t->rows; y++) {
        const uint8_t *row = &t->mask[y * t->columns];
        int *above = open[(y + 1) & 1], *here = open[y & 1];
        int above_count = open_count[(y + 1) & 1], k = 0;
        open_count[y & 1] = 0;
        for (int x = 0; x < t->columns;) {
            if (row[x] != value) { x++; continue; }
            int end = x;
            while (end < t->columns && row[end] == value) end++;
            while (k < above_count && t->rects[above[k]].x0 < x) k++;
            int r;
            if (k < above_count && t->rects[above[k]].x0 == x && t->rects[above[k]].x1 == end) {
                r = above[k];
                t->rects[r].y1 = (uint16_t)(y + 1);
            } else {
                if (n == SBFX_TILE_RECTS) return -1;
                r = n++;
                t->rects[r] = (sbfx_tile_rect){(uint16_t)x, (uint16_t)y, (uint16_t)end, (uint16_t)(y + 1)};
            }
            here[open_count[y & 1]++] = r;
            x = end;
        }
    }
    return n - first;
}

/* Too many rectangles (particles strewn over the screen): each row's marked tiles become one
 * span from its first to its last, at most a rectangle a row inside and two outside. */
static void fill_row_gaps(sbfx_tiles *t)
{
    for (int y = 0; y < t->rows; y++) {
        uint8_t *row = &t->mask[y * t->columns];
        int first = 0, last = t->columns - 1;
        while (first < t->columns && !row[first]) first++;
        while (last > first && !row[last]) last--;
        if (first < last) memset(row + first, 1, (size_t)(last - first + 1));
    }
}

static void count_cover(sbfx_tiles *t, int width, int height)
{
    t->marked = 0;
    for (int i = 0; i < t->columns * t->rows; i++) t->marked += t->mask[i];
    t->pixels = 0;
    for (int i = 0; i < t->inside; i++) {
        const sbfx_tile_rect *r = &t->rects[i];
        int x1 = r->x1 * t->size > width ? width : r->x1 * t->size;
        int y1 = r->y1 * t->size > height ? height : r->y1 * t->size;
        t->pixels += (long long)(x1 - r->x0 * t->size) * (y1 - r->y0 * t->size);
    }
}

static void make_rects(sbfx_tiles *t, bool outside)
{
    for (int attempt = 0; attempt < 2; attempt++) {
        int inside = build_rects(t, 1, 0);
        int rest = inside < 0 ? -1 : outside ? build_rects(t, 0, inside) : 0;
        if (inside >= 0 && rest >= 0) {
            t->inside = inside, t->outside = rest;
            return;
        }
        fill_row_gaps(t);
    }
    t->inside = t->outside = 0; /* not reached: a row holds at most one span and two gaps */
}

/* The grid over the output: SBFX_TILE_SIZE pixels a tile (or the size a test or the bench
 * wants), doubled until the grid fits. */
static void size_grid(sbfx_tiles *t, int width, int height)
{
    int wanted = t->size_wanted > 0 ? t->size_wanted : SBFX_TILE_SIZE;
    for (t->shift = 3; (1 << t->shift) < wanted; t->shift++) {}
    t->size = 1 << t->shift;
    while ((width + t->size - 1) / t->size > SBFX_TILE_GRID || (height + t->size - 1) / t->size > SBFX_TILE_GRID)
        t->size = 1 << ++t->shift;
    t->columns = (width + t->size - 1) / t->size;
    t->rows = (height + t->size - 1) / t->size;
}

/* The marked tiles as rectangles, the rest's too where sbfx owns the scene, into the buffer. */
static void upload_rects(sbfx *fx, const sbfx_frame *f)
{
    sbfx_tiles *t = &fx->render->tiles;
    make_rects(t, fx->scene->plan.owns_scene);
    count_cover(t, f->width, f->height);
    fx->counters.composite_tiles = t->marked;
    fx->counters.composite_pixels = (int)t->pixels;
    int rects = t->inside + t->outside;
    if (rects == 0) return;
    glBindBuffer(GL_ARRAY_BUFFER, t->buffer);
    glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)(rects * sizeof(sbfx_tile_rect)), t->rects);
}

void sbfx_tiles_plan(sbfx *fx, const sbfx_frame *f, const frame_params *fp, int count)
{
    sbfx_tiles *t = &fx->render->tiles;
    const sbfx_gl *gl = fx->gl;
    int divisor = fx->scene->desc.target_divisor;
    size_grid(t, f->width, f->height);
    bool all = t->full_screen;
    memset(t->mask, all ? 1 : 0, (size_t)(t->columns * t->rows));
    region_axis axes[4];
    region_axes(fp, gl->low_width, gl->low_height, fx->scene->desc.opacity == SBFX_OPACITY_FLOOR, axes);
    for (int i = 0; i < count && !all; i++) {
        particle_region g;
        if (particle_region_of(&fx->sim->view[i], fp, axes, gl->low_width, gl->low_height, &g))
            all = mark_particle(t, &g, divisor, f->width, f->height);
    }
    if (all) memset(t->mask, 1, (size_t)(t->columns * t->rows));
    upload_rects(fx, f);
}

void sbfx_tiles_plan_idle(sbfx *fx, const sbfx_frame *f)
{
    sbfx_tiles *t = &fx->render->tiles;
    size_grid(t, f->width, f->height);
    memset(t->mask, t->full_screen ? 1 : 0, (size_t)(t->columns * t->rows));
    upload_rects(fx, f);
}

bool sbfx_tiles_any(const sbfx *fx) { return fx->render->tiles.inside > 0; }

bool sbfx_tiles_box(const sbfx *fx, const frame_params *fp, const sbfx_view_particle *v, int box[4])
{
    const sbfx_tiles *t = &fx->render->tiles;
    const sbfx_gl *gl = fx->gl;
    region_axis axes[4];
    region_axes(fp, gl->low_width, gl->low_height, fx->scene->desc.opacity == SBFX_OPACITY_FLOOR, axes);
    particle_region g;
    if (!particle_region_of(v, fp, axes, gl->low_width, gl->low_height, &g)) return false;
    const double d = fx->scene->desc.target_divisor;
    const int last[2] = {t->columns - 1, t->rows - 1};
    for (int k = 0; k < 2; k++) { /* output pixels (p + 1/2 = d q), then tiles, clamped to the grid */
        double lo = smaller(larger(floor(d * g.range[k][0] - 0.5), 0.0), (double)(last[k] << t->shift));
        double hi = smaller(larger(ceil(d * g.range[k][1] - 0.5), 0.0), (double)(last[k] << t->shift));
        box[k] = (int)lo >> t->shift;
        box[2 + k] = (int)hi >> t->shift;
    }
    return true;
}

void sbfx_tiles_draw(sbfx *fx, const sbfx_pass_uniforms *u, bool inside, int width, int height, int divisor)
{
    const sbfx_tiles *t = &fx->render->tiles;
    int first = inside ? 0 : t->inside, n = inside ? t->inside : t->outside;
    if (n == 0) return;
    glUniform2f(u->tile_size, (float)t->size / (float)divisor, (float)t->size / (float)divisor);
    glUniform2f(u->tile_grid, (float)t->columns, (float)t->rows);
    glUniform2f(u->tile_target, (float)width, (float)height);
    glBindVertexArray(t->vao);
    glBindBuffer(GL_ARRAY_BUFFER, t->buffer);
    glVertexAttribPointer(0, 4, GL_UNSIGNED_SHORT, GL_FALSE, sizeof(sbfx_tile_rect),
                          (const void *)(size_t)((size_t)first * sizeof(sbfx_tile_rect)));
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, n);
    fx->counters.draw_calls++;
}
