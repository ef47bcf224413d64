/* SPDX-License-Identifier: Apache-2.0 */
/* Test helpers for Modbus ASCII and the 32-bit register extension ([ASCII-32]), on top of
 * the world harness (world.h): ASCII frames as text, character timing, the one-shot
 * timer, and a controller laid out for the [ASCII-32] §4.5 examples. */
#ifndef MODCP_TEST_ASCII_WORLD_H
#define MODCP_TEST_ASCII_WORLD_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "world.h"

/* 1 ms per character: about one character time at 9600 baud 7E1 (10 bits) */
#define ASCII_CHAR_US 1000u

/* The world_example_params() set in ASCII framing, 9600 7E1. */
void ascii_example_params(modcp_params_t *p);

/* [ASCII-32] §4.5 32-bit ranges: 3000-4999 int16 -> DB2, 5000-5099 int32 -> DB3,
 * 7000-9999 float -> DB4 (writes: DB limits 2 ... 899) on top of *p. */
void regs32_example_ranges(modcp_params_t *p);

/* A started world with params p whose controller has DB2 (4000 bytes), DB3 (400),
 * DB4 (12000) as the [ASCII-32] §4.5 example needs, the FB work DB 80, DB800, DB805 ([ASCII-32]
 * §9.12's FC16 target, in place of the harness's DB802) and DB901. Free it with
 * ascii_world_free(). */
world_t *ascii_world_started(const modcp_params_t *p);
void ascii_world_free(world_t *w);

/* Feed the characters of text, gap_us apart (each time stamp is a character end). */
void ascii_feed(world_t *w, const char *text, uint32_t gap_us);
/* Feed n raw bytes, gap_us apart. */
void ascii_feed_bytes(world_t *w, const uint8_t *b, size_t n, uint32_t gap_us);
/* Let the armed one-shot timer expire: time advances by its delay. False if none is
 * armed. */
bool ascii_fire(world_t *w);
/* After a frame: fire the timer (if armed) and run FB cycles until the CP transmits
 * or max_ms passed; completes the transmission. Returns the reply length (0 = none). */
uint16_t ascii_finish(world_t *w, uint32_t max_ms);
/* ascii_feed(text, 1 ms per character) + ascii_finish(). */
uint16_t ascii_request(world_t *w, const char *text, uint32_t max_ms);
/* The last transmission as a string (static buffer; non-printables as \xNN). */
const char *ascii_reply(const world_t *w);
/* ":" + hex(bin) + LRC + CR LF (static buffer, big enough for 300 bytes). */
const char *ascii_frame(const uint8_t *bin, size_t n);
/* ascii_frame() of a spaced hex string "05 03 00 50 00 02". */
const char *ascii_frame_hex(const char *hex);
/* Is ev anywhere in the diagnostic buffer? */
bool world_has_event(const world_t *w, modcp_event_t ev);

#endif
