/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — identification of the extended set: FC17 report slave ID (Modbus
 * Application Protocol V1.1b3 §6.13) and FC43/14 read device identification (§6.21),
 * both from the parameter record's strings (docs/parameters.md: vendor, product, revision,
 * user application name; at most 16 characters each). An empty revision is modcp's
 * version, MODCP_VERSION (modcp/version.h, generated from the top-level CMakeLists.txt).
 *
 * FC17 reply: 11, byte count, slave ID (= the slave address), run indicator (FF: the
 * CP is ready and the CPU side answers its jobs; 00: the last CPU job timed out and
 * none has succeeded since), then "vendor product revision" in ASCII, separated by
 * one space (empty strings left out).
 *
 * FC43/14: conformity level 82H (regular identification, stream and individual
 * access). Objects: 00 vendor name, 01 product code (basic, always present, possibly
 * empty), 02 major/minor revision (basic; modcp's version when the parameter is empty),
 * 06 user application name (regular; present when the parameter is not empty).
 * 03/04/05 are not provided.
 *   ReadDevId 01 stream basic (00..02), 02 stream regular (00..02, 06), 03 extended:
 *   answered as regular (the CP's conformity level; ReadDevId echoed as requested),
 *   04 one object. Stream access from an object id that is not in the category
 *   restarts at object 00 (Application Protocol §6.21); individual access to an
 *   object that does not exist: exception 02 ((0E)51H).
 *   More follows / next object id: when the next object does not fit into the reply
 *   (max. 253 bytes of PDU), More follows = FF and next object id = its id; with
 *   strings of at most 16 characters this never happens in the CP.
 *   MEI type other than 0E: exception 01 ((08)31H); ReadDevId not 01..04: exception 03
 *   ((08)3BH); a request that is not exactly 2B 0E code object: exception 03 ((08)33H). */
#include <stddef.h>
#include <string.h>

#include "modcp/version.h"
#include "pdu_internal.h"

#define PDU_MAX 253u
#define CONFORMITY 0x82u
#define ID_MAX ((uint8_t)MODCP_ID_STRING_MAX) /* characters of an object's string */

static uint8_t id_len(const char *str)
{
    uint8_t n = 0;
    while (n < ID_MAX && str[n] != '\0') {
        n++;
    }
    return n;
}

static bool run_indicator(const modcp_pdu_env_t *env)
{
    return env->fb_ready && !(env->ext != NULL && env->ext->cpu_stalled);
}

/* The objects of the CP in id order, i = 0..3: 00 vendor, 01 product, 02 revision,
 * 06 application name (present when not empty). */
_Static_assert(sizeof MODCP_VERSION <= (sizeof(((modcp_params_t *)0)->revision)),
               "the version fits into the revision object");

/* Object i's string; the revision (i = 2) left empty by the configuration is modcp's
 * version. */
static const char *obj_value(const modcp_params_t *p, size_t i)
{
    const char *v = p->app_name;
    if (i == 0u) {
        v = p->vendor;
    } else if (i == 1u) {
        v = p->product;
    } else if (i == 2u) {
        v = (id_len(p->revision) == 0u) ? MODCP_VERSION : p->revision;
    } else {
        /* 3: the application name */
    }
    return v;
}

static uint8_t obj_id(size_t i)
{
    return i < 3u ? (uint8_t)i : 0x06u;
}

modcp_pdu_action_t modcp_pdu_fc17(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                  uint16_t len, uint16_t cap, uint16_t *out_len)
{
    (void)len; /* 1: the function-code table */
    if (cap < 4u) {
        return modcp_pdu_err(s, MODCP_EV_JOB_LENGTH, MODCP_EXC_DEVICE_FAILURE);
    }
    uint16_t o = 4; /* fc, byte count, slave id, run indicator */
    for (size_t i = 0; i < 3u; i++) { /* vendor, product, revision */
        const char *part = obj_value(env->p, i);
        uint8_t n = id_len(part);
        if (n == 0u) {
            continue;
        }
        if (o > 4u && o < cap) {
            pdu[o++] = ' ';
        }
        if ((uint32_t)o + n > cap) {
            break; /* never with the CP's buffer (at most 4 + 50 bytes) */
        }
        (void)memcpy(pdu + o, part, n);
        o = (uint16_t)(o + n);
    }
    pdu[1] = (uint8_t)(o - 2u);
    pdu[2] = env->p->slave_addr;
    pdu[3] = run_indicator(env) ? 0xFFu : 0x00u;
    *out_len = o;
    return MODCP_PDU_REPLY;
}

modcp_pdu_action_t modcp_pdu_fc43(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                  uint16_t len, uint16_t cap, uint16_t *out_len)
{
    if (pdu[1] != 0x0Eu) { /* length >= 2: the function-code table */
        return modcp_pdu_err(s, MODCP_EV_ILLEGAL_FC, MODCP_EXC_ILLEGAL_FUNCTION);
    }
    if (len != 4u) {
        return modcp_pdu_err(s, MODCP_EV_BYTE_COUNT, MODCP_EXC_ILLEGAL_VALUE);
    }
    const uint8_t code = pdu[2];
    const uint8_t want = pdu[3];
    if (code < 1u || code > 4u) {
        return modcp_pdu_err(s, MODCP_EV_MEI_CODE, MODCP_EXC_ILLEGAL_VALUE);
    }
    const modcp_params_t *p = env->p;
    size_t total = 3u;
    if (id_len(p->app_name) > 0u) {
        total = 4u;
    }
    /* one past the last object of the category: basic 00..02; regular / extended and
     * the individual access: all */
    size_t last = code == 1u ? 3u : total;
    size_t first = 0;
    while (first < last && obj_id(first) != want) {
        first++;
    }
    if (code == 4u) {
        if (first == last) {
            return modcp_pdu_err(s, MODCP_EV_NO_WINDOW, MODCP_EXC_ILLEGAL_ADDRESS);
        }
        last = first + 1u;
    } else if (first == last) {
        first = 0; /* not an object of this category: restart at 00 */
    } else {
        /* a stream of the category from its first object */
    }
    const uint16_t limit = cap < PDU_MAX ? cap : (uint16_t)PDU_MAX;
    if (limit < 7u) {
        return modcp_pdu_err(s, MODCP_EV_JOB_LENGTH, MODCP_EXC_DEVICE_FAILURE);
    }
    uint16_t o = 7; /* 2B 0E code conformity more next count */
    uint8_t count = 0;
    uint8_t more = 0x00;
    uint8_t next = 0x00;
    for (size_t i = first; i < last; i++) {
        const char *value = obj_value(p, i);
        uint8_t n = id_len(value);
        if ((uint32_t)o + 2u + n > limit) {
            if (count == 0u) {
                return modcp_pdu_err(s, MODCP_EV_JOB_LENGTH, MODCP_EXC_DEVICE_FAILURE);
            }
            more = 0xFFu;
            next = obj_id(i);
            break;
        }
        pdu[o] = obj_id(i);
        pdu[o + 1u] = n;
        (void)memcpy(pdu + o + 2u, value, n);
        o = (uint16_t)(o + 2u + n);
        count++;
    }
    pdu[2] = code;
    pdu[3] = CONFORMITY;
    pdu[4] = more;
    pdu[5] = next;
    pdu[6] = count;
    *out_len = o;
    return MODCP_PDU_REPLY;
}
