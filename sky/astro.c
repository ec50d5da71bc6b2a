/*
 * Positional astronomy (see astro.h). Formulas from J. Meeus, Astronomical
 * Algorithms, 2nd ed. (1998), cited by chapter and equation; the VSOP87 and
 * ELP terms are in astro_tables.c.
 */
#include "astro.h"
#include "astro_tables.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>

#define PI 3.14159265358979323846
#define TWO_PI (2.0 * PI)
#define DEG (PI / 180.0)
#define ARCSEC (PI / 648000.0)
#define J2000 2451545.0
#define AU_KM 149597870.7
#define EARTH_RADIUS_KM 6378.137     /* WGS84 equatorial */
#define EARTH_FLATTENING (1.0 / 298.257223563)
#define MOON_RADIUS_KM 1737.4
#define SUN_RADIUS_KM 696000.0       /* IAU nominal: 959.63" at 1 au */

static double astro_clamp(double x, double lo, double hi) { return x < lo ? lo : (x > hi ? hi : x); }
/* asin/acos of a value rounding may have pushed past +-1 */
static double safe_asin(double x) { return asin(astro_clamp(x, -1.0, 1.0)); }
static double wrap_2pi(double a)
{
    a = fmod(a, TWO_PI);
    return a < 0.0 ? a + TWO_PI : a;
}
static double poly(double t, const double *c, int n)
{
    double s = 0.0;
    for (int i = n - 1; i >= 0; i--) s = s * t + c[i];
    return s;
}

/* ---- time ---------------------------------------------------------------------- */

double sky_jd_from_calendar(int year, int month, int day, int hour, int minute, double second)
{
    /* Proleptic Gregorian to Julian day number (Fliegel & Van Flandern
     * 1968), with floor division so it holds for negative years too. */
    long a = (14 - month) / 12;
    long y = (long)year + 4800 - a;
    long m = month + 12 * a - 3;
    long yd = y >= 0 ? y / 4 : -((-y + 3) / 4);
    long yc = y >= 0 ? y / 100 : -((-y + 99) / 100);
    long yq = y >= 0 ? y / 400 : -((-y + 399) / 400);
    long jdn = day + (153 * m + 2) / 5 + 365 * y + yd - yc + yq - 32045;
    return (double)jdn - 0.5 + (hour + (minute + second / 60.0) / 60.0) / 24.0;
}

void sky_calendar_from_jd(double jd, int *year, int *month, int *day, double *day_fraction)
{
    /* inverse of the above (Richards' algorithm), floor-based */
    double z = floor(jd + 0.5);
    *day_fraction = jd + 0.5 - z;
    long j = (long)z;
    long f = j + 1401 + (((4 * j + 274277) / 146097) * 3) / 4 - 38;
    if (4 * j + 274277 < 0) f = j + 1401 + ((((4 * j + 274277) - 146096) / 146097) * 3) / 4 - 38;
    long e = 4 * f + 3;
    long g = (e % 1461 + 1461) % 1461 / 4;
    long h = 5 * g + 2;
    *day = (int)((h % 153) / 5 + 1);
    *month = (int)((h / 153 + 2) % 12 + 1);
    long ediv = e >= 0 ? e / 1461 : -((-e + 1460) / 1461);
    *year = (int)(ediv - 4716 + (14 - *month) / 12);
}

double sky_jd_from_unix(double unix_seconds) { return 2440587.5 + unix_seconds / 86400.0; }

double sky_delta_t(double jd_ut)
{
    /* Espenak & Meeus (2006), "Polynomial expressions for Delta T",
     * NASA Five Millennium Canon of Solar Eclipses; y is the decimal year. */
    double y = 2000.0 + (jd_ut - J2000) / 365.25;
    double u, t;
    if (y < -500.0) {
        u = (y - 1820.0) / 100.0;
        return -20.0 + 32.0 * u * u;
    }
    if (y < 500.0) {
        static const double c[7] = {10583.6, -1014.41, 33.78311, -5.952053, -0.1798452, 0.022174192, 0.0090316521};
        return poly(y / 100.0, c, 7);
    }
    if (y < 1600.0) {
        static const double c[7] = {1574.2, -556.01, 71.23472, 0.319781, -0.8503463, -0.005050998, 0.0083572073};
        return poly((y - 1000.0) / 100.0, c, 7);
    }
    if (y < 1700.0) {
        t = y - 1600.0;
        return 120.0 - 0.9808 * t - 0.01532 * t * t + t * t * t / 7129.0;
    }
    if (y < 1800.0) {
        t = y - 1700.0;
        return 8.83 + 0.1603 * t - 0.0059285 * t * t + 0.00013336 * t * t * t - t * t * t * t / 1174000.0;
    }
    if (y < 1860.0) {
        static const double c[8] = {13.72,         -0.332447,  0.0068612,      0.0041116,
                                    -0.00037436,  0.0000121272, -0.0000001699, 0.000000000875};
        return poly(y - 1800.0, c, 8);
    }
    if (y < 1900.0) {
        static const double c[6] = {7.62, 0.5737, -0.251754, 0.01680668, -0.0004473624, 1.0 / 233174.0};
        return poly(y - 1860.0, c, 6);
    }
    if (y < 1920.0) {
        static const double c[5] = {-2.79, 1.494119, -0.0598939, 0.0061966, -0.000197};
        return poly(y - 1900.0, c, 5);
    }
    if (y < 1941.0) {
        static const double c[4] = {21.20, 0.84493, -0.076100, 0.0020936};
        return poly(y - 1920.0, c, 4);
    }
    if (y < 1961.0) {
        static const double c[4] = {29.07, 0.407, -1.0 / 233.0, 1.0 / 2547.0};
        return poly(y - 1950.0, c, 4);
    }
    if (y < 1986.0) {
        static const double c[4] = {45.45, 1.067, -1.0 / 260.0, -1.0 / 718.0};
        return poly(y - 1975.0, c, 4);
    }
    if (y < 2005.0) {
        static const double c[6] = {63.86, 0.3345, -0.060374, 0.0017275, 0.000651814, 0.00002373599};
        return poly(y - 2000.0, c, 6);
    }
    if (y < 2050.0) {
        t = y - 2000.0;
        return 62.92 + 0.32217 * t + 0.005589 * t * t;
    }
    u = (y - 1820.0) / 100.0;
    if (y < 2150.0) return -20.0 + 32.0 * u * u - 0.5628 * (2150.0 - y);
    return -20.0 + 32.0 * u * u;
}

