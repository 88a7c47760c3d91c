/* The mode a board profile or --mode asks for (drm_mode_spec.h). */
#include "drm/drm_mode_spec.h"

#include <errno.h>
#include <stdlib.h>

/* A run of decimal digits at *p as a number in 1..max, advancing *p; -1 if there is none. */
static long read_number(const char **p, long max)
{
    if (**p < '0' || **p > '9') return -1;
    char *end = NULL;
    long v = strtol(*p, &end, 10);
    *p = end;
    return v >= 1 && v <= max ? v : -1;
}

int mode_spec_parse(const char *text, int *width, int *height, int *refresh)
{
    const char *p = text;
    if (!p) return -EINVAL;
    long w = read_number(&p, 16384);
    if (w < 0 || *p++ != 'x') return -EINVAL;
    long h = read_number(&p, 16384), hz = 0;
    if (h > 0 && *p == '@') {
        p++;
        hz = read_number(&p, 1000);
    }
    if (h < 0 || hz < 0 || *p != '\0') return -EINVAL;
    *width = (int)w, *height = (int)h, *refresh = (int)hz;
    return 0;
}
