/*
 * Hillaire's LUT atmosphere, the CPU builder (hillaire.h). Pure C, float
 * tables, double arithmetic. No GL, no global mutable state, no printing.
 *
 * Conventions shared by every table (so the GLSL twins can mirror them):
 *  - a table coordinate x in 0..1 maps to the texture coordinate
 *    0.5/N + x (1 - 1/N) (Bruneton 2017, GetTextureCoordFromUnitRange):
 *    x = 0 and x = 1 land on the centres of the edge texels, so texel i
 *    stores the value at x = i / (N - 1) exactly;
 *  - lookups are bilinear exactly as GL_LINEAR with CLAMP_TO_EDGE does
 *    them (texel centres at (i + 0.5) / N, indices clamped to the edge);
 *  - ray/sphere distances use the discriminant r^2 (mu^2 - 1) + R^2
 *    clamped at 0 before the sqrt, and the root that cancels is written
 *    as (r^2 - R^2) / (-r mu + sqrt(disc)) (Bruneton 2017, sec. 2.2);
 *  - whether a ray meets the ground is decided once from the doubles the
 *    caller has (or from the table row a texel belongs to), never
 *    re-derived from a texture coordinate.
 *
 * Along every ray the optical depth of each segment is integrated
 * analytically, with each exponential density exactly exponential in
 * path length between the segment's ends (exact on a vertical ray) and
 * the ozone tent by the trapezoid; the in-scattered light of a segment
 * uses the energy-conserving form (S - S T_seg) / sigma_t (Hillaire 2020,
 * sec. 5.6.3). Segments close quadratically onto the ray's lowest point
 * (its start, its end or the tangent point), where the air is densest.
 */
#include "hillaire.h"
#include "atmosphere.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* ---- the medium ------------------------------------------------------------ */

typedef struct hl_medium {
    double R, Rt, H;      /* ground, top, sqrt(Rt^2 - R^2): km */
    double hr, hm;        /* scale heights */
    double oz_peak, oz_hw;
    double g;
    double br[3], bms[3], bme[3], bo[3], albedo[3];
} hl_medium;

static void medium_from(const sky_atmosphere_params *a, hl_medium *m)
{
    m->R = a->planet_radius_km;
    m->Rt = a->top_radius_km;
    m->H = sqrt(m->Rt * m->Rt - m->R * m->R);
    m->hr = a->rayleigh_scale_height_km;
    m->hm = a->mie_scale_height_km;
    m->oz_peak = a->ozone_peak_km;
    m->oz_hw = a->ozone_half_width_km;
    m->g = a->mie_g;
    for (int c = 0; c < 3; c++) {
        m->br[c] = a->rayleigh_scattering[c];
        m->bms[c] = a->mie_scattering[c];
        m->bme[c] = a->mie_extinction[c];
        m->bo[c] = a->ozone_absorption[c];
        m->albedo[c] = a->ground_albedo[c];
    }
}

/* Relative densities at a radius: Rayleigh, Mie (exponential) and ozone
 * (the tent of sky.h). */
typedef struct hl_dens {
    double r, m, o;
} hl_dens;

static hl_dens density_at(const hl_medium *m, double radius)
{
    double h = radius - m->R;
    if (h < 0.0) h = 0.0;
    hl_dens d;
    d.r = exp(-h / m->hr);
    d.m = exp(-h / m->hm);
    double o = 1.0 - fabs(h - m->oz_peak) / m->oz_hw;
    d.o = o > 0.0 ? o : 0.0;
    return d;
}

/* Integral over a segment of length ds of a density exp(-h / scale)
 * that is exponential in path length between heights ha and hb (values
 * da, db): ds (db - da) / x with x = ln(db / da) = -(hb - ha) / scale,
 * which needs no further exponential; a Taylor term for x near 0. */
static double seg_exp(double da, double db, double ha, double hb, double scale, double ds)
{
    double x = -(hb - ha) / scale;
    if (fabs(x) < 1e-4) return da * ds * (1.0 + x * (0.5 + x / 6.0));
    return ds * (db - da) / x;
}

/* Antiderivative in altitude of the ozone tent max(0, 1 - |h - p| / w). */
static double tent_integral(double h, double p, double w)
{
    double x = h - p;
    if (x <= -w) return 0.0;
    if (x <= 0.0) return 0.5 * (x + w) * (x + w) / w;
    if (x < w) return 0.5 * w + x - 0.5 * x * x / w;
    return w;
}

/* The ozone column of a segment. Every segment lies on one side of the
 * ray's lowest point (the layout puts a boundary there), so altitude is
 * monotone along it; taking it as linear in path length, the tent's
 * kinks are integrated exactly (a trapezoid across the peak at 25 km is
 * off by several per cent of the column on the long grazing segments). */
static double seg_ozone(const hl_medium *m, double ha, double hb, double oa, double ob, double ds)
{
    double dh = hb - ha;
    if (fabs(dh) < 1e-6 * m->oz_hw) return 0.5 * (oa + ob) * ds;
    return ds * (tent_integral(hb, m->oz_peak, m->oz_hw) - tent_integral(ha, m->oz_peak, m->oz_hw)) / dh;
}

/* The column (sea-level-equivalent km of each constituent) of a segment. */
static hl_dens seg_column(const hl_medium *m, hl_dens a, double ra, hl_dens b, double rb, double ds)
{
    hl_dens c;
    double ha = ra - m->R, hb = rb - m->R;
    if (ha < 0.0) ha = 0.0;
    if (hb < 0.0) hb = 0.0;
    c.r = seg_exp(a.r, b.r, ha, hb, m->hr, ds);
    c.m = seg_exp(a.m, b.m, ha, hb, m->hm, ds);
    c.o = seg_ozone(m, ha, hb, a.o, b.o, ds);
    return c;
}

static double tau_of(const hl_medium *m, int ch, hl_dens col)
{
    return m->br[ch] * col.r + m->bme[ch] * col.m + m->bo[ch] * col.o;
}

/* (1 - e^-tau) / tau, the energy-conserving weight of a segment, from
 * e = e^-tau that the caller has anyway; a series where 1 - e cancels. */
static double seg_weight(double tau, double e)
{
    if (tau > 1e-3) return (1.0 - e) / tau;
    return 1.0 - tau * (0.5 - tau / 6.0);
}

/* ---- geometry ---------------------------------------------------------------- */

static double clamp(double x, double lo, double hi)
{
    return x < lo ? lo : x > hi ? hi : x;
}

static double safe_sqrt(double x)
{
    return sqrt(x > 0.0 ? x : 0.0);
}

/* Distance from radius r (inside the shell) along mu to the top. */
static double dist_to_top(const hl_medium *m, double r, double mu)
{
    double disc = r * r * (mu * mu - 1.0) + m->Rt * m->Rt;
    double d = -r * mu + safe_sqrt(disc);
    return d > 0.0 ? d : 0.0;
}

/* Whether the ray from r along mu meets the ground (r >= R). */
static int hits_ground(const hl_medium *m, double r, double mu)
{
    return mu < 0.0 && r * r * (mu * mu - 1.0) + m->R * m->R >= 0.0;
}

/* Distance to the ground for a ray that meets it, in the form without
 * cancellation (the product of the two roots is r^2 - R^2). */
static double dist_to_ground(const hl_medium *m, double r, double mu)
{
    double disc = r * r * (mu * mu - 1.0) + m->R * m->R;
    double num = r * r - m->R * m->R;
    double den = -r * mu + safe_sqrt(disc);
    if (!(num > 0.0) || !(den > 0.0)) return 0.0;
    return num / den;
}

/* Segment boundaries on [0, L]: n segments closing quadratically onto
 * the lowest point tl (clamped into [0, L]) from both sides. The
 * quadratic map keeps the spacing smooth (the quadrature stays second
 * order) while the segments in the densest air are short. */
typedef struct hl_layout {
    double L, tl;
    int n1, n2;
} hl_layout;

static void layout_init(hl_layout *ly, double L, double tl, int n)
{
    ly->L = L;
    if (n < 2 || !(tl > 0.0) || !(L > 0.0)) {
        ly->tl = 0.0;
        ly->n1 = 0;
        ly->n2 = n;
    } else if (tl >= L) {
        ly->tl = L;
        ly->n1 = n;
        ly->n2 = 0;
    } else {
        ly->tl = tl;
        int n1 = (int)floor(n * tl / L + 0.5);
        if (n1 < 1) n1 = 1;
        if (n1 > n - 1) n1 = n - 1;
        ly->n1 = n1;
        ly->n2 = n - n1;
    }
}

static double layout_t(const hl_layout *ly, int k)
{
    if (k <= ly->n1) {
        if (ly->n1 == 0) return 0.0;
        double u = (double)(ly->n1 - k) / ly->n1;
        return ly->tl * (1.0 - u * u);
    }
    double u = (double)(k - ly->n1) / ly->n2;
    return k == ly->n1 + ly->n2 ? ly->L : ly->tl + (ly->L - ly->tl) * u * u;
}

