/*
 * carmen_log.h - CARMEN log files (plain or gzip) read line by line, and the lines
 * houghloc-import-carmen uses parsed without guessing (private to tools/carmen).
 *
 * Line formats (whitespace separated; ranges in metres, angles in radians):
 *
 *   FLASER n r_1 .. r_n x y theta odom_x odom_y odom_theta timestamp [hostname [logger_ts]]
 *   PARAM name value [...]
 *
 * Every other line (comments starting with '#', empty lines, ODOM, RLASER, NEFF, ...)
 * is CARMEN_SKIP. A FLASER line must hold exactly n + 7 numbers after its beam count,
 * then optionally a hostname (not a number) and a logger timestamp (a number); anything
 * else is malformed, with a reason naming the field, so that a wrong beam count is
 * reported rather than read as shifted poses.
 */
#ifndef HOUGHLOC_TOOLS_CARMEN_LOG_H
#define HOUGHLOC_TOOLS_CARMEN_LOG_H

#include <stdbool.h>
#include <stdint.h>

#define CARMEN_MAX_BEAMS 8192           /* beams per FLASER line */
#define CARMEN_MAX_LINE (1 << 20)       /* bytes per line, without the newline */
#define CARMEN_WHY_LEN 256

/* ---- reading lines ---------------------------------------------------------------- */

typedef struct carmen_reader carmen_reader_t;

/**
 * Opens @p path (plain text or gzip; zlib tells them apart) for reading.
 * @return the reader, or NULL with a one-line reason in @p why (CARMEN_WHY_LEN bytes).
 */
carmen_reader_t *carmen_open(const char *path, char *why);

/**
 * The next line, without its line end ("\n" or "\r\n"), NUL-terminated, in storage the
 * reader owns until the next call. @p lineno gets its 1-based number.
 * @return 1 for a line, 0 at the end of the file, -1 on a read or gzip error or a line
 *         longer than CARMEN_MAX_LINE (reason in @p why, without the file name).
 */
int carmen_next_line(carmen_reader_t *r, char **line, long *lineno, char *why);

/** Closes @p r; NULL is allowed. */
void carmen_close(carmen_reader_t *r);

/* ---- parsing lines ---------------------------------------------------------------- */

typedef enum carmen_kind {
    CARMEN_SKIP = 0,        /* comment, empty, or a line type not used here */
    CARMEN_FLASER,
    CARMEN_PARAM,
} carmen_kind_t;

typedef struct carmen_pose {
    double x, y, theta;     /* metres, radians; finite */
} carmen_pose_t;

typedef struct carmen_flaser {
    int nbeams;             /* 2..CARMEN_MAX_BEAMS */
    double *ranges;         /* caller's storage for CARMEN_MAX_BEAMS values; each finite
                               and >= 0 */
    carmen_pose_t pose;     /* x y theta: the laser's pose (odometry in a raw log) */
    carmen_pose_t odom;     /* odom_x odom_y odom_theta */
    int64_t time_us;        /* the timestamp field in microseconds, exactly, >= 0 */
} carmen_flaser_t;

typedef struct carmen_param {
    const char *name;       /* point into the parsed line */
    const char *value;
} carmen_param_t;

typedef struct carmen_line {
    carmen_kind_t kind;
    carmen_flaser_t flaser; /* set ranges before parsing; filled for CARMEN_FLASER */
    carmen_param_t param;   /* filled for CARMEN_PARAM */
} carmen_line_t;

/**
 * Parses @p line (modified: split into tokens in place) into @p out, whose
 * flaser.ranges must point at CARMEN_MAX_BEAMS doubles.
 * @return 0, or -1 for a malformed FLASER or PARAM line with the reason in @p why
 *         (CARMEN_WHY_LEN bytes), e.g. "FLASER with 180 beams: beam 17 'x' is not a
 *         number".
 */
int carmen_parse_line(char *line, carmen_line_t *out, char *why);

/**
 * A decimal number ("12", "-0.5", ".25", "1e-3"); no hex, no inf or nan, no trailing
 * characters. @return true with the value in @p out.
 */
bool carmen_parse_number(const char *tok, double *out);

/**
 * A non-negative timestamp in seconds as microseconds, exactly for plain decimals
 * ("1134860000.001000": digits beyond the sixth decimal round half up), else through
 * carmen_parse_number. At most 10^12 s. @return true with the value in @p out.
 */
bool carmen_parse_time_us(const char *tok, int64_t *out);

#endif
