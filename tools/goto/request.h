/*
 * request.h - what houghloc-goto and houghloc-ctl share (private to tools/goto): the
 * common options (--lcm-url, --prefix, --key, --timeout, --deadline) and their checks,
 * one request sent to houghlocd (stamped with a seq from the clock, signed, published)
 * and the wait for the REPLY messages that carry its seq, each printed as one line,
 * ending in one of the exit codes below. A destination's wait follows the robot's
 * progress in STATUS, so that a long trip needs no long timeout.
 *
 * Messages go through the bus codecs (houghloc/bus.h) and lcm_publish, never the
 * generated code. Every message printed starts with the program's name, given by the
 * caller as @p prog (must not be NULL).
 */
#ifndef HOUGHLOC_TOOLS_GOTO_REQUEST_H
#define HOUGHLOC_TOOLS_GOTO_REQUEST_H

#include <stdbool.h>
#include <stdint.h>

#include "houghloc/bus.h"

#define REQ_DEFAULT_URL "udpm://239.255.76.67:7667?ttl=0"

/* The exit codes of both clients, as their --help lists them. */
enum {
    EXIT_DONE = 0,      /* the request was carried out; also --help, --version */
    EXIT_ERROR = 1,     /* LCM cannot start, key file refused, ... */
    EXIT_USAGE = 2,
    EXIT_REJECTED = 3,  /* REJECTED_FENCE, _AUTH, _REPLAY, _INVALID */
    EXIT_NO_ROBOT = 4,
    EXIT_FAILED = 5,
    EXIT_TIMEOUT = 6,
    EXIT_SIGNAL = 128,  /* + the signal: interrupted (SIGINT 130, SIGTERM 143) */
    WAITING = -1,       /* not an exit code: go on */
    REQ_NOT_MINE = -2,  /* not an exit code: req_parse_option does not know the option */
};

/* The options both clients take. */
typedef struct req_options {
    const char *url;        /* NULL: $LCM_DEFAULT_URL, else REQ_DEFAULT_URL */
    const char *prefix;     /* channel prefix, already checked by req_parse_option */
    const char *key_file;   /* NULL: unsigned */
    double timeout_s;       /* 0.1 .. 3600: the longest wait for an answer or, while a
                               destination is under way, the longest silence */
    double deadline_s;      /* 0: none; else 0.1 .. 86400, the longest whole wait */
} req_options_t;

/* The defaults: no prefix, unsigned, 10 s of silence, no deadline. */
#define REQ_OPTIONS_DEFAULT \
    { .url = NULL, .prefix = "", .key_file = NULL, .timeout_s = 10.0, .deadline_s = 0.0 }

/** Prints "<prog>: <message>; try <prog> --help" on stderr. @return EXIT_USAGE. */
__attribute__((format(printf, 2, 3))) int req_usage_error(const char *prog, const char *fmt,
                                                          ...);

/** @return true when the whole of @p s (not NULL) is a decimal number, possibly inf or
 *          nan (no leading spaces, no hexadecimal), and then stores it in @p out (not
 *          NULL). */
bool req_parse_number(const char *s, double *out);

/**
 * Parses one number argument named @p name (e.g. "X"), printing a usage error naming it
 * when it is not a finite number or, for a coordinate (@p coordinate), when it lies
 * beyond +-HL_COORD_MAX_MM once rounded to the millimetre. A heading may be any finite
 * number of degrees.
 * @param[out] out  the value in metres (coordinate) or degrees; written only on success.
 * @return WAITING on success, else EXIT_USAGE after the message.
 */
int req_parse_value(const char *prog, const char *name, const char *arg, bool coordinate,
                    double *out);

/**
 * Parses argv[*i] when it is one of the common options, as "--name VALUE" or
 * "--name=VALUE", into @p o, and moves *i past the value it took.
 * @return WAITING when taken; REQ_NOT_MINE (nothing printed, nothing changed) for any
 *         other argument; EXIT_USAGE after a one-line message on a bad or missing value.
 */
int req_parse_option(const char *prog, int argc, char **argv, int *i, req_options_t *o);

/* What a client adds to the common command line: its arguments and its own options. */
typedef struct req_args {
    const char *prog;
    const char *usage;      /* printed by --help */
    /** One positional argument. @return WAITING, or an exit code after a message. */
    int (*positional)(void *user, const char *arg);
    /** A client option (NULL if none). @return WAITING when taken, REQ_NOT_MINE if not. */
    int (*option)(void *user, const char *arg);
    void *user;
} req_args_t;

