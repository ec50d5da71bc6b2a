/*
 * The engine examples (examples/), run as an integrator would see them:
 * each under an X server (make test-examples runs this runner under Xvfb),
 * headless with --frames and --screenshot, through the options and output
 * lines of examples/README.md. What is checked is what libsky promises a
 * host: the sky above and the host's scene below with not one scene pixel
 * changed, the sun where sky_get_lighting puts it through the engine's own
 * camera, a left-handed engine's own matrices giving the right-handed
 * picture, and the same frame in every depth convention and drawing order.
 */
#include "test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <stb/stb_image.h>

static const char *const examples[3] = {"sky-sdl2", "sky-osg", "sky-irrlicht"};

/* One run of an example: its output lines and its screenshot (RGB, rows
 * top first), or rc != 0 and the log. */
typedef struct run {
    int rc;
    char log[4096];
    int w, h;
    unsigned char *px;
    int has_sun;
    double sun_x, sun_y;
    int drawn; /* the last sky_draw's result */
} run;

static void run_example(const char *name, const char *options, run *r)
{
    const char *dir = getenv("SKY_EXAMPLES");
    char shot[256], cmd[1024];
    memset(r, 0, sizeof *r);
    snprintf(shot, sizeof shot, "/tmp/sky-example-%d.png", (int)getpid());
    remove(shot);
    snprintf(cmd, sizeof cmd, "%s/%s --frames 3 --screenshot %s %s 2>&1", dir ? dir : "build/examples", name, shot,
             options);
    r->rc = run_command(cmd, r->log, sizeof r->log);
    int w = 0, h = 0;
    const char *line = strstr(r->log, "size ");
    if (line) sscanf(line, "size %d %d", &w, &h);
    line = strstr(r->log, "sun_pixel ");
    r->has_sun = line && sscanf(line, "sun_pixel %lf %lf", &r->sun_x, &r->sun_y) == 2;
    line = strstr(r->log, "sky_draw ");
    if (!line || sscanf(line, "sky_draw %d", &r->drawn) != 1) r->drawn = -100;
    int comp = 0;
    if (r->rc == 0) r->px = stbi_load(shot, &r->w, &r->h, &comp, 3);
    remove(shot);
    if (r->rc == 0 && (!r->px || r->w != w || r->h != h)) {
        r->rc = -1;
        snprintf(r->log, sizeof r->log, "%s: no screenshot of %dx%d (size line %dx%d)", name, r->w, r->h, w, h);
    }
}

static void run_free(run *r)
{
    stbi_image_free(r->px);
    r->px = NULL;
}

/* A run that must succeed: checks it and says so; 0 if it did not. */
static int ran(const char *name, const char *options, run *r)
{
    run_example(name, options, r);
    CHECK(r->rc == 0, "%s %s ran and wrote its screenshot (exit %d): %.600s", name, options, r->rc, r->log);
    return r->rc == 0;
}

static int max_difference(const run *a, const run *b, int *differing)
{
    int most = 0;
    *differing = 0;
    for (size_t i = 0; i < (size_t)a->w * (size_t)a->h * 3; i++) {
        int d = abs((int)a->px[i] - (int)b->px[i]);
        if (d > most) most = d;
        *differing += d > 0;
    }
    return most;
}

/* Noon-ish, some cloud: the frame with the sky and the engine's own frame
 * (--no-sky, cleared to black). Every pixel the engine's scene drew is
 * the same in both; the scene fills the bottom of the frame; the top
 * rows are sky: not the clear colour, bright and bluish on average. */
