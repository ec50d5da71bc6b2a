/*
 * Command-line and whole-program tests: sky-render's contract, the emulated
 * old GPU, the texture budget and the committed textures.
 */
#include "test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <stb/stb_image.h>
#include <unistd.h>


/* Mesa pretending to be a 2004-class GPU (docs/guide.md, "Old GPUs"). */
#define OLD_GPU                                                                                  \
    "MESA_GL_VERSION_OVERRIDE=2.0 MESA_GLSL_VERSION_OVERRIDE=110 MESA_EXTENSION_MAX_YEAR=2004 " \
    "MESA_EXTENSION_OVERRIDE='-GL_ARB_texture_float -GL_ARB_framebuffer_object "               \
    "-GL_ARB_texture_non_power_of_two' "

/* Integer value of "key":N in a JSON text, or -1. */
static double json_number(const char *json, const char *key)
{
    char pat[64];
    snprintf(pat, sizeof pat, "\"%s\":", key);
    const char *p = strstr(json, pat);
    return p ? atof(p + strlen(pat)) : -1.0;
}

SLOW_TEST(profiles_compat_on_emulated_2004_gpu)
{
    char render[512], core_png[512], old_png[512], soft_png[512], cmd[2048], out[8192];
    bin_path("sky-render", render, sizeof render);
    tmp_path("core.png", core_png, sizeof core_png);
    tmp_path("old.png", old_png, sizeof old_png);
    tmp_path("soft.png", soft_png, sizeof soft_png);
    /* every preset, so each shader variant (clouds, stars, moon, eclipse) runs on both profiles */
    const char *scenes[] = {"--preset noon",    "--preset sunset --yaw 270 --pitch 10",
                            "--preset starry",  "--preset overcast",
                            "--preset moonlit", "--preset eclipse", "--preset solar-eclipse",
                            "--preset minimal"};
    for (size_t k = 0; k < sizeof scenes / sizeof scenes[0]; k++) {
        snprintf(cmd, sizeof cmd, "%s --size 320x180 %s --gl core --out %s 2>&1", render, scenes[k], core_png);
        int rc1 = run_command(cmd, out, sizeof out);
        snprintf(cmd, sizeof cmd, OLD_GPU "%s --size 320x180 %s --out %s --stats 2>&1", render, scenes[k], old_png);
        int rc2 = run_command(cmd, out, sizeof out);
        CHECK(rc1 == 0 && rc2 == 0, "renders exit 0 (%d, %d): %s", rc1, rc2, out);
        CHECK(strstr(out, "\"profile\":\"compat\"") != NULL, "AUTO picks COMPAT20 on the old GPU: %s", out);
        CHECK(strstr(out, "\"gl_version\":\"2.0") != NULL, "the context really is GL 2.0: %.80s", out);
        image a, b;
        if (image_load_png(core_png, &a) || image_load_png(old_png, &b)) {
            CHECK(0, "cannot read the rendered PNGs");
            return;
        }
        double psnr = image_psnr(&a, &b);
        NOTE("%s: CORE33 vs emulated GL 2.0 PSNR %.1f dB", scenes[k], psnr);
        CHECK(psnr >= 35.0, "old GPU image must agree with CORE33 (%.1f dB)", psnr);
        image_free(&a);
        image_free(&b);
    }
    /* softpipe: a far slower rasteriser, as a worst case */
    snprintf(cmd, sizeof cmd, OLD_GPU "GALLIUM_DRIVER=softpipe %s --size 160x90 --out %s --stats 2>&1", render,
             soft_png);
    int rc = run_command(cmd, out, sizeof out);
    CHECK(rc == 0 && strstr(out, "\"profile\":\"compat\""), "softpipe under the old-GPU overrides: %s", out);
    NOTE("softpipe 160x90 frame_ms %.1f", json_number(out, "frame_ms"));
    remove(core_png);
    remove(old_png);
    remove(soft_png);
}

/* Every atmosphere path (the blend with either partner) under every layer
 * at once, in both profiles and on the emulated 2004 GPU (no NPOT: the
 * dome's image needs its corner snippet too): each shader that carries
 * the atmosphere and the clouds' cover stays within the program's
 * snippets and builds. */
