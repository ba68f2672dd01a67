/* Tests for tools/console/hub.c: the frames every stream gets, what a late page gets at
 * once, the wake of an idle stream, the trajectories; and the bounds on memory: a page
 * that stops reading gets the newest of each coalesced kind instead of every one, replies
 * kept in order, the per-page caps, the total cap that cuts off the slowest page, and
 * the byte count of what is held. The hub is driven directly: no clock, no sockets. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hub.h"

static int wakes, cuts;
static void on_wake(void *user, hub_stream_t *s, bool suspended)
{
    assert_ptr_equal(user, &wakes);
    assert_non_null(s);
    if (s->dead)
        cuts++;
    else
        assert_true(suspended);
    wakes++;
}

/* Everything queued on @p s, as a string (at most 1 MiB). */
static const char *drain(hub_stream_t *s)
{
    static char buf[1 << 20];
    size_t n = 0, got;
    while ((got = hub_stream_read(s, buf + n, 7)) > 0) { /* in small pieces, as a socket may */
        n += got;
        assert_true(n < sizeof buf - 7);
    }
    buf[n] = '\0';
    return buf;
}

/* Reads and drops everything queued on @p s: a page that keeps up. */
static void discard(hub_stream_t *s)
{
    static char buf[65536];
    while (hub_stream_read(s, buf, sizeof buf) > 0)
        ;
}

static void publish(hub_t *h, hub_kind_t k, const char *json, int32_t x, int32_t y)
{
    assert_true(hub_publish(h, k, json, strlen(json), x, y));
}

/* A JSON text of @p n bytes (a string of 'x'), in a buffer of the caller's. */
static char *big_json(size_t n)
{
    char *j = malloc(n + 1);
    assert_non_null(j);
    memset(j, 'x', n);
    j[0] = '"';
    j[n - 1] = '"';
    j[n] = '\0';
    return j;
}

static void test_live_frames_and_wake(void **state)
{
    (void)state;
    hub_t h;
    assert_true(hub_init(&h, on_wake, &wakes));
    publish(&h, HUB_HELLO, "{\"v\":1}", 0, 0);
    hub_stream_t *s = hub_stream_open(&h, NULL);
    assert_non_null(s);
    assert_int_equal(h.nstreams, 1);
    assert_string_equal(drain(s), "event: hello\ndata: {\"v\":1}\n\n"
                                  "event: tracks\ndata: {\"estimate\":[],\"truth\":[]}\n\n");
    assert_true(s->idle);
    wakes = 0;
    publish(&h, HUB_POSE, "{\"p\":1}", 10, 20);
    assert_int_equal(wakes, 1);     /* idle: woken once */
    publish(&h, HUB_STATUS, "{\"s\":2}", 0, 0);
    assert_int_equal(wakes, 1);     /* not idle any more: no second wake */
    assert_string_equal(drain(s), "event: pose\ndata: {\"p\":1}\n\nevent: status\ndata: {\"s\":2}\n\n");
    hub_keepalive(&h);
    assert_int_equal(wakes, 2);
    assert_string_equal(drain(s), ": keepalive\n\n");
    hub_stream_close(s);
    assert_int_equal(h.nstreams, 0);
    hub_free(&h);
}

static void test_late_page_snapshot(void **state)
{
    (void)state;
    hub_t h;
    assert_true(hub_init(&h, NULL, NULL));
    publish(&h, HUB_HELLO, "{}", 0, 0);
    publish(&h, HUB_MAP, "{\"m\":1}", 0, 0);
    publish(&h, HUB_MAP, "{\"m\":2}", 0, 0);
    publish(&h, HUB_POSE, "{\"p\":1}", 1, 2);
    publish(&h, HUB_POSE, "{\"p\":2}", 3, 4);
    publish(&h, HUB_TRUTH, "{\"t\":1}", -5, 6);
    publish(&h, HUB_STATUS, "{\"s\":1}", 0, 0);
    publish(&h, HUB_PATH, "{\"path\":1}", 0, 0);
    publish(&h, HUB_PATH, "{\"path\":2}", 0, 0);
    for (int i = 0; i < HUB_REPLIES_KEPT + 3; i++) {
        char r[32];
        snprintf(r, sizeof r, "{\"r\":%d}", i);
        publish(&h, HUB_REPLY, r, 0, 0);
    }
    publish(&h, HUB_SENT, "{\"d\":1}", 0, 0);
    hub_stream_t *s = hub_stream_open(&h, NULL);
    const char *all = drain(s);
    const char *want_start =
        "event: hello\ndata: {}\n\n"
        "event: tracks\ndata: {\"estimate\":[1,2,3,4],\"truth\":[-5,6]}\n\n"
        "event: map\ndata: {\"m\":2}\n\n"
        "event: status\ndata: {\"s\":1}\n\n"
        "event: pose\ndata: {\"p\":2}\n\n"
        "event: truth\ndata: {\"t\":1}\n\n"
        "event: path\ndata: {\"path\":2}\n\n"      /* the last way planned */
        "event: sent\ndata: {\"d\":1}\n\n"
        "event: reply\ndata: {\"r\":3}\n\n";       /* the oldest reply kept */
    assert_memory_equal(all, want_start, strlen(want_start));
    assert_non_null(strstr(all, "event: reply\ndata: {\"r\":18}\n\n"));
    assert_null(strstr(all, "{\"r\":2}"));
    hub_stream_close(s);
    hub_free(&h);
}

