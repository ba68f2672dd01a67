/* Tests for the parameter table (params.c, params_table.c): every key reads back what it
 * was set to, at its default and at both ends of its range; values out of range, of the
 * wrong form and unknown keys are refused with one line naming the key; the profiles
 * apply over the defaults; fixed keys take their own value only; the rules over several
 * keys name them; and the stage modules' defaults are the table's. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "houghloc-internal/params.h"

/* The value of @p key in @p p (a static buffer). */
static const char *get(const hl_params_t *p, const char *key)
{
    static char v[64];
    assert_int_equal(hl_params_get(p, key, v, sizeof v), HL_OK);
    return v;
}

/* Sets @p key to @p value, which must read back as @p expect. */
static void round_trip(hl_params_t *p, const char *key, const char *value, const char *expect)
{
    if (hl_params_set(p, key, value) != HL_OK)
        fail_msg("%s = %s: %s", key, value, hl_params_error(p));
    assert_null(hl_params_error(p));
    assert_string_equal(get(p, key), expect);
}

/* A number as the table writes it: whole numbers without decimals. */
static void number_text(double v, char *buf, size_t cap)
{
    if (v == (double)(int64_t)v)
        snprintf(buf, cap, "%lld", (long long)v);
    else
        snprintf(buf, cap, "%.15g", v);
}

static void test_every_key_round_trips(void **state)
{
    (void)state;
    hl_params_t p;
    hl_params_default(&p);
    size_t keys = 0;
    for (size_t i = 0; i < hl_param_table_len; i++) {
        const hl_param_entry_t *e = &hl_param_table[i];
        const hl_param_info_t *k = hl_params_info(i);
        assert_ptr_equal(k, &e->info);
        assert_non_null(k->key);
        assert_non_null(strchr(k->key, '.'));
        assert_non_null(k->value);
        if (k->level == HL_PARAM_FIXED)
            continue;
        keys++;
        assert_non_null(k->help);
        assert_non_null(k->range);
        /* the default, as the table writes it, is what a new object holds */
        assert_string_equal(get(&p, k->key), k->value);
        round_trip(&p, k->key, k->value, k->value);
        if (k->type == HL_PARAM_BOOL) {
            round_trip(&p, k->key, "yes", "true");
            round_trip(&p, k->key, "0", "false");
        } else if (k->type != HL_PARAM_PRESET) {
            char lo[40], hi[40];
            number_text(e->min, lo, sizeof lo);
            number_text(e->max, hi, sizeof hi);
            round_trip(&p, k->key, lo, lo);
            round_trip(&p, k->key, hi, hi);
            if (e->zero_ok)
                round_trip(&p, k->key, "0", "0");
        }
        round_trip(&p, k->key, k->value, k->value);
    }
    assert_null(hl_params_info(hl_param_table_len));
    assert_true(keys >= 40);
    /* what the defaults set is the whole table's: a new object prints as this one */
    hl_params_t q;
    hl_params_default(&q);
    assert_memory_equal(hl_params_slam(&p), hl_params_slam(&q), sizeof(hl_slam_params_t));
}

/* A refusal: the status, the values unchanged, one line naming the key. */
static void refused(hl_params_t *p, const char *key, const char *value, hl_status_t st,
                    const char *why)
{
    hl_slam_params_t before = *hl_params_slam(p);
    assert_int_equal(hl_params_set(p, key, value), st);
    assert_memory_equal(&before, hl_params_slam(p), sizeof before);
    const char *e = hl_params_error(p);
    assert_non_null(e);
    assert_null(strchr(e, '\n'));
    assert_true(strlen(e) < HL_PARAMS_WHY_LEN - 1);
    if (!strstr(e, why))
        fail_msg("'%s' does not say '%s'", e, why);
}

