/* EFFECT[@X,Y,Z] (effect_at.h). */
#include "gpio/effect_at.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define TEXT_MAX 160

bool effect_name_valid(const char *name, size_t len)
{
    if (len == 0 || len >= EFFECT_NAME_MAX) return false;
    for (size_t i = 0; i < len; i++) {
        unsigned char c = (unsigned char)name[i];
        if (!isalnum(c) && c != '_' && c != '-' && c != '.') return false;
    }
    return true;
}

bool effect_position_parse(const char *s, float position[3])
{
    for (int k = 0; k < 3; k++) {
        if (!*s || isspace((unsigned char)*s)) return false;
        char *end = NULL;
        errno = 0;
        double v = strtod(s, &end);
        if (end == s || errno == ERANGE || !isfinite(v)) return false;
        if (*end != (k < 2 ? ',' : '\0')) return false;
        position[k] = (float)v;
        s = end + (k < 2);
    }
    return true;
}

const char *effect_at_parse(const char *text, size_t len, char effect[EFFECT_NAME_MAX], float position[3])
{
    char buf[TEXT_MAX];
    if (len >= sizeof(buf)) return "longer than 159 bytes";
    if (memchr(text, '\0', len)) return "a NUL byte inside";
    memcpy(buf, text, len);
    buf[len] = '\0';
    const char *at = strchr(buf, '@');
    size_t name_len = at ? (size_t)(at - buf) : len;
    if (!effect_name_valid(buf, name_len)) return "the effect name must be 1..63 of A-Z a-z 0-9 _ - .";
    float p[3] = {0, 0, 0};
    if (at && !effect_position_parse(at + 1, p)) return "the position must be three finite numbers X,Y,Z";
    memcpy(effect, buf, name_len);
    effect[name_len] = '\0';
    memcpy(position, p, sizeof(p));
    return NULL;
}
