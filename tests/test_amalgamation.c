/*
 * The amalgamation (make amalgamation, tools/amalgamate.sh): the library
 * as build/amalgamation/sky.c and sky.h. The runner's build makes them
 * (build/bin/sky-tests waits for them), so their absence is a failure.
 */
#include "test.h"

#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <stb/stb_image.h>

#define AMALG_C "build/amalgamation/sky.c"
#define AMALG_H "build/amalgamation/sky.h"

/* One translation unit of every source the Makefile's SKY_SRC names (asked
 * of make, so the list is the build's own), each once; the internal headers
 * inlined, so that its only #include "..." is sky.h; _POSIX_C_SOURCE ahead
 * of every system header; stb_image's licence kept; a diagnostic pragma
 * ignored only between a push and its pop; sky.h sky/sky.h under a banner. */
TEST(amalgamation_is_one_file)
{
    size_t len = 0;
    char *c = read_text_file(AMALG_C, &len), *h = read_text_file(AMALG_H, NULL), *pub = read_text_file("sky/sky.h", NULL);
    CHECK(c && h, "%s and %s exist (make amalgamation writes them)", AMALG_C, AMALG_H);
    if (!c || !h || !pub) goto done;
    const char *h_body = strstr(h, "*/\n");
    CHECK(h_body && !strcmp(h_body + 3, pub), "%s is sky/sky.h under its banner", AMALG_H);

    static char list[8192];
    int rc = run_command("make -s --no-print-directory --eval 'amalgamation-sources: ; @echo $(SKY_SRC)' "
                         "amalgamation-sources 2>&1",
                         list, sizeof list);
    CHECK(rc == 0 && strstr(list, "sky/sky.c"), "make names SKY_SRC (exit %d): %.200s", rc, list);
    int sources = 0;
    for (char *src = strtok(list, " \n"); rc == 0 && src; src = strtok(NULL, " \n")) {
        char banner[512];
        snprintf(banner, sizeof banner, "/* ==== amalgamated: %s ==== */\n", src);
        const char *at = strstr(c, banner);
        CHECK(at && !strstr(at + 1, banner), "%s is in the amalgamation once", src);
        sources++;
    }
    CHECK(sources >= 40, "the library's sources listed (%d)", sources);

    int quoted = 0;
    for (const char *p = strstr(c, "\n#include \""); p; p = strstr(p + 1, "\n#include \"")) {
        CHECK(!strncmp(p, "\n#include \"sky.h\"\n", 18), "only sky.h is included by quotes: %.60s", p + 1);
        quoted++;
    }
    CHECK(quoted == 1, "sky.h included once (%d)", quoted);

    const char *posix = strstr(c, "#define _POSIX_C_SOURCE"), *system = strstr(c, "#include <");
    CHECK(posix && system && posix < system, "_POSIX_C_SOURCE is defined before the first system header");

    CHECK(strstr(c, "stb_image - v") && strstr(c, "ALTERNATIVE A - MIT License") &&
              strstr(c, "ALTERNATIVE B - Public Domain"),
          "stb_image is inlined with its licence notice");

    /* every "ignored" inside a push ... pop */
    int depth = 0, stray = 0;
    for (const char *p = strstr(c, "#pragma GCC diagnostic "); p; p = strstr(p + 1, "#pragma GCC diagnostic ")) {
        const char *what = p + strlen("#pragma GCC diagnostic ");
        if (!strncmp(what, "push", 4)) depth++;
        else if (!strncmp(what, "pop", 3)) depth--;
        else if (depth <= 0) stray++;
    }
    CHECK(depth == 0 && stray == 0, "diagnostic pragmas balanced (%d) with none outside a push (%d)", depth, stray);
done:
    free(c);
    free(h);
    free(pub);
}

/* Reads a binary PPM (P6, 8-bit) as RGB. Returns NULL or the pixels. */
static unsigned char *read_ppm(const char *path, int *w, int *h)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    int maxv = 0;
    unsigned char *px = NULL;
    if (fscanf(f, "P6 %d %d %d", w, h, &maxv) == 3 && maxv == 255 && fgetc(f) != EOF && *w > 0 && *h > 0) {
        size_t n = (size_t)*w * (size_t)*h * 3;
        px = malloc(n);
        if (px && fread(px, 1, n, f) != n) {
            free(px);
            px = NULL;
        }
    }
    fclose(f);
    return px;
}

/* A program built from the two files alone: tests/amalgamation/frame.c
 * copied into an empty directory beside sky.c and sky.h and compiled there
 * at -std=c11 -Wall -Wextra -Wshadow -pedantic -Wvla -Werror (no -I, no
 * -D; -Wshadow: no file's statics shadow a later file's locals) with gcc
 * and with clang, linked with OSMesa and libm; its fisheye frame equals,
 * byte for byte, sky-render's (the library as make builds it) for the same
 * inputs: a day with clouds and the sun in a 3.3 core context, a night
 * with the stars, planets and glows in a legacy one. */
