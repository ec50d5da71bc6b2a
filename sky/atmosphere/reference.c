/*
 * The atmosphere reference (reference.h): a CPU, double-precision,
 * spectral model of the sky's light for the real-time paths to be
 * measured against. Correctness over speed; no GL, no global state.
 *
 * Light transport (Hillaire 2020 sec. 4 and 5; Bruneton 2017's CPU
 * reference in spirit):
 *  - single scattering by deterministic quadrature along the view ray,
 *    each segment in the energy-conserving form (S - S T_seg) / sigma_t
 *    (Hillaire 2020, sec. 5.6.3), plus the ground's
 *    first-order (sun -> ground -> eye) term;
 *  - orders >= 2 by Monte Carlo path tracing per wavelength with
 *    free-flight sampling, next-event estimation toward the sun at
 *    vertices of order >= 2 and Russian roulette; it reports its own
 *    standard error.
 * Optical depth is integrated per segment analytically, assuming the
 * density is exponential in path length between the segment's ends
 * (exact for an exponential profile along a vertical ray) and linear for
 * the ozone tent; segments are spaced quadratically toward the ray's
 * lowest point (its origin, its end, or the tangent point) so that the
 * scale heights are resolved at grazing angles.
 * The spectra (the sun, colour matching, the description's coefficients
 * at any wavelength) are spectrum.c's, which the library shares; this
 * file itself is compiled into sky-bench and the tests, not libsky.
 */
#include "reference.h"
#include "spectrum.h"
#include "../sky.h"

#include <math.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define REF_DEFAULT_VIEW_SEGMENTS 256
#define REF_DEFAULT_SUN_SEGMENTS 128
#define REF_DEFAULT_PATHS 256
#define REF_MAX_SEGMENTS 65536
#define REF_MAX_PATHS (1 << 24)
#define REF_MAX_ORDER 1000

/* ---- the medium --------------------------------------------------------------- */
/* Written apart from hillaire_cpu.c on purpose, density profiles included:
 * the reference shares no code with what it is the yardstick for. */

typedef struct ref_medium {
    double R, Rt;         /* ground and top radii, km */
    double hr, hm;        /* scale heights */
    double oz_peak, oz_hw;
    double g;
    int n;                /* wavelengths in use (16, or 1 for only_nm) */
    double lambda[SKY_REF_WAVELENGTHS];
    double br[SKY_REF_WAVELENGTHS], bms[SKY_REF_WAVELENGTHS], bme[SKY_REF_WAVELENGTHS];
    double bo[SKY_REF_WAVELENGTHS], albedo[SKY_REF_WAVELENGTHS], esun[SKY_REF_WAVELENGTHS];
} ref_medium;

/* Densities relative to sea level: Rayleigh, Mie, ozone. */
typedef struct dens3 {
    double r, m, o;
} dens3;

static dens3 density_at(const ref_medium *md, double radius)
{
    double alt = radius - md->R;
    if (alt < 0.0) alt = 0.0;
    dens3 d;
    d.r = exp(-alt / md->hr);
    d.m = exp(-alt / md->hm);
    double o = 1.0 - fabs(alt - md->oz_peak) / md->oz_hw;
    d.o = o > 0.0 ? o : 0.0;
    return d;
}

static void medium_init(ref_medium *md, const sky_atmosphere_params *atm, double only_nm)
{
    md->R = atm->planet_radius_km;
    md->Rt = atm->top_radius_km;
    md->hr = atm->rayleigh_scale_height_km;
    md->hm = atm->mie_scale_height_km;
    md->oz_peak = atm->ozone_peak_km;
    md->oz_hw = atm->ozone_half_width_km;
    md->g = atm->mie_g;
    md->n = only_nm > 0.0 ? 1 : SKY_REF_WAVELENGTHS;
    for (int i = 0; i < md->n; i++) {
        double l = only_nm > 0.0 ? only_nm : sky_spectrum_wavelength_nm(i);
        md->lambda[i] = l;
        sky_spectrum_coefficients(atm, l, &md->br[i], &md->bms[i], &md->bme[i], &md->bo[i]);
        double a = sky_spectrum_interpolate(atm->ground_albedo, l);
        md->albedo[i] = a > 1.0 ? 1.0 : a;
        md->esun[i] = sky_spectrum_solar_irradiance(l);
    }
}

