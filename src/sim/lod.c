/* Particle level of detail, the ladder's last resort: lod.h has the math and the contract. */
#include "sim/lod.h"

#include <float.h>
#include <math.h>
#include <string.h>

#define LOD_MORTON_BITS 10 /* per axis: 30 bits, the medium in the top 2 */

size_t lod_work_size(int max_particles)
{
    size_t n = max_particles > 0 ? (size_t)max_particles : 1;
    return n * (6 * sizeof(uint32_t) + sizeof(float) + sizeof(uint8_t));
}

void lod_init(particle_lod *l, void *work, int max_particles)
{
    size_t n = max_particles > 0 ? (size_t)max_particles : 1;
    uint32_t *u = work;
    *l = (particle_lod){.capacity = (int)n};
    l->key = u, l->key_tmp = u + n, l->idx = u + 2 * n, l->idx_tmp = u + 3 * n;
    l->pair_a = u + 4 * n, l->pair_b = u + 5 * n;
    l->weight = (float *)(u + 6 * n);
    l->gone = (uint8_t *)(l->weight + n);
}

double lod_weight(const sbfx_view_particle *p)
{
    double r = p->radius, i = p->intensity;
    double d2 = (double)p->center[0] * p->center[0] + (double)p->center[1] * p->center[1]
              + (double)p->center[2] * p->center[2];
    double w = i * r * r * r / fmax(d2, r * r);
    return isfinite(w) && w > 0.0 && r > 0.0 ? w : 0.0;
}

/* Stable LSD radix sort of idx[0..n) by key, 4 passes of 8 bits (ends in the same arrays). */
static void lod_sort(particle_lod *l, int n)
{
    uint32_t *k = l->key, *kt = l->key_tmp, *x = l->idx, *xt = l->idx_tmp;
    for (int shift = 0; shift < 32; shift += 8) {
        uint32_t start[256] = {0};
        for (int i = 0; i < n; i++) start[(k[i] >> shift) & 255u]++;
        uint32_t sum = 0;
        for (int b = 0; b < 256; b++) {
            uint32_t c = start[b];
            start[b] = sum;
            sum += c;
        }
        for (int i = 0; i < n; i++) {
            uint32_t at = start[(k[i] >> shift) & 255u]++;
            kt[at] = k[i], xt[at] = x[i];
        }
        uint32_t *t = k; k = kt, kt = t;
        t = x, x = xt, xt = t;
    }
}

/* IEEE bits of a non-negative float order like its value; NaN and Inf sort last. */
static uint32_t lod_float_key(double v)
{
    float f = isfinite(v) && v >= 0.0 ? (float)fmin(v, FLT_MAX) : FLT_MAX;
    uint32_t bits;
    memcpy(&bits, &f, sizeof(bits));
    return bits;
}

static uint32_t lod_spread_bits(uint32_t x)
{
    x &= 0x3ffu;
    x = (x | (x << 16)) & 0x030000ffu;
    x = (x | (x << 8)) & 0x0300f00fu;
    x = (x | (x << 4)) & 0x030c30c3u;
    x = (x | (x << 2)) & 0x09249249u;
    return x;
}

/* Medium, then the Morton code of the centre over the centres' bounding box. */
static void lod_morton_keys(particle_lod *l, const sbfx_view_particle *v, int n)
{
    float lo[3] = {FLT_MAX, FLT_MAX, FLT_MAX}, hi[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX};
    for (int i = 0; i < n; i++)
        for (int a = 0; a < 3; a++)
            lo[a] = fminf(lo[a], v[i].center[a]), hi[a] = fmaxf(hi[a], v[i].center[a]);
    for (int i = 0; i < n; i++) {
        uint32_t code = 0;
        for (int a = 0; a < 3; a++) {
            double extent = (double)hi[a] - lo[a];
            double q = extent > 0.0 ? ((double)v[i].center[a] - lo[a]) / extent * 1023.0 : 0.0;
            uint32_t qi = q > 0.0 ? (uint32_t)fmin(q + 0.5, 1023.0) : 0u;
            code |= lod_spread_bits(qi) << a;
        }
        l->key[i] = ((uint32_t)v[i].medium & 3u) << (3 * LOD_MORTON_BITS) | code;
        l->idx[i] = (uint32_t)i;
    }
}

/* Consecutive particles of one medium along the curve; returns the number of pairs. */
static int lod_pairs(particle_lod *l, const sbfx_view_particle *v, int n)
{
    int pairs = 0;
    for (int s = 0; s + 1 < n;) {
        uint32_t a = l->idx[s], b = l->idx[s + 1];
        if (v[a].medium == v[b].medium) {
            l->pair_a[pairs] = a, l->pair_b[pairs++] = b;
            s += 2;
        } else {
            s++;
        }
    }
    return pairs;
}

