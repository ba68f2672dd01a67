/* Tests for the configuration's presets and printouts (config.c, profiles.c, the robot
 * profiles of src/robot/profile.c): the sensor profiles' keys (the core's presets) and
 * their order against single keys, refusals naming the choices, robot.profile's
 * calibration under calibration.*, the operator's printout and its read-back, the
 * fragment of --print-profile, the advice for a map larger than the configuration, and
 * the daemon's defaults of the core's keys (the library's own). */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "config.h"
#include "config_keys.h"
#include "profiles.h"

typedef struct fixture {
    char path[64];
    hl_config_t a, b;
    char why[HL_CONFIG_WHY_LEN];
} fixture_t;

static int setup(void **state)
{
    fixture_t *f = calloc(1, sizeof *f);
    snprintf(f->path, sizeof f->path, "/tmp/hl-config-XXXXXX");
    int fd = mkstemp(f->path);
    if (fd < 0)
        return -1;
    close(fd);
    *state = f;
    return 0;
}

static int teardown(void **state)
{
    fixture_t *f = *state;
    unlink(f->path);
    free(f);
    return 0;
}

static void write_file(const char *path, const char *text)
{
    FILE *fp = fopen(path, "w");
    assert_non_null(fp);
    fputs(text, fp);
    fclose(fp);
}

/* What a printer writes, in a string the caller frees. */
static char *printed(const hl_config_t *c, void (*print)(const hl_config_t *, FILE *))
{
    char *buf = NULL;
    size_t len = 0;
    FILE *fp = open_memstream(&buf, &len);
    assert_non_null(fp);
    print(c, fp);
    fclose(fp);
    return buf;
}

/* The value of the core's @p key in @p c, as text (a static buffer). */
static const char *get(const hl_config_t *c, const char *key)
{
    static char v[64];
    assert_int_equal(hl_params_get(&c->params, key, v, sizeof v), HL_OK);
    return v;
}

static void load_ok(fixture_t *f, hl_config_t *c, const char *path, const char *set1,
                    const char *set2)
{
    const char *sets[2] = { set1, set2 };
    int n = set2 ? 2 : set1 ? 1 : 0;
    bool ok = hl_config_load(c, path, false, sets, n, f->why);
    if (!ok)
        fail_msg("%s", f->why);
}

/* The default profile sets nothing: the compiled-in defaults. */
static void test_sonar_stops_is_the_defaults(void **state)
{
    fixture_t *f = *state;
    hl_config_defaults(&f->a);
    assert_string_equal(get(&f->a, "slam.profile"), "sonar-stops");
    load_ok(f, &f->b, NULL, "slam.profile=sonar-stops", NULL);
    char *x = printed(&f->a, hl_config_print), *y = printed(&f->b, hl_config_print);
    assert_string_equal(x, y);
    free(x);
    free(y);
    assert_int_equal(hl_sensor_profile_find("sonar-stops")->count, 0);
}

/* The daemon's defaults of the core's keys are the library's: a configuration without a
 * key holds what hl_params_default does, key for key. */
static void test_defaults_are_the_librarys(void **state)
{
    fixture_t *f = *state;
    load_ok(f, &f->a, NULL, NULL, NULL);
    hl_params_t lib;
    hl_params_default(&lib);
    const hl_param_info_t *k;
    size_t n = 0;
    for (size_t i = 0; (k = hl_params_info(i)); i++) {
        char mine[64], theirs[64];
        assert_int_equal(hl_params_get(&f->a.params, k->key, mine, sizeof mine), HL_OK);
        assert_int_equal(hl_params_get(&lib, k->key, theirs, sizeof theirs), HL_OK);
        assert_string_equal(mine, theirs);
        assert_string_equal(mine, k->value);    /* and the table's default, as it writes it */
        n++;
    }
    assert_true(n > 40);
    assert_string_equal(get(&f->a, "slam.lost_after"), "2");     /* the LOST state on */
    assert_string_equal(get(&f->a, "slam.search_every"), "10");
}