SLOW_TEST(profiles_every_path_with_every_layer)
{
    static const char *const paths[] = {"gradient", "preetham", "rayleigh", "hillaire", "blend",
                                        "blend --blend-partner preetham"};
    static const char *const gls[3] = {"--gl core", "--gl compat", "--gl auto"};
    char render[512], png[512], cmd[2048], out[2048];
    bin_path("sky-render", render, sizeof render);
    tmp_path("layers.png", png, sizeof png);
    for (size_t p = 0; p < sizeof paths / sizeof paths[0]; p++)
        for (int g = 0; g < 3; g++) {
            snprintf(cmd, sizeof cmd,
                     "%s%s --size 64x36 --time 0.02 --atmosphere %s %s --features "
                     "clouds,sun,moon,flicker,stars,starmap,eclipse,solar-eclipse --out %s 2>&1",
                     g == 2 ? OLD_GPU : "", render, paths[p], gls[g], png);
            int rc = run_command(cmd, out, sizeof out);
            CHECK(rc == 0, "--atmosphere %s, %s: exit %d: %s", paths[p], g == 2 ? "emulated 2004 GPU" : gls[g], rc,
                  out);
        }
    remove(png);
}

/* A context older than OpenGL 2.0 gets a clear error, not a crash. */
TEST(profiles_too_old_context_is_an_error)
{
    char render[512], cmd[1024], out[2048];
    snprintf(cmd, sizeof cmd, "MESA_GL_VERSION_OVERRIDE=1.5 %s --size 16x16 --stats 2>&1",
             bin_path("sky-render", render, sizeof render));
    int rc = run_command(cmd, out, sizeof out);
    CHECK(rc == 1 && strstr(out, "too old") && strstr(out, "2.0"), "GL 1.5 context: exit 1 with a clear message (%d: %s)",
          rc, out);
}

TEST(texture_budget_minimal_path)
{
    char render[512], cmd[1024], out[8192];
    snprintf(cmd, sizeof cmd, OLD_GPU "%s --size 64x64 --preset minimal --stats 2>&1",
             bin_path("sky-render", render, sizeof render));
    int rc = run_command(cmd, out, sizeof out);
    CHECK(rc == 0, "minimal preset renders: %s", out);
    double bytes = json_number(out, "gpu_bytes");
    NOTE("minimal path on COMPAT20: %.0f bytes of GPU memory (%.3f MiB), %g textures", bytes, bytes / 1048576.0,
         json_number(out, "textures"));
    CHECK(bytes > 0 && bytes <= 1.5 * 1048576.0, "minimal path must fit 1.5 MiB (%.0f bytes)", bytes);
}

/* Seam check: the jump across a tile's wrap must look like any other step
 * between neighbouring texels. */
TEST(textures_tile_without_seams)
{
    const char *files[1] = {"textures/clouds.png"};
    for (int f = 0; f < 1; f++) {
        image im;
        if (image_load_png(files[f], &im)) {
            CHECK(0, "cannot read %s", files[f]);
            continue;
        }
        int channels = 3; /* R photo, G noise, B detail tile; A is the sunset ramp */
        for (int c = 0; c < channels; c++)
            for (int axis = 0; axis < 2; axis++) {
                double inner = 0, wrap = 0;
                int n = axis ? im.w : im.h, m = axis ? im.h : im.w;
                for (int i = 0; i < m; i++) {
                    for (int j = 0; j + 1 < n; j++) {
                        int x0 = axis ? i : j, y0 = axis ? j : i, x1 = axis ? i : j + 1, y1 = axis ? j + 1 : i;
                        inner += fabs(im.px[3 * (y0 * im.w + x0) + c] - im.px[3 * (y1 * im.w + x1) + c]);
                    }
                    int xa = axis ? i : n - 1, ya = axis ? n - 1 : i;
                    wrap += fabs(im.px[3 * (ya * im.w + xa) + c] - im.px[3 * ((axis ? 0 : i) * im.w + (axis ? i : 0)) + c]);
                }
                inner /= (double)m * (n - 1);
                wrap /= m;
                CHECK(wrap < 2.0 * inner + 1e-3, "%s channel %d axis %d: seam step %.4f vs typical %.4f", files[f], c,
                      axis, wrap, inner);
            }
        image_free(&im);
    }
}

/* The flicker texture's stars carry their rate, variance and phase into
 * their 3x3 neighbourhood, so linear filtering never mixes two stars'
 * parameters (flicker.glsl relies on it). */
