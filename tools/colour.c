/*
 * The 8-bit output's colours against the sky's own (colour.h). Terms: the
 * saturation of linear RGB is (largest - smallest) / largest, its hue the
 * HSV hue; an 8-bit value is a pixel's largest channel. The LDR frame is
 * read back as floats, quantised to 8 bits as a display would show it,
 * then decoded from sRGB to linear light.
 */
#include "colour.h"

#include "osmesa_ctx.h"
#include "cli.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

const double sky_colour_suns[SKY_COLOUR_SUNS] = {-8.0, -4.0, 0.5, 3.0, 8.0, 15.0, 30.0, 60.0};

/* 40 N 0 E, the sunset preset's place, on the 2026 June solstice, when
 * the sun reaches every height of the table; an evening sun, as the
 * preset's. */
static sky_observer colour_observer(void)
{
    sky_observer o;
    memset(&o, 0, sizeof o);
    o.latitude_deg = 40.0;
    o.julian_day_utc = sky_julian_day(2026, 6, 21, 12, 0, 0.0);
    o.time_from_params = 1;
    return o;
}

/* The time slider after noon at which the sun stands at alt_deg. */
static double evening_time(const sky_observer *o, double alt_deg)
{
    double lo = 0.5, hi = 1.0; /* the sun sinks from noon to midnight */
    for (int i = 0; i < 50; i++) {
        double mid = 0.5 * (lo + hi);
        sky_astronomy a;
        if (sky_compute_astronomy(o, (float)mid, NULL, 0, NULL, &a, NULL, 0) != SKY_OK) break;
        if (a.sun.alt_deg > alt_deg) lo = mid;
        else hi = mid;
    }
    return 0.5 * (lo + hi);
}

static double luminance(const float *rgb) { return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]; }

/* HSV hue (degrees) and saturation of linear RGB; saturation 0 for black. */
static void hue_saturation(const double c[3], double *hue, double *sat)
{
    double mx = fmax(c[0], fmax(c[1], c[2])), mn = fmin(c[0], fmin(c[1], c[2])), d = mx - mn;
    *sat = mx > 0.0 ? d / mx : 0.0;
    double h = 0.0;
    if (d > 0.0) {
        if (mx == c[0]) h = fmod((c[1] - c[2]) / d, 6.0);
        else if (mx == c[1]) h = (c[2] - c[0]) / d + 2.0;
        else h = (c[0] - c[1]) / d + 4.0;
    }
    h *= 60.0;
    *hue = h < 0.0 ? h + 360.0 : h;
}

static double srgb_decode(double v) { return v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4); }

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double quantile(double *v, int n, double q)
{
    if (n <= 0) return -1.0;
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    int i = (int)floor(q * (n - 1) + 0.5);
    return v[i < 0 ? 0 : (i >= n ? n - 1 : i)];
}

/* A pixel's direction (unit, horizon frame) in a frame drawn with view and
 * proj, w x h, rows bottom first: the camera's right, up and forward axes
 * are the view matrix's rows. */
static void pixel_direction(const float view[16], const float proj[16], int w, int h, int x, int y, double d[3])
{
    double xn = (2.0 * (x + 0.5) / w - 1.0) / proj[0], yn = (2.0 * (y + 0.5) / h - 1.0) / proj[5];
    const double right[3] = {view[0], view[4], view[8]}, up[3] = {view[1], view[5], view[9]},
                 fwd[3] = {-view[2], -view[6], -view[10]};
    for (int i = 0; i < 3; i++) d[i] = xn * right[i] + yn * up[i] + fwd[i];
    double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int i = 0; i < 3; i++) d[i] /= len;
}

/* An LDR pixel as a display shows it: each channel quantised to 8 bits
 * (byte), then decoded from sRGB to linear light (lin). */
static void displayed(const float *L, int byte[3], double lin[3])
{
    for (int i = 0; i < 3; i++) {
        double v = L[i] < 0.0f ? 0.0 : (L[i] > 1.0f ? 1.0 : L[i]);
        byte[i] = (int)floor(v * 255.0 + 0.5);
        lin[i] = srgb_decode(byte[i] / 255.0);
    }
}

/* The 8-bit pixels of an LDR frame whose direction is more than min_deg
 * above the horizon: their count, the mean of their display luminance
 * (decoded to linear) in *mean, and, with channels (3 n ints, n = w h),
 * their bytes channel by channel (channel c's at c n). */
