/* Tests for src/core/posegraph.c: a loop's drift taken back by one match, a wrong match
 * dropped, a wrong match weighed down by the kernel, wrong matches under the kernel
 * dropped at once, a match weighed down pulls less, steps given either way round, pose 0
 * held, a consistent graph left alone, headings of the poses' own, bad calls refused; a
 * refit solved on the kept factorization (a match added; the first pose forgotten) as a
 * fresh workspace's fit solves it. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>

#include "houghloc-internal/posegraph.h"

#define N 12                /* poses around a loop */
#define PI 3.14159265358979323846
#define SIGMA_MM 50.0
#define SIGMA_RAD (1.5 * PI / 180)

/* The true poses: a 12-gon of 1 m sides, each pose facing along its side. */
static void truth(hl_pg_pose_t *p)
{
    p[0] = (hl_pg_pose_t){ 0, 0, 0 };
    for (int i = 1; i < N; i++)
        p[i] = hl_pg_compose(p[i - 1], (hl_pg_pose_t){ 1000, 0, 2 * PI / N });
}

/* Steps measured with a heading bias of @p bias_rad each (drift), and the poses they
 * chain to. */
static uint32_t drifting_chain(const hl_pg_pose_t *t, double bias_rad, hl_pg_pose_t *poses,
                               hl_pg_edge_t *edges)
{
    poses[0] = t[0];
    for (int i = 1; i < N; i++) {
        hl_pg_pose_t rel = hl_pg_between(t[i - 1], t[i]);
        rel.theta += bias_rad;
        edges[i - 1] = (hl_pg_edge_t){ (uint32_t)i - 1, (uint32_t)i, rel, false };
        poses[i] = hl_pg_compose(poses[i - 1], rel);
    }
    return N - 1;
}

/* The fit of the loop's N poses, no heading of their own. */
static uint32_t fit(hl_posegraph_t *g, hl_pg_pose_t *poses, hl_pg_edge_t *edges, uint32_t *n,
                    double kernel, double gate)
{
    return hl_posegraph_fit(g, poses, N, edges, n, NULL, 0, SIGMA_MM, SIGMA_RAD, kernel, gate);
}

static double worst_mm(const hl_pg_pose_t *a, const hl_pg_pose_t *b)
{
    double w = 0;
    for (int i = 0; i < N; i++)
        w = fmax(w, hypot(a[i].x - b[i].x, a[i].y - b[i].y));
    return w;
}

static void copy(hl_pg_pose_t *to, const hl_pg_pose_t *from)
{
    for (int i = 0; i < N; i++)
        to[i] = from[i];
}

static void test_one_match_takes_back_a_loops_drift(void **state)
{
    (void)state;
    hl_pg_pose_t t[N], poses[N];
    hl_pg_edge_t edges[N + 2];
    truth(t);
    uint32_t n = drifting_chain(t, 5.0 * PI / 180, poses, edges);
    double before = worst_mm(poses, t);
    assert_true(before > 1000);     /* 5 degrees a step: more than a metre off by the end */
    /* The last pose seen again from the first, as it truly lies. */
    edges[n++] = (hl_pg_edge_t){ 0, N - 1, hl_pg_between(t[0], t[N - 1]), true };
    hl_posegraph_t *g = hl_posegraph_create(N, N + 2);
    assert_non_null(g);
    assert_int_equal(fit(g, poses, edges, &n, 0.0, 3.0), 0);
    assert_int_equal(n, N);
    /* The 55 degrees of bias spread over the loop's 12 edges: every pose within a
     * fraction of what it was off, the last one's heading a twelfth of it. */
    assert_true(worst_mm(poses, t) < before / 4);
    double turn = fabs(remainder(poses[N - 1].theta - t[N - 1].theta, 2 * PI));
    assert_true(turn > 4.0 * PI / 180 && turn < 5.2 * PI / 180);
    hl_posegraph_destroy(g);
}

