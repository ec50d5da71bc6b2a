/*
 * The atmosphere paths against the CPU reference: see atmo_error.h.
 */
#include "atmo_error.h"

#include "astro.h"
#include "atmosphere/reference.h"
#include "cli.h"
#include "osmesa_ctx.h"

#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846
#define FACES 6

const double sky_atmo_sun_elevations[SKY_ATMO_SUNS] = {90.0, 60.0, 30.0, 15.0, 5.0, 2.0, 0.0, -2.0, -4.0, -6.0};

void sky_atmo_direction(int k, double sun_az_deg, double *elevation_deg, double *azimuth_deg, double *weight)
{
    int ring = k / SKY_ATMO_AZIMUTHS, a = k % SKY_ATMO_AZIMUTHS;
    *elevation_deg = asin((ring + 0.5) / SKY_ATMO_RINGS) * 180.0 / PI;
    *azimuth_deg = sun_az_deg + 180.0 * a / (SKY_ATMO_AZIMUTHS - 1);
    /* trapezoid over the half circle: the two end azimuths count half */
    double w_az = (a == 0 || a == SKY_ATMO_AZIMUTHS - 1) ? 0.5 : 1.0;
    *weight = w_az / ((SKY_ATMO_AZIMUTHS - 1) * (double)SKY_ATMO_RINGS);
}

/* Horizon-frame unit vector for degrees (astro.c's, which takes radians). */
static void horizon_dir(double elevation_deg, double azimuth_deg, double d[3])
{
    sky_horizon_vector(elevation_deg * PI / 180.0, azimuth_deg * PI / 180.0, d);
}

double sky_atmo_time_for_altitude(const sky_observer *o, double alt_deg)
{
    double lo = 0.0, hi = 0.5;
    for (int i = 0; i < 60; i++) {
        double mid = 0.5 * (lo + hi);
        sky_astronomy a;
        if (sky_compute_astronomy(o, (float)mid, NULL, 0, NULL, &a, NULL, 0) != SKY_OK) return 0.5 * (lo + hi);
        if (a.sun.alt_deg < alt_deg) lo = mid;
        else hi = mid;
    }
    return 0.5 * (lo + hi);
}

/* ---- the reference, computed and cached ----------------------------------------------------- */

typedef struct make_job {
    sky_atmo_reference *ref;
    sky_atmosphere_params atm;
    int next, total, failed;
    pthread_mutex_t lock;
    FILE *progress;
} make_job;

static void *make_worker(void *arg)
{
    make_job *job = arg;
    for (;;) {
        pthread_mutex_lock(&job->lock);
        int item = job->next++;
        pthread_mutex_unlock(&job->lock);
        if (item >= job->total) return NULL;
        int s = item / SKY_ATMO_DIRECTIONS, k = item % SKY_ATMO_DIRECTIONS;
        double sun[3], view[3], el, az, w;
        horizon_dir(sky_atmo_sun_elevations[s], 90.0, sun);
        sky_atmo_direction(k, 90.0, &el, &az, &w);
        horizon_dir(el, az, view);
        sky_ref_options opt;
        memset(&opt, 0, sizeof opt);
        opt.paths = job->ref->paths;
        opt.seed = 0x5EEDull + (unsigned long long)item; /* reproducible, independent per item */
        sky_ref_result r;
        int rc = sky_ref_radiance(&job->atm, 0.0, view, sun, &opt, &r);
        pthread_mutex_lock(&job->lock);
        if (rc) job->failed = 1;
        for (int c = 0; c < 3; c++) job->ref->rgb[s][k][c] = r.rgb[c];
        job->ref->std_err[s][k] = r.luminance_std_err;
        if (job->progress && item % SKY_ATMO_DIRECTIONS == 0) {
            fputc('.', job->progress);
            fflush(job->progress);
        }
        pthread_mutex_unlock(&job->lock);
    }
}