static size_t sky_above(const float *ldr, const float view[16], const float proj[16], int w, int h, double min_deg,
                        int *channels, double *mean)
{
    size_t n = (size_t)w * (size_t)h, count = 0;
    double sum = 0.0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double d[3], lin[3];
            int byte[3];
            pixel_direction(view, proj, w, h, x, y, d);
            if (d[1] < sin(min_deg * PI / 180.0)) continue;
            displayed(ldr + 4 * ((size_t)y * w + x), byte, lin);
            if (channels)
                for (int i = 0; i < 3; i++) channels[i * n + count] = byte[i];
            sum += 0.2126 * lin[0] + 0.7152 * lin[1] + 0.0722 * lin[2];
            count++;
        }
    *mean = count ? sum / (double)count : 0.0;
    return count;
}

/* One frame of the sky in its own float context: HDR or LDR output, the
 * features given (0: the library's default set), the observer o, clouds
 * off. */
static int render(sky_atmosphere_path path, sky_tone_map tone_map, sky_gl_profile profile, sky_output output,
                  unsigned features, const sky_observer *o, double t, const float view[16], const float proj[16],
                  int w, int h, float *out, float sun_dir[3], char *err, size_t err_len)
{
    sky_osmesa ctx;
    if (sky_osmesa_create(&ctx, w, h, profile, 1, err, err_len)) return -1;
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.features = features;
    cfg.atmosphere = path;
    cfg.output = output;
    cfg.tone_map = tone_map;
    cfg.gl_profile = profile;
    cfg.get_proc_address = sky_osmesa_loader();
    sky *s = sky_create(&cfg, err, err_len);
    int rc = -1;
    if (s) {
        sky_params p = sky_default_params();
        p.cover = 0.0f;
        p.time = (float)t;
        sky_set_observer(s, o);
        sky_set_params(s, &p);
        sky_lighting l;
        sky_get_lighting(s, &l);
        memcpy(sun_dir, l.sun_direction, sizeof l.sun_direction);
        if (sky_draw(s, view, proj) == SKY_OK) {
            sky_osmesa_finish(&ctx);
            memcpy(out, ctx.pixels, sizeof(float) * 4 * (size_t)w * (size_t)h);
            rc = 0;
        } else {
            snprintf(err, err_len, "sky_draw: %s", sky_last_error(s));
        }
        sky_destroy(s);
    }
    sky_osmesa_destroy(&ctx);
    return rc;
}