double sky_gmst(double jd_ut)
{
    /* Meeus 12.4; the day count is split so the large linear term keeps
     * its precision */
    double d = jd_ut - J2000, t = d / 36525.0;
    double whole = floor(d), frac = d - whole;
    double deg = 280.46061837 + 360.98564736629 * frac + fmod(0.98564736629 * whole, 360.0) +
                 0.000387933 * t * t - t * t * t / 38710000.0;
    return wrap_2pi(deg * DEG);
}

/* ---- rotations --------------------------------------------------------------------- */

typedef double mat3[9]; /* row-major */

static void mat_mul(const double *a, const double *b, double *out)
{
    double r[9];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) r[i * 3 + j] = a[i * 3] * b[j] + a[i * 3 + 1] * b[3 + j] + a[i * 3 + 2] * b[6 + j];
    for (int i = 0; i < 9; i++) out[i] = r[i];
}
static void mat_vec(const double *m, const double *v, double *out)
{
    double r[3];
    for (int i = 0; i < 3; i++) r[i] = m[i * 3] * v[0] + m[i * 3 + 1] * v[1] + m[i * 3 + 2] * v[2];
    out[0] = r[0], out[1] = r[1], out[2] = r[2];
}
/* Frame rotations about x, y, z by angle a (the frame turns, vectors keep). */
static void rot_x(double a, double *m)
{
    double c = cos(a), s = sin(a);
    double r[9] = {1, 0, 0, 0, c, s, 0, -s, c};
    for (int i = 0; i < 9; i++) m[i] = r[i];
}
static void rot_y(double a, double *m)
{
    double c = cos(a), s = sin(a);
    double r[9] = {c, 0, -s, 0, 1, 0, s, 0, c};
    for (int i = 0; i < 9; i++) m[i] = r[i];
}
static void rot_z(double a, double *m)
{
    double c = cos(a), s = sin(a);
    double r[9] = {c, s, 0, -s, c, 0, 0, 0, 1};
    for (int i = 0; i < 9; i++) m[i] = r[i];
}

static void spherical_to_vec(double lon, double lat, double *v)
{
    v[0] = cos(lat) * cos(lon);
    v[1] = cos(lat) * sin(lon);
    v[2] = sin(lat);
}
static void vec_to_spherical(const double *v, double *lon, double *lat)
{
    double r = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    *lon = wrap_2pi(atan2(v[1], v[0]));
    *lat = r > 0.0 ? safe_asin(v[2] / r) : 0.0;
}

/* ---- nutation, obliquity, precession ---------------------------------------------------- */

/* Mean obliquity, Laskar (1986) as in Meeus 22.3: good to 0.01" over
 * 1000 years and a few arcseconds over 10000. t in Julian centuries TT. */
static double mean_obliquity(double t)
{
    static const double c[11] = {84381.448, -4680.93, -1.55, 1999.25, -51.38, -249.67,
                                 -39.05,    7.12,     27.87, 5.79,    2.45};
    return poly(t / 100.0, c, 11) * ARCSEC;
}

/* Nutation in longitude and obliquity, the four largest terms (Meeus
 * ch. 22): 0.5" in longitude, 0.1" in obliquity. */
static void nutation(double t, double *dpsi, double *deps)
{
    double omega = (125.04452 - 1934.136261 * t + 0.0020708 * t * t + t * t * t / 450000.0) * DEG;
    double l_sun = (280.4665 + 36000.7698 * t) * DEG, l_moon = (218.3165 + 481267.8813 * t) * DEG;
    *dpsi = (-17.20 * sin(omega) - 1.32 * sin(2 * l_sun) - 0.23 * sin(2 * l_moon) + 0.21 * sin(2 * omega)) * ARCSEC;
    *deps = (9.20 * cos(omega) + 0.57 * cos(2 * l_sun) + 0.10 * cos(2 * l_moon) - 0.09 * cos(2 * omega)) * ARCSEC;
}

/* J2000 mean equator -> mean equator of date: Lieske et al. (1977) angles,
 * Meeus 21.2-21.4; P = Rz(-z) Ry(theta) Rz(-zeta). */
static void precession_matrix(double t, double *p)
{
    double zeta = (2306.2181 * t + 0.30188 * t * t + 0.017998 * t * t * t) * ARCSEC;
    double z = (2306.2181 * t + 1.09468 * t * t + 0.018203 * t * t * t) * ARCSEC;
    double theta = (2004.3109 * t - 0.42665 * t * t - 0.041833 * t * t * t) * ARCSEC;
    double a[9], b[9], c[9];
    rot_z(-zeta, a);
    rot_y(theta, b);
    rot_z(-z, c);
    mat_mul(b, a, p);
    mat_mul(c, p, p);
}

/* ---- the sun ---------------------------------------------------------------------------- */

static double vsop_sum(const sky_vsop_series *series, int n, double tau)
{
    double total = 0.0, tp = 1.0;
    for (int i = 0; i < n; i++, tp *= tau) {
        double s = 0.0;
        for (int k = 0; k < series[i].count; k++) {
            const sky_vsop_term *term = &series[i].terms[k];
            s += term->a * cos(term->b + term->c * tau);
        }
        total += s * tp;
    }
    return total * 1e-8;
}

/* Apparent geocentric ecliptic longitude and latitude of the sun and its
 * distance in au (Meeus ch. 25, higher accuracy): VSOP87 heliocentric
 * Earth, FK5 correction (32.3), nutation, aberration. Also the true
 * geometric longitude (for stellar aberration), and the Earth's
 * heliocentric rectangular position (for the planets). */
static void earth_lbr(double t, double lbr[3])
{
    double tau = t / 10.0;
    lbr[0] = vsop_sum(sky_earth_L, 6, tau);
    lbr[1] = vsop_sum(sky_earth_B, 2, tau);
    lbr[2] = vsop_sum(sky_earth_R, 5, tau);
}

static void sun_position(double t, const double lbr[3], double dpsi, double *lambda, double *beta, double *r_au,
                         double *true_lon, double earth[3])
{
    double l = lbr[0], b = lbr[1], r = lbr[2];
    earth[0] = r * cos(b) * cos(l);
    earth[1] = r * cos(b) * sin(l);
    earth[2] = r * sin(b);
    double theta = wrap_2pi(l + PI), bet = -b;
    double lp = theta - (1.397 * t + 0.00031 * t * t) * DEG;
    theta += -0.09033 * ARCSEC;
    bet += 0.03916 * ARCSEC * (cos(lp) - sin(lp));
    *true_lon = theta;
    *lambda = wrap_2pi(theta + dpsi - 20.4898 * ARCSEC / r);
    *beta = bet;
    *r_au = r;
}

