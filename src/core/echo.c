/* echo.c - estimating each reading's echo bearing within its beam (see echo.h). */
#include "houghloc-internal/echo.h"

#include <stddef.h>
#include <stdlib.h>

#include "houghloc-internal/flank.h"
#include "houghloc-internal/params.h"
#include "valid_scan.h"

void hl_echo_params_default(hl_echo_params_t *p)
{
    p->step = hl_bam_from_deg(HL_ECHO_STEP_DEG);
    p->noise_mm = HL_ECHO_NOISE_MM;
    p->noise_permille = HL_ECHO_NOISE_PERMILLE;
    p->cap_q8 = (uint16_t)(HL_ECHO_CAP * 256);
    p->tie_q8 = (uint16_t)(HL_ECHO_TIE * 256);
    /* the half beam and flank normals: echo.* (params_table.c) */
    hl_params_fill_defaults(p, offsetof(hl_slam_params_t, echo), sizeof *p);
}

static uint32_t candidates(const hl_echo_params_t *p)
{
    return 2u * p->half_beam / p->step + 1;
}

const char *hl_echo_params_error(const hl_echo_params_t *p)
{
    if (!p)
        return "no echo parameters";
    if (p->half_beam < hl_bam_from_deg(1.0) || p->half_beam > hl_bam_from_deg(45.0))
        return "echo half_beam must be in 1..45 degrees";
    if (p->step < 1 || candidates(p) > HL_ECHO_MAX_CANDIDATES)
        return "echo step must be positive and give at most 257 candidate bearings";
    if (p->noise_mm < 1)
        return "echo noise_mm must be at least 1";
    return NULL;
}