int sky_colour_measure(sky_atmosphere_path path, sky_tone_map tone_map, sky_gl_profile profile, double sun_deg,
                       int toward, int w, int h, sky_colour_row *row, char *err, size_t err_len)
{
    memset(row, 0, sizeof *row);
    row->path = path;
    row->tone_map = tone_map;
    row->sun_deg = sun_deg;
    row->toward = toward;
    sky_observer o = colour_observer();
    double t = evening_time(&o, sun_deg);
    sky_astronomy a;
    if (sky_compute_astronomy(&o, (float)t, NULL, 0, NULL, &a, NULL, 0) != SKY_OK) {
        snprintf(err, err_len, "no astronomy for time %g", t);
        return -1;
    }
    /* the sun's true azimuth: the camera faces it, or turns its back */
    double yaw = a.sun.az_deg + (toward ? 0.0 : 180.0), pitch = toward ? 8.0 : 20.0;
    float view[16], proj[16];
    sky_cli_camera_at(yaw, pitch, 60.0, w, h, view, proj);
    size_t n = (size_t)w * (size_t)h;
    float *hdr = malloc(sizeof(float) * 4 * n), *ldr = malloc(sizeof(float) * 4 * n);
    double *kept = malloc(sizeof(double) * n), *shift = malloc(sizeof(double) * n);
    float sun[3];
    int rc = -1;
    if (!hdr || !ldr || !kept || !shift) {
        snprintf(err, err_len, "out of memory");
        goto done;
    }
    if (render(path, tone_map, profile, SKY_OUTPUT_HDR, SKY_SUN, &o, t, view, proj, w, h, hdr, sun, err, err_len) ||
        render(path, tone_map, profile, SKY_OUTPUT_LDR, SKY_SUN, &o, t, view, proj, w, h, ldr, sun, err, err_len))
        goto done;
    double sun_az = atan2(sun[0], -sun[2]);
    int counted = 0, sky_px = 0, clipped = 0, under = 0, elsewhere = 0, ground_px = 0;
    double sky_sum = 0.0, ground_sum = 0.0, under_sum = 0.0, elsewhere_sum = 0.0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double d[3];
            pixel_direction(view, proj, w, h, x, y, d);
            const float *H = hdr + 4 * ((size_t)y * w + x), *L = ldr + 4 * ((size_t)y * w + x);
            if (d[1] < 0.0) {
                double lum = luminance(H), daz = fabs(remainder(atan2(d[0], -d[2]) - sun_az, 2.0 * PI)) * 180.0 / PI;
                ground_sum += lum, ground_px++;
                if (daz < 4.0) under_sum += lum, under++;
                if (daz > 20.0) elsewhere_sum += lum, elsewhere++;
                continue;
            }
            sky_sum += luminance(H);
            double cos_sun = d[0] * sun[0] + d[1] * sun[1] + d[2] * sun[2];
            if (cos_sun > cos(3.0 * PI / 180.0)) continue;
            sky_px++;
            int byte[3];
            double lin[3], hdr_rgb[3] = {H[0], H[1], H[2]};
            displayed(L, byte, lin);
            int top = byte[0] > byte[1] ? byte[0] : byte[1];
            top = top > byte[2] ? top : byte[2];
            if (top == 255) clipped++;
            double hue_h, sat_h, hue_l, sat_l;
            hue_saturation(hdr_rgb, &hue_h, &sat_h);
            if (sat_h <= 0.15 || top < 25) continue;
            hue_saturation(lin, &hue_l, &sat_l);
            kept[counted] = sat_l / sat_h;
            double dh = fabs(hue_l - hue_h);
            shift[counted] = dh > 180.0 ? 360.0 - dh : dh;
            counted++;
        }
    row->counted = counted;
    row->saturation_kept_median = quantile(kept, counted, 0.5);
    row->saturation_kept_p10 = quantile(kept, counted, 0.1);
    row->hue_shift_median = quantile(shift, counted, 0.5);
    row->hue_shift_p90 = quantile(shift, counted, 0.9);
    row->clipped = sky_px ? (double)clipped / sky_px : 0.0;
    row->pillar = toward && sun_deg >= 0.0 && sun_deg <= 8.0 && under && elsewhere && elsewhere_sum > 0.0
                      ? (under_sum / under) / (elsewhere_sum / elsewhere)
                      : -1.0;
    int sky_all = w * h - ground_px;
    row->ground_to_sky =
        sun_deg < 0.0 && ground_px && sky_all && sky_sum > 0.0 ? (ground_sum / ground_px) / (sky_sum / sky_all) : -1.0;
    rc = 0;
done:
    free(hdr);
    free(ldr);
    free(kept);
    free(shift);
    return rc;
}

int sky_colour_row_ok(const sky_colour_row *r, char *why, size_t why_len)
{
    why[0] = '\0';
    int colour = r->sun_deg >= -4.0; /* the colour targets' range */
    if (colour && r->counted > 0 && (r->hue_shift_median > 3.0 || r->hue_shift_p90 > 8.0))
        snprintf(why, why_len, "hue shift %.1f / %.1f degrees (<= 3 / 8)", r->hue_shift_median, r->hue_shift_p90);
    else if (colour && r->counted > 0 && (r->saturation_kept_median < 0.85 || r->saturation_kept_p10 < 0.6))
        snprintf(why, why_len, "saturation kept %.2f / %.2f (>= 0.85 / 0.6)", r->saturation_kept_median,
                 r->saturation_kept_p10);
    else if (colour && r->clipped > 0.01)
        snprintf(why, why_len, "%.1f %% of the sky clipped (<= 1 %%)", 100.0 * r->clipped);
    else if (r->pillar > 1.05)
        snprintf(why, why_len, "the ground under the sun %.2fx the rest (<= 1.05)", r->pillar);
    else if (r->ground_to_sky >= 0.0 && r->ground_to_sky < 0.05)
        snprintf(why, why_len, "the twilight ground %.3f of the sky (>= 0.05)", r->ground_to_sky);
    return why[0] == '\0';
}

const double sky_dusk_suns[SKY_DUSK_SUNS] = {50.0, 10.0, 4.0, 0.0, -3.0, -6.0, -9.0, -12.0, -15.0, -18.0};

/* The library's default observer (sky.h): the 2026 vernal equinox from
 * 40 N 0 E, the time slider setting the time of day. */
static sky_observer default_observer(void)
{
    sky_observer o;
    memset(&o, 0, sizeof o);
    o.latitude_deg = 40.0;
    o.julian_day_utc = sky_julian_day(2026, 3, 20, 12, 0, 0.0);
    o.time_from_params = 1;
    return o;
}