/* Extinction optical depth of a column (sea-level-equivalent km). */
static double tau_of(const ref_medium *md, int i, dens3 col)
{
    return md->br[i] * col.r + md->bme[i] * col.m + md->bo[i] * col.o;
}

/* ---- geometry ------------------------------------------------------------------ */

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* The part of the ray from radius r with cosine mu (to the local
 * vertical) that lies in the shell: [t0, t1], ending on the ground when
 * *ground. Returns 0 if the ray misses the shell. Roots are taken in the
 * cancellation-free form (the product of the roots is r^2 - rho^2) and
 * the discriminant written r^2 (mu^2 - 1) + rho^2 (Bruneton 2017). */
static int ray_interval(const ref_medium *md, double r, double mu, double *t0, double *t1, int *ground)
{
    double R = md->R, Rt = md->Rt;
    if (r < R) r = R; /* a point a rounding error below the ground */
    double b = r * mu;
    *ground = 0;
    if (r > Rt) {
        double disc = r * r * (mu * mu - 1.0) + Rt * Rt;
        if (mu >= 0.0 || disc < 0.0) return 0;
        double sq = sqrt(disc);
        *t0 = (r * r - Rt * Rt) / (-b + sq);
        *t1 = -b + sq;
    } else {
        double disc = r * r * (mu * mu - 1.0) + Rt * Rt;
        *t0 = 0.0;
        *t1 = -b + sqrt(disc > 0.0 ? disc : 0.0);
    }
    if (mu < 0.0) {
        double dg = r * r * (mu * mu - 1.0) + R * R;
        if (dg >= 0.0) {
            double num = r * r - R * R;
            double tg = (num > 0.0 ? num : 0.0) / (-b + sqrt(dg));
            if (tg <= *t1) {
                *t1 = tg;
                *ground = 1;
            }
        }
    }
    if (*t1 < *t0) *t1 = *t0;
    return 1;
}

/* Segment boundaries along [t0, t1]: n1 segments closing quadratically
 * onto the lowest point ts from the start, n2 opening quadratically from
 * it to the end. The quadratic map keeps the spacing smooth (second-order
 * quadrature stays second order) while the first segments at the lowest,
 * densest air are n^2 times shorter than uniform ones. */
typedef struct ray_layout {
    double r, mu;  /* origin radius and cosine of the ray to its vertical */
    double t0, t1, ts;
    int n1, n2;
} ray_layout;

static void layout_init(ray_layout *L, double r, double mu, double t0, double t1, int n)
{
    L->r = r;
    L->mu = mu;
    L->t0 = t0;
    L->t1 = t1;
    double ts = -r * mu; /* closest approach to the centre */
    if (ts <= t0) {
        L->ts = t0;
        L->n1 = 0;
        L->n2 = n;
    } else if (ts >= t1) {
        L->ts = t1;
        L->n1 = n;
        L->n2 = 0;
    } else {
        L->ts = ts;
        int n1 = (int)floor(n * (ts - t0) / (t1 - t0) + 0.5);
        if (n1 < 1) n1 = 1;
        if (n1 > n - 1) n1 = n - 1;
        if (n1 < 1) n1 = 1; /* n == 1: one segment on each side */
        L->n1 = n1;
        L->n2 = n - n1 > 0 ? n - n1 : 1;
    }
}

static int layout_count(const ray_layout *L)
{
    return L->n1 + L->n2;
}

static double layout_t(const ray_layout *L, int k)
{
    if (k <= L->n1) {
        if (L->n1 == 0) return L->t0;
        double u = (double)(L->n1 - k) / L->n1;
        return k == L->n1 ? L->ts : L->ts - (L->ts - L->t0) * u * u;
    }
    double u = (double)(k - L->n1) / L->n2;
    return k == L->n1 + L->n2 ? L->t1 : L->ts + (L->t1 - L->ts) * u * u;
}

