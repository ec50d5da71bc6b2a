/*
 * Render tests: properties of images, never golden files. Linear (HDR)
 * renders are read as luminance in kcd/m^2; LDR renders as 0..1 sRGB.
 */
#include "test.h"
#include "sky_internal.h"
#include "cli.h"

#include <GL/gl.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

/* Largest relative difference of two linear images. */
static double max_rel_diff(const image *a, const image *b)
{
    double worst = 0.0;
    for (size_t i = 0; i < 3u * (size_t)a->w * (size_t)a->h; i++) {
        double d = fabs((double)a->px[i] - b->px[i]) / (fabs((double)b->px[i]) + 1e-6);
        if (d > worst) worst = d;
    }
    return worst;
}

/* Pixels brighter than every 8-neighbour by at least `contrast`: stars.
 * Only inside the fisheye circle (radius 0.95), away from its black rim. */
static int count_point_sources(const image *im, float contrast)
{
    int n = 0;
    double r_max = 0.95 * 0.5 * (im->w < im->h ? im->w : im->h);
    for (int y = 1; y < im->h - 1; y++)
        for (int x = 1; x < im->w - 1; x++) {
            if (hypot(x + 0.5 - 0.5 * im->w, y + 0.5 - 0.5 * im->h) > r_max) continue;
            float c = image_luminance(im, x, y), brightest = 0.0f;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++)
                    if (dx || dy) {
                        float v = image_luminance(im, x + dx, y + dy);
                        if (v > brightest) brightest = v;
                    }
            /* a star is a local maximum standing above the local background */
            float bg = 0.25f * (image_luminance(im, x - 1, y - 1) + image_luminance(im, x + 1, y - 1) +
                                image_luminance(im, x - 1, y + 1) + image_luminance(im, x + 1, y + 1));
            if (c >= brightest && c - bg > contrast) n++;
        }
    return n;
}

static scene sky_only(unsigned features)
{
    scene sc = scene_default();
    sc.cfg.features = features;
    sc.pitch = 45.0; /* nothing but sky in view */
    return sc;
}

TEST(render_cover_zero_has_no_clouds)
{
    scene with = sky_only(SKY_CLOUDS | SKY_SUN), without = sky_only(SKY_SUN);
    with.params.cover = without.params.cover = 0.0f;
    image a, b;
    if (render_scene(&with, 1, SKY_GL_AUTO, &a) || render_scene(&without, 1, SKY_GL_AUTO, &b)) {
        CHECK(0, "render failed");
        return;
    }
    double d = max_rel_diff(&a, &b);
    NOTE("cover 0 vs no cloud layer: max relative difference %.2e", d);
    CHECK(d < 1e-4, "cover 0 must leave no cloud pixel (max relative difference %g)", d);
    image_free(&a);
    image_free(&b);
}

/* Fraction of pixels whose colour differs by more than 5 %. */
static double changed_fraction(const image *a, const image *b)
{
    int changed = 0;
    for (int y = 0; y < a->h; y++)
        for (int x = 0; x < a->w; x++) {
            const float *p = a->px + 3 * ((size_t)y * (size_t)a->w + (size_t)x);
            const float *q = b->px + 3 * ((size_t)y * (size_t)a->w + (size_t)x);
            double dl = 0;
            for (int c = 0; c < 3; c++) dl = fmax(dl, fabs((double)p[c] - q[c]) / (fabs((double)q[c]) + 1e-6));
            changed += dl > 0.05;
        }
    return (double)changed / (a->w * a->h);
}

TEST(render_full_cover_hides_sky)
{
    scene clouds = sky_only(SKY_CLOUDS), clear = sky_only(SKY_FEATURES_NONE);
    clouds.params.cover = 1.0f;
    clouds.params.density = 1.0f;
    image a, b;
    if (render_scene(&clouds, 1, SKY_GL_AUTO, &a) || render_scene(&clear, 1, SKY_GL_AUTO, &b)) {
        CHECK(0, "render failed");
        return;
    }
    double f = changed_fraction(&a, &b);
    NOTE("cover 1, density 1: %.1f %% of the sky changed by the clouds", 100.0 * f);
    CHECK(f > 0.8, "full cover must hide most of the sky (%.2f)", f);
    image_free(&a);
    image_free(&b);
}

static double mean_luminance(const image *im)
{
    double s = 0;
    for (int y = 0; y < im->h; y++)
        for (int x = 0; x < im->w; x++) s += image_luminance(im, x, y);
    return s / (im->w * im->h);
}

static int cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

/* The q-quantile of an image's luminance. */
static double luminance_quantile(const image *im, double q)
{
    size_t n = (size_t)im->w * (size_t)im->h;
    float *l = malloc(n * sizeof(float));
    for (int y = 0; y < im->h; y++)
        for (int x = 0; x < im->w; x++) l[(size_t)y * (size_t)im->w + (size_t)x] = image_luminance(im, x, y);
    qsort(l, n, sizeof(float), cmp_float);
    double v = l[(size_t)(q * (double)(n - 1))];
    free(l);
    return v;
}

TEST(render_density_darkens_clouds)
{
    /* R-P lines 20-24: dense clouds get darker where they are thick */
    scene thin = sky_only(SKY_CLOUDS), dense = sky_only(SKY_CLOUDS);
    thin.params.cover = dense.params.cover = 1.0f;
    thin.params.sunset = dense.params.sunset = 0.0f;
    thin.params.density = 0.2f;
    dense.params.density = 1.0f;
    image a, b;
    if (render_scene(&thin, 1, SKY_GL_AUTO, &a) || render_scene(&dense, 1, SKY_GL_AUTO, &b)) {
        CHECK(0, "render failed");
        return;
    }
    double la = luminance_quantile(&a, 0.1), lb = luminance_quantile(&b, 0.1);
    NOTE("darkest tenth of the sky at cover 1: density 0.2 -> %.3f, density 1 -> %.3f kcd/m^2", la, lb);
    CHECK(lb < 0.85 * la, "dense clouds must have darker cores (%.3f vs %.3f)", lb, la);
    image_free(&a);
    image_free(&b);
}

