/*
 * The physical paths against published photometry: see photometry.h.
 */
#include "photometry.h"

#include "astro.h"
#include "atmo_error.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)

const double sky_phot_shape_suns[SKY_PHOT_SHAPES] = {10.0, 30.0, 50.0, 70.0};

/* ISO 15469:2004 / CIE S 011/E:2003, table 1: the gradation (a, b) and
 * indicatrix (c, d, e) parameters of the three clear-sky types. */
static const double cie_params[3][5] = {
    {-1.0, -0.55, 10.0, -3.0, 0.45}, /* 11: white-blue sky, distinct solar corona */
    {-1.0, -0.32, 10.0, -3.0, 0.45}, /* 12: CIE standard clear sky, low turbidity */
    {-1.0, -0.32, 16.0, -3.0, 0.30}, /* 13: CIE standard clear sky, polluted      */
};

double sky_cie_ratio(int type, double z_rad, double chi_rad, double zs_rad)
{
    const double *p = cie_params[type < 11 ? 0 : type > 13 ? 2 : type - 11];
    double a = p[0], b = p[1], c = p[2], d = p[3], e = p[4];
    /* gradation: phi(90 deg) = 1, cos Z -> 0+ makes exp(b / cos Z) -> 0 */
    double cz = cos(z_rad);
    double gradation = cz > 1e-6 ? 1.0 + a * exp(b / cz) : 1.0;
    double gradation_zenith = 1.0 + a * exp(b);
    double indicatrix = 1.0 + c * (exp(d * chi_rad) - exp(d * PI / 2.0)) + e * cos(chi_rad) * cos(chi_rad);
    double indicatrix_zenith = 1.0 + c * (exp(d * zs_rad) - exp(d * PI / 2.0)) + e * cos(zs_rad) * cos(zs_rad);
    return indicatrix * gradation / (indicatrix_zenith * gradation_zenith);
}

/* Radiance's gensky, clear sky: Karayel, Navvab, Ne'eman and Selkowitz
 * (1984), zenith luminance (1.376 T - 1.81) tan(altitude) + 0.38 kcd/m^2. */
double sky_gensky_zenith_kcd(double turbidity, double sun_alt_deg)
{
    return (1.376 * turbidity - 1.81) * tan(sun_alt_deg * DEG) + 0.38;
}

/* IES Lighting Handbook, clear sky: diffuse horizontal 0.8 + 15.5
 * sqrt(sin altitude) klx; direct normal A exp(-B / sin altitude) with
 * A = 127.5 klx and B = 0.21 (the clear-sky extinction). */
double sky_ies_diffuse_klx(double sun_alt_deg) { return 0.8 + 15.5 * sqrt(sin(sun_alt_deg * DEG)); }
double sky_ies_direct_normal_klx(double sun_alt_deg) { return 127.5 * exp(-0.21 / sin(sun_alt_deg * DEG)); }

/* m = -2.5 log10(L / 10.8e4 cd/m^2) */
double sky_mag_arcsec2(double kcd) { return -2.5 * log10(fmax(kcd * 1000.0, 1e-30) / 1.08e5); }

static double luminance(const double rgb[3]) { return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]; }

static void direction(double elevation_deg, double azimuth_deg, double d[3])
{
    sky_horizon_vector(elevation_deg * DEG, azimuth_deg * DEG, d);
}

static double angle_between(const double a[3], const double b[3])
{
    double c = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    return acos(c > 1.0 ? 1.0 : c < -1.0 ? -1.0 : c);
}

/* The direction chi_deg from the sun (elevation, azimuth), turned
 * around_deg about it from the sun's vertical. */
static void ring_point(double sun_el, double sun_az, double chi_deg, double around_deg, double d[3])
{
    double sun[3], up[3], side[3];
    direction(sun_el, sun_az, sun);
    direction(sun_el + 90.0, sun_az, up); /* in the sun's vertical, 90 degrees above it */
    side[0] = sun[1] * up[2] - sun[2] * up[1];
    side[1] = sun[2] * up[0] - sun[0] * up[2];
    side[2] = sun[0] * up[1] - sun[1] * up[0];
    double c = cos(chi_deg * DEG), s = sin(chi_deg * DEG), ca = cos(around_deg * DEG), sa = sin(around_deg * DEG);
    for (int i = 0; i < 3; i++) d[i] = c * sun[i] + s * (ca * up[i] + sa * side[i]);
}