/* A match weighed at a tenth of a step pulls the loop's end back less: the same loop as
 * above, the last pose's heading error after the fit larger than with the match at full
 * weight, the steps' share of the bias smaller. Weights out of (0, 1] are refused. */
static void test_a_match_weighed_down_pulls_less(void **state)
{
    (void)state;
    hl_pg_pose_t t[N], full[N], tenth[N];
    hl_pg_edge_t edges[N + 2];
    truth(t);
    double end_off[2];
    hl_pg_pose_t *poses[2] = { full, tenth };
    for (int k = 0; k < 2; k++) {
        uint32_t n = drifting_chain(t, 5.0 * PI / 180, poses[k], edges);
        edges[n++] = (hl_pg_edge_t){ 0, N - 1, hl_pg_between(t[0], t[N - 1]), true };
        hl_posegraph_t *g = hl_posegraph_create(N, N + 2);
        assert_non_null(g);
        assert_true(hl_posegraph_weigh_matches(g, k ? 0.1 : 1.0));
        assert_int_equal(fit(g, poses[k], edges, &n, 0.0, 100.0), 0);
        end_off[k] = hypot(poses[k][N - 1].x - t[N - 1].x, poses[k][N - 1].y - t[N - 1].y);
        assert_false(hl_posegraph_weigh_matches(g, 0));
        assert_false(hl_posegraph_weigh_matches(g, 1.5));
        assert_false(hl_posegraph_weigh_matches(g, NAN));
        assert_false(hl_posegraph_weigh_matches(NULL, 0.5));
        hl_posegraph_destroy(g);
    }
    /* Full weight: the end within 9 mm of its truth; a tenth: 288 mm, the steps keeping
     * more of their bias (the chain alone ends more than a metre off). */
    assert_true(end_off[0] < 20);
    assert_true(end_off[1] > 200 && end_off[1] < 400);
}

static void test_a_wrong_match_is_dropped(void **state)
{
    (void)state;
    hl_pg_pose_t t[N], poses[N], clean[N];
    hl_pg_edge_t edges[N + 2];
    truth(t);
    uint32_t n = drifting_chain(t, 0.5 * PI / 180, poses, edges);
    edges[n++] = (hl_pg_edge_t){ 0, N - 1, hl_pg_between(t[0], t[N - 1]), true };
    copy(clean, poses);
    hl_pg_edge_t clean_edges[N + 2];
    for (uint32_t k = 0; k < n; k++)
        clean_edges[k] = edges[k];
    uint32_t n_clean = n;
    /* A match 3 m and 40 degrees off what the others say. */
    hl_pg_pose_t wrong = hl_pg_between(t[2], t[8]);
    wrong.x += 3000;
    wrong.theta += 40 * PI / 180;
    edges[n++] = (hl_pg_edge_t){ 2, 8, wrong, true };
    hl_posegraph_t *g = hl_posegraph_create(N, N + 2);
    assert_int_equal(fit(g, poses, edges, &n, 0.0, 3.0), 1);
    assert_int_equal(n, N);                       /* the wrong one gone, the order kept */
    assert_int_equal(edges[N - 1].from, 0);
    assert_int_equal(edges[N - 1].to, N - 1);
    assert_int_equal(fit(g, clean, clean_edges, &n_clean, 0.0, 3.0), 0);
    assert_true(worst_mm(poses, clean) < 1.0);    /* as if it had never been there */
    hl_posegraph_destroy(g);
}

