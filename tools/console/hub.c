/* hub.c - the console's event streams and what late pages get (hub.h). */
#include "hub.h"

#include <stdlib.h>
#include <string.h>

static const char *const kind_names[HUB_KINDS] = {
    [HUB_HELLO] = "hello", [HUB_MAP] = "map", [HUB_POSE] = "pose", [HUB_STATUS] = "status",
    [HUB_TRUTH] = "truth", [HUB_REPLY] = "reply", [HUB_SENT] = "sent", [HUB_PATH] = "path",
};

const char *hub_kind_name(hub_kind_t k)
{
    return k < HUB_KINDS ? kind_names[k] : "unknown";
}

bool hub_init(hub_t *h, void (*wake)(void *user, hub_stream_t *s), void *wake_user)
{
    *h = (hub_t){ .wake = wake, .wake_user = wake_user };
    for (int t = 0; t < 2; t++) {
        h->track[t].xy = malloc(sizeof(int32_t) * 2 * HUB_TRACK_MAX);
        if (!h->track[t].xy) {
            hub_free(h);
            return false;
        }
    }
    return true;
}

void hub_free(hub_t *h)
{
    for (int k = 0; k < HUB_KINDS; k++)
        jbuf_free(&h->latest[k]);
    for (int l = 0; l < 2; l++)
        for (int i = 0; i < HUB_REPLIES_KEPT; i++)
            jbuf_free(&h->recent[l][i]);
    for (int t = 0; t < 2; t++) {
        free(h->track[t].xy);
        h->track[t].xy = NULL;
    }
}

/* One SSE frame into @p b: the data is one line (the bridge writes no newline). */
static void frame(jbuf_t *b, const char *event, const char *json, size_t len)
{
    jbuf_puts(b, "event: ");
    jbuf_puts(b, event);
    jbuf_puts(b, "\ndata: ");
    jbuf_put(b, json, len);
    jbuf_puts(b, "\n\n");
}

/* Queues bytes on a stream, cutting it off when it reads too slowly. */
static void push(hub_t *h, hub_stream_t *s, const char *bytes, size_t len)
{
    if (s->dead)
        return;
    jbuf_put(&s->queue, bytes, len);
    if (s->queue.failed) {
        s->dead = true;
        h->cut_off++;
    }
    if (s->idle && h->wake) {
        s->idle = false;
        h->wake(h->wake_user, s);
    }
}

static void track_add(hub_track_t *t, int32_t x, int32_t y)
{
    uint32_t i = (t->start + t->count) % HUB_TRACK_MAX;
    t->xy[2 * i] = x;
    t->xy[2 * i + 1] = y;
    if (t->count < HUB_TRACK_MAX)
        t->count++;
    else
        t->start = (t->start + 1) % HUB_TRACK_MAX;
}

bool hub_publish(hub_t *h, hub_kind_t k, const char *json, size_t len, int32_t x_mm,
                 int32_t y_mm)
{
    if (k >= HUB_KINDS)
        return false;
    jbuf_t *keep;
    if (k == HUB_REPLY || k == HUB_SENT) {
        int l = k == HUB_SENT;
        keep = &h->recent[l][h->recent_next[l]];
        h->recent_next[l] = (h->recent_next[l] + 1) % HUB_REPLIES_KEPT;
        if (h->recent_count[l] < HUB_REPLIES_KEPT)
            h->recent_count[l]++;
    } else {
        keep = &h->latest[k];
    }
    if (k == HUB_POSE || k == HUB_TRUTH)
        track_add(&h->track[k == HUB_TRUTH], x_mm, y_mm);
    jbuf_reset(keep);
    frame(keep, kind_names[k], json, len);
    if (keep->failed) {
        jbuf_free(keep);
        return false;
    }
    for (hub_stream_t *s = h->streams; s; s = s->next)
        push(h, s, keep->data, keep->len);
    return true;
}

void hub_keepalive(hub_t *h)
{
    static const char ping[] = ": keepalive\n\n";
    for (hub_stream_t *s = h->streams; s; s = s->next)
        push(h, s, ping, sizeof ping - 1);
}

/* {"estimate":[x,y,...],"truth":[x,y,...]} */
static void tracks_json(const hub_t *h, jbuf_t *b)
{
    static const char *const names[2] = { "{\"estimate\":[", "],\"truth\":[" };
    for (int t = 0; t < 2; t++) {
        const hub_track_t *tr = &h->track[t];
        jbuf_puts(b, names[t]);
        for (uint32_t i = 0; i < tr->count; i++) {
            uint32_t j = (tr->start + i) % HUB_TRACK_MAX;
            if (i)
                jbuf_putc(b, ',');
            jbuf_int(b, tr->xy[2 * j]);
            jbuf_putc(b, ',');
            jbuf_int(b, tr->xy[2 * j + 1]);
        }
    }
    jbuf_puts(b, "]}");
}

hub_stream_t *hub_stream_open(hub_t *h, void *conn)
{
    hub_stream_t *s = calloc(1, sizeof *s);
    if (!s)
        return NULL;
    jbuf_init(&s->queue, HUB_QUEUE_MAX);
    s->conn = conn;
    s->hub = h;
    jbuf_t *q = &s->queue;
    jbuf_put(q, h->latest[HUB_HELLO].data ? h->latest[HUB_HELLO].data : "",
             h->latest[HUB_HELLO].len);
    jbuf_t tracks;
    jbuf_init(&tracks, 0);
    tracks_json(h, &tracks);
    frame(q, "tracks", tracks.data ? tracks.data : "{}", tracks.len);
    jbuf_free(&tracks);
    static const hub_kind_t order[] = { HUB_MAP, HUB_STATUS, HUB_POSE, HUB_TRUTH, HUB_PATH };
    for (size_t i = 0; i < sizeof order / sizeof order[0]; i++)
        if (h->latest[order[i]].len)
            jbuf_put(q, h->latest[order[i]].data, h->latest[order[i]].len);
    for (int l = 1; l >= 0; l--) {  /* what was sent before the answers to it */
        unsigned n = h->recent_count[l];
        for (unsigned i = 0; i < n; i++) {
            const jbuf_t *r = &h->recent[l][(h->recent_next[l] + HUB_REPLIES_KEPT - n + i) %
                                             HUB_REPLIES_KEPT];
            jbuf_put(q, r->data, r->len);
        }
    }
    if (q->failed) {
        jbuf_free(q);
        free(s);
        return NULL;
    }
    s->next = h->streams;
    h->streams = s;
    h->nstreams++;
    return s;
}

size_t hub_stream_read(hub_stream_t *s, char *buf, size_t max)
{
    size_t n = s->queue.len < max ? s->queue.len : max;
    if (n == 0) {
        s->idle = true;
        return 0;
    }
    memcpy(buf, s->queue.data, n);
    jbuf_consume(&s->queue, n);
    return n;
}

void hub_stream_close(hub_stream_t *s)
{
    hub_t *h = s->hub;
    for (hub_stream_t **p = &h->streams; *p; p = &(*p)->next) {
        if (*p == s) {
            *p = s->next;
            h->nstreams--;
            break;
        }
    }
    jbuf_free(&s->queue);
    free(s);
}