/* laser: its keys, the realeval settings. */
static void test_laser_keys(void **state)
{
    fixture_t *f = *state;
    load_ok(f, &f->a, NULL, "slam.profile=laser", NULL);
    const hl_config_t *c = &f->a;
    assert_string_equal(get(c, "slam.map_capacity"), "15000");
    assert_string_equal(get(c, "slam.map_per_place"), "1");
    assert_string_equal(get(c, "slam.window_mm"), "500");
    assert_string_equal(get(c, "slam.echo_bearings"), "false");
    assert_string_equal(get(c, "slam.fit_normals"), "true");
    assert_string_equal(get(c, "normals.keep_unfitted"), "true");
    assert_string_equal(get(c, "localize.reading_stride"), "2");
    assert_string_equal(get(c, "localize.group_mm"), "48");
    assert_string_equal(get(c, "reloc.coarse_cell_mm"), "200");
    assert_string_equal(get(c, "reloc.coarse_max_cells"), "2097152");
    assert_string_equal(get(c, "slam.refine"), "true");     /* the defaults', untouched */
    assert_string_equal(get(c, "slam.lost_after"), "0");    /* LOST off */
    assert_int_equal(hl_sensor_profile_capacity(hl_sensor_profile_find("laser")), 15000);
}

/* The profile first wherever written, then single keys over it. */
static void test_order_profile_keys(void **state)
{
    fixture_t *f = *state;
    write_file(f->path, "[slam]\nmap_capacity = 800\nwindow_mm = 700\nprofile = laser\n");
    load_ok(f, &f->a, f->path, NULL, NULL);
    assert_string_equal(get(&f->a, "slam.profile"), "laser");
    assert_string_equal(get(&f->a, "slam.map_capacity"), "800");   /* the key over it */
    assert_string_equal(get(&f->a, "slam.window_mm"), "700");
    assert_string_equal(get(&f->a, "localize.group_mm"), "48");    /* the profile's */
    /* an override of the profile wins over the file's */
    load_ok(f, &f->b, f->path, "slam.profile=sonar-continuous", NULL);
    assert_string_equal(get(&f->b, "slam.profile"), "sonar-continuous");
    assert_string_equal(get(&f->b, "echo.half_beam_deg"), "11");
    assert_string_equal(get(&f->b, "localize.group_mm"), "0");
    assert_string_equal(get(&f->b, "slam.map_capacity"), "800");
    /* the paper's method is a profile too */
    load_ok(f, &f->b, NULL, "slam.profile=paper", "slam.window_mm=300");
    assert_string_equal(get(&f->b, "localize.cell_mm"), "47");
    assert_string_equal(get(&f->b, "slam.guarded"), "false");
    assert_string_equal(get(&f->b, "slam.window_mm"), "300");
}

/* Keys that are settings no more: their fixed value read with a warning, another refused
 * naming it; the [daemon] keys the tracker's table took over read under their new names. */
static void test_retired_keys(void **state)
{
    fixture_t *f = *state;
    write_file(f->path, "[slam]\nmode = improved\nwild_mm = 500\n[echo]\ntie = 0.50\n"
                        "[link]\npulse_ms = 500\n[daemon]\nlost_after = 0\n");
    load_ok(f, &f->a, f->path, NULL, NULL);
    assert_int_equal(f->a.n_notes, 5);
    assert_non_null(strstr(f->a.notes[0], ":2: key 'slam.mode' is no longer a setting "
                                          "(fixed at improved): ignored"));
    assert_non_null(strstr(f->a.notes[4], ":9: key 'daemon.lost_after' is now slam.lost_after"));
    assert_string_equal(get(&f->a, "slam.lost_after"), "0");
    write_file(f->path, "[echo]\ntie = 0.8\n");
    assert_false(hl_config_load(&f->a, f->path, false, NULL, 0, f->why));
    assert_non_null(strstr(f->why, ":2: key 'echo.tie': no longer a setting, fixed at 0.5"));
    const char *paper[1] = { "slam.mode=paper" };
    assert_false(hl_config_load(&f->a, NULL, false, paper, 1, f->why));
    assert_string_equal(f->why, "--set slam.mode=paper: no longer a setting, fixed at improved "
                                "(the paper's method is slam.profile = paper)");
    const char *link[1] = { "link.sync_tries=3" };
    assert_false(hl_config_load(&f->a, NULL, false, link, 1, f->why));
    assert_string_equal(f->why, "--set link.sync_tries=3: no longer a setting, fixed at 6");
    /* a study's key is the library's, not houghlocd's */
    const char *study[1] = { "reloc.max_ratio=0.4" };
    assert_false(hl_config_load(&f->a, NULL, false, study, 1, f->why));
    assert_non_null(strstr(f->why, "not of houghlocd"));
}