/* Radius at distance t along a ray from radius r with cosine mu. */
static double radius_along(double r, double mu, double t)
{
    return safe_sqrt(r * r + 2.0 * r * mu * t + t * t);
}

/* ---- texture coordinates -------------------------------------------------------- */

static double unit_to_tex(double x, int n)
{
    return 0.5 / n + x * (1.0 - 1.0 / n);
}

/* GL_LINEAR + CLAMP_TO_EDGE on a w x h RGB float table. */
static void bilinear(const float *tab, int w, int h, double u, double v, double rgb[3])
{
    if (!isfinite(u)) u = 0.0;
    if (!isfinite(v)) v = 0.0;
    double x = clamp(u, 0.0, 1.0) * w - 0.5, y = clamp(v, 0.0, 1.0) * h - 0.5;
    double fx0 = floor(x), fy0 = floor(y);
    double fx = x - fx0, fy = y - fy0;
    int x0 = (int)fx0, y0 = (int)fy0, x1 = x0 + 1, y1 = y0 + 1;
    if (x0 < 0) x0 = 0;
    if (y0 < 0) y0 = 0;
    if (x1 > w - 1) x1 = w - 1;
    if (y1 > h - 1) y1 = h - 1;
    if (x0 > w - 1) x0 = w - 1;
    if (y0 > h - 1) y0 = h - 1;
    const float *p00 = tab + ((size_t)y0 * w + x0) * 3, *p10 = tab + ((size_t)y0 * w + x1) * 3;
    const float *p01 = tab + ((size_t)y1 * w + x0) * 3, *p11 = tab + ((size_t)y1 * w + x1) * 3;
    for (int c = 0; c < 3; c++) {
        double a = p00[c] + (p10[c] - p00[c]) * fx;
        double b = p01[c] + (p11[c] - p01[c]) * fx;
        rgb[c] = a + (b - a) * fy;
    }
}

/* Bruneton 2017 (GetTransmittanceTextureUvFromRMu): x_r = rho / H with
 * rho = sqrt(r^2 - R^2) the distance to the horizon; x_mu places the
 * distance d to the top between d_min = Rt - r (straight up) and
 * d_max = rho + H (the ray that grazes the ground). Only rays that do not
 * meet the ground have a texel; mu below the horizon clamps to the
 * grazing column (callers decide ground hits themselves). */
static void transmittance_unit(const hl_medium *m, double r, double mu, double *xmu, double *xr)
{
    r = clamp(r, m->R, m->Rt);
    mu = clamp(mu, -1.0, 1.0);
    double rho = safe_sqrt(r * r - m->R * m->R);
    double d = dist_to_top(m, r, mu);
    double dmin = m->Rt - r, dmax = rho + m->H;
    *xmu = dmax > dmin ? clamp((d - dmin) / (dmax - dmin), 0.0, 1.0) : 0.0;
    *xr = clamp(rho / m->H, 0.0, 1.0);
}

/* The inverse: the (r, mu) a table coordinate stands for. */
static void transmittance_rmu(const hl_medium *m, double xmu, double xr, double *r, double *mu)
{
    double rho = m->H * xr;
    double rr = sqrt(rho * rho + m->R * m->R);
    double dmin = m->Rt - rr, dmax = rho + m->H;
    double d = dmin + xmu * (dmax - dmin);
    /* the law of cosines in the triangle centre - point - exit point */
    double c = d <= 0.0 ? 1.0 : (m->H * m->H - rho * rho - d * d) / (2.0 * rr * d);
    *r = rr;
    *mu = clamp(c, -1.0, 1.0);
}

/* ---- settings and allocation ---------------------------------------------------- */

static int size_ok(int v)
{
    return v >= 4 && v <= 1024;
}

static int steps_ok(int v)
{
    return v >= 1 && v <= 256;
}

static int pick(int v, int dflt)
{
    return v == 0 ? dflt : v;
}

/* The Legendre moment chi_l = 2 pi int p(mu) P_l(mu) dmu of Cornette and
 * Shanks' phase (chi_0 = 1): (3/2) (1 + mu^2) / (2 + g^2) times
 * Henyey-Greenstein's, whose chi_l is g^l, and mu^2 P_l = a P_l+2 + b P_l
 * + c P_l-2 (from (2l + 1) mu P_l = (l + 1) P_l+1 + l P_l-1). */
static double cs_moment(int l, double g)
{
    double n = 2.0 * l + 1.0;
    double a = (l + 1.0) * (l + 2.0) / (n * (n + 2.0));
    double b = (l + 1.0) * (l + 1.0) / (n * (n + 2.0)) + (double)l * l / (n * (n - 2.0));
    double c = l * (l - 1.0) / (n * (n - 2.0));
    double g_l2 = 1.0; /* g^(l - 2), or 0 for l < 2 */
    for (int i = 2; i < l; i++) g_l2 *= g;
    if (l < 2) g_l2 = 0.0;
    double g_l = l < 2 ? (l ? g : 1.0) : g_l2 * g * g;
    return 1.5 / (2.0 + g * g) * ((1.0 + b) * g_l + a * g_l * g * g + c * g_l2);
}

int sky_hillaire_init(sky_hillaire_tables *t, const sky_atmosphere_params *atm, const sky_hillaire_settings *s,
                      char *err, size_t err_len)
{
    if (err && err_len) err[0] = '\0';
    if (!t) {
        sky_format(err, err_len, "hillaire: tables is NULL");
        return -1;
    }
    memset(t, 0, sizeof *t);
    if (!atm) {
        sky_format(err, err_len, "hillaire: atmosphere is NULL");
        return -1;
    }
    sky_atmosphere_params a;
    if (sky_atmosphere_is_zero(atm)) {
        sky_atmosphere_get_preset(SKY_ATMOSPHERE_PRESET_EARTH, &a);
    } else {
        if (sky_atmosphere_check(atm, err, err_len) != SKY_OK) return -1;
        a = *atm;
    }
    sky_hillaire_settings st;
    if (s) st = *s;
    else memset(&st, 0, sizeof st);
    st.transmittance_width = pick(st.transmittance_width, 256);
    st.transmittance_height = pick(st.transmittance_height, 64);
    st.transmittance_steps = pick(st.transmittance_steps, 40);
    st.multiscatter_size = pick(st.multiscatter_size, 32);
    st.multiscatter_directions = pick(st.multiscatter_directions, 64);
    st.multiscatter_steps = pick(st.multiscatter_steps, 20);
    st.skyview_width = pick(st.skyview_width, 192);
    st.skyview_height = pick(st.skyview_height, 108);
    st.skyview_steps = pick(st.skyview_steps, 30);
    const char *bad = NULL;
    if (!size_ok(st.transmittance_width) || !size_ok(st.transmittance_height)) bad = "transmittance size (4..1024)";
    else if (!size_ok(st.multiscatter_size)) bad = "multiscatter_size (4..1024)";
    else if (!size_ok(st.skyview_width) || !size_ok(st.skyview_height)) bad = "skyview size (4..1024)";
    else if (!steps_ok(st.transmittance_steps)) bad = "transmittance_steps (1..256)";
    else if (!steps_ok(st.multiscatter_directions)) bad = "multiscatter_directions (1..256)";
    else if (!steps_ok(st.multiscatter_steps)) bad = "multiscatter_steps (1..256)";
    else if (!steps_ok(st.skyview_steps)) bad = "skyview_steps (1..256)";
    if (bad) {
        sky_format(err, err_len, "hillaire: %s is out of range", bad);
        return -1;
    }
    size_t nt = (size_t)st.transmittance_width * st.transmittance_height * 3;
    size_t nm = (size_t)st.multiscatter_size * st.multiscatter_size * 3;
    size_t ns = (size_t)st.skyview_width * st.skyview_height * 3;
    t->transmittance = calloc(nt, sizeof(float));
    t->multiscatter = calloc(nm, sizeof(float));
    t->ms_moments = calloc(nm / 3 * SKY_HL_MOMENTS, sizeof(float));
    /* the sky-view builder's: a line of both tables, 8 numbers a column */
    t->scratch = calloc((size_t)st.multiscatter_size * SKY_HL_MS_ALL + (size_t)st.skyview_width * 8, sizeof(double));
    t->skyview = calloc(ns, sizeof(float));
    if (!t->transmittance || !t->multiscatter || !t->ms_moments || !t->scratch || !t->skyview) {
        sky_hillaire_free(t);
        sky_format(err, err_len, "hillaire: out of memory");
        return -1;
    }
    t->settings = st;
    t->atm = a;
    t->chi[0] = cs_moment(1, a.mie_g);
    t->chi[1] = cs_moment(2, a.mie_g);
    t->chi[2] = 0.1; /* Rayleigh's: Cornette-Shanks' at g = 0 */
    t->chi[3] = cs_moment(3, a.mie_g);
    t->chi[4] = cs_moment(4, a.mie_g);
    return 0;
}

