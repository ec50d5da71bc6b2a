/*
 * The browser build (make web), as a visitor's browser runs it: Debian's
 * headless Chromium with WebGL 1 through SwiftShader (ANGLE), the page
 * served from 127.0.0.1, its console on Chromium's stderr and its picture
 * from Chromium's screenshot. The page is build/web/index.html; its
 * address takes sky-demo's options (?args=...) and a preset to pick from
 * its menu once the sky runs (?switch=NAME).
 */
#include "test.h"

#include <math.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

enum { PAGE_W = 1280, PAGE_H = 800, BAR_H = 50 }; /* the menu's bar above the canvas */

/* The page's server: python3's, for the test's duration. */
static pid_t server;
static int port;

static int serve(void)
{
    if (server > 0) return 0;
    const char *dir = getenv("SKY_WEB") ? getenv("SKY_WEB") : "build/web";
    port = 18000 + (int)(getpid() % 2000);
    char portarg[16];
    snprintf(portarg, sizeof portarg, "%d", port);
    server = fork();
    if (server == 0) {
        freopen("/dev/null", "w", stderr);
        freopen("/dev/null", "w", stdout);
        execlp("python3", "python3", "-m", "http.server", portarg, "--bind", "127.0.0.1", "--directory", dir,
               (char *)NULL);
        _exit(127);
    }
    if (server < 0) return -1;
    /* until it answers */
    char cmd[256], out[256];
    snprintf(cmd, sizeof cmd, "python3 -c \"import urllib.request as u; u.urlopen('http://127.0.0.1:%d/index.html')\" 2>&1",
             port);
    for (int i = 0; i < 50; i++) {
        if (run_command(cmd, out, sizeof out) == 0) return 0;
        usleep(100000);
    }
    return -1;
}

static void stop_serving(void)
{
    if (server > 0) {
        kill(server, SIGTERM);
        waitpid(server, NULL, 0);
        server = 0;
    }
}

/* The page at query, in a fresh headless Chromium: its screenshot into
 * *shot (the canvas below the bar), its console lines into console.
 * Returns 0, or -1 after a failed CHECK. */
static int visit(const char *query, image *shot, char *console, size_t len)
{
    if (serve()) {
        CHECK(0, "the page's server on 127.0.0.1 did not answer");
        return -1;
    }
    /* SKY_WEB_SHOT: the default page's screenshot is kept there (the
     * guide's picture, make screenshots), written beside it first */
    const char *keep = getenv("SKY_WEB_SHOT") && !query[0] ? getenv("SKY_WEB_SHOT") : NULL;
    char png[1024], cmd[2048];
    if (keep)
        snprintf(png, sizeof png, "%s.%d.tmp.png", keep, (int)getpid());
    else
        tmp_path("web.png", png, sizeof png);
    remove(png);
    /* virtual time: the page's frames run until the budget is spent, then
     * the screenshot is taken */
    snprintf(cmd, sizeof cmd,
             "chromium-headless-shell --headless --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader "
             "--enable-logging=stderr --v=0 --window-size=%d,%d --virtual-time-budget=8000 --screenshot=%s "
             "'http://127.0.0.1:%d/index.html%s' 2>&1 | grep CONSOLE",
             PAGE_W, PAGE_H, png, port, query);
    run_command(cmd, console, len);
    image full;
    if (image_load_png(png, &full)) {
        CHECK(0, "no screenshot of %s: %s", query, console);
        return -1;
    }
    if (!keep || rename(png, keep)) remove(png);
    shot->w = full.w;
    shot->h = full.h - BAR_H;
    shot->px = malloc(sizeof(float) * 3u * (size_t)shot->w * (size_t)shot->h);
    memcpy(shot->px, full.px + 3 * BAR_H * full.w, sizeof(float) * 3u * (size_t)shot->w * (size_t)shot->h);
    image_free(&full);
    return 0;
}

/* What the console must not hold: an uncaught exception, the program's
 * stderr (the page logs it as "stderr: ..."), a WebGL error. */
static void console_clean(const char *console, const char *what)
{
    static const char *const bad[] = {"Uncaught", "stderr:", "GL_INVALID", "GL ERROR", "WebGL:", "INVALID_"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        const char *hit = strstr(console, bad[i]);
        CHECK(!hit, "%s: the console has \"%s\": %.200s", what, bad[i], hit ? hit : "");
    }
}

/* Mean of channel c over the canvas rows y0..y1, columns 400..1200 (clear
 * of the overlay's panels). */