TEST(flicker_texture_neighbourhoods)
{
    int w, h, n;
    unsigned char *p = stbi_load("textures/flicker.png", &w, &h, &n, 4);
    if (!p) {
        CHECK(0, "cannot read textures/flicker.png");
        return;
    }
    int stars = 0, mixed = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            const unsigned char *c = p + 4 * (y * w + x);
            if (!c[0]) continue;
            stars++;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    const unsigned char *q = p + 4 * (((y + dy + h) % h) * w + (x + dx + w) % w);
                    mixed += memcmp(q + 1, c + 1, 3) != 0 || ((dx || dy) && q[0] != 0);
                }
        }
    NOTE("%d stars per 256x256 tile", stars);
    CHECK(stars > 150, "the tile holds many stars (%d)", stars);
    CHECK(mixed == 0, "%d neighbour texels disagree with their star", mixed);
    stbi_image_free(p);
}

SLOW_TEST(cli_exit_codes_and_messages)
{
    struct {
        const char *args;
        int status;
        const char *message; /* must appear in stderr */
    } cases[] = {
        {"--cover 1.5", 2, "--cover"},
        {"--cover", 2, "--cover"},
        {"--cover abc", 2, "--cover"},
        {"--cover nan", 2, "--cover"},
        {"--time -0.1", 2, "--time"},
        {"--size 0x10", 2, "--size"},
        {"--size 100", 2, "--size"},
        {"--fov 0", 2, "--fov"},
        {"--pitch 91", 2, "--pitch"},
        {"--frames 0", 2, "--frames"},
        {"--frames 2.5", 2, "--frames"},
        {"--gl metal", 2, "--gl"},
        {"--features clouds,rain", 2, "rain"},
        {"--features clouds,", 2, "--features"},
        {"--atmosphere fog", 2, "--atmosphere"},
        {"--luts huge", 2, "--luts"},
        {"--blend 1.5", 2, "--blend"},
        {"--blend-partner hillaire", 2, "--blend-partner"},
        {"--blend-partner", 2, "--blend-partner"},
        {"--preset beach", 2, "--preset"},
        {"--date 2011-06-15", 2, "--date"},
        /* the supported years' calendar edges: the option is named with
         * its range before any rendering (it used to reach the library
         * and exit 1 with an observer message) */
        {"--size 8x8 --date 3001-01-01T00:00:00Z", 2, "--date"},
        {"--size 8x8 --date 3001-01-01T00:00:00Z", 2, "-1999..3000"},
        {"--size 8x8 --date 3000-12-31T23:59:60.5Z", 2, "--date"},
        {"--size 8x8 --date -2000-12-31T23:59:59Z", 2, "--date"},
        {"--query --date 3000-12-31T23:59:59Z", 0, ""},
        {"--query --date -1999-01-01T00:00:00Z", 0, ""},
        {"--turbidity 0.5", 2, "--turbidity"},
        {"--dome-divisor 9", 2, "--dome-divisor"},
        {"--tone-map aces", 2, "--tone-map"},
        {"--dome-divisor 2.5", 2, "--dome-divisor"},
        {"--planet venus", 2, "--planet"},
        {"--bogus", 2, "--bogus"},
        {"stray", 2, "stray"},
        {"--cover 0.2 --cover 0.3", 2, "more than once"},
        {"--seconds -1", 2, "--seconds"},
        {"--out /nonexistent-dir/x.png --size 8x8", 1, "/nonexistent-dir/x.png"},
        /* an output's name says its format: PNG data in a.jpg was written
         * without a word; the case of the extension does not matter (the
         * accepted ones fail only at writing, exit 1) */
        {"--size 8x8 --out /nonexistent-dir/a.jpg", 2, "--out"},
        {"--size 8x8 --out /nonexistent-dir/a.jpg", 2, ".png"},
        {"--size 8x8 --out /nonexistent-dir/png", 2, "--out"},
        {"--size 8x8 --out-pfm /nonexistent-dir/a.png", 2, "--out-pfm"},
        {"--size 8x8 --out-pfm /nonexistent-dir/a.png", 2, ".pfm"},
        {"--size 8x8 --out /nonexistent-dir/X.PNG", 1, "X.PNG"},
        {"--size 8x8 --out-pfm /nonexistent-dir/X.Pfm", 1, "X.Pfm"},
        {"--size 8x8 --cover 0 --cover-typo 1", 2, "--cover-typo"},
        {"--help", 0, ""},
        {"--size 16x8 --preset overcast --cover 0.1", 0, ""},
        {"--size 16x8 --preset moonlit", 0, ""},
        {"--size 16x8 --preset eclipse --date 2026-03-03T12:00:00Z --yaw 10", 0, ""},
    };
    char render[512], cmd[1024], out[4096];
    bin_path("sky-render", render, sizeof render);
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        snprintf(cmd, sizeof cmd, "%s %s 2>&1 >/dev/null", render, cases[i].args);
        int rc = run_command(cmd, out, sizeof out);
        CHECK(rc == cases[i].status, "'%s' exits %d, expected %d (%s)", cases[i].args, rc, cases[i].status, out);
        CHECK(strstr(out, cases[i].message) != NULL, "'%s': message '%s' should name '%s'", cases[i].args, out,
              cases[i].message);
    }
    CHECK(access("/nonexistent-dir/x.png", F_OK) != 0, "no partial file");
}

