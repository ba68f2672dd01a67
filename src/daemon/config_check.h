/*
 * config_check.h - the rules that tie configuration keys together (private to config.c).
 *
 * Each key's own range is its table's (config_keys.c, or the core's for the tracker's
 * keys), checked as it is read, with the file and line. What is left are rules over
 * several keys: the tracker's are the core's (hl_params_check, in the keys' names); the
 * robot layer's (drive.max_leg_mm at least drive.arrive_mm, ...) know their parameters,
 * not the keys, so each is stated here again in the keys' names, its message naming
 * every key involved with its value as written ("drive.max_leg_mm (200)"), and the
 * libraries' checks run after, for any rule not stated here.
 */
#ifndef HOUGHLOC_DAEMON_CONFIG_CHECK_H
#define HOUGHLOC_DAEMON_CONFIG_CHECK_H

#include <stdbool.h>

#include "config.h"

/** Checks the combination of values of @p c. @return true, or false with one line in
 *  @p why (HL_CONFIG_WHY_LEN bytes): "config: KEY (VALUE) must ... KEY (VALUE)". */
bool hl_config_check(const hl_config_t *c, char *why);

#endif