static void test_unknown_profile_refused(void **state)
{
    fixture_t *f = *state;
    const char *sets[1] = { "slam.profile=sonar" };
    assert_false(hl_config_load(&f->a, NULL, false, sets, 1, f->why));
    assert_string_equal(f->why, "--set slam.profile=sonar: 'sonar' is not one of "
                                "sonar-stops, sonar-continuous, laser or paper");
    write_file(f->path, "[slam]\n\nprofile = lidar\n");
    assert_false(hl_config_load(&f->a, f->path, false, NULL, 0, f->why));
    assert_non_null(strstr(f->why, ":3: key 'slam.profile': 'lidar' is not one of "
                                   "sonar-stops, sonar-continuous, laser or paper"));
}

/* robot.profile carries a calibration; calibration.* wins wherever it is written. */
static void test_robot_profile_calibration(void **state)
{
    fixture_t *f = *state;
    load_ok(f, &f->a, NULL, "robot.profile=houghloc-sim", NULL);
    assert_int_equal(f->a.sounder.calib.gain_q16, 70124);
    assert_int_equal(f->a.sounder.calib.offset_mm, -35);
    assert_int_equal(f->a.sounder.calib.min_raw, 200);
    write_file(f->path, "[calibration]\ngain_q16 = 66000\n[robot]\nprofile = houghloc-sim\n");
    load_ok(f, &f->b, f->path, NULL, NULL);
    assert_int_equal(f->b.sounder.calib.gain_q16, 66000);
    assert_int_equal(f->b.sounder.calib.offset_mm, -35);
    load_ok(f, &f->b, NULL, "robot.profile=pioneer3", NULL);
    assert_int_equal(f->b.sounder.calib.gain_q16, 65536);
    assert_int_equal(f->b.sounder.calib.offset_mm, 0);
    const char *sets[1] = { "robot.profile=sim" };
    assert_false(hl_config_load(&f->a, NULL, false, sets, 1, f->why));
    assert_non_null(strstr(f->why, "(bonnie, pioneer3 or houghloc-sim)"));
}

/* The operator's printout: exactly the operator's keys at the defaults, under 80 lines. */
static void test_operator_printout_of_the_defaults(void **state)
{
    fixture_t *f = *state;
    hl_config_defaults(&f->a);
    char *text = printed(&f->a, hl_config_print_operator);
    int lines = 0, keys = 0;
    for (const char *s = text; *s; s++)
        lines += *s == '\n';
    for (const char *s = text; s; s = strchr(s, '\n'), s = s ? s + 1 : NULL)
        keys += *s && *s != ';' && *s != '[' && *s != '\n';    /* "key = value" lines */
    for (size_t i = 0; i < hl_config_nkeys; i++) {
        const hl_config_key_t *k = &hl_config_keys[i];
        char line[80];
        snprintf(line, sizeof line, "\n%s = ", strchr(k->name, '.') + 1);
        if (k->type != HL_KEY_CORE && hl_config_key_for_operator(k))
            assert_non_null(strstr(text, line));
    }
    const hl_param_info_t *info;
    for (size_t i = 0; (info = hl_params_info(i)); i++) {
        char line[80];
        snprintf(line, sizeof line, "\n%s = ", strchr(info->key, '.') + 1);
        if (info->level == HL_PARAM_OPERATOR)
            assert_non_null(strstr(text, line));
        else if (info->level == HL_PARAM_EXPERT)
            assert_null(strstr(text, line));
    }
    assert_int_equal(keys, 25);
    assert_true(lines < 90);
    assert_null(strstr(text, "\nwindow_mm = "));
    assert_null(strstr(text, "\nmode = "));
    free(text);
}

/* A research knob set away from its preset's value shows, and the printout reads back
 * to the whole configuration. */