/* ---- the moon ----------------------------------------------------------------------------- */

/* The moon's mean arguments (Meeus 47.1-47.5), radians. */
typedef struct moon_args {
    double lp, d, m, mp, f;
} moon_args;

static moon_args moon_arguments(double t)
{
    double t2 = t * t, t3 = t2 * t, t4 = t3 * t;
    moon_args g;
    g.lp = (218.3164477 + 481267.88123421 * t - 0.0015786 * t2 + t3 / 538841.0 - t4 / 65194000.0) * DEG;
    g.d = (297.8501921 + 445267.1114034 * t - 0.0018819 * t2 + t3 / 545868.0 - t4 / 113065000.0) * DEG;
    g.m = (357.5291092 + 35999.0502909 * t - 0.0001536 * t2 + t3 / 24490000.0) * DEG;
    g.mp = (134.9633964 + 477198.8675055 * t + 0.0087414 * t2 + t3 / 69699.0 - t4 / 14712000.0) * DEG;
    g.f = (93.2720950 + 483202.0175233 * t - 0.0036539 * t2 - t3 / 3526000.0 + t4 / 863310000.0) * DEG;
    return g;
}

/* The sums of Meeus tables 47.A and 47.B, all terms, with the additive
 * terms of A1..A3: sum l and sum b in 1e-6 degrees, sum r in metres. */
static void moon_sums(double t, double sums[3])
{
    moon_args g = moon_arguments(t);
    double a1 = (119.75 + 131.849 * t) * DEG, a2 = (53.09 + 479264.290 * t) * DEG,
           a3 = (313.45 + 481266.484 * t) * DEG;
    double e = 1.0 - 0.002516 * t - 0.0000074 * t * t;
    double sl = 0.0, sr = 0.0, sb = 0.0;
    for (int i = 0; i < 60; i++) {
        const sky_moon_term *k = &sky_moon_lr[i];
        double arg = k->d * g.d + k->m * g.m + k->mp * g.mp + k->f * g.f;
        double ef = k->m == 0 ? 1.0 : (k->m == 1 || k->m == -1 ? e : e * e); /* 47.6 */
        sl += k->a * ef * sin(arg);
        sr += k->b * ef * cos(arg);
    }
    for (int i = 0; i < 60; i++) {
        const sky_moon_term *k = &sky_moon_b[i];
        double arg = k->d * g.d + k->m * g.m + k->mp * g.mp + k->f * g.f;
        double ef = k->m == 0 ? 1.0 : (k->m == 1 || k->m == -1 ? e : e * e);
        sb += k->a * ef * sin(arg);
    }
    sl += 3958.0 * sin(a1) + 1962.0 * sin(g.lp - g.f) + 318.0 * sin(a2);
    sb += -2235.0 * sin(g.lp) + 382.0 * sin(a3) + 175.0 * sin(a1 - g.f) + 175.0 * sin(a1 + g.f) +
          127.0 * sin(g.lp - g.mp) - 115.0 * sin(g.lp + g.mp);
    sums[0] = sl;
    sums[1] = sb;
    sums[2] = sr;
}

/* Geocentric ecliptic longitude (of date, without nutation), latitude and
 * distance (km) of the moon from the sums of its series (Meeus ch. 47).
 * Also the mean argument F and the ascending node (ch. 53). */
static void moon_position(double t, const double sums[3], double *lambda, double *beta, double *dist, double *f_out,
                          double *node)
{
    moon_args g = moon_arguments(t);
    double t2 = t * t, t3 = t2 * t, t4 = t3 * t;
    *lambda = wrap_2pi(g.lp + sums[0] * 1e-6 * DEG);
    *beta = sums[1] * 1e-6 * DEG;
    *dist = 385000.56 + sums[2] / 1000.0;
    *f_out = g.f;
    *node = (125.0445479 - 1934.1362891 * t + 0.0020754 * t2 + t3 / 467441.0 - t4 / 60616000.0) * DEG;
}

/* ---- the slow terms, at nodes ------------------------------------------------------------- */

static void node_at(double index, sky_astro_node *n)
{
    double t = (index / SKY_ASTRO_NODES_PER_DAY - J2000) / 36525.0;
    n->index = index;
    earth_lbr(t, n->earth_lbr);
    moon_sums(t, n->moon_sums);
}

/* The node with this index: from the cache, or evaluated into a free
 * slot or the least recently used one other than keep's. */
static const sky_astro_node *node_get(sky_astro_cache *cache, double index, double keep)
{
    sky_astro_node *n = NULL;
    for (int i = 0; i < cache->count && !n; i++)
        if (cache->node[i].index == index) n = &cache->node[i];
    if (!n) {
        if (cache->count < SKY_ASTRO_CACHE_NODES) {
            n = &cache->node[cache->count++];
        } else {
            for (int i = 0; i < SKY_ASTRO_CACHE_NODES; i++) {
                sky_astro_node *c = &cache->node[i];
                if (c->index != keep && (!n || c->last_use < n->last_use)) n = c;
            }
        }
        node_at(index, n);
    }
    n->last_use = ++cache->uses;
    return n;
}

/* The Earth's place and the moon's sums at jd_tt, interpolated linearly
 * between the nodes around it (astro.h). The VSOP87 longitude and the sums
 * are continuous series (not wrapped), so they interpolate as they are. */
static void slow_terms(double jd_tt, sky_astro_cache *cache, double lbr[3], double sums[3])
{
    sky_astro_cache local = {0};
    if (!cache) cache = &local;
    double x = jd_tt * SKY_ASTRO_NODES_PER_DAY, i0 = floor(x), w = x - i0;
    /* each lookup keeps the other's node, so a stays valid */
    const sky_astro_node *a = node_get(cache, i0, i0 + 1.0), *b = node_get(cache, i0 + 1.0, i0);
    for (int k = 0; k < 3; k++) {
        lbr[k] = a->earth_lbr[k] + w * (b->earth_lbr[k] - a->earth_lbr[k]);
        sums[k] = a->moon_sums[k] + w * (b->moon_sums[k] - a->moon_sums[k]);
    }
}

/* ---- horizon ------------------------------------------------------------------------------- */