void sky_hillaire_free(sky_hillaire_tables *t)
{
    if (!t) return;
    free(t->transmittance);
    free(t->multiscatter);
    free(t->ms_moments);
    free(t->scratch);
    t->scratch = NULL;
    free(t->skyview);
    t->transmittance = t->multiscatter = t->ms_moments = t->skyview = NULL;
}

/* ---- transmittance ---------------------------------------------------------------- */

/* Optical depth per channel from r along mu over [0, L] in n segments. */
static void optical_depth(const hl_medium *m, double r, double mu, double L, int n, double tau[3])
{
    hl_layout ly;
    layout_init(&ly, L, -r * mu, n);
    hl_dens col = {0.0, 0.0, 0.0};
    double ta = 0.0, ra = r;
    hl_dens da = density_at(m, ra);
    for (int k = 1; k <= n; k++) {
        double tb = layout_t(&ly, k), rb = radius_along(r, mu, tb);
        hl_dens db = density_at(m, rb);
        hl_dens c = seg_column(m, da, ra, db, rb, tb - ta);
        col.r += c.r;
        col.m += c.m;
        col.o += c.o;
        ta = tb;
        ra = rb;
        da = db;
    }
    for (int c = 0; c < 3; c++) tau[c] = tau_of(m, c, col);
}

void sky_hillaire_build_transmittance(sky_hillaire_tables *t)
{
    if (!t || !t->transmittance) return;
    hl_medium m;
    medium_from(&t->atm, &m);
    int w = t->settings.transmittance_width, h = t->settings.transmittance_height;
    int n = t->settings.transmittance_steps;
    for (int j = 0; j < h; j++) {
        for (int i = 0; i < w; i++) {
            /* texel (i, j) holds x = i / (w - 1), y = j / (h - 1) */
            double r, mu, tau[3];
            transmittance_rmu(&m, (double)i / (w - 1), (double)j / (h - 1), &r, &mu);
            optical_depth(&m, r, mu, dist_to_top(&m, r, mu), n, tau);
            float *p = t->transmittance + ((size_t)j * w + i) * 3;
            for (int c = 0; c < 3; c++) p[c] = (float)exp(-tau[c]);
        }
    }
}

void sky_hillaire_transmittance_uv_sized(const sky_atmosphere_params *atm, double r, double mu, int width,
                                         int height, double *u, double *v)
{
    double xmu = 0.0, xr = 0.0;
    sky_atmosphere_params earth;
    if (atm && sky_atmosphere_is_zero(atm)) {
        sky_atmosphere_get_preset(SKY_ATMOSPHERE_PRESET_EARTH, &earth);
        atm = &earth;
    }
    if (atm && atm->top_radius_km > atm->planet_radius_km && atm->planet_radius_km > 0.0f) {
        hl_medium m;
        medium_from(atm, &m);
        transmittance_unit(&m, isfinite(r) ? r : m.R, isfinite(mu) ? mu : 1.0, &xmu, &xr);
    }
    if (width < 1) width = 1;
    if (height < 1) height = 1;
    if (u) *u = unit_to_tex(xmu, width);
    if (v) *v = unit_to_tex(xr, height);
}

void sky_hillaire_transmittance_uv(const sky_atmosphere_params *atm, double r, double mu, double *u, double *v)
{
    sky_hillaire_transmittance_uv_sized(atm, r, mu, 256, 64, u, v);
}

/* Table transmittance from (r, mu) inside the shell to the top, for a
 * ray the caller knows does not meet the ground. */
static void trans_table(const sky_hillaire_tables *t, const hl_medium *m, double r, double mu, double rgb[3])
{
    int w = t->settings.transmittance_width, h = t->settings.transmittance_height;
    double xmu, xr;
    transmittance_unit(m, r, mu, &xmu, &xr);
    bilinear(t->transmittance, w, h, unit_to_tex(xmu, w), unit_to_tex(xr, h), rgb);
}

/* The sun's transmittance at a point (0 in the planet's shadow). */
static void sun_transmittance(const sky_hillaire_tables *t, const hl_medium *m, double r, double mu_s, double rgb[3])
{
    if (hits_ground(m, r, mu_s)) {
        rgb[0] = rgb[1] = rgb[2] = 0.0;
        return;
    }
    trans_table(t, m, r, mu_s, rgb);
}

void sky_hillaire_transmittance(const sky_hillaire_tables *t, double r, double mu, double rgb[3])
{
    if (!rgb) return;
    rgb[0] = rgb[1] = rgb[2] = 0.0;
    if (!t || !t->transmittance || !isfinite(r) || !isfinite(mu)) return;
    hl_medium m;
    medium_from(&t->atm, &m);
    mu = clamp(mu, -1.0, 1.0);
    if (r < m.R) r = m.R;
    if (r > m.Rt) {
        /* above the top: the ray enters at the top (or misses the shell) */
        double disc = r * r * (mu * mu - 1.0) + m.Rt * m.Rt;
        if (mu >= 0.0 || disc < 0.0) {
            rgb[0] = rgb[1] = rgb[2] = 1.0;
            return;
        }
        double t0 = (r * r - m.Rt * m.Rt) / (-r * mu + sqrt(disc));
        double mu2 = (r * mu + t0) / m.Rt;
        r = m.Rt;
        mu = clamp(mu2, -1.0, 1.0);
    }
    if (hits_ground(&m, r, mu)) return;
    trans_table(t, &m, r, mu, rgb);
}

/* ---- phase functions ------------------------------------------------------------------ */

static double phase_rayleigh(double c)
{
    return 3.0 / (16.0 * M_PI) * (1.0 + c * c);
}

/* Cornette & Shanks 1992 (Hillaire 2020 eq. 4 uses it for Mie). */
static double phase_cs(double c, double g)
{
    double g2 = g * g, den = 1.0 + g2 - 2.0 * g * c;
    return 3.0 / (8.0 * M_PI) * (1.0 - g2) * (1.0 + c * c) / ((2.0 + g2) * den * sqrt(den));
}

/* ---- multiple scattering ---------------------------------------------------------- */

/* Hillaire 2020 Fig. 7 / sec. 5.5 maps u = 0.5 + 0.5 mu_s; here u = 0.5 +
 * 0.5 sign(mu_s) sqrt|mu_s|, so that the columns crowd where Psi_ms
 * changes fastest, the sun at the horizon (32 columns: 0.004 apart in
 * mu_s there instead of 0.065; what it gained against the reference:
 * docs/validation.md). v = altitude over the shell's thickness. Both go
 * through the texel-centre map. */
static double ms_u(double mu_s)
{
    mu_s = clamp(mu_s, -1.0, 1.0);
    return 0.5 + 0.5 * (mu_s < 0.0 ? -sqrt(-mu_s) : sqrt(mu_s));
}

/* The inverse: the mu_s of u (column i of n: u = i / (n - 1)). */
static double ms_mu_s(double u)
{
    double x = clamp(2.0 * u - 1.0, -1.0, 1.0);
    return x < 0.0 ? -x * x : x * x;
}

/* The multiple-scattering tables are interpolated in Psi^(1/16) and the
 * moments' ratios to Psi (hillaire.h). In the Earth's shadow Psi falls
 * by a factor of ten or more from one column to the next, and a linear
 * interpolation between them overshoots the geometric mean several
 * times over where the sixteenth root stays close (docs/validation.md
 * has the figures). */
static double ms_root(double psi)
{
    return psi > 0.0 ? pow(psi, 1.0 / 16.0) : 0.0;
}
static double ms_power(double root)
{
    double x = root * root;
    x *= x;
    x *= x;
    return x * x;
}
/* Interpolated roots and ratios (n of them after the three roots) back
 * to Psi and the moments, in place. */
static void ms_decode(double *v, int n)
{
    for (int c = 0; c < 3; c++) v[c] = ms_power(v[c]);
    for (int q = 0; q < n; q++) v[3 + q] *= v[q % 3];
}
/* ... and the other way */
static void ms_encode(double *v, int n)
{
    for (int q = 0; q < n; q++) v[3 + q] = v[q % 3] > 0.0 ? v[3 + q] / v[q % 3] : 0.0;
    for (int c = 0; c < 3; c++) v[c] = ms_root(v[c]);
}

static void multiscatter_unit(const hl_medium *m, double r, double mu_s, double *x, double *y)
{
    *x = ms_u(mu_s);
    *y = clamp((r - m->R) / (m->Rt - m->R), 0.0, 1.0);
}

static void ms_table(const sky_hillaire_tables *t, const hl_medium *m, double r, double mu_s, double rgb[3])
{
    int n = t->settings.multiscatter_size;
    double x, y;
    multiscatter_unit(m, r, mu_s, &x, &y);
    bilinear(t->multiscatter, n, n, unit_to_tex(x, n), unit_to_tex(y, n), rgb);
    ms_decode(rgb, 0);
}

