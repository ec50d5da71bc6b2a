/*
 * The photometry yardstick (tools/photometry.c): its published figures
 * come out of the formulas they are published as, and its measurement
 * reads a sky the way the formulas describe one. The paths' own figures
 * against their targets are held by the tests of the issue that meets
 * them.
 */
#include "test.h"

#include "photometry.h"

#include <math.h>
#include <string.h>

#define PI 3.14159265358979323846

TEST(photometry_published_formulas)
{
    sky_photometry pub;
    sky_photometry_published(&pub);
    /* the figures the issue quotes from the CIE, gensky and IES */
    CHECK(fabs(pub.glow_ratio_30 - 10.2) < 0.05, "CIE 12 glow 5-8 deg around a sun at 30 deg: %.3f (10.2)",
          pub.glow_ratio_30);
    CHECK(fabs(pub.horizon_ratio_70 - 0.68) < 0.01, "CIE 12 horizon opposite a sun at 70 deg: %.3f (0.68)",
          pub.horizon_ratio_70);
    CHECK(fabs(pub.zenith_kcd_70 - 5.8) < 0.05, "gensky's clear zenith, T 2.75, sun 70 deg: %.3f kcd/m^2 (5.8)",
          pub.zenith_kcd_70);
    CHECK(fabs(pub.diffuse_klx_30 - 11.8) < 0.05, "IES diffuse horizontal, sun 30 deg: %.3f klx (11.8)",
          pub.diffuse_klx_30);
    CHECK(fabs(pub.direct_klx_10 - 38.0) < 0.5, "IES direct normal, sun 10 deg: %.2f klx (38)", pub.direct_klx_10);
    /* 1 cd/m^2 is 12.58 mag/arcsec^2; ten times brighter is 2.5 less */
    CHECK(fabs(sky_mag_arcsec2(1e-3) - 12.58) < 0.01 && fabs(sky_mag_arcsec2(1e-2) - 10.08) < 0.01,
          "mag/arcsec^2 of 1 and 10 cd/m^2: %.3f, %.3f", sky_mag_arcsec2(1e-3), sky_mag_arcsec2(1e-2));
    /* every CIE type is 1 at the zenith, brightest toward the sun, and its
     * clear types darken from the zenith to 75 degrees opposite a high sun */
    for (int t = 11; t <= 13; t++) {
        double zs = 40.0 * PI / 180.0;
        CHECK(fabs(sky_cie_ratio(t, 0.0, zs, zs) - 1.0) < 1e-12, "type %d: L/Lz at the zenith %.6f", t,
              sky_cie_ratio(t, 0.0, zs, zs));
        CHECK(sky_cie_ratio(t, zs, 0.1, zs) > 3.0 * sky_cie_ratio(t, zs, PI / 2.0, zs),
              "type %d: brighter 6 degrees from the sun than 90 degrees away", t);
    }
}

/* Every path measured: finite, positive, and in the ranges that any sky
 * lit by a sun must be in (a closest CIE type among 11-13; brighter glow
 * than zenith; twilight darker at -12 than at -6). */
TEST(photometry_measures_every_path)
{
    static const sky_atmosphere_path paths[5] = {SKY_ATMOSPHERE_GRADIENT, SKY_ATMOSPHERE_PREETHAM,
                                                 SKY_ATMOSPHERE_RAYLEIGH, SKY_ATMOSPHERE_HILLAIRE,
                                                 SKY_ATMOSPHERE_BLEND};
    for (int p = 0; p < 5; p++) {
        sky_config cfg = sky_photometry_config(paths[p]);
        sky_photometry m;
        char err[256] = "";
        int rc = sky_photometry_measure(&cfg, &m, err, sizeof err);
        CHECK(rc == 0, "path %d measured: %s", (int)paths[p], err);
        if (rc) continue;
        for (int i = 0; i < SKY_PHOT_SHAPES; i++)
            CHECK(isfinite(m.cie_median[i]) && m.cie_median[i] >= 0.0 && m.cie_type[i] >= 11 && m.cie_type[i] <= 13,
                  "path %d, sun %.0f: shape deviation %.3f against type %d", (int)paths[p], sky_phot_shape_suns[i],
                  m.cie_median[i], m.cie_type[i]);
        CHECK(m.glow_ratio_30 > 1.0 && m.zenith_kcd_70 > 0.0 && m.diffuse_klx_30 > 0.0 && m.direct_klx_10 > 0.0,
              "path %d: glow %.2f, zenith %.3f kcd/m^2, diffuse %.2f klx, direct %.1f klx", (int)paths[p],
              m.glow_ratio_30, m.zenith_kcd_70, m.diffuse_klx_30, m.direct_klx_10);
        CHECK(m.civil_lx > m.nautical_lx && m.nautical_lx > 0.0 && isfinite(m.night_zenith_mag),
              "path %d: %.4g lx at -6, %.4g lx at -12, night zenith %.2f mag/arcsec^2", (int)paths[p], m.civil_lx,
              m.nautical_lx, m.night_zenith_mag);
    }
}

