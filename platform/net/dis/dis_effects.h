/* Which effect a detonation sets off: the scene's dis.effects, a list of rules
 *     { munition = "K.D.C.C.S.S.E"; result = N; effect = "NAME"; }
 * tried in order, the first match wins, dis.default when none matches (and without it the
 * detonation is ignored). munition is the descriptor's entity type, kind.domain.country.category.
 * subcategory.specific.extra, each field a number or "*" (any); "*" alone matches every type.
 * result (optional: any) is the detonation result (SISO-REF-010: 0 other, 1 entity impact,
 * 3 ground impact, 5 detonation, 7 air burst...). Pure logic, no I/O. */
#ifndef SBFX_DIS_EFFECTS_H
#define SBFX_DIS_EFFECTS_H

#include <stdbool.h>

#include "net/dis/dis_pdu.h"

#define DIS_EFFECTS_MAX 64
#define DIS_EFFECT_NAME_MAX 64
#define DIS_MUNITION_FIELDS 7
#define DIS_ANY (-1)

struct dis_effect_rule {
    int munition[DIS_MUNITION_FIELDS]; /* each a value or DIS_ANY */
    int result;                        /* 0..255 or DIS_ANY */
    char effect[DIS_EFFECT_NAME_MAX];
};

struct dis_effect_map {
    struct dis_effect_rule rules[DIS_EFFECTS_MAX];
    int count;
    char fallback[DIS_EFFECT_NAME_MAX]; /* dis.default; "" for none */
};

/* "K.D.C.C.S.S.E" (seven fields, each a number in the field's range or "*") or "*": 0, or -1
 * with the reason in why. */
int dis_munition_parse(const char *text, int fields[DIS_MUNITION_FIELDS], const char **why);
/* The effect for a detonation's munition type and result: the first rule that matches, else the
 * fallback; NULL when there is neither. */
const char *dis_effect_find(const struct dis_effect_map *m, const struct dis_entity_type *type,
                            int result);
/* "2.9.225.2.1.*.*" for messages (out: at least 48 bytes). */
void dis_munition_format(const int fields[DIS_MUNITION_FIELDS], char *out, int n);

#endif
