/*
 * profiles.h - the sensor profiles of slam.profile: compiled-in sets of configuration
 * keys that fit the localizer and the map to how the robot senses.
 *
 *   sonar-stops       the paper's ring sounded at stops a metre or so apart: the
 *                     compiled-in defaults, it sets no key
 *   sonar-continuous  a sonar ring sounded several times a second while the robot moves
 *   laser             a laser scanner: hundreds of thin beams several times a second
 *
 * A profile is applied after slam.mode's preset and before every other key, wherever
 * slam.profile is written (config.c), so that single keys can still adjust it, and so
 * that the fragment `houghlocd --print-profile NAME` prints (installed as
 * share/houghloc/profiles/NAME.conf) read as a configuration means the same.
 */
#ifndef HOUGHLOC_DAEMON_PROFILES_H
#define HOUGHLOC_DAEMON_PROFILES_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

/* The names, for messages: "sonar-stops, sonar-continuous or laser". */
#define HL_SENSOR_PROFILE_NAMES "sonar-stops, sonar-continuous or laser"
#define HL_SENSOR_PROFILE_DEFAULT "sonar-stops"
#define HL_SENSOR_PROFILE_NAME_MAX 24

/** One key a profile sets, as it would be written in the file, and why. */
typedef struct hl_profile_key {
    const char *key;        /* "section.key" */
    const char *value;
    const char *why;        /* one comment line */
} hl_profile_key_t;

typedef struct hl_sensor_profile {
    const char *name;
    const char *summary;    /* one comment line: the sensor it is made for */
    const hl_profile_key_t *keys;
    size_t n_keys;
} hl_sensor_profile_t;

/** @return the profile called @p name, or NULL. */
const hl_sensor_profile_t *hl_sensor_profile_find(const char *name);

/** The profiles in table order: @p i in 0..hl_sensor_profile_count()-1, else NULL. */
size_t hl_sensor_profile_count(void);
const hl_sensor_profile_t *hl_sensor_profile_at(size_t i);

/** Writes the keys @p p sets as a commented INI fragment (--print-profile). */
void hl_sensor_profile_print(const hl_sensor_profile_t *p, FILE *out);

/** The smallest map capacity (slam.map_capacity) @p p sets, 0 if it sets none. */
uint32_t hl_sensor_profile_capacity(const hl_sensor_profile_t *p);

/**
 * The refusal of a map file that holds more vectors than the configured capacity, naming
 * the setting to raise: "PATH: holds N vectors, more than slam.map_capacity = C: raise it
 * (--set slam.map_capacity=N, or slam.profile = laser) or start afresh with --fresh-map
 * ...". The profile is named only when one holds N vectors.
 */
void hl_capacity_advice(const char *path, uint32_t count, uint32_t capacity, char *out,
                        size_t cap);

#endif
