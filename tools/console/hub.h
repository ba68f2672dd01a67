/*
 * hub.h - the console's event streams (private to tools/console): the latest of every
 * message, kept for a page that connects late, and one outgoing queue per connected
 * page, of Server-Sent Events frames ("event: NAME\ndata: JSON\n\n"). No I/O: the HTTP
 * layer reads the queues and is told (the wake callback) when a queue it left empty has
 * something again, so that it can resume the stream it suspended, or when a stream was
 * cut off, so that it can end it.
 *
 * Kept for late pages: the last MAP, POSE, STATUS, GROUND_TRUTH, PATH and hello, the last
 * HUB_REPLIES_KEPT replies and destinations sent, and the trajectories (estimate and
 * truth) as polylines of at most HUB_TRACK_MAX points.
 *
 * Memory is bounded whatever the pages do (docs/manual/houghloc-console.md, "Limits"):
 *   - a frame is made once and shared by every queue that holds it (counted references);
 *   - a queued frame of a kind where only the latest matters (map, pose, status, truth,
 *     path, hello, keepalive) that a page has not begun to read is replaced by the newer
 *     one in place: a page that reads slowly gets the newest map, not every map. Replies
 *     and destinations sent are small and kept in order;
 *   - a page whose queue holds more than HUB_CLIENT_MAX bytes or HUB_STREAM_FRAMES frames
 *     is cut off;
 *   - when the frames held by the hub and all queues together pass HUB_TOTAL_MAX bytes,
 *     the page with the largest queue (the slowest) is cut off, then the next, until
 *     they fit.
 * A page cut off reconnects (EventSource does) and gets the snapshot afresh.
 *
 * Why these caps: a page's queue holds at most one map being sent and one newer (the
 * console thins a map's JSON to at most 65,536 vectors, 2 MB: bridge.h), the
 * trajectories (0.7 MB at most) and small frames: about 5 MB, under HUB_CLIENT_MAX, so
 * that cap only catches what coalescing cannot (a pile of replies). HUB_TOTAL_MAX
 * (16 MiB) holds the snapshot and several slow pages' maps in flight, and keeps the
 * console under 64 MiB resident with 64 pages that stopped reading while maps of the
 * largest size the wire allows (12.6 MB, decoded once more) arrive
 * (tools/lab/trials/console.sh).
 */
#ifndef HOUGHLOC_TOOLS_CONSOLE_HUB_H
#define HOUGHLOC_TOOLS_CONSOLE_HUB_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define HUB_REPLIES_KEPT 16
#define HUB_TRACK_MAX 20000
#define HUB_STREAM_FRAMES 128               /* frames queued on one page at most */
#define HUB_CLIENT_MAX ((size_t)8 << 20)    /* bytes queued on one page at most */
#define HUB_TOTAL_MAX ((size_t)16 << 20)    /* bytes of frames held in all */

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

/* One SSE frame, shared by the queues that hold it (its body is in hub.c). */
typedef struct hub_frame hub_frame_t;

typedef struct hub_stream {
    hub_frame_t *ring[HUB_STREAM_FRAMES];   /* the frames not yet read, oldest first */
    unsigned head, count;
    size_t offset;              /* bytes of the oldest frame already read */
    size_t bytes;               /* bytes queued and not yet read */
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

/**
 * The HTTP layer's callback: @p s has frames again after it was found empty
 * (@p suspended: its response waits to be resumed), or it was cut off (s->dead: end it).
 */
typedef void (*hub_wake_fn)(void *user, hub_stream_t *s, bool suspended);

typedef struct hub {
    hub_frame_t *latest[HUB_KINDS];     /* the last frame of each kind (REPLY, SENT: none) */
    hub_frame_t *recent[2][HUB_REPLIES_KEPT];   /* replies, sent destinations: rings */
    unsigned recent_next[2], recent_count[2];
    hub_track_t track[2];       /* 0: POSE, 1: GROUND_TRUTH */
    hub_frame_t *tracks;        /* the trajectories' frame, made when a page opens and
                                   dropped by the next POSE or GROUND_TRUTH */
    hub_frame_t *keepalive;
    hub_stream_t *streams;
    unsigned nstreams;
    size_t bytes;               /* bytes of every frame alive: the hub's and the queues' */
    size_t peak_bytes;          /* the most `bytes` has been */
    uint64_t cut_off;           /* streams cut off for reading too slowly */
    uint64_t coalesced;         /* queued frames replaced by a newer one of their kind */
    hub_wake_fn wake;
    void *wake_user;
} hub_t;

/** Sets up an empty hub. @return false when out of memory. */
bool hub_init(hub_t *h, hub_wake_fn wake, void *wake_user);
/** Frees everything; every stream must have been closed. Accepts a zeroed hub. */
void hub_free(hub_t *h);

/** The event's name on the wire ("map", "pose", ...). */
const char *hub_kind_name(hub_kind_t k);

/**
 * Publishes one message's JSON (one line, @p len bytes) to every stream and keeps it
 * for late pages. For POSE and GROUND_TRUTH, (@p x_mm, @p y_mm) extends the trajectory
 * (the coordinates are ignored for other kinds). Then cuts off the slowest pages while
 * the frames held pass HUB_TOTAL_MAX.
 * @return false when the hub ran out of memory (the event is then lost).
 */
bool hub_publish(hub_t *h, hub_kind_t k, const char *json, size_t len, int32_t x_mm,
                 int32_t y_mm);

/** Adds a comment frame to every stream, so that a page that went away is noticed. */
void hub_keepalive(hub_t *h);

/**
 * Opens a stream for the connection @p conn with everything kept queued at once: the
 * hello, the trajectories, the map, status, pose, truth, path, then the kept replies and
 * destinations, oldest first. @return NULL when out of memory.
 */
hub_stream_t *hub_stream_open(hub_t *h, void *conn);
/** Copies at most @p max queued bytes into @p buf and drops them from the queue.
 *  @return the number copied; 0 when the queue is empty (s->idle is then set) or the
 *  stream was cut off. */
size_t hub_stream_read(hub_stream_t *s, char *buf, size_t max);
/** Removes @p s from its hub and frees it (the HTTP layer's end-of-response callback). */
void hub_stream_close(hub_stream_t *s);

#endif