int sky_dusk_brightness(sky_atmosphere_path path, sky_gl_profile profile, double sun_deg, int w, int h, double *mean,
                        char *err, size_t err_len)
{
    *mean = -1.0;
    sky_observer o = default_observer();
    /* noon: the sun's highest (50 degrees), for any height it never reaches */
    double t = sun_deg >= 49.0 ? 0.5 : evening_time(&o, sun_deg);
    sky_astronomy a;
    if (sky_compute_astronomy(&o, (float)t, NULL, 0, NULL, &a, NULL, 0) != SKY_OK) {
        snprintf(err, err_len, "no astronomy for time %g", t);
        return -1;
    }
    size_t n = (size_t)w * (size_t)h;
    float *ldr = malloc(sizeof(float) * 4 * n), sun[3];
    if (!ldr) {
        snprintf(err, err_len, "out of memory");
        return -1;
    }
    double sum_of_means = 0.0;
    for (int toward = 0; toward < 2; toward++) {
        float view[16], proj[16];
        sky_cli_camera_at(a.sun.az_deg + (toward ? 0.0 : 180.0), toward ? 10.0 : 20.0, 60.0, w, h, view, proj);
        if (render(path, SKY_TONE_MAP_HUE, profile, SKY_OUTPUT_LDR, 0, &o, t, view, proj, w, h, ldr, sun, err,
                   err_len)) {
            free(ldr);
            return -1;
        }
        double view_mean;
        sky_above(ldr, view, proj, w, h, 5.0, NULL, &view_mean);
        sum_of_means += view_mean;
    }
    free(ldr);
    *mean = 0.5 * sum_of_means;
    return 0;
}

int sky_dusk_measure(sky_atmosphere_path path, sky_gl_profile profile, int w, int h, double rel[SKY_DUSK_SUNS],
                     char *err, size_t err_len)
{
    double noon = 0.0;
    for (int i = 0; i < SKY_DUSK_SUNS; i++) {
        double m;
        if (sky_dusk_brightness(path, profile, sky_dusk_suns[i], w, h, &m, err, err_len)) return -1;
        if (i == 0) noon = m;
        rel[i] = noon > 0.0 ? m / noon : 0.0;
    }
    return 0;
}

int sky_dusk_ok(const double rel[SKY_DUSK_SUNS], char *why, size_t why_len)
{
    why[0] = '\0';
    static const double limit_at[3][2] = {{-6.0, 0.5}, {-12.0, 0.2}, {-18.0, 0.1}};
    for (int i = 0; i < SKY_DUSK_SUNS && !why[0]; i++) {
        double sun = sky_dusk_suns[i];
        for (int k = 0; k < 3; k++)
            if (sun == limit_at[k][0] && rel[i] > limit_at[k][1])
                snprintf(why, why_len, "%.3f of noon at %g degrees (<= %g)", rel[i], sun, limit_at[k][1]);
        if (!why[0] && sun == 0.0 && rel[i] > 1.0) snprintf(why, why_len, "sunset %.3f of noon (<= 1)", rel[i]);
        if (!why[0] && i > 0 && sky_dusk_suns[i - 1] <= 4.0 && rel[i] > 1.05 * rel[i - 1])
            snprintf(why, why_len, "%g degrees %.3f after %.3f at %g (at most 5 %% brighter)", sun, rel[i], rel[i - 1],
                     sky_dusk_suns[i - 1]);
    }
    return why[0] == '\0';
}

static int cmp_int(const void *a, const void *b) { return *(const int *)a - *(const int *)b; }

int sky_night_measure(sky_atmosphere_path path, sky_gl_profile profile, int full_moon, int w, int h,
                      sky_night_view *out, char *err, size_t err_len)
{
    memset(out, 0, sizeof *out);
    sky_observer o;
    memset(&o, 0, sizeof o);
    o.latitude_deg = 45.0;
    o.longitude_deg = full_moon ? 0.0 : 10.0;
    o.julian_day_utc = full_moon ? sky_julian_day(2024, 1, 26, 0, 0, 0.0) : sky_julian_day(2024, 1, 11, 22, 0, 0.0);
    float view[16], proj[16], sun[3];
    sky_cli_camera_at(full_moon ? 0.0 : 180.0, 30.0, 60.0, w, h, view, proj);
    size_t n = (size_t)w * (size_t)h;
    float *ldr = malloc(sizeof(float) * 4 * n);
    int *channel = malloc(sizeof(int) * 3 * n);
    int rc = -1;
    if (!ldr || !channel) {
        snprintf(err, err_len, "out of memory");
        goto done;
    }
    unsigned features = SKY_FEATURES_DEFAULT | SKY_MOON;
    if (render(path, SKY_TONE_MAP_HUE, profile, SKY_OUTPUT_LDR, features, &o, 0.0, view, proj, w, h, ldr, sun, err,
               err_len))
        goto done;
    size_t count = sky_above(ldr, view, proj, w, h, 10.0, channel, &out->mean);
    if (!count) {
        snprintf(err, err_len, "no sky more than 10 degrees up in the view");
        goto done;
    }
    double med[3];
    for (int i = 0; i < 3; i++) {
        qsort(channel + i * n, count, sizeof(int), cmp_int);
        out->median[i] = channel[i * n + count / 2];
        med[i] = out->median[i];
    }
    double sat;
    hue_saturation(med, &out->hue, &sat);
    out->b_over_r = med[2] / fmax(med[0], 1.0);
    rc = 0;
done:
    free(ldr);
    free(channel);
    return rc;
}