/* Every option: missing, malformed, out of range and given twice exit 2
 * naming it; the outputs to an unwritable place exit 1 naming the path and
 * leave no file. */
SLOW_TEST(cli_every_option_checked)
{
    static const struct {
        const char *opt, *malformed, *out_of_range; /* NULL: no such case */
    } opts[] = {
        {"--size", "12by9", "0x10"},     {"--cover", "lots", "1.01"},       {"--height", "x", "-0.1"},
        {"--density", "0.5.5", "2"},     {"--sunset", "", "inf"},            {"--speed", "nan", "7"},
        {"--time", "noon", "-1"},        {"--seconds", "soon", "-5"},        {"--date", "yesterday", "4000-01-01T00:00:00Z"},
        {"--lat", "north", "91"},        {"--lon", "east", "181"},           {"--alt", "high", "200000"},
        {"--yaw", "left", "400"},        {"--pitch", "up", "-91"},           {"--fov", "wide", "180"},
        {"--atmosphere", "fog", NULL},   {"--features", "rain", NULL},       {"--gl", "vulkan", NULL},
        {"--preset", "beach", NULL},     {"--frames", "many", "0"},          {"--moon-scale", "big", "51"},
        {"--exposure", "bright", "11"},  {"--capture", "big", "60"},
        {"--hip", "sirius", "0"},        {"--out", NULL, NULL},              {"--out-pfm", NULL, NULL},
    };
    char render[512], cmd[1024], out[2048];
    bin_path("sky-render", render, sizeof render);
    int checked = 0;
    for (size_t i = 0; i < sizeof opts / sizeof opts[0]; i++) {
        const char *o = opts[i].opt;
        const char *extra = !strcmp(o, "--hip") ? "--query " : "";
        const char *variants[3] = {NULL, opts[i].malformed, opts[i].out_of_range};
        for (int v = 0; v < 4; v++) {
            if (v == 0)
                snprintf(cmd, sizeof cmd, "%s %s%s 2>&1 >/dev/null", render, extra, o); /* missing value */
            else if (v == 3)
                snprintf(cmd, sizeof cmd, "%s %s%s %s %s %s 2>&1 >/dev/null", render, extra, o,
                         !strcmp(o, "--out") ? "/tmp/x.png" : !strcmp(o, "--out-pfm") ? "/tmp/x.pfm"
                                                 : (opts[i].out_of_range ? "1" : "auto"),
                         o, !strcmp(o, "--out") ? "/tmp/y.png" : !strcmp(o, "--out-pfm") ? "/tmp/y.pfm" : "1"); /* twice */
            else if (variants[v])
                snprintf(cmd, sizeof cmd, "%s %s%s '%s' 2>&1 >/dev/null", render, extra, o, variants[v]);
            else
                continue;
            int rc = run_command(cmd, out, sizeof out);
            CHECK(rc == 2 && strstr(out, o), "%s: exit %d, message '%.120s' (case %d)", cmd, rc, out, v);
            checked++;
        }
    }
    /* --capture writes one PNG: without --out, or with what it cannot
     * write, it is a usage error */
    static const char *const capture_bad[3] = {"--capture 16", "--capture 16 --out /tmp/c.png --frames 2",
                                                "--capture 16 --out-pfm /tmp/c.pfm"};
    for (int k = 0; k < 3; k++) {
        snprintf(cmd, sizeof cmd, "%s %s 2>&1 >/dev/null", render, capture_bad[k]);
        int rc = run_command(cmd, out, sizeof out);
        CHECK(rc == 2 && strstr(out, "--capture"), "%s: exit %d, '%.120s'", capture_bad[k], rc, out);
        checked++;
    }
    /* unwritable outputs */
    const char *paths[2] = {"--out /proc/sky-test.png", "--out-pfm /proc/sky-test.pfm"};
    for (int k = 0; k < 2; k++) {
        snprintf(cmd, sizeof cmd, "%s --size 8x8 %s 2>&1 >/dev/null", render, paths[k]);
        int rc = run_command(cmd, out, sizeof out);
        CHECK(rc == 1 && strstr(out, "/proc/sky-test"), "%s: exit %d, '%s'", paths[k], rc, out);
        CHECK(access(strchr(paths[k], ' ') + 1, F_OK) != 0, "no partial %s", paths[k]);
        checked++;
    }
    NOTE("%d malformed command lines checked", checked);
}