/* Valid readings' indices in bearing order: key = bearing << 16 | index. */
static int by_key(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

/* How strongly reading k, longer than r_i, contradicts an echo at r_i inside its cone:
 * ((r_k - r_i) / sigma_k)^2 / 2 in Q8, capped. */
static uint32_t contradiction(const hl_echo_params_t *p, int32_t r_i, int32_t r_k)
{
    int64_t excess = (int64_t)r_k - r_i;
    if (excess <= 0)
        return 0;
    int64_t sigma = p->noise_mm + (int64_t)r_k * p->noise_permille / 1000;
    int64_t q8 = excess * excess * 128 / (sigma * sigma);
    return q8 > p->cap_q8 ? p->cap_q8 : (uint32_t)q8;
}

/* Adds reading k's contradiction to the candidates its cone covers. Candidate s of
 * reading i lies at b_i - h + s * step; it is inside k's cone when
 * |b_i - h + s * step - b_k| <= h, i.e. d <= s * step <= d + 2h with d = b_k - b_i. */
static void add_neighbour(const hl_echo_params_t *p, int32_t d, uint32_t penalty,
                          uint32_t *score, int32_t n)
{
    int32_t lo = d <= 0 ? 0 : (d + p->step - 1) / p->step;
    int32_t top = d + 2 * (int32_t)p->half_beam;
    if (top < 0)
        return;
    int32_t hi = top / p->step;
    if (hi > n - 1)
        hi = n - 1;
    for (int32_t s = lo; s <= hi; s++)
        score[s] += penalty;
}

/* The least contradicted candidates: the first and last within tie_q8 of the best. */
static void least_contradicted(const hl_echo_params_t *p, const uint32_t *score, int32_t n,
                               int32_t *first, int32_t *last)
{
    uint32_t least = score[0];
    for (int32_t s = 1; s < n; s++)
        least = score[s] < least ? score[s] : least;
    *first = *last = -1;
    for (int32_t s = 0; s < n; s++) {
        if (score[s] <= least + p->tie_q8) {
            if (*first < 0)
                *first = s;
            *last = s;
        }
    }
}

/* The positions in @p order (valid readings by bearing) of reading a's neighbours within
 * @p reach BAM: first backwards round the ring, then forwards over the ones the backward
 * walk did not reach. @return how many. */
static uint32_t neighbours(const hl_scan_t *in, const uint32_t *order, uint32_t n, uint32_t a,
                           int32_t reach, uint32_t *out)
{
    hl_bam_t b = in->readings[order[a] & 0xFFFF].bearing;
    uint32_t m = 0, back = 0;
    for (uint32_t step = 1; step < n; step++, back++) {
        uint32_t k = (a + n - step) % n;
        int32_t d = hl_bam_diff(in->readings[order[k] & 0xFFFF].bearing, b);
        if (d > 0 || d < -reach)
            break;
        out[m++] = k;
    }
    for (uint32_t step = 1; step + back < n; step++) {
        uint32_t k = (a + step) % n;
        int32_t d = hl_bam_diff(in->readings[order[k] & 0xFFFF].bearing, b);
        if (d < 0 || d > reach)
            break;
        out[m++] = k;
    }
    return m;
}

static hl_status_t correct(const hl_echo_params_t *p, const hl_scan_t *in, bool check,
                           hl_scan_t *out);

hl_status_t hl_echo_correct(const hl_echo_params_t *p, const hl_scan_t *in, hl_scan_t *out)
{
    return correct(p, in, true, out);
}

hl_status_t hl_echo_correct_valid(const hl_echo_params_t *p, const hl_scan_t *in,
                                  hl_scan_t *out)
{
    return correct(p, in, false, out);
}

/* hl_echo_correct; the scan checked only when @p check. */
static hl_status_t correct(const hl_echo_params_t *p, const hl_scan_t *in, bool check,
                           hl_scan_t *out)
{
    if (!in || !out || in == out || hl_echo_params_error(p))
        return HL_ERR_ARG;
    if (check && hl_scan_check(in) != HL_OK)
        return HL_ERR_RANGE;
    uint32_t order[HL_SCAN_MAX_READINGS];
    uint32_t n = 0;
    for (uint32_t i = 0; i < in->count; i++)
        if (in->readings[i].valid)
            order[n++] = (uint32_t)in->readings[i].bearing << 16 | i;
    qsort(order, n, sizeof order[0], by_key);

    /* An isolated spike, longer than both its ring neighbours by more than three sigma,
     * is a bounced echo (the neighbours' cones overlap most of its own): it contradicts
     * nothing. */
    bool spike[HL_SCAN_MAX_READINGS] = { false };
    for (uint32_t a = 0; n >= 3 && a < n; a++) {
        int32_t r = in->readings[order[a] & 0xFFFF].range_mm;
        int32_t l = in->readings[order[(a + n - 1) % n] & 0xFFFF].range_mm;
        int32_t h = in->readings[order[(a + 1) % n] & 0xFFFF].range_mm;
        int32_t longest = l > h ? l : h;
        spike[a] = r - longest > 3 * (p->noise_mm + (int64_t)r * p->noise_permille / 1000);
    }

    *out = *in;
    const int32_t ncand = (int32_t)candidates(p), reach = 2 * (int32_t)p->half_beam;
    uint32_t score[HL_ECHO_MAX_CANDIDATES];
    uint32_t near[HL_SCAN_MAX_READINGS];
    for (uint32_t a = 0; a < n; a++) {
        const hl_reading_t *ri = &in->readings[order[a] & 0xFFFF];
        for (int32_t s = 0; s < ncand; s++)
            score[s] = 0;
        uint32_t m = neighbours(in, order, n, a, reach, near);
        for (uint32_t k = 0; k < m; k++) {
            const hl_reading_t *rk = &in->readings[order[near[k]] & 0xFFFF];
            if (!spike[near[k]])
                add_neighbour(p, hl_bam_diff(rk->bearing, ri->bearing),
                              contradiction(p, ri->range_mm, rk->range_mm), score, ncand);
        }
        int32_t first, last;
        least_contradicted(p, score, ncand, &first, &last);
        /* The middle of the least contradicted bearings. On a flank the echo is at the
         * span's outer edge, not its middle, but taking the edge when the span touches
         * one end of the cone did worse on noisy soundings (docs/results/experiments.md). */
        out->readings[order[a] & 0xFFFF].bearing =
            (hl_bam_t)(ri->bearing - p->half_beam + (first + last) * p->step / 2);
    }
    if (p->flank_normals)
        hl_flank_normals(p, in, order, n, out);
    return HL_OK;
}