/* Henyey-Greenstein's inverse distribution: the cosine about the peak
 * for xi in 0..1, and its density in that cosine (integral 1 over -1..1) */
static double hg_cosine(double g, double xi)
{
    if (fabs(g) < 1e-3) return 2.0 * xi - 1.0;
    double s = (1.0 - g * g) / (1.0 - g + 2.0 * g * xi);
    return clamp((1.0 + g * g - s * s) / (2.0 * g), -1.0, 1.0);
}
static double hg_density(double g, double c)
{
    double d = 1.0 + g * g - 2.0 * g * c;
    return 0.5 * (1.0 - g * g) / (d * sqrt(d));
}

/* Direction k of the n_half that one column traces, for the sun s =
 * (sx, sy, 0). Two sets, weighted by the balance heuristic: the first
 * n_half - n_peak spread evenly over the sphere in rings about the
 * zenith, so that the horizon, where the light's column jumps from the
 * ground's to the whole sky's, falls between rings; the n_peak others
 * distributed about the sun like Henyey-Greenstein with the aerosol's g,
 * for the first bounce's forward peak. Evenly spread directions alone
 * alias the two (they did not converge monotonically with their number:
 * docs/validation.md). Azimuths are a
 * golden-ratio sequence on 0..pi. The plane z = 0 holds the sun and the
 * observer, so the mirror image (x, y, -z) of each direction sees the
 * same light: the builder traces the half (z >= 0) and counts it twice.
 * *weight is what the direction's light counts in the mean over the
 * sphere (1 / n_half when all are even). */
static void ms_direction(int k, int n_half, int n_peak, double g, double sx, double sy, double d[3], double *weight)
{
    int n_even = n_half - n_peak;
    int first = k < n_even, j = first ? k : k - n_even, n_set = first ? n_even : n_peak;
    double xi = (j + 0.5) / n_set;
    double c = first ? 2.0 * xi - 1.0 : hg_cosine(g, xi);
    double phi = M_PI * fmod((j + 0.5) * 0.6180339887498949, 1.0), s = safe_sqrt(1.0 - c * c);
    if (first) { /* c along the zenith, s cos(phi) toward the sun's azimuth (x) */
        d[0] = s * cos(phi);
        d[1] = c;
    } else { /* c along the sun, s cos(phi) along (-sy, sx, 0) */
        d[0] = c * sx - s * cos(phi) * sy;
        d[1] = c * sy + s * cos(phi) * sx;
    }
    d[2] = s * sin(phi);
    *weight = 1.0 / (n_even + 2.0 * n_peak * hg_density(g, d[0] * sx + d[1] * sy));
}

/* ---- multiple scattering, order by order ------------------------------------------ */

/* Where each quantity sits in one order's texel (SKY_HL_ORDER floats):
 * the mean, then the moments in ms_moments' order, then the irradiance. */
enum {
    ORD_MEAN = 0,
    ORD_DX = 3,
    ORD_DY = 6,
    ORD_QXX = 9,
    ORD_QYY = 12,
    ORD_QXY = 15,
    ORD_Z3 = 18,
    ORD_Z4 = 21,
    ORD_IRR = 24
};

/* An order's table at (r, mu_s), bilinear as ms_table. */
static void order_lookup(const float *ord, const hl_medium *m, int n, double r, double mu_s, double out[SKY_HL_ORDER])
{
    double ux, uy;
    multiscatter_unit(m, r, mu_s, &ux, &uy);
    double x = clamp(unit_to_tex(ux, n), 0.0, 1.0) * n - 0.5, y = clamp(unit_to_tex(uy, n), 0.0, 1.0) * n - 0.5;
    double fx = x - floor(x), fy = y - floor(y);
    int x0 = (int)floor(x), y0 = (int)floor(y), x1 = x0 + 1, y1 = y0 + 1;
    x0 = x0 < 0 ? 0 : x0 > n - 1 ? n - 1 : x0;
    y0 = y0 < 0 ? 0 : y0 > n - 1 ? n - 1 : y0;
    x1 = x1 > n - 1 ? n - 1 : x1;
    y1 = y1 > n - 1 ? n - 1 : y1;
    const float *p00 = ord + ((size_t)y0 * n + x0) * SKY_HL_ORDER, *p10 = ord + ((size_t)y0 * n + x1) * SKY_HL_ORDER;
    const float *p01 = ord + ((size_t)y1 * n + x0) * SKY_HL_ORDER, *p11 = ord + ((size_t)y1 * n + x1) * SKY_HL_ORDER;
    for (int q = 0; q < SKY_HL_ORDER; q++) {
        double a = p00[q] + (p10[q] - p00[q]) * fx, b = p01[q] + (p11[q] - p01[q]) * fx;
        out[q] = a + (b - a) * fy;
    }
    ms_decode(out, SKY_HL_MOMENTS);
    for (int c = 0; c < 3; c++) out[ORD_IRR + c] = ms_power(out[ORD_IRR + c]);
}

/* The light that reaches a point (mean psi, moments mo as ms_moments)
 * scattered once more into the direction v, per unit scattering
 * coefficient: jr by the air, jm by the aerosol. v in the point's frame:
 * vx toward the sun's azimuth, vy up, vz2 the rest squared; p3, p4 the
 * Legendre polynomials of v's cosine to the sun. By Funk and Hecke, int
 * p(v . w) L(w) dw = sum over l of chi_l L_l(v), L_l the light's degree-l
 * spherical harmonic part and chi_l the phase's Legendre moments:
 * L_1(v) = D . v, L_2(v) = (5/2) v^T Q v, and the zonal parts about the
 * sun Z_l P_l(s . v). Rayleigh's phase has l = 0 and 2 alone. */
static void scatter_moments(const sky_hillaire_tables *t, const double *psi, const double *mo, double vx, double vy,
                            double vz2, double p3, double p4, double jr[3], double jm[3])
{
    for (int c = 0; c < 3; c++) {
        double l1 = mo[c] * vx + mo[3 + c] * vy;
        double qxx = mo[6 + c], qyy = mo[9 + c];
        double l2 = 2.5 * (qxx * vx * vx + qyy * vy * vy - (qxx + qyy) * vz2 + 2.0 * mo[12 + c] * vx * vy);
        double zonal = t->chi[3] * mo[15 + c] * p3 + t->chi[4] * mo[18 + c] * p4;
        /* the truncated expansion of a light that is nearly all in one
         * direction (a deep twilight) can go below zero; the light it
         * stands for cannot */
        jr[c] = fmax(psi[c] + t->chi[2] * l2, 0.0);
        jm[c] = fmax(psi[c] + t->chi[0] * l1 + t->chi[1] * l2 + zonal, 0.0);
    }
}

/* Legendre's P_3 and P_4 */
static double legendre3(double x)
{
    return 0.5 * x * (5.0 * x * x - 3.0);
}
static double legendre4(double x)
{
    double x2 = x * x;
    return 0.125 * (35.0 * x2 * x2 - 30.0 * x2 + 3.0);
}

/* One ray from a texel of radius r along a direction of cosine mu to
 * the zenith, marched for an order's table: its length, whether it meets
 * the ground, the transmittance to its end, and per segment the
 * midpoint's distance and radius and the weights (scattering coefficient
 * x column x transmittance x the energy-conserving factor) that the
 * air's and the aerosol's light there takes. */
typedef struct hl_ray {
    int n, ground;
    double L, tr[3];
    double tm[SKY_HL_MAX_STEPS], rm[SKY_HL_MAX_STEPS], wr[SKY_HL_MAX_STEPS][3], wm[SKY_HL_MAX_STEPS][3];
} hl_ray;

static void march_ray(const hl_medium *m, double r, double mu, int ns, hl_ray *g)
{
    g->ground = hits_ground(m, r, mu);
    g->L = g->ground ? dist_to_ground(m, r, mu) : dist_to_top(m, r, mu);
    g->n = g->L > 0.0 ? (ns < SKY_HL_MAX_STEPS ? ns : SKY_HL_MAX_STEPS) : 0;
    g->tr[0] = g->tr[1] = g->tr[2] = 1.0;
    if (!g->n) return;
    hl_layout ly;
    layout_init(&ly, g->L, -r * mu, g->n);
    double ta = 0.0, ra = r;
    hl_dens da = density_at(m, ra);
    for (int s = 0; s < g->n; s++) {
        double tb = layout_t(&ly, s + 1), rb = radius_along(r, mu, tb);
        hl_dens db = density_at(m, rb);
        hl_dens col = seg_column(m, da, ra, db, rb, tb - ta);
        g->tm[s] = 0.5 * (ta + tb);
        g->rm[s] = radius_along(r, mu, g->tm[s]);
        for (int c = 0; c < 3; c++) {
            double tau = tau_of(m, c, col), e = exp(-tau), wgt = seg_weight(tau, e) * g->tr[c];
            g->wr[s][c] = m->br[c] * col.r * wgt;
            g->wm[s][c] = m->bms[c] * col.m * wgt;
            g->tr[c] *= e;
        }
        ta = tb;
        ra = rb;
        da = db;
    }
}

