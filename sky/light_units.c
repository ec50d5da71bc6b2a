/*
 * Light units and colour shared by the rooms (light_units.h).
 */
#include "light_units.h"

double sky_kcd_to_mag_arcsec2(double kcd)
{
    return -2.5 * log10(kcd > 1e-30 ? kcd * SKY_ARCSEC2_SR / SKY_V0_ILLUMINANCE_KLX : 1e-30);
}

static double clampd(double x, double lo, double hi) { return x < lo ? lo : (x > hi ? hi : x); }

/* B-V to linear sRGB of unit luminance: temperature after Ballesteros
 * (2012), the Planckian locus fit of Kim et al. (2002) for its
 * chromaticity, then XYZ to linear sRGB (IEC 61966-2-1). */
void sky_star_color(double bv, float rgb[3])
{
    bv = clampd(bv, -0.4, 2.5);
    double t = 4600.0 * (1.0 / (0.92 * bv + 1.7) + 1.0 / (0.92 * bv + 0.62));
    t = clampd(t, 1667.0, 25000.0);
    double t1 = 1e3 / t, t2 = t1 * t1, t3 = t2 * t1, x, y;
    if (t <= 4000.0)
        x = -0.2661239 * t3 - 0.2343589 * t2 + 0.8776956 * t1 + 0.179910;
    else
        x = -3.0258469 * t3 + 2.1070379 * t2 + 0.2226347 * t1 + 0.240390;
    double x2 = x * x, x3 = x2 * x;
    if (t <= 2222.0)
        y = -1.1063814 * x3 - 1.34811020 * x2 + 2.18555832 * x - 0.20219683;
    else if (t <= 4000.0)
        y = -0.9549476 * x3 - 1.37418593 * x2 + 2.09137015 * x - 0.16748867;
    else
        y = 3.0817580 * x3 - 5.87338670 * x2 + 3.75112997 * x - 0.37001483;
    const double xyz[3] = {x / y, 1.0, (1.0 - x - y) / y};
    double lin[3];
    sky_xyz_to_linear_srgb(xyz, lin);
    double r = lin[0] > 0 ? lin[0] : 0, g = lin[1] > 0 ? lin[1] : 0, b = lin[2] > 0 ? lin[2] : 0;
    /* the clamp can change the luminance; set it back to 1 */
    double lum = 0.2126 * r + 0.7152 * g + 0.0722 * b;
    rgb[0] = (float)(r / lum), rgb[1] = (float)(g / lum), rgb[2] = (float)(b / lum);
}

void sky_xyz_to_linear_srgb(const double xyz[3], double rgb[3])
{
    rgb[0] = 3.2406 * xyz[0] - 1.5372 * xyz[1] - 0.4986 * xyz[2];
    rgb[1] = -0.9689 * xyz[0] + 1.8758 * xyz[1] + 0.0415 * xyz[2];
    rgb[2] = 0.0557 * xyz[0] - 0.2040 * xyz[1] + 1.0570 * xyz[2];
}