TEST(cli_outputs_png_pfm_stats)
{
    char render[512], png[512], pfm[512], seq[512], cmd[2048], out[8192];
    bin_path("sky-render", render, sizeof render);
    tmp_path("o.png", png, sizeof png);
    tmp_path("o.pfm", pfm, sizeof pfm);
    tmp_path("seq.png", seq, sizeof seq);
    snprintf(cmd, sizeof cmd, "%s --size 64x32 --out %s --out-pfm %s --stats", render, png, pfm);
    int rc = run_command(cmd, out, sizeof out);
    CHECK(rc == 0, "render exits 0");
    static const char *keys[] = {"\"gl_version\":", "\"profile\":", "\"features\":[", "\"frame_ms\":", "\"lut_ms\":",
                                 "\"gpu_bytes\":", "\"textures\":", "\"programs\":", "\"draws_per_frame\":",
                                 "\"layers\":{", "\"atmosphere\":{\"ms\":"};
    for (size_t k = 0; k < sizeof keys / sizeof keys[0]; k++)
        CHECK(strstr(out, keys[k]) != NULL, "stats JSON has %s: %s", keys[k], out);
    image im;
    CHECK(image_load_png(png, &im) == 0 && im.w == 64 && im.h == 32, "PNG of the asked size");
    image_free(&im);
    /* --capture: a 4N x 3N cube cross (its first row at the top), the
     * corners around it empty, the up face (top) the blue sky, the down
     * one (bottom) the ground */
    char cross[512];
    tmp_path("cross.png", cross, sizeof cross);
    snprintf(cmd, sizeof cmd, "%s --preset noon --capture 16 --out %s", render, cross);
    CHECK(run_command(cmd, out, sizeof out) == 0, "--capture exits 0: %s", out);
    if (image_load_png(cross, &im) == 0) {
        CHECK(im.w == 64 && im.h == 48, "the cross is 64 x 48: %d x %d", im.w, im.h);
        const float *up = im.px + (8 * 64 + 24) * 3, *down = im.px + (40 * 64 + 24) * 3;
        float corner = image_luminance(&im, 2, 2);
        CHECK(corner == 0.0f && up[2] > up[0] && down[0] >= down[2],
              "corner %g; +Y (%g, %g, %g) blue, -Y (%g, %g, %g) the ground", corner, up[0], up[1], up[2], down[0],
              down[1], down[2]);
        image_free(&im);
    } else {
        CHECK(0, "no cross written");
    }
    FILE *f = fopen(pfm, "rb");
    CHECK(f != NULL, "PFM written");
    if (f) {
        int w = 0, h = 0;
        double scale = 0;
        char magic[3] = "";
        CHECK(fscanf(f, "%2s %d %d %lf", magic, &w, &h, &scale) == 4 && !strcmp(magic, "PF") && w == 64 && h == 32 &&
                  scale < 0,
              "PFM header: %s %d %d %g", magic, w, h, scale);
        fgetc(f);
        float px[3 * 64];
        int finite = 1;
        double ymax = 0;
        for (int y = 0; y < h; y++) {
            if (fread(px, sizeof(float), 3 * 64, f) != 3 * 64) {
                finite = 0;
                break;
            }
            for (int i = 0; i < 3 * 64; i++) finite &= isfinite(px[i]) && px[i] >= 0.0f;
            for (int x = 0; x < 64; x++) ymax = fmax(ymax, 0.2126 * px[3 * x] + 0.7152 * px[3 * x + 1] + 0.0722 * px[3 * x + 2]);
        }
        fclose(f);
        CHECK(finite, "PFM values finite and non-negative");
        CHECK(ymax > 1.0 && ymax < 1e7, "PFM is linear kcd/m^2 (max %.3g)", ymax);
    }
    snprintf(cmd, sizeof cmd, "%s --size 16x16 --frames 3 --out %s 2>&1", render, seq);
    rc = run_command(cmd, out, sizeof out);
    CHECK(rc == 0 && strstr(out, "frame 3/3"), "--frames reports progress on stderr: %s", out);
    for (int i = 1; i <= 3; i++) {
        char name[600];
        snprintf(name, sizeof name, "%.*s_%04d.png", (int)(strlen(seq) - 4), seq, i);
        CHECK(access(name, F_OK) == 0, "frame file %s", name);
        remove(name);
    }
    remove(png);
    remove(pfm);
}