double sky_refraction(double h, double pressure_factor)
{
    /* Saemundsson (1986), Meeus 16.4, for the true altitude in degrees;
     * +0.0019279' makes it vanish at the zenith. Below -1 degree the
     * formula heads for its pole at -5.1; the taper keeps it continuous,
     * finite and the apparent altitude monotonic. */
    double hd = h / DEG;
    double hc = hd > -1.0 ? hd : -1.0;
    double r_arcmin = 1.02 / tan((hc + 10.3 / (hc + 5.11)) * DEG) + 0.0019279;
    if (hd >= 89.999) r_arcmin = 0.0;
    double taper = hd >= -1.0 ? 1.0 : astro_clamp((hd + 6.0) / 5.0, 0.0, 1.0);
    return r_arcmin / 60.0 * DEG * taper * pressure_factor;
}

void sky_horizon_vector(double alt, double az, double out[3])
{
    out[0] = cos(alt) * sin(az);  /* east */
    out[1] = sin(alt);            /* up */
    out[2] = -cos(alt) * cos(az); /* south: azimuth 0 is north (-z) */
}

/* True equator of date -> horizon frame: rows are east, up, south in
 * equatorial coordinates for local apparent sidereal time `last`. */
static void horizon_matrix(double last, double lat, double *m)
{
    double sl = sin(last), cl = cos(last), sp = sin(lat), cp = cos(lat);
    /* zenith = (cp cl, cp sl, sp); north = (-sp cl, -sp sl, cp); east = (-sl, cl, 0) */
    double r[9] = {-sl, cl, 0.0, cp * cl, cp * sl, sp, sp * cl, sp * sl, -cp};
    for (int i = 0; i < 9; i++) m[i] = r[i];
}

static void horizon_from_vector(const double *v, double pressure, double *alt, double *alt_geo, double *az,
                                double dir[3])
{
    double n = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    double h = safe_asin(v[1] / n);
    *alt_geo = h;
    *az = wrap_2pi(atan2(v[0], -v[2]));
    *alt = h + sky_refraction(h, pressure);
    sky_horizon_vector(*alt, *az, dir);
}

/* Topocentric horizon place of a body at geocentric apparent (ra, dec,
 * distance_km): the observer's geocentric position is subtracted in the
 * equatorial frame of date (rigorous parallax, Meeus ch. 11 and 40). */
static void body_place(const sky_astro *a, const double obs_eq[3], sky_astro_body *b)
{
    double v[3], h[3];
    spherical_to_vec(b->ra, b->dec, v);
    for (int i = 0; i < 3; i++) v[i] = v[i] * b->distance_km - obs_eq[i];
    b->topo_distance_km = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    mat_vec(a->horizon, v, h);
    horizon_from_vector(h, a->pressure_factor, &b->alt, &b->alt_geometric, &b->az, b->dir);
    sky_horizon_vector(b->alt_geometric, b->az, b->dir_geometric);
}

static void ecl_to_eq(double lambda, double beta, double eps, double *ra, double *dec)
{
    double v[3], m[9];
    spherical_to_vec(lambda, beta, v);
    rot_x(-eps, m);
    mat_vec(m, v, v);
    vec_to_spherical(v, ra, dec);
}

/* Angular distance between two points on the sphere (haversine form,
 * accurate for small and large angles). */
static double separation(double ra1, double dec1, double ra2, double dec2)
{
    double sd = sin((dec2 - dec1) / 2), sr = sin((ra2 - ra1) / 2);
    double h = sd * sd + cos(dec1) * cos(dec2) * sr * sr;
    return 2.0 * safe_asin(sqrt(astro_clamp(h, 0.0, 1.0)));
}

/* Area of the lens where two discs of radii r1, r2 at distance d overlap. */
static double overlap_area(double r1, double r2, double d)
{
    if (d >= r1 + r2) return 0.0;
    double rmin = fmin(r1, r2);
    if (d <= fabs(r1 - r2)) return PI * rmin * rmin;
    double c1 = astro_clamp((d * d + r1 * r1 - r2 * r2) / (2.0 * d * r1), -1.0, 1.0);
    double c2 = astro_clamp((d * d + r2 * r2 - r1 * r1) / (2.0 * d * r2), -1.0, 1.0);
    double k = (-d + r1 + r2) * (d + r1 - r2) * (d - r1 + r2) * (d + r1 + r2);
    return r1 * r1 * acos(c1) + r2 * r2 * acos(c2) - 0.5 * sqrt(fmax(k, 0.0));
}

void sky_solar_eclipse(double sun_radius, double moon_radius, double separation, double *obscuration,
                       double *magnitude, double *flux_fraction)
{
    /* anything not finite is no eclipse (fmax would let a NaN through as
     * the other operand) */
    int sane = isfinite(sun_radius) && isfinite(moon_radius) && isfinite(separation);
    double rs = sane ? fmax(sun_radius, 1e-12) : 1.0, rm = sane ? fmax(moon_radius, 0.0) : 0.0;
    double d = sane ? fmax(separation, 0.0) : 1.0;
    double covered = 0.0, mag = 0.0, flux = 1.0;
    if (rm > 0.0 && d < rs + rm) {
        covered = astro_clamp(overlap_area(rs, rm, d) / (PI * rs * rs), 0.0, 1.0);
        mag = (rs + rm - d) / (2.0 * rs);
        /* The limb-darkened light behind the moon (Schneegans et al.
         * eq. 1), over rings of the sun's disc at mu = sqrt(1 - (rho/R)^2),
         * where rho drho = -R^2 mu dmu: each ring weighted by its
         * brightness and the arc of it inside the moon's disc. Rings
         * nearer the sun's centre than |d - r_m| lie wholly inside (or
         * outside) the moon: closed form. Between |d - r_m| and d + r_m
         * the arc opens like a square root at both ends: mu = c + h cos t
         * with the midpoint rule in t takes the roots out. */
        const double u = SKY_SUN_LIMB_DARKENING;
        double rho_a = fmin(fabs(d - rm), rs), rho_b = fmin(d + rm, rs);
        double mu_a = sqrt(fmax(1.0 - (rho_a / rs) * (rho_a / rs), 0.0));
        double mu_b = sqrt(fmax(1.0 - (rho_b / rs) * (rho_b / rs), 0.0));
        double hidden = 0.0;
        if (rm > d) /* the rings inside rho_a are covered whole */
            hidden = 2.0 * PI * ((1.0 - u) * (1.0 - mu_a * mu_a) / 2.0 + u * (1.0 - mu_a * mu_a * mu_a) / 3.0);
        const int n = 256;
        double c = 0.5 * (mu_a + mu_b), h = 0.5 * (mu_a - mu_b), partial = 0.0;
        for (int i = 0; h > 0.0 && i < n; i++) {
            double t = (i + 0.5) * PI / n, mu = c + h * cos(t), rho = rs * sqrt(fmax(1.0 - mu * mu, 0.0));
            double arc = rho > 0.0 && d > 0.0
                             ? 2.0 * acos(astro_clamp((rho * rho + d * d - rm * rm) / (2.0 * rho * d), -1.0, 1.0))
                             : 0.0;
            partial += (1.0 - u * (1.0 - mu)) * arc * mu * h * sin(t);
        }
        hidden += partial * PI / n;
        /* per unit R^2; the whole disc gives pi (1 - u/3) */
        hidden *= rs * rs;
        flux = astro_clamp(1.0 - hidden / (PI * rs * rs * (1.0 - u / 3.0)), 0.0, 1.0);
    }
    if (obscuration) *obscuration = covered;
    if (magnitude) *magnitude = mag;
    if (flux_fraction) *flux_fraction = flux;
}

