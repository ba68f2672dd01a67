/* hub.c - the console's event streams and what late pages get (hub.h). */
#include "hub.h"

#include <stdlib.h>
#include <string.h>

#include "jbuf.h"

/* The frames the hub makes itself, beside the message kinds. */
enum { FRAME_TRACKS = HUB_KINDS, FRAME_KEEPALIVE };

struct hub_frame {
    unsigned refs;              /* the hub's slot and every queue holding it */
    int kind;                   /* hub_kind_t, FRAME_TRACKS or FRAME_KEEPALIVE */
    size_t len;
    char data[];                /* "event: NAME\ndata: JSON\n\n" */
};

static const char *const kind_names[HUB_KINDS] = {
    [HUB_HELLO] = "hello", [HUB_MAP] = "map", [HUB_POSE] = "pose", [HUB_STATUS] = "status",
    [HUB_TRUTH] = "truth", [HUB_REPLY] = "reply", [HUB_SENT] = "sent", [HUB_PATH] = "path",
};

const char *hub_kind_name(hub_kind_t k)
{
    return k < HUB_KINDS ? kind_names[k] : "unknown";
}

/* Kinds where a page needs only the newest: a queued one not yet begun is replaced. */
static bool coalesces(int kind)
{
    return kind != HUB_REPLY && kind != HUB_SENT && kind != FRAME_TRACKS;
}

/* A new frame of @p parts (NULL-ended), with one reference (the caller's). */
static hub_frame_t *frame_new(hub_t *h, int kind, const char *const *parts, const size_t *lens)
{
    size_t len = 0;
    for (int i = 0; parts[i]; i++)
        len += lens[i];
    hub_frame_t *f = malloc(sizeof *f + len + 1);
    if (!f)
        return NULL;
    *f = (hub_frame_t){ .refs = 1, .kind = kind, .len = len };
    size_t at = 0;
    for (int i = 0; parts[i]; i++) {
        memcpy(f->data + at, parts[i], lens[i]);
        at += lens[i];
    }
    f->data[len] = '\0';
    h->bytes += len;
    if (h->bytes > h->peak_bytes)
        h->peak_bytes = h->bytes;
    return f;
}

/* An event frame: the data is one line (the bridge writes no newline). */
static hub_frame_t *event_new(hub_t *h, int kind, const char *event, const char *json,
                              size_t len)
{
    const char *parts[] = { "event: ", event, "\ndata: ", json, "\n\n", NULL };
    const size_t lens[] = { 7, strlen(event), 7, len, 2 };
    return frame_new(h, kind, parts, lens);
}

static hub_frame_t *frame_ref(hub_frame_t *f)
{
    f->refs++;
    return f;
}

static void frame_unref(hub_t *h, hub_frame_t *f)
{
    if (f && --f->refs == 0) {
        h->bytes -= f->len;
        free(f);
    }
}

bool hub_init(hub_t *h, hub_wake_fn wake, void *wake_user)
{
    *h = (hub_t){ .wake = wake, .wake_user = wake_user };
    static const char ping[] = ": keepalive\n\n";
    const char *parts[] = { ping, NULL };
    const size_t lens[] = { sizeof ping - 1 };
    h->keepalive = frame_new(h, FRAME_KEEPALIVE, parts, lens);
    for (int t = 0; t < 2; t++)
        h->track[t].xy = malloc(sizeof(int32_t) * 2 * HUB_TRACK_MAX);
    if (!h->keepalive || !h->track[0].xy || !h->track[1].xy) {
        hub_free(h);
        return false;
    }
    return true;
}

void hub_free(hub_t *h)
{
    for (int k = 0; k < HUB_KINDS; k++) {
        frame_unref(h, h->latest[k]);
        h->latest[k] = NULL;
    }
    for (int l = 0; l < 2; l++)
        for (int i = 0; i < HUB_REPLIES_KEPT; i++) {
            frame_unref(h, h->recent[l][i]);
            h->recent[l][i] = NULL;
        }
    frame_unref(h, h->tracks);
    frame_unref(h, h->keepalive);
    h->tracks = h->keepalive = NULL;
    for (int t = 0; t < 2; t++) {
        free(h->track[t].xy);
        h->track[t].xy = NULL;
    }
}

/* Drops every frame queued on @p s. */
static void release(hub_t *h, hub_stream_t *s)
{
    for (; s->count; s->count--) {
        frame_unref(h, s->ring[s->head]);
        s->head = (s->head + 1) % HUB_STREAM_FRAMES;
    }
    s->offset = 0;
    s->bytes = 0;
}

/* Cuts @p s off: its frames are dropped now, and the HTTP layer is told to end it. */
static void cut(hub_t *h, hub_stream_t *s)
{
    release(h, s);
    s->dead = true;
    h->cut_off++;
    bool suspended = s->idle;
    s->idle = false;
    if (h->wake)
        h->wake(h->wake_user, s, suspended);
}

/* Queues @p f on @p s: in place of a queued frame of its kind not yet begun, when only
 * the newest of the kind matters; else at the end. */