int sky_atmo_reference_make(const char *path, int paths, int threads, FILE *progress, char *err, size_t err_len)
{
    sky_atmo_reference *ref = calloc(1, sizeof *ref);
    if (!ref) {
        snprintf(err, err_len, "out of memory");
        return -1;
    }
    make_job job;
    memset(&job, 0, sizeof job);
    job.ref = ref;
    ref->paths = paths;
    sky_atmosphere_get_preset(SKY_ATMOSPHERE_PRESET_EARTH, &job.atm);
    job.total = SKY_ATMO_SUNS * SKY_ATMO_DIRECTIONS;
    job.progress = progress;
    pthread_mutex_init(&job.lock, NULL);
    pthread_t tid[16];
    int started = 0;
    if (threads < 1) threads = 1;
    if (threads > 16) threads = 16;
    for (int i = 0; i < threads; i++)
        if (pthread_create(&tid[i], NULL, make_worker, &job) == 0) started++;
    if (!started) make_worker(&job);
    for (int i = 0; i < started; i++) pthread_join(tid[i], NULL);
    pthread_mutex_destroy(&job.lock);
    if (progress) fputc('\n', progress);
    if (job.failed) {
        snprintf(err, err_len, "the reference refused a direction (a bug)");
        free(ref);
        return -1;
    }
    FILE *f = fopen(path, "w");
    if (!f) {
        snprintf(err, err_len, "cannot write %s", path);
        free(ref);
        return -1;
    }
    fprintf(f, "# libsky atmosphere reference (sky/atmosphere/reference.c), written by sky-bench --make-reference.\n"
               "# Earth preset, observer at sea level, sun at azimuth 90. Rows: sun index, direction index\n"
               "# (tools/atmo_error.c: equal-area rings x azimuths from the sun), linear sRGB in kcd/m^2,\n"
               "# standard error of the luminance.\n");
    fprintf(f, "paths %d suns %d directions %d\n", paths, SKY_ATMO_SUNS, SKY_ATMO_DIRECTIONS);
    for (int s = 0; s < SKY_ATMO_SUNS; s++)
        for (int k = 0; k < SKY_ATMO_DIRECTIONS; k++)
            fprintf(f, "%d %d %.9g %.9g %.9g %.4g\n", s, k, ref->rgb[s][k][0], ref->rgb[s][k][1], ref->rgb[s][k][2],
                    ref->std_err[s][k]);
    int bad = ferror(f);
    if (fclose(f) || bad) {
        snprintf(err, err_len, "error writing %s", path);
        free(ref);
        return -1;
    }
    free(ref);
    return 0;
}

int sky_atmo_reference_load(const char *path, sky_atmo_reference *ref, char *err, size_t err_len)
{
    memset(ref, 0, sizeof *ref);
    FILE *f = fopen(path, "r");
    if (!f) {
        snprintf(err, err_len, "cannot read the reference %s (sky-bench --make-reference writes it)", path);
        return -1;
    }
    char line[256];
    int suns = 0, dirs = 0, rows = 0, header = 0;
    static char seen[SKY_ATMO_SUNS][SKY_ATMO_DIRECTIONS];
    memset(seen, 0, sizeof seen);
    while (fgets(line, sizeof line, f)) {
        if (line[0] == '#') continue;
        if (!header) {
            if (sscanf(line, "paths %d suns %d directions %d", &ref->paths, &suns, &dirs) != 3 ||
                suns != SKY_ATMO_SUNS || dirs != SKY_ATMO_DIRECTIONS || ref->paths < 1)
                break;
            header = 1;
            continue;
        }
        int s, k;
        double r, g, b, se;
        if (sscanf(line, "%d %d %lf %lf %lf %lf", &s, &k, &r, &g, &b, &se) != 6 || s < 0 || s >= SKY_ATMO_SUNS ||
            k < 0 || k >= SKY_ATMO_DIRECTIONS || !isfinite(r) || !isfinite(g) || !isfinite(b) || !isfinite(se) ||
            seen[s][k])
            break;
        seen[s][k] = 1;
        ref->rgb[s][k][0] = r, ref->rgb[s][k][1] = g, ref->rgb[s][k][2] = b;
        ref->std_err[s][k] = se;
        rows++;
    }
    fclose(f);
    if (!header || rows != SKY_ATMO_SUNS * SKY_ATMO_DIRECTIONS) {
        snprintf(err, err_len, "%s: malformed or incomplete (%d of %d rows)", path, rows,
                 SKY_ATMO_SUNS * SKY_ATMO_DIRECTIONS);
        return -1;
    }
    return 0;
}