TEST(render_day_bright_night_dark_with_stars)
{
    scene day = sky_only(SKY_FLICKER_STARS), night = sky_only(SKY_FLICKER_STARS);
    day.params.time = 0.5f;
    night.params.time = 0.0f;
    day.params.cover = night.params.cover = 0.0f;
    day.fisheye = night.fisheye = 1;
    day.w = day.h = night.w = night.h = 256;
    image dh, nh, dl, nl;
    if (render_scene(&day, 1, SKY_GL_AUTO, &dh) || render_scene(&night, 1, SKY_GL_AUTO, &nh) ||
        render_scene(&day, 0, SKY_GL_AUTO, &dl) || render_scene(&night, 0, SKY_GL_AUTO, &nl)) {
        CHECK(0, "render failed");
        return;
    }
    double zd = image_luminance(&dh, 128, 128), zn = image_luminance(&nh, 128, 128);
    NOTE("zenith luminance: day %.3g, night %.3g kcd/m^2", zd, zn);
    CHECK(zd > 1.0 && zd < 20.0, "clear noon zenith %.3g kcd/m^2 should be a few kcd/m^2", zd);
    CHECK(zd > 1e5 * zn, "night zenith must be far darker than day (%.3g vs %.3g)", zn, zd);
    int stars_night = count_point_sources(&nl, 0.15f), stars_day = count_point_sources(&dl, 0.15f);
    NOTE("point sources in the LDR image: %d at night, %d at noon", stars_night, stars_day);
    /* the 256x256 fisheye minifies the star tiles about eight times, so
     * only the brighter stars survive as separate points */
    CHECK(stars_night > 150, "a clear night shows many stars (%d)", stars_night);
    CHECK(stars_day == 0, "no star at noon (%d)", stars_day);
    CHECK(mean_luminance(&nl) < 0.25, "the night image is dark (mean %.3f)", mean_luminance(&nl));
    /* (the default tone map keeps the sky's saturation: a blue noon is
     * 5-10 % darker in mean than the old per-channel curve made it) */
    CHECK(mean_luminance(&dl) > 0.45, "the day image is bright (mean %.3f)", mean_luminance(&dl));
    image_free(&dh);
    image_free(&nh);
    image_free(&dl);
    image_free(&nl);
}

TEST(render_no_star_work_at_noon)
{
    fixture f;
    if (fixture_open(&f, SKY_GL_AUTO, NULL)) {
        CHECK(0, "fixture");
        return;
    }
    sky *s = f.s;
    sky_params p = sky_default_params();
    sky_layer_stats flicker, sun;
    p.time = 0.5f;
    sky_set_params(s, &p);
    sky_draw_fisheye(s);
    CHECK(sky_get_layer_stats(s, SKY_LAYER_FLICKER, &flicker) == SKY_OK && !flicker.drawn,
          "flicker stars must be skipped at noon");
    CHECK(sky_flicker_star_luminance(s->layer_state[SKY_LAYER_FLICKER]) == 0.0f, "the star term is switched off, not just dim");
    p.time = 0.0f;
    sky_set_params(s, &p);
    sky_draw_fisheye(s);
    CHECK(sky_get_layer_stats(s, SKY_LAYER_FLICKER, &flicker) == SKY_OK && flicker.drawn,
          "flicker stars are drawn at midnight");
    CHECK(sky_get_layer_stats(s, SKY_LAYER_SUN, &sun) == SKY_OK && !sun.drawn, "no sun at midnight");
    fixture_close(&f);

    /* skipping changes nothing visible: noon with and without the layer */
    scene with = sky_only(SKY_FLICKER_STARS), without = sky_only(SKY_FEATURES_NONE);
    with.params.time = without.params.time = 0.5f;
    image a, b;
    if (render_scene(&with, 1, SKY_GL_AUTO, &a) || render_scene(&without, 1, SKY_GL_AUTO, &b)) {
        CHECK(0, "render failed");
        return;
    }
    double d = max_rel_diff(&a, &b);
    CHECK(d < 1e-4, "noon with the star layer equals noon without it (%g)", d);
    image_free(&a);
    image_free(&b);
}

