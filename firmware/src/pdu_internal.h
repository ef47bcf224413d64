/* modcp — internal interface between the PDU engine (pdu.c) and the extended function
 * set (pdu_ext.c, serial_diag.c, devid.c). Not for other modules. */
#ifndef MODCP_PDU_INTERNAL_H
#define MODCP_PDU_INTERNAL_H

#include <stdbool.h>
#include <stdint.h>

#include "modcp/pdu.h"

/* pdu.c: record ev and answer with exception `code` (0: the event's code, else 04). Counts
 * the exception (also for broadcast, Serial Line V1.02 §6.1 counter 3) and, for a
 * broadcast, the missing response. */
modcp_pdu_action_t modcp_pdu_fail(modcp_pdu_t *s, const modcp_pdu_env_t *env, modcp_event_t ev,
                                  uint8_t code, uint8_t *pdu, uint16_t *out_len);

/* First look at every request (s->fc, s->broadcast set): logs the FC12 receive event;
 * in listen-only mode takes the request (returns true, *a = NO_REPLY) unless it is
 * processed as FC08 sub 01 there. */
bool modcp_pdu_ext_pre(modcp_pdu_t *s, const modcp_pdu_env_t *env, const uint8_t *pdu,
                       uint16_t len, modcp_pdu_action_t *a);

/* Function codes of the extended set (only with function set `extended`). */
bool modcp_pdu_ext_supported(const modcp_pdu_env_t *env, uint8_t fc);

/* True when pdu_ext.c serves this request: FC08 / 0B / 0C / 11 / 16 / 17 / 2B in the
 * extended set, and FC03 / 06 / 10 on scanner addresses. */
bool modcp_pdu_ext_claims(const modcp_pdu_env_t *env, const uint8_t *pdu, uint16_t len);

/* Serve a claimed request (after the broadcast, function-code and FB-ready checks). */
modcp_pdu_action_t modcp_pdu_ext_request(modcp_pdu_t *s, const modcp_pdu_env_t *env,
                                         uint8_t *pdu, uint16_t len, uint16_t cap,
                                         uint16_t *out_len);

/* A job of a request with s->x.seq != 0 finished: next job, the reply, or 04. */
modcp_pdu_action_t modcp_pdu_ext_complete(modcp_pdu_t *s, const modcp_pdu_env_t *env,
                                          modcp_event_t ev, uint8_t *pdu, uint16_t *out_len);

/* serial_diag.c: FC08 (extended), FC11, FC12. */
modcp_pdu_action_t modcp_pdu_fc08(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                  uint16_t len, uint16_t *out_len);
modcp_pdu_action_t modcp_pdu_fc11(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                  uint16_t len, uint16_t *out_len);
modcp_pdu_action_t modcp_pdu_fc12(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                  uint16_t len, uint16_t cap, uint16_t *out_len);

/* devid.c: FC17, FC43/14. */
modcp_pdu_action_t modcp_pdu_fc17(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                  uint16_t len, uint16_t cap, uint16_t *out_len);
modcp_pdu_action_t modcp_pdu_fc43(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                  uint16_t len, uint16_t cap, uint16_t *out_len);

#endif