/* ---- colour ------------------------------------------------------------------------------------ */

static double luminance(const double rgb[3]) { return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]; }

/* linear sRGB -> XYZ (IEC 61966-2-1) -> CIELAB with the D65 white of
 * luminance white_y */
static void rgb_to_lab(const double rgb[3], double white_y, double lab[3])
{
    double X = 0.4124 * rgb[0] + 0.3576 * rgb[1] + 0.1805 * rgb[2];
    double Y = 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
    double Z = 0.0193 * rgb[0] + 0.1192 * rgb[1] + 0.9505 * rgb[2];
    double t[3] = {X / (0.95047 * white_y), Y / white_y, Z / (1.08883 * white_y)}, f[3];
    for (int i = 0; i < 3; i++) {
        double v = t[i] > 0.0 ? t[i] : 0.0;
        f[i] = v > 216.0 / 24389.0 ? cbrt(v) : (24389.0 / 27.0 * v + 16.0) / 116.0;
    }
    lab[0] = 116.0 * f[1] - 16.0;
    lab[1] = 500.0 * (f[0] - f[1]);
    lab[2] = 200.0 * (f[1] - f[2]);
}

double sky_atmo_de2000(const double lab1[3], const double lab2[3])
{
    const double deg = PI / 180.0;
    double C1 = hypot(lab1[1], lab1[2]), C2 = hypot(lab2[1], lab2[2]), Cbar = 0.5 * (C1 + C2);
    double C7 = pow(Cbar, 7.0), G = 0.5 * (1.0 - sqrt(C7 / (C7 + pow(25.0, 7.0))));
    double a1 = (1.0 + G) * lab1[1], a2 = (1.0 + G) * lab2[1];
    double c1 = hypot(a1, lab1[2]), c2 = hypot(a2, lab2[2]);
    double h1 = (a1 == 0.0 && lab1[2] == 0.0) ? 0.0 : atan2(lab1[2], a1);
    double h2 = (a2 == 0.0 && lab2[2] == 0.0) ? 0.0 : atan2(lab2[2], a2);
    if (h1 < 0.0) h1 += 2.0 * PI;
    if (h2 < 0.0) h2 += 2.0 * PI;
    double dL = lab2[0] - lab1[0], dC = c2 - c1, dh = 0.0;
    if (c1 * c2 != 0.0) {
        dh = h2 - h1;
        if (dh > PI) dh -= 2.0 * PI;
        else if (dh < -PI) dh += 2.0 * PI;
    }
    double dH = 2.0 * sqrt(c1 * c2) * sin(0.5 * dh);
    double Lbar = 0.5 * (lab1[0] + lab2[0]), cbar = 0.5 * (c1 + c2), hbar = h1 + h2;
    if (c1 * c2 != 0.0) {
        if (fabs(h1 - h2) <= PI) hbar = 0.5 * (h1 + h2);
        else hbar = (h1 + h2 < 2.0 * PI) ? 0.5 * (h1 + h2 + 2.0 * PI) : 0.5 * (h1 + h2 - 2.0 * PI);
    }
    double T = 1.0 - 0.17 * cos(hbar - 30.0 * deg) + 0.24 * cos(2.0 * hbar) + 0.32 * cos(3.0 * hbar + 6.0 * deg) -
               0.20 * cos(4.0 * hbar - 63.0 * deg);
    double dtheta = 30.0 * deg * exp(-pow((hbar / deg - 275.0) / 25.0, 2.0));
    double c7 = pow(cbar, 7.0), Rc = 2.0 * sqrt(c7 / (c7 + pow(25.0, 7.0)));
    double Sl = 1.0 + 0.015 * (Lbar - 50.0) * (Lbar - 50.0) / sqrt(20.0 + (Lbar - 50.0) * (Lbar - 50.0));
    double Sc = 1.0 + 0.045 * cbar, Sh = 1.0 + 0.015 * cbar * T, Rt = -sin(2.0 * dtheta) * Rc;
    double l = dL / Sl, c = dC / Sc, h = dH / Sh;
    return sqrt(l * l + c * c + h * h + Rt * c * h);
}