static void sky_above_scene_below(const char *name)
{
    run with, own;
    if (!ran(name, "--time 0.45", &with) || !ran(name, "--time 0.45 --no-sky", &own)) goto done;
    CHECK(with.w == own.w && with.h == own.h, "both frames %dx%d", with.w, with.h);
    int w = with.w, h = with.h, scene_px = 0, changed = 0, bottom = 0, top = 0;
    double top_r = 0, top_b = 0, top_sum = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            const unsigned char *o = own.px + ((size_t)y * w + x) * 3, *s = with.px + ((size_t)y * w + x) * 3;
            int is_scene = (o[0] | o[1] | o[2]) != 0;
            scene_px += is_scene;
            changed += is_scene && (o[0] != s[0] || o[1] != s[1] || o[2] != s[2]);
            bottom += is_scene && y >= h * 9 / 10;
            if (y < h / 5) {
                top += is_scene;
                top_r += s[0];
                top_b += s[2];
                top_sum += s[0] + s[1] + s[2];
            }
        }
    int top_px = w * (h / 5);
    CHECK(changed == 0, "%s: the sky changed %d of the scene's %d pixels", name, changed, scene_px);
    CHECK(bottom == w * (h - h * 9 / 10), "%s: the scene fills the bottom tenth (%d of %d pixels)", name, bottom,
          w * (h - h * 9 / 10));
    CHECK(top == 0, "%s: no scene in the top fifth (%d pixels)", name, top);
    CHECK(top_b > top_r * 1.05 && top_sum / (3.0 * top_px) > 100.0,
          "%s: the top fifth is daylit sky (mean R %.0f, B %.0f, level %.0f)", name, top_r / top_px, top_b / top_px,
          top_sum / (3.0 * top_px));
    NOTE("%s: %d scene pixels, none changed by the sky", name, scene_px);
done:
    run_free(&with);
    run_free(&own);
}

/* The sun's disc: the centroid of the near-white pixels (the scenes have
 * none); pixel centres at +0.5. Returns their count. */
static int sun_disc(const run *r, double *cx, double *cy)
{
    double sx = 0, sy = 0;
    int n = 0;
    for (int y = 0; y < r->h; y++)
        for (int x = 0; x < r->w; x++) {
            const unsigned char *p = r->px + ((size_t)y * r->w + x) * 3;
            if (p[0] >= 250 && p[1] >= 250 && p[2] >= 250) {
                sx += x + 0.5;
                sy += y + 0.5;
                n++;
            }
        }
    *cx = n ? sx / n : -1;
    *cy = n ? sy / n : -1;
    return n;
}

/* Mid-morning, clear, the camera turned so the sun stands left of the
 * centre: the disc's centre is within 2 px of where the example's engine
 * camera puts sky_get_lighting's sun direction. */
static void sun_where_lighting_says(const char *name)
{
    run r;
    if (!ran(name, "--time 0.35 --cover 0 --face-sun", &r)) goto done;
    double cx, cy;
    int n = sun_disc(&r, &cx, &cy);
    CHECK(r.has_sun, "%s reports the sun's pixel: %.300s", name, r.log);
    CHECK(n >= 20 && n < 5000, "%s: a sun disc of %d near-white pixels", name, n);
    if (r.has_sun && n) {
        double off = hypot(cx - r.sun_x, cy - r.sun_y);
        CHECK(off <= 2.0, "%s: the disc at (%.2f, %.2f), the camera's sun at (%.2f, %.2f): %.2f px apart", name, cx,
              cy, r.sun_x, r.sun_y, off);
        CHECK(r.sun_x < r.w * 0.5, "%s: the sun left of the centre as --face-sun turns it (x %.1f)", name, r.sun_x);
        NOTE("%s: disc (%.2f, %.2f), camera (%.2f, %.2f): %.2f px", name, cx, cy, r.sun_x, r.sun_y, off);
    }
done:
    run_free(&r);
}

TEST(examples_sdl2_sky_above_scene_below) { sky_above_scene_below(examples[0]); }
TEST(examples_osg_sky_above_scene_below) { sky_above_scene_below(examples[1]); }
TEST(examples_irrlicht_sky_above_scene_below) { sky_above_scene_below(examples[2]); }
TEST(examples_sdl2_sun_where_lighting_says) { sun_where_lighting_says(examples[0]); }
TEST(examples_osg_sun_where_lighting_says) { sun_where_lighting_says(examples[1]); }
TEST(examples_irrlicht_sun_where_lighting_says) { sun_where_lighting_says(examples[2]); }