static void test_ranges_enforced(void **state)
{
    (void)state;
    hl_params_t p;
    hl_params_default(&p);
    for (size_t i = 0; i < hl_param_table_len; i++) {
        const hl_param_entry_t *e = &hl_param_table[i];
        const hl_param_info_t *k = &e->info;
        char named[80], v[48];
        snprintf(named, sizeof named, "key '%s': ", k->key);
        if (k->level == HL_PARAM_FIXED || k->type == HL_PARAM_PRESET)
            continue;
        if (k->type == HL_PARAM_BOOL) {
            refused(&p, k->key, "maybe", HL_ERR_PARSE, named);
            continue;
        }
        refused(&p, k->key, "abc", HL_ERR_PARSE, named);
        refused(&p, k->key, "", HL_ERR_PARSE, "is not a number");
        refused(&p, k->key, "1e999", HL_ERR_PARSE, "is not a number");
        number_text(e->max + (e->max < 1000 ? 0.5 : e->max * 0.5), v, sizeof v);
        refused(&p, k->key, v, k->type == HL_PARAM_INT && e->max < 1000 ? HL_ERR_PARSE
                                                                           : HL_ERR_RANGE,
                named);
        number_text(e->max * 2 + 2, v, sizeof v);
        refused(&p, k->key, v, HL_ERR_RANGE, "is outside");
        number_text(e->min > 0 ? -e->min : -1, v, sizeof v);
        refused(&p, k->key, v, HL_ERR_RANGE, k->range);
        if (k->type == HL_PARAM_INT)
            refused(&p, k->key, "2.5", HL_ERR_PARSE, "is not a whole number");
    }
    refused(&p, "localize.cell_mm", "0", HL_ERR_RANGE, "key 'localize.cell_mm': 0 is outside 1..1000");
    refused(&p, "localize.group_mm", "4", HL_ERR_RANGE, "4 is outside 0 or 8..1000");
    round_trip(&p, "localize.group_mm", "0", "0");
    round_trip(&p, "localize.group_mm", "8", "8");
    refused(&p, "slam.window_mm", "1e3x", HL_ERR_PARSE, "is not a number");
    round_trip(&p, "slam.window_mm", "1e3 ", "1000");    /* trailing blanks are fine */
    refused(&p, "slam.nope", "1", HL_ERR_ARG, "unknown key 'slam.nope'");
    refused(&p, "window_mm", "1", HL_ERR_ARG, "unknown key 'window_mm'");
    assert_int_equal(hl_params_set(&p, NULL, "1"), HL_ERR_ARG);
    assert_int_equal(hl_params_set(&p, "slam.window_mm", NULL), HL_ERR_ARG);
    assert_int_equal(hl_params_set(NULL, "slam.window_mm", "1"), HL_ERR_ARG);
    char buf[8] = "x";
    assert_int_equal(hl_params_get(&p, "slam.nope", buf, sizeof buf), HL_ERR_ARG);
    assert_string_equal(buf, "");
    /* a success clears the line */
    round_trip(&p, "slam.window_mm", "900", "900");
    assert_null(hl_params_error(&p));
}

/* Each profile sets its settings over the defaults, whatever was set before. */
static void test_presets_apply(void **state)
{
    (void)state;
    const hl_param_preset_t *pr;
    size_t n = 0;
    for (size_t i = 0; (pr = hl_params_preset(i)); i++, n++) {
        hl_params_t p, fresh;
        hl_params_default(&p);
        hl_params_default(&fresh);
        round_trip(&p, "slam.map_capacity", "777", "777");
        round_trip(&p, "slam.profile", pr->name, pr->name);
        for (size_t k = 0; k < pr->count; k++) {
            const hl_param_setting_t *s = &pr->settings[k];
            assert_non_null(hl_param_find(s->key));
            assert_non_null(s->why);
            char want[64];      /* the setting as the table writes it */
            assert_int_equal(hl_params_set(&fresh, s->key, s->value), HL_OK);
            snprintf(want, sizeof want, "%s", get(&fresh, s->key));
            assert_string_equal(get(&p, s->key), want);
        }
        assert_int_equal(hl_params_check(&p), HL_OK);
        if (strcmp(get(&p, "slam.map_capacity"), "777") == 0)
            fail_msg("profile %s kept a key set before it", pr->name);
    }
    assert_int_equal(n, 4);
    assert_string_equal(hl_params_preset(0)->name, "sonar-stops");
    assert_int_equal(hl_params_preset(0)->count, 0);
    hl_params_t p;
    hl_params_default(&p);
    round_trip(&p, "slam.profile", "paper", "paper");
    assert_string_equal(get(&p, "localize.cell_mm"), "47");
    assert_string_equal(get(&p, "slam.guarded"), "false");
    assert_string_equal(get(&p, "slam.lost_after"), "0");
    assert_string_equal(get(&p, "slam.search_every"), "0");
    round_trip(&p, "slam.profile", "laser", "laser");
    assert_string_equal(get(&p, "localize.cell_mm"), "24");   /* the defaults under it */
    assert_string_equal(get(&p, "slam.map_capacity"), "15000");
    refused(&p, "slam.profile", "lidar", HL_ERR_PARSE,
            "key 'slam.profile': 'lidar' is not one of sonar-stops, sonar-continuous, laser "
            "or paper");
    assert_string_equal(get(&p, "slam.profile"), "laser");
}

