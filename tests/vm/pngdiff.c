/* tests/vm helper: compares two PNGs of the same size channel by channel (RGB; alpha ignored:
 * a display has none). Prints "max M mean X differing D of N pixels" and exits 0; exits 2 when
 * a file cannot be read or the sizes differ. */
#include <stdio.h>
#include <stdlib.h>

#include "image/png_io.h"

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: pngdiff A.png B.png\n");
        return 2;
    }
    uint8_t *a = NULL, *b = NULL;
    int wa, ha, wb, hb;
    char err[512];
    if (png_read_rgba(argv[1], &a, &wa, &ha, err, sizeof(err)) != 0 ||
        png_read_rgba(argv[2], &b, &wb, &hb, err, sizeof(err)) != 0) {
        fprintf(stderr, "pngdiff: %s\n", err);
        free(a);
        return 2;
    }
    if (wa != wb || ha != hb) {
        fprintf(stderr, "pngdiff: %dx%d vs %dx%d\n", wa, ha, wb, hb);
        free(a), free(b);
        return 2;
    }
    int max = 0;
    long long sum = 0, differing = 0, pixels = (long long)wa * ha;
    for (long long i = 0; i < pixels; i++) {
        int worst = 0;
        for (int c = 0; c < 3; c++) {
            int d = abs((int)a[4 * i + c] - (int)b[4 * i + c]);
            sum += d;
            if (d > worst) worst = d;
        }
        if (worst) differing++;
        if (worst > max) max = worst;
    }
    printf("max %d mean %.5f differing %lld of %lld pixels\n", max, (double)sum / (3.0 * pixels),
           differing, pixels);
    free(a), free(b);
    return 0;
}
