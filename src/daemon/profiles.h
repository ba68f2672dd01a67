/*
 * profiles.h - the sensor profiles of slam.profile as houghlocd shows them: the core's
 * presets (houghloc/params.h, hl_params_preset: sonar-stops, sonar-continuous, laser,
 * paper) printed as configuration fragments, and the advice for a map file larger than
 * the configured map.
 *
 * A profile is applied before every other key, wherever slam.profile is written
 * (config.c), so that single keys can still adjust it, and so that the fragment
 * `houghlocd --print-profile NAME` prints (installed as share/houghloc/profiles/NAME.conf)
 * read as a configuration means the same.
 */
#ifndef HOUGHLOC_DAEMON_PROFILES_H
#define HOUGHLOC_DAEMON_PROFILES_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "houghloc/params.h"

/** @return the profile called @p name, or NULL. */
const hl_param_preset_t *hl_sensor_profile_find(const char *name);

/** The profiles' names, for messages: "sonar-stops, sonar-continuous, laser or paper". */
const char *hl_sensor_profile_names(void);

/** Writes the keys @p p sets as a commented INI fragment (--print-profile). */
void hl_sensor_profile_print(const hl_param_preset_t *p, FILE *out);

/** The map capacity (slam.map_capacity) @p p sets, 0 if it sets none. */
uint32_t hl_sensor_profile_capacity(const hl_param_preset_t *p);

/**
 * The refusal of a map file that holds more vectors than the configured capacity, naming
 * the setting to raise: "PATH: holds N vectors, more than slam.map_capacity = C: raise it
 * (--set slam.map_capacity=N, or slam.profile = laser) or start afresh with --fresh-map
 * ...". The profile is named only when one holds N vectors.
 */
void hl_capacity_advice(const char *path, uint32_t count, uint32_t capacity, char *out,
                        size_t cap);

#endif