/* sky-demo and sky-game write their --screenshot as PNG whatever its name:
 * a name that does not end in .png (any case) is a bad argument, exit 2
 * naming --screenshot, before any window or rendering. Without a display
 * the demo renders headless, so the old behaviour showed as an attempt to
 * write the file (exit 1). */
TEST(cli_screenshot_must_be_png)
{
    static const char *const progs[2] = {"sky-demo", "sky-game"};
    char bin[512], cmd[1024], out[2048];
    for (int p = 0; p < 2; p++) {
        bin_path(progs[p], bin, sizeof bin);
        snprintf(cmd, sizeof cmd,
                 "env -u DISPLAY -u WAYLAND_DISPLAY %s --size 8x8 --frames 1 --screenshot /nonexistent-dir/shot.jpg "
                 "2>&1 >/dev/null",
                 bin);
        int rc = run_command(cmd, out, sizeof out);
        CHECK(rc == 2 && strstr(out, "--screenshot") && strstr(out, ".png"),
              "%s --screenshot shot.jpg: exit 2 naming --screenshot and .png (%d: %s)", progs[p], rc, out);
        snprintf(cmd, sizeof cmd,
                 "env -u DISPLAY -u WAYLAND_DISPLAY %s --size 8x8 --frames 1 --screenshot /nonexistent-dir/SHOT.PNG "
                 "2>&1 >/dev/null",
                 bin);
        rc = run_command(cmd, out, sizeof out);
        CHECK(rc != 2 && !strstr(out, "--screenshot"), "%s --screenshot SHOT.PNG is accepted (%d: %s)", progs[p], rc,
              out);
    }
}

/* sky-render with nothing to write (no --out, --out-pfm, --stats or
 * --query) still renders, as a check of GL, but says on stderr that
 * nothing was written and how to write; a command with an output does not. */
TEST(cli_no_output_says_so)
{
    char render[512], cmd[1024], out[2048];
    bin_path("sky-render", render, sizeof render);
    snprintf(cmd, sizeof cmd, "%s --size 8x8 --preset noon 2>&1 >/dev/null", render);
    int rc = run_command(cmd, out, sizeof out);
    CHECK(rc == 0, "no output is not an error (exit %d: %s)", rc, out);
    CHECK(strstr(out, "nothing") && strstr(out, "--out FILE.png") && strstr(out, "--out-pfm FILE.pfm"),
          "stderr says nothing was written and names --out and --out-pfm: '%s'", out);
    static const char *const with_output[2] = {"--size 8x8 --stats", "--query"};
    for (int k = 0; k < 2; k++) {
        snprintf(cmd, sizeof cmd, "%s %s 2>&1 >/dev/null", render, with_output[k]);
        rc = run_command(cmd, out, sizeof out);
        CHECK(rc == 0 && !strstr(out, "nothing"), "'%s' prints no such note (%d: '%s')", with_output[k], rc, out);
    }
}

/* --help and -h print the usage on stdout and exit 0, with nothing on
 * stderr (sky-bench called them a bad argument, exit 2). */
