/*
 * sky-bench's preset table as a program: the interleaved rounds, the
 * Roden & Parberry rows and sky_update's figure are all there and
 * consistent, and the Markdown form (docs/benchmarks.md) holds the same
 * rows as the JSON. Speed itself is never asserted here: sky-bench
 * reports it.
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

/* The (preset, profile) pairs of the preset table, in order, from the
 * JSON's "presets" list or from the Markdown table's rows whose
 * sky_update cell is a figure (the R-P and baseline rows have "-"). Each
 * pair is written "preset|profile;" into out. Returns how many. */
static int json_presets(const char *json, char *out, size_t len)
{
    int n = 0;
    out[0] = '\0';
    const char *rp = strstr(json, "\"rp_rows\":");
    for (const char *r = strstr(json, "{\"preset\":\""); r && (!rp || r < rp); r = strstr(r + 1, "{\"preset\":\"")) {
        const char *name = r + strlen("{\"preset\":\""), *prof = strstr(r, "\"profile\":\"");
        if (!prof) break;
        prof += strlen("\"profile\":\"");
        size_t used = strlen(out);
        snprintf(out + used, len - used, "%.*s|%.*s;", (int)strcspn(name, "\""), name, (int)strcspn(prof, "\""), prof);
        n++;
    }
    return n;
}

/* The Markdown table under the header line `head`: its rows' cells, split
 * at " | ". Checks every row has as many cells as the header, and writes
 * the pairs as json_presets does. Returns the number of preset rows, or
 * -1 when the table is not there or a row is malformed. */
static int markdown_presets(const char *md, const char *head, char *out, size_t len)
{
    out[0] = '\0';
    const char *t = strstr(md, head);
    if (!t) return -1;
    int cols = 0;
    for (const char *p = t; *p && *p != '\n'; p++) cols += *p == '|';
    const char *line = strchr(t, '\n');
    if (!line || strncmp(line + 1, "|---|", 5)) return -1;
    line = strchr(line + 1, '\n');
    int n = 0;
    while (line && line[1] == '|') {
        line++;
        const char *end = strchr(line, '\n');
        if (!end) end = line + strlen(line);
        int bars = 0;
        const char *cell[16];
        for (const char *p = line; p < end; p++)
            if (*p == '|' && bars < 16) cell[bars++] = p;
        if (bars != cols) return -1;
        /* cells 0: preset, 1: profile, last: sky_update us ("-" for the quads) */
        const char *upd = cell[bars - 2] + 2;
        if (*upd != '-') {
            size_t used = strlen(out);
            snprintf(out + used, len - used, "%.*s|%.*s;", (int)(cell[1] - line - 3), line + 2,
                     (int)(cell[2] - cell[1] - 3), cell[1] + 2);
            n++;
        }
        line = *end ? end : NULL;
    }
    return n;
}

/* --markdown writes the same preset table as --json, as a Markdown page:
 * a "# " title, a header table naming the command and each profile's
 * renderer, a "## Presets" section (the anchor the README and the docs
 * cite) with the table's header line and a row per preset and profile.
 * Structure only: never a speed. */
SLOW_TEST(bench_markdown_matches_json)
{
    char path[512], cmd[1024];
    static char md[32768], json[32768];
    static const char args[] = "--only-presets --rounds 1 --frames 3 --size 64x36 --gl core,compat "
                               "--presets 'minimal;noon --dome-divisor 2;noon + scene over half, sky after'";
    snprintf(cmd, sizeof cmd, "%s --markdown %s 2>&1", bin_path("sky-bench", path, sizeof path), args);
    int rc = run_command(cmd, md, sizeof md);
    CHECK(rc == 0, "sky-bench --markdown exits 0 (exit %d): %.300s", rc, md);
    snprintf(cmd, sizeof cmd, "%s --json %s 2>&1", bin_path("sky-bench", path, sizeof path), args);
    int rc2 = run_command(cmd, json, sizeof json);
    CHECK(rc2 == 0, "sky-bench --json exits 0 (exit %d): %.300s", rc2, json);
    if (rc || rc2) return;

    CHECK(!strncmp(md, "# Benchmarks\n", 13), "the page starts with its title: %.60s", md);
    CHECK(strstr(md, "Written by `sky-bench --markdown --only-presets") != NULL, "the header names the command");
    CHECK(strstr(md, "`build/bin/sky-bench --markdown > docs/benchmarks.md`") != NULL,
          "the header says how to write the page again");
    char version[64];
    snprintf(version, sizeof version, "| libsky | %d.%d.%d", SKY_VERSION_MAJOR, SKY_VERSION_MINOR, SKY_VERSION_PATCH);
    CHECK(strstr(md, version) != NULL, "the header gives the library's version (%s)", version);
    CHECK(strstr(md, "| renderer, core | ") && strstr(md, "| renderer, compat | ") && !strstr(md, "| renderer, es20"),
          "the header names the renderer of each profile run, and only those");
    CHECK(strstr(md, "| frames | 64x36, median of 3 frames a measurement, 1 interleaved rounds |") != NULL,
          "the header gives the size, frames and rounds");
    const char *sec = strstr(md, "\n## Presets\n\n");
    CHECK(sec != NULL, "a \"## Presets\" section");
    CHECK(!strstr(md, "\"preset\""), "no JSON in the page");

    static const char head[] = "| preset | profile | GPU bytes | textures | programs | draws | frame ms | x baseline | "
                               "x baseline, rounds min-max | sky_update us |";
    char from_md[2048], from_json[2048];
    int n_md = markdown_presets(sec ? sec : md, head, from_md, sizeof from_md);
    int n_json = json_presets(json, from_json, sizeof from_json);
    CHECK(n_md == 6 && n_json == 6, "3 presets in 2 profiles in each form (Markdown %d, JSON %d rows)", n_md, n_json);
    CHECK(!strcmp(from_md, from_json), "the same presets and profiles in the same order:\n      Markdown %s\n      JSON     %s",
          from_md, from_json);
    /* the quads timed beside them: the baseline after a scene and R-P's shader, in both profiles */
    int rp = 0;
    for (const char *p = strstr(md, "| R-P 2005 as printed | "); p; p = strstr(p + 1, "| R-P 2005 as printed | ")) rp++;
    CHECK(rp == 2, "Roden & Parberry's shader as printed in both profiles (%d rows)", rp);
}

/* The two forms of the report are one or the other. */
TEST(bench_markdown_or_json)
{
    char path[512], cmd[1024], out[2048];
    snprintf(cmd, sizeof cmd, "%s --only-presets --json --markdown 2>&1", bin_path("sky-bench", path, sizeof path));
    int rc = run_command(cmd, out, sizeof out);
    CHECK(rc == 2 && strstr(out, "--markdown"), "--json with --markdown is a usage error naming them (exit %d): %.200s",
          rc, out);
}