void sky_photometry_published(sky_photometry *out)
{
    memset(out, 0, sizeof *out);
    for (int i = 0; i < SKY_PHOT_SHAPES; i++) out->cie_type[i] = 12;
    /* the CIE clear sky (type 12) over the same bands as the measurement */
    double sun70[3], d[3];
    direction(70.0, 0.0, sun70);
    double glow = 0.0, horizon = 0.0;
    int n = 0;
    for (double chi = 5.25; chi < 8.0; chi += 0.5)
        for (double around = 0.0; around < 360.0; around += 15.0, n++) {
            ring_point(30.0, 0.0, chi, around, d);
            glow += sky_cie_ratio(12, acos(d[1]), chi * DEG, 60.0 * DEG);
        }
    out->glow_ratio_30 = glow / n;
    n = 0;
    for (double z = 80.25; z < 85.0; z += 0.5)
        for (double da = -15.0; da <= 15.0; da += 5.0, n++) {
            direction(90.0 - z, 180.0 + da, d);
            horizon += sky_cie_ratio(12, z * DEG, angle_between(d, sun70), 20.0 * DEG);
        }
    out->horizon_ratio_70 = horizon / n;
    out->zenith_kcd_70 = sky_gensky_zenith_kcd(2.75, 70.0);
    out->diffuse_klx_30 = sky_ies_diffuse_klx(30.0);
    out->direct_klx_10 = sky_ies_direct_normal_klx(10.0);
    out->civil_lx = 3.4;          /* Bond & Henderson (1963), sun -6 deg  */
    out->nautical_lx = 0.008;     /* the same, sun -12 deg                */
    out->night_zenith_mag = 21.8; /* Garstang (1989), Benn & Ellison (1998): 21.5-22 */
}

static double read_luminance(const sky_atmo_hemisphere *h, double elevation_deg, double azimuth_deg)
{
    double d[3], rgb[3];
    direction(elevation_deg, azimuth_deg, d);
    sky_atmo_hemisphere_read(h, d, rgb);
    return luminance(rgb);
}

/* Sky illuminance on a horizontal surface, klx: L cos(z) over the upper
 * hemisphere in 1 x 2 degree cells (the discs are not drawn). */
