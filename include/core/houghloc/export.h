/*
 * export.h - HL_API marks the core's public functions. The core is compiled with
 * -fvisibility=hidden, so libhoughloc.so exports what its public headers declare with
 * HL_API and nothing else: the internal modules (houghloc-internal, the headers of
 * src/core) stay out of its ABI, and a program cannot come to depend on them by accident.
 */
#ifndef HOUGHLOC_EXPORT_H
#define HOUGHLOC_EXPORT_H

#if defined(__GNUC__) || defined(__clang__)
#define HL_API __attribute__((visibility("default")))
#else
#define HL_API
#endif

#endif