TEST(render_flicker_changes_with_seconds)
{
    /* the default night: the flicker stars over the airglow */
    scene a_sc = sky_only(SKY_FLICKER_STARS | SKY_AIRGLOW), b_sc;
    a_sc.params.time = 0.0f;
    a_sc.params.cover = 0.0f;
    b_sc = a_sc;
    b_sc.seconds = 0.3;
    image a, b;
    if (render_scene(&a_sc, 1, SKY_GL_AUTO, &a) || render_scene(&b_sc, 1, SKY_GL_AUTO, &b)) {
        CHECK(0, "render failed");
        return;
    }
    /* star pixels stand well above the darkest pixel of their 5x5
     * neighbourhood; the smooth galaxy glow and the plain sky do not */
    int star_px = 0, star_changed = 0, bg_px = 0, bg_changed = 0;
    double sum_a = 0, sum_b = 0;
    for (int y = 2; y < a.h - 2; y++)
        for (int x = 2; x < a.w - 2; x++) {
            float la = image_luminance(&a, x, y), lb = image_luminance(&b, x, y), floor_a = la, floor_b = lb;
            for (int dy = -2; dy <= 2; dy++)
                for (int dx = -2; dx <= 2; dx++) {
                    floor_a = fminf(floor_a, image_luminance(&a, x + dx, y + dy));
                    floor_b = fminf(floor_b, image_luminance(&b, x + dx, y + dy));
                }
            if (la > 3.0f * floor_a || lb > 3.0f * floor_b) {
                star_px++;
                star_changed += fabs((double)la - lb) > 0.05 * fmax(la, lb);
                sum_a += la;
                sum_b += lb;
            } else if (la < 1.02f * floor_a && lb < 1.02f * floor_b) {
                bg_px++;
                bg_changed += fabs((double)la - lb) > 1e-4 * fmax(la, lb);
            }
        }
    NOTE("%d star pixels, %d changed by > 5 %% in 0.3 s; brightness sum ratio %.3f", star_px, star_changed,
         sum_b / sum_a);
    CHECK(star_px > 100, "stars found (%d)", star_px);
    CHECK(star_changed > star_px / 4, "stars flicker: %d of %d changed", star_changed, star_px);
    /* a few faint halo texels of filtered stars fall under the threshold */
    CHECK(bg_px > a.w * a.h / 3 && bg_changed < bg_px / 200, "the sky between stars does not flicker (%d of %d changed)",
          bg_changed, bg_px);
    CHECK(sum_b / sum_a > 0.7 && sum_b / sum_a < 1.4, "flicker keeps the mean brightness (%g)", sum_b / sum_a);
    image_free(&a);
    image_free(&b);
}

/* Normalised cross-correlation of a centred window of a with b shifted by
 * (dx, dy) (b(x+dx, y+dy) against a(x, y)). */
static double ncc(const image *a, const image *b, int half, double dx, double dy)
{
    int cx = a->w / 2, cy = a->h / 2;
    double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
    int n = 0;
    for (int y = cy - half; y < cy + half; y++)
        for (int x = cx - half; x < cx + half; x++) {
            int bx = x + (int)lround(dx), by = y + (int)lround(dy);
            double va = image_luminance(a, x, y), vb = image_luminance(b, bx, by);
            sa += va;
            sb += vb;
            saa += va * va;
            sbb += vb * vb;
            sab += va * vb;
            n++;
        }
    double cov = sab / n - (sa / n) * (sb / n);
    double var = (saa / n - (sa / n) * (sa / n)) * (sbb / n - (sb / n) * (sb / n));
    return var > 0 ? cov / sqrt(var) : 0.0;
}

/* Pixel motion (right, down) of a pattern fixed to one cloud layer in a
 * fisheye image of size n near the zenith, for offset change d (texture
 * periods). m: the layer's 2x2 texture-coordinate matrix (row-major),
 * uv = m p + offset; s: the uv scale from the height slider. */
static void layer_motion(const double d[2], const double m[4], double k, double s, int n, double out[2])
{
    /* p moves by -(k m)^-1 d; m is a rotation, so its inverse is m^T */
    double dp[2] = {-(m[0] * d[0] + m[2] * d[1]) / k, -(m[1] * d[0] + m[3] * d[1]) / k};
    /* d.xz = p / s near the zenith; image x = -d.x, image down = +d.z */
    out[0] = -dp[0] / s * n / PI;
    out[1] = dp[1] / s * n / PI;
}

TEST(render_clouds_drift_by_expected_offset)
{
    scene sc = scene_default();
    sc.cfg.features = SKY_CLOUDS;
    sc.fisheye = 1;
    sc.w = sc.h = 256;
    sc.params.cover = 0.6f;
    sc.params.density = 1.0f;
    sc.params.height = 0.5f;
    sc.params.speed = 1.0f;
    sc.params.time = 0.5f;
    sc.seconds = 10.0;
    const double dt = 2.0;
    scene later = sc;
    later.seconds = sc.seconds + dt;
    image a, b;
    if (render_scene(&sc, 1, SKY_GL_AUTO, &a) || render_scene(&later, 1, SKY_GL_AUTO, &b)) {
        CHECK(0, "render failed");
        return;
    }
    /* search the shift that best maps frame a onto frame b */
    double best = -2, bx = 0, by = 0;
    for (int dy = -16; dy <= 16; dy++)
        for (int dx = -16; dx <= 16; dx++) {
            double c = ncc(&a, &b, 40, dx, dy);
            if (c > best) best = c, bx = dx, by = dy;
        }
    /* sub-pixel: parabola through the neighbours */
    double cxm = ncc(&a, &b, 40, bx - 1, by), cxp = ncc(&a, &b, 40, bx + 1, by);
    double cym = ncc(&a, &b, 40, bx, by - 1), cyp = ncc(&a, &b, 40, bx, by + 1);
    double sx = bx + 0.5 * (cxm - cxp) / (cxm - 2 * best + cxp), sy = by + 0.5 * (cym - cyp) / (cym - 2 * best + cyp);
    /* expected: each primary layer's own motion; the blend moves between */
    double s = 0.15 * pow(4.0, 0.5);
    const double id[4] = {1, 0, 0, 1}, rot[4] = {0.96, -0.28, 0.28, 0.96};
    double d0[2] = {sky_cloud_velocity[0][0] * dt, sky_cloud_velocity[0][1] * dt};
    double d1[2] = {sky_cloud_velocity[1][0] * dt, sky_cloud_velocity[1][1] * dt};
    double m0[2], m1[2];
    layer_motion(d0, id, 1.0, s, sc.w, m0);
    layer_motion(d1, rot, 1.15, s, sc.w, m1);
    NOTE("measured shift (%.2f, %.2f) px, correlation %.3f; layer 0 (%.2f, %.2f), layer 1 (%.2f, %.2f)", sx, sy, best,
         m0[0], m0[1], m1[0], m1[1]);
    double lo_x = fmin(m0[0], m1[0]) - 1.5, hi_x = fmax(m0[0], m1[0]) + 1.5;
    double lo_y = fmin(m0[1], m1[1]) - 1.5, hi_y = fmax(m0[1], m1[1]) + 1.5;
    CHECK(best > 0.8, "the shifted frames correlate (%.3f)", best);
    CHECK(sx >= lo_x && sx <= hi_x && sy >= lo_y && sy <= hi_y,
          "cloud motion (%.2f, %.2f) px outside the layers' range [%.2f..%.2f]x[%.2f..%.2f]", sx, sy, lo_x, hi_x, lo_y,
          hi_y);
    image_free(&a);
    image_free(&b);
}

