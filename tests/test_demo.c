/*
 * The window programs under a real X server (Xvfb, installed by make's
 * deps step): sky-demo shows the sky with its sliders, a synthetic mouse
 * drag on the cover slider changes the clouds, the readout's frame time is
 * the sky's GPU time as sky-bench measures it, and sky-game lights its
 * world differently at noon and at night. And their headless paths
 * (DISPLAY unset), which render through OSMesa.
 */
#include "test.h"
#include "cli.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define XVFB "xvfb-run -a -s '-screen 0 1280x720x24' "

static const char *tmp(const char *name, char *buf, size_t len)
{
    snprintf(buf, len, "/tmp/sky-test-%d-%s", (int)getpid(), name);
    return buf;
}

/* Mean saturation (max - min over max) of a region: blue sky is high,
 * white and grey clouds are low. */
static double saturation(const image *im, int x0, int y0, int x1, int y1)
{
    double s = 0;
    int n = 0;
    for (int y = y0; y < y1; y++)
        for (int x = x0; x < x1; x++) {
            const float *p = im->px + 3 * (y * im->w + x);
            float mx = fmaxf(p[0], fmaxf(p[1], p[2])), mn = fminf(p[0], fminf(p[1], p[2]));
            s += mx > 0 ? (mx - mn) / mx : 0;
            n++;
        }
    return n ? s / n : 0;
}

static int run_demo(const char *args, const char *png, image *out)
{
    char path[512], cmd[2048], log[4096];
    snprintf(cmd, sizeof cmd, XVFB "%s --size 640x360 --frames 3 --screenshot %s %s 2>&1",
             bin_path("sky-demo", path, sizeof path), png, args);
    int rc = run_command(cmd, log, sizeof log);
    if (rc != 0 || image_load_png(png, out)) {
        printf("    %s\n    exit %d: %s\n", cmd, rc, log);
        return -1;
    }
    remove(png);
    return 0;
}

TEST(demo_window_shows_sky_and_sliders)
{
    char png[256];
    image im;
    if (run_demo("--cover 0.3 --time 0.45", tmp("demo.png", png, sizeof png), &im)) {
        CHECK(0, "sky-demo under Xvfb");
        return;
    }
    /* the sky: blue dominates away from the overlay */
    double b = 0, r = 0;
    for (int y = 200; y < 260; y++)
        for (int x = 400; x < 600; x++) r += im.px[3 * (y * 640 + x)], b += im.px[3 * (y * 640 + x) + 2];
    CHECK(b > 1.05 * r, "the window shows a blue day sky (blue %.1f, red %.1f)", b, r);
    /* the slider panel: the 'time' bar (row 6) is filled to 0.45 of its
     * width with the bar colour, the rest darker */
    int y = 20 + 5 * 22 + 6;
    CHECK(image_luminance(&im, 100 + 40, y) > image_luminance(&im, 100 + 180, y) + 0.15f,
          "the time slider is drawn filled to its value");
    image_free(&im);
}

SLOW_TEST(demo_drag_on_cover_slider)
{
    char png[256];
    image before, after;
    if (run_demo("--cover 0.1 --time 0.45", tmp("before.png", png, sizeof png), &before) ||
        run_demo("--cover 0.1 --time 0.45 --drag cover:0.1:0.9", tmp("after.png", png, sizeof png), &after)) {
        CHECK(0, "sky-demo under Xvfb");
        return;
    }
    double s0 = saturation(&before, 0, 170, 640, 250), s1 = saturation(&after, 0, 170, 640, 250);
    NOTE("sky saturation: %.3f at cover 0.1, %.3f after dragging cover to 0.9", s0, s1);
    CHECK(s1 < 0.6 * s0, "dragging the cover slider covers the sky with clouds");
    /* the slider itself moved: cover's bar now filled near its end */
    int y = 20 + 6;
    CHECK(image_luminance(&after, 100 + 180, y) > image_luminance(&before, 100 + 180, y) + 0.2f,
          "the cover bar follows the drag");
    image_free(&before);
    image_free(&after);
}

/* The readout's cost line, which sky-demo also prints when it leaves
 * after --frames: the sky's GPU frame time (median of the frames after the
 * first, by a timer query that agreed with the clock, else by the clock
 * around glFinish, as sky-bench) and the frame rate. */