SLOW_TEST(amalgamation_frames_match_sky_render)
{
    char dir[] = "/tmp/sky-amalgamation-XXXXXX", cmd[4096], out[8192], path[512];
    if (access(AMALG_C, R_OK) || access(AMALG_H, R_OK)) {
        CHECK(0, "%s and %s exist (make amalgamation writes them)", AMALG_C, AMALG_H);
        return;
    }
    CHECK(mkdtemp(dir) != NULL, "a temporary directory");
    snprintf(cmd, sizeof cmd, "cp %s %s tests/amalgamation/frame.c %s/ 2>&1", AMALG_C, AMALG_H, dir);
    CHECK(run_command(cmd, out, sizeof out) == 0, "copied: %s", out);
    static const char *const compilers[2] = {"gcc", "clang"};
    int built[2] = {0, 0};
    for (int k = 0; k < 2; k++) {
        snprintf(cmd, sizeof cmd,
                 "cd %s && %s -std=c11 -Wall -Wextra -Wshadow -pedantic -Wvla -Werror -o frame-%s frame.c sky.c -lOSMesa -lm 2>&1",
                 dir, compilers[k], compilers[k]);
        int rc = run_command(cmd, out, sizeof out);
        built[k] = rc == 0;
        CHECK(rc == 0, "the two files and the program build with %s (exit %d): %s\n      %.2000s", compilers[k], rc, cmd,
              out);
    }
    static const struct {
        const char *gl, *names;
        unsigned features;
        const char *sliders[6];
    } cases[2] = {
        {"core", "clouds,sun,solar-eclipse", SKY_CLOUDS | SKY_SUN | SKY_SOLAR_ECLIPSE,
         {"0.35", "0.6", "0.2", "0", "0.2", "0.5"}},
        {"compat", "stars,planets,starmap,airglow,zodiacal,clouds,solar-eclipse",
         SKY_STARS | SKY_PLANETS | SKY_STARMAP | SKY_AIRGLOW | SKY_ZODIACAL | SKY_CLOUDS | SKY_SOLAR_ECLIPSE,
         {"0.15", "0.6", "0.2", "0", "0.1", "0"}},
    };
    const int n = 96;
    for (int i = 0; i < 2; i++) {
        char png[600];
        snprintf(png, sizeof png, "%s/render-%d.png", dir, i);
        snprintf(cmd, sizeof cmd,
                 "%s --fisheye --size %dx%d --gl %s --features %s --cover %s --height %s --density %s --sunset %s "
                 "--speed %s --time %s --out %s 2>&1",
                 bin_path("sky-render", path, sizeof path), n, n, cases[i].gl, cases[i].names, cases[i].sliders[0],
                 cases[i].sliders[1], cases[i].sliders[2], cases[i].sliders[3], cases[i].sliders[4],
                 cases[i].sliders[5], png);
        int rc = run_command(cmd, out, sizeof out);
        CHECK(rc == 0, "sky-render (exit %d): %s", rc, out);
        int w = 0, h = 0, comp = 0;
        unsigned char *want = rc == 0 ? stbi_load(png, &w, &h, &comp, 3) : NULL;
        CHECK(want && w == n && h == n, "sky-render's frame read (%dx%d)", w, h);
        for (int k = 0; k < 2 && want; k++) {
            if (!built[k]) continue;
            snprintf(cmd, sizeof cmd, "cd %s && ./frame-%s frame-%d.ppm %d %s %u %s %s %s %s %s %s 2>&1", dir,
                     compilers[k], i, n, cases[i].gl, cases[i].features, cases[i].sliders[0], cases[i].sliders[1],
                     cases[i].sliders[2], cases[i].sliders[3], cases[i].sliders[4], cases[i].sliders[5]);
            rc = run_command(cmd, out, sizeof out);
            CHECK(rc == 0, "the amalgamation's program ran (exit %d): %s", rc, out);
            char ppm[600];
            snprintf(ppm, sizeof ppm, "%s/frame-%d.ppm", dir, i);
            int gw = 0, gh = 0;
            unsigned char *got = rc == 0 ? read_ppm(ppm, &gw, &gh) : NULL;
            CHECK(got && gw == n && gh == n, "its frame read (%dx%d)", gw, gh);
            if (got && gw == n && gh == n) {
                size_t bytes = (size_t)n * (size_t)n * 3, differ = 0;
                for (size_t b = 0; b < bytes; b++) differ += got[b] != want[b];
                CHECK(differ == 0, "%s, %s context, built with %s: %zu of %zu bytes differ from sky-render's",
                      cases[i].names, cases[i].gl, compilers[k], differ, bytes);
            }
            free(got);
            remove(ppm);
        }
        stbi_image_free(want);
        remove(png);
    }
    static const char *const files[] = {"sky.c", "sky.h", "frame.c", "frame-gcc", "frame-clang"};
    for (size_t f = 0; f < sizeof files / sizeof files[0]; f++) {
        snprintf(path, sizeof path, "%s/%s", dir, files[f]);
        remove(path);
    }
    rmdir(dir);
}
