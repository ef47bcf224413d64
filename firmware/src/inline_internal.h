/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — where a function is placed: out of line, or inlined, by build goal (-Os for
 * the MCU builds, -O2 for the host). Internal to the core: not part of the public API. */
#ifndef MODCP_INLINE_INTERNAL_H
#define MODCP_INLINE_INTERNAL_H

/* Keep a cold path out of the hot one (a leaf function needs no stack frame). */
#if defined(__GNUC__)
#define MODCP_NOINLINE __attribute__((noinline))
#else
#define MODCP_NOINLINE
#endif
/* One copy where it is called from several places, in the builds for size (-Os: the MCU
 * builds); the compiler decides elsewhere (-O2: the host, where inlining saves the
 * calls). */
#if defined(__GNUC__) && defined(__OPTIMIZE_SIZE__)
#define MODCP_SIZE_NOINLINE __attribute__((noinline))
#else
#define MODCP_SIZE_NOINLINE
#endif
/* The same, and inlined in every caller in the optimised builds for speed (-O2: the
 * host), where the compiler would keep a larger function with several callers out. */
#if defined(__GNUC__) && defined(__OPTIMIZE_SIZE__)
#define MODCP_SIZE_NOINLINE_SPEED_INLINE __attribute__((noinline))
#elif defined(__GNUC__) && defined(__OPTIMIZE__)
#define MODCP_SIZE_NOINLINE_SPEED_INLINE __attribute__((always_inline)) inline
#else
#define MODCP_SIZE_NOINLINE_SPEED_INLINE
#endif
/* Placed for speed only (-O2: the host), the compiler's choice for size (-Os: there the
 * function often has a single caller, e.g. without the RTU block path): kept out of
 * line / inlined in every caller. */
#if defined(__GNUC__) && !defined(__OPTIMIZE_SIZE__)
#define MODCP_SPEED_NOINLINE __attribute__((noinline))
#else
#define MODCP_SPEED_NOINLINE
#endif
#if defined(__GNUC__) && defined(__OPTIMIZE__) && !defined(__OPTIMIZE_SIZE__)
#define MODCP_SPEED_INLINE __attribute__((always_inline)) inline
#else
#define MODCP_SPEED_INLINE
#endif
/* Inlined in every caller, in every build (a small helper on a path that pays per call). */
#if defined(__GNUC__)
#define MODCP_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define MODCP_ALWAYS_INLINE inline
#endif

#endif