TEST(demo_readout_is_gpu_frame_time)
{
    char path[512], cmd[2048], log[4096], png[256];
    snprintf(cmd, sizeof cmd, XVFB "%s --size 320x180 --frames 8 --screenshot %s --preset noon 2>&1",
             bin_path("sky-demo", path, sizeof path), tmp("readout.png", png, sizeof png));
    int rc = run_command(cmd, log, sizeof log);
    remove(png);
    CHECK(rc == 0, "sky-demo under Xvfb (exit %d): %s", rc, log);
    const char *line = strstr(log, "sky-demo: sky ");
    double ms = -1, fps = -1;
    int n = 0;
    char method[32] = "";
    if (line) sscanf(line, "sky-demo: sky %lf ms GPU (%31[^,], median of %d frames), %lf fps", &ms, method, &n, &fps);
    NOTE("%.*s", line ? (int)strcspn(line, "\n") : 0, line ? line : "");
    CHECK(ms > 0.0 && fps > 0.0, "the readout has a frame time and a frame rate: %s", line ? line : log);
    CHECK(!strcmp(method, "timer query") || !strcmp(method, "glFinish"), "it says how it measured ('%s')", method);
    CHECK(n == 7 || (!strcmp(method, "timer query") && n >= 1 && n <= 7),
          "the median of every frame but the first (%d of 8; a timer query's come two frames late)", n);
}

SLOW_TEST(game_lit_by_the_sky)
{
    char path[512], cmd[2048], log[4096], png[256];
    double mean[3];
    /* noon, midnight, and the README's moonless night (the starry preset:
     * the night glows, no moon) */
    const char *when[3] = {"--time 0.5", "--time 0.0", "--preset starry"};
    for (int k = 0; k < 3; k++) {
        tmp(k == 2 ? "starry.png" : k ? "night.png" : "noon.png", png, sizeof png);
        snprintf(cmd, sizeof cmd, XVFB "%s --size 640x360 --frames 3 --screenshot %s %s 2>&1",
                 bin_path("sky-game", path, sizeof path), png, when[k]);
        image im;
        int rc = run_command(cmd, log, sizeof log);
        if (rc != 0 || image_load_png(png, &im)) {
            CHECK(0, "sky-game under Xvfb: exit %d: %s", rc, log);
            return;
        }
        /* the big box in the lower left: the lit world, not the sky */
        double s = 0;
        int n = 0;
        for (int y = 230; y < 300; y++)
            for (int x = 170; x < 240; x++) s += image_luminance(&im, x, y), n++;
        mean[k] = s / n;
        image_free(&im);
        remove(png);
    }
    NOTE("sky-game: a box's mean brightness %.3f at noon, %.3f at midnight, %.3f under the starry preset's moonless "
         "sky", mean[0], mean[1], mean[2]);
    CHECK(mean[0] > 0.15 && mean[0] > 5.0 * mean[1] + 0.02, "the world is lit by the sky: bright at noon, dark at night");
    /* and readable under a moonless sky, not black: the night's grade
     * (display.glsl) lifts what the sky lights to an eighth of its
     * luminance (the box showed 0 of 255 before the night's toe went, 5
     * after, about 12 graded) */
    CHECK(mean[2] >= 8.0 / 255.0, "the box under the moonless sky %.1f of 255, at least 8", 255.0 * mean[2]);
}

/* The spread of an image's luminance: its 95th percentile less its 5th
 * (0 for a uniform image such as an unrendered buffer). */
static double luminance_spread(const image *im)
{
    int hist[256] = {0}, n = im->w * im->h;
    for (int y = 0; y < im->h; y++)
        for (int x = 0; x < im->w; x++) hist[(int)(image_luminance(im, x, y) * 255.0f + 0.5f)]++;
    int lo = -1, hi = -1, seen = 0;
    for (int v = 0; v < 256; v++) {
        seen += hist[v];
        if (lo < 0 && seen > n / 20) lo = v;
        if (hi < 0 && seen >= n - n / 20) hi = v;
    }
    return (hi - lo) / 255.0;
}

/* With DISPLAY unset each window program falls back to OSMesa; the frame
 * it writes must be the rendered sky, not the untouched (black) buffer. */
