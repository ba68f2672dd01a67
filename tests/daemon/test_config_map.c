/* Tests for the map file's default location (map_location.c) and for the refusal of a
 * map file larger than the configured map (mapstore.c's HL_ERR_CAPACITY tells how many
 * vectors it holds, so that the daemon can name the capacity to set). */
#include "mapstore_fixture.h"

#include "map_location.h"

static char *saved_env[4];
static const char *const env_names[4] = { "STATE_DIRECTORY", "XDG_STATE_HOME", "HOME", NULL };

static int save_env(void **state)
{
    for (int i = 0; env_names[i]; i++) {
        const char *v = getenv(env_names[i]);
        saved_env[i] = v ? strdup(v) : NULL;
    }
    return setup(state);
}

static int restore_env(void **state)
{
    for (int i = 0; env_names[i]; i++) {
        if (saved_env[i])
            setenv(env_names[i], saved_env[i], 1);
        else
            unsetenv(env_names[i]);
        free(saved_env[i]);
    }
    return teardown(state);
}

static bool system_dir_writable(void)
{
    return access(HL_MAP_SYSTEM_DIR, W_OK | X_OK) == 0;
}

static void test_state_directory_first(void **state)
{
    (void)state;
    char path[512], why[HL_MAP_LOCATION_WHY_LEN];
    const char *from = NULL;
    setenv("STATE_DIRECTORY", "/var/lib/private/houghloc:/other", 1);
    assert_true(hl_map_location_default(true, path, sizeof path, &from, why));
    assert_string_equal(path, "/var/lib/private/houghloc/map.hlmap");
    assert_string_equal(from, "$STATE_DIRECTORY");
}

/* A user's run: $XDG_STATE_HOME/houghloc, created 0700 (unless /var/lib/houghloc is
 * writable here, which then comes first). */
static void test_user_folder_created(void **state)
{
    fixture_t *f = *state;
    char path[512], want[512], xdg[160], why[HL_MAP_LOCATION_WHY_LEN];
    const char *from = NULL;
    unsetenv("STATE_DIRECTORY");
    snprintf(xdg, sizeof xdg, "%s/state", f->dir);
    setenv("XDG_STATE_HOME", xdg, 1);
    assert_true(hl_map_location_default(false, path, sizeof path, &from, why));
    if (system_dir_writable()) {
        assert_string_equal(path, HL_MAP_SYSTEM_DIR "/map.hlmap");
        return;
    }
    snprintf(want, sizeof want, "%s/houghloc/map.hlmap", xdg);
    assert_string_equal(path, want);
    struct stat st;
    assert_int_equal(stat(xdg, &st), -1);   /* a look creates nothing */
    assert_true(hl_map_location_default(true, path, sizeof path, &from, why));
    assert_string_equal(path, want);
    snprintf(want, sizeof want, "%s/houghloc", xdg);
    assert_int_equal(stat(want, &st), 0);
    assert_int_equal(st.st_mode & 0777, 0700);
    assert_int_equal(stat(xdg, &st), 0);
    assert_int_equal(st.st_mode & 0777, 0700);
    /* a relative $XDG_STATE_HOME is ignored for ~/.local/state */
    setenv("XDG_STATE_HOME", "relative", 1);
    setenv("HOME", f->dir, 1);
    assert_true(hl_map_location_default(true, path, sizeof path, &from, why));
    snprintf(want, sizeof want, "%s/.local/state/houghloc/map.hlmap", f->dir);
    assert_string_equal(path, want);
    snprintf(want, sizeof want, "%s/.local/state/houghloc", f->dir);
    char sub[512];
    snprintf(sub, sizeof sub, "rm -rf %s/.local %s/state", f->dir, f->dir);
    assert_int_equal(system(sub), 0);
}

/* Nowhere to go: the locations tried, and --map. */
static void test_nowhere(void **state)
{
    (void)state;
    if (system_dir_writable())
        skip();
    char path[512], why[HL_MAP_LOCATION_WHY_LEN];
    const char *from = NULL;
    unsetenv("STATE_DIRECTORY");
    setenv("XDG_STATE_HOME", "/proc/no-such-folder", 1);
    assert_false(hl_map_location_default(true, path, sizeof path, &from, why));
    assert_non_null(strstr(why, "tried " HL_MAP_SYSTEM_DIR " ("));
    assert_non_null(strstr(why, "/proc/no-such-folder/houghloc: "));
    assert_non_null(strstr(why, "give --map FILE"));
    unsetenv("XDG_STATE_HOME");
    unsetenv("HOME");
    assert_false(hl_map_location_default(true, path, sizeof path, &from, why));
    assert_non_null(strstr(why, "neither it nor $HOME"));
}

/* A map of more vectors than the configuration takes: refused, with the count. */
static void test_capacity_refusal_counts(void **state)
{
    fixture_t *f = *state;
    hl_mapfile_t m = sample(f->a, 7, 100), got;
    char why[HL_MAPSTORE_WHY_LEN];
    assert_int_equal(hl_mapstore_save(f->path, &m, why), HL_OK);
    assert_int_equal(load_into(f, &got, 5, why), HL_ERR_CAPACITY);
    assert_int_equal(got.needed, 7);
    assert_int_equal(got.count, 777);   /* nothing else changed */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_state_directory_first, save_env, restore_env),
        cmocka_unit_test_setup_teardown(test_user_folder_created, save_env, restore_env),
        cmocka_unit_test_setup_teardown(test_nowhere, save_env, restore_env),
        cmocka_unit_test_setup_teardown(test_capacity_refusal_counts, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