/* Irrlicht's own left-handed matrices with a reflecting horizon_to_world
 * give the picture that right-handed matrices with the identity give;
 * its own matrices with the identity give a mirror image and the
 * warning. */
TEST(examples_irrlicht_left_handed)
{
    static const char *const base = "--time 0.35 --cover 0.3 --face-sun";
    char opts[256];
    run own, right, mirrored;
    int ok = ran(examples[2], base, &own);
    snprintf(opts, sizeof opts, "%s --right-handed", base);
    ok &= ran(examples[2], opts, &right);
    snprintf(opts, sizeof opts, "%s --no-reflection", base);
    ok &= ran(examples[2], opts, &mirrored);
    if (ok) {
        int differing, most = max_difference(&own, &right, &differing);
        CHECK(most <= 1, "own matrices + reflection vs right-handed: %d channels differ, by up to %d", differing, most);
        CHECK(own.drawn == 0 && right.drawn == 0, "both draw without a warning (%d, %d)", own.drawn, right.drawn);
        CHECK(mirrored.drawn == 2, "own matrices, no reflection: SKY_WARN_MIRRORED (2), got %d", mirrored.drawn);
        (void)max_difference(&own, &mirrored, &differing);
        CHECK(differing > own.w * own.h / 10, "and its sky is another picture (%d channels differ)", differing);
    }
    run_free(&own);
    run_free(&right);
    run_free(&mirrored);
}

/* The SDL2 host in the three depth conventions, the sky drawn first and
 * drawn after its scene: each frame keeps every pixel of its scene (the
 * same options with --no-sky), and its sky pixels are those of the
 * far-one, sky-after frame. (The scenes themselves may differ by a pixel
 * where two of their surfaces meet: the conventions' depth precision
 * differs, and that is the host's depth test, not the sky.) */
TEST(examples_sdl2_depth_conventions)
{
    static const char *const modes[6] = {"--depth far-one",   "--depth far-one --sky-first",
                                         "--depth reversed-z", "--depth reversed-z --sky-first",
                                         "--depth reversed-z-clip01", "--depth reversed-z-clip01 --sky-first"};
    run first, first_own, r, own;
    int ok = ran(examples[0], "--time 0.45 --depth far-one", &first);
    ok &= ran(examples[0], "--time 0.45 --depth far-one --no-sky", &first_own);
    for (int m = 0; ok && m < 6; m++) {
        char opts[128];
        snprintf(opts, sizeof opts, "--time 0.45 %s", modes[m]);
        run_example(examples[0], opts, &r);
        if (r.rc == 3) { /* no glClipControl: said, and not counted */
            NOTE("%s: %.200s", modes[m], r.log);
            continue;
        }
        CHECK(r.rc == 0, "%s ran (exit %d): %.400s", modes[m], r.rc, r.log);
        snprintf(opts, sizeof opts, "--time 0.45 %s --no-sky", modes[m]);
        if (r.rc == 0 && ran(examples[0], opts, &own)) {
            int scene_changed = 0, sky_differs = 0, sky_px = 0;
            for (size_t i = 0; i < (size_t)r.w * (size_t)r.h; i++) {
                const unsigned char *o = own.px + i * 3, *p = r.px + i * 3, *f = first.px + i * 3;
                const unsigned char *fo = first_own.px + i * 3;
                if (o[0] | o[1] | o[2]) {
                    scene_changed += memcmp(o, p, 3) != 0;
                } else if (!(fo[0] | fo[1] | fo[2])) { /* sky in both */
                    sky_px++;
                    sky_differs += memcmp(f, p, 3) != 0;
                }
            }
            CHECK(scene_changed == 0, "%s: %d of the scene's pixels changed by the sky", modes[m], scene_changed);
            CHECK(sky_differs == 0 && sky_px > r.w * r.h / 3,
                  "%s: %d of %d sky pixels differ from the far-one, sky-after frame's", modes[m], sky_differs, sky_px);
            CHECK(r.drawn == 0, "%s: sky_draw returned %d", modes[m], r.drawn);
            run_free(&own);
        }
        run_free(&r);
    }
    run_free(&first);
    run_free(&first_own);
}