TEST(headless_frames_are_rendered)
{
    static const char *const progs[] = {"sky-demo", "sky-game"};
    for (size_t k = 0; k < sizeof progs / sizeof progs[0]; k++) {
        char path[512], cmd[2048], log[4096], png[256];
        tmp("headless.png", png, sizeof png);
        remove(png);
        snprintf(cmd, sizeof cmd, "env -u DISPLAY -u WAYLAND_DISPLAY %s --size 320x180 --preset noon --screenshot %s 2>&1",
                 bin_path(progs[k], path, sizeof path), png);
        int rc = run_command(cmd, log, sizeof log);
        image im;
        if (rc != 0 || image_load_png(png, &im)) {
            CHECK(0, "%s headless: exit %d: %s", progs[k], rc, log);
            continue;
        }
        double mean = 0.0;
        for (int y = 0; y < im.h; y++)
            for (int x = 0; x < im.w; x++) mean += image_luminance(&im, x, y);
        mean /= (double)im.w * im.h;
        double spread = luminance_spread(&im);
        NOTE("%s headless, noon: mean luminance %.3f, 5-95 %% spread %.3f", progs[k], mean, spread);
        CHECK(mean > 0.2 && spread > 0.05, "%s renders a noon sky headless, not a uniform buffer", progs[k]);
        image_free(&im);
        remove(png);
    }
}

/* Outside the source tree (a temporary directory, no build/ in it) the
 * headless sky-demo writes sky.png in the current directory, or --out's
 * file. */
TEST(headless_demo_writes_where_asked)
{
    char rel[512], bin[PATH_MAX], dir[256], cmd[PATH_MAX + 1024], log[4096], png[600];
    if (!realpath(bin_path("sky-demo", rel, sizeof rel), bin)) {
        CHECK(0, "no %s", rel);
        return;
    }
    tmp("elsewhere", dir, sizeof dir);
    snprintf(cmd, sizeof cmd, "rm -rf %s && mkdir %s", dir, dir);
    CHECK(run_command(cmd, log, sizeof log) == 0, "mkdir %s: %s", dir, log);
    static const char *const outs[2] = {"", "--out named.png"};
    static const char *const files[2] = {"sky.png", "named.png"};
    for (int k = 0; k < 2; k++) {
        snprintf(cmd, sizeof cmd, "cd %s && env -u DISPLAY -u WAYLAND_DISPLAY %s --size 64x36 %s 2>&1", dir, bin, outs[k]);
        int rc = run_command(cmd, log, sizeof log);
        snprintf(png, sizeof png, "%s/%s", dir, files[k]);
        image im;
        int loaded = image_load_png(png, &im) == 0;
        CHECK(rc == 0 && loaded && im.w == 64 && im.h == 36, "sky-demo %s in %s: exit %d, %s %s: %s", outs[k], dir,
              rc, files[k], loaded ? "written" : "missing", log);
        if (loaded) image_free(&im);
    }
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    run_command(cmd, NULL, 0);
    /* make run's script writes build/sky.png, or SKY_RUN_OUT's file: the
     * test's own, so the picture make run left is not replaced */
    struct stat before, after;
    int had = stat("build/sky.png", &before) == 0;
    tmp("run.png", png, sizeof png);
    remove(png);
    snprintf(cmd, sizeof cmd, "env -u DISPLAY -u WAYLAND_DISPLAY SKY_RUN_OUT=%s sh tools/run.sh --size 48x27 2>&1", png);
    int rc = run_command(cmd, log, sizeof log);
    image im;
    int loaded = image_load_png(png, &im) == 0;
    CHECK(rc == 0 && loaded && im.w == 48, "tools/run.sh headless: exit %d, %s %s: %s", rc, png,
          loaded ? "written" : "missing", log);
    int kept = had ? stat("build/sky.png", &after) == 0 && after.st_mtime == before.st_mtime &&
                         after.st_size == before.st_size
                   : stat("build/sky.png", &after) != 0;
    CHECK(kept, "tools/run.sh with SKY_RUN_OUT left build/sky.png as it was");
    remove(png);
    if (loaded) image_free(&im);
}

/* xvfb-run is there (make's deps step installs it; a machine without it
 * skips the window tests that use this). */
static int have_xvfb(void) { return run_command("command -v xvfb-run >/dev/null 2>&1", NULL, 0) == 0; }

/* A screenshot that cannot be written is a failure a script must see:
 * exit status 1 and the message, in a window and headless. */
