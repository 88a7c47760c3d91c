/* An effect at a place, EFFECT[@X,Y,Z]: the syntax --gpio's value ends with and an MQTT
 * trigger's payload is. Pure parsing, no module needed. */
#ifndef SBFX_EFFECT_AT_H
#define SBFX_EFFECT_AT_H

#include <stdbool.h>
#include <stddef.h>

#define EFFECT_NAME_MAX 64

/* 1..63 of A-Z a-z 0-9 _ - . */
bool effect_name_valid(const char *name, size_t len);
/* "X,Y,Z": three finite numbers, the whole of s. */
bool effect_position_parse(const char *s, float position[3]);
/* "EFFECT" or "EFFECT@X,Y,Z" in text[0..len) (not NUL-terminated: a payload): the name and the
 * position (the origin when not given). NULL, or what is wrong. */
const char *effect_at_parse(const char *text, size_t len, char effect[EFFECT_NAME_MAX], float position[3]);

#endif