static void test_track_ring(void **state)
{
    (void)state;
    hub_t h;
    assert_true(hub_init(&h, NULL, NULL));
    for (int i = 0; i < HUB_TRACK_MAX + 5; i++)
        publish(&h, HUB_POSE, "{}", i, -i);
    assert_int_equal(h.track[0].count, HUB_TRACK_MAX);
    assert_int_equal(h.track[1].count, 0);
    hub_stream_t *s = hub_stream_open(&h, NULL);
    const char *all = drain(s);
    assert_non_null(strstr(all, "{\"estimate\":[5,-5,6,-6,"));
    assert_non_null(strstr(all, ",20004,-20004],\"truth\":[]}"));
    hub_stream_close(s);
    hub_free(&h);
}

/* A page that stops reading: the map it has begun is finished, then only the newest map,
 * pose, status, truth and path follow; every reply and destination sent, in order. */
static void test_coalesce_slow_page(void **state)
{
    (void)state;
    hub_t h;
    assert_true(hub_init(&h, NULL, NULL));
    hub_stream_t *s = hub_stream_open(&h, NULL);
    drain(s);
    publish(&h, HUB_MAP, "{\"m\":1}", 0, 0);
    char head[8];
    assert_int_equal(hub_stream_read(s, head, 5), 5);  /* map 1 begun: it stays */
    publish(&h, HUB_REPLY, "{\"r\":1}", 0, 0);
    for (int i = 2; i <= 100; i++) {
        char j[32];
        snprintf(j, sizeof j, "{\"m\":%d}", i);
        publish(&h, HUB_MAP, j, 0, 0);
        snprintf(j, sizeof j, "{\"p\":%d}", i);
        publish(&h, HUB_POSE, j, i, i);
        snprintf(j, sizeof j, "{\"s\":%d}", i);
        publish(&h, HUB_STATUS, j, 0, 0);
        publish(&h, HUB_PATH, j, 0, 0);
        publish(&h, HUB_TRUTH, j, 0, 0);
        hub_keepalive(&h);
        if (i == 50)
            publish(&h, HUB_SENT, "{\"d\":50}", 0, 0);
        if (i == 60)
            publish(&h, HUB_REPLY, "{\"r\":60}", 0, 0);
    }
    assert_int_equal(s->count, 10); /* map 1, reply 1, map, pose, status, path, truth,
                                       keepalive, sent, reply 60 */
    assert_string_equal(drain(s), ": map\ndata: {\"m\":1}\n\n"
                                  "event: reply\ndata: {\"r\":1}\n\n"
                                  "event: map\ndata: {\"m\":100}\n\n"
                                  "event: pose\ndata: {\"p\":100}\n\n"
                                  "event: status\ndata: {\"s\":100}\n\n"
                                  "event: path\ndata: {\"s\":100}\n\n"
                                  "event: truth\ndata: {\"s\":100}\n\n"
                                  ": keepalive\n\n"
                                  "event: sent\ndata: {\"d\":50}\n\n"
                                  "event: reply\ndata: {\"r\":60}\n\n");
    assert_int_equal(h.coalesced, 98 * 6); /* all but the first of each kind */
    assert_false(s->dead);
    hub_stream_close(s);
    hub_free(&h);
}

/* A frame is made once: a hundred pages behind on the same map hold one copy of it. */
static void test_frames_shared(void **state)
{
    (void)state;
    hub_t h;
    assert_true(hub_init(&h, NULL, NULL));
    size_t empty = h.bytes;
    hub_stream_t *s[100];
    for (int i = 0; i < 100; i++)
        s[i] = hub_stream_open(&h, NULL);
    char *j = big_json(1 << 20);
    assert_true(hub_publish(&h, HUB_MAP, j, 1 << 20, 0, 0));
    assert_true(h.bytes < empty + (1u << 20) + 4096);  /* one map, the tracks frame */
    assert_true(hub_publish(&h, HUB_MAP, j, 1 << 20, 0, 0)); /* replaces it everywhere */
    assert_true(h.bytes < empty + (1u << 20) + 4096);
    for (int i = 0; i < 100; i++) {
        assert_int_equal(s[i]->count, 2); /* the tracks, then the one map */
        hub_stream_close(s[i]);
    }
    assert_true(h.bytes < empty + (1u << 20) + 4096);   /* the hub keeps the last map */
    free(j);
    hub_free(&h);
    assert_int_equal(h.bytes, 0);   /* every byte counted is given back */
}