/* Issue Real skies: Preetham's twilight follows the measured one. Its sky
 * illuminance on a horizontal surface within x3 of Bond & Henderson's
 * 3.4 lx at -6 degrees and 0.008 lx at -12 (the fit's own horizon sky,
 * faded a decade per 3 degrees, gave 102 and 0.98 lx); the night
 * (sun -30) at the night floor, a dark site's 21.5-22.3 mag/arcsec^2; and
 * the daytime shape against the CIE clear skies no worse than before the
 * change (5 / 6 / 15 / 30 %, held at 10 / 10 / 20 / 35 %): the twilight
 * scale is one factor per frame, which leaves L/Lz alone. */
TEST(photometry_preetham_twilight)
{
    sky_config cfg = sky_photometry_config(SKY_ATMOSPHERE_PREETHAM);
    sky_photometry m, pub;
    char err[256] = "";
    int rc = sky_photometry_measure(&cfg, &m, err, sizeof err);
    CHECK(rc == 0, "preetham measured: %s", err);
    if (rc) return;
    sky_photometry_published(&pub);
    NOTE("preetham: %.3g lx at -6 (%.3g), %.3g lx at -12 (%.3g), night zenith %.2f mag/arcsec^2", m.civil_lx,
         pub.civil_lx, m.nautical_lx, pub.nautical_lx, m.night_zenith_mag);
    CHECK(m.civil_lx > pub.civil_lx / 3.0 && m.civil_lx < pub.civil_lx * 3.0,
          "preetham civil twilight (sun -6): %.3g lx, published %.3g (within x3)", m.civil_lx, pub.civil_lx);
    CHECK(m.nautical_lx > pub.nautical_lx / 3.0 && m.nautical_lx < pub.nautical_lx * 3.0,
          "preetham nautical twilight (sun -12): %.3g lx, published %.3g (within x3)", m.nautical_lx, pub.nautical_lx);
    CHECK(m.night_zenith_mag >= 21.5 && m.night_zenith_mag <= 22.3,
          "preetham night zenith (sun -30): %.2f mag/arcsec^2 (21.5-22.3)", m.night_zenith_mag);
    static const double shape_limit[SKY_PHOT_SHAPES] = {0.10, 0.10, 0.20, 0.35};
    for (int i = 0; i < SKY_PHOT_SHAPES; i++)
        CHECK(m.cie_median[i] <= shape_limit[i], "preetham, sun %.0f deg: shape %.1f %% from CIE type %d (<= %.0f %%)",
              sky_phot_shape_suns[i], 100.0 * m.cie_median[i], m.cie_type[i], 100.0 * shape_limit[i]);
}

/* Issue Real skies' targets for HILLAIRE and BLEND with the default
 * Earth: the CIE clear-sky shape within 20 % at sun 10-70 deg; gensky's
 * clear zenith and the IES diffuse illuminance within 25 %; civil and
 * nautical twilight within x2 of Bond & Henderson; the night zenith
 * 21.5-22.3 mag/arcsec^2. */