/* ---- rendering and comparing ----------------------------------------------------------------- */

/* The six faces of a cube map: up, then north, east, south, west at the
 * horizon, as sky-render's camera builds them, and down (the ground: only
 * the irradiance reads it). */
static const double face_yaw[FACES] = {0.0, 0.0, 90.0, 180.0, 270.0, 0.0};
static const double face_pitch[FACES] = {90.0, 0.0, 0.0, 0.0, 0.0, -90.0};

typedef struct face {
    float view[16], proj[16];
    float *px; /* n^2 RGBA, bottom row first */
} face;

struct sky_atmo_hemisphere {
    sky_osmesa ctx;
    sky *s;
    sky_observer observer;
    face faces[FACES];
    float cover, density; /* the clouds (with SKY_CLOUDS in the config) */
    int n;                /* the faces' size */
};

sky_atmo_hemisphere *sky_atmo_hemisphere_create(const sky_config *base, char *err, size_t err_len)
{
    sky_atmo_hemisphere *h = calloc(1, sizeof *h);
    if (!h) {
        snprintf(err, err_len, "out of memory");
        return NULL;
    }
    /* 128 x 128 faces; 512 with clouds, which at 128 fade their detail
     * (clouds.glsl's footprint fade) over most of the sky */
    h->n = (base->features & SKY_CLOUDS) ? 512 : 128;
    if (sky_osmesa_create(&h->ctx, h->n, h->n, base->gl_profile, 1, err, err_len)) {
        free(h);
        return NULL;
    }
    sky_config cfg = *base;
    cfg.output = SKY_OUTPUT_HDR;
    /* the dome and what it holds of the base's: clouds, the night glows */
    unsigned keep = base->features & (SKY_CLOUDS | SKY_AIRGLOW | SKY_ZODIACAL);
    cfg.features = keep ? keep : SKY_FEATURES_NONE;
    cfg.get_proc_address = sky_osmesa_loader();
    h->s = sky_create(&cfg, err, err_len);
    int ok = h->s != NULL;
    for (int f = 0; f < FACES; f++) {
        sky_cli_camera_at(face_yaw[f], face_pitch[f], 90.0, h->n, h->n, h->faces[f].view, h->faces[f].proj);
        h->faces[f].px = malloc(sizeof(float) * 4 * h->n * h->n);
        if (!h->faces[f].px && ok) {
            snprintf(err, err_len, "out of memory");
            ok = 0;
        }
    }
    /* The equator's noon sun passes the zenith when the latitude is the
     * sun's declination: find it at the 2026 March equinox. */
    h->observer.julian_day_utc = sky_julian_day(2026, 3, 20, 12, 0, 0.0);
    h->observer.time_from_params = 1;
    sky_astronomy a;
    if (sky_compute_astronomy(&h->observer, 0.5f, NULL, 0, NULL, &a, NULL, 0) == SKY_OK)
        h->observer.latitude_deg = a.sun.dec_deg;
    if (!ok) {
        sky_atmo_hemisphere_destroy(h);
        return NULL;
    }
    return h;
}

void sky_atmo_hemisphere_destroy(sky_atmo_hemisphere *h)
{
    if (!h) return;
    for (int f = 0; f < FACES; f++) free(h->faces[f].px);
    sky_destroy(h->s);
    sky_osmesa_destroy(&h->ctx);
    free(h);
}

sky *sky_atmo_hemisphere_sky(sky_atmo_hemisphere *h) { return h->s; }

const sky_osmesa *sky_atmo_hemisphere_context(const sky_atmo_hemisphere *h) { return &h->ctx; }

void sky_atmo_hemisphere_clouds(sky_atmo_hemisphere *h, float cover, float density)
{
    h->cover = cover;
    h->density = density;
}