TEST(cli_help_exits_0)
{
    static const char *const progs[2] = {"sky-render", "sky-bench"};
    static const char *const flags[2] = {"--help", "-h"};
    char bin[512], cmd[1024], out[8192], usage[64];
    for (int p = 0; p < 2; p++)
        for (int f = 0; f < 2; f++) {
            bin_path(progs[p], bin, sizeof bin);
            snprintf(usage, sizeof usage, "usage: %s", progs[p]);
            snprintf(cmd, sizeof cmd, "%s %s 2>/dev/null", bin, flags[f]);
            int rc = run_command(cmd, out, sizeof out);
            CHECK(rc == 0 && strstr(out, usage) && strstr(out, "--size"),
                  "%s %s: exit 0 with the usage on stdout (%d: %.200s)", progs[p], flags[f], rc, out);
            snprintf(cmd, sizeof cmd, "%s %s 2>&1 >/dev/null", bin, flags[f]);
            rc = run_command(cmd, out, sizeof out);
            CHECK(rc == 0 && out[0] == '\0', "%s %s: nothing on stderr (%d: %.200s)", progs[p], flags[f], rc, out);
        }
}

/* Whether word is one of text's words (split at spaces, punctuation and
 * slashes, so "Up/Down" holds "Up" and "Down", "+/-" holds "+" and "-"). */
static int has_word(const char *text, const char *word)
{
    static const char *const seps = " \t\n,;:/()";
    size_t n = strlen(word);
    for (const char *p = text; *p;) {
        p += strspn(p, seps);
        size_t k = strcspn(p, seps);
        if (k == n && !strncmp(p, word, n)) return 1;
        p += k;
    }
    return 0;
}

/* sky-demo --help names every key demo.c's handler answers (Left/Right
 * and O were missing): each GLFW_KEY_ in demo/demo.c is looked up in the
 * usage, so a key added without its line fails here. sky-game, which has
 * no keys, lists none. */
TEST(cli_demo_help_lists_every_key)
{
    static const struct {
        const char *glfw, *shown;
    } names[] = {{"LEFT", "Left"},   {"RIGHT", "Right"}, {"UP", "Up"},         {"DOWN", "Down"},
                 {"SPACE", "Space"}, {"EQUAL", "+"},     {"KP_ADD", "+"},      {"MINUS", "-"},
                 {"KP_SUBTRACT", "-"}, {"ESCAPE", "Esc"}, {"1", "1-6"},        {"6", "1-6"}};
    char bin[512], cmd[1024];
    static char help[16384], game_help[16384];
    snprintf(cmd, sizeof cmd, "%s --help 2>&1", bin_path("sky-demo", bin, sizeof bin));
    int rc = run_command(cmd, help, sizeof help);
    CHECK(rc == 0 && strstr(help, "usage: sky-demo"), "sky-demo --help exits 0 (%d)", rc);
    FILE *f = fopen("demo/demo.c", "rb");
    CHECK(f != NULL, "demo/demo.c readable from the working directory");
    if (!f) return;
    static char src[262144];
    size_t len = fread(src, 1, sizeof src - 1, f);
    src[len] = '\0';
    fclose(f);
    int keys = 0;
    for (const char *p = strstr(src, "GLFW_KEY_"); p; p = strstr(p + 1, "GLFW_KEY_")) {
        char id[32];
        size_t k = 0;
        for (const char *q = p + 9; k + 1 < sizeof id && (*q == '_' || (*q >= 'A' && *q <= 'Z') || (*q >= '0' && *q <= '9'));
             q++)
            id[k++] = *q;
        id[k] = '\0';
        const char *shown = k == 1 && id[0] >= 'A' && id[0] <= 'Z' ? id : NULL;
        for (size_t i = 0; !shown && i < sizeof names / sizeof names[0]; i++)
            if (!strcmp(names[i].glfw, id)) shown = names[i].shown;
        CHECK(shown != NULL, "GLFW_KEY_%s: this test has no help name for it", id);
        if (!shown) continue;
        CHECK(has_word(help, shown), "sky-demo --help names the key GLFW_KEY_%s as '%s'", id, shown);
        keys++;
    }
    NOTE("%d key uses in demo/demo.c checked against sky-demo --help", keys);
    CHECK(keys >= 20, "the key handler was found (%d keys)", keys);
    CHECK(strstr(help, "Left/Right") && strstr(help, "turn the view"), "Left/Right: turn the view");
    snprintf(cmd, sizeof cmd, "%s --help 2>&1", bin_path("sky-game", bin, sizeof bin));
    rc = run_command(cmd, game_help, sizeof game_help);
    CHECK(rc == 0 && !strstr(game_help, "Left/Right"), "sky-game, which has no keys, lists none (%d)", rc);
}
