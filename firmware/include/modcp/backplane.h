/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the CPU–CP backplane interface (docs/cpu-cp-interface.md).
 *
 * The only thing the CP side and the CPU side share. Two single-producer /
 * single-consumer rings of 32-byte blocks, one per direction. A block is "requested"
 * when the producer publishes it (head++) and "acknowledged" when the consumer has
 * copied it out (tail++). Every block carries a per-direction sequence number that the
 * consumer checks, the message kind, FIRST/LAST flags and the job tag.
 *
 * Safe between two threads, or between an interrupt and a main loop, on any target
 * where 32-bit C11 atomics are lock-free (Cortex-M3/M4, x86-64, aarch64).
 *
 * Messages (first block of a message carries its header in data[]):
 *   CPU -> CP  PARAMS   the parameter record (data = record bytes, several blocks)
 *   CPU -> CP  INIT     modcp_bp_init_t (work area, area sizes, record CRC)
 *   CP -> CPU  INIT_ACK modcp_bp_ack_t (event: NONE = ready)
 *   CP -> CPU  JOB      first block modcp_bp_job_t, then the write data
 *   CPU -> CP  REPLY    first block modcp_bp_reply_t, then the read data
 * (a JOB / REPLY whose data fits after its header is that one block, FIRST and LAST)
 * A job is cancelled by the CP writing its tag to `abort_tag` (after a timeout); the
 * CPU side does not execute a job whose tag equals abort_tag, and the CP drops
 * REPLY blocks whose tag is not the tag of its current job. */
#ifndef MODCP_BACKPLANE_H
#define MODCP_BACKPLANE_H

#include <stdatomic.h>
#include <stdbool.h>
#include <stdint.h>
#include <string.h>

#include "modcp/events.h"
#include "modcp/map.h"

#define MODCP_BLOCK_SIZE 32u
#ifndef MODCP_BP_DEPTH
#define MODCP_BP_DEPTH 4u /* blocks per direction; power of two */
#endif

/* Block kinds (modcp_block_t.kind). */
#define MODCP_BP_PARAMS 1u
#define MODCP_BP_INIT 2u
#define MODCP_BP_INIT_ACK 3u
#define MODCP_BP_JOB 4u
#define MODCP_BP_REPLY 5u

/* Block flags (modcp_block_t.flags). */
#define MODCP_BLK_FIRST 0x01u
#define MODCP_BLK_LAST 0x02u

typedef struct {
    uint8_t data[MODCP_BLOCK_SIZE];
    uint8_t len;   /* valid bytes in data, 0 ... 32 */
    uint8_t kind;  /* MODCP_BP_* */
    uint8_t flags; /* MODCP_BLK_* */
    uint8_t tag;   /* job tag (JOB / REPLY), 0 otherwise */
    uint8_t seq;   /* per-direction sequence number, +1 per block, wraps */
} modcp_block_t;

typedef struct {
    modcp_block_t slot[MODCP_BP_DEPTH];
    _Atomic uint32_t head; /* producer: blocks published */
    _Atomic uint32_t tail; /* consumer: blocks acknowledged */
} modcp_ring_t;

/* CP status area: published by the CP side (seqlock), read by the CPU side, so the
 * user program sees the CP's state and diagnostics without touching the CP. */
#define MODCP_CPST_CONFIGURED 0x0001u  /* valid parameters applied */
#define MODCP_CPST_READY 0x0002u       /* configured and FB initialised */
#define MODCP_CPST_SF 0x0004u          /* group error LED */
#define MODCP_CPST_COMMLOSS 0x0008u    /* comm-loss supervision expired */
#define MODCP_CPST_LISTEN_ONLY 0x0010u /* FC08 sub 04 listen-only mode */
#define MODCP_CPST_WIRE_BREAK 0x0100u  /* BREAK on RxD (normal mode) until a good character */
#define MODCP_CPST_PARAM_ERROR 0x0200u /* the last PARAMS record was rejected */

/* Two runs of fields are laid out as their owners hold them, so that the CP publishes
 * each as one copy: events_total ... buffer_len as in modcp_diag_t (diag.h), diag_irq ...
 * systat_ack as in modcp_cpdiag_t (cpdiag.h); the SYSTAT image (systat) is written here
 * directly by modcp_cpdiag_systat. */
typedef struct {
    uint32_t flags;        /* MODCP_CPST_* */
    /* line discipline (leds.h, signals.h) */
    uint8_t leds;           /* LED levels: bit MODCP_LED_SF / TXD / RXD */
    uint8_t signals;        /* RS232 signals: MODCP_SIGBIT_* (RTS, DTR, CTS, DSR, AUTO) */
    uint16_t signal_aborts; /* sends / receptions aborted by CTS / DSR */
    uint32_t events_total; /* events since start (changes whenever an event is added) */
    uint16_t counters[8];   /* Modbus serial-line counters (modcp_counter_t order) */
    uint16_t frames_too_long; /* frames longer than the receive buffer */
    uint16_t char_errors;   /* characters with parity / framing / overrun error */
    uint16_t breaks;        /* BREAKs */
    uint16_t t15_discards;  /* frames discarded by the t1.5 check */
    uint16_t status;        /* STATUS word of the last event */
    modcp_event_t buffer[9]; /* diagnostic buffer, newest first */
    uint8_t buffer_len;
    modcp_event_t param_event; /* why the CP is not configured (NONE if it is) */
    uint8_t diag_irq[4];    /* last diagnostic interrupt record ([VIPA-341] §8.4) */
    uint32_t diag_irq_count; /* advances with every diagnostic interrupt */
    uint32_t systat_ack;    /* SYSTAT request answered by systat[] */
    uint8_t systat[16];     /* SYSTAT image ([RTU-2003] §7.4), cleared in the CP when taken */
} modcp_cp_status_t;