static void test_pose_zero_is_held_and_a_consistent_graph_stays(void **state)
{
    (void)state;
    hl_pg_pose_t t[N], poses[N];
    hl_pg_edge_t edges[N + 2];
    truth(t);
    uint32_t n = drifting_chain(t, 0.0, poses, edges);
    edges[n++] = (hl_pg_edge_t){ 3, 9, hl_pg_between(t[3], t[9]), true };
    hl_posegraph_t *g = hl_posegraph_create(N, N + 2);
    assert_int_equal(fit(g, poses, edges, &n, 0.0, 3.0), 0);
    assert_true(worst_mm(poses, t) < 0.01);
    /* Moved away as a whole, the graph is fitted back to pose 0, which stays. */
    for (int i = 0; i < N; i++)
        poses[i].x += (i == 0) ? 0 : 500;
    fit(g, poses, edges, &n, 0.0, 3.0);
    assert_true(poses[0].x == t[0].x && poses[0].y == t[0].y && poses[0].theta == t[0].theta);
    assert_true(worst_mm(poses, t) < 0.01);
    hl_posegraph_destroy(g);
}

static void test_a_kernel_weighs_a_wrong_match_down(void **state)
{
    (void)state;
    hl_pg_pose_t t[N], start[N], clean[N], plain[N], robust[N];
    hl_pg_edge_t edges[N + 2];
    truth(t);
    uint32_t n = drifting_chain(t, 0.5 * PI / 180, start, edges);
    edges[n++] = (hl_pg_edge_t){ 0, N - 1, hl_pg_between(t[0], t[N - 1]), true };
    hl_posegraph_t *g = hl_posegraph_create(N, N + 2);
    const double never = 1e9;    /* no edge dropped: the kernel alone */
    copy(clean, start);
    uint32_t m = n;
    assert_int_equal(fit(g, clean, edges, &m, 0.0, never), 0);
    /* A match 400 mm and 6 degrees off what the others say. */
    hl_pg_pose_t wrong = hl_pg_between(t[2], t[8]);
    wrong.x += 400;
    wrong.theta += 6 * PI / 180;
    edges[n++] = (hl_pg_edge_t){ 2, 8, wrong, true };
    copy(plain, start);
    m = n;
    assert_int_equal(fit(g, plain, edges, &m, 0.0, never), 0);
    copy(robust, start);
    assert_int_equal(fit(g, robust, edges, &m, 1.0, never), 0);
    assert_int_equal(m, n);
    /* Plain least squares bends every pose towards it; the kernel keeps the fit within a
     * fraction of that of the fit without it. */
    double bent = worst_mm(plain, clean);
    assert_true(bent > 100);
    assert_true(worst_mm(robust, clean) < bent / 4);
    hl_posegraph_destroy(g);
}

static void test_wrong_matches_under_the_kernel_go_at_once(void **state)
{
    (void)state;
    hl_pg_pose_t t[N], poses[N], clean[N];
    hl_pg_edge_t edges[N + 8], clean_edges[N + 8];
    truth(t);
    uint32_t n = drifting_chain(t, 0.5 * PI / 180, poses, edges);
    for (uint32_t i = 0; i + 6 < N; i++)     /* right matches across the loop */
        edges[n++] = (hl_pg_edge_t){ i, i + 6, hl_pg_between(t[i], t[i + 6]), true };
    copy(clean, poses);
    uint32_t n_clean = n;
    for (uint32_t k = 0; k < n; k++)
        clean_edges[k] = edges[k];
    /* Two matches 3 m and 40 degrees off what the others say, one before the right ones. */
    hl_pg_pose_t wrong = hl_pg_between(t[2], t[9]);
    wrong.x += 3000;
    wrong.theta += 40 * PI / 180;
    for (uint32_t k = n; k > N - 1; k--)
        edges[k] = edges[k - 1];
    edges[N - 1] = (hl_pg_edge_t){ 2, 9, wrong, true };
    n++;
    wrong = hl_pg_between(t[1], t[10]);
    wrong.y -= 3000;
    wrong.theta -= 40 * PI / 180;
    edges[n++] = (hl_pg_edge_t){ 1, 10, wrong, true };
    hl_posegraph_t *g = hl_posegraph_create(N, N + 8);
    assert_int_equal(fit(g, poses, edges, &n, 1.0, 3.0), 2);
    assert_int_equal(n, n_clean);              /* both gone, the right ones in order */
    for (uint32_t k = 0; k < n; k++) {
        assert_int_equal(edges[k].from, clean_edges[k].from);
        assert_int_equal(edges[k].to, clean_edges[k].to);
    }
    assert_int_equal(fit(g, clean, clean_edges, &n_clean, 1.0, 3.0), 0);
    assert_true(worst_mm(poses, clean) < 5.0);  /* as if they had never been there */
    assert_true(worst_mm(poses, t) < 50.0);
    hl_posegraph_destroy(g);
}