/**
 * Walks the command line both clients share: --help, --version, the common options,
 * "--", and positional arguments (anything not starting with '-', "-" itself and
 * negative numbers, and everything after "--").
 * @return WAITING when every argument was taken, else the exit code (EXIT_DONE after
 *         --help or --version, EXIT_USAGE after a one-line message).
 */
int req_walk_args(const req_args_t *a, int argc, char **argv, req_options_t *o);

/* ---- one request and its answers -------------------------------------------------- */

typedef enum req_kind {
    REQ_DESTINATION,        /* msg.destination on DESTINATION */
    REQ_COMMAND,            /* msg.command on COMMAND */
} req_kind_t;

typedef struct req_request {
    req_kind_t kind;
    union {
        hl_bus_destination_t destination;
        hl_bus_command_t command;
    } msg;                  /* everything but utime, seq and mac, which req_run fills */
    bool accepted_ends;     /* ACCEPTED ends the wait with EXIT_DONE; otherwise it is
                               printed and the wait goes on for ARRIVED or a refusal */
    bool follow_progress;   /* a destination: ACCEPTED, and every STATUS that shows it
                               under way and something changed (state, scans, the
                               estimate), restart the o->timeout_s wait */
    const char *accepted_text;  /* printed for an ACCEPTED whose message is empty */
    bool wait_for_robot;    /* a destination: NO_ROBOT, or no answer at all (the daemon
                               is starting), is asked again (a new seq) until an answer
                               other than NO_ROBOT comes or o->timeout_s passes */
    bool stop_on_signal;    /* SIGINT or SIGTERM while waiting: send STOP before exiting
                               (the robot must not drive on without its operator) */
    bool accepted;          /* out: an ACCEPTED came (tells a timeout after it apart) */
} req_request_t;

/**
 * Sends @p r with the options @p o and waits for its answers. In order: resolves the URL
 * and the channel names (with o->prefix), stamps utime and seq with the wall clock in
 * microseconds (strictly increasing from call to call, as the daemon requires of the
 * seq it shares between DESTINATION and COMMAND), signs with the key in o->key_file for
 * o->prefix's channels when one is given, subscribes to REPLY (and STATUS when r->follow_progress), publishes, and
 * handles the messages with poll() until an answer to this seq ends the wait, o->timeout_s
 * passes with no answer (with r->follow_progress: no sign of progress either), or
 * o->deadline_s (when not 0) passes since the request was sent.
 *
 * With a key, only REPLY messages whose MAC is right for the key and o->prefix count
 * (auth.h): any other answer to the seq (a forged ARRIVED, or that of a daemon without
 * the key) is ignored, with one warning on stderr the first time, and the wait goes on;
 * their number is added to a timeout's message. An unverifiable REJECTED_AUTH (what a
 * daemon answers a client whose key is not its own) is reported, EXIT_REJECTED, only
 * when the wait runs out with no signed answer.
 *
 * Each answer is printed as one line "<prog>: <RESULT>: <message>", ACCEPTED and ARRIVED
 * on stdout, the others on stderr. After a timeout with no answer at all it says so on
 * stderr (naming the reply channel); after ACCEPTED it says which limit ran out and the
 * last state STATUS showed.
 *
 * @param[in,out] r  the request (not NULL); r->msg's stamps and r->accepted are written.
 * With r->wait_for_robot, NO_ROBOT and silence are waited out as it says; with
 * r->stop_on_signal, SIGINT or SIGTERM sends a STOP command (unsigned unless a key is
 * given: the daemon takes STOP from anyone), waits up to two seconds for its answer and
 * ends with EXIT_SIGNAL + the signal.
 *
 * @return the exit code: EXIT_DONE on ARRIVED, or ACCEPTED when r->accepted_ends;
 *         EXIT_REJECTED, EXIT_NO_ROBOT, EXIT_FAILED per the answer; EXIT_TIMEOUT;
 *         EXIT_SIGNAL + the signal when interrupted;
 *         EXIT_USAGE for a prefix that does not fit; EXIT_ERROR when the key file is
 *         refused, LCM does not start or stops, or the message does not encode (each
 *         after a one-line message).
 */
int req_run(const char *prog, const req_options_t *o, req_request_t *r);

#endif
