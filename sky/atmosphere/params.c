/*
 * Atmosphere descriptions (Elek 2009: a parametrisable atmosphere): the
 * presets and the check every consumer relies on.
 */
#include "atmosphere.h"
#include "spectrum.h"

#include <math.h>
#include <string.h>

/* The Earth's gases, common to its presets: Rayleigh exactly lambda^-4
 * through 680/550/440 nm, a vertical optical depth of 0.0973 at 550 nm
 * (Bucholtz 1995, US Standard Atmosphere 1976), over a 7.5 km scale
 * height: the e-folding of the air above the tropopause (26.2 % of the
 * mass lies above 10 km in the US Standard Atmosphere). Hillaire's 8 km
 * is the surface value and puts twice the real air at 40 km, which is
 * what twilight lights: civil twilight came out at twice Bond &
 * Henderson's 3.4 lx on every physical path and in the reference. Ozone
 * in a tent 25 +- 15 km (about 300 Dobson units). */
#define EARTH_GASES 6360.0f, 6460.0f, {5.552e-3f, 12.97e-3f, 31.67e-3f}, 7.5f
/* Hillaire 2020's gases: 8 km, 0.108 at 550 nm */
#define HILLAIRE_GASES 6360.0f, 6460.0f, {5.802e-3f, 13.558e-3f, 33.1e-3f}, 8.0f
#define EARTH_OZONE {0.650e-3f, 1.881e-3f, 0.085e-3f}, 25.0f, 15.0f
/* Mixed land in the visible, 0.2 (vegetation 0.05-0.15, dry grass and
 * bare soil 0.2-0.35); 0.3 is the planet's albedo with its clouds. */
#define EARTH_GROUND {0.2f, 0.2f, 0.2f}
/* Aerosol extinction at 680/550/440 nm, 1/km at sea level, for an
 * optical depth aod at 550 nm over an exponential layer of scale height h
 * km, falling with wavelength as Angstrom's lambda^-1.3 (continental
 * aerosol; Angstrom 1929, Holben et al. 2001's AERONET climatology), and
 * the scattered part for a single-scattering albedo ssa. */
#define AEROSOL(aod, h, ssa)                                                                       \
    {(ssa) * (aod) / (h) * 0.7590f, (ssa) * (aod) / (h), (ssa) * (aod) / (h) * 1.3366f},            \
        {(aod) / (h) * 0.7590f, (aod) / (h), (aod) / (h) * 1.3366f}, (h)

/* Clear Earth, the default: aerosol optical depth 0.085 at 550 nm
 * (real clear skies: 0.05-0.2, the global mean about 0.12), in a 1.5 km
 * layer, single-scattering albedo 0.9, asymmetry 0.65. Chosen against published
 * photometry (sky-bench's photometry section): the CIE clear skies'
 * shape, gensky's clear zenith, the IES illuminances. */
static const sky_atmosphere_params earth_preset = {
    EARTH_GASES, AEROSOL(0.085f, 1.5f, 0.9f), 0.65f, EARTH_OZONE, EARTH_GROUND,
};

/* Very clean air (high mountains, the open ocean): optical depth 0.04. */
static const sky_atmosphere_params very_clean = {
    EARTH_GASES, AEROSOL(0.04f, 1.2f, 0.95f), 0.7f, EARTH_OZONE, EARTH_GROUND,
};

/* Hazy: optical depth 0.3 in a deeper mixing layer (2 km), g 0.7. */
static const sky_atmosphere_params hazy = {
    EARTH_GASES, AEROSOL(0.3f, 2.0f, 0.9f), 0.7f, EARTH_OZONE, EARTH_GROUND,
};

/* Polluted (a city in summer smog): optical depth 0.6 in a 2 km layer of
 * absorbing particles (single-scattering albedo 0.85). */
static const sky_atmosphere_params polluted = {
    EARTH_GASES, AEROSOL(0.6f, 2.0f, 0.85f), 0.7f, EARTH_OZONE, EARTH_GROUND,
};

/* Hillaire 2020's reference constants, as his published implementation
 * sets them: aerosol optical depth 0.0053 (grey), g 0.8; for comparison
 * with other implementations of his paper. */
static const sky_atmosphere_params hillaire_2020 = {
    HILLAIRE_GASES, {3.996e-3f, 3.996e-3f, 3.996e-3f}, {4.40e-3f, 4.40e-3f, 4.40e-3f}, 1.2f, 0.8f, EARTH_OZONE,
    {0.3f, 0.3f, 0.3f},
};