static double mean_abs_diff(const image *a, const image *b)
{
    double s = 0;
    size_t n = 3u * (size_t)a->w * (size_t)a->h;
    for (size_t i = 0; i < n; i++) s += fabs((double)a->px[i] - b->px[i]);
    return s / (double)n;
}

TEST(render_drift_stays_smooth_after_years)
{
    /* frame-to-frame change after 3 years of running equals that at start */
    double diffs[2];
    const double starts[2] = {5.0, 1e8};
    for (int k = 0; k < 2; k++) {
        scene sc = sky_only(SKY_CLOUDS | SKY_FLICKER_STARS);
        sc.params.speed = 0.6f;
        sc.params.time = 0.2f; /* dawn: stars and clouds both visible */
        sc.seconds = starts[k];
        scene next = sc;
        next.seconds += 1.0 / 30.0;
        image a, b;
        if (render_scene(&sc, 0, SKY_GL_AUTO, &a) || render_scene(&next, 0, SKY_GL_AUTO, &b)) {
            CHECK(0, "render failed");
            return;
        }
        diffs[k] = mean_abs_diff(&a, &b);
        image_free(&a);
        image_free(&b);
    }
    NOTE("mean frame-to-frame change: %.5f at t = 5 s, %.5f at t = 1e8 s", diffs[0], diffs[1]);
    CHECK(diffs[1] < 2.0 * diffs[0] + 1e-4 && diffs[1] > 0.5 * diffs[0],
          "motion after 1e8 s (%.5f) must look like motion at the start (%.5f)", diffs[1], diffs[0]);
}

static double mean_gradient(const image *im, int half)
{
    double s = 0;
    int n = 0, cx = im->w / 2, cy = im->h / 2;
    for (int y = cy - half; y < cy + half; y++)
        for (int x = cx - half; x < cx + half; x++) {
            double l = image_luminance(im, x, y);
            s += fabs(image_luminance(im, x + 1, y) - l) + fabs(image_luminance(im, x, y + 1) - l);
            n++;
        }
    return s / n;
}

TEST(render_height_changes_cloud_scale)
{
    scene low = scene_default();
    low.cfg.features = SKY_CLOUDS;
    low.fisheye = 1;
    low.w = low.h = 256;
    low.params.cover = 0.7f;
    low.params.density = 0.5f;
    low.params.height = 0.0f;
    scene high = low;
    high.params.height = 1.0f;
    image a, b;
    if (render_scene(&low, 1, SKY_GL_AUTO, &a) || render_scene(&high, 1, SKY_GL_AUTO, &b)) {
        CHECK(0, "render failed");
        return;
    }
    double ga = mean_gradient(&a, 50), gb = mean_gradient(&b, 50);
    NOTE("mean luminance gradient near the zenith: height 0 -> %.4f, height 1 -> %.4f", ga, gb);
    CHECK(gb > 1.6 * ga, "high clouds must have finer features (%.4f vs %.4f)", gb, ga);
    image_free(&a);
    image_free(&b);
}

/* Luminance-weighted centroid of the pixels above half the maximum. */
static void bright_centroid(const image *im, double *cx, double *cy, double *peak)
{
    double mx = 0;
    for (int y = 0; y < im->h; y++)
        for (int x = 0; x < im->w; x++) mx = fmax(mx, image_luminance(im, x, y));
    double sx = 0, sy = 0, sw = 0;
    for (int y = 0; y < im->h; y++)
        for (int x = 0; x < im->w; x++) {
            double l = image_luminance(im, x, y);
            if (l > 0.5 * mx) {
                sx += l * (x + 0.5);
                sy += l * (y + 0.5);
                sw += l;
            }
        }
    *cx = sw > 0 ? sx / sw : -1;
    *cy = sw > 0 ? sy / sw : -1;
    *peak = mx;
}

static int sun_direction(const scene *sc, double dir[3])
{
    fixture f;
    if (fixture_open(&f, SKY_GL_AUTO, &sc->cfg)) return -1;
    sky_set_params(f.s, &sc->params);
    sky_lighting l;
    sky_get_lighting(f.s, &l);
    for (int i = 0; i < 3; i++) dir[i] = l.sun_direction[i];
    fixture_close(&f);
    return 0;
}

