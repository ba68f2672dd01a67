/*
 * config_check.h - the rules that tie configuration keys together (private to config.c).
 *
 * Each key's own range is the key table's (config_keys.c), checked as it is read, with
 * the file and line. What is left are rules over several keys (drive.max_leg_mm at least
 * drive.arrive_mm, ...) and the few ranges a table's min..max cannot say ("0 or
 * 10..1000"). The libraries check the same rules (hl_slam_params_error and the others)
 * but know their parameters, not the keys; their messages name neither the section nor
 * the value. So each rule is stated here again in the keys' names, its message naming
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