/* The light a marched ray g along w brings a texel of radius r under the
 * sun (sx, sy, 0), lk: the previous order's field (prev, an n x n table)
 * scattered toward it at each segment's midpoint (scatter_moments at the
 * midpoint's own texel, with w as the view), or for order 1 (prev NULL)
 * the sunlight the real phase functions turn toward it; where w meets
 * the Lambertian ground, the ground's reflection of the previous order's
 * irradiance (of the sun's for order 1). */
static void ray_light(const sky_hillaire_tables *t, const hl_medium *m, double r, const float *prev, int n,
                      const hl_ray *g, const double w[3], double sx, double sy, double lk[3])
{
    double mu = w[1], cos_sw = w[0] * sx + w[1] * sy, p3 = legendre3(cos_sw), p4 = legendre4(cos_sw);
    /* the sun's light turned toward x: from the sun into -w */
    double pr = phase_rayleigh(cos_sw), pm = phase_cs(cos_sw, m->g);
    lk[0] = lk[1] = lk[2] = 0.0;
    for (int s = 0; s < g->n; s++) {
        double tm = g->tm[s], rm = g->rm[s], jr[3], jm[3];
        double mus = clamp((w[0] * tm * sx + (r + w[1] * tm) * sy) / rm, -1.0, 1.0);
        if (!prev) {
            double ts[3];
            sun_transmittance(t, m, rm, mus, ts);
            for (int c = 0; c < 3; c++) jr[c] = pr * ts[c], jm[c] = pm * ts[c];
        } else { /* w in the midpoint's frame */
            double o[SKY_HL_ORDER], sh = safe_sqrt(1.0 - mus * mus);
            double vy = clamp((tm + r * mu) / rm, -1.0, 1.0);
            double vx = sh > 1e-6 ? clamp((cos_sw - mus * vy) / sh, -1.0, 1.0) : 0.0;
            order_lookup(prev, m, n, rm, mus, o);
            scatter_moments(t, o + ORD_MEAN, o + ORD_DX, vx, vy, fmax(1.0 - vx * vx - vy * vy, 0.0), p3, p4, jr, jm);
        }
        for (int c = 0; c < 3; c++) lk[c] += g->wr[s][c] * jr[c] + g->wm[s][c] * jm[c];
    }
    if (g->ground) { /* the irradiance there: the sun's, or the previous order's */
        double gx = w[0] * g->L, gy = r + w[1] * g->L, gz = w[2] * g->L;
        double rg = sqrt(gx * gx + gy * gy + gz * gz), mug = clamp((gx * sx + gy * sy) / rg, -1.0, 1.0);
        double e[3] = {0, 0, 0};
        if (!prev) {
            if (mug > 0.0) trans_table(t, m, m->R, mug, e);
            for (int c = 0; c < 3; c++) e[c] *= fmax(mug, 0.0);
        } else {
            double o[SKY_HL_ORDER];
            order_lookup(prev, m, n, m->R, mug, o);
            for (int c = 0; c < 3; c++) e[c] = o[ORD_IRR + c];
        }
        for (int c = 0; c < 3; c++) lk[c] += g->tr[c] * e[c] * m->albedo[c] / M_PI;
    }
}

/* One row (radius r, every mu_s) of an order's table: the light that
 * reaches each texel after k scatterings, from the one before (prev; NULL:
 * k = 1, the sun's light scattered once and the sunlit ground), along
 * the directions w of ms_direction (ray_light). Means over the sphere:
 *   mean = mean of L(w), D = 3 mean(L w), Q = 3 mean(L w w^T) - mean,
 *   Z_l = (2l + 1) mean(L P_l(s . w)) (k = 1 only: the later orders are
 *   smooth), irradiance = 4 pi mean(L max(w_y, 0)).
 * The evenly spread directions' rings are the same at every column (only
 * their azimuth from the sun differs): each ring's ray is marched once
 * for the row; those about the sun's peak, once per column. sums: the
 * row's scratch, n x 27 doubles.
 * Hillaire 2020 sec. 5.5 sums the orders after the first as a geometric
 * series of the first's mean, scattered isotropically; with a forward
 * aerosol and a low sun that left the light near the ground short, and a
 * degree-2 first bounce rang from the sun's aureole to its far side
 * (docs/validation.md): see sky_hillaire_add_order. */
static void order_row(const sky_hillaire_tables *t, const hl_medium *m, double r, const float *prev, float *row,
                      double *sums)
{
    int n = t->settings.multiscatter_size, nd, ns, n_peak;
    sky_hillaire_order_samples(t, prev ? 2 : 1, &nd, &n_peak, &ns);
    for (size_t q = 0; q < (size_t)n * 27; q++) sums[q] = 0.0;
    hl_ray g;
    g.n = g.ground = 0;
    g.L = 0.0;
    for (int k = 0; k < nd; k++) {
        int even = k < nd - n_peak;
        for (int i = 0; i < n; i++) {
            double mu_s = ms_mu_s((double)i / (n - 1)), sx = safe_sqrt(1.0 - mu_s * mu_s), sy = mu_s;
            double w[3], wk, lk[3];
            ms_direction(k, nd, n_peak, m->g, sx, sy, w, &wk);
            if (!even || i == 0) march_ray(m, r, w[1], ns, &g);
            ray_light(t, m, r, prev, n, &g, w, sx, sy, lk);
            double cos_sw = w[0] * sx + w[1] * sy;
            double f[9] = {1.0, w[0], w[1], w[0] * w[0], w[1] * w[1], w[0] * w[1], prev ? 0.0 : legendre3(cos_sw),
                           prev ? 0.0 : legendre4(cos_sw), fmax(w[1], 0.0)};
            double *sum = sums + (size_t)i * 27;
            for (int q = 0; q < 9; q++)
                for (int c = 0; c < 3; c++) sum[q * 3 + c] += lk[c] * wk * f[q];
        }
    }
    for (int i = 0; i < n; i++) {
        const double *sum = sums + (size_t)i * 27;
        double o[SKY_HL_ORDER];
        for (int c = 0; c < 3; c++) {
            double mean = sum[c];
            o[ORD_MEAN + c] = mean;
            o[ORD_DX + c] = 3.0 * sum[3 + c];
            o[ORD_DY + c] = 3.0 * sum[6 + c];
            o[ORD_QXX + c] = 3.0 * sum[9 + c] - mean;
            o[ORD_QYY + c] = 3.0 * sum[12 + c] - mean;
            o[ORD_QXY + c] = 3.0 * sum[15 + c];
            o[ORD_Z3 + c] = 7.0 * sum[18 + c];
            o[ORD_Z4 + c] = 9.0 * sum[21 + c];
            o[ORD_IRR + c] = ms_root(4.0 * M_PI * sum[24 + c]);
        }
        ms_encode(o, SKY_HL_MOMENTS);
        for (int q = 0; q < SKY_HL_ORDER; q++) row[(size_t)i * SKY_HL_ORDER + (size_t)q] = (float)o[q];
    }
}

void sky_hillaire_order_samples(const sky_hillaire_tables *t, int k, int *half_directions, int *peaked, int *steps)
{
    /* multiscatter_directions rounded up to even, as mirrored pairs */
    int nd = t ? (t->settings.multiscatter_directions + 1) / 2 : 1, ns = t ? t->settings.multiscatter_steps : 1;
    int np = nd - (nd + 1) / 2;
    if (k > 1) { /* smooth: no forward peak to follow */
        nd = (nd + 1) / 2;
        np = 0;
        ns = (ns + 1) / 2;
    }
    if (half_directions) *half_directions = nd;
    if (peaked) *peaked = np;
    if (steps) *steps = ns;
}

/* The orders after the last form a geometric series whose ratio is the
 * last order's mean over the one before (per texel and channel; about
 * 0.3 by day), capped: where the orders grow (light diffusing into the
 * Earth's shadow) the series would not converge. 1 km views from the
 * ground with the sun 5 deg up: 3 orders and the series give the light
 * of 4 orders and theirs within 0.1 %. */
#define ORDER_RATIO_MAX 0.95

