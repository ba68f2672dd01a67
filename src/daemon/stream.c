/* stream.c - the order of one sensor stream from the network (stream.h). */
#include "stream.h"

void hl_stream_init(hl_stream_t *s, bool has_seq)
{
    *s = (hl_stream_t){ .has_seq = has_seq };
}

/* b - a when b is after a, at most @p max; else -1. Unsigned, so that values at the ends
 * of the int64 range (a forged utime of 2^63 - 1) cannot overflow. */
static int64_t step_after(int64_t a, int64_t b, int64_t max)
{
    if (b <= a)
        return -1;
    uint64_t d = (uint64_t)b - (uint64_t)a;
    return d <= (uint64_t)max ? (int64_t)d : -1;
}

bool hl_stream_follows(const hl_stream_t *s, hl_stream_mark_t a, hl_stream_mark_t b)
{
    if (step_after(a.utime, b.utime, HL_STREAM_MAX_TIME_STEP_US) < 0)
        return false;
    return !s->has_seq || step_after(a.seq, b.seq, HL_STREAM_MAX_SEQ_STEP) >= 0;
}

static void take(hl_stream_t *s, hl_stream_mark_t m)
{
    s->started = true;
    s->last = m;
    s->candidate_len = 0;
}

hl_stream_verdict_t hl_stream_offer(hl_stream_t *s, hl_stream_mark_t m)
{
    if (!s->started || hl_stream_follows(s, s->last, m)) {
        take(s, m);
        return HL_STREAM_TAKE;
    }
    if (s->candidate_len > 0 && hl_stream_follows(s, s->candidate, m))
        s->candidate_len++;
    else
        s->candidate_len = 1;   /* a run starts with this message */
    s->candidate = m;
    if (s->candidate_len < HL_STREAM_CONFIRM)
        return HL_STREAM_HOLD;
    take(s, m);
    return HL_STREAM_RESYNC;
}