static void test_operator_printout_reads_back(void **state)
{
    fixture_t *f = *state;
    load_ok(f, &f->a, NULL, "slam.profile=laser", "slam.echo_bearings=true");
    char *text = printed(&f->a, hl_config_print_operator);
    assert_non_null(strstr(text, "\nprofile = laser\n"));
    assert_non_null(strstr(text, "\necho_bearings = true\n"));  /* the profile's is false */
    assert_null(strstr(text, "\nwindow_mm = "));                /* the profile's value */
    assert_non_null(strstr(text, "\nmap_capacity = 15000\n"));   /* an operator's key */
    write_file(f->path, text);
    load_ok(f, &f->b, f->path, NULL, NULL);
    char *x = printed(&f->a, hl_config_print), *y = printed(&f->b, hl_config_print);
    assert_string_equal(x, y);
    free(x);
    free(y);
    free(text);
    load_ok(f, &f->a, NULL, "slam.profile=paper", NULL);
    text = printed(&f->a, hl_config_print_operator);
    assert_non_null(strstr(text, "\nprofile = paper\n"));
    assert_null(strstr(text, "\nguarded = "));                 /* the profile's value */
    free(text);
}

/* Each profile's fragment, read as a file, sets what the key does. */
static void test_fragments_read_back(void **state)
{
    fixture_t *f = *state;
    const hl_param_preset_t *p;
    size_t n = 0;
    for (size_t i = 0; (p = hl_params_preset(i)); i++, n++) {
        FILE *fp = fopen(f->path, "w");
        assert_non_null(fp);
        hl_sensor_profile_print(p, fp);
        fclose(fp);
        char set[64];
        snprintf(set, sizeof set, "slam.profile=%s", p->name);
        load_ok(f, &f->a, NULL, set, NULL);
        load_ok(f, &f->b, f->path, set, NULL);
        char *x = printed(&f->a, hl_config_print), *y = printed(&f->b, hl_config_print);
        assert_string_equal(x, y);
        free(x);
        free(y);
        load_ok(f, &f->b, f->path, NULL, NULL);   /* the fragment alone */
        const hl_param_info_t *k;
        for (size_t j = 0; (k = hl_params_info(j)); j++) {
            char x1[64], y1[64];
            if (k->type == HL_PARAM_PRESET)
                continue;
            hl_params_get(&f->a.params, k->key, x1, sizeof x1);
            hl_params_get(&f->b.params, k->key, y1, sizeof y1);
            assert_string_equal(x1, y1);
        }
    }
    assert_int_equal(n, 4);
    assert_null(hl_sensor_profile_find("nope"));
}

static void test_capacity_advice(void **state)
{
    (void)state;
    char out[512];
    hl_capacity_advice("/x/map.hlmap", 15000, 1500, out, sizeof out);
    assert_string_equal(out, "/x/map.hlmap: holds 15000 vectors, more than slam.map_capacity "
                             "= 1500: raise it (--set slam.map_capacity=15000, or slam.profile "
                             "= sonar-continuous) or start afresh with --fresh-map (which moves this file "
                             "aside)");
    hl_capacity_advice("m", 20000, 15000, out, sizeof out);
    assert_non_null(strstr(out, "(--set slam.map_capacity=20000) or start afresh"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_sonar_stops_is_the_defaults, setup, teardown),
        cmocka_unit_test_setup_teardown(test_laser_keys, setup, teardown),
        cmocka_unit_test_setup_teardown(test_defaults_are_the_librarys, setup, teardown),
        cmocka_unit_test_setup_teardown(test_order_profile_keys, setup, teardown),
        cmocka_unit_test_setup_teardown(test_retired_keys, setup, teardown),
        cmocka_unit_test_setup_teardown(test_unknown_profile_refused, setup, teardown),
        cmocka_unit_test_setup_teardown(test_robot_profile_calibration, setup, teardown),
        cmocka_unit_test_setup_teardown(test_operator_printout_of_the_defaults, setup, teardown),
        cmocka_unit_test_setup_teardown(test_operator_printout_reads_back, setup, teardown),
        cmocka_unit_test_setup_teardown(test_fragments_read_back, setup, teardown),
        cmocka_unit_test_setup_teardown(test_capacity_advice, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