/* Replies are never coalesced: a page that lets HUB_STREAM_FRAMES of them pile up, or
 * more than HUB_CLIENT_MAX bytes, is cut off; a page that reads is not. */
static void test_per_page_caps(void **state)
{
    (void)state;
    hub_t h;
    assert_true(hub_init(&h, on_wake, &wakes));
    hub_stream_t *slow = hub_stream_open(&h, NULL), *fast = hub_stream_open(&h, NULL);
    discard(fast);
    wakes = cuts = 0;
    int sent = 0;
    while (!slow->dead && sent < 10 * HUB_STREAM_FRAMES) {
        publish(&h, HUB_REPLY, "{\"r\":1}", 0, 0);
        sent++;
        discard(fast);
    }
    assert_true(slow->dead);
    assert_int_equal(sent, HUB_STREAM_FRAMES); /* the tracks and the replies fill it */
    assert_false(fast->dead);
    assert_int_equal(cuts, 1);      /* the HTTP layer is told, to end the response */
    assert_int_equal(slow->count, 0);
    assert_int_equal(hub_stream_read(slow, (char[8]){ 0 }, 8), 0);
    hub_stream_close(slow);

    /* bytes: replies of 1 MiB each pass HUB_CLIENT_MAX long before the frame count */
    slow = hub_stream_open(&h, NULL);
    char *j = big_json(1 << 20);
    sent = 0;
    while (!slow->dead && sent < 100) {
        assert_true(hub_publish(&h, HUB_REPLY, j, 1 << 20, 0, 0));
        sent++;
        discard(fast);
    }
    assert_true(slow->dead);
    assert_int_equal((size_t)sent, HUB_CLIENT_MAX / (1 << 20));
    assert_false(fast->dead);
    assert_int_equal(h.cut_off, 2);
    free(j);
    hub_stream_close(slow);
    hub_stream_close(fast);
    hub_free(&h);
}

/* Half the pages stop reading, each in the middle of another large map; the other half
 * read as far as the newest map and wait. When the maps held pass HUB_TOTAL_MAX, the pages
 * with the largest queues (the stopped ones: an old map and the newest) are cut off until
 * the maps fit; the others stay. */
static void test_total_cap_cuts_slowest(void **state)
{
    (void)state;
    hub_t h;
    assert_true(hub_init(&h, on_wake, &wakes));
    enum { PAGES = 64, STOPPED = PAGES / 2 };
    const size_t map = 1u << 20;
    char *j = big_json(map);
    hub_stream_t *s[PAGES];
    for (int i = 0; i < PAGES; i++)
        s[i] = hub_stream_open(&h, NULL);
    wakes = cuts = 0;
    for (int m = 0; m < STOPPED; m++) {
        assert_true(hub_publish(&h, HUB_MAP, j, map, 0, 0));
        assert_true(h.bytes <= HUB_TOTAL_MAX);
        /* page m reads its tracks, begins this map and stops there for good */
        char head[16];
        if (!s[m]->dead)
            while (s[m]->count > 1 || s[m]->offset == 0)
                hub_stream_read(s[m], head, sizeof head);
    }
    assert_true(h.peak_bytes <= HUB_TOTAL_MAX + map + 4096);
    int stopped_alive = 0;
    for (int i = 0; i < STOPPED; i++)
        stopped_alive += !s[i]->dead;
    for (int i = STOPPED; i < PAGES; i++)
        assert_false(s[i]->dead);   /* one map behind: not the slowest */
    /* 32 maps begun plus the newest do not fit in 16 MiB: about half went */
    assert_true(stopped_alive > 0 && stopped_alive < STOPPED);
    assert_int_equal(h.cut_off, (uint64_t)(STOPPED - stopped_alive));
    assert_int_equal(cuts, STOPPED - stopped_alive);
    for (int i = 0; i < PAGES; i++)
        hub_stream_close(s[i]);
    free(j);
    hub_free(&h);
    assert_int_equal(h.bytes, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_live_frames_and_wake),
        cmocka_unit_test(test_late_page_snapshot),
        cmocka_unit_test(test_track_ring),
        cmocka_unit_test(test_coalesce_slow_page),
        cmocka_unit_test(test_frames_shared),
        cmocka_unit_test(test_per_page_caps),
        cmocka_unit_test(test_total_cap_cuts_slowest),
    };
    return cmocka_run_group_tests_name("console_hub", tests, NULL, NULL);
}
