/*
 * Spectra shared by the library and its atmosphere reference (spectrum.h).
 * They began in reference.c; the library needs them (its sun's colour and
 * the wavelengths it renders at), the rest of the reference it does not.
 */
#include "spectrum.h"
#include "atmosphere.h"

#include <math.h>

/* ---- samples ------------------------------------------------------------------ */

double sky_spectrum_wavelength_nm(int i)
{
    if (i < 0) i = 0;
    if (i >= SKY_SPECTRUM_SAMPLES) i = SKY_SPECTRUM_SAMPLES - 1;
    return 400.0 + SKY_SPECTRUM_STEP_NM * i;
}

/* ---- the atmosphere description at any wavelength -------------------------------- */

/* When all three are positive, ln(value) is the quadratic in ln(lambda)
 * through them: a power law (Rayleigh's lambda^-4, an Angstrom exponent)
 * comes out exactly, and a curved log-log spectrum smoothly. With a zero
 * among them a logarithm does not exist: piecewise linear in lambda,
 * constant outside 440..680 nm. */
double sky_spectrum_interpolate(const float v[3], double lambda)
{
    static const double node[3] = {680.0, 550.0, 440.0};
    if (v[0] > 0.0f && v[1] > 0.0f && v[2] > 0.0f) {
        double x = log(lambda), acc = 0.0;
        for (int i = 0; i < 3; i++) {
            double li = 1.0, xi = log(node[i]);
            for (int j = 0; j < 3; j++)
                if (j != i) li *= (x - log(node[j])) / (xi - log(node[j]));
            acc += li * log((double)v[i]);
        }
        return exp(acc);
    }
    double r;
    if (lambda <= 440.0) r = v[2];
    else if (lambda >= 680.0) r = v[0];
    else if (lambda <= 550.0) r = v[2] + (v[1] - v[2]) * (lambda - 440.0) / 110.0;
    else r = v[1] + (v[0] - v[1]) * (lambda - 550.0) / 130.0;
    return r > 0.0 ? r : 0.0;
}

void sky_spectrum_coefficients(const sky_atmosphere_params *atm, double lambda_nm, double *rayleigh_scattering,
                               double *mie_scattering, double *mie_extinction, double *ozone_absorption)
{
    sky_atmosphere_params earth;
    if (!atm || sky_atmosphere_is_zero(atm)) {
        sky_atmosphere_get_preset(SKY_ATMOSPHERE_PRESET_EARTH, &earth);
        atm = &earth;
    }
    double ms = sky_spectrum_interpolate(atm->mie_scattering, lambda_nm);
    double me = sky_spectrum_interpolate(atm->mie_extinction, lambda_nm);
    /* the two Mie curves are interpolated separately; extinction below
     * scattering would mean negative absorption */
    if (me < ms) me = ms;
    if (rayleigh_scattering) *rayleigh_scattering = sky_spectrum_interpolate(atm->rayleigh_scattering, lambda_nm);
    if (mie_scattering) *mie_scattering = ms;
    if (mie_extinction) *mie_extinction = me;
    if (ozone_absorption) *ozone_absorption = sky_spectrum_interpolate(atm->ozone_absorption, lambda_nm);
}

/* ---- the sun ----------------------------------------------------------------------- */

/* The sun as a 5778 K blackbody (its effective temperature) scaled so
 * that its total over all wavelengths is the total solar irradiance,
 * 1361 W/m^2 (Kopp & Lean 2011): E(lambda) = 1361 pi B(lambda, T) /
 * (sigma T^4), since pi * integral of Planck's B over lambda = sigma T^4
 * (Stefan-Boltzmann). It lies within a few per cent of the measured
 * spectrum across the visible range, without its Fraunhofer lines. */
double sky_spectrum_solar_irradiance(double lambda_nm)
{
    const double h = 6.62607015e-34, c = 2.99792458e8, k = 1.380649e-23, sigma = 5.670374419e-8;
    const double T = 5778.0, tsi = 1361.0;
    if (!(lambda_nm > 0.0) || !isfinite(lambda_nm)) return 0.0;
    double l = lambda_nm * 1e-9;
    double x = h * c / (l * k * T);
    double b = 2.0 * h * c * c / (l * l * l * l * l) / expm1(x); /* W m^-2 sr^-1 m^-1 */
    return tsi * SKY_PI * b * 1e-9 / (sigma * T * T * T * T);    /* W m^-2 nm^-1      */
}

/* ---- colour ------------------------------------------------------------------------- */

/* CIE 1931 2-degree colour matching functions: the multi-lobe piecewise
 * Gaussian fit of Wyman, Sloan & Shirley 2013, "Simple Analytic
 * Approximations to the CIE XYZ Color Matching Functions", JCGT 2(2),
 * eq. 2 (each lobe has one width left of its peak and another right). */
static double lobe(double x, double mu, double s_left, double s_right)
{
    double t = (x - mu) / (x < mu ? s_left : s_right);
    return exp(-0.5 * t * t);
}

void sky_spectrum_cmf(double l, double out[3])
{
    out[0] = 1.056 * lobe(l, 599.8, 37.9, 31.0) + 0.362 * lobe(l, 442.0, 16.0, 26.7) -
             0.065 * lobe(l, 501.1, 20.4, 26.2);
    out[1] = 0.821 * lobe(l, 568.8, 46.9, 40.5) + 0.286 * lobe(l, 530.9, 16.3, 31.1);
    out[2] = 1.217 * lobe(l, 437.0, 11.8, 36.0) + 0.681 * lobe(l, 459.0, 26.0, 13.8);
}

/* 20 nm rectangle rule, 683 lm/W, /1000 so that radiance gives kcd/m^2
 * and irradiance klx. The sky and the sun go through the same sum, so
 * their white balance agrees. */
void sky_spectrum_to_xyz(const double s[SKY_SPECTRUM_SAMPLES], double xyz[3])
{
    xyz[0] = xyz[1] = xyz[2] = 0.0;
    for (int i = 0; i < SKY_SPECTRUM_SAMPLES; i++) {
        double c[3];
        sky_spectrum_cmf(sky_spectrum_wavelength_nm(i), c);
        for (int k = 0; k < 3; k++) xyz[k] += s[i] * c[k];
    }
    for (int k = 0; k < 3; k++) xyz[k] *= SKY_SPECTRUM_LM_PER_W * SKY_SPECTRUM_STEP_NM / 1000.0;
}

void sky_spectrum_xyz_to_linear_srgb(const double xyz[3], double rgb[3])
{
    sky_xyz_to_linear_srgb(xyz, rgb);
}

void sky_spectrum_sun_xyz(double xyz[3])
{
    double e[SKY_SPECTRUM_SAMPLES];
    if (!xyz) return;
    for (int i = 0; i < SKY_SPECTRUM_SAMPLES; i++) e[i] = sky_spectrum_solar_irradiance(sky_spectrum_wavelength_nm(i));
    sky_spectrum_to_xyz(e, xyz);
}

void sky_sun_irradiance_rgb(double rgb[3])
{
    /* the reference's sun: a 5778 K blackbody of 1361 W/m^2 through the
     * same colour matching functions (125 klx) */
    double xyz[3];
    sky_spectrum_sun_xyz(xyz);
    sky_xyz_to_linear_srgb(xyz, rgb);
}