int sky_atmo_hemisphere_render(sky_atmo_hemisphere *h, double sun_alt_deg, double *elevation_deg,
                               double *azimuth_deg, char *err, size_t err_len)
{
    sky_params p = sky_default_params();
    p.cover = h->cover;
    p.density = h->density;
    p.time = (float)sky_atmo_time_for_altitude(&h->observer, sun_alt_deg);
    sky_set_observer(h->s, &h->observer);
    sky_set_params(h->s, &p);
    sky_lighting l;
    sky_get_lighting(h->s, &l);
    *elevation_deg = asin(l.sun_direction[1] > 1.0f ? 1.0 : l.sun_direction[1]) * 180.0 / PI;
    *azimuth_deg = atan2(l.sun_direction[0], -l.sun_direction[2]) * 180.0 / PI;
    for (int f = 0; f < FACES; f++) {
        if (sky_draw(h->s, h->faces[f].view, h->faces[f].proj) != SKY_OK) {
            snprintf(err, err_len, "sky_draw: %s", sky_last_error(h->s));
            return -1;
        }
        sky_osmesa_finish(&h->ctx);
        memcpy(h->faces[f].px, h->ctx.pixels, sizeof(float) * 4 * h->n * h->n);
    }
    return 0;
}

/* Bilinear read of direction d from the face that sees it most squarely. */
void sky_atmo_hemisphere_read(const sky_atmo_hemisphere *h, const double d[3], double rgb[3])
{
    const face *faces = h->faces;
    int best = 0;
    double best_z = -2.0;
    for (int f = 0; f < FACES; f++) {
        /* row 2 of the view matrix is minus the forward axis */
        const float *v = faces[f].view;
        double z = -(v[2] * d[0] + v[6] * d[1] + v[10] * d[2]);
        if (z > best_z) best_z = z, best = f;
    }
    const float *v = faces[best].view;
    double xc = v[0] * d[0] + v[4] * d[1] + v[8] * d[2], yc = v[1] * d[0] + v[5] * d[1] + v[9] * d[2];
    /* 90 degree square faces: ndc = camera x / z, y / z */
    double px = (xc / best_z * 0.5 + 0.5) * h->n - 0.5, py = (yc / best_z * 0.5 + 0.5) * h->n - 0.5;
    px = px < 0.0 ? 0.0 : (px > h->n - 1 ? h->n - 1 : px);
    py = py < 0.0 ? 0.0 : (py > h->n - 1 ? h->n - 1 : py);
    int x0 = (int)px, y0 = (int)py, x1 = x0 + 1 < h->n ? x0 + 1 : x0, y1 = y0 + 1 < h->n ? y0 + 1 : y0;
    double fx = px - x0, fy = py - y0;
    const float *p = faces[best].px;
    for (int c = 0; c < 3; c++) {
        double a = p[(y0 * h->n + x0) * 4 + c] * (1 - fx) + p[(y0 * h->n + x1) * 4 + c] * fx;
        double b = p[(y1 * h->n + x0) * 4 + c] * (1 - fx) + p[(y1 * h->n + x1) * 4 + c] * fx;
        rgb[c] = a * (1 - fy) + b * fy;
    }
}

void sky_atmo_hemisphere_irradiance(const sky_atmo_hemisphere *h, const double n[3], double rgb[3])
{
    rgb[0] = rgb[1] = rgb[2] = 0.0;
    for (int f = 0; f < FACES; f++) {
        const float *v = h->faces[f].view;
        for (int py = 0; py < h->n; py++)
            for (int px = 0; px < h->n; px++) {
                /* the pixel's direction: camera (x, y, -1) back to the
                 * world through the view's rotation (its transpose) */
                double x = (px + 0.5) / h->n * 2.0 - 1.0, y = (py + 0.5) / h->n * 2.0 - 1.0;
                double len = sqrt(x * x + y * y + 1.0), d[3];
                for (int k = 0; k < 3; k++) d[k] = (v[4 * k] * x + v[4 * k + 1] * y - v[4 * k + 2]) / len;
                double c = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
                if (c <= 0.0) continue;
                /* the pixel's solid angle on a 90-degree face */
                double w = (2.0 / h->n) * (2.0 / h->n) / (len * len * len);
                const float *p = h->faces[f].px + 4 * ((size_t)py * h->n + (size_t)px);
                for (int k = 0; k < 3; k++) rgb[k] += p[k] * c * w;
            }
    }
}