static double lod_pair_cost(const particle_lod *l, const sbfx_view_particle *v, uint32_t a, uint32_t b)
{
    double d2 = 0.0, rr = (double)v[a].radius + v[b].radius;
    for (int k = 0; k < 3; k++) {
        double d = (double)v[a].center[k] - v[b].center[k];
        d2 += d * d;
    }
    return ((double)l->weight[a] + l->weight[b]) * (1.0 + d2 / (rr * rr));
}

/* a := the merge of a and b (lod.h: w, w·I and the centroid conserved). */
static void lod_merge(sbfx_view_particle *a, const sbfx_view_particle *b)
{
    double wa = lod_weight(a), wb = lod_weight(b), w = wa + wb;
    if (!(w > 0.0))
        return; /* both invisible: b goes, a stays as it was */
    double intensity = (wa * a->intensity + wb * b->intensity) / w, c[3], p[3], d2 = 0.0;
    for (int k = 0; k < 3; k++) {
        c[k] = (wa * a->center[k] + wb * b->center[k]) / w;
        p[k] = (wa * a->previous_center[k] + wb * b->previous_center[k]) / w;
        d2 += c[k] * c[k];
    }
    double r = cbrt(w * d2 / intensity);
    if (r * r > d2)
        r = w / intensity; /* the camera inside: D is floored at r, w = I r */
    if (!((float)r > 0.0f) || !isfinite((float)r)) { /* degenerate sizes: keep the heavier */
        if (wb > wa)
            *a = *b;
        return;
    }
    if (wb > wa)
        memcpy(a->detail, b->detail, sizeof(a->detail));
    for (int k = 0; k < 3; k++)
        a->center[k] = (float)c[k], a->previous_center[k] = (float)p[k];
    a->radius = (float)r;
    a->intensity = (float)intensity;
}

static int lod_compact(particle_lod *l, sbfx_view_particle *v, int n)
{
    int kept = 0;
    for (int i = 0; i < n; i++)
        if (!l->gone[i]) {
            if (kept != i) v[kept] = v[i];
            kept++;
        }
    return kept;
}

/* One round: pair along the curve, merge the cheapest pairs (all of them if more must go). */
static int lod_round(particle_lod *l, sbfx_view_particle *v, int n, int max_count)
{
    for (int i = 0; i < n; i++)
        l->weight[i] = (float)lod_weight(&v[i]);
    lod_morton_keys(l, v, n);
    lod_sort(l, n);
    int pairs = lod_pairs(l, v, n);
    int merge = n - max_count < pairs ? n - max_count : pairs;
    if (merge <= 0)
        return n;
    if (merge < pairs) {
        for (int p = 0; p < pairs; p++) {
            l->key[p] = lod_float_key(lod_pair_cost(l, v, l->pair_a[p], l->pair_b[p]));
            l->idx[p] = (uint32_t)p;
        }
        lod_sort(l, pairs);
    } else {
        for (int p = 0; p < pairs; p++) l->idx[p] = (uint32_t)p;
    }
    memset(l->gone, 0, (size_t)n);
    for (int s = 0; s < merge; s++) {
        uint32_t p = l->idx[s];
        lod_merge(&v[l->pair_a[p]], &v[l->pair_b[p]]);
        l->gone[l->pair_b[p]] = 1;
    }
    l->merges += merge;
    return lod_compact(l, v, n);
}

/* Where merging cannot go further (one particle per medium left): the least weighty go. */
static int lod_drop(particle_lod *l, sbfx_view_particle *v, int n, int max_count)
{
    for (int i = 0; i < n; i++) {
        l->key[i] = lod_float_key(lod_weight(&v[i]));
        l->idx[i] = (uint32_t)i;
    }
    lod_sort(l, n);
    memset(l->gone, 0, (size_t)n);
    for (int s = 0; s < n - max_count; s++)
        l->gone[l->idx[s]] = 1;
    l->drops += n - max_count;
    return lod_compact(l, v, n);
}

int lod_reduce(particle_lod *l, sbfx_view_particle *v, int count, int max_count)
{
    l->merges = l->drops = 0;
    if (max_count < 1)
        max_count = 1;
    if (count > l->capacity)
        count = l->capacity; /* never past the work memory (the pool's capacity) */
    while (count > max_count) {
        int n = lod_round(l, v, count, max_count);
        if (n == count)
            return lod_drop(l, v, n, max_count);
        count = n;
    }
    return count;
}