static double radius_at(const ray_layout *L, double t)
{
    double q = L->r * L->r + 2.0 * L->r * L->mu * t + t * t;
    return sqrt(q > 0.0 ? q : 0.0);
}

/* The integral over a segment of length ds of a density that is
 * exponential in path length from a to b: ds (b - a) / ln(b / a), written
 * with expm1 so that a ~ b keeps its precision. */
static double seg_exp(double a, double b, double ds)
{
    if (!(a > 0.0) || !(b > 0.0)) return 0.5 * (a + b) * ds; /* underflowed: negligible either way */
    double x = log(b / a);
    if (fabs(x) < 1e-9) return a * ds * (1.0 + 0.5 * x);
    return a * ds * expm1(x) / x;
}

static dens3 seg_column(dens3 a, dens3 b, double ds)
{
    dens3 c;
    c.r = seg_exp(a.r, b.r, ds);
    c.m = seg_exp(a.m, b.m, ds);
    c.o = 0.5 * (a.o + b.o) * ds; /* the tent is linear in altitude: trapezoid */
    return c;
}

/* Column (Rayleigh, Mie, ozone) from radius r along mu to the top, in n
 * segments; returns 0 if the ray hits the ground (the point is in the
 * planet's shadow), 1 otherwise. */
static int column_to_space(const ref_medium *md, double r, double mu, int n, dens3 *col)
{
    double t0, t1;
    int ground;
    col->r = col->m = col->o = 0.0;
    if (!ray_interval(md, r, mu, &t0, &t1, &ground)) return 1;
    if (ground) return 0;
    ray_layout L;
    layout_init(&L, r, mu, t0, t1, n);
    int m = layout_count(&L);
    double ta = layout_t(&L, 0);
    dens3 da = density_at(md, radius_at(&L, ta));
    for (int k = 1; k <= m; k++) {
        double tb = layout_t(&L, k);
        dens3 db = density_at(md, radius_at(&L, tb));
        dens3 c = seg_column(da, db, tb - ta);
        col->r += c.r;
        col->m += c.m;
        col->o += c.o;
        ta = tb;
        da = db;
    }
    return 1;
}

/* ---- phase functions -------------------------------------------------------------- */

static double phase_rayleigh(double c)
{
    return 3.0 / (16.0 * M_PI) * (1.0 + c * c);
}

/* Cornette & Shanks 1992, eq. 4 (Hillaire 2020 uses it for Mie). */
static double phase_cs(double c, double g)
{
    double g2 = g * g, den = 1.0 + g2 - 2.0 * g * c;
    return 3.0 / (8.0 * M_PI) * (1.0 - g2) * (1.0 + c * c) / ((2.0 + g2) * den * sqrt(den));
}

static double phase_hg(double c, double g)
{
    double g2 = g * g, den = 1.0 + g2 - 2.0 * g * c;
    return (1.0 - g2) / (4.0 * M_PI * den * sqrt(den));
}

/* ---- validation ------------------------------------------------------------------- */

static int unit_ok(const double v[3])
{
    if (!v || !isfinite(v[0]) || !isfinite(v[1]) || !isfinite(v[2])) return 0;
    double len = sqrt(dot3(v, v));
    return fabs(len - 1.0) <= 1e-6;
}

/* sky.h's convention: the all-zero description means the Earth preset.
 * Tested here rather than through the library's internal helper, which
 * the reference, outside the library, does not see. */
static int atm_is_zero(const sky_atmosphere_params *atm)
{
    static const sky_atmosphere_params zero;
    return memcmp(atm, &zero, sizeof zero) == 0;
}

/* Resolves the zero description to Earth and checks it. */
static int resolve_atm(const sky_atmosphere_params *atm, sky_atmosphere_params *out)
{
    if (!atm) return -1;
    if (atm_is_zero(atm)) return sky_atmosphere_get_preset(SKY_ATMOSPHERE_PRESET_EARTH, out) == SKY_OK ? 0 : -1;
    if (sky_atmosphere_check(atm, NULL, 0) != SKY_OK) return -1;
    *out = *atm;
    return 0;
}