/* A step may be measured from the later pose to the earlier one: the fit (and its
 * preconditioner, built from the steps between consecutive poses) takes either way. */
static void test_steps_either_way_round_fit_alike(void **state)
{
    (void)state;
    hl_pg_pose_t t[N], drifted[N], forward[N], backward[N];
    hl_pg_edge_t edges[N + 2], reversed[N + 2];
    truth(t);
    drifting_chain(t, 3.0 * PI / 180, drifted, edges);      /* a start far from the fit */
    uint32_t n = drifting_chain(t, 0.0, forward, edges);     /* steps as they truly are */
    edges[n++] = (hl_pg_edge_t){ 0, N - 1, hl_pg_between(t[0], t[N - 1]), true };
    for (uint32_t k = 0; k < n; k++) {
        hl_pg_pose_t a = { 0, 0, 0 }, b = hl_pg_compose(a, edges[k].rel);
        reversed[k] = edges[k].loop ? edges[k]
                                    : (hl_pg_edge_t){ edges[k].to, edges[k].from,
                                                      hl_pg_between(b, a), false };
    }
    copy(forward, drifted);
    copy(backward, drifted);
    hl_posegraph_t *g = hl_posegraph_create(N, N + 2);
    uint32_t m = n;
    assert_int_equal(fit(g, forward, edges, &m, 0.0, 3.0), 0);
    m = n;
    assert_int_equal(fit(g, backward, reversed, &m, 0.0, 3.0), 0);
    assert_true(worst_mm(drifted, t) > 1000);
    assert_true(worst_mm(forward, t) < 0.01);
    assert_true(worst_mm(backward, t) < 0.01);
    hl_posegraph_destroy(g);
}

/* A chain whose every step turns a little too far, as a map turns about its first pose:
 * headings of its own, measured against the world, turn it back (closure.h, "Square
 * walls"); a weak one 20 degrees off (a stop that saw mostly clutter) moves little. */
static void test_headings_of_their_own_turn_a_chain_back(void **state)
{
    (void)state;
    hl_pg_pose_t t[N], poses[N], plain[N];
    hl_pg_edge_t edges[N + 2];
    hl_pg_heading_t headings[N];
    truth(t);
    uint32_t n = drifting_chain(t, 1.0 * PI / 180, poses, edges), m = n;
    copy(plain, poses);
    hl_posegraph_t *g = hl_posegraph_create(N, N + 2);
    assert_non_null(g);
    assert_int_equal(fit(g, plain, edges, &m, 1.0, 3.0), 0);
    /* Steps alone: nothing to take the drift back, the last pose 11 degrees turned. */
    assert_true(fabs(remainder(plain[N - 1].theta - t[N - 1].theta, 2 * PI)) > 10.5 * PI / 180);
    for (uint32_t i = 1; i < N; i++)
        headings[i - 1] = (hl_pg_heading_t){ i, t[i].theta, 1.0 * PI / 180 };
    headings[4].theta += 20 * PI / 180;
    headings[4].sigma_rad = 7.5 * PI / 180;
    assert_int_equal(hl_posegraph_fit(g, poses, N, edges, &n, headings, N - 1, SIGMA_MM,
                                      SIGMA_RAD, 1.0, 3.0), 0);
    double worst_turn = 0;
    for (int i = 0; i < N; i++)
        worst_turn = fmax(worst_turn, fabs(remainder(poses[i].theta - t[i].theta, 2 * PI)));
    assert_true(worst_turn < 1.5 * PI / 180);
    assert_true(worst_mm(poses, t) < worst_mm(plain, t) / 4);
    /* A heading naming no pose, with no spread or no number, or none at all, is refused:
     * nothing moves. */
    copy(plain, poses);
    headings[0].pose = N;
    assert_int_equal(hl_posegraph_fit(g, poses, N, edges, &n, headings, N - 1, SIGMA_MM,
                                      SIGMA_RAD, 1.0, 3.0), 0);
    headings[0].pose = 1;
    headings[1].sigma_rad = 0;
    assert_int_equal(hl_posegraph_fit(g, poses, N, edges, &n, headings, N - 1, SIGMA_MM,
                                      SIGMA_RAD, 1.0, 3.0), 0);
    headings[1].sigma_rad = 1.0 * PI / 180;
    headings[2].theta = NAN;
    assert_int_equal(hl_posegraph_fit(g, poses, N, edges, &n, headings, N - 1, SIGMA_MM,
                                      SIGMA_RAD, 1.0, 3.0), 0);
    assert_int_equal(hl_posegraph_fit(g, poses, N, edges, &n, NULL, 1, SIGMA_MM, SIGMA_RAD,
                                      1.0, 3.0), 0);
    assert_true(worst_mm(poses, plain) == 0);
    hl_posegraph_destroy(g);
}

