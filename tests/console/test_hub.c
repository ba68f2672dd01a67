/* Tests for tools/console/hub.c: the frames every stream gets, what a late page gets at
 * once, the wake of an idle stream, the trajectories, and the cut-off of a slow page. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <string.h>

#include "hub.h"

static int wakes;
static void on_wake(void *user, hub_stream_t *s)
{
    assert_ptr_equal(user, &wakes);
    assert_non_null(s);
    wakes++;
}

/* Everything queued on @p s, as a string (at most 64 KiB). */
static const char *drain(hub_stream_t *s)
{
    static char buf[65536];
    size_t n = 0, got;
    while ((got = hub_stream_read(s, buf + n, 7)) > 0) /* in small pieces, as a socket may */
        n += got;
    buf[n] = '\0';
    return buf;
}

static void publish(hub_t *h, hub_kind_t k, const char *json, int32_t x, int32_t y)
{
    assert_true(hub_publish(h, k, json, strlen(json), x, y));
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
    const char *all = s->queue.data;
    assert_non_null(strstr(all, "{\"estimate\":[5,-5,6,-6,"));
    assert_non_null(strstr(all, ",20004,-20004],\"truth\":[]}"));
    hub_stream_close(s);
    hub_free(&h);
}

/* A page that does not read is cut off at HUB_QUEUE_MAX; the others go on. */
static void test_slow_page_cut_off(void **state)
{
    (void)state;
    hub_t h;
    assert_true(hub_init(&h, NULL, NULL));
    hub_stream_t *slow = hub_stream_open(&h, NULL), *fast = hub_stream_open(&h, NULL);
    drain(fast);
    static char big[1 << 20];
    memset(big, 'x', sizeof big - 1);
    size_t sent = 0;
    while (!slow->dead && sent < 2 * HUB_QUEUE_MAX) {
        assert_true(hub_publish(&h, HUB_MAP, big, sizeof big - 1, 0, 0));
        sent += sizeof big;
        jbuf_consume(&fast->queue, fast->queue.len); /* the fast page reads everything */
    }
    assert_true(slow->dead);
    assert_false(fast->dead);
    assert_int_equal(h.cut_off, 1);
    assert_true(sent <= HUB_QUEUE_MAX + sizeof big);
    hub_stream_close(slow);
    hub_stream_close(fast);
    hub_free(&h);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_live_frames_and_wake),
        cmocka_unit_test(test_late_page_snapshot),
        cmocka_unit_test(test_track_ring),
        cmocka_unit_test(test_slow_page_cut_off),
    };
    return cmocka_run_group_tests_name("console_hub", tests, NULL, NULL);
}