/* ---- transmittance ------------------------------------------------------------------ */

void sky_ref_transmittance(const sky_atmosphere_params *atm, double altitude_km, const double dir[3],
                           double transmittance[SKY_REF_WAVELENGTHS])
{
    if (!transmittance) return;
    for (int i = 0; i < SKY_REF_WAVELENGTHS; i++) transmittance[i] = 0.0;
    sky_atmosphere_params a;
    if (resolve_atm(atm, &a) || !unit_ok(dir) || !isfinite(altitude_km) || altitude_km < 0.0) return;
    ref_medium md;
    medium_init(&md, &a, 0.0);
    dens3 col;
    /* 1024 segments: this is the standalone query, cost is no concern */
    if (!column_to_space(&md, md.R + altitude_km, dir[1], 1024, &col)) return;
    for (int i = 0; i < SKY_REF_WAVELENGTHS; i++) transmittance[i] = exp(-tau_of(&md, i, col));
}

/* ---- single scattering ---------------------------------------------------------------- */

/* First-order radiance along the view ray for every wavelength, into
 * single[]. pos is the eye in the planet-centred frame. */
static void single_scattering(const ref_medium *md, const double eye[3], const double view[3], const double sun[3],
                              int view_segments, int sun_segments, double max_distance, double single[SKY_REF_WAVELENGTHS],
                              double transmittance[SKY_REF_WAVELENGTHS])
{
    for (int i = 0; i < md->n; i++) single[i] = 0.0, transmittance[i] = 1.0;
    double r = sqrt(dot3(eye, eye));
    double mu = dot3(eye, view) / r;
    double t0, t1;
    int ground;
    if (!ray_interval(md, r, mu, &t0, &t1, &ground)) return; /* misses the shell: black space */
    if (max_distance > 0.0 && t1 > max_distance) { /* aerial perspective: the ray ends there */
        t1 = fmax(max_distance, t0);
        ground = 0;
    }
    double cos_theta = dot3(view, sun);
    double pr = phase_rayleigh(cos_theta), pm = phase_cs(cos_theta, md->g);
    double tau_eye[SKY_REF_WAVELENGTHS] = {0};

    ray_layout L;
    layout_init(&L, r, mu, t0, t1, view_segments);
    int m = t1 > t0 ? layout_count(&L) : 0;
    double ta = layout_t(&L, 0);
    dens3 da = density_at(md, radius_at(&L, ta));
    for (int k = 1; k <= m; k++) {
        double tb = layout_t(&L, k);
        dens3 db = density_at(md, radius_at(&L, tb));
        dens3 c = seg_column(da, db, tb - ta);
        /* the sun's light at the segment's midpoint (midpoint rule for
         * the slowly varying factors, exact attenuation inside) */
        double tm = 0.5 * (ta + tb), x[3];
        for (int j = 0; j < 3; j++) x[j] = eye[j] + view[j] * tm;
        double rm = sqrt(dot3(x, x));
        dens3 cs;
        int lit = column_to_space(md, rm, dot3(x, sun) / rm, sun_segments, &cs);
        for (int i = 0; i < md->n; i++) {
            double tau = tau_of(md, i, c);
            if (lit) {
                /* (S - S T_seg) / sigma_t with the segment's mean
                 * coefficients: sigma_s ds (1 - e^-tau) / tau */
                double sds = md->br[i] * c.r * pr + md->bms[i] * c.m * pm;
                double f = tau > 1e-12 ? -expm1(-tau) / tau : 1.0 - 0.5 * tau;
                single[i] += exp(-tau_eye[i]) * sds * f * exp(-tau_of(md, i, cs)) * md->esun[i];
            }
            tau_eye[i] += tau;
        }
        ta = tb;
        da = db;
    }
    for (int i = 0; i < md->n; i++) transmittance[i] = exp(-tau_eye[i]);
    if (ground) {
        /* sun -> ground -> eye (Lambertian) */
        double x[3];
        for (int j = 0; j < 3; j++) x[j] = eye[j] + view[j] * t1;
        double rg = sqrt(dot3(x, x));
        double mus = dot3(x, sun) / rg;
        if (mus > 0.0) {
            dens3 cs;
            if (column_to_space(md, md->R, mus, sun_segments, &cs))
                for (int i = 0; i < md->n; i++)
                    single[i] += md->albedo[i] / M_PI * md->esun[i] * mus * exp(-tau_of(md, i, cs)) *
                                 exp(-tau_eye[i]);
        }
    }
}