static void test_bad_calls_change_nothing(void **state)
{
    (void)state;
    hl_pg_pose_t t[N], poses[N];
    hl_pg_edge_t edges[N + 2];
    truth(t);
    uint32_t n = drifting_chain(t, 0.1, poses, edges);
    hl_posegraph_t *g = hl_posegraph_create(4, N + 2);     /* too few poses */
    assert_int_equal(fit(g, poses, edges, &n, 0.0, 3.0), 0);
    assert_int_equal(n, N - 1);
    assert_true(worst_mm(poses, t) > 1000);               /* not fitted */
    assert_int_equal(fit(NULL, poses, edges, &n, 0.0, 3.0), 0);
    hl_posegraph_destroy(g);
    g = hl_posegraph_create(N, N + 2);
    assert_int_equal(fit(g, poses, edges, &n, -1.0, 3.0), 0);
    assert_int_equal(fit(g, poses, edges, &n, NAN, 3.0), 0);
    assert_true(worst_mm(poses, t) > 1000);               /* a bad kernel: not fitted */
    assert_int_equal(hl_posegraph_fit(g, poses, N, edges, &n, NULL, 0, 0.0, SIGMA_RAD, 1.0, 3.0), 0);
    assert_int_equal(hl_posegraph_fit(g, poses, N, edges, &n, NULL, 0, SIGMA_MM, NAN, 1.0, 3.0), 0);
    assert_true(worst_mm(poses, t) > 1000);               /* a bad sigma: not fitted */
    hl_posegraph_destroy(g);
    hl_posegraph_destroy(NULL);
}

/* A fit of @p n_poses poses on a fresh workspace, for comparison. */
static void fresh_fit(hl_pg_pose_t *poses, uint32_t n_poses, hl_pg_edge_t *edges, uint32_t n)
{
    hl_posegraph_t *g = hl_posegraph_create(N, N + 4);
    assert_non_null(g);
    hl_posegraph_fit(g, poses, n_poses, edges, &n, NULL, 0, SIGMA_MM, SIGMA_RAD, 1.0, 3.0);
    hl_pg_work_t w = hl_posegraph_work(g);
    assert_int_equal(w.factorizations > 0, 1);
    hl_posegraph_destroy(g);
}

/* The next fit after a small change (a match added; then the first pose forgotten, as a
 * full record forgets its oldest) is solved by conjugate gradients on the factorization
 * kept from the fit before, with no new one, and lands where a fresh workspace's fit of
 * the same graph from the same poses does. */