static void test_fixed_keys(void **state)
{
    (void)state;
    hl_params_t p;
    hl_params_default(&p);
    size_t fixed = 0;
    for (size_t i = 0; i < hl_param_table_len; i++) {
        const hl_param_info_t *k = &hl_param_table[i].info;
        if (k->level != HL_PARAM_FIXED)
            continue;
        fixed++;
        hl_slam_params_t before = *hl_params_slam(&p);
        if (hl_params_set(&p, k->key, k->value) != HL_OK)
            fail_msg("%s = %s: %s", k->key, k->value, hl_params_error(&p));
        assert_memory_equal(&before, hl_params_slam(&p), sizeof before);
        assert_string_equal(get(&p, k->key), k->value);
        refused(&p, k->key, k->type == HL_PARAM_BOOL ? "false" : k->type == HL_PARAM_WORD
                                                                    ? "paper" : "7.25",
                k->type == HL_PARAM_INT ? HL_ERR_PARSE : HL_ERR_RANGE, k->key);
    }
    assert_true(fixed >= 30);
    refused(&p, "slam.wild_mm", "300", HL_ERR_RANGE,
            "key 'slam.wild_mm': no longer a setting, fixed at 500");
    round_trip(&p, "echo.tie", "0.50", "0.5");
    round_trip(&p, "localize.theta_step_deg", "1.1", "1.1");
    refused(&p, "slam.mode", "paper", HL_ERR_RANGE, "the paper's method is slam.profile = paper");
    /* the values the constants hold are the stage modules' */
    const hl_slam_params_t *s = hl_params_slam(&p);
    assert_int_equal(s->echo.tie_q8, 128);
    assert_int_equal(s->loc.theta_step, hl_bam_from_deg(1.1));
    assert_int_equal(s->reloc.fine_window_mm, 300);
    assert_int_equal(s->refine_params.min_matches, 12);
}

static void test_rules_name_their_keys(void **state)
{
    (void)state;
    hl_params_t p;
    hl_params_default(&p);
    assert_int_equal(hl_params_check(&p), HL_OK);
    assert_null(hl_params_error(&p));
    round_trip(&p, "localize.blur_sigma_mm", "300", "300");
    assert_int_equal(hl_params_check(&p), HL_ERR_RANGE);
    assert_string_equal(hl_params_error(&p), "localize.blur_sigma_mm (300) must be at most 10 "
                                             "x localize.cell_mm (24)");
    assert_null(hl_slam_create(&p));
    hl_params_default(&p);
    round_trip(&p, "localize.max_cells", "1000", "1000");
    assert_int_equal(hl_params_check(&p), HL_ERR_RANGE);
    assert_non_null(strstr(hl_params_error(&p), "slam.window_mm (1000) needs 119952 raster cells "
                                                "of localize.cell_mm (24) over 17 headings, "
                                                "more than localize.max_cells (1000)"));
    hl_params_default(&p);
    round_trip(&p, "slam.square_walls", "true", "true");
    assert_int_equal(hl_params_check(&p), HL_ERR_RANGE);
    assert_string_equal(hl_params_error(&p), "slam.square_walls (true) needs slam.close_loops "
                                             "(false) set to true");
    round_trip(&p, "slam.close_loops", "true", "true");
    assert_int_equal(hl_params_check(&p), HL_OK);
    hl_params_default(&p);
    round_trip(&p, "slam.crowd_square_mm", "300", "300");
    assert_int_equal(hl_params_check(&p), HL_ERR_RANGE);
    assert_non_null(strstr(hl_params_error(&p), "slam.crowd_square_mm (300)"));
    round_trip(&p, "slam.cull_crowded", "true", "true");
    assert_int_equal(hl_params_check(&p), HL_ERR_RANGE);
    assert_non_null(strstr(hl_params_error(&p), "slam.cull_choices (1)"));
    round_trip(&p, "slam.cull_choices", "8", "8");
    assert_int_equal(hl_params_check(&p), HL_ERR_RANGE);
    assert_non_null(strstr(hl_params_error(&p), "slam.map_per_place (0)"));
    round_trip(&p, "slam.map_per_place", "2", "2");
    assert_int_equal(hl_params_check(&p), HL_OK);
    hl_slam_t *s = hl_slam_create(&p);
    assert_non_null(s);
    hl_slam_destroy(s);
    /* a value put past its range from inside (the laboratory's hl_params_slam) */
    hl_params_slam(&p)->reloc.hypotheses = 0;
    assert_int_equal(hl_params_check(&p), HL_ERR_RANGE);
    assert_non_null(strstr(hl_params_error(&p), "slam parameters: reloc hypotheses"));
    assert_null(hl_slam_create(&p));
    assert_int_equal(hl_params_check(NULL), HL_ERR_ARG);
    assert_null(hl_slam_create(NULL));
}