/* ---- Monte Carlo, orders >= 2 ----------------------------------------------------------- */

/* xoshiro256** (Blackman & Vigna 2018), seeded through splitmix64: a
 * local generator per call, so results depend on the seed alone. */
typedef struct ref_rng {
    unsigned long long s[4];
} ref_rng;

static unsigned long long splitmix64(unsigned long long *x)
{
    unsigned long long z = (*x += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}

static void rng_seed(ref_rng *g, unsigned long long seed)
{
    for (int i = 0; i < 4; i++) g->s[i] = splitmix64(&seed);
}

static unsigned long long rotl64(unsigned long long x, int k)
{
    return (x << k) | (x >> (64 - k));
}

static double rng_uniform(ref_rng *g) /* [0, 1) with 53 bits */
{
    unsigned long long *s = g->s;
    unsigned long long result = rotl64(s[1] * 5, 7) * 9;
    unsigned long long t = s[1] << 17;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = rotl64(s[3], 45);
    return (double)(result >> 11) * (1.0 / 9007199254740992.0);
}

/* A direction at cosine c from d with azimuth phi, using the branchless
 * orthonormal basis of Duff et al. 2017 (JCGT 6(1)). */
static void rotate_about(const double d[3], double c, double phi, double out[3])
{
    double sign = d[2] >= 0.0 ? 1.0 : -1.0;
    double a = -1.0 / (sign + d[2]);
    double b = d[0] * d[1] * a;
    double b1[3] = {1.0 + sign * d[0] * d[0] * a, sign * b, -sign * d[0]};
    double b2[3] = {b, sign + d[1] * d[1] * a, -d[1]};
    double s = sqrt(fmax(0.0, 1.0 - c * c));
    double cp = cos(phi) * s, sp = sin(phi) * s;
    double len = 0.0;
    for (int j = 0; j < 3; j++) {
        out[j] = b1[j] * cp + b2[j] * sp + d[j] * c;
        len += out[j] * out[j];
    }
    len = sqrt(len);
    for (int j = 0; j < 3; j++) out[j] /= len;
}

/* Rayleigh's phase in cos theta has pdf 3/8 (1 + c^2); its CDF set to xi
 * is the depressed cubic c^3 + 3c - q = 0 with q = 8 xi - 4, whose one
 * real root is Cardano's. */
static double sample_rayleigh(double xi)
{
    double q = 8.0 * xi - 4.0;
    double s = sqrt(0.25 * q * q + 1.0);
    double c = cbrt(0.5 * q + s) + cbrt(0.5 * q - s);
    return c < -1.0 ? -1.0 : c > 1.0 ? 1.0 : c;
}

/* Henyey-Greenstein by inversion of its CDF. */
static double sample_hg(double xi, double g)
{
    if (fabs(g) < 1e-4) return 2.0 * xi - 1.0;
    double f = (1.0 - g * g) / (1.0 - g + 2.0 * g * xi);
    double c = (1.0 + g * g - f * f) / (2.0 * g);
    return c < -1.0 ? -1.0 : c > 1.0 ? 1.0 : c;
}

/* Where along the ray from pos in d a free flight of optical depth
 * tau_target (wavelength i) ends. Returns 1 with *t_hit and the local
 * densities there, or 0 if the ray leaves the shell first (*ground then
 * says whether it left through the ground, at *t_end). Inside a segment
 * each density follows the same exponential (ozone: linear) form as the
 * optical depth, and the distance is solved by safeguarded Newton. */
static int free_flight(const ref_medium *md, int i, const double pos[3], const double d[3], int n, double tau_target,
                       double t_max, double *t_hit, dens3 *dens, int *ground, double *t_end, double *tau_total)
{
    *tau_total = 0.0;
    double r = sqrt(dot3(pos, pos)), mu = dot3(pos, d) / r, t0, t1;
    *ground = 0;
    *t_end = 0.0;
    if (!ray_interval(md, r, mu, &t0, &t1, ground)) return 0;
    if (t1 > t_max) { /* aerial perspective: the ray ends short of the ground or the top */
        t1 = t_max;
        *ground = 0;
    }
    *t_end = t1;
    if (!(t1 > t0)) return 0;
    ray_layout L;
    layout_init(&L, r, mu, t0, t1, n);
    int m = layout_count(&L);
    double ta = layout_t(&L, 0), acc = 0.0;
    dens3 da = density_at(md, radius_at(&L, ta));
    for (int k = 1; k <= m; k++) {
        double tb = layout_t(&L, k), ds = tb - ta;
        dens3 db = density_at(md, radius_at(&L, tb));
        double tau = tau_of(md, i, seg_column(da, db, ds));
        if (acc + tau >= tau_target && tau > 0.0 && ds > 0.0) {
            double need = tau_target - acc;
            /* per-component rates of the exponential forms */
            double kr = (da.r > 0.0 && db.r > 0.0) ? log(db.r / da.r) / ds : 0.0;
            double km = (da.m > 0.0 && db.m > 0.0) ? log(db.m / da.m) / ds : 0.0;
            double so = (db.o - da.o) / ds;
            double lo = 0.0, hi = ds, u = ds * need / tau;
            for (int it = 0; it < 60; it++) {
                double er = kr * u, em = km * u;
                double cr = da.r * u * (fabs(er) < 1e-9 ? 1.0 + 0.5 * er : expm1(er) / er);
                double cm = da.m * u * (fabs(em) < 1e-9 ? 1.0 + 0.5 * em : expm1(em) / em);
                double co = da.o * u + 0.5 * so * u * u;
                double f = md->br[i] * cr + md->bme[i] * cm + md->bo[i] * co - need;
                double fp = md->br[i] * da.r * exp(er) + md->bme[i] * da.m * exp(em) + md->bo[i] * (da.o + so * u);
                if (f > 0.0) hi = u;
                else lo = u;
                if (fabs(f) <= 1e-13 * tau || hi - lo <= 1e-13 * ds) break;
                double nu = fp > 0.0 ? u - f / fp : 0.5 * (lo + hi);
                u = (nu > lo && nu < hi) ? nu : 0.5 * (lo + hi);
            }
            dens->r = da.r * exp(kr * u);
            dens->m = da.m * exp(km * u);
            dens->o = fmax(0.0, da.o + so * u);
            *t_hit = ta + u;
            return 1;
        }
        acc += tau;
        ta = tb;
        da = db;
    }
    *tau_total = acc;
    return 0;
}

/* The sun's transmitted irradiance at a point (0 in the planet's shadow). */
static double sun_at(const ref_medium *md, int i, const double x[3], const double sun[3], int n)
{
    double r = sqrt(dot3(x, x));
    dens3 cs;
    if (!column_to_space(md, r, dot3(x, sun) / r, n, &cs)) return 0.0;
    return md->esun[i] * exp(-tau_of(md, i, cs));
}

/* One path's contribution of orders 2..max_order (0 = unbounded). */
static double trace_path(const ref_medium *md, int i, const double start[3], const double view[3], const double sun[3],
                         int n, int max_order, double first_max, ref_rng *rng)
{
    double pos[3] = {start[0], start[1], start[2]}, d[3] = {view[0], view[1], view[2]};
    double w = 1.0, c = 0.0;
    for (int order = 1; w > 0.0; order++) {
        double t_hit, t_end, tau_total;
        dens3 dn;
        int ground;
        double tau_target = -log(1.0 - rng_uniform(rng));
        if (order == 1) {
            /* Forced first collision: along a thin view ray most free
             * flights escape and add nothing. Draw the first vertex from
             * the flight distribution restricted to the ray, and carry the
             * probability of scattering there, 1 - T, in the weight. Where
             * the ray ends on the ground, half the paths go there instead
             * (weight T / 0.5) so the ground's bounce keeps its share. */
            (void)free_flight(md, i, pos, d, n, INFINITY, first_max, &t_hit, &dn, &ground, &t_end, &tau_total);
            double transmitted = exp(-tau_total), p_force = ground ? 0.5 : 1.0;
            if (rng_uniform(rng) < p_force) {
                double xi = rng_uniform(rng);
                tau_target = -log1p(-xi * -expm1(-tau_total));
                w *= -expm1(-tau_total) / p_force;
            } else {
                tau_target = INFINITY;
                w *= transmitted / (1.0 - p_force);
            }
        }
        int scattered = free_flight(md, i, pos, d, n, tau_target, order == 1 ? first_max : INFINITY, &t_hit, &dn, &ground,
                                    &t_end, &tau_total);
        if (scattered) {
            for (int j = 0; j < 3; j++) pos[j] += d[j] * t_hit;
            double ssr = md->br[i] * dn.r, ssm = md->bms[i] * dn.m;
            double st = ssr + md->bme[i] * dn.m + md->bo[i] * dn.o;
            if (!(st > 0.0)) break;
            if (order >= 2) {
                double ct = dot3(d, sun);
                double e = sun_at(md, i, pos, sun, n);
                if (e > 0.0) c += w * (ssr * phase_rayleigh(ct) + ssm * phase_cs(ct, md->g)) / st * e;
            }
            if (max_order && order >= max_order) break;
            double ss = ssr + ssm;
            if (!(ss > 0.0)) break;
            w *= ss / st; /* single-scattering albedo */
            double nd[3], phi = 2.0 * M_PI * rng_uniform(rng);
            if (rng_uniform(rng) * ss < ssr) {
                rotate_about(d, sample_rayleigh(rng_uniform(rng)), phi, nd);
            } else {
                /* Cornette-Shanks sampled through Henyey-Greenstein of the
                 * same g, weighted by their ratio (both normalised) */
                double ct = sample_hg(rng_uniform(rng), md->g);
                w *= phase_cs(ct, md->g) / phase_hg(ct, md->g);
                rotate_about(d, ct, phi, nd);
            }
            for (int j = 0; j < 3; j++) d[j] = nd[j];
        } else if (ground) {
            for (int j = 0; j < 3; j++) pos[j] += d[j] * t_end;
            double rg = sqrt(dot3(pos, pos)), nrm[3];
            for (int j = 0; j < 3; j++) {
                nrm[j] = pos[j] / rg;
                pos[j] = nrm[j] * md->R; /* exactly on the ground */
            }
            double a = md->albedo[i];
            if (!(a > 0.0)) break;
            if (order >= 2) {
                /* order 1 at the ground is the deterministic ground term */
                double mus = dot3(nrm, sun);
                if (mus > 0.0) c += w * a / M_PI * mus * sun_at(md, i, pos, sun, n);
            }
            if (max_order && order >= max_order) break;
            w *= a; /* Lambertian BRDF x cosine / cosine-weighted pdf */
            double xi = rng_uniform(rng);
            double ct = sqrt(xi), nd[3];
            rotate_about(nrm, ct, 2.0 * M_PI * rng_uniform(rng), nd);
            for (int j = 0; j < 3; j++) d[j] = nd[j];
        } else {
            break; /* escaped to space */
        }
        if (order >= 3) {
            double q = w < 0.95 ? (w > 0.05 ? w : 0.05) : 0.95;
            if (rng_uniform(rng) >= q) break;
            w /= q;
        }
    }
    return c;
}

/* ---- the public entry -------------------------------------------------------------------- */

int sky_ref_radiance(const sky_atmosphere_params *atm, double altitude_km, const double view[3],
                     const double sun[3], const sky_ref_options *opt, sky_ref_result *out)
{
    sky_atmosphere_params a;
    if (!out) return -1;
    memset(out, 0, sizeof *out);
    if (resolve_atm(atm, &a) || !unit_ok(view) || !unit_ok(sun)) return -1;
    if (!isfinite(altitude_km) || altitude_km < 0.0 || altitude_km > 1e6) return -1;
    sky_ref_options o;
    if (opt) o = *opt;
    else memset(&o, 0, sizeof o);
    if (o.view_segments < 0 || o.view_segments > REF_MAX_SEGMENTS || o.sun_segments < 0 ||
        o.sun_segments > REF_MAX_SEGMENTS || o.paths < 0 || o.paths > REF_MAX_PATHS || o.max_order < 0 ||
        o.max_order > REF_MAX_ORDER || !isfinite(o.only_nm) || (o.only_nm != 0.0 && (o.only_nm < 360.0 || o.only_nm > 830.0)) ||
        !isfinite(o.max_distance_km) || o.max_distance_km < 0.0)
        return -1;
    int nv = o.view_segments ? o.view_segments : REF_DEFAULT_VIEW_SEGMENTS;
    int ns = o.sun_segments ? o.sun_segments : REF_DEFAULT_SUN_SEGMENTS;
    int np = o.paths ? o.paths : REF_DEFAULT_PATHS;
    unsigned long long seed = o.seed ? o.seed : 0x5EED5C1E5ULL;

    ref_medium md;
    medium_init(&md, &a, o.only_nm);
    double eye[3] = {0.0, md.R + altitude_km, 0.0};
    double dmax = o.max_distance_km;
    single_scattering(&md, eye, view, sun, nv, ns, dmax, out->single, out->transmittance);
    for (int i = 0; i < md.n; i++) out->spectral[i] = out->single[i];

    if (o.max_order != 1) {
        /* the first vertex of every path lies in the shell: start there */
        double r = md.R + altitude_km, t0, t1, start[3];
        int ground;
        if (ray_interval(&md, r, view[1], &t0, &t1, &ground)) {
            for (int j = 0; j < 3; j++) start[j] = eye[j] + view[j] * t0;
            for (int i = 0; i < md.n; i++) {
                ref_rng rng;
                unsigned long long s = seed ^ (0xA24BAED4963EE407ULL * (unsigned long long)(i + 1));
                rng_seed(&rng, s);
                double sum = 0.0, sum2 = 0.0;
                for (int p = 0; p < np; p++) {
                    double c = trace_path(&md, i, start, view, sun, ns, o.max_order,
                                          dmax > 0.0 ? fmax(dmax - t0, 0.0) : INFINITY, &rng);
                    sum += c;
                    sum2 += c * c;
                }
                double mean = sum / np;
                double var = np > 1 ? (sum2 - sum * mean) / (np - 1) : 0.0;
                out->spectral[i] += mean;
                out->spectral_std_err[i] = sqrt(var > 0.0 ? var / np : 0.0);
            }
        }
    }
    if (o.only_nm == 0.0) {
        sky_spectrum_to_xyz(out->spectral, out->xyz);
        sky_spectrum_xyz_to_linear_srgb(out->xyz, out->rgb);
        /* the transmittance of sunlight per channel */
        double et[SKY_REF_WAVELENGTHS], xyz_et[3], xyz_e[3], rgb_e[3];
        for (int i = 0; i < SKY_REF_WAVELENGTHS; i++) et[i] = md.esun[i] * out->transmittance[i];
        sky_spectrum_to_xyz(et, xyz_et);
        sky_spectrum_xyz_to_linear_srgb(xyz_et, out->transmittance_rgb);
        sky_spectrum_to_xyz(md.esun, xyz_e);
        sky_spectrum_xyz_to_linear_srgb(xyz_e, rgb_e);
        for (int c = 0; c < 3; c++) out->transmittance_rgb[c] = rgb_e[c] > 0.0 ? out->transmittance_rgb[c] / rgb_e[c] : 0.0;
        double v = 0.0;
        for (int i = 0; i < SKY_REF_WAVELENGTHS; i++) {
            double c[3];
            sky_spectrum_cmf(sky_spectrum_wavelength_nm(i), c);
            double e = c[1] * out->spectral_std_err[i];
            v += e * e;
        }
        out->luminance_std_err = SKY_SPECTRUM_LM_PER_W * SKY_SPECTRUM_STEP_NM / 1000.0 * sqrt(v);
    }
    return 0;
}