/* Mueller sec. 5's day-night fades of the stars and the moon for a sun
 * whose up component is s_z; the powers act on clamped bases so they stay
 * finite. */
static double star_fade(double s_z) { return 1.0 / sqrt(1.0 + pow(astro_clamp(s_z + 1.14, 0.0, 2.14), 32.0)); }
static double moon_fade(double s_z) { return 0.5 + 1.0 / sqrt(2.0 + 2.0 * pow(astro_clamp(s_z + 1.05, 0.0, 2.05), 32.0)); }

static void set_error(char *err, size_t len, const char *fmt, ...)
{
    if (!err || !len) return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, len, fmt, ap);
    va_end(ap);
}

int sky_astro_compute(double jd_ut, const sky_astro_observer *obs, sky_astro *a, char *err, size_t err_len)
{
    return sky_astro_compute_dt(jd_ut, isfinite(jd_ut) ? sky_delta_t(jd_ut) : 0.0, obs, a, err, err_len);
}

int sky_astro_compute_dt(double jd_ut, double delta_t, const sky_astro_observer *obs, sky_astro *a, char *err,
                         size_t err_len)
{
    return sky_astro_compute_cached(jd_ut, delta_t, obs, NULL, a, err, err_len);
}

int sky_astro_compute_cached(double jd_ut, double delta_t, const sky_astro_observer *obs, sky_astro_cache *cache,
                             sky_astro *a, char *err, size_t err_len)
{
    if (!isfinite(jd_ut) || !isfinite(delta_t) || !obs || !isfinite(obs->latitude) || !isfinite(obs->longitude) ||
        !isfinite(obs->altitude_m)) {
        set_error(err, err_len, "date or observer is not finite");
        return -1;
    }
    double year = 2000.0 + (jd_ut - J2000) / 365.25;
    if (year < SKY_ASTRO_YEAR_MIN || year >= SKY_ASTRO_YEAR_MAX + 1) {
        set_error(err, err_len, "year %.0f is outside the supported range %d..%d", floor(year), SKY_ASTRO_YEAR_MIN,
                  SKY_ASTRO_YEAR_MAX);
        return -1;
    }
    if (fabs(obs->latitude) > PI / 2 + 1e-12) {
        set_error(err, err_len, "latitude %.6g degrees is outside -90..90", obs->latitude / DEG);
        return -1;
    }
    if (obs->altitude_m < -500.0 || obs->altitude_m > 100000.0) {
        set_error(err, err_len, "altitude %.6g m is outside -500..100000", obs->altitude_m);
        return -1;
    }
    double lat = astro_clamp(obs->latitude, -PI / 2, PI / 2);
    a->jd_ut = jd_ut;
    a->delta_t = delta_t;
    a->jd_tt = jd_ut + a->delta_t / 86400.0;
    double t = (a->jd_tt - J2000) / 36525.0;
    a->years_since_j2000 = (a->jd_tt - J2000) / 365.25;

    double dpsi, deps;
    nutation(t, &dpsi, &deps);
    double eps0 = mean_obliquity(t), eps = eps0 + deps;
    a->obliquity = eps;
    a->nutation_longitude = dpsi;
    double gmst = sky_gmst(jd_ut);
    a->lmst = wrap_2pi(gmst + obs->longitude);
    a->last = wrap_2pi(gmst + dpsi * cos(eps) + obs->longitude);
    horizon_matrix(a->last, lat, a->horizon);
    /* refraction at the observer's pressure (scale height 8.4 km) */
    a->pressure_factor = exp(-obs->altitude_m / 8434.5);

    /* the observer's geocentric position, equatorial of date, km (WGS84
     * ellipsoid, Meeus ch. 11) */
    double b_a = 1.0 - EARTH_FLATTENING;
    double u = atan(b_a * tan(lat));
    double rho_sin = b_a * sin(u) + obs->altitude_m / 1000.0 / EARTH_RADIUS_KM * sin(lat);
    double rho_cos = cos(u) + obs->altitude_m / 1000.0 / EARTH_RADIUS_KM * cos(lat);
    double *obs_eq = a->observer_eq;
    obs_eq[0] = EARTH_RADIUS_KM * rho_cos * cos(a->last);
    obs_eq[1] = EARTH_RADIUS_KM * rho_cos * sin(a->last);
    obs_eq[2] = EARTH_RADIUS_KM * rho_sin;

    /* sun */
    double lbr[3], sums[3];
    slow_terms(a->jd_tt, cache, lbr, sums);
    double sl, sb, sr, true_lon;
    sun_position(t, lbr, dpsi, &sl, &sb, &sr, &true_lon, a->earth_helio);
    ecl_to_eq(sl, sb, eps, &a->sun.ra, &a->sun.dec);
    a->sun.distance_km = sr * AU_KM;
    body_place(a, obs_eq, &a->sun);
    a->sun_semidiameter = atan(SUN_RADIUS_KM / a->sun.distance_km);

    /* moon: apparent longitude adds nutation (Meeus 47); no aberration,
     * the moon moves with the Earth (light time is 1.3 s: 0.7") */
    double ml, mb, md, f, node;
    moon_position(t, sums, &ml, &mb, &md, &f, &node);
    double ml_app = wrap_2pi(ml + dpsi);
    ecl_to_eq(ml_app, mb, eps, &a->moon.ra, &a->moon.dec);
    a->moon.distance_km = md;
    body_place(a, obs_eq, &a->moon);
    a->moon_semidiameter = asin(astro_clamp(MOON_RADIUS_KM / md, 0.0, 1.0));

    /* phase (Meeus 48.2-48.5, geocentric) */
    double psi = separation(a->sun.ra, a->sun.dec, a->moon.ra, a->moon.dec);
    a->moon_phase_angle = atan2(a->sun.distance_km * sin(psi), md - a->sun.distance_km * cos(psi));
    a->moon_illuminated = (1.0 + cos(a->moon_phase_angle)) / 2.0;
    double dra = a->sun.ra - a->moon.ra;
    a->moon_bright_limb = wrap_2pi(atan2(cos(a->sun.dec) * sin(dra), sin(a->sun.dec) * cos(a->moon.dec) -
                                                                          cos(a->sun.dec) * sin(a->moon.dec) * cos(dra)));
    /* optical libration and position angle of the axis (Meeus 53.1-53.2,
     * physical libration left out: under 0.04 degrees) */
    const double inc = 1.54242 * DEG;
    double w = ml_app - dpsi - node;
    double lib_a = atan2(sin(w) * cos(mb) * cos(inc) - sin(mb) * sin(inc), cos(w) * cos(mb));
    double lib_l = wrap_2pi(lib_a - f);
    a->moon_libration_lon = lib_l > PI ? lib_l - TWO_PI : lib_l;
    a->moon_libration_lat = safe_asin(-sin(w) * cos(mb) * sin(inc) - sin(mb) * cos(inc));
    double v_node = node + dpsi;
    double x = sin(inc) * sin(v_node), y = sin(inc) * cos(v_node) * cos(eps) - cos(inc) * sin(eps);
    double omega = atan2(x, y);
    a->moon_axis_angle = safe_asin(sqrt(x * x + y * y) * cos(a->moon.ra - omega) / cos(a->moon_libration_lat));
    /* parallactic angle (Meeus 14.1) at the moon's geocentric place; the
     * topocentric shift changes it by far less than the disc shows */
    double hour = a->last - a->moon.ra;
    a->moon_parallactic = atan2(sin(hour), tan(lat) * cos(a->moon.dec) - sin(a->moon.dec) * cos(hour));

    /* lunar eclipse: Danjon's rule as used by Espenak's canon. The shadow
     * axis points at the antisolar point; pi' is the moon's parallax on
     * the Earth's mean radius; the 1.01 enlarges the shadow for the
     * atmosphere. */
    double pi_moon = asin(EARTH_RADIUS_KM / md) * 0.998340, pi_sun = asin(EARTH_RADIUS_KM / a->sun.distance_km);
    a->umbra_radius = 1.01 * pi_moon + pi_sun - a->sun_semidiameter;
    a->penumbra_radius = 1.01 * pi_moon + pi_sun + a->sun_semidiameter;
    a->shadow_distance = separation(wrap_2pi(a->sun.ra + PI), -a->sun.dec, a->moon.ra, a->moon.dec);
    a->umbral_magnitude = (a->umbra_radius + a->moon_semidiameter - a->shadow_distance) / (2.0 * a->moon_semidiameter);
    a->penumbral_magnitude =
        (a->penumbra_radius + a->moon_semidiameter - a->shadow_distance) / (2.0 * a->moon_semidiameter);

    /* solar eclipse: the discs as the observer sees them (topocentric,
     * before refraction, which moves both alike) */
    const double *sun_h = a->sun.dir_geometric, *moon_h = a->moon.dir_geometric;
    double cr[3];
    cr[0] = sun_h[1] * moon_h[2] - sun_h[2] * moon_h[1];
    cr[1] = sun_h[2] * moon_h[0] - sun_h[0] * moon_h[2];
    cr[2] = sun_h[0] * moon_h[1] - sun_h[1] * moon_h[0];
    a->sun_moon_separation = atan2(sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]),
                                   sun_h[0] * moon_h[0] + sun_h[1] * moon_h[1] + sun_h[2] * moon_h[2]);
    a->sun_topo_semidiameter = atan(SUN_RADIUS_KM / a->sun.topo_distance_km);
    a->moon_topo_semidiameter = safe_asin(MOON_RADIUS_KM / a->moon.topo_distance_km);
    sky_solar_eclipse(a->sun_topo_semidiameter, a->moon_topo_semidiameter, a->sun_moon_separation,
                      &a->solar_obscuration, &a->solar_magnitude, &a->solar_flux_fraction);

    /* day-night fades (Mueller sec. 5) from the sun's up component */
    a->star_visibility = star_fade(a->sun.dir[1]);
    a->moon_visibility = moon_fade(a->sun.dir[1]);
    /* A deep solar eclipse darkens the sky like a sun 8 degrees below the
     * horizon (the zenith keeps some 3e-4 of its light, about 1 cd/m^2,
     * which the twilight sky has there): once the zenith keeps less than
     * 1 % of its light, the fades move toward their values at -8 degrees
     * (fully at 0.1 %, reached within a minute of totality), so the bright
     * stars come out. */
    double residual = a->solar_flux_fraction + (1.0 - a->solar_flux_fraction) * SKY_ECLIPSE_ZENITH_RESIDUAL;
    double dark = log10(fmax(residual, 1e-12));
    dark = astro_clamp((dark + 2.0) / -1.0, 0.0, 1.0);
    dark = dark * dark * (3.0 - 2.0 * dark);
    if (dark > 0.0) {
        double s8 = sin(-8.0 * DEG);
        a->star_visibility += dark * fmax(star_fade(s8) - a->star_visibility, 0.0);
        a->moon_visibility += dark * fmax(moon_fade(s8) - a->moon_visibility, 0.0);
    }

    /* stars: one precession-nutation matrix for the frame (Mueller eq. 7-8)
     * and the annual aberration as Earth's velocity over c (Meeus 23.2 in
     * vector form: circular term toward longitude sun - 90, plus the
     * eccentricity term), in the true equator of date */
    double pm[9], nm[9], r1[9], r2[9], r3[9];
    precession_matrix(t, pm);
    rot_x(eps0, r1);
    rot_z(-dpsi, r2);
    rot_x(-eps, r3);
    mat_mul(r2, r1, nm);
    mat_mul(r3, nm, nm);
    mat_mul(nm, pm, a->precession_nutation);
    const double kappa = 20.49552 * ARCSEC;
    double ecc = 0.016708634 - 0.000042037 * t - 0.0000001267 * t * t;
    double peri = (102.93735 + 1.71946 * t + 0.00046 * t * t) * DEG;
    double ab_ecl[3] = {kappa * (sin(true_lon) - ecc * sin(peri)), -kappa * (cos(true_lon) - ecc * cos(peri)), 0.0};
    double ecl_to_eq_m[9];
    rot_x(-eps, ecl_to_eq_m);
    mat_vec(ecl_to_eq_m, ab_ecl, a->aberration);
    return 0;
}