SLOW_TEST(unwritable_screenshot_fails)
{
    if (!have_xvfb()) {
        SKIP("xvfb-run is not installed");
        return;
    }
    static const char *const runs[][2] = {
        {XVFB, "sky-demo"}, {XVFB, "sky-game"}, {"env -u DISPLAY -u WAYLAND_DISPLAY ", "sky-demo"},
        {"env -u DISPLAY -u WAYLAND_DISPLAY ", "sky-game"}};
    for (size_t k = 0; k < sizeof runs / sizeof runs[0]; k++) {
        char path[512], cmd[2048], log[4096];
        snprintf(cmd, sizeof cmd, "%s%s --size 64x36 --frames 1 --screenshot /nonexistent/x.png 2>&1", runs[k][0],
                 bin_path(runs[k][1], path, sizeof path));
        int rc = run_command(cmd, log, sizeof log);
        CHECK(rc == 1 && strstr(log, "cannot write /nonexistent/x.png"), "%s: exit %d (want 1): %s", cmd, rc, log);
    }
}

/* Mean absolute difference of two images of one size, over every channel. */
static double mean_abs_diff(const image *a, const image *b)
{
    double d = 0.0;
    size_t n = 3u * (size_t)a->w * (size_t)a->h;
    for (size_t i = 0; i < n; i++) d += fabs(a->px[i] - b->px[i]);
    return d / (double)n;
}

/* sky-game --gl compat asks GLFW for a 2.0 compatibility context, which
 * SKY_GL_COMPAT20 needs, and draws its world there in GLSL 1.10: the same
 * picture as the 3.3 core profile's. */
SLOW_TEST(game_compat_context)
{
    if (!have_xvfb()) {
        SKIP("xvfb-run is not installed");
        return;
    }
    image im[2];
    static const char *const gl[2] = {"core", "compat"};
    for (int k = 0; k < 2; k++) {
        char path[512], cmd[2048], log[4096], png[256];
        tmp(k ? "compat.png" : "core.png", png, sizeof png);
        snprintf(cmd, sizeof cmd, XVFB "%s --size 320x180 --frames 2 --time 0.45 --gl %s --screenshot %s 2>&1",
                 bin_path("sky-game", path, sizeof path), gl[k], png);
        int rc = run_command(cmd, log, sizeof log);
        if (rc != 0 || image_load_png(png, &im[k])) {
            CHECK(0, "sky-game --gl %s under Xvfb: exit %d: %s", gl[k], rc, log);
            if (k) image_free(&im[0]);
            return;
        }
        remove(png);
    }
    double d = mean_abs_diff(&im[0], &im[1]);
    NOTE("sky-game: core and compat pictures differ by %.4f on average", d);
    CHECK(d < 2.0 / 255.0, "the compat profile's picture is the core one's (mean difference %.4f)", d);
    image_free(&im[0]);
    image_free(&im[1]);
}

/* Mean luminance of an image. */
static double mean_luminance(const image *im)
{
    double s = 0.0;
    for (int y = 0; y < im->h; y++)
        for (int x = 0; x < im->w; x++) s += image_luminance(im, x, y);
    return s / ((double)im->w * im->h);
}

/* sky-game renders headless (DISPLAY unset) with these options; returns 0
 * with the image, or -1 after a failed CHECK. */
static int game_headless(const char *args, image *out)
{
    char path[512], cmd[2048], log[4096], png[256];
    tmp("game.png", png, sizeof png);
    snprintf(cmd, sizeof cmd, "env -u DISPLAY -u WAYLAND_DISPLAY %s --size 320x180 %s --out %s 2>&1",
             bin_path("sky-game", path, sizeof path), args, png);
    int rc = run_command(cmd, log, sizeof log);
    if (rc != 0 || image_load_png(png, out)) {
        CHECK(0, "%s: exit %d: %s", cmd, rc, log);
        return -1;
    }
    remove(png);
    return 0;
}

/* sky-game's --help lists the game's options, not sky-render's; the ones
 * it lists do something, and sky-render's that make no sense for a world
 * (--fisheye, --tone-map) are refused. */