TEST(render_sun_where_direction_projects)
{
    const double yaws[3] = {180.0, 165.0, 200.0}, pitches[3] = {40.0, 30.0, 55.0};
    for (int k = 0; k < 3; k++) {
        scene sc = scene_default();
        sc.cfg.features = SKY_SUN;
        sc.params.time = 0.45f;
        sc.yaw = yaws[k];
        sc.pitch = pitches[k];
        sc.w = 320;
        sc.h = 240;
        double d[3];
        image im;
        if (sun_direction(&sc, d) || render_scene(&sc, 1, SKY_GL_AUTO, &im)) {
            CHECK(0, "render failed");
            return;
        }
        float view[16], proj[16];
        scene_camera(&sc, view, proj);
        double e[4], c[4];
        for (int r = 0; r < 4; r++) e[r] = view[r] * d[0] + view[4 + r] * d[1] + view[8 + r] * d[2];
        e[3] = 0.0;
        for (int r = 0; r < 4; r++) c[r] = proj[r] * e[0] + proj[4 + r] * e[1] + proj[8 + r] * e[2] + proj[12 + r] * e[3];
        double px = (c[0] / c[3] + 1.0) * 0.5 * sc.w, py = (1.0 - c[1] / c[3]) * 0.5 * sc.h;
        double mx, my, peak;
        bright_centroid(&im, &mx, &my, &peak);
        double err = hypot(mx - px, my - py);
        NOTE("yaw %.0f pitch %.0f: sun expected at (%.2f, %.2f), found at (%.2f, %.2f): %.2f px", sc.yaw, sc.pitch, px,
             py, mx, my, err);
        CHECK(err <= 2.0, "sun %.2f px from where its direction projects", err);
        CHECK(peak > 1e5, "the disc is as bright as the sun (%.3g kcd/m^2)", peak);
        image_free(&im);
    }
}

TEST(render_sun_in_fisheye)
{
    scene sc = scene_default();
    sc.cfg.features = SKY_SUN;
    sc.fisheye = 1;
    sc.w = sc.h = 400;
    sc.params.time = 0.32f; /* morning, in the east: left of centre */
    double d[3];
    image im;
    if (sun_direction(&sc, d) || render_scene(&sc, 1, SKY_GL_AUTO, &im)) {
        CHECK(0, "render failed");
        return;
    }
    double theta = acos(d[1]), hl = hypot(d[0], d[2]);
    double r = theta / (PI / 2);
    double px = (1.0 - r * d[0] / hl) * 0.5 * sc.w; /* east (+x) to the left  */
    double py = (1.0 + r * d[2] / hl) * 0.5 * sc.h; /* north (-z) to the top  */
    double mx, my, peak;
    bright_centroid(&im, &mx, &my, &peak);
    double err = hypot(mx - px, my - py);
    NOTE("fisheye: sun expected at (%.2f, %.2f), found at (%.2f, %.2f): %.2f px", px, py, mx, my, err);
    CHECK(err <= 2.0, "fisheye sun %.2f px off", err);
    CHECK(mx < sc.w / 2, "morning sun on the east (left) side");
    image_free(&im);
}

TEST(render_hdr_finite_everywhere)
{
    const float times[6] = {0.0f, 0.24f, 0.25f, 0.2501f, 0.5f, 0.76f};
    int bad = 0, frames = 0;
    double mean[6][2] = {{0}};
    for (int t = 0; t < 6; t++)
        for (int fish = 0; fish < 2; fish++) {
            scene sc = scene_default();
            sc.cfg.features = SKY_CLOUDS | SKY_SUN | SKY_FLICKER_STARS;
            sc.params.time = times[t];
            sc.params.cover = (float)(t % 2);
            sc.params.density = (float)(t % 3 == 0);
            sc.params.height = (float)(t % 2 == 0);
            sc.params.sunset = 1.0f;
            sc.fisheye = fish;
            sc.pitch = fish ? 0.0 : 5.0; /* horizon in view */
            image im;
            if (render_scene(&sc, 1, SKY_GL_AUTO, &im)) {
                CHECK(0, "render failed");
                return;
            }
            frames++;
            double sum = 0.0;
            for (size_t i = 0; i < 3u * (size_t)im.w * (size_t)im.h; i++) {
                if (!isfinite(im.px[i]) || im.px[i] < 0.0f) bad++;
                else sum += im.px[i];
            }
            /* and a sky, not a cleared frame: linear output is the sky's
             * luminance before exposure, above zero even at midnight's
             * starlight (t = 0) */
            mean[t][fish] = sum / (3.0 * im.w * im.h);
            CHECK(mean[t][fish] > 0.0, "time %.4f%s: an all-black linear frame", (double)times[t],
                  fish ? " (fisheye)" : "");
            image_free(&im);
        }
    CHECK(bad == 0, "%d non-finite or negative values in %d linear frames", bad, frames);
    /* noon's sky outshines midnight's by orders of magnitude in either
     * projection (about 10^6 in luminance; asserted: 10^3) */
    for (int fish = 0; fish < 2; fish++)
        CHECK(mean[4][fish] > 1e3 * mean[0][fish], "noon's mean %g against midnight's %g%s", mean[4][fish],
              mean[0][fish], fish ? " (fisheye)" : "");
}

TEST(profiles_core_and_compat_agree)
{
    const float times[3] = {0.45f, 0.735f, 0.02f};
    for (int k = 0; k < 3; k++) {
        scene sc = scene_default();
        sc.params.time = times[k];
        sc.params.cover = 0.5f;
        sc.yaw = k == 1 ? 270.0 : 180.0;
        image core, compat;
        if (render_scene(&sc, 0, SKY_GL_CORE33, &core) || render_scene(&sc, 0, SKY_GL_COMPAT20, &compat)) {
            CHECK(0, "render failed");
            return;
        }
        double psnr = image_psnr(&core, &compat);
        NOTE("time %.3f: CORE33 vs COMPAT20 PSNR %.1f dB", times[k], psnr);
        CHECK(psnr >= 40.0, "the two profiles must agree (PSNR %.1f dB)", psnr);
        image_free(&core);
        image_free(&compat);
    }
}