void sky_astro_star(const sky_astro *a, const sky_star *s, double *alt, double *alt_geometric, double *az,
                    double dir[3])
{
    /* proper motion, linear in ra/dec over the supported centuries */
    double yrs = a->years_since_j2000;
    double cd = cos(s->dec);
    double ra = s->ra + (cd > 1e-9 ? s->pm_ra / cd : 0.0) * 1e-3 * ARCSEC * yrs;
    double dec = s->dec + s->pm_dec * 1e-3 * ARCSEC * yrs;
    double v[3], h[3];
    spherical_to_vec(ra, dec, v);
    mat_vec(a->precession_nutation, v, v);
    for (int i = 0; i < 3; i++) v[i] += a->aberration[i];
    mat_vec(a->horizon, v, h);
    horizon_from_vector(h, a->pressure_factor, alt, alt_geometric, az, dir);
}

/* ---- planets -------------------------------------------------------------------------- */

#define LIGHT_DAYS_PER_AU 0.0057755183      /* Meeus 33.3 */
#define GAUSS_K2 (0.01720209895 * 0.01720209895) /* the sun's GM, au^3/day^2 */
#define DAYS_PER_MILLENNIUM 365250.0

typedef struct planet_data {
    const char *name;
    const sky_vsop_planet *series;
    double radius_km; /* equatorial (IAU WGCCRE 2015) */
    double bv;        /* B-V of the planet's integrated light, as Allen's
                         Astrophysical Quantities (4th ed., 2000) lists it */
} planet_data;

