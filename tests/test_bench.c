/*
 * sky-bench's preset table as a program: the interleaved rounds, the
 * Roden & Parberry rows and sky_update's figure are all there and
 * consistent. Speed itself is never asserted here: sky-bench reports it.
 */
#include "test.h"

#include <stdlib.h>
#include <string.h>

/* The number after "key": within [from, end), or NAN-like -1e300 if absent. */
static double field(const char *from, const char *end, const char *key)
{
    char pat[64];
    snprintf(pat, sizeof pat, "\"%s\":", key);
    const char *p = strstr(from, pat);
    if (!p || p >= end) return -1e300;
    return strtod(p + strlen(pat), NULL);
}

/* How many numbers the JSON list "key":[...] holds, each > 0 or not. */
static int positive_list(const char *json, const char *key, int *all_positive)
{
    char pat[64];
    snprintf(pat, sizeof pat, "\"%s\":[", key);
    const char *p = strstr(json, pat);
    *all_positive = 1;
    if (!p) return 0;
    p += strlen(pat);
    int n = 0;
    while (*p && *p != ']') {
        char *end;
        double v = strtod(p, &end);
        if (end == p) break;
        n++;
        if (!(v > 0.0)) *all_positive = 0;
        p = *end == ',' ? end + 1 : end;
    }
    return n;
}

SLOW_TEST(bench_preset_table_in_rounds)
{
    char path[512], cmd[1024];
    static char out[32768];
    snprintf(cmd, sizeof cmd, "%s --only-presets --json --rounds 3 --frames 3 --size 64x36 2>&1",
             bin_path("sky-bench", path, sizeof path));
    int rc = run_command(cmd, out, sizeof out);
    CHECK(rc == 0, "sky-bench --only-presets --json exits 0 (exit %d): %.300s", rc, out);
    if (rc) return;
    CHECK(strstr(out, "\"rounds\":3") != NULL, "the JSON says how many rounds");
    int pos;
    CHECK(positive_list(out, "rounds_ms", &pos) == 3 && pos, "the core baseline has 3 positive per-round figures");
    CHECK(positive_list(out, "compat_rounds_ms", &pos) == 3 && pos, "the compat baseline too");
    CHECK(field(out, out + strlen(out), "frame_ms") > 0.0, "the baseline's median is there");

    /* every preset row: the ratio is the median of the rounds', so within
     * their range; sky_update's CPU figure is measured */
    int presets = 0;
    /* (the sharpness section after the presets has rows of its own) */
    const char *sharpness = strstr(out, "\"sharpness\":");
    const char *presets_end = sharpness ? sharpness : out + strlen(out);
    for (const char *r = strstr(out, "{\"preset\":"); r && r < presets_end; r = strstr(r + 1, "{\"preset\":")) {
        const char *end = strchr(r, '}');
        if (!end) break;
        double ratio = field(r, end, "ratio"), lo = field(r, end, "ratio_min"), hi = field(r, end, "ratio_max");
        double us = field(r, end, "sky_update_us");
        CHECK(ratio > 0.0 && lo <= ratio && ratio <= hi, "a preset's ratio %.3f within its rounds' %.3f-%.3f: %.80s",
              ratio, lo, hi, r);
        CHECK(us > 0.0, "a preset's sky_update us is measured (%.3f): %.80s", us, r);
        presets++;
    }
    CHECK(presets == 32,
          "8 presets, noon over hillaire and preetham, at two dome divisors, before and after a scene at two "
          "divisors, in 2 profiles (%d rows)",
          presets);

    /* the sharpness section beside it: six presets at two sizes in both
     * profiles, each kept figure a ratio of fine structures (a frame
     * filtered up from fewer pixels keeps at most about all of it) and
     * its PSNR that of a close picture */
    CHECK(sharpness != NULL, "the JSON has the sharpness section");
    int sharp_rows = 0;
    for (const char *r = sharpness ? strstr(sharpness, "{\"preset\":") : NULL; r; r = strstr(r + 1, "{\"preset\":")) {
        const char *end = strchr(r, '}');
        if (!end) break;
        double k2 = field(r, end, "kept_k2"), k5 = field(r, end, "kept_k5"), psnr = field(r, end, "psnr_db");
        CHECK(k2 > 0.3 && k2 <= 1.05 && k5 > 0.3 && k5 <= 1.05 && psnr > 30.0,
              "a sharpness row's kept figures in (0.3, 1.05] and PSNR over 30 dB: %.140s", r);
        sharp_rows++;
    }
    CHECK(sharp_rows == 24, "6 presets x 2 sizes x 2 profiles of sharpness (%d rows)", sharp_rows);

    /* Roden & Parberry's shader, as printed and packed, and the baseline
     * drawn after a scene, in both profiles */
    static const char *const names[3] = {"R-P 2005 as printed", "R-P packed (2 fetches)",
                                         "baseline + scene over half, after"};
    static const int textures[3] = {4, 1, 1}, fetches[3] = {4, 2, 1};
    for (int k = 0; k < 3; k++) {
        char pat[96];
        snprintf(pat, sizeof pat, "{\"name\":\"%s\"", names[k]);
        int n = 0;
        for (const char *r = strstr(out, pat); r; r = strstr(r + 1, pat)) {
            const char *end = strchr(r, '}');
            if (!end) break;
            CHECK(field(r, end, "textures") == textures[k] && field(r, end, "fetches") == fetches[k],
                  "%s: %d textures, %d fetches: %.120s", names[k], textures[k], fetches[k], r);
            CHECK(field(r, end, "ratio") > 0.0 && field(r, end, "frame_ms") > 0.0, "%s is timed: %.120s", names[k], r);
            n++;
        }
        CHECK(n == 2, "%s in both profiles (%d rows)", names[k], n);
    }
}

