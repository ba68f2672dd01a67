/* forge_req.c - the requests of the Commands trial (see forge_req.h). */
#include "forge_req.h"

#include <string.h>
#include <time.h>

static const char *const kind_names[FORGE_KINDS] = {
    "valid", "forged", "replayed", "stale", "unsigned", "out_of_fence",
};

const char *forge_kind_name(forge_kind_t k)
{
    return (unsigned)k < FORGE_KINDS ? kind_names[k] : "?";
}

bool forge_init(forge_t *f, const hl_auth_key_t *key, const char *prefix, uint64_t seed,
                double fence_m)
{
    memset(f, 0, sizeof *f);
    if (!hl_auth_init() || strlen(prefix) > HL_BUS_PREFIX_MAX)
        return false;
    memcpy(f->prefix, prefix, strlen(prefix) + 1);
    f->key = *key;
    for (int i = 0; i < HL_AUTH_KEY_BYTES; i++)
        f->wrong_key.bytes[i] = (uint8_t)(key->bytes[i] ^ 0x5a);
    hl_rng_seed(&f->rng, seed);
    f->fence_mm = (int32_t)(fence_m * 1000.0);
    return true;
}

static int64_t now_utime(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

/* A coordinate well inside the fence (half of it), or well outside (1.5 to 4 times). */
static int32_t inside(forge_t *f)
{
    return (int32_t)hl_rng_below(&f->rng, (uint32_t)f->fence_mm + 1) - f->fence_mm / 2;
}

static int32_t outside(forge_t *f)
{
    int32_t d = f->fence_mm * 3 / 2 + (int32_t)hl_rng_below(&f->rng, (uint32_t)f->fence_mm * 5 / 2);
    return hl_rng_below(&f->rng, 2) ? d : -d;
}

static void destination(forge_t *f, hl_bus_destination_t *d, int64_t seq, bool in_fence)
{
    *d = (hl_bus_destination_t){ .utime = now_utime(), .seq = seq,
                                 .x_mm = in_fence ? inside(f) : outside(f),
                                 .y_mm = in_fence ? inside(f) : inside(f),
                                 .has_heading = hl_rng_below(&f->rng, 2) != 0,
                                 .heading = (hl_bam_t)hl_rng_next(&f->rng) };
}

/* SET_POSE five times in six, SAVE the sixth (each SAVE writes the map file, and one
 * within 5 s of the last write waits for the 5 s: channels.md). */
static void command(forge_t *f, hl_bus_command_t *c, int64_t seq)
{
    bool save = hl_rng_below(&f->rng, 6) == 0;
    *c = (hl_bus_command_t){ .utime = now_utime(), .seq = seq,
                             .kind = save ? HL_BUS_COMMAND_SAVE : HL_BUS_COMMAND_SET_POSE };
    if (!save)
        c->pose = (hl_pose_t){ inside(f), inside(f), (hl_bam_t)hl_rng_next(&f->rng) };
}

static void encode(forge_req_t *r, const hl_bus_destination_t *d, const hl_bus_command_t *c)
{
    r->len = r->command ? hl_bus_encode_command(c, r->bytes, sizeof r->bytes)
                        : hl_bus_encode_destination(d, r->bytes, sizeof r->bytes);
}

/* A well-formed request with seq @p seq, signed with @p key (NULL: unsigned), then with
 * @p tamper applied to the signed message: 0 none, 1 flip a MAC bit, 2 change a field. */
static void build(forge_t *f, forge_req_t *r, int64_t seq, bool in_fence,
                  const hl_auth_key_t *key, int tamper)
{
    hl_bus_destination_t d;
    hl_bus_command_t c;
    r->seq = seq;
    if (r->command) {
        command(f, &c, seq);
        r->what = c.kind == HL_BUS_COMMAND_SAVE ? "SAVE" : "SET_POSE";
        r->waits_for_save = c.kind == HL_BUS_COMMAND_SAVE;
        if (key)
            hl_auth_sign_command(key, f->prefix, &c);
    } else {
        destination(f, &d, seq, in_fence);
        r->what = "destination";
        if (key)
            hl_auth_sign_destination(key, f->prefix, &d);
    }
    uint8_t *mac = r->command ? c.mac : d.mac;
    if (tamper == 1)
        mac[hl_rng_below(&f->rng, HL_BUS_MAC_BYTES)] ^= (uint8_t)(1u << hl_rng_below(&f->rng, 8));
    if (tamper == 2) {
        if (r->command)
            c.pose.theta ^= 1;      /* for SAVE too: the MAC covers every field */
        else
            d.y_mm += d.y_mm < 0 ? 1 : -1;
    }
    encode(r, &d, &c);
}

void forge_make(forge_t *f, forge_kind_t kind, forge_req_t *r)
{
    if ((kind == FORGE_REPLAYED && f->n_accepted == 0) || (kind == FORGE_STALE && f->last_seq < 2))
        kind = FORGE_VALID;
    memset(r, 0, sizeof *r);
    r->kind = kind;
    /* DESTINATION and COMMAND in turn for each kind; a fence is a destination's only */
    r->command = kind != FORGE_FENCE && (f->variant[kind] % 2) == 1;
    int v = f->variant[kind]++;
    int64_t fresh = f->last_seq + 1;
    switch (kind) {
    case FORGE_VALID:
        build(f, r, fresh, true, &f->key, 0);
        r->expect = r->command ? HL_BUS_REPLY_ACCEPTED : HL_BUS_REPLY_NO_ROBOT;
        break;
    case FORGE_FORGED: {
        /* each variant with a fresh seq, the very one the next valid request takes: a
         * refused MAC must not use it up */
        static const char *const variants[] = { "wrong key", "flipped MAC bit",
                                                "field changed after signing" };
        int which = (v / 2) % 3;    /* every variant on both channels */
        build(f, r, fresh, true, which == 0 ? &f->wrong_key : &f->key, which);
        r->what = variants[which];
        r->expect = HL_BUS_REPLY_REJECTED_AUTH;
        break;
    }
    case FORGE_REPLAYED:
        *r = f->accepted[hl_rng_below(&f->rng, (uint32_t)f->n_accepted)];
        r->kind = FORGE_REPLAYED;
        r->expect = HL_BUS_REPLY_REJECTED_REPLAY;
        break;
    case FORGE_STALE: {
        /* below the last accepted, by up to a second of the clock the seqs follow */
        uint32_t below = f->last_seq - 1 > 1000000 ? 1000000u : (uint32_t)(f->last_seq - 1);
        build(f, r, f->last_seq - 1 - (int64_t)hl_rng_below(&f->rng, below), true, &f->key, 0);
        r->expect = HL_BUS_REPLY_REJECTED_REPLAY;
        break;
    }
    case FORGE_UNSIGNED:
        build(f, r, fresh, true, NULL, 0);
        r->expect = HL_BUS_REPLY_REJECTED_AUTH;
        break;
    default:    /* FORGE_FENCE */
        build(f, r, fresh, false, &f->key, 0);
        r->expect = HL_BUS_REPLY_REJECTED_FENCE;
        break;
    }
}

void forge_answered(forge_t *f, const forge_req_t *r, int8_t result)
{
    /* past the MAC and the freshness check the daemon has taken the seq */
    if (result != HL_BUS_REPLY_REJECTED_AUTH && result != HL_BUS_REPLY_REJECTED_REPLAY &&
        r->seq > f->last_seq)
        f->last_seq = r->seq;
    bool took = result == HL_BUS_REPLY_ACCEPTED || result == HL_BUS_REPLY_NO_ROBOT;
    if (r->kind == FORGE_VALID && took && f->n_accepted < FORGE_ACCEPTED_MAX)
        f->accepted[f->n_accepted++] = *r;
}