void sky_hillaire_add_order(sky_hillaire_tables *t, int k, const float *order, const float *prev)
{
    if (!t || !t->multiscatter || !t->ms_moments || !order || k < 1 || k > SKY_HL_ORDERS) return;
    if (k > 1 && !prev) return;
    size_t n = (size_t)t->settings.multiscatter_size * t->settings.multiscatter_size;
    for (size_t i = 0; i < n; i++) {
        double o[SKY_HL_MS_ALL], sum[SKY_HL_MS_ALL];
        float *psi = t->multiscatter + i * 3, *mo = t->ms_moments + i * SKY_HL_MOMENTS;
        for (int q = 0; q < SKY_HL_MS_ALL; q++) {
            o[q] = order[i * SKY_HL_ORDER + (size_t)q];
            /* the sum so far (orders 1 .. k - 1), as these calls left it */
            sum[q] = k == 1 ? 0.0 : q < 3 ? psi[q] : mo[q - 3];
        }
        ms_decode(o, SKY_HL_MOMENTS);
        for (int c = 0; c < 3; c++) {
            double scale = 1.0;
            if (k == SKY_HL_ORDERS && k > 1) {
                double before = ms_power(prev[i * SKY_HL_ORDER + ORD_MEAN + (size_t)c]);
                double ratio = before > 0.0 ? clamp(o[ORD_MEAN + c] / before, 0.0, ORDER_RATIO_MAX) : 0.0;
                scale = 1.0 / (1.0 - ratio);
            }
            for (int q = c; q < SKY_HL_MS_ALL; q += 3) sum[q] += scale * o[q];
        }
        /* the last order leaves the tables as the lookups read them */
        if (k == SKY_HL_ORDERS) ms_encode(sum, SKY_HL_MOMENTS);
        for (int q = 0; q < SKY_HL_MS_ALL; q++) {
            if (q < 3) psi[q] = (float)sum[q];
            else mo[q - 3] = (float)sum[q];
        }
    }
}

int sky_hillaire_build_multiscatter(sky_hillaire_tables *t)
{
    if (!t || !t->multiscatter || !t->ms_moments || !t->transmittance) return -1;
    hl_medium m;
    medium_from(&t->atm, &m);
    int n = t->settings.multiscatter_size;
    size_t row = (size_t)n * SKY_HL_ORDER;
    float *prev = malloc(sizeof(float) * row * (size_t)n), *cur = malloc(sizeof(float) * row * (size_t)n);
    double *sums = malloc(sizeof(double) * 27u * (size_t)n);
    if (!prev || !cur || !sums) {
        free(prev);
        free(cur);
        free(sums);
        return -1;
    }
    for (int k = 1; k <= SKY_HL_ORDERS; k++) {
        for (int j = 0; j < n; j++)
            order_row(t, &m, m.R + (m.Rt - m.R) * j / (n - 1), k > 1 ? prev : NULL, cur + (size_t)j * row, sums);
        sky_hillaire_add_order(t, k, cur, prev);
        float *tmp = prev;
        prev = cur;
        cur = tmp;
    }
    free(prev);
    free(cur);
    free(sums);
    return 0;
}

void sky_hillaire_multiscatter(const sky_hillaire_tables *t, double r, double mu_s, double rgb[3])
{
    if (!rgb) return;
    rgb[0] = rgb[1] = rgb[2] = 0.0;
    if (!t || !t->multiscatter || !isfinite(r) || !isfinite(mu_s)) return;
    hl_medium m;
    medium_from(&t->atm, &m);
    ms_table(t, &m, r, mu_s, rgb);
}

/* ---- sky view ------------------------------------------------------------------------ */

/* The observer's radius for an altitude (below the ground = on it). */
static double observer_radius(const hl_medium *m, double altitude_km)
{
    if (!isfinite(altitude_km) || altitude_km < 0.0) altitude_km = 0.0;
    if (altitude_km > 1e6) altitude_km = 1e6;
    return m->R + altitude_km;
}

/* The zenith angle of the geometric horizon seen from radius r: the
 * tangent to the ground is asin(R / r) from the nadir (Hillaire 2020
 * sec. 5.3; pi/2 on the ground, dipping below it with altitude). */
static double horizon_zenith(const hl_medium *m, double r)
{
    return M_PI - asin(clamp(m->R / r, 0.0, 1.0));
}

/* Hillaire 2020 sec. 5.3: elevation to v with the horizon at v = 0.5 and
 * a square-root concentration of texels toward it from both sides:
 *   above: v = 0.5 (1 - sqrt(1 - theta / theta_h))
 *   below: v = 0.5 + 0.5 sqrt((theta - theta_h) / (pi - theta_h))
 * azimuth to u = sqrt((1 - cos az) / 2) = sin(az / 2): the sun's vertical
 * at u = 0, the anti-solar one at u = 1, texels denser toward the sun
 * where the Mie lobe is. Both go through the texel-centre map. */
static void skyview_unit(const hl_medium *m, double r, double view_mu, double cos_az, double *x, double *y)
{
    double th_h = horizon_zenith(m, r);
    double th = acos(clamp(view_mu, -1.0, 1.0));
    if (th < th_h) {
        double q = 1.0 - th / th_h;
        *y = 0.5 * (1.0 - sqrt(q > 0.0 ? q : 0.0));
    } else {
        double beta = M_PI - th_h;
        double q = beta > 0.0 ? (th - th_h) / beta : 1.0;
        *y = 0.5 + 0.5 * sqrt(clamp(q, 0.0, 1.0));
    }
    *x = sqrt(clamp(0.5 - 0.5 * cos_az, 0.0, 1.0));
}

void sky_hillaire_skyview_uv(const sky_hillaire_tables *t, double view_mu, double cos_azimuth_from_sun,
                             double altitude_km, double *u, double *v)
{
    double x = 0.0, y = 0.0;
    int w = 192, h = 108;
    if (t) {
        hl_medium m;
        medium_from(&t->atm, &m);
        if (!isfinite(view_mu)) view_mu = 1.0;
        if (!isfinite(cos_azimuth_from_sun)) cos_azimuth_from_sun = 1.0;
        skyview_unit(&m, observer_radius(&m, altitude_km), view_mu, cos_azimuth_from_sun, &x, &y);
        w = t->settings.skyview_width;
        h = t->settings.skyview_height;
    }
    if (u) *u = unit_to_tex(x, w);
    if (v) *v = unit_to_tex(y, h);
}

/* Samples for a ray of length L: the full count for the long rays near
 * the horizon, fewer (never under a third, never under 4) for short
 * ones; the quadratic layout already puts them where the air is. */
static int skyview_steps_for(const hl_medium *m, int steps, double L)
{
    double full = 2.0 * m->H; /* about the longest ray in the shell */
    double f = L / full;
    f = clamp(sqrt(f > 0.0 ? f : 0.0), 1.0 / 3.0, 1.0);
    int n = (int)ceil(steps * f);
    if (n < 4) n = 4;
    if (n > steps) n = steps;
    return n;
}

/* The sun's transmittance at a sample whose rho = sqrt(r^2 - R^2) and
 * table row coordinate are known (they do not depend on the sun). */
static void sun_transmittance_at(const sky_hillaire_tables *t, const hl_medium *m, double r, double rho, double v_tex,
                                 double mu_s, double rgb[3])
{
    if (hits_ground(m, r, mu_s)) {
        rgb[0] = rgb[1] = rgb[2] = 0.0;
        return;
    }
    double d = dist_to_top(m, r, mu_s), dmin = m->Rt - r, dmax = rho + m->H;
    double xmu = dmax > dmin ? clamp((d - dmin) / (dmax - dmin), 0.0, 1.0) : 0.0;
    int w = t->settings.transmittance_width, h = t->settings.transmittance_height;
    bilinear(t->transmittance, w, h, unit_to_tex(xmu, w), v_tex, rgb);
}

/* Psi_ms and its moments at column k, between rows y0 and y1 (fraction
 * fy): SKY_HL_MS_ALL numbers, Psi's three first */
static void ms_texel(const sky_hillaire_tables *t, int y0, int y1, double fy, int k, double out[SKY_HL_MS_ALL])
{
    int n = t->settings.multiscatter_size;
    const float *a = t->multiscatter + ((size_t)y0 * n + k) * 3, *b = t->multiscatter + ((size_t)y1 * n + k) * 3;
    const float *ma = t->ms_moments + ((size_t)y0 * n + k) * SKY_HL_MOMENTS;
    const float *mb = t->ms_moments + ((size_t)y1 * n + k) * SKY_HL_MOMENTS;
    for (int c = 0; c < 3; c++) out[c] = a[c] + (b[c] - a[c]) * fy;
    for (int q = 0; q < SKY_HL_MOMENTS; q++) out[3 + q] = ma[q] + (mb[q] - ma[q]) * fy;
}

/* One row of the sky-view table: zenith angle th of every view, ground
 * telling whether the row is below the horizon (decided from the row,
 * not re-derived from the rounded angle). Radiance per unit solar
 * illuminance: Hillaire 2020 eq. 1-3 for single scattering (phase x
 * sun transmittance x sun visibility), eq. 11 for the multiple
 * scattering (sigma_s Psi_ms), each segment in the energy-conserving
 * form, and the sunlit Lambertian ground at the end of rays that meet
 * it. A ray's geometry, optical depth and weights are the same at every
 * azimuth (only the angle to the sun changes), so the row's ray is
 * marched once and each column only looks up the sun's transmittance
 * and Psi_ms at its own solar cosine.
 * Hillaire scatters Psi_ms isotropically toward the observer. Here the
 * light that reaches a sample is scattered once more by the real phase
 * functions, from the table's mean, dipole, quadrupole and the first
 * bounce's zonal harmonics of degrees 3 and 4 about the sun
 * (scatter_moments). An aerosol scatters forward (chi_1 0.71, chi_2 0.52
 * at g 0.65), so it sends the observer the light that arrives from
 * beyond the view rather than the sky's mean: the isotropic second order
 * made a high sun's sky too bright and a low sun's horizon too dark
 * (docs/validation.md). The first bounce's
 * aureole about a sun near the horizon needs the zonal terms: cut at
 * degree 2 it rang to the aureole's far side. */