static double region_mean(const image *im, int c, int y0, int y1)
{
    double sum = 0.0;
    int n = 0;
    for (int y = y0; y < y1 && y < im->h; y++)
        for (int x = 400; x < 1200 && x < im->w; x++, n++) sum += im->px[3 * (y * im->w + x) + c];
    return n ? sum / n : 0.0;
}

static double spread(const image *im)
{
    double lo = 1e9, hi = -1e9;
    for (int y = 220; y < im->h - 60; y += 7)
        for (int x = 400; x < 1200; x += 7) {
            double l = im->px[3 * (y * im->w + x) + 1];
            lo = fmin(lo, l);
            hi = fmax(hi, l);
        }
    return hi - lo;
}

static double mean_abs_diff(const image *a, const image *b)
{
    double sum = 0.0;
    size_t n = 0;
    for (int y = 220; y < a->h && y < b->h; y++)
        for (int x = 400; x < 1200; x++, n += 3)
            for (int c = 0; c < 3; c++) sum += fabs(a->px[3 * (y * a->w + x) + c] - b->px[3 * (y * b->w + x) + c]);
    return n ? sum / (double)n : 0.0;
}

TEST(web_page_shows_a_sky)
{
    char console[8192];
    image im;
    if (visit("", &im, console, sizeof console)) return;
    NOTE("%.*s", (int)strcspn(console, "\n"), console);
    CHECK(strstr(console, "sky-demo: running in OpenGL ES 2.0 (WebGL 1.0") != NULL,
          "the page runs the sky in a WebGL 1 context: %.300s", console);
    console_clean(console, "the default page");
    double r = region_mean(&im, 0, 220, 420), g = region_mean(&im, 1, 220, 420), b = region_mean(&im, 2, 220, 420);
    NOTE("the canvas's sky: mean RGB %.3f %.3f %.3f, spread %.3f", r, g, b, spread(&im));
    CHECK(b > r * 1.05 && b > 0.3, "a blue day sky (R %.3f, B %.3f)", r, b);
    CHECK(spread(&im) > 0.05, "not a uniform canvas (spread %.3f)", spread(&im));
    image_free(&im);
}

/* sky-demo's --drag test hook, through the page's address: the cover
 * slider dragged from 0.1 to 0.9 covers the sky. */
TEST(web_drag_changes_the_frame)
{
    char console[8192];
    image before, after;
    if (visit("?args=--cover%200.1%20--time%200.45", &before, console, sizeof console)) return;
    console_clean(console, "cover 0.1");
    if (visit("?args=--cover%200.1%20--time%200.45%20--drag%20cover:0.1:0.9", &after, console, sizeof console)) {
        image_free(&before);
        return;
    }
    console_clean(console, "the cover dragged");
    double d = mean_abs_diff(&before, &after);
    double b0 = region_mean(&before, 2, 220, 520) - region_mean(&before, 0, 220, 520);
    double b1 = region_mean(&after, 2, 220, 520) - region_mean(&after, 0, 220, 520);
    NOTE("dragging cover 0.1 -> 0.9 changes the frame by %.4f; blue over red %.3f -> %.3f", d, b0, b1);
    CHECK(d > 10.0 / 255.0, "the drag changes the frame (%.4f)", d);
    CHECK(b1 < 0.7 * b0, "the sky is covered: less blue over red (%.3f -> %.3f)", b0, b1);
    image_free(&before);
    image_free(&after);
}

/* The preset menu: switching from noon to starry gives a dark sky with
 * stars in it: its green no brighter than the moonless night's brightest
 * channel may be (40 of 255, docs/DUSK.md's target; noon's is about 0.7). */
TEST(web_preset_switch)
{
    char console[8192];
    image im;
    if (visit("?switch=starry", &im, console, sizeof console)) return;
    console_clean(console, "the preset switch");
    CHECK(strstr(console, "sky-demo: preset starry") != NULL, "the menu picked starry: %.300s", console);
    double mean = region_mean(&im, 1, 60, 500);
    int stars = 0;
    for (int y = 60; y < 500; y++)
        for (int x = 400; x < 1200; x++) stars += im.px[3 * (y * im.w + x) + 1] > mean + 0.25;
    NOTE("starry: mean green %.3f, %d star pixels", mean, stars);
    CHECK(mean < 40.0 / 255.0, "a night sky after the switch (mean %.3f)", mean);
    CHECK(stars > 30, "stars in it (%d bright pixels)", stars);
    image_free(&im);
    stop_serving();
}