typedef struct {
    modcp_ring_t to_cpu;       /* CP -> CPU */
    modcp_ring_t to_cp;        /* CPU -> CP */
    _Atomic uint32_t abort_tag; /* tag of the last job the CP gave up on (0x100 = none) */
    _Atomic uint32_t status_seq; /* seqlock: odd while the CP writes `status` */
    modcp_cp_status_t status;
    _Atomic uint32_t systat_req; /* CPU side: number of the last SYSTAT request */
    _Atomic uint32_t commloss_reset; /* CPU side: counts comm-loss resets (a latched loss
                                        is cleared when the CP sees it change) */
} modcp_backplane_t;

/* Job operations (modcp_bp_job_t.op). */
#define MODCP_JOB_READ 1u     /* read count bytes / T,C elements (FC01/02/03/04) */
#define MODCP_JOB_WRITE 2u    /* write bytes (FC06/16) */
#define MODCP_JOB_BITWRITE 3u /* read-modify-write of count bits from operand.bit (FC05/15) */
#define MODCP_JOB_MASKWRITE 4u /* FC22: the word at the operand (M, Q, DB; count 2 bytes)
                                  := (cur AND data[0..1]) OR (data[2..3] AND NOT data[0..1]),
                                  len 4 (AND mask, OR mask, high byte first), read and
                                  written in one FB call (atomic) */

/* JOB header, first block of a job (serialised little-endian into data[]). */
typedef struct {
    uint8_t op; /* MODCP_JOB_* */
    modcp_operand_t opnd;
    uint16_t len; /* data bytes that follow (write) or are expected back (read) */
} modcp_bp_job_t;

/* REPLY header. */
typedef struct {
    modcp_event_t event; /* NONE = done; else (0E)38H, (0E)39H, (0E)3AH, (0E)57H ... */
    uint16_t error_nr;   /* FB ERROR_NR (10..19) when event = (0E)57H */
    uint16_t len;        /* data bytes that follow */
} modcp_bp_reply_t;

/* INIT payload. */
typedef struct {
    modcp_areas_t areas;
    uint16_t record_crc; /* modcp_bp_record_id() of the PARAMS record the CP must hold */
} modcp_bp_init_t;

/* Both sides: the identity of a PARAMS record, as the manual's CP tells "parameters
 * already on the CP" by their time stamp (VIPA CP 341 manual §7.2, (00)04H): the CRC-16
 * of the record without its last two bytes, i.e. an MCPR record's own CRC (the CRC over
 * a record that ends in its own CRC is always 0, so it cannot be the whole record's). */
uint16_t modcp_bp_record_id(const uint8_t *record, uint16_t len);

/* INIT_ACK payload. */
typedef struct {
    modcp_event_t event; /* NONE = CP ready and initialised, else why not */
} modcp_bp_ack_t;

/* Both sides: empty rings and status area (before either side runs). */
void modcp_bp_init(modcp_backplane_t *bp);

/* CPU side: read a consistent copy; false if the CP was writing (try again). */
bool modcp_bp_read_status(const modcp_backplane_t *bp, modcp_cp_status_t *out);
/* CPU side: ask for the SYSTAT image (reading clears SYSTAT in the CP, as SFB STATUS
 * does, [RTU-2003] §7.4). Returns the request number; the CP answers at its next poll. */
uint32_t modcp_bp_systat_request(modcp_backplane_t *bp);
/* CPU side: reset a latched comm loss (MODCP_CPST_COMMLOSS, params.commloss_auto off;
 * the Altivar's "fault reset" of SLF1, [ALTIVAR] §7); the CP clears it at its next poll and
 * times the supervision from then. */
void modcp_bp_commloss_reset(modcp_backplane_t *bp);
/* CPU side: true when request `req` has been answered; copies the 16-byte image
 * (byte 0 state 02H RUN / 05H fault, byte 2 flags F U B, bytes 4..15 six events). */
bool modcp_bp_systat_result(const modcp_backplane_t *bp, uint32_t req, uint8_t out[16]);

/* Header (de)serialisation into block data; return bytes used / false if short.
 * Layouts: backplane.c. The JOB and REPLY codecs run once per request each (inline). */
#define MODCP_BP_JOB_HDR_LEN 11u
#define MODCP_BP_REPLY_HDR_LEN 6u
/* A JOB whose write data fits after its header (up to 21 bytes) and a REPLY whose read
 * data fits after its header (up to 26 bytes) cross as that one block, FIRST and LAST. */
#define MODCP_BP_JOB_INLINE (MODCP_BLOCK_SIZE - MODCP_BP_JOB_HDR_LEN)
#define MODCP_BP_REPLY_INLINE (MODCP_BLOCK_SIZE - MODCP_BP_REPLY_HDR_LEN)

#endif
