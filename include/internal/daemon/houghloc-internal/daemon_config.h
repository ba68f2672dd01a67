/*
 * daemon_config.h - the slam parameters houghlocd would run with, for the laboratory's
 * research tools (hl-kidnap, hl-tour-study). They replay logs through the core with the
 * daemon's configuration, read by the daemon's own loader so that every key, preset and
 * error means the same in both. Implemented by houghlocd's library
 * (libhoughloc_daemon.a, src/daemon/config.c).
 */
#ifndef HOUGHLOC_INTERNAL_DAEMON_CONFIG_H
#define HOUGHLOC_INTERNAL_DAEMON_CONFIG_H

#include <stdbool.h>

#include "houghloc/slam.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HL_DAEMON_CONFIG_WHY_LEN 640

/**
 * The slam parameters of houghlocd's configuration file @p path (NULL: the defaults) with
 * the "section.key=value" @p overrides applied after it, as `houghlocd --config PATH
 * --set ...` builds them.
 * @return true, or false with the loader's one line in @p why.
 */
bool hl_daemon_config_slam(const char *path, const char *const *overrides, int n_overrides,
                           hl_slam_params_t *out, char why[HL_DAEMON_CONFIG_WHY_LEN]);

#ifdef __cplusplus
}
#endif
#endif