SLOW_TEST(game_options_are_its_own)
{
    char path[512], cmd[1024], log[8192];
    snprintf(cmd, sizeof cmd, "%s --help 2>&1", bin_path("sky-game", path, sizeof path));
    int rc = run_command(cmd, log, sizeof log);
    CHECK(rc == 0 && strstr(log, "usage: sky-game"), "sky-game --help: exit %d: %s", rc, log);
    static const char *const listed[] = {"--screenshot", "--out FILE.png", "--gl auto|core|compat", "--seconds",
                                         "--exposure", "--preset"};
    for (size_t k = 0; k < sizeof listed / sizeof listed[0]; k++)
        CHECK(strstr(log, listed[k]) != NULL, "sky-game --help lists %s", listed[k]);
    static const char *const absent[] = {"--fisheye", "--tone-map", "--out-pfm", "--stats"};
    for (size_t k = 0; k < sizeof absent / sizeof absent[0]; k++)
        CHECK(strstr(log, absent[k]) == NULL, "sky-game --help does not list %s", absent[k]);
    static const char *const refused[] = {"--fisheye", "--tone-map filmic"};
    for (size_t k = 0; k < sizeof refused / sizeof refused[0]; k++) {
        snprintf(cmd, sizeof cmd, "env -u DISPLAY %s %s --size 64x36 --out /dev/null 2>&1", path, refused[k]);
        rc = run_command(cmd, log, sizeof log);
        CHECK(rc == 2, "sky-game %s: exit %d (want 2): %s", refused[k], rc, log);
    }
    /* --seconds moves the clouds; --exposure brightens the frame */
    image base, later, darker;
    if (game_headless("--time 0.45 --speed 1", &base)) return;
    if (!game_headless("--time 0.45 --speed 1 --seconds 600", &later)) {
        double d = mean_abs_diff(&base, &later);
        NOTE("--seconds 600: the frame changes by %.4f on average", d);
        CHECK(d > 2.0 / 255.0, "--seconds moves the clouds (mean difference %.4f)", d);
        image_free(&later);
    }
    if (!game_headless("--time 0.45 --speed 1 --exposure -1", &darker)) {
        double a = mean_luminance(&base), b = mean_luminance(&darker);
        NOTE("--exposure -1: mean luminance %.3f against %.3f", b, a);
        CHECK(b < a - 0.05, "--exposure -1 darkens sky and world (%.3f against %.3f)", b, a);
        image_free(&darker);
    }
    image_free(&base);
}

/* sky-game's ground in the clouds' shadows: seen from 300 m up (--eye)
 * under a cloudy sky they darken patches of it, which move on in a minute,
 * where a clear sky lights the plain evenly; a height out of range is
 * refused. */
static double ground_spread(const image *im)
{
    /* the spread of the ground's luminance below the horizon band */
    double sum = 0.0, sum2 = 0.0;
    int n = 0;
    for (int y = im->h / 2; y < im->h; y++)
        for (int x = 0; x < im->w; x++) {
            const float *p = im->px + 3 * (y * im->w + x);
            double l = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
            sum += l, sum2 += l * l, n++;
        }
    double mean = sum / n;
    return sqrt(fmax(sum2 / n - mean * mean, 0.0));
}

SLOW_TEST(game_cloud_shadows_from_above)
{
    static const char *const view = "--time 0.45 --eye 300 --pitch -18";
    char args[256];
    image clear, cloudy, later;
    snprintf(args, sizeof args, "%s --weather clear", view);
    if (game_headless(args, &clear)) return;
    snprintf(args, sizeof args, "%s --weather cloudy", view);
    if (game_headless(args, &cloudy)) {
        image_free(&clear);
        return;
    }
    snprintf(args, sizeof args, "%s --weather cloudy --seconds 60", view);
    if (!game_headless(args, &later)) {
        double a = ground_spread(&clear), b = ground_spread(&cloudy), moved = mean_abs_diff(&cloudy, &later);
        NOTE("the ground's spread of luminance: clear %.4f, cloudy %.4f; a minute on it changes by %.4f", a, b, moved);
        CHECK(b > 3.0 * a && b > 0.02, "cloud shadows pattern the ground (%.4f against clear's %.4f)", b, a);
        CHECK(moved > 2.0 / 255.0, "and move on (%.4f)", moved);
        image_free(&later);
    }
    image_free(&clear);
    image_free(&cloudy);
    char path[512], cmd[1024], log[1024];
    snprintf(cmd, sizeof cmd, "env -u DISPLAY %s --eye 0.1 --size 64x36 --out /dev/null 2>&1",
             bin_path("sky-game", path, sizeof path));
    int rc = run_command(cmd, log, sizeof log);
    CHECK(rc == 2 && strstr(log, "--eye"), "--eye 0.1: exit %d (want 2): %s", rc, log);
}