TEST(photometry_physical_paths_targets)
{
    static const sky_atmosphere_path paths[2] = {SKY_ATMOSPHERE_HILLAIRE, SKY_ATMOSPHERE_BLEND};
    static const char *const names[2] = {"hillaire", "blend"};
    sky_photometry pub;
    sky_photometry_published(&pub);
    for (int p = 0; p < 2; p++) {
        sky_config cfg = sky_photometry_config(paths[p]);
        sky_photometry m;
        char err[256] = "";
        int rc = sky_photometry_measure(&cfg, &m, err, sizeof err);
        CHECK(rc == 0, "%s measured: %s", names[p], err);
        if (rc) continue;
        NOTE("%s: shape %.0f/%.0f/%.0f/%.0f %%, zenith %.2f kcd/m^2, diffuse %.1f klx, twilight %.3g / %.3g lx, night "
             "%.2f mag/arcsec^2",
             names[p], 100.0 * m.cie_median[0], 100.0 * m.cie_median[1], 100.0 * m.cie_median[2],
             100.0 * m.cie_median[3], m.zenith_kcd_70, m.diffuse_klx_30, m.civil_lx, m.nautical_lx,
             m.night_zenith_mag);
        for (int i = 0; i < SKY_PHOT_SHAPES; i++)
            CHECK(m.cie_median[i] <= 0.20, "%s, sun %.0f deg: shape %.1f %% from CIE type %d (<= 20 %%)", names[p],
                  sky_phot_shape_suns[i], 100.0 * m.cie_median[i], m.cie_type[i]);
        CHECK(fabs(m.zenith_kcd_70 / pub.zenith_kcd_70 - 1.0) <= 0.25,
              "%s: zenith at sun 70 %.2f kcd/m^2, gensky %.2f (within 25 %%)", names[p], m.zenith_kcd_70,
              pub.zenith_kcd_70);
        CHECK(fabs(m.diffuse_klx_30 / pub.diffuse_klx_30 - 1.0) <= 0.25,
              "%s: diffuse at sun 30 %.2f klx, IES %.2f (within 25 %%)", names[p], m.diffuse_klx_30, pub.diffuse_klx_30);
        CHECK(m.civil_lx > pub.civil_lx / 2.0 && m.civil_lx < pub.civil_lx * 2.0,
              "%s: civil twilight %.3g lx, published %.3g (within x2)", names[p], m.civil_lx, pub.civil_lx);
        CHECK(m.nautical_lx > pub.nautical_lx / 2.0 && m.nautical_lx < pub.nautical_lx * 2.0,
              "%s: nautical twilight %.3g lx, published %.3g (within x2)", names[p], m.nautical_lx, pub.nautical_lx);
        CHECK(m.night_zenith_mag >= 21.5 && m.night_zenith_mag <= 22.3,
              "%s: night zenith %.2f mag/arcsec^2 (21.5-22.3)", names[p], m.night_zenith_mag);
    }
}

/* The analytic path with the Earth's shadow and multiple scattering (issue
 * Real skies' targets, the default Earth): its night is the night sky's
 * own light (21.5-22.3 mag/arcsec^2), its civil and nautical twilight
 * within a factor 2 of Bond & Henderson's 3.4 and 0.008 lx, its clear sky
 * shaped like the CIE's within 30 % at suns of 10, 30, 50 and 70 deg
 * (measured 4.5 lx, 0.0046 lx, 21.7 mag/arcsec^2, shape 7 / 9 / 12 / 5
 * %; the nautical figure is near its bound, 0.004 lx: the path's twilight
 * is darker than Hillaire's tables, 0.009 lx in the same atmosphere). */
TEST(photometry_rayleigh_goes_dark)
{
    sky_config cfg = sky_photometry_config(SKY_ATMOSPHERE_RAYLEIGH);
    sky_photometry m, pub;
    char err[256] = "";
    if (sky_photometry_measure(&cfg, &m, err, sizeof err)) {
        CHECK(0, "rayleigh measured: %s", err);
        return;
    }
    sky_photometry_published(&pub);
    NOTE("rayleigh: %.3g lx at -6, %.3g lx at -12, night zenith %.2f mag/arcsec^2; shape %.1f / %.1f / %.1f / %.1f %%",
         m.civil_lx, m.nautical_lx, m.night_zenith_mag, 100.0 * m.cie_median[0], 100.0 * m.cie_median[1],
         100.0 * m.cie_median[2], 100.0 * m.cie_median[3]);
    /* the night: the sky of a sun 30 deg down is the airglow's and the
     * zodiacal light's (Garstang; Benn & Ellison), not the 15.2
     * mag/arcsec^2 that an optical-depth cap left */
    CHECK(m.night_zenith_mag >= 21.5 && m.night_zenith_mag <= 22.3, "night zenith %.2f mag/arcsec^2 (21.5-22.3)",
          m.night_zenith_mag);
    CHECK(m.civil_lx > pub.civil_lx / 2.0 && m.civil_lx < pub.civil_lx * 2.0,
          "civil twilight %.3g lx, published %.3g (within x2)", m.civil_lx, pub.civil_lx);
    CHECK(m.nautical_lx > pub.nautical_lx / 2.0 && m.nautical_lx < pub.nautical_lx * 2.0,
          "nautical twilight %.4g lx, published %.3g (within x2)", m.nautical_lx, pub.nautical_lx);
    CHECK(m.civil_lx > 100.0 * m.nautical_lx, "twilight falls: %.3g lx at -6, %.3g at -12", m.civil_lx,
          m.nautical_lx);
    for (int i = 0; i < SKY_PHOT_SHAPES; i++)
        CHECK(m.cie_median[i] <= 0.30, "sun %.0f deg: shape deviation %.1f %% (<= 30 %%)", sky_phot_shape_suns[i],
              100.0 * m.cie_median[i]);
}
