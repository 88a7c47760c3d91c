/* The dis.effects table (dis_effects.h). */
#include "net/dis/dis_effects.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The largest value of each entity type field: country is 16 bits, the others 8. */
static const long field_max[DIS_MUNITION_FIELDS] = {255, 255, 65535, 255, 255, 255, 255};

/* One field at *p ("*" or decimal digits), advancing *p; -2 when it is neither or out of range. */
static long read_field(const char **p, long max)
{
    if (**p == '*') {
        (*p)++;
        return DIS_ANY;
    }
    if (**p < '0' || **p > '9') return -2;
    char *end = NULL;
    long v = strtol(*p, &end, 10);
    *p = end;
    return v <= max ? v : -2;
}

int dis_munition_parse(const char *text, int fields[DIS_MUNITION_FIELDS], const char **why)
{
    if (strcmp(text, "*") == 0) {
        for (int i = 0; i < DIS_MUNITION_FIELDS; i++) fields[i] = DIS_ANY;
        return 0;
    }
    const char *p = text;
    for (int i = 0; i < DIS_MUNITION_FIELDS; i++) {
        long v = read_field(&p, field_max[i]);
        if (v == -2) {
            *why = i == 2 ? "the country must be * or 0..65535" : "a field must be * or 0..255";
            return -1;
        }
        fields[i] = (int)v;
        if (i < DIS_MUNITION_FIELDS - 1 && *p++ != '.') {
            *why = "the entity type has seven fields, kind.domain.country.category.subcategory.specific.extra";
            return -1;
        }
    }
    if (*p) {
        *why = "the entity type has seven fields, kind.domain.country.category.subcategory.specific.extra";
        return -1;
    }
    return 0;
}

static bool matches(const struct dis_effect_rule *r, const int type[DIS_MUNITION_FIELDS], int result)
{
    for (int i = 0; i < DIS_MUNITION_FIELDS; i++)
        if (r->munition[i] != DIS_ANY && r->munition[i] != type[i]) return false;
    return r->result == DIS_ANY || r->result == result;
}

const char *dis_effect_find(const struct dis_effect_map *m, const struct dis_entity_type *t, int result)
{
    const int type[DIS_MUNITION_FIELDS] = {t->kind, t->domain, t->country, t->category, t->subcategory,
                                           t->specific, t->extra};
    for (int i = 0; i < m->count; i++)
        if (matches(&m->rules[i], type, result)) return m->rules[i].effect;
    return m->fallback[0] ? m->fallback : NULL;
}

void dis_munition_format(const int fields[DIS_MUNITION_FIELDS], char *out, int n)
{
    int used = 0;
    out[0] = '\0';
    for (int i = 0; i < DIS_MUNITION_FIELDS && used < n; i++) {
        int w = fields[i] == DIS_ANY ? snprintf(out + used, (size_t)(n - used), "%s*", i ? "." : "")
                                     : snprintf(out + used, (size_t)(n - used), "%s%d", i ? "." : "", fields[i]);
        if (w < 0) return;
        used += w;
    }
}