/* Mars-like: a 3389.5 km planet. CO2 at 610 Pa and 210 K has 0.83 % of
 * Earth's sea-level number density and about 2.6 times air's Rayleigh
 * cross-section, so 2.2 % of Earth's Rayleigh coefficients. Dust of
 * visible optical depth 0.5 over an 11 km scale height (0.045/km, grey
 * extinction) that absorbs blue: single-scattering albedo 0.98, 0.90, 0.70
 * at 680, 550, 440 nm; g 0.7. No ozone; a reddish ground. */
static const sky_atmosphere_params mars = {
    3389.5f, 3509.5f,
    {0.125e-3f, 0.293e-3f, 0.715e-3f}, 11.1f,
    {44.1e-3f, 40.5e-3f, 31.5e-3f}, {45.0e-3f, 45.0e-3f, 45.0e-3f}, 11.0f, 0.7f,
    {0.0f, 0.0f, 0.0f}, 25.0f, 15.0f,
    {0.30f, 0.20f, 0.12f},
};

sky_result sky_atmosphere_get_preset(sky_atmosphere_preset preset, sky_atmosphere_params *out)
{
    if (!out) return SKY_ERR_INVALID_ARGUMENT;
    switch (preset) {
    case SKY_ATMOSPHERE_PRESET_EARTH: *out = earth_preset; return SKY_OK;
    case SKY_ATMOSPHERE_PRESET_HAZY: *out = hazy; return SKY_OK;
    case SKY_ATMOSPHERE_PRESET_MARS: *out = mars; return SKY_OK;
    case SKY_ATMOSPHERE_PRESET_VERY_CLEAN: *out = very_clean; return SKY_OK;
    case SKY_ATMOSPHERE_PRESET_POLLUTED: *out = polluted; return SKY_OK;
    case SKY_ATMOSPHERE_PRESET_HILLAIRE_2020: *out = hillaire_2020; return SKY_OK;
    }
    return SKY_ERR_INVALID_ARGUMENT;
}

int sky_atmosphere_is_zero(const sky_atmosphere_params *atm)
{
    static const sky_atmosphere_params zero;
    return memcmp(atm, &zero, sizeof zero) == 0;
}

static int bad_triple(const float v[3], double lo, double hi)
{
    for (int i = 0; i < 3; i++)
        if (!isfinite(v[i]) || v[i] < lo || v[i] > hi) return 1;
    return 0;
}

sky_result sky_atmosphere_check(const sky_atmosphere_params *a, char *err, size_t err_len)
{
    if (err && err_len) err[0] = '\0';
    if (!a) {
        sky_format(err, err_len, "atmosphere: params is NULL");
        return SKY_ERR_INVALID_ARGUMENT;
    }
    const char *bad = NULL;
    /* coefficients above 10/km would make the sea-level air opaque within
     * 100 m: no longer a sky, and past what the 8-bit LUT encoding holds */
    if (!isfinite(a->planet_radius_km) || a->planet_radius_km < 1.0f || a->planet_radius_km > 1e6f)
        bad = "planet_radius_km (1..1e6)";
    else if (!isfinite(a->top_radius_km) || a->top_radius_km < a->planet_radius_km + 1.0f ||
             a->top_radius_km > 2.0f * a->planet_radius_km)
        bad = "top_radius_km (planet + 1 km .. 2 x planet)";
    else if (bad_triple(a->rayleigh_scattering, 0.0, 10.0)) bad = "rayleigh_scattering (0..10 per km)";
    else if (bad_triple(a->mie_scattering, 0.0, 10.0)) bad = "mie_scattering (0..10 per km)";
    else if (bad_triple(a->mie_extinction, 0.0, 10.0)) bad = "mie_extinction (0..10 per km)";
    else if (bad_triple(a->ozone_absorption, 0.0, 10.0)) bad = "ozone_absorption (0..10 per km)";
    else if (bad_triple(a->ground_albedo, 0.0, 1.0)) bad = "ground_albedo (0..1)";
    else if (!isfinite(a->mie_g) || fabsf(a->mie_g) > 0.999f) bad = "mie_g (-0.999..0.999)";
    else if (!isfinite(a->rayleigh_scale_height_km) || a->rayleigh_scale_height_km < 0.01f ||
             !isfinite(a->mie_scale_height_km) || a->mie_scale_height_km < 0.01f)
        bad = "scale heights (>= 0.01 km)";
    else if (!isfinite(a->ozone_peak_km) || !isfinite(a->ozone_half_width_km) || a->ozone_half_width_km < 0.01f)
        bad = "ozone_peak_km / ozone_half_width_km (finite, half width >= 0.01 km)";
    for (int i = 0; !bad && i < 3; i++)
        if (a->mie_extinction[i] < a->mie_scattering[i]) bad = "mie_extinction (must be >= mie_scattering)";
    if (bad) {
        sky_format(err, err_len, "atmosphere: %s is out of range", bad);
        return SKY_ERR_INVALID_ARGUMENT;
    }
    return SKY_OK;
}

