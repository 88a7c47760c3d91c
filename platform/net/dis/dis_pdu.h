/* DIS (IEEE 1278.1) PDUs out of a UDP datagram: any PDU's header, and the body of the Detonation
 * PDU (type 3, family 2 "warfare"), for protocol versions 6 (IEEE 1278.1a-1998) and 7
 * (IEEE 1278.1-2012). Pure functions over a byte buffer: no allocation, no I/O; fuzzed
 * (tests/fuzz/fuzz_dis.c, make fuzz).
 *
 * Big-endian; offsets in bytes. The fields and their sizes are those the standard gives and
 * Open-DIS marshals in this order (open-dis-cpp src/dis6/DetonationPdu.cpp, src/dis7/Pdu.cpp and
 * DetonationPdu.cpp: EntityID 6, EventID 6, Vector3Float 12, Vector3Double 24, BurstDescriptor /
 * MunitionDescriptor 16 (EntityType 8 + 4 x u16), ArticulationParameter / VariableParameter 16):
 *     0  protocol version u8        1  exercise ID u8        2  PDU type u8 (3)
 *     3  protocol family u8 (2)     4  timestamp u32         8  length u16 (the whole PDU)
 *    10  padding u16 (v7: PDU status u8, padding u8)
 *    12  firing entity ID (site u16, application u16, entity u16)
 *    18  target entity ID
 *    24  munition entity ID (v7: the exploding entity)
 *    30  event ID (site u16, application u16, event number u16)
 *    36  velocity, 3 x float32 (m/s)
 *    48  location in world coordinates, 3 x float64 (geocentric ECEF, metres)
 *    72  descriptor: entity type (kind u8, domain u8, country u16, category u8, subcategory u8,
 *        specific u8, extra u8), warhead u16, fuse u16, quantity u16, rate u16 (v7's explosion
 *        descriptor keeps the entity type there and puts material, padding and force after it)
 *    88  location in entity coordinates, 3 x float32
 *   100  detonation result u8       101  number of variable parameters u8       102  padding u16
 *   104  variable parameter records, 16 bytes each
 * A datagram may carry several PDUs one after the other (bundling); zero bytes between them
 * (alignment to 8 bytes) are skipped. */
#ifndef SBFX_DIS_PDU_H
#define SBFX_DIS_PDU_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define DIS_HEADER_SIZE 12
#define DIS_DETONATION_SIZE 104        /* without variable parameter records */
#define DIS_VARIABLE_PARAMETER_SIZE 16
#define DIS_MAX_PDU_SIZE 8192          /* the largest PDU (and datagram) taken */
#define DIS_PDU_DETONATION 3
#define DIS_FAMILY_WARFARE 2

enum dis_status {
    DIS_DETONATION,    /* a well-formed Detonation PDU */
    DIS_OTHER,         /* a well-formed header of another PDU type (its body is not read) */
    DIS_TRUNCATED,     /* fewer bytes than a header, or than the length field says */
    DIS_BAD_VERSION,   /* not protocol version 6 or 7 */
    DIS_BAD_LENGTH,    /* a length field under the header's size, or a Detonation PDU's length
                          other than 104 + 16 x its number of variable parameters */
    DIS_BAD_FAMILY,    /* PDU type 3 outside the warfare family */
    DIS_BAD_LOCATION,  /* a world location that is not a finite number */
    DIS_OVERSIZED,     /* a datagram over DIS_MAX_PDU_SIZE (the receiver's finding) */
    DIS_STATUS_COUNT
};

struct dis_entity_id {
    uint16_t site, application, entity; /* for an event ID: entity is the event number */
};

/* The munition's (or explosion's) entity type: kind.domain.country.category.subcategory.specific.extra */
struct dis_entity_type {
    uint8_t kind, domain;
    uint16_t country;
    uint8_t category, subcategory, specific, extra;
};

struct dis_header {
    uint8_t version, exercise, type, family;
    uint32_t timestamp;
    uint16_t length;
};

struct dis_detonation {
    struct dis_entity_id firing, target, munition, event;
    float velocity[3];
    double location[3];            /* ECEF metres */
    struct dis_entity_type munition_type;
    uint16_t warhead, fuse, quantity, rate;
    float entity_location[3];
    uint8_t result;                /* detonation result (SISO-REF-010: 1 entity impact, 3 ground impact...) */
    uint8_t variable_parameters;
};

struct dis_pdu {
    struct dis_header header;
    struct dis_detonation detonation; /* DIS_DETONATION only */
};

#define DIS_PDU_ENTITY_STATE 1
#define DIS_ENTITY_STATE_SIZE 144    /* + 16 per articulation parameter */

/* What the player follows of an Entity State PDU (type 1; IEEE 1278.1 5.3.3.1): offsets 12 entity
 * ID, 48 location (3 x float64, ECEF m), 72 orientation (psi, theta, phi, 3 x float32, radians:
 * Euler angles of the body axes from ECEF's, z-y-x). */
struct dis_entity_state {
    struct dis_entity_id id;
    double location[3];
    float orientation[3];
};

/* An Entity State PDU's fields above (buf: the PDU, len: its length field, a well-formed header
 * of type 1): false when it is shorter than 144 bytes or a value is not a number. */
bool dis_entity_state_parse(const uint8_t *buf, size_t len, struct dis_entity_state *out);

/* The PDU at the start of buf (len: the bytes left in the datagram). *used: the bytes it spans
 * (its length field) when that could be trusted, else len (the rest cannot be delimited). */
enum dis_status dis_pdu_parse(const uint8_t *buf, size_t len, struct dis_pdu *out, size_t *used);

/* The PDUs of one datagram, in order. */
struct dis_cursor {
    const uint8_t *data;
    size_t len, at;
};

void dis_cursor_init(struct dis_cursor *c, const uint8_t *data, size_t len);
/* The next PDU: false at the end of the datagram (only zero padding left). */
bool dis_cursor_next(struct dis_cursor *c, struct dis_pdu *out, enum dis_status *status);

/* "truncated", "wrong version"... for logs. */
const char *dis_status_name(enum dis_status status);
/* A malformed PDU: one to count and drop. */
bool dis_status_malformed(enum dis_status status);

#endif
