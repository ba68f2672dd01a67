/* judge.c - how well a scan placed at a pose agrees with the map (see judge.h). */
#include "judge.h"

#include "houghloc-internal/fixed.h"

bool hl_judge_init(hl_judge_t *j, const hl_reloc_params_t *p, uint32_t capacity)
{
    j->p = *p;
    int32_t cell = p->verify_mm > p->verify_along_mm ? p->verify_mm : p->verify_along_mm;
    return hl_cellhash_init(&j->near, cell, capacity);
}

void hl_judge_free(hl_judge_t *j)
{
    hl_cellhash_free(&j->near);
}

size_t hl_judge_mem_bytes(const hl_judge_t *j)
{
    return hl_cellhash_mem_bytes(&j->near);
}

void hl_judge_build(hl_judge_t *j, const hl_vector_t *map, uint32_t n)
{
    hl_cellhash_build(&j->near, map, n);
}

/* Whether a map vector's surface passes within @p across mm of (wx, wy), at most @p along
 * mm along it from the vector, facing along @p normal within @p gate; looked for in the
 * 3 x 3 cells around it (cells are at least as large as both). */
static bool facing_near(const hl_judge_t *j, int64_t wx, int64_t wy, hl_bam_t normal,
                        int32_t gate, int32_t across, int32_t along)
{
    const hl_cellhash_t *g = &j->near;
    int32_t cx = hl_cellhash_cell(g, (double)wx), cy = hl_cellhash_cell(g, (double)wy);
    for (int ddy = -1; ddy <= 1; ddy++)
        for (int ddx = -1; ddx <= 1; ddx++) {
            uint32_t b = hl_cellhash_bucket(g, cx + ddx, cy + ddy);
            for (uint32_t e = g->start[b]; e < g->start[b + 1]; e++) {
                int32_t dn = hl_bam_diff(g->normal[e], normal);
                if ((dn < 0 ? -dn : dn) > gate)
                    continue;
                int64_t ex = wx - g->x[e], ey = wy - g->y[e];
                int32_t nx, ny;         /* the vector's unit normal, Q14 */
                hl_polar_to_xy(1 << 14, g->normal[e], &nx, &ny);
                int64_t d_across = (ex * nx + ey * ny) >> 14;
                int64_t d_along = (ey * nx - ex * ny) >> 14;
                if (d_across <= across && d_across >= -across && d_along <= along &&
                    d_along >= -along)
                    return true;
            }
        }
    return false;
}

/* Whether a map surface facing the sensor lies across the beam at @p pose's bearing @p a,
 * between @p from_mm and @p to_mm from the sensor; looked for every verify_mm. Any
 * surface facing the sensor's side stops a beam, whatever the judge's gate. */
static bool surface_on_beam(const hl_judge_t *j, hl_pose_t pose, hl_bam_t a, int32_t from_mm,
                            int32_t to_mm)
{
    int32_t step = j->p.verify_mm;
    hl_bam_t facing = (hl_bam_t)(a + HL_BAM_HALF_TURN);
    for (int32_t d = from_mm; d < to_mm; d += step) {
        int32_t dx, dy;
        hl_polar_to_xy(d, a, &dx, &dy);
        if (facing_near(j, (int64_t)pose.x_mm + dx, (int64_t)pose.y_mm + dy, facing,
                        HL_BAM_QUARTER_TURN, step / 2, j->p.verify_along_mm))
            return true;
    }
    return false;
}

/* Whether reading @p rd, not explained at @p pose (its beam along world bearing @p a),
 * contradicts the map: its beam passed
 * through a mapped surface (from 300 mm out to 300 mm short of the echo: it would have
 * echoed there), or, with short_mm, it stopped short of one lying within short_mm beyond
 * the echo (something the map does not hold stood in front of a surface it does: at a
 * wrong pose that is the common case, at the right one a person or a moved chair). */
static bool contradicts(const hl_judge_t *j, hl_pose_t pose, hl_bam_t a, const hl_reading_t *rd)
{
    const int32_t margin = 300;
    if (surface_on_beam(j, pose, a, margin, rd->range_mm - margin))
        return true;
    return j->p.short_mm > 0 &&
           surface_on_beam(j, pose, a, rd->range_mm + margin, rd->range_mm + j->p.short_mm);
}

uint32_t hl_judge_explained(const hl_judge_t *j, const hl_scan_t *scan, hl_pose_t pose,
                            int32_t tol_mm, uint32_t *contradicted, int8_t *verdict)
{
    uint32_t count = 0, against = 0;
    for (uint32_t i = 0; i < scan->count; i++) {
        const hl_reading_t *rd = &scan->readings[i];
        if (verdict)
            verdict[i] = 0;
        if (!rd->valid)
            continue;
        hl_bam_t a = (hl_bam_t)(pose.theta + rd->bearing);
        int32_t dx, dy;
        hl_polar_to_xy(rd->range_mm, a, &dx, &dy);
        if (facing_near(j, (int64_t)pose.x_mm + dx, (int64_t)pose.y_mm + dy,
                        hl_reading_normal(rd, pose.theta), j->p.judge_gate, tol_mm,
                        j->p.verify_along_mm)) {
            count++;
            if (verdict)
                verdict[i] = 1;
        } else if (contradicted && contradicts(j, pose, a, rd)) {
            against++;
            if (verdict)
                verdict[i] = -1;
        }
    }
    if (contradicted)
        *contradicted = against;
    return count;
}

uint32_t hl_judge_score(const hl_judge_t *j, const hl_scan_t *scan, hl_pose_t pose)
{
    uint32_t against, good = hl_judge_explained(j, scan, pose, j->p.verify_mm, &against, NULL);
    return good > against ? good - against : 0;
}

void hl_judge_edges(hl_judge_t *j, const hl_scan_t *scan, hl_pose_t a, hl_pose_t b,
                    uint32_t *edge, uint32_t *b_edge)
{
    uint32_t against;
    hl_judge_explained(j, scan, a, j->p.verify_mm, &against, j->verdict_a);
    hl_judge_explained(j, scan, b, j->p.verify_mm, &against, j->verdict_b);
    *edge = *b_edge = 0;
    for (uint32_t i = 0; i < scan->count; i++) {
        int32_t d = j->verdict_a[i] - j->verdict_b[i];
        if (d > 0)
            *edge += (uint32_t)d;
        else
            *b_edge += (uint32_t)-d;
    }
}
