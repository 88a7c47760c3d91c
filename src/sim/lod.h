/* The quality ladder's last resort (docs/design.md §6, issue 11 item 2): particle level of detail that
 * draws at most N particles (the `lodN` flag of a level name) at any load, merging the least
 * visible nearby particles of one medium while conserving their integrated optical depth and
 * their light. No GL, no allocation (work memory sized at load), deterministic.
 *
 * The math. Every opacity model's optical depth through a particle (docs/design.md §2.1) is
 * τ_medium · intensity · r · f(d / r, ...) — the profile (1 − d/r) times a chord ∝ r — so its
 * integral over the area it covers, seen from distance D (solid angle dΩ = dA / D²), is
 *
 *     ∫ τ dΩ  =  τ_medium · k_model · I · r³ / D²        (exact model: k = π/3)
 *
 * the particle's *weight* w = I r³ / D² (D = |centre|, floored at r: camera inside). In the
 * optically thin limit the image is the sum of these integrals, so a merge conserves the image's
 * opacity to first order if it conserves Σ w per medium; light likewise: scattered light is
 * albedo · C_in · α (C_in nearly equal at nearby points), emitted light L_e(T(I)) · α with the
 * fire's temperature linear in I. A merge of particles a, b (one medium) into m:
 *
 *     w_m = w_a + w_b                                      (∫τ dΩ conserved exactly)
 *     I_m = (w_a I_a + w_b I_b) / w_m                      (so Σ w·I conserved exactly: the
 *                                                           density look, the fire's temperature
 *                                                           and its light to first order)
 *     c_m = (w_a c_a + w_b c_b) / w_m                      (the opacity's centroid)
 *     r_m = cbrt(w_m D_m² / I_m),  D_m = |c_m|             (from w_m = I_m r_m³ / D_m²)
 *     previous centre weighted like c_m; detail window of the heavier one.
 * (A merge whose radius would not be a positive finite float — radii near 1e-30 or 1e30 —
 * keeps the heavier particle instead.)
 *
 * What a merge does not keep: the overlap of the two (optically thick parts saturate
 * differently) and the spread (one sphere at the centroid instead of two): the error that the
 * bench measures against the CPU reference for each lodN level (docs/quality-and-budgets.md "Frame budgets").
 *
 * Which particles: the centres are ordered along a Morton (Z-order) curve over their bounding
 * box, medium first (radix sort), and consecutive particles of one medium are paired; a pair's
 * cost is its visibility times its spread,
 *
 *     cost = (w_a + w_b) · (1 + |c_a − c_b|² / (r_a + r_b)²)
 *
 * and the count − N cheapest pairs are merged (all pairs when more must go, and again, each
 * round halving the count at most). Only when fewer particles of one medium than media present
 * remain (N below the number of media drawn) are the least weighty particles dropped.
 * count ≤ N never changes anything: a level without lodN, or a load under N, is bit-identical.
 *
 * Use (the render path, before the back-to-front sort):
 *     at load:  fx->lod_work = sbfx_calloc(fx, 1, lod_work_size(capacity));
 *               lod_init(&fx->lod, fx->lod_work, capacity);
 *     a frame:  count = lod_reduce(&fx->lod, fx->view, count, n_of_lodN);
 * lod_reduce rewrites v[0 .. returned count) in place (the merged particles, in the order of
 * their first member), never more than max_count, never more than it was given. */
#ifndef SBFX_LOD_H
#define SBFX_LOD_H

#include <stddef.h>
#include <stdint.h>
#include "sim/particles.h"

typedef struct particle_lod {
    int capacity;
    uint32_t *key, *key_tmp;    /* sort keys (Morton codes, then pair costs) */
    uint32_t *idx, *idx_tmp;    /* sort order */
    uint32_t *pair_a, *pair_b;  /* candidate pairs */
    float *weight;              /* w of each particle */
    uint8_t *gone;              /* merged into another this round */
    int merges, drops;          /* of the last call */
} particle_lod;

size_t lod_work_size(int max_particles);
/* `work`: lod_work_size(max_particles) bytes, aligned for uint32_t/float (calloc's). */
void lod_init(particle_lod *l, void *work, int max_particles);
/* At most max_count particles left (max_count < 1 counts as 1); returns the new count. */
int lod_reduce(particle_lod *l, sbfx_view_particle *v, int count, int max_count);
/* w = I r³ / D² of one particle (0 for a non-finite or empty one): what merges conserve. */
double lod_weight(const sbfx_view_particle *p);

#endif