TEST(bench_rejects_bad_rounds)
{
    char path[512], cmd[1024], out[2048];
    static const char *const bad[3] = {"0", "51", "x"};
    for (int i = 0; i < 3; i++) {
        snprintf(cmd, sizeof cmd, "%s --only-presets --rounds %s 2>&1", bin_path("sky-bench", path, sizeof path), bad[i]);
        int rc = run_command(cmd, out, sizeof out);
        CHECK(rc == 2 && strstr(out, "--rounds"), "--rounds %s is a usage error naming the option (exit %d): %.200s",
              bad[i], rc, out);
    }
}

/* --gl es20 runs the preset table on ES 2.0 contexts: its own baseline
 * ("es20_frame_ms", per round) and every preset's row marked es20; the
 * tables that need a desktop context refuse it with a message. */
SLOW_TEST(bench_es20_presets)
{
    char path[512], cmd[1024];
    static char out[32768];
    snprintf(cmd, sizeof cmd, "%s --only-presets --gl es20 --json --rounds 2 --frames 3 --size 64x36 2>&1",
             bin_path("sky-bench", path, sizeof path));
    int rc = run_command(cmd, out, sizeof out);
    CHECK(rc == 0, "sky-bench --only-presets --gl es20 exits 0 (exit %d): %.300s", rc, out);
    if (rc) return;
    int pos;
    CHECK(positive_list(out, "es20_rounds_ms", &pos) == 2 && pos, "the ES20 baseline has 2 positive round figures");
    CHECK(strstr(out, "\"compat_frame_ms\"") == NULL, "only the profile asked for runs");
    int rows = 0, es = 0;
    const char *sharp_es = strstr(out, "\"sharpness\":");
    for (const char *r = strstr(out, "{\"preset\":"); r && (!sharp_es || r < sharp_es); r = strstr(r + 1, "{\"preset\":")) {
        const char *end = strchr(r, '}');
        if (!end) break;
        rows++;
        const char *p = strstr(r, "\"profile\":\"es20\"");
        es += p && p < end;
        CHECK(field(r, end, "ratio") > 0.0, "an ES20 row has its ratio: %.80s", r);
    }
    CHECK(rows > 8 && es == rows, "%d of %d rows are ES20's", es, rows);
    snprintf(cmd, sizeof cmd, "%s --gl es20 --frames 3 2>&1", bin_path("sky-bench", path, sizeof path));
    rc = run_command(cmd, out, sizeof out);
    CHECK(rc == 2 && strstr(out, "--gl es20"), "the full run with --gl es20 is refused (exit %d): %.200s", rc, out);
    snprintf(cmd, sizeof cmd, "%s --only-presets --gl core,metal 2>&1", bin_path("sky-bench", path, sizeof path));
    rc = run_command(cmd, out, sizeof out);
    CHECK(rc == 2, "an unknown profile is a bad argument (exit %d)", rc);
}