static const planet_data planet_data_table[SKY_ASTRO_PLANETS] = {
    {"mercury", &sky_vsop_mercury, 2440.53, 0.93}, {"venus", &sky_vsop_venus, 6051.8, 0.82},
    {"mars", &sky_vsop_mars, 3396.19, 1.36},       {"jupiter", &sky_vsop_jupiter, 71492.0, 0.83},
    {"saturn", &sky_vsop_saturn, 60268.0, 1.04},
};

void sky_astro_topocentric(const sky_astro *a, sky_astro_body *b) { body_place(a, a->observer_eq, b); }

double sky_astro_planet_bv(int planet)
{
    return planet_data_table[planet >= 0 && planet < SKY_ASTRO_PLANETS ? planet : 0].bv;
}

const char *sky_astro_planet_name(int planet)
{
    return planet >= 0 && planet < SKY_ASTRO_PLANETS ? planet_data_table[planet].name : NULL;
}

/* A VSOP87 coordinate and its rate (per millennium) at tau: the sum over
 * powers alpha of tau^alpha S_alpha, differentiated term by term. */
static void vsop_value_rate(const sky_vsop_series *series, int n, double tau, double *value, double *rate)
{
    double v = 0.0, r = 0.0, tp = 1.0, dtp = 0.0; /* tau^i and its derivative */
    for (int i = 0; i < n; i++) {
        double s = 0.0, ds = 0.0;
        for (int k = 0; k < series[i].count; k++) {
            const sky_vsop_term *term = &series[i].terms[k];
            double arg = term->b + term->c * tau;
            s += term->a * cos(arg);
            ds -= term->a * term->c * sin(arg);
        }
        v += s * tp;
        r += ds * tp + s * dtp;
        dtp = (i + 1) * tp;
        tp *= tau;
    }
    *value = v * 1e-8;
    *rate = r * 1e-8;
}

void sky_planet_state_at(int planet, double jd_tt, sky_planet_state *st)
{
    const sky_vsop_planet *p = planet_data_table[planet < 0 ? 0 : (planet >= SKY_ASTRO_PLANETS ? 0 : planet)].series;
    double tau = (jd_tt - J2000) / DAYS_PER_MILLENNIUM, lbr[3], rate[3];
    for (int c = 0; c < 3; c++) {
        vsop_value_rate(p->series[c], p->powers[c], tau, &lbr[c], &rate[c]);
        rate[c] /= DAYS_PER_MILLENNIUM;
    }
    double cl = cos(lbr[0]), sl = sin(lbr[0]), cb = cos(lbr[1]), sb = sin(lbr[1]), r = lbr[2];
    st->jd_tt = jd_tt;
    st->pos[0] = r * cb * cl;
    st->pos[1] = r * cb * sl;
    st->pos[2] = r * sb;
    st->vel[0] = rate[2] * cb * cl - r * sb * cl * rate[1] - r * cb * sl * rate[0];
    st->vel[1] = rate[2] * cb * sl - r * sb * sl * rate[1] + r * cb * cl * rate[0];
    st->vel[2] = rate[2] * sb + r * cb * rate[1];
}

/* Mars's brightness by season, Mallama (2007, Icarus 192, 404), table 8:
 * the correction every 10 degrees of the areocentric solar longitude Ls
 * from 0 to 360 (Mallama & Hilton 2018 add it to eq. 6-7). */
static const double mars_season[37] = {
    -0.029, -0.017, -0.014, -0.006, -0.018, -0.020, -0.014, -0.030, -0.008, -0.040, -0.024, -0.037, -0.036,
    -0.032, 0.010,  0.010,  -0.001, 0.044,  0.025,  -0.004, -0.016, -0.008, 0.029,  -0.054, -0.033, 0.055,
    0.017,  0.052,  0.006,  0.087,  0.006,  0.064,  0.030,  0.019,  -0.030, -0.017, -0.029};