/* What a single ray asks of skyview_row beyond the table's row (NULL for
 * a table): where the view ends, whether the ground's own light is
 * wanted, the transmittance to the end, the running sums. */
typedef struct hl_view {
    double max_len;             /* km from the observer; INFINITY: the ray's end */
    int no_ground;              /* 1: the light scattered on the way alone        */
    double tr[3];               /* out: the view's transmittance at its end       */
    sky_hillaire_point *points; /* out, if not NULL: the running sums (w == 1)    */
    int max_points, count;
} hl_view;

/* A running sum at km from the observer, if the view keeps them. */
static void record_point(hl_view *v, double km, const double inscatter[3], const double tr[3])
{
    if (!v || !v->points || v->count >= v->max_points) return;
    sky_hillaire_point *p = &v->points[v->count++];
    p->km = km;
    for (int c = 0; c < 3; c++) p->inscatter[c] = inscatter[c], p->transmittance[c] = tr[c];
}

static void skyview_row(const sky_hillaire_tables *t, const hl_medium *m, double r0, double th, int ground,
                        const double sun[3], int w, float *row, hl_view *view)
{
    enum { MAX_STEPS = SKY_HL_MAX_STEPS };
    double ct = cos(th), st = sin(th), max_len = view ? view->max_len : INFINITY;
    for (int i = 0; i < w * 3; i++) row[i] = 0.0f;
    if (view) {
        view->tr[0] = view->tr[1] = view->tr[2] = 1.0;
        view->count = 0;
        if (view->no_ground) ground = 0;
    }
    static const double zero[3] = {0.0, 0.0, 0.0}, one[3] = {1.0, 1.0, 1.0};
    record_point(view, 0.0, zero, one);
    double r = r0, mu = ct, start = 0.0;
    if (r > m->Rt) {
        double disc = r * r * (mu * mu - 1.0) + m->Rt * m->Rt;
        if (mu >= 0.0 || disc < 0.0) return; /* misses the shell: space */
        start = (r * r - m->Rt * m->Rt) / (-r * mu + sqrt(disc));
        r = m->Rt;
        mu = clamp((r0 * ct + start) / m->Rt, -1.0, 1.0);
        record_point(view, fmin(start, max_len), zero, one);
    }
    double L = ground ? dist_to_ground(m, r, mu) : dist_to_top(m, r, mu);
    /* aerial perspective: the view ends max_len from the observer, short
     * of the ground it would have met */
    if (start + L > max_len) {
        if (max_len <= start) return;
        L = max_len - start;
        ground = 0;
    }
    int n = L > 0.0 ? skyview_steps_for(m, t->settings.skyview_steps, L) : 0;
    /* per sample: radius, distance from the observer, the table rows of
     * the two lookups, and the Rayleigh and Mie weights per channel */
    double rs[MAX_STEPS], ds[MAX_STEPS], rho[MAX_STEPS], vt[MAX_STEPS], vm[MAX_STEPS];
    double wr[MAX_STEPS][3], wm[MAX_STEPS][3], tr[3] = {1.0, 1.0, 1.0}, trs[MAX_STEPS][3], ends[MAX_STEPS];
    int tr_h = t->settings.transmittance_height, ms_n = t->settings.multiscatter_size;
    if (n > 0) {
        hl_layout ly;
        layout_init(&ly, L, -r * mu, n);
        double ta = 0.0, ra = r;
        hl_dens da = density_at(m, ra);
        for (int s = 0; s < n; s++) {
            double tb = layout_t(&ly, s + 1), rb = radius_along(r, mu, tb);
            hl_dens db = density_at(m, rb);
            hl_dens col = seg_column(m, da, ra, db, rb, tb - ta);
            double tm = 0.5 * (ta + tb), rm = radius_along(r, mu, tm);
            rs[s] = rm;
            ds[s] = start + tm;
            rho[s] = safe_sqrt(rm * rm - m->R * m->R);
            vt[s] = unit_to_tex(clamp(rho[s] / m->H, 0.0, 1.0), tr_h);
            vm[s] = unit_to_tex(clamp((rm - m->R) / (m->Rt - m->R), 0.0, 1.0), ms_n);
            for (int c = 0; c < 3; c++) {
                double tau = tau_of(m, c, col), e = exp(-tau), f = tr[c] * seg_weight(tau, e);
                wr[s][c] = m->br[c] * col.r * f;
                wm[s][c] = m->bms[c] * col.m * f;
                tr[c] *= e;
                trs[s][c] = tr[c];
            }
            ends[s] = start + tb;
            ta = tb;
            ra = rb;
            da = db;
        }
    }
    /* per column (in the tables' scratch, after the line below): the
     * view's angle to the sun, the phase functions and the sum */
    double *cos_th = t->scratch + (size_t)ms_n * SKY_HL_MS_ALL, *ph_r = cos_th + w, *ph_m = ph_r + w;
    double *p3 = ph_m + w, *p4 = p3 + w, *out = p4 + w;
    for (int i = 0; i < w; i++) {
        double x = w > 1 ? (double)i / (w - 1) : 0.0;
        double caz = clamp(1.0 - 2.0 * x * x, -1.0, 1.0), saz = safe_sqrt(1.0 - caz * caz);
        cos_th[i] = st * caz * sun[0] + ct * sun[1] + st * saz * sun[2];
        ph_r[i] = phase_rayleigh(cos_th[i]);
        ph_m[i] = phase_cs(cos_th[i], m->g);
        p3[i] = legendre3(cos_th[i]);
        p4[i] = legendre4(cos_th[i]);
        out[3 * i] = out[3 * i + 1] = out[3 * i + 2] = 0.0;
    }
    /* Sample by sample: the multiple-scattering table and its moments at
     * the sample's altitude (bilinear filtering taken in two steps). A
     * wide row interpolates them once into a line over mu_s that every
     * column reads at its own solar cosine; a single ray (the host's
     * lighting) reads its two texels of each row. */
    double *line = w >= ms_n ? t->scratch : NULL;
    for (int s = 0; s < n; s++) {
        double y = clamp(vm[s], 0.0, 1.0) * ms_n - 0.5, fy = y - floor(y);
        int y0 = (int)floor(y), y1 = y0 + 1;
        y0 = y0 < 0 ? 0 : y0 > ms_n - 1 ? ms_n - 1 : y0;
        y1 = y1 > ms_n - 1 ? ms_n - 1 : y1;
        for (int k = 0; line && k < ms_n; k++) ms_texel(t, y0, y1, fy, k, line + k * SKY_HL_MS_ALL);
        /* the view in the sample's frame: y up (the same at every
         * azimuth), x toward the sun's azimuth */
        double vy = clamp((r0 * ct + ds[s]) / rs[s], -1.0, 1.0);
        for (int i = 0; i < w; i++) {
            /* the sample is observer + view * ds: its solar cosine */
            double mus = clamp((r0 * sun[1] + ds[s] * cos_th[i]) / rs[s], -1.0, 1.0);
            double ts[3], ms[SKY_HL_MS_ALL], a[SKY_HL_MS_ALL], b[SKY_HL_MS_ALL];
            sun_transmittance_at(t, m, rs[s], rho[s], vt[s], mus, ts);
            double x = clamp(unit_to_tex(ms_u(mus), ms_n), 0.0, 1.0) * ms_n - 0.5, fx = x - floor(x);
            int x0 = (int)floor(x), x1 = x0 + 1;
            x0 = x0 < 0 ? 0 : x0 > ms_n - 1 ? ms_n - 1 : x0;
            x1 = x1 > ms_n - 1 ? ms_n - 1 : x1;
            const double *pa = line ? line + x0 * SKY_HL_MS_ALL : a, *pb = line ? line + x1 * SKY_HL_MS_ALL : b;
            if (!line) {
                ms_texel(t, y0, y1, fy, x0, a);
                ms_texel(t, y0, y1, fy, x1, b);
            }
            for (int q = 0; q < SKY_HL_MS_ALL; q++) ms[q] = pa[q] + (pb[q] - pa[q]) * fx;
            ms_decode(ms, SKY_HL_MOMENTS);
            /* (undefined, and unneeded, under a zenith sun) */
            double sh = safe_sqrt(1.0 - mus * mus), jr[3], jm[3];
            double vx = sh > 1e-6 ? clamp((cos_th[i] - mus * vy) / sh, -1.0, 1.0) : 0.0;
            scatter_moments(t, ms, ms + 3, vx, vy, fmax(1.0 - vx * vx - vy * vy, 0.0), p3[i], p4[i], jr, jm);
            for (int c = 0; c < 3; c++)
                out[3 * i + c] += wr[s][c] * (ph_r[i] * ts[c] + jr[c]) + wm[s][c] * (ph_m[i] * ts[c] + jm[c]);
        }
        if (w == 1) record_point(view, ends[s], out, trs[s]);
    }
    if (view)
        for (int c = 0; c < 3; c++) view->tr[c] = tr[c];
    double rg = ground ? radius_along(r, mu, L) : 0.0;
    for (int i = 0; i < w; i++) {
        if (ground && rg > 0.0) {
            double mug = (r0 * sun[1] + (start + L) * cos_th[i]) / rg;
            if (mug > 0.0) {
                double ts[3];
                trans_table(t, m, m->R, clamp(mug, 0.0, 1.0), ts);
                for (int c = 0; c < 3; c++) out[3 * i + c] += tr[c] * m->albedo[c] / M_PI * mug * ts[c];
            }
        }
        for (int c = 0; c < 3; c++) row[i * 3 + c] = (float)out[3 * i + c];
    }
}