/* Local maxima of a - b above `contrast` (0..1 LDR): what a layer added as
 * points. */
static int count_added_points(const image *a, const image *b, float contrast)
{
    int n = 0;
    for (int y = 1; y < a->h - 1; y++)
        for (int x = 1; x < a->w - 1; x++) {
            float d = image_luminance(a, x, y) - image_luminance(b, x, y), brightest = 0.0f;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++)
                    if (dx || dy) {
                        float v = image_luminance(a, x + dx, y + dy) - image_luminance(b, x + dx, y + dy);
                        if (v > brightest) brightest = v;
                    }
            if (d > contrast && d >= brightest) n++;
        }
    return n;
}

TEST(render_total_solar_eclipse)
{
    /* 2024-04-08 near Nazas, Durango, at greatest eclipse (18:17:20 UT,
     * the sun at 70 degrees): the whole sky, and the stars in the east
     * (Capella, Aldebaran, Elnath, Betelgeuse, Rigel stand 10-35 degrees
     * up there), against the same scene an hour later */
    scene sc = scene_default();
    sc.cfg.features = SKY_SUN | SKY_MOON | SKY_STARS | SKY_SOLAR_ECLIPSE;
    sc.cfg.atmosphere = SKY_ATMOSPHERE_HILLAIRE;
    /* a dry desert 1.2 km up in April: very clean air */
    sky_atmosphere_get_preset(SKY_ATMOSPHERE_PRESET_VERY_CLEAN, &sc.cfg.atmosphere_params);
    sc.has_observer = 1;
    sc.observer.julian_day_utc = sky_julian_day(2024, 4, 8, 18, 17, 20.0);
    sc.observer.latitude_deg = 25.29;
    sc.observer.longitude_deg = -104.14;
    sc.fisheye = 1;
    sc.w = sc.h = 128;
    scene later = sc;
    later.observer.julian_day_utc += 1.0 / 24.0;
    image tot, after;
    if (render_scene(&sc, 1, SKY_GL_AUTO, &tot) || render_scene(&later, 1, SKY_GL_AUTO, &after)) {
        CHECK(0, "render failed");
        return;
    }
    /* the sky's median, away from the sun and the corona */
    double m_tot = luminance_quantile(&tot, 0.5), m_after = luminance_quantile(&after, 0.5);
    NOTE("median sky %.3g kcd/m^2 at totality, %.3g an hour later (x%.2g)", m_tot, m_after, m_tot / m_after);
    CHECK(m_tot < 0.003 * m_after, "totality is only %.3g times the sky an hour later", m_tot / m_after);
    /* the horizon glows brighter than the zenith during totality */
    double zen = image_luminance(&tot, 64, 64), hor = 0.0;
    for (int k = 0; k < 4; k++) hor += image_luminance(&tot, k == 0 ? 3 : k == 1 ? 124 : 64, k == 2 ? 3 : k == 3 ? 124 : 64) / 4.0;
    NOTE("totality: horizon %.3g, zenith %.3g kcd/m^2", hor, zen);
    CHECK(hor > 2.0 * zen, "the horizon ring (%.3g) is not brighter than the zenith (%.3g)", hor, zen);
    image_free(&tot);
    image_free(&after);

    scene east = sc;
    east.fisheye = 0;
    east.w = 640, east.h = 360;
    east.yaw = 70.0, east.pitch = 22.0, east.fov = 50.0;
    scene east_bare = east;
    east_bare.cfg.features = SKY_SUN | SKY_MOON | SKY_SOLAR_ECLIPSE;
    scene east_later = east, east_later_bare = east_bare;
    east_later.observer.julian_day_utc += 1.0 / 24.0;
    east_later_bare.observer.julian_day_utc += 1.0 / 24.0;
    image s1, s0, l1, l0;
    if (render_scene(&east, 0, SKY_GL_AUTO, &s1) || render_scene(&east_bare, 0, SKY_GL_AUTO, &s0) ||
        render_scene(&east_later, 0, SKY_GL_AUTO, &l1) || render_scene(&east_later_bare, 0, SKY_GL_AUTO, &l0)) {
        CHECK(0, "render failed");
        return;
    }
    int stars_tot = count_added_points(&s1, &s0, 0.02f), stars_later = count_added_points(&l1, &l0, 0.02f);
    NOTE("stars standing out by 2 %% of white: %d at totality, %d an hour later", stars_tot, stars_later);
    /* two at least: with a realistic sky (the sun at its full photometric
     * brightness, real aerosol even in very clean air) the sky around the
     * umbra hides the fainter of the five */
    CHECK(stars_tot >= 2, "only %d stars show at totality", stars_tot);
    CHECK(stars_later == 0, "%d stars show in daylight", stars_later);
    image_free(&s1);
    image_free(&s0);
    image_free(&l1);
    image_free(&l0);

    /* the host's lighting goes with the sky: direct sun gone, ambient and
     * fog at deep-twilight levels, against an hour later */
    fixture fx;
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.features = SKY_SUN | SKY_MOON | SKY_SOLAR_ECLIPSE;
    cfg.atmosphere = SKY_ATMOSPHERE_HILLAIRE;
    if (fixture_open(&fx, SKY_GL_AUTO, &cfg)) {
        CHECK(0, "no sky");
        return;
    }
    sky_lighting at, after_l;
    sky_set_observer(fx.s, &sc.observer);
    sky_get_lighting(fx.s, &at);
    sky_set_observer(fx.s, &later.observer);
    sky_get_lighting(fx.s, &after_l);
    NOTE("lighting at totality: sun %.3g klx (green), ambient %.3g, fog %.3g; an hour later %.3g, %.3g, %.3g",
         (double)at.sun_color[1], (double)at.ambient_color[1], (double)at.fog_color[1], (double)after_l.sun_color[1],
         (double)after_l.ambient_color[1], (double)after_l.fog_color[1]);
    CHECK(at.sun_color[1] <= 1e-6f * after_l.sun_color[1], "the sun still lights the scene at totality (%g klx)",
          (double)at.sun_color[1]);
    CHECK(at.ambient_color[1] < 0.003f * after_l.ambient_color[1] && at.fog_color[1] < 0.01f * after_l.fog_color[1],
          "ambient %g / fog %g at totality against %g / %g", (double)at.ambient_color[1], (double)at.fog_color[1],
          (double)after_l.ambient_color[1], (double)after_l.fog_color[1]);
    fixture_close(&fx);

    /* without SKY_SOLAR_ECLIPSE the same instant is an ordinary day: the
     * astronomy still reports the eclipse, nothing else follows it */
    cfg.features = SKY_SUN | SKY_MOON;
    if (fixture_open(&fx, SKY_GL_AUTO, &cfg)) {
        CHECK(0, "no sky");
        return;
    }
    sky_lighting plain;
    sky_astronomy astro;
    sky_set_observer(fx.s, &sc.observer);
    sky_get_lighting(fx.s, &plain);
    sky_get_astronomy(fx.s, &astro);
    NOTE("without the feature: sun %.3g klx, ambient %.3g (obscuration %.4f)", (double)plain.sun_color[1],
         (double)plain.ambient_color[1], astro.solar_obscuration);
    CHECK(astro.solar_obscuration > 0.999 && plain.sun_color[1] > 0.5f * after_l.sun_color[1] &&
              plain.ambient_color[1] > 0.5f * after_l.ambient_color[1],
          "left out, the eclipse still dims the scene (sun %g, ambient %g klx)", (double)plain.sun_color[1],
          (double)plain.ambient_color[1]);
    fixture_close(&fx);
}