void sky_atmo_hemisphere_sh_check(sky_atmo_hemisphere *h, const double n[3], double *rendered, double *sh_all,
                                  double *sh_nine)
{
    sky_irradiance_sh sh, nine;
    sky_get_irradiance_sh(h->s, &sh); /* cached after the first normal */
    nine = sh;
    memset(nine.radiance_l4, 0, sizeof nine.radiance_l4);
    memset(nine.radiance_zonal, 0, sizeof nine.radiance_zonal);
    double ref[3], e[3], e9[3];
    float nf[3] = {(float)n[0], (float)n[1], (float)n[2]}, ef[3], ef9[3];
    sky_atmo_hemisphere_irradiance(h, n, ref);
    sky_irradiance_sh_eval(&sh, nf, ef);
    sky_irradiance_sh_eval(&nine, nf, ef9);
    for (int i = 0; i < 3; i++) e[i] = ef[i], e9[i] = ef9[i];
    *rendered = luminance(ref);
    *sh_all = luminance(e);
    *sh_nine = luminance(e9);
}

int sky_atmo_measure(const sky_atmo_reference *ref, const sky_config *base, sky_atmo_errors *out, char *err,
                     size_t err_len)
{
    memset(out, 0, sizeof *out);
    sky_atmo_hemisphere *h = sky_atmo_hemisphere_create(base, err, err_len);
    if (!h) return -1;
    int rc = 0;
    double day_weight = 0.0, tw_weight = 0.0;
    for (int si = 0; si < SKY_ATMO_SUNS && !rc; si++) {
        double el = 0.0, az = 0.0, target = sky_atmo_sun_elevations[si];
        rc = sky_atmo_hemisphere_render(h, target, &el, &az, err, err_len);
        if (rc) break;
        /* fixed exposure: the reference sky's mean luminance at half the
         * white (L* 76) */
        double mean_ref = 0.0;
        for (int k = 0; k < SKY_ATMO_DIRECTIONS; k++) {
            double de, da, w;
            sky_atmo_direction(k, az, &de, &da, &w);
            mean_ref += w * luminance(ref->rgb[si][k]);
        }
        double white = 2.0 * (mean_ref > 0.0 ? mean_ref : 1e-30);
        double sum_rel = 0.0, max_rel = 0.0, sum_de = 0.0;
        for (int k = 0; k < SKY_ATMO_DIRECTIONS; k++) {
            double de, da, w, d[3], rgb[3], lab_ref[3], lab[3];
            sky_atmo_direction(k, az, &de, &da, &w);
            horizon_dir(de, da, d);
            sky_atmo_hemisphere_read(h, d, rgb);
            double y_ref = luminance(ref->rgb[si][k]), y = luminance(rgb);
            /* relative to the reference, which may be all but black in
             * deep twilight (the planet's shadow): floored at 1 % of the
             * sky's mean */
            double rel = fabs(y - y_ref) / fmax(y_ref, 0.01 * mean_ref + 1e-30);
            sum_rel += w * rel;
            if (rel > max_rel) max_rel = rel;
            rgb_to_lab(ref->rgb[si][k], white, lab_ref);
            rgb_to_lab(rgb, white, lab);
            sum_de += w * sky_atmo_de2000(lab_ref, lab);
        }
        out->mean_rel[si] = sum_rel;
        out->max_rel[si] = max_rel;
        out->mean_de2000[si] = sum_de;
        if (target >= 0.0) {
            out->mean_rel_day += sum_rel;
            out->mean_de2000_day += sum_de;
            if (max_rel > out->max_rel_day) out->max_rel_day = max_rel;
            day_weight += 1.0;
        } else {
            out->mean_rel_twilight += sum_rel;
            out->mean_de2000_twilight += sum_de;
            tw_weight += 1.0;
        }
    }
    if (day_weight > 0.0) out->mean_rel_day /= day_weight, out->mean_de2000_day /= day_weight;
    if (tw_weight > 0.0) out->mean_rel_twilight /= tw_weight, out->mean_de2000_twilight /= tw_weight;
    sky_atmo_hemisphere_destroy(h);
    return rc;
}