static double horizontal_klx(const sky_atmo_hemisphere *h)
{
    double sum = 0.0, dz = 1.0 * DEG, da = 2.0 * DEG;
    for (int i = 0; i < 90; i++) {
        double z = (i + 0.5) * dz;
        for (int j = 0; j < 180; j++) sum += read_luminance(h, 90.0 - z / DEG, (j + 0.5) * 2.0) * cos(z) * sin(z);
    }
    return sum * dz * da;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* Median over an equal-area grid (zenith angle < 75 deg, more than 12 deg
 * from the sun) of |(L/Lz) / CIE - 1|, for the closest type. */
static double cie_shape(const sky_atmo_hemisphere *h, double sun_el, double sun_az, int *type)
{
    enum { RINGS = 40, AZIMUTHS = 72 };
    double dev[3][RINGS * AZIMUTHS];
    double sun[3], lz = read_luminance(h, 90.0, 0.0), zs = (90.0 - sun_el) * DEG;
    direction(sun_el, sun_az, sun);
    int n = 0;
    double u0 = cos(75.0 * DEG);
    for (int i = 0; i < RINGS; i++) {
        double u = u0 + (i + 0.5) * (1.0 - u0) / RINGS, el = 90.0 - acos(u) / DEG;
        for (int j = 0; j < AZIMUTHS; j++) {
            double az = (j + 0.5) * 360.0 / AZIMUTHS, d[3];
            direction(el, az, d);
            double chi = angle_between(d, sun);
            if (chi < 12.0 * DEG) continue;
            double ratio = read_luminance(h, el, az) / fmax(lz, 1e-30);
            for (int t = 0; t < 3; t++) dev[t][n] = fabs(ratio / sky_cie_ratio(11 + t, acos(u), chi, zs) - 1.0);
            n++;
        }
    }
    double best = 1e30;
    for (int t = 0; t < 3; t++) {
        qsort(dev[t], (size_t)n, sizeof(double), cmp_double);
        double median = n % 2 ? dev[t][n / 2] : 0.5 * (dev[t][n / 2 - 1] + dev[t][n / 2]);
        if (median < best) best = median, *type = 11 + t;
    }
    return best;
}

sky_config sky_photometry_config(sky_atmosphere_path path)
{
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.gl_profile = SKY_GL_CORE33;
    cfg.atmosphere = path;
    /* the night's own light: the night zenith is measured with it */
    cfg.features = SKY_AIRGLOW | SKY_ZODIACAL;
    return cfg;
}

int sky_photometry_measure(const sky_config *cfg, sky_photometry *out, char *err, size_t err_len)
{
    memset(out, 0, sizeof *out);
    sky_atmo_hemisphere *h = sky_atmo_hemisphere_create(cfg, err, err_len);
    if (!h) return -1;
    double el, az;
    int rc = 0;
    for (int i = 0; i < SKY_PHOT_SHAPES && !rc; i++) {
        rc = sky_atmo_hemisphere_render(h, sky_phot_shape_suns[i], &el, &az, err, err_len);
        if (rc) break;
        out->cie_median[i] = cie_shape(h, el, az, &out->cie_type[i]);
        double lz = read_luminance(h, 90.0, 0.0);
        if (sky_phot_shape_suns[i] == 30.0) {
            /* the ring 5-8 degrees around the sun */
            double glow = 0.0, d[3], rgb[3];
            int n = 0;
            for (double chi = 5.25; chi < 8.0; chi += 0.5)
                for (double around = 0.0; around < 360.0; around += 15.0, n++) {
                    ring_point(el, az, chi, around, d);
                    sky_atmo_hemisphere_read(h, d, rgb);
                    glow += luminance(rgb);
                }
            out->glow_ratio_30 = glow / n / fmax(lz, 1e-30);
            out->diffuse_klx_30 = horizontal_klx(h);
        } else if (sky_phot_shape_suns[i] == 70.0) {
            double horizon = 0.0;
            int n = 0;
            for (double z = 80.25; z < 85.0; z += 0.5)
                for (double da = -15.0; da <= 15.0; da += 5.0, n++) horizon += read_luminance(h, 90.0 - z, az + 180.0 + da);
            out->horizon_ratio_70 = horizon / n / fmax(lz, 1e-30);
            out->zenith_kcd_70 = lz;
        } else if (sky_phot_shape_suns[i] == 10.0) {
            sky_lighting l;
            sky_get_lighting(sky_atmo_hemisphere_sky(h), &l);
            double sun[3] = {l.sun_color[0], l.sun_color[1], l.sun_color[2]};
            out->direct_klx_10 = luminance(sun);
        }
    }
    if (!rc) rc = sky_atmo_hemisphere_render(h, -6.0, &el, &az, err, err_len);
    if (!rc) out->civil_lx = 1000.0 * horizontal_klx(h);
    if (!rc) rc = sky_atmo_hemisphere_render(h, -12.0, &el, &az, err, err_len);
    if (!rc) out->nautical_lx = 1000.0 * horizontal_klx(h);
    if (!rc) rc = sky_atmo_hemisphere_render(h, -30.0, &el, &az, err, err_len);
    if (!rc) out->night_zenith_mag = sky_mag_arcsec2(read_luminance(h, 90.0, 0.0));
    sky_atmo_hemisphere_destroy(h);
    return rc;
}

int sky_photometry_sky_lux(const sky_config *cfg, const double *alts, int n, double *lux, char *err, size_t err_len)
{
    sky_atmo_hemisphere *h = sky_atmo_hemisphere_create(cfg, err, err_len);
    if (!h) return -1;
    int rc = 0;
    for (int i = 0; i < n && !rc; i++) {
        double el, az;
        rc = sky_atmo_hemisphere_render(h, alts[i], &el, &az, err, err_len);
        if (!rc) lux[i] = 1000.0 * horizontal_klx(h);
    }
    sky_atmo_hemisphere_destroy(h);
    return rc;
}