/* Mean colour of a region (x0 <= x < x1, y0 <= y < y1). */
static void region_mean(const image *im, int x0, int y0, int x1, int y1, double rgb[3])
{
    rgb[0] = rgb[1] = rgb[2] = 0.0;
    for (int y = y0; y < y1; y++)
        for (int x = x0; x < x1; x++)
            for (int c = 0; c < 3; c++) rgb[c] += im->px[3 * (y * im->w + x) + c];
    for (int c = 0; c < 3; c++) rgb[c] /= (double)(x1 - x0) * (y1 - y0);
}

static double colour_distance(const double a[3], const double b[3])
{
    return fabs(a[0] - b[0]) + fabs(a[1] - b[1]) + fabs(a[2] - b[2]);
}

/* Aerial perspective: the hills 2 to 20 km away (stone like the boxes
 * by the eye, their sunlit faces turned to it) fade into the sky behind
 * them the farther they are (sky_aerial_apply in the game's shader),
 * while a box 40 m away keeps its colour. Each hill is sampled where the
 * game's camera projects a point on its face, the sky just above its
 * top. */
TEST(game_fog_grows_with_distance)
{
    image im;
    if (game_headless("--time 0.45", &im)) return;
    /* demo/game.c's: the eye 1.7 m up, looking south (+z) 20 degrees up;
     * a point on the face of the box 40 m away, of each hill, and the
     * sky 1 degree above each */
    static const double points[7][3] = {{-12, 3, 36},        {-1064, 40, 1880},    {2906, 120, 3700},
                                        {-5086, 200, 6600},  {9562, 300, 10300},   {-1312, 1390, 13800},
                                        {2811, 1926, 18200}};
    static const double tops[7] = {6, 90, 260, 420, 700, 2000, 2500};
    float view[16], proj[16];
    sky_cli_camera_at(180.0, 20.0, 60.0, im.w, im.h, view, proj);
    double colour[7][3], above[7][3], fade[7];
    for (int k = 0; k < 7; k++)
        for (int which = 0; which < 2; which++) {
            /* relative to the eye; the sky 1 degree above the top, at the same bearing */
            double dist = hypot(points[k][0], points[k][2]);
            double p[3] = {points[k][0], which ? tops[k] - 1.7 + dist * tan(M_PI / 180.0) : points[k][1] - 1.7,
                           points[k][2]};
            /* eye space, then clip space */
            double e[4], clip[4];
            for (int r = 0; r < 4; r++) e[r] = view[12 + r] + view[r] * p[0] + view[4 + r] * p[1] + view[8 + r] * p[2];
            for (int r = 0; r < 4; r++)
                clip[r] = proj[r] * e[0] + proj[4 + r] * e[1] + proj[8 + r] * e[2] + proj[12 + r] * e[3];
            int x = (int)((clip[0] / clip[3] * 0.5 + 0.5) * im.w), y = (int)((0.5 - clip[1] / clip[3] * 0.5) * im.h);
            if (x < 1 || x >= im.w - 1 || y < 1 || y >= im.h - 1) {
                CHECK(0, "point %d projects outside the frame (%d, %d)", k, x, y);
                image_free(&im);
                return;
            }
            region_mean(&im, x - 1, y - 1, x + 2, y + 2, which ? above[k] : colour[k]);
        }
    for (int k = 0; k < 7; k++) {
        fade[k] = colour_distance(colour[k], above[k]);
        NOTE("%s %5.0f m: %.3f %.3f %.3f, the sky above it %.3f %.3f %.3f: %.3f apart", k ? "hill" : "box ",
             hypot(points[k][0], points[k][2]), colour[k][0], colour[k][1], colour[k][2], above[k][0], above[k][1],
             above[k][2], fade[k]);
        if (k) CHECK(fade[k] < fade[k - 1], "the hill %d is no nearer the sky's colour than the one before (%.3f, %.3f)",
                     k, fade[k], fade[k - 1]);
    }
    CHECK(fade[6] < 0.5 * fade[0], "the farthest hill has faded at least half way into the sky (%.3f from it, the "
          "near box %.3f)", fade[6], fade[0]);
    image_free(&im);
}

/* Under the full moon of the moonlit preset, a wall facing the eye (and
 * away from the moon) is lit by the sky and the moonlit ground at the
 * sky's exposure: darker than the sky behind it, as a silhouette, but not
 * black (it was: lit by the sky's ambient alone, it fell below the tone
 * curve's toe). */
