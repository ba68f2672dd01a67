/*
 * simd.h (private) - lets a hot loop use AVX2 where the processor has it while the
 * binary still runs on any x86-64 (GCC function multi-versioning: the loader picks the
 * clone once, through an ifunc). Elsewhere, and under the sanitizers, it is empty.
 */
#ifndef HOUGHLOC_CORE_SIMD_H
#define HOUGHLOC_CORE_SIMD_H

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && \
    defined(__linux__) && !defined(__SANITIZE_ADDRESS__)
#define HL_VECTOR_KERNEL __attribute__((target_clones("avx2", "default")))
#else
#define HL_VECTOR_KERNEL
#endif

/* A function the compiler must copy into each caller, so that the constant arguments of
 * each call fold away (localize.c's vote loop, once for each way it runs). */
#if defined(__GNUC__)
#define HL_ALWAYS_INLINE __attribute__((always_inline)) inline
#else
#define HL_ALWAYS_INLINE inline
#endif

#endif