/* The LDR dome drawn into its reduced image (the default, 1/4 per axis)
 * against the dome at every pixel (dome_divisor 1): the same sky and
 * clouds, a little softer; the sun, and at night the stars and the
 * flicker stars, as sharp and as bright, where the clouds let them be. */
TEST(render_dome_image_agrees_with_every_pixel)
{
    scene day = scene_default();
    day.cfg.features = SKY_CLOUDS | SKY_SUN;
    day.params.time = 0.45f;
    day.params.cover = 0.5f;
    day.w = 320;
    day.h = 240;
    day.pitch = 40.0;
    scene night = sky_only(SKY_CLOUDS | SKY_STARS | SKY_FLICKER_STARS);
    night.params.time = 0.0f;
    night.params.cover = 0.3f;
    night.w = 320;
    night.h = 240;
    scene *scenes[2] = {&day, &night};
    for (int k = 0; k < 2; k++) {
        scene full = *scenes[k], reduced = *scenes[k];
        full.cfg.dome_divisor = 1;
        image a, b;
        if (render_scene(&full, 0, SKY_GL_AUTO, &a) || render_scene(&reduced, 0, SKY_GL_AUTO, &b)) {
            CHECK(0, "render failed");
            return;
        }
        double ma = mean_luminance(&a), mb = mean_luminance(&b), psnr = image_psnr(&a, &b);
        NOTE("%s: mean 8-bit luminance %.4f at every pixel, %.4f from the image; PSNR %.1f dB", k ? "night" : "day", ma,
             mb, psnr);
        CHECK(fabs(mb / ma - 1.0) < 0.02, "the image keeps the sky's brightness (%.4f vs %.4f)", mb, ma);
        CHECK(psnr > 30.0, "the image shows the same sky (PSNR %.1f dB)", psnr);
        if (k == 0) {
            double ax, ay, ap, bx, by, bp;
            bright_centroid(&a, &ax, &ay, &ap);
            bright_centroid(&b, &bx, &by, &bp);
            NOTE("sun at (%.2f, %.2f) peak %.3f, from the image at (%.2f, %.2f) peak %.3f", ax, ay, ap, bx, by, bp);
            CHECK(hypot(ax - bx, ay - by) < 0.5 && fabs(ap - bp) < 0.02, "the sun is drawn at full resolution");
        } else {
            int sa = count_point_sources(&a, 0.1f), sb = count_point_sources(&b, 0.1f);
            NOTE("point sources: %d at every pixel, %d over the image", sa, sb);
            CHECK(sa > 100 && abs(sa - sb) < sa / 10, "the stars stay sharp (%d vs %d)", sa, sb);
        }
        image_free(&a);
        image_free(&b);
    }
}

#define DEG (3.14159265358979323846 / 180.0)

/* Illuminance (klx, luminance-weighted) the sun layer adds to a scene:
 * the HDR render with SKY_SUN minus the same view with clouds at cover 0
 * (the same dome), each pixel's luminance times its solid angle (on the
 * image plane at distance 1 a pixel is s = 2 tan(fov / 2) / h wide and
 * subtends s^2 cos^3 of its angle off the axis). */