TEST(game_walls_seen_at_night)
{
    image im;
    if (game_headless("--preset moonlit --yaw 180 --pitch 20", &im)) return;
    /* 320x180: the face of the tall box on the left, and the sky beside it
     * just above the horizon (row 146.7) */
    double wall[3], sky_beside[3];
    region_mean(&im, 90, 120, 118, 145, wall);
    region_mean(&im, 0, 120, 55, 140, sky_beside);
    double w = 0.2126 * wall[0] + 0.7152 * wall[1] + 0.0722 * wall[2];
    double s = 0.2126 * sky_beside[0] + 0.7152 * sky_beside[1] + 0.0722 * sky_beside[2];
    NOTE("moonlit: wall %.1f, sky beside it %.1f (8-bit luma)", 255.0 * w, 255.0 * s);
    CHECK(w > 0.1 * s && w < 0.8 * s, "the wall is darker than the sky but not black (%.1f against %.1f of 255)",
          255.0 * w, 255.0 * s);
    image_free(&im);
}

/* sky-demo under Xvfb, 640x360, three frames; keys (--keys) are pressed
 * after the first. The sky below the overlay (rows 180 to 360) into
 * *out, and what sky-demo printed into log. Returns 0, or -1 after a
 * failed CHECK. */
static int demo_sky(const char *args, image *out, char *log, size_t len)
{
    char path[512], cmd[2048], png[256];
    tmp("keys.png", png, sizeof png);
    snprintf(cmd, sizeof cmd, XVFB "%s --size 640x360 --frames 3 --screenshot %s %s 2>&1",
             bin_path("sky-demo", path, sizeof path), png, args);
    int rc = run_command(cmd, log, len);
    image full;
    if (rc != 0 || image_load_png(png, &full)) {
        CHECK(0, "%s: exit %d: %s", cmd, rc, log);
        return -1;
    }
    remove(png);
    out->w = full.w;
    out->h = full.h - 180;
    out->px = malloc(sizeof(float) * 3u * (size_t)out->w * (size_t)out->h);
    memcpy(out->px, full.px + 3 * 180 * full.w, sizeof(float) * 3u * (size_t)out->w * (size_t)out->h);
    image_free(&full);
    return 0;
}

/* A layer toggled off and on again rebuilds the sky; the new sky takes
 * the animation clock where the old one was, so the clouds stay put
 * instead of jumping back to where they were at 0 s. */
SLOW_TEST(demo_rebuild_keeps_the_clock)
{
    if (!have_xvfb()) {
        SKIP("xvfb-run is not installed");
        return;
    }
    char log[4096];
    image kept, rebuilt, at_zero;
    const char *clouds = "--time 0.45 --cover 0.5 --speed 1";
    char args[256];
    snprintf(args, sizeof args, "%s --seconds 300", clouds);
    if (demo_sky(args, &kept, log, sizeof log)) return;
    snprintf(args, sizeof args, "%s --seconds 300 --keys CC", clouds);
    if (demo_sky(args, &rebuilt, log, sizeof log)) {
        image_free(&kept);
        return;
    }
    /* what a clock started over would show: the same scene at 0 s */
    if (demo_sky(clouds, &at_zero, log, sizeof log)) {
        image_free(&kept);
        image_free(&rebuilt);
        return;
    }
    double d_rebuilt = mean_abs_diff(&kept, &rebuilt), d_zero = mean_abs_diff(&kept, &at_zero);
    NOTE("clouds after a rebuild differ by %.4f from the unbroken run; the clock at 0 s by %.4f", d_rebuilt, d_zero);
    CHECK(d_zero > 5.0 / 255.0, "the clouds move in 300 s (%.4f), so the test can see a reset", d_zero);
    CHECK(d_rebuilt < 0.5 / 255.0, "the rebuilt sky shows the clouds where they were (%.4f)", d_rebuilt);
    image_free(&kept);
    image_free(&rebuilt);
    image_free(&at_zero);
    /* and a change of weather goes on through the rebuild: a fifth of a
     * second's change, its last frame the same as the unbroken run's (a
     * change ended at the rebuild would have stopped a frame in) */
    static const char *const change = "--time 0.45 --weather clear --weather-to overcast --weather-seconds 0.2 "
                                      "--seconds 0.05";
    image unbroken, broken;
    snprintf(args, sizeof args, "%s --speed 0", change);
    if (demo_sky(args, &unbroken, log, sizeof log)) return;
    snprintf(args, sizeof args, "%s --speed 0 --keys CC", change);
    if (demo_sky(args, &broken, log, sizeof log)) {
        image_free(&unbroken);
        return;
    }
    double d_change = mean_abs_diff(&unbroken, &broken);
    NOTE("mid-change, the rebuilt sky differs by %.4f from the unbroken run", d_change);
    CHECK(d_change < 0.5 / 255.0, "the change of weather goes on through the rebuild (%.4f)", d_change);
    image_free(&unbroken);
    image_free(&broken);
}