/* Turbidity (Linke 1922; Preetham, Shirley & Smits 1999, sec. 3): the
 * ratio of the atmosphere's vertical optical depth at 550 nm to that of
 * its molecules alone, so the aerosol's is (T - 1) times the molecules'.
 * The description keeps its aerosol's colour, albedo, asymmetry and
 * height; only the amount follows T. A description with no aerosol takes
 * the default Earth's. */
void sky_atmosphere_with_turbidity(const sky_atmosphere_params *in, double turbidity, sky_atmosphere_params *out)
{
    *out = *in;
    if (turbidity <= 0.0) return;
    double molecules = in->rayleigh_scattering[1] * in->rayleigh_scale_height_km;
    double target = (turbidity - 1.0) * molecules;
    double aod = in->mie_extinction[1] * in->mie_scale_height_km;
    if (aod <= 0.0) { /* nothing to scale: the clear Earth's aerosol */
        for (int c = 0; c < 3; c++) {
            out->mie_scattering[c] = earth_preset.mie_scattering[c];
            out->mie_extinction[c] = earth_preset.mie_extinction[c];
        }
        out->mie_scale_height_km = earth_preset.mie_scale_height_km;
        out->mie_g = earth_preset.mie_g;
        aod = earth_preset.mie_extinction[1] * earth_preset.mie_scale_height_km;
    }
    /* held within the description's limits: extinction <= 10/km */
    double k = target / aod, largest = fmax(out->mie_extinction[0], fmax(out->mie_extinction[1], out->mie_extinction[2]));
    if (k * largest > 10.0) k = 10.0 / largest;
    for (int c = 0; c < 3; c++) {
        out->mie_scattering[c] = (float)(out->mie_scattering[c] * k);
        out->mie_extinction[c] = (float)(out->mie_extinction[c] * k);
    }
}

double sky_atmosphere_turbidity(const sky_atmosphere_params *a)
{
    double molecules = a->rayleigh_scattering[1] * a->rayleigh_scale_height_km;
    return molecules > 0.0 ? 1.0 + a->mie_extinction[1] * a->mie_scale_height_km / molecules : 1.0;
}

void sky_atmosphere_effective(const sky_atmosphere_params *in, sky_atmosphere_params *out)
{
    /* The description gives coefficients at 680/550/440 nm; the reference
     * renders the spectrum through them (spectrum.c's interpolation). A
     * channel's coefficient is that spectrum's mean over the channel's
     * share of sunlight, rgb_c(E beta) / rgb_c(E): thin air then takes as
     * much out of the sun's channel c as it does out of the whole spectrum.
     * Each component keeps its own spectrum: the molecules' red is
     * weighted toward 640 nm, and ozone's red takes in the Chappuis band
     * around 600 nm (three times its 680 nm value), which is what
     * reddens and dims the light that grazes the ozone layer at sunrise.
     * One shared wavelength per channel (the lambda^-4 one, 642/548/442
     * nm) left ozone's red at a third (what the bands gained against the
     * spectral reference: docs/validation.md). */
    double e[SKY_SPECTRUM_SAMPLES], spectra[4][SKY_SPECTRUM_SAMPLES], xyz[3], sun[3], band[4][3];
    for (int i = 0; i < SKY_SPECTRUM_SAMPLES; i++) {
        double l = sky_spectrum_wavelength_nm(i), r, ms, me, oz;
        e[i] = sky_spectrum_solar_irradiance(l);
        sky_spectrum_coefficients(in, l, &r, &ms, &me, &oz);
        spectra[0][i] = e[i] * r;
        spectra[1][i] = e[i] * ms;
        spectra[2][i] = e[i] * me;
        spectra[3][i] = e[i] * oz;
    }
    sky_sun_irradiance_rgb(sun); /* the same sun, its sRGB channels */
    for (int k = 0; k < 4; k++) {
        sky_spectrum_to_xyz(spectra[k], xyz);
        sky_xyz_to_linear_srgb(xyz, band[k]);
    }
    *out = *in;
    for (int c = 0; c < 3; c++) {
        /* sRGB's colour matching has negative lobes: a channel's mean may
         * leave the spectrum's range, so it is held within the
         * description's own limits (0..10/km, extinction >= scattering)
         * and every valid description stays valid here */
        double ms = sky_clampd(band[1][c] / sun[c], 0.0, 10.0);
        out->rayleigh_scattering[c] = (float)sky_clampd(band[0][c] / sun[c], 0.0, 10.0);
        out->mie_scattering[c] = (float)ms;
        out->mie_extinction[c] = (float)sky_clampd(fmax(band[2][c] / sun[c], ms), 0.0, 10.0);
        out->ozone_absorption[c] = (float)sky_clampd(band[3][c] / sun[c], 0.0, 10.0);
    }
}