static double sun_layer_flux(const scene *sc)
{
    scene with = *sc, without = *sc;
    with.cfg.features = SKY_SUN;
    without.cfg.features = SKY_CLOUDS;
    image a, b;
    if (render_scene(&with, 1, SKY_GL_AUTO, &a)) return -1.0;
    if (render_scene(&without, 1, SKY_GL_AUTO, &b)) {
        image_free(&a);
        return -1.0;
    }
    double s = 2.0 * tan(sc->fov * DEG / 2.0) / sc->h, sum = 0.0;
    for (int y = 0; y < sc->h; y++)
        for (int x = 0; x < sc->w; x++) {
            double u = (x + 0.5 - sc->w / 2.0) * s, v = (y + 0.5 - sc->h / 2.0) * s;
            sum += (image_luminance(&a, x, y) - image_luminance(&b, x, y)) * s * s / pow(1.0 + u * u + v * v, 1.5);
        }
    image_free(&a);
    image_free(&b);
    return sum;
}

TEST(render_sun_disc_sums_to_sunlight)
{
    /* the equator at the equinox, the sun from the zenith down to 7
     * degrees: the disc (limb-darkened, through the same transmittance)
     * sums to the sun_color sky_get_lighting reports */
    const float times[] = {0.5f, 0.375f, 0.3f, 0.27f};
    for (int i = 0; i < 4; i++) {
        scene sc = scene_default();
        sc.params.cover = 0.0f;
        sc.params.time = times[i];
        sc.has_observer = 1;
        sc.observer = equator_equinox();
        sc.w = sc.h = 256;
        sc.fov = 5.0; /* 16 sun radii (the glare) either side of the centre */
        sky_config cfg;
        memset(&cfg, 0, sizeof cfg);
        cfg.features = SKY_SUN;
        fixture f;
        if (fixture_open(&f, SKY_GL_AUTO, &cfg)) {
            CHECK(0, "fixture");
            return;
        }
        sky_lighting l;
        sky_set_params(f.s, &sc.params);
        sky_set_observer(f.s, &sc.observer);
        sky_get_lighting(f.s, &l);
        fixture_close(&f);
        const float *d = l.sun_direction; /* horizon frame: +x east, +y up, +z south */
        sc.yaw = atan2(d[0], -d[2]) / DEG;
        sc.pitch = asin(d[1]) / DEG;
        double light = 0.2126 * l.sun_color[0] + 0.7152 * l.sun_color[1] + 0.0722 * l.sun_color[2];
        double disc = sun_layer_flux(&sc);
        NOTE("sun at %.1f deg: disc %.2f klx, sun_color %.2f klx (%+.2f %%)", l.sun_altitude_deg, disc, light,
             100.0 * (disc / light - 1.0));
        CHECK(light > 0.0 && fabs(disc / light - 1.0) <= 0.03, "sun at %.1f deg: disc %.2f klx vs sun_color %.2f klx",
              l.sun_altitude_deg, disc, light);
    }
}

/* The dome draws only its triangles in view (dome.c's select_triangles):
 * whatever the camera (any yaw, pitch and roll, 3 to 170 degrees of view,
 * wide and tall viewports), it still covers every pixel: none keeps the
 * magenta it was cleared to. Drawn at every pixel (dome_divisor 1), where
 * a missing triangle would leave its pixels as they were. */
TEST(render_dome_covers_every_view)
{
    static const int sizes[2][2] = {{160, 90}, {60, 120}};
    for (int z = 0; z < 2; z++) {
        const int w = sizes[z][0], h = sizes[z][1];
        sky_config cfg;
        memset(&cfg, 0, sizeof cfg);
        cfg.features = SKY_SUN;
        cfg.dome_divisor = 1;
        fixture f;
        if (fixture_open_sized(&f, w, h, 0, SKY_GL_AUTO, &cfg)) {
            CHECK(0, "fixture");
            return;
        }
        unsigned seed = 12345u + (unsigned)z;
        int holes = 0, worst_view = -1;
        for (int v = 0; v < 60; v++) {
            seed = seed * 1664525u + 1013904223u;
            double yaw = (seed >> 8) % 360;
            seed = seed * 1664525u + 1013904223u;
            double pitch = (double)((seed >> 8) % 181) - 90.0;
            seed = seed * 1664525u + 1013904223u;
            double roll = (seed >> 8) % 360 * (3.14159265358979 / 180.0);
            seed = seed * 1664525u + 1013904223u;
            double fov = v % 4 == 0 ? 3.0 : 10.0 + (seed >> 8) % 161;
            float view[16], proj[16], rolled[16];
            sky_cli_camera_at(yaw, pitch, fov, w, h, view, proj);
            /* roll: turn the camera's frame about its forward axis */
            for (int c = 0; c < 4; c++) {
                rolled[c * 4 + 0] = (float)(cos(roll) * view[c * 4 + 0] - sin(roll) * view[c * 4 + 1]);
                rolled[c * 4 + 1] = (float)(sin(roll) * view[c * 4 + 0] + cos(roll) * view[c * 4 + 1]);
                rolled[c * 4 + 2] = view[c * 4 + 2];
                rolled[c * 4 + 3] = view[c * 4 + 3];
            }
            glViewport(0, 0, w, h);
            glClearColor(1.0f, 0.0f, 1.0f, 1.0f);
            glClear(GL_COLOR_BUFFER_BIT);
            CHECK(sky_draw(f.s, rolled, proj) == SKY_OK, "draw: %s", sky_last_error(f.s));
            sky_osmesa_finish(&f.ctx);
            const unsigned char *px = f.ctx.pixels;
            int here = 0;
            for (int i = 0; i < w * h; i++) here += px[4 * i] == 255 && px[4 * i + 1] == 0 && px[4 * i + 2] == 255;
            if (here > holes) holes = here, worst_view = v;
        }
        NOTE("%dx%d, 60 views: at most %d pixels left uncovered (view %d)", w, h, holes, worst_view);
        CHECK(holes == 0, "%dx%d: the dome leaves %d pixels uncovered in view %d", w, h, holes, worst_view);
        fixture_close(&f);
    }
}