int sky_night_ok(const sky_night_view *v, int full_moon, double noon, char *why, size_t why_len)
{
    why[0] = '\0';
    int top = v->median[0] > v->median[1] ? v->median[0] : v->median[1];
    top = top > v->median[2] ? top : v->median[2];
    double hue_hi = full_moon ? 250.0 : 260.0, ratio = full_moon ? 1.6 : 1.2;
    if (v->hue < 190.0 || v->hue > hue_hi)
        snprintf(why, why_len, "hue %.0f (190..%.0f)", v->hue, hue_hi);
    else if (v->b_over_r < ratio)
        snprintf(why, why_len, "b/r %.2f (>= %.1f)", v->b_over_r, ratio);
    else if (full_moon ? top < 40 : (top < 8 || top > 40))
        snprintf(why, why_len, "brightest channel %d (%s)", top, full_moon ? ">= 40" : "8..40");
    else if (full_moon && v->mean > 0.35 * noon)
        snprintf(why, why_len, "%.3f of noon (<= 0.35)", v->mean / noon);
    return why[0] == '\0';
}

int sky_moon_disc_hues(sky_atmosphere_path path, sky_gl_profile profile, int w, int h, double *hdr_hue,
                       double *ldr_hue, char *err, size_t err_len)
{
    *hdr_hue = *ldr_hue = -1.0;
    sky_observer o;
    memset(&o, 0, sizeof o);
    o.latitude_deg = 45.0;
    o.julian_day_utc = sky_julian_day(2024, 1, 26, 0, 0, 0.0);
    sky_astronomy a;
    if (sky_compute_astronomy(&o, 0.0f, NULL, 0, NULL, &a, NULL, 0) != SKY_OK) {
        snprintf(err, err_len, "no astronomy for the full moon's date");
        return -1;
    }
    float view[16], proj[16], sun[3];
    sky_cli_camera_at(a.moon.az_deg, a.moon.alt_deg, 3.0, w, h, view, proj);
    size_t n = (size_t)w * (size_t)h;
    float *hdr = malloc(sizeof(float) * 4 * n), *ldr = malloc(sizeof(float) * 4 * n);
    int rc = -1;
    unsigned features = SKY_FEATURES_DEFAULT | SKY_MOON;
    if (!hdr || !ldr) {
        snprintf(err, err_len, "out of memory");
    } else if (!render(path, SKY_TONE_MAP_HUE, profile, SKY_OUTPUT_HDR, features, &o, 0.0, view, proj, w, h, hdr, sun,
                       err, err_len) &&
               !render(path, SKY_TONE_MAP_HUE, profile, SKY_OUTPUT_LDR, features, &o, 0.0, view, proj, w, h, ldr, sun,
                       err, err_len)) {
        double peak = 0.0, sum_h[3] = {0.0, 0.0, 0.0}, sum_l[3] = {0.0, 0.0, 0.0}, sat;
        for (size_t i = 0; i < n; i++) peak = fmax(peak, luminance(hdr + 4 * i));
        for (size_t i = 0; i < n; i++) {
            if (!(luminance(hdr + 4 * i) > 0.5 * peak)) continue;
            double lin[3];
            int byte[3];
            displayed(ldr + 4 * i, byte, lin);
            for (int c = 0; c < 3; c++) sum_h[c] += hdr[4 * i + c], sum_l[c] += lin[c];
        }
        hue_saturation(sum_h, hdr_hue, &sat);
        hue_saturation(sum_l, ldr_hue, &sat);
        rc = peak > 0.0 ? 0 : -1;
        if (rc) snprintf(err, err_len, "no moon in the view");
    }
    free(hdr);
    free(ldr);
    return rc;
}
