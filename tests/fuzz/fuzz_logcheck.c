/*
 * fuzz_logcheck.c - the LCM log reader (include/bus/houghloc/logcheck.h): the input is an
 * event log file, walked by hl_log_check through a path as every program of ours does
 * before it hands a log to liblcm, and then, when the check passes, read by liblcm's own
 * event reader, which logcheck.h says is then safe. The same bytes also go to
 * hl_log_url_path as an LCM URL (a log replay's --lcm-url).
 *
 * Checked: a refusal has a status logcheck.h lists and one line naming the file; a log
 * that passes is whole events end to end (info.bytes is the file size) and liblcm reads
 * exactly those events with the same timestamps.
 */
#include <lcm/eventlog.h>
#include <string.h>
#include <unistd.h>

#include "fuzz.h"
#include "houghloc/logcheck.h"

static void check_log(const uint8_t *data, size_t size)
{
    char path[FUZZ_PATH_MAX], why[HL_LOG_WHY_LEN] = "";
    int fd = fuzz_memfile(data, size, path);
    FUZZ_CHECK(fd >= 0);
    hl_log_info_t info;
    hl_status_t st = hl_log_check(path, &info, why);
    if (st != HL_OK) {
        FUZZ_CHECK(st == HL_ERR_PARSE || st == HL_ERR_EMPTY);
        FUZZ_CHECK(memchr(why, '\0', sizeof why) != NULL && strchr(why, '\n') == NULL);
        FUZZ_CHECK(strncmp(why, path, strlen(path)) == 0);
        close(fd);
        return;
    }
    FUZZ_CHECK(info.events >= 1 && info.bytes == size);

    lcm_eventlog_t *log = lcm_eventlog_create(path, "r");
    FUZZ_CHECK(log != NULL);
    uint64_t events = 0;
    lcm_eventlog_event_t *ev;
    while ((ev = lcm_eventlog_read_next_event(log)) != NULL) {
        FUZZ_CHECK(ev->channellen >= 1 && ev->channellen <= HL_LOG_CHANNEL_MAX);
        FUZZ_CHECK(ev->datalen >= 0);
        if (events == 0)
            FUZZ_CHECK(ev->timestamp == info.first_utime);
        events++;
        if (events == info.events)
            FUZZ_CHECK(ev->timestamp == info.last_utime);
        lcm_eventlog_free_event(ev);
    }
    lcm_eventlog_destroy(log);
    FUZZ_CHECK(events == info.events);
    close(fd);
}

static void check_url(const uint8_t *data, size_t size)
{
    char *url = malloc(size + 1);
    FUZZ_CHECK(url != NULL);
    memcpy(url, data, size);
    url[size] = '\0';
    size_t caps[] = { 0, 1, 16, 4096 };
    for (size_t i = 0; i < sizeof caps / sizeof caps[0]; i++) {
        char *out = malloc(caps[i] > 0 ? caps[i] : 1);
        FUZZ_CHECK(out != NULL);
        int r = hl_log_url_path(url, caps[i] > 0 ? out : NULL, caps[i]);
        FUZZ_CHECK(r >= -1 && r <= 1);
        if (r == 1) {
            /* The path is the text after "file:" or "file://", up to any '?'. */
            size_t n = strlen(out);
            FUZZ_CHECK(n >= 1 && n < caps[i] && strchr(out, '?') == NULL);
            FUZZ_CHECK(strncmp(url, "file:", 5) == 0);
            const char *rest = strncmp(url, "file://", 7) == 0 ? url + 7 : url + 5;
            FUZZ_CHECK(strncmp(rest, out, n) == 0 && (rest[n] == '\0' || rest[n] == '?'));
        }
        free(out);
    }
    free(url);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    check_log(data, size);
    check_url(data, size);
    return 0;
}