double sky_astro_planet_magnitude(int planet, double r_au, double delta_au, double alpha, double ring_lat,
                                  double helio_lon)
{
    /* Mallama & Hilton 2018 ("Computing apparent planetary magnitudes for
     * The Astronomical Almanac", Astronomy and Computing 25, 10), the
     * geocentric forms by phase angle a in degrees: Mercury eq. 2, Venus
     * 3-4, Mars 6-7 with the season term (not the rotation term of Mallama
     * 2007, +-0.06, which needs the planet's central meridian), Jupiter
     * 8-9, Saturn 10 (globe and rings). */
    double a = astro_clamp(alpha / DEG, 0.0, 180.0), a2 = a * a, a3 = a2 * a, a4 = a3 * a, v;
    switch (planet) {
    case SKY_ASTRO_MERCURY:
        v = -0.613 + 6.3280e-02 * a - 1.6336e-03 * a2 + 3.3644e-05 * a3 - 3.4265e-07 * a4 + 1.6893e-09 * a4 * a -
            3.0334e-12 * a4 * a2;
        break;
    case SKY_ASTRO_VENUS:
        if (a < 163.7)
            v = -4.384 - 1.044e-03 * a + 3.687e-04 * a2 - 2.814e-06 * a3 + 8.938e-09 * a4;
        else
            v = 236.05828 - 2.81914 * a + 8.39034e-03 * a2;
        break;
    case SKY_ASTRO_MARS: {
        if (a <= 50.0)
            v = -1.601 + 2.267e-02 * a - 1.302e-04 * a2;
        else
            v = -0.367 - 0.02573 * a + 0.0003445 * a2;
        /* Ls from the heliocentric longitude (Mallama & Hilton: minus 85) */
        double ls = fmod(wrap_2pi(helio_lon) / DEG - 85.0 + 360.0, 360.0) / 10.0;
        int i = (int)ls;
        i = i < 0 ? 0 : (i > 35 ? 35 : i);
        v += mars_season[i] + (ls - i) * (mars_season[i + 1] - mars_season[i]);
        break;
    }
    case SKY_ASTRO_JUPITER:
        if (a <= 12.0)
            v = -9.395 - 3.7e-04 * a + 6.16e-04 * a2;
        else {
            double x = a / 180.0, x2 = x * x;
            double f = 1.0 - 1.507 * x - 0.363 * x2 - 0.062 * x2 * x + 2.809 * x2 * x2 - 1.876 * x2 * x2 * x;
            v = -9.428 - 2.5 * log10(fmax(f, 1e-6));
        }
        break;
    default: {
        /* from the Earth, a < 6.5 and the latitude < 27 degrees: eq. 10 holds */
        double sb = sin(astro_clamp(ring_lat, 0.0, 27.0 * DEG));
        v = -8.914 - 1.825 * sb + 0.026 * a - 0.378 * sb * exp(-2.25 * a);
    }
    }
    return v + 5.0 * log10(fmax(r_au * delta_au, 1e-12));
}

static double norm3(const double v[3]) { return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

/* Latitude over Saturn's rings of a direction (lambda, beta) seen from
 * Saturn's centre, ecliptic of date: Meeus 45.1-45.3 (the rings' plane
 * inclination i and node Omega, T in Julian centuries). */
static double saturn_ring_latitude(double t, double lambda, double beta)
{
    double i = (28.075216 - 0.012998 * t + 0.000004 * t * t) * DEG;
    double node = (169.508470 + 1.394681 * t + 0.000412 * t * t) * DEG;
    return safe_asin(sin(i) * cos(beta) * sin(lambda - node) - cos(i) * sin(beta));
}

void sky_astro_planet_place(const sky_astro *a, int planet, const sky_planet_state *st, sky_astro_planet *out)
{
    if (planet < 0 || planet >= SKY_ASTRO_PLANETS) planet = 0;
    const planet_data *pd = &planet_data_table[planet];
    const double *earth = a->earth_helio;
    /* The Taylor step: position, velocity and the sun's pull at the
     * state's instant (the planets' pulls on each other change the path by
     * far less within a day). */
    double r0 = fmax(norm3(st->pos), 1e-6), acc[3];
    for (int k = 0; k < 3; k++) acc[k] = -GAUSS_K2 * st->pos[k] / (r0 * r0 * r0);
    /* light time (Meeus 33): the planet where it was when the light left */
    double p[3], g[3], delta = 0.0, light = 0.0, dt0 = a->jd_tt - st->jd_tt;
    for (int iter = 0; iter < 3; iter++) {
        double dt = dt0 - light;
        for (int k = 0; k < 3; k++) {
            p[k] = st->pos[k] + st->vel[k] * dt + 0.5 * acc[k] * dt * dt;
            g[k] = p[k] - earth[k];
        }
        delta = fmax(norm3(g), 1e-9);
        light = LIGHT_DAYS_PER_AU * delta;
    }
    double t = (a->jd_tt - J2000) / 36525.0;
    double lambda = wrap_2pi(atan2(g[1], g[0])), beta = safe_asin(g[2] / delta);
    /* Saturn's rings: the Earth's and the sun's latitudes over them
     * (Meeus ch. 45 B and B'), before the corrections to the Earth's view */
    double ring_lat = 0.0;
    out->ring_tilt = 0.0;
    if (planet == SKY_ASTRO_SATURN) {
        double r = norm3(p);
        double b_earth = saturn_ring_latitude(t, lambda, beta);
        double b_sun = saturn_ring_latitude(t, atan2(p[1], p[0]), safe_asin(p[2] / r));
        out->ring_tilt = b_earth;
        /* eq. 10's latitude: the square root of the product, 0 when the
         * sun and the Earth are on opposite sides of the rings */
        ring_lat = b_earth * b_sun > 0.0 ? sqrt(b_earth * b_sun) : 0.0;
    }
    /* FK5 (Meeus 32.3), nutation, then annual aberration as a vector (as for
     * the stars): the light-time position is the planet's true place, and
     * only the Earth's motion is left to add */
    double lp = lambda - (1.397 * t + 0.00031 * t * t) * DEG;
    lambda += (-0.09033 + 0.03916 * (cos(lp) + sin(lp)) * tan(beta)) * ARCSEC + a->nutation_longitude;
    beta += 0.03916 * (cos(lp) - sin(lp)) * ARCSEC;
    double ra, dec, v[3];
    ecl_to_eq(lambda, beta, a->obliquity, &ra, &dec);
    spherical_to_vec(ra, dec, v);
    for (int k = 0; k < 3; k++) v[k] += a->aberration[k];
    vec_to_spherical(v, &out->body.ra, &out->body.dec);
    out->body.distance_km = delta * AU_KM;
    body_place(a, a->observer_eq, &out->body);

    double r = fmax(norm3(p), 1e-9), big_r = fmax(norm3(earth), 1e-9);
    out->distance_au = delta;
    out->sun_distance_au = r;
    out->phase_angle = acos(astro_clamp((r * r + delta * delta - big_r * big_r) / (2.0 * r * delta), -1.0, 1.0));
    out->illuminated = (1.0 + cos(out->phase_angle)) / 2.0;
    out->diameter = 2.0 * atan(pd->radius_km / out->body.distance_km);
    out->bv = pd->bv;
    out->vmag = sky_astro_planet_magnitude(planet, r, delta, out->phase_angle, ring_lat, atan2(p[1], p[0]));
}

/* This file's constants are its own (the amalgamation, one translation
 * unit, holds sky/observer.c's DEG after it). */
#undef PI
#undef TWO_PI
#undef DEG
#undef ARCSEC
#undef J2000
#undef EARTH_RADIUS_KM
