/* cycle_save.c - when the map is saved: every daemon.save_every integrations, and on a
 * SAVE request, at most one write per HL_CYCLE_SAVE_MIN_INTERVAL_MS for requests.
 *
 * A save writes the whole map file and syncs it twice (mapstore.h); nothing bounded how
 * often SAVE requests made the daemon do it, and a client sending 1,000 of them a second
 * had it write 130 MB and sync 12,600 times in 6 s while POSE waited up to 7 s. So a
 * SAVE inside the interval after the last write is not written then:
 *  - the map unchanged since that write: answered at once, ACCEPTED, with the write's age
 *    (the file holds the map already);
 *  - the map changed: the request waits for the interval's end, then the map is written
 *    and the request answered (a later SAVE meanwhile supersedes it: the earlier one is
 *    answered at once, the later one when written). Nothing asked for is lost.
 * Which of the two is loop.c's to say (maplock.h's test, on the file's side): the cycle
 * says when a save is due, whether a due one may wait, and answers. daemon.save_every's
 * saves, SIGHUP's and the stop's are never held back.
 */
#include <stdio.h>

#include "cycle_internal.h"
#include "log.h"

#define MIN_INTERVAL_US ((int64_t)HL_CYCLE_SAVE_MIN_INTERVAL_MS * 1000)

static int64_t now_us(const hl_cycle_t *c)
{
    return c->io.now_us(c->io.ctx);
}

static bool every_due(const hl_cycle_t *c)
{
    return c->p.save_every > 0 && c->since_save >= c->p.save_every;
}

/* Inside the interval after this process's last write. */
static bool too_soon(const hl_cycle_t *c)
{
    return c->saved_once && now_us(c) - c->last_save_us < MIN_INTERVAL_US;
}

void hl_cycle_on_save(hl_cycle_t *c, int64_t seq)
{
    if (c->save_requested) {
        char what[HL_BUS_TEXT_MAX];
        snprintf(what, sizeof what, "superseded by SAVE request %lld, which the next save "
                 "answers", (long long)seq);
        hl_cycle_reply(c, c->save_request_seq, HL_BUS_REPLY_ACCEPTED, what);
    }
    c->save_requested = true;
    c->save_request_seq = seq;
}

bool hl_cycle_save_due(const hl_cycle_t *c)
{
    if (every_due(c))
        return true;
    /* a request is due at once, for the loop to look at; once it waits, at its time */
    return c->save_requested && (!c->save_waiting || !too_soon(c));
}

bool hl_cycle_save_may_wait(const hl_cycle_t *c)
{
    return c->save_requested && !every_due(c) && too_soon(c);
}

void hl_cycle_save_wait(hl_cycle_t *c)
{
    if (!c->save_waiting)
        hl_log(HL_LOG_INFO, "SAVE request %lld: the map changed since the save %.1f s ago; "
               "written %.1f s after it (at most one save per %.0f s for requests)",
               (long long)c->save_request_seq, (now_us(c) - c->last_save_us) / 1e6,
               MIN_INTERVAL_US / 1e6, MIN_INTERVAL_US / 1e6);
    c->save_waiting = true;
}

int64_t hl_cycle_save_wake_us(const hl_cycle_t *c)
{
    return c->save_requested && c->save_waiting ? c->last_save_us + MIN_INTERVAL_US
                                                : INT64_MAX;
}

/* The request (if any) is answered, the count starts over. */
static void done(hl_cycle_t *c, int8_t result, const char *message)
{
    c->since_save = 0;
    if (c->save_request_seq)
        hl_cycle_reply(c, c->save_request_seq, result, message);
    c->save_requested = false;
    c->save_request_seq = 0;
    c->save_waiting = false;
}

void hl_cycle_saved(hl_cycle_t *c, bool ok, const char *why)
{
    /* after a failure too: its cost was paid, and save_every's retry comes after
     * save_every more integrations */
    c->saved_once = true;
    c->last_save_us = now_us(c);
    if (ok)
        hl_count_add(&c->n.saves, 1);
    else
        hl_cycle_fault(c, NULL, "save", why);
    done(c, ok ? HL_BUS_REPLY_ACCEPTED : HL_BUS_REPLY_FAILED, ok ? "map saved" : why);
}

int64_t hl_cycle_save_request(const hl_cycle_t *c)
{
    return c->save_requested ? c->save_request_seq : 0;
}

void hl_cycle_save_unchanged(hl_cycle_t *c)
{
    char what[HL_BUS_TEXT_MAX];
    if (c->saved_once)
        snprintf(what, sizeof what, "map unchanged since the last save, %.1f s ago: nothing "
                 "written (the file holds it)", (now_us(c) - c->last_save_us) / 1e6);
    else
        snprintf(what, sizeof what, "map unchanged since the last save: nothing written");
    done(c, HL_BUS_REPLY_ACCEPTED, what);
}