static void test_a_refit_solves_on_the_kept_factorization(void **state)
{
    (void)state;
    hl_pg_pose_t t[N], poses[N], fresh[N];
    hl_pg_edge_t edges[N + 4], copy_edges[N + 4];
    truth(t);
    uint32_t n = drifting_chain(t, 0.05 * PI / 180, poses, edges);
    edges[n++] = (hl_pg_edge_t){ 0, N - 1, hl_pg_between(t[0], t[N - 1]), true };
    hl_posegraph_t *g = hl_posegraph_create(N, N + 4);
    assert_non_null(g);
    assert_int_equal(hl_posegraph_fit(g, poses, N, edges, &n, NULL, 0, SIGMA_MM, SIGMA_RAD,
                                      1.0, 3.0), 0);
    hl_pg_work_t before = hl_posegraph_work(g);
    assert_true(before.factorizations > 0);
    /* A match across the loop, a little off the fit. */
    hl_pg_pose_t rel = hl_pg_between(poses[3], poses[9]);
    rel.x += 10;
    edges[n++] = (hl_pg_edge_t){ 3, 9, rel, true };
    copy(fresh, poses);
    for (uint32_t k = 0; k < n; k++)
        copy_edges[k] = edges[k];
    fresh_fit(fresh, N, copy_edges, n);
    assert_int_equal(hl_posegraph_fit(g, poses, N, edges, &n, NULL, 0, SIGMA_MM, SIGMA_RAD,
                                      1.0, 3.0), 0);
    hl_pg_work_t after = hl_posegraph_work(g);
    assert_true(after.steps > before.steps);
    assert_true(after.factorizations == before.factorizations);
    assert_true(after.pcg_solves == before.pcg_solves + (after.steps - before.steps));
    assert_true(worst_mm(poses, fresh) < 1e-3);
    assert_true(worst_mm(poses, t) > 1);     /* and it moved: the match was off */
    /* The first pose forgotten: its edges gone, the rest one down, the shift told. */
    uint32_t kept = 0;
    for (uint32_t k = 0; k < n; k++)
        if (edges[k].from > 0)
            edges[kept++] = (hl_pg_edge_t){ edges[k].from - 1, edges[k].to - 1, edges[k].rel,
                                            edges[k].loop };
    for (int i = 0; i + 1 < N; i++)
        poses[i] = poses[i + 1];
    poses[2].x += 5;            /* and one pose off, for the refit to take back */
    hl_posegraph_shift(g, 1);
    for (int i = 0; i + 1 < N; i++)
        fresh[i] = poses[i];
    for (uint32_t k = 0; k < kept; k++)
        copy_edges[k] = edges[k];
    fresh_fit(fresh, N - 1, copy_edges, kept);
    before = after;
    assert_int_equal(hl_posegraph_fit(g, poses, N - 1, edges, &kept, NULL, 0, SIGMA_MM,
                                      SIGMA_RAD, 1.0, 3.0), 0);
    after = hl_posegraph_work(g);
    assert_true(after.factorizations == before.factorizations);
    assert_true(after.pcg_solves > before.pcg_solves);
    double worst = 0;
    for (int i = 0; i + 1 < N; i++)
        worst = fmax(worst, hypot(poses[i].x - fresh[i].x, poses[i].y - fresh[i].y));
    assert_true(worst < 1e-3);
    hl_posegraph_destroy(g);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_one_match_takes_back_a_loops_drift),
        cmocka_unit_test(test_a_match_weighed_down_pulls_less),
        cmocka_unit_test(test_a_wrong_match_is_dropped),
        cmocka_unit_test(test_a_kernel_weighs_a_wrong_match_down),
        cmocka_unit_test(test_pose_zero_is_held_and_a_consistent_graph_stays),
        cmocka_unit_test(test_wrong_matches_under_the_kernel_go_at_once),
        cmocka_unit_test(test_steps_either_way_round_fit_alike),
        cmocka_unit_test(test_headings_of_their_own_turn_a_chain_back),
        cmocka_unit_test(test_bad_calls_change_nothing),
        cmocka_unit_test(test_a_refit_solves_on_the_kept_factorization),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