/* A sky-view build's sun cosine: one that is not a number is the
 * zenith's. */
static double skyview_sun_mu(double sun_mu)
{
    return isfinite(sun_mu) ? clamp(sun_mu, -1.0, 1.0) : 1.0;
}

/* What a table records of its inputs (skyview_altitude_km,
 * skyview_sun_mu): the altitude as observer_radius has it. */
static void skyview_record(sky_hillaire_tables *t, double altitude_km, double sun_mu)
{
    hl_medium m;
    medium_from(&t->atm, &m);
    t->skyview_altitude_km = observer_radius(&m, altitude_km) - m.R;
    t->skyview_sun_mu = skyview_sun_mu(sun_mu);
}

void sky_hillaire_build_skyview_rows(const sky_hillaire_tables *t, double altitude_km, double sun_mu, int row0,
                                     int row1, float *table)
{
    if (!t || !table || !t->transmittance || !t->multiscatter || !t->ms_moments || !t->scratch) return;
    hl_medium m;
    medium_from(&t->atm, &m);
    sun_mu = skyview_sun_mu(sun_mu);
    double r0 = observer_radius(&m, altitude_km);
    int w = t->settings.skyview_width, h = t->settings.skyview_height;
    if (row0 < 0) row0 = 0;
    if (row1 > h) row1 = h;
    /* the sun at azimuth 0 (+x): u = 0 is its vertical */
    double sun[3] = {sqrt(1.0 - sun_mu * sun_mu), sun_mu, 0.0};
    double th_h = horizon_zenith(&m, r0), beta = M_PI - th_h;
    for (int j = row0; j < row1; j++) {
        /* row j holds y = j / (h - 1); the inverse of skyview_unit */
        double y = (double)j / (h - 1), th;
        int below = y > 0.5;
        if (!below) {
            double q = 1.0 - 2.0 * y;
            th = th_h * (1.0 - q * q);
        } else {
            double q = 2.0 * y - 1.0;
            th = th_h + beta * q * q;
        }
        skyview_row(t, &m, r0, th, below, sun, w, table + (size_t)j * w * 3, NULL);
    }
}

void sky_hillaire_build_skyview(sky_hillaire_tables *t, double altitude_km, double sun_mu)
{
    if (!t || !t->skyview || !t->transmittance || !t->multiscatter || !t->ms_moments || !t->scratch) return;
    sky_hillaire_build_skyview_rows(t, altitude_km, sun_mu, 0, t->settings.skyview_height, t->skyview);
    skyview_record(t, altitude_km, sun_mu);
}

void sky_hillaire_install_skyview(sky_hillaire_tables *t, float **table, double altitude_km, double sun_mu)
{
    if (!t || !table || !*table) return;
    float *old = t->skyview;
    t->skyview = *table;
    *table = old;
    skyview_record(t, altitude_km, sun_mu);
}

/* One view ray of skyview_row for a caller's view and sun (any length,
 * any azimuth); rgb: what it gathered. */
static void march_view(const sky_hillaire_tables *t, double altitude_km, const double view[3], const double sun_dir[3],
                       hl_view *v, double rgb[3])
{
    rgb[0] = rgb[1] = rgb[2] = 0.0;
    v->tr[0] = v->tr[1] = v->tr[2] = 1.0;
    v->count = 0;
    if (!(v->max_len >= 0.0)) return;
    if (!t || !t->transmittance || !t->multiscatter || !t->ms_moments || !t->scratch || !view || !sun_dir) return;
    for (int k = 0; k < 3; k++)
        if (!isfinite(view[k]) || !isfinite(sun_dir[k])) return;
    double vl = sqrt(view[0] * view[0] + view[1] * view[1] + view[2] * view[2]);
    double sl = sqrt(sun_dir[0] * sun_dir[0] + sun_dir[1] * sun_dir[1] + sun_dir[2] * sun_dir[2]);
    if (!(vl > 0.0) || !(sl > 0.0)) return;
    hl_medium m;
    medium_from(&t->atm, &m);
    double r0 = observer_radius(&m, altitude_km);
    double th = acos(clamp(view[1] / vl, -1.0, 1.0));
    /* the row's column 0 looks along its own azimuth: turn the sun into
     * that frame (only the azimuth between the two matters) */
    double hv = hypot(view[0], view[2]), hs = hypot(sun_dir[0], sun_dir[2]);
    double caz = 1.0, saz = 0.0;
    if (hv > 1e-12 * vl && hs > 1e-12 * sl) {
        caz = (view[0] * sun_dir[0] + view[2] * sun_dir[2]) / (hv * hs);
        saz = (view[0] * sun_dir[2] - view[2] * sun_dir[0]) / (hv * hs);
    }
    double sun[3] = {hs / sl * caz, sun_dir[1] / sl, hs / sl * saz};
    float out[3];
    skyview_row(t, &m, r0, th, th > horizon_zenith(&m, r0), sun, 1, out, v);
    for (int c = 0; c < 3; c++) rgb[c] = out[c];
}

void sky_hillaire_segment(const sky_hillaire_tables *t, double altitude_km, const double view[3],
                          const double sun_dir[3], double max_km, double rgb[3], double transmittance[3])
{
    if (!rgb) return;
    hl_view v = {.max_len = max_km, .no_ground = isfinite(max_km)};
    march_view(t, altitude_km, view, sun_dir, &v, rgb);
    if (transmittance)
        for (int c = 0; c < 3; c++) transmittance[c] = v.tr[c];
}

int sky_hillaire_profile(const sky_hillaire_tables *t, double altitude_km, const double view[3],
                         const double sun_dir[3], sky_hillaire_point *points, int max_points)
{
    if (!points || max_points < 1) return 0;
    hl_view v = {.max_len = INFINITY, .no_ground = 1, .points = points, .max_points = max_points};
    double rgb[3];
    march_view(t, altitude_km, view, sun_dir, &v, rgb);
    if (v.count == 0) { /* a rejected ray: nothing between, seen through */
        points[0] = (sky_hillaire_point){0.0, {0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}};
        v.count = 1;
    }
    return v.count;
}

void sky_hillaire_ray(const sky_hillaire_tables *t, double altitude_km, const double view[3], const double sun_dir[3],
                      double rgb[3])
{
    sky_hillaire_segment(t, altitude_km, view, sun_dir, INFINITY, rgb, NULL);
}

void sky_hillaire_sky(const sky_hillaire_tables *t, const double view[3], const double sun_dir[3], double rgb[3])
{
    if (!rgb) return;
    rgb[0] = rgb[1] = rgb[2] = 0.0;
    if (!t || !t->skyview || !view || !sun_dir) return;
    for (int k = 0; k < 3; k++)
        if (!isfinite(view[k]) || !isfinite(sun_dir[k])) return;
    double vl = sqrt(view[0] * view[0] + view[1] * view[1] + view[2] * view[2]);
    if (!(vl > 0.0)) return;
    double vmu = view[1] / vl;
    /* azimuth between the vertical planes of the view and the sun; either
     * one vertical leaves it free (the table is the same along a row's
     * zenith/nadir edge), so 1 */
    double hv = hypot(view[0], view[2]), hs = hypot(sun_dir[0], sun_dir[2]);
    double caz = 1.0;
    if (hv > 1e-12 * vl && hs > 1e-12) caz = clamp((view[0] * sun_dir[0] + view[2] * sun_dir[2]) / (hv * hs), -1.0, 1.0);
    double u, v;
    sky_hillaire_skyview_uv(t, vmu, caz, t->skyview_altitude_km, &u, &v);
    bilinear(t->skyview, t->settings.skyview_width, t->settings.skyview_height, u, v, rgb);
}
