/* golden_text.h - hl-eval text (golden_text.c): one channel of a log as text, one line
 * per message, every field of its LCM type in order as NAME=VALUE, so that two streams
 * compare as text and a difference reads as a diff (the goldens, tests/golden/README.md,
 * which documents the format). */
#ifndef HOUGHLOC_TESTS_GOLDEN_TEXT_H
#define HOUGHLOC_TESTS_GOLDEN_TEXT_H

/**
 * Writes every message of the log @p log on @p channel (POSE and GROUND_TRUTH: pose_t;
 * SONAR: scan_t; ODOMETRY: odometry_t) to @p file as text, one line each.
 * @return 0; 1 after one line on stderr starting with @p prog (a bad log, a message that
 *         does not decode whole, a write error); 2 for a channel of another type.
 */
int hl_eval_text(const char *prog, const char *log, const char *channel, const char *file);

#endif