/* The A key's first press goes to the next real path (the default path
 * is the gradient), five presses come back round, and the demo names the
 * path on screen. */
SLOW_TEST(demo_atmosphere_key)
{
    if (!have_xvfb()) {
        SKIP("xvfb-run is not installed");
        return;
    }
    char log[4096];
    image none, once, five;
    if (demo_sky("--time 0.45", &none, log, sizeof log)) return;
    CHECK(strstr(log, "sky-demo: atmosphere gradient") != NULL, "the default path is named gradient: %s", log);
    if (demo_sky("--time 0.45 --keys A", &once, log, sizeof log)) {
        image_free(&none);
        return;
    }
    CHECK(strstr(log, "sky-demo: atmosphere preetham") != NULL, "one press: preetham: %s", log);
    if (demo_sky("--time 0.45 --keys AAAAA", &five, log, sizeof log)) {
        image_free(&none);
        image_free(&once);
        return;
    }
    CHECK(strstr(log, "sky-demo: atmosphere gradient") != NULL, "five presses: gradient again: %s", log);
    double d1 = mean_abs_diff(&none, &once), d5 = mean_abs_diff(&none, &five);
    NOTE("the sky after one press differs by %.4f, after five by %.4f", d1, d5);
    CHECK(d1 > 5.0 / 255.0, "the first press changes the sky (%.4f)", d1);
    CHECK(d5 < 0.5 / 255.0, "five presses bring the same sky back (%.4f)", d5);
    image_free(&none);
    image_free(&once);
    image_free(&five);
}

/* --out, like --screenshot, takes only a name ending in .png (any case):
 * anything else is a bad argument naming it, exit 2, before rendering. */
TEST(headless_out_must_be_png)
{
    static const char *const progs[2] = {"sky-demo", "sky-game"};
    for (int p = 0; p < 2; p++) {
        char path[512], cmd[1024], log[2048];
        bin_path(progs[p], path, sizeof path);
        snprintf(cmd, sizeof cmd, "env -u DISPLAY -u WAYLAND_DISPLAY %s --size 8x8 --out /nonexistent-dir/x.jpg 2>&1", path);
        int rc = run_command(cmd, log, sizeof log);
        CHECK(rc == 2 && strstr(log, "--out") && strstr(log, ".png"), "%s --out x.jpg: exit %d (want 2): %s",
              progs[p], rc, log);
        snprintf(cmd, sizeof cmd, "env -u DISPLAY -u WAYLAND_DISPLAY %s --size 8x8 --out /nonexistent-dir/X.PNG 2>&1", path);
        rc = run_command(cmd, log, sizeof log);
        CHECK(rc == 1 && strstr(log, "cannot write"), "%s --out X.PNG is taken (then cannot be written): exit %d: %s",
              progs[p], rc, log);
    }
}

/* --gl es20 opens an OpenGL ES 2.0 window (GLX's ES profile under Xvfb)
 * and the sky in it is COMPAT20's. */
SLOW_TEST(demo_es20_window)
{
    if (!have_xvfb()) {
        SKIP("xvfb-run is not installed");
        return;
    }
    char log[4096];
    image es, gl2;
    if (demo_sky("--gl es20 --time 0.45 --cover 0.4", &es, log, sizeof log)) return;
    CHECK(strstr(log, "trying OpenGL 2.0") == NULL, "an ES 2.0 window opened: %s", log);
    if (demo_sky("--gl compat --time 0.45 --cover 0.4", &gl2, log, sizeof log)) {
        image_free(&es);
        return;
    }
    double d = mean_abs_diff(&es, &gl2);
    NOTE("the ES 2.0 window's sky differs from the OpenGL 2.0 window's by %.5f", d);
    CHECK(d < 1.0 / 255.0, "the same sky in both windows (%.5f)", d);
    image_free(&es);
    image_free(&gl2);
}
