/* tests/seam.sh's judge: the frames of N channels side by side against the one wide frame, every
 * differing pixel accounted for (docs/simulators.md "What the seam test proves").
 *
 *   seam_check BAND TOLERANCE WIDE.png HOST_WIDE.png SLICE.png... -- HOST_SLICE.png...
 *
 * The slices are joined left to right (equal heights); HOST_* are the same frames drawn without
 * any effect (the host's test scene alone). A pixel whose RGB differs is accounted for when
 *   seam  it lies within BAND pixels of a seam: a channel's particle target ends at its edge, so
 *         the upsample there clamps where the wide frame reads the neighbour's texels;
 *   host  the host's own picture differs there (its triangles rasterised through another
 *         projection), which sbfx composites over;
 *   texel its value is one the wide frame has within BAND pixels (each channel between the least
 *         and the most there): the nearest-depth upsample picks, of the particle target's texels
 *         around a pixel, the one whose depth is nearest the host's; where two are nearly equal,
 *         the rounding of another projection picks the other, a neighbour's colour;
 *   ray   it differs by at most TOLERANCE (of 255): each channel's rays come through its own
 *         projection matrix, rounded in float, so a sample can land a rounding away.
 * Prints the counts and exits 1 when any pixel is left unaccounted for (2: unreadable input). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image/png_io.h"

struct image {
    uint8_t *px;
    int w, h;
};

static int load(const char *path, struct image *im)
{
    char err[512];
    if (png_read_rgba(path, &im->px, &im->w, &im->h, err, sizeof(err)) == 0) return 0;
    fprintf(stderr, "seam_check: %s\n", err);
    return 2;
}

/* The slices joined left to right; seams[] gets each inner edge's x. */
static int join(char **paths, int count, struct image *out, int *seams)
{
    struct image parts[16] = {{0}};
    int width = 0;
    for (int i = 0; i < count; i++) {
        if (load(paths[i], &parts[i])) return 2;
        if (i && parts[i].h != parts[0].h) {
            fprintf(stderr, "seam_check: %s is %d rows high, %s %d\n", paths[i], parts[i].h, paths[0], parts[0].h);
            return 2;
        }
        if (i) seams[i - 1] = width;
        width += parts[i].w;
    }
    out->w = width, out->h = parts[0].h;
    out->px = malloc((size_t)width * out->h * 4);
    for (int y = 0, x0 = 0; y < out->h; y++, x0 = 0)
        for (int i = 0; i < count; x0 += parts[i].w, i++)
            memcpy(out->px + ((size_t)y * width + x0) * 4, parts[i].px + (size_t)y * parts[i].w * 4,
                   (size_t)parts[i].w * 4);
    for (int i = 0; i < count; i++) free(parts[i].px);
    return 0;
}

static int difference(const struct image *a, const struct image *b, size_t i)
{
    int d = 0;
    for (int k = 0; k < 3; k++) {
        int e = abs(a->px[4 * i + k] - b->px[4 * i + k]);
        if (e > d) d = e;
    }
    return d;
}

/* The joined pixel's RGB lies, channel by channel, within what the wide frame has around it. */
static bool among_neighbours(const struct image *wide, const struct image *joined, int x, int y, int band)
{
    size_t i = (size_t)y * wide->w + x;
    for (int k = 0; k < 3; k++) {
        int lo = 255, hi = 0, v = joined->px[4 * i + k];
        for (int yy = y - band; yy <= y + band; yy++)
            for (int xx = x - band; xx <= x + band; xx++) {
                if (xx < 0 || yy < 0 || xx >= wide->w || yy >= wide->h) continue;
                int w = wide->px[4 * ((size_t)yy * wide->w + xx) + k];
                lo = w < lo ? w : lo, hi = w > hi ? w : hi;
            }
        if (v < lo || v > hi) return false;
    }
    return true;
}

int main(int argc, char **argv)
{
    int dash = 0;
    for (int i = 5; i < argc; i++)
        if (strcmp(argv[i], "--") == 0) dash = i;
    int slices = dash - 5;
    if (argc < 7 || !dash || slices < 1 || slices > 16 || argc - dash - 1 != slices) {
        fprintf(stderr, "usage: seam_check BAND TOLERANCE WIDE.png HOST_WIDE.png SLICE.png... -- HOST_SLICE.png...\n");
        return 2;
    }
    int band = atoi(argv[1]), tolerance = atoi(argv[2]);
    struct image wide, host_wide, joined, host_joined;
    int seams[16], host_seams[16];
    if (load(argv[3], &wide) || load(argv[4], &host_wide) || join(argv + 5, slices, &joined, seams) ||
        join(argv + dash + 1, slices, &host_joined, host_seams))
        return 2;
    if (joined.w != wide.w || joined.h != wide.h || host_wide.w != wide.w || host_joined.w != wide.w) {
        fprintf(stderr, "seam_check: the slices make %dx%d, the wide frame is %dx%d\n", joined.w, joined.h, wide.w,
                wide.h);
        return 2;
    }
    long long seam = 0, host = 0, texel = 0, ray = 0, left = 0, differing = 0;
    int worst = 0, worst_x = -1, worst_y = -1;
    for (int y = 0; y < wide.h; y++)
        for (int x = 0; x < wide.w; x++) {
            size_t i = (size_t)y * wide.w + x;
            int d = difference(&wide, &joined, i);
            if (!d) continue;
            differing++;
            bool near_seam = false;
            for (int s = 0; s < slices - 1; s++) near_seam |= x >= seams[s] - band && x < seams[s] + band;
            if (near_seam) seam++;
            else if (difference(&host_wide, &host_joined, i)) host++;
            else if (among_neighbours(&wide, &joined, x, y, band)) texel++;
            else if (d <= tolerance) ray++;
            else {
                left++;
                if (d > worst) worst = d, worst_x = x, worst_y = y;
            }
        }
    printf("%dx%d: %lld pixels differ: %lld at the seams (within %d px), %lld where the host's picture differs, "
           "%lld a neighbour's value (upsample), %lld by at most %d (rays), %lld unaccounted for", wide.w, wide.h,
           differing, seam, band, host, texel, ray, tolerance, left);
    if (left) printf(" (the largest %d at %d,%d)", worst, worst_x, worst_y);
    printf("\n");
    return left ? 1 : 0;
}