static void push(hub_t *h, hub_stream_t *s, hub_frame_t *f)
{
    if (s->dead)
        return;
    bool replaced = false;
    if (coalesces(f->kind)) {
        for (unsigned i = s->offset ? 1 : 0; i < s->count && !replaced; i++) {
            hub_frame_t **slot = &s->ring[(s->head + i) % HUB_STREAM_FRAMES];
            if ((*slot)->kind != f->kind)
                continue;
            hub_frame_t *old = *slot;
            *slot = frame_ref(f);
            s->bytes = s->bytes - old->len + f->len;
            frame_unref(h, old);
            h->coalesced++;
            replaced = true;
        }
    }
    if (!replaced) {
        if (s->count == HUB_STREAM_FRAMES) {
            cut(h, s);
            return;
        }
        s->ring[(s->head + s->count) % HUB_STREAM_FRAMES] = frame_ref(f);
        s->count++;
        s->bytes += f->len;
    }
    if (s->bytes > HUB_CLIENT_MAX) {
        cut(h, s);
        return;
    }
    if (s->idle) {
        s->idle = false;
        if (h->wake)
            h->wake(h->wake_user, s, true);
    }
}

/* While the frames held pass HUB_TOTAL_MAX: cut off the page with the largest queue, the
 * one furthest behind. */
static void fit_total(hub_t *h)
{
    while (h->bytes > HUB_TOTAL_MAX) {
        hub_stream_t *worst = NULL;
        for (hub_stream_t *s = h->streams; s; s = s->next)
            if (!s->dead && s->bytes > 0 && (!worst || s->bytes > worst->bytes))
                worst = s;
        if (!worst)
            return;
        cut(h, worst);
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
    if (k == HUB_POSE || k == HUB_TRUTH) {
        track_add(&h->track[k == HUB_TRUTH], x_mm, y_mm);
        frame_unref(h, h->tracks); /* made again when a page opens */
        h->tracks = NULL;
    }
    hub_frame_t *f = event_new(h, (int)k, kind_names[k], json, len);
    if (!f)
        return false;
    hub_frame_t **keep = &h->latest[k];
    if (k == HUB_REPLY || k == HUB_SENT) {
        int l = k == HUB_SENT;
        keep = &h->recent[l][h->recent_next[l]];
        h->recent_next[l] = (h->recent_next[l] + 1) % HUB_REPLIES_KEPT;
        if (h->recent_count[l] < HUB_REPLIES_KEPT)
            h->recent_count[l]++;
    }
    frame_unref(h, *keep);
    *keep = f;
    for (hub_stream_t *s = h->streams; s; s = s->next)
        push(h, s, f);
    fit_total(h);
    return true;
}

void hub_keepalive(hub_t *h)
{
    for (hub_stream_t *s = h->streams; s; s = s->next)
        push(h, s, h->keepalive);
}

/* {"estimate":[x,y,...],"truth":[x,y,...]} as a frame; NULL when out of memory. */
static hub_frame_t *tracks_frame(hub_t *h)
{
    static const char *const names[2] = { "{\"estimate\":[", "],\"truth\":[" };
    jbuf_t b;
    jbuf_init(&b, 0);
    for (int t = 0; t < 2; t++) {
        const hub_track_t *tr = &h->track[t];
        jbuf_puts(&b, names[t]);
        for (uint32_t i = 0; i < tr->count; i++) {
            uint32_t j = (tr->start + i) % HUB_TRACK_MAX;
            if (i)
                jbuf_putc(&b, ',');
            jbuf_int(&b, tr->xy[2 * j]);
            jbuf_putc(&b, ',');
            jbuf_int(&b, tr->xy[2 * j + 1]);
        }
    }
    jbuf_puts(&b, "]}");
    hub_frame_t *f = b.failed ? NULL : event_new(h, FRAME_TRACKS, "tracks", b.data, b.len);
    jbuf_free(&b);
    return f;
}

hub_stream_t *hub_stream_open(hub_t *h, void *conn)
{
    if (!h->tracks)
        h->tracks = tracks_frame(h); /* shared by the pages that open before a new pose */
    hub_stream_t *s = h->tracks ? calloc(1, sizeof *s) : NULL;
    if (!s)
        return NULL;
    s->conn = conn;
    s->hub = h;
    if (h->latest[HUB_HELLO])
        push(h, s, h->latest[HUB_HELLO]);
    push(h, s, h->tracks);
    static const hub_kind_t order[] = { HUB_MAP, HUB_STATUS, HUB_POSE, HUB_TRUTH, HUB_PATH };
    for (size_t i = 0; i < sizeof order / sizeof order[0]; i++)
        if (h->latest[order[i]])
            push(h, s, h->latest[order[i]]);
    for (int l = 1; l >= 0; l--) {  /* what was sent before the answers to it */
        unsigned n = h->recent_count[l];
        for (unsigned i = 0; i < n; i++)
            push(h, s, h->recent[l][(h->recent_next[l] + HUB_REPLIES_KEPT - n + i) %
                                    HUB_REPLIES_KEPT]);
    }
    s->next = h->streams;
    h->streams = s;
    h->nstreams++;
    return s;
}

size_t hub_stream_read(hub_stream_t *s, char *buf, size_t max)
{
    size_t n = 0;
    while (n < max && s->count) {
        hub_frame_t *f = s->ring[s->head];
        size_t take = f->len - s->offset;
        if (take > max - n)
            take = max - n;
        memcpy(buf + n, f->data + s->offset, take);
        n += take;
        s->offset += take;
        s->bytes -= take;
        if (s->offset == f->len) {
            frame_unref(s->hub, f);
            s->head = (s->head + 1) % HUB_STREAM_FRAMES;
            s->count--;
            s->offset = 0;
        }
    }
    if (n == 0 && !s->dead)
        s->idle = true;
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
    release(h, s);
    free(s);
}
