/*
 * hub.h - the console's event streams (private to tools/console): the latest of every
 * message, kept for a page that connects late, and one outgoing queue per connected
 * page, as Server-Sent Events frames ("event: NAME\ndata: JSON\n\n"). No I/O: the HTTP
 * layer reads the queues and is told (the wake callback) when a queue it left empty has
 * something again, so that it can resume the stream it suspended.
 *
 * Kept for late pages: the last MAP, POSE, STATUS, GROUND_TRUTH, PATH and hello, the last
 * HUB_REPLIES_KEPT replies and destinations sent, and the trajectories (estimate and
 * truth) as polylines of at most HUB_TRACK_MAX points. A page that reads too slowly
 * (a queue above HUB_QUEUE_MAX bytes) is cut off rather than let the console's memory
 * grow: it reconnects and gets the snapshot afresh.
 */
#ifndef HOUGHLOC_TOOLS_CONSOLE_HUB_H
#define HOUGHLOC_TOOLS_CONSOLE_HUB_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "jbuf.h"

#define HUB_QUEUE_MAX ((size_t)64 << 20)
#define HUB_REPLIES_KEPT 16
#define HUB_TRACK_MAX 20000

typedef enum hub_kind {
    HUB_HELLO,          /* the console itself: version, signing, options */
    HUB_MAP,
    HUB_POSE,
    HUB_STATUS,
    HUB_TRUTH,
    HUB_REPLY,          /* kept as a list, not only the last */
    HUB_SENT,           /* a DESTINATION the console published; kept as a list */
    HUB_PATH,           /* the way planned to the destination */
    HUB_KINDS,
} hub_kind_t;

typedef struct hub_stream {
    jbuf_t queue;               /* frames not yet read */
    bool dead;                  /* cut off: the HTTP layer ends the response */
    bool idle;                  /* the HTTP layer found the queue empty and waits */
    void *conn;                 /* the HTTP layer's connection */
    struct hub *hub;            /* the hub it belongs to */
    struct hub_stream *next;
} hub_stream_t;

typedef struct hub_track {
    int32_t *xy;                /* [2 * HUB_TRACK_MAX], a ring */
    uint32_t start, count;
} hub_track_t;

typedef struct hub {
    jbuf_t latest[HUB_KINDS];   /* the last frame of each kind (HUB_REPLY, HUB_SENT: none) */
    jbuf_t recent[2][HUB_REPLIES_KEPT];     /* replies, sent destinations: rings */
    unsigned recent_next[2], recent_count[2];
    hub_track_t track[2];       /* 0: POSE, 1: GROUND_TRUTH */
    hub_stream_t *streams;
    unsigned nstreams;
    uint64_t cut_off;           /* streams cut off for reading too slowly */
    void (*wake)(void *user, hub_stream_t *s);
    void *wake_user;
} hub_t;

/** Sets up an empty hub. @return false when out of memory. */
bool hub_init(hub_t *h, void (*wake)(void *user, hub_stream_t *s), void *wake_user);
/** Frees everything; every stream must have been closed. Accepts a zeroed hub. */
void hub_free(hub_t *h);

/** The event's name on the wire ("map", "pose", ...). */
const char *hub_kind_name(hub_kind_t k);

/**
 * Publishes one message's JSON (one line, @p len bytes) to every stream and keeps it
 * for late pages. For POSE and GROUND_TRUTH, (@p x_mm, @p y_mm) extends the trajectory
 * (the coordinates are ignored for other kinds).
 * @return false when the hub ran out of memory (the event is then lost to some pages).
 */
bool hub_publish(hub_t *h, hub_kind_t k, const char *json, size_t len, int32_t x_mm,
                 int32_t y_mm);

/** Adds a comment line to every stream, so that a page that went away is noticed. */
void hub_keepalive(hub_t *h);

/**
 * Opens a stream for the connection @p conn with everything kept queued at once: the
 * hello, the trajectories, the map, status, pose, truth, path, then the kept replies and
 * destinations, oldest first. @return NULL when out of memory.
 */
hub_stream_t *hub_stream_open(hub_t *h, void *conn);
/** Copies at most @p max queued bytes into @p buf and drops them from the queue.
 *  @return the number copied; 0 when the queue is empty (s->idle is then set). */
size_t hub_stream_read(hub_stream_t *s, char *buf, size_t max);
/** Removes @p s from its hub and frees it (the HTTP layer's end-of-response callback). */
void hub_stream_close(hub_stream_t *s);

#endif