/* What a program shows: the keys a program offers, each printed on one line of at most
 * 198 characters (houghlocd's reader) with its comment. */
static void test_offered_keys_print_on_one_line(void **state)
{
    (void)state;
    size_t offered = 0, operator_keys = 0;
    const hl_param_info_t *k;
    for (size_t i = 0; (k = hl_params_info(i)); i++) {
        if (k->level > HL_PARAM_EXPERT)
            continue;
        offered++;
        operator_keys += k->level == HL_PARAM_OPERATOR;
        assert_true(strlen(k->help) + 2 <= 198);
        assert_null(strchr(k->help, '\n'));
        assert_true(strlen(strchr(k->key, '.') + 1) + 3 + 20 <= 198);
    }
    assert_int_equal(operator_keys, 4);
    assert_true(offered <= 42);     /* few: every knob is one more thing to get wrong */
}

/* The stage modules' defaults are the table's. */
static void test_module_defaults_are_the_tables(void **state)
{
    (void)state;
    hl_params_t p;
    hl_params_default(&p);
    const hl_slam_params_t *s = hl_params_slam(&p);
    hl_loc_params_t loc;
    hl_reloc_params_t reloc;
    hl_echo_params_t echo;
    hl_normals_params_t normals;
    hl_map_params_t map, from_slam;
    memset(&echo, 0, sizeof echo);          /* padding, for the comparisons below */
    memset(&normals, 0, sizeof normals);
    hl_loc_params_default(&loc);
    hl_reloc_params_default(&reloc);
    hl_echo_params_default(&echo);
    hl_normals_params_default(&normals);
    hl_map_params_default(&map);
    hl_slam_map_params(s, &from_slam);
    assert_memory_equal(&loc, &s->loc, sizeof loc);
    assert_memory_equal(&reloc, &s->reloc, sizeof reloc);
    assert_memory_equal(&echo, &s->echo, sizeof echo);
    assert_memory_equal(&normals, &s->normals, sizeof normals);
    assert_int_equal(map.capacity, from_slam.capacity);
    assert_int_equal(map.seed, from_slam.seed);
    assert_int_equal(map.per_place, from_slam.per_place);
    assert_int_equal(map.square_mm, from_slam.square_mm);
    assert_int_equal(map.cull_choices, from_slam.cull_choices);
    assert_int_equal(map.confirm_mm, from_slam.confirm_mm);
    assert_int_equal(map.cull_crowded, from_slam.cull_crowded);
    assert_int_equal(map.crowd_square_mm, from_slam.crowd_square_mm);
    assert_int_equal(map.round_places, from_slam.round_places);
    assert_int_equal(loc.cell_mm, 24);
    assert_int_equal(map.capacity, 1500);
    assert_int_equal(map.confirm_mm, HL_MAP_CONFIRM_MM);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_key_round_trips),
        cmocka_unit_test(test_ranges_enforced),
        cmocka_unit_test(test_presets_apply),
        cmocka_unit_test(test_fixed_keys),
        cmocka_unit_test(test_rules_name_their_keys),
        cmocka_unit_test(test_offered_keys_print_on_one_line),
        cmocka_unit_test(test_module_defaults_are_the_tables),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
