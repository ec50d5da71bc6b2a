/*
 * The sky as a light for the host's scene (issue: the sky lights the
 * scene): the spherical-harmonic irradiance against a brute-force
 * integral of the same sky rendered in HDR into the six faces of a cube,
 * and the API's checks.
 */
#include "test.h"

#include "atmo_error.h"

#include <math.h>
#include <string.h>

void test_lighting_sh_irradiance_matches_render(void);
void test_lighting_sh_checks_its_input(void);
void test_lighting_sh_in_the_world_frame(void);

/* Issue target: the SH irradiance within 3 % of a brute-force integral of
 * the rendered sky on an upward, a horizontal and a downward normal, by
 * day, at sunset and at night, on every path (discs, stars and clouds
 * left out of both; the render's own sky is the SH's source). */
void test_lighting_sh_irradiance_matches_render(void)
{
    static const sky_atmosphere_path paths[5] = {SKY_ATMOSPHERE_GRADIENT, SKY_ATMOSPHERE_PREETHAM,
                                                 SKY_ATMOSPHERE_RAYLEIGH, SKY_ATMOSPHERE_HILLAIRE,
                                                 SKY_ATMOSPHERE_BLEND};
    static const char *const names[5] = {"gradient", "preetham", "rayleigh", "hillaire", "blend"};
    static const double suns[3] = {30.0, 2.0, -20.0};
    static const char *const when[3] = {"day", "sunset", "night"};
    static const double normals[4][3] = {{0, 1, 0}, {1, 0, 0}, {0, 0, 1}, {0, -1, 0}};
    static const char *const facing[4] = {"up", "east (toward the sun)", "south", "down"};
    double worst = 0.0, worst9 = 0.0;
    for (int p = 0; p < 5; p++) {
        sky_config cfg;
        memset(&cfg, 0, sizeof cfg);
        cfg.gl_profile = SKY_GL_CORE33;
        cfg.atmosphere = paths[p];
        char err[256] = "";
        sky_atmo_hemisphere *h = sky_atmo_hemisphere_create(&cfg, err, sizeof err);
        if (!h) {
            CHECK(0, "%s: %s", names[p], err);
            continue;
        }
        for (int k = 0; k < 3; k++) {
            double el, az;
            if (sky_atmo_hemisphere_render(h, suns[k], &el, &az, err, sizeof err)) {
                CHECK(0, "%s: %s", names[p], err);
                break;
            }
            sky_irradiance_sh sh;
            CHECK(sky_get_irradiance_sh(sky_atmo_hemisphere_sky(h), &sh) == SKY_OK, "%s: no SH", names[p]);
            /* the 9 coefficients of degree <= 2 alone, as a shader uses them */
            sky_irradiance_sh nine = sh;
            memset(nine.radiance_l4, 0, sizeof nine.radiance_l4);
            memset(nine.radiance_zonal, 0, sizeof nine.radiance_zonal);
            for (int n = 0; n < 4; n++) {
                double ref[3];
                float nf[3] = {(float)normals[n][0], (float)normals[n][1], (float)normals[n][2]}, e[3], e9[3];
                sky_atmo_hemisphere_irradiance(h, normals[n], ref);
                sky_irradiance_sh_eval(&sh, nf, e);
                sky_irradiance_sh_eval(&nine, nf, e9);
                double ly = 0.2126 * ref[0] + 0.7152 * ref[1] + 0.0722 * ref[2];
                double ls = 0.2126 * e[0] + 0.7152 * e[1] + 0.0722 * e[2];
                double l9 = 0.2126 * e9[0] + 0.7152 * e9[1] + 0.0722 * e9[2];
                double rel = fabs(ls / ly - 1.0);
                worst = fmax(worst, rel);
                worst9 = fmax(worst9, fabs(l9 / ly - 1.0));
                if (n == 0 || n == 3)
                    NOTE("%s, %s (sun %.1f deg), facing %s: %.4g klx rendered, %.4g from the SH (%+.1f %%), %.4g "
                         "from its degree <= 2 (%+.1f %%)",
                         names[p], when[k], el, facing[n], ly, ls, 100.0 * (ls / ly - 1.0), l9,
                         100.0 * (l9 / ly - 1.0));
                CHECK(ly > 0.0 && rel <= 0.03, "%s, %s, facing %s: SH %.4g klx, rendered %.4g (%.1f %%, limit 3 %%)",
                      names[p], when[k], facing[n], ls, ly, 100.0 * rel);
            }
        }
        sky_atmo_hemisphere_destroy(h);
    }
    NOTE("worst difference %.2f %% (%.1f %% from the degree <= 2 coefficients alone)", 100.0 * worst,
         100.0 * worst9);
}

void test_lighting_sh_checks_its_input(void)
{
    sky_irradiance_sh sh;
    memset(&sh, 0, sizeof sh);
    sh.radiance[0][0] = sh.radiance[0][1] = sh.radiance[0][2] = 1.0f;
    float e[3], up[3] = {0.0f, 2.0f, 0.0f}, zero[3] = {0, 0, 0}, nan3[3] = {NAN, 0.0f, 1.0f},
               inf3[3] = {0.0f, INFINITY, 0.0f};
    CHECK(sky_get_irradiance_sh(NULL, &sh) == SKY_ERR_INVALID_ARGUMENT, "a NULL sky is refused");
    CHECK(sky_irradiance_sh_eval(NULL, up, e) == SKY_ERR_INVALID_ARGUMENT, "NULL coefficients are refused");
    CHECK(sky_irradiance_sh_eval(&sh, NULL, e) == SKY_ERR_INVALID_ARGUMENT, "a NULL normal is refused");
    CHECK(sky_irradiance_sh_eval(&sh, up, NULL) == SKY_ERR_INVALID_ARGUMENT, "a NULL output is refused");
    CHECK(sky_irradiance_sh_eval(&sh, zero, e) == SKY_ERR_INVALID_ARGUMENT, "a zero normal is refused");
    CHECK(sky_irradiance_sh_eval(&sh, nan3, e) == SKY_ERR_INVALID_ARGUMENT, "a NaN normal is refused");
    CHECK(sky_irradiance_sh_eval(&sh, inf3, e) == SKY_ERR_INVALID_ARGUMENT, "an infinite normal is refused");
    /* a uniform sky of radiance L (Y_0 = 0.282095, so L = 1 / (2 sqrt(pi)))
     * gives pi L on every surface, whatever the normal's length */
    CHECK(sky_irradiance_sh_eval(&sh, up, e) == SKY_OK, "a normal of length 2 is taken");
    double L = 1.0 * 0.282095;
    CHECK(fabs(e[1] - 3.14159265 * L) < 1e-5, "uniform sky: %.6f klx, expected %.6f", e[1], 3.14159265 * L);
}

/* The coefficients are in the host's world: a Z-up world (OpenSceneGraph)
 * and a left-handed one (Irrlicht) see the same irradiance on the same
 * physical surface as the identity frame, within float rounding; and the
 * horizon's up, 'up', is where horizon_to_world puts +y. */
void test_lighting_sh_in_the_world_frame(void)
{
    static const float frames[3][9] = {{1, 0, 0, 0, 1, 0, 0, 0, 1}, {1, 0, 0, 0, 0, 1, 0, -1, 0},
                                       {1, 0, 0, 0, 1, 0, 0, 0, -1}};
    static const char *const names[3] = {"identity", "Z up", "left-handed"};
    /* physical normals in the horizon frame: up, toward the sun's side, south-west, down */
    static const float normals[4][3] = {{0, 1, 0}, {0.6f, 0.8f, 0}, {-0.6f, 0, 0.8f}, {0, -1, 0}};
    float e_ref[4][3] = {{0}};
    for (int k = 0; k < 3; k++) {
        sky_config cfg;
        memset(&cfg, 0, sizeof cfg);
        if (k) memcpy(cfg.horizon_to_world, frames[k], sizeof cfg.horizon_to_world);
        fixture f;
        if (fixture_open(&f, SKY_GL_CORE33, &cfg)) {
            CHECK(0, "%s: no sky", names[k]);
            continue;
        }
        sky_params p = sky_default_params();
        p.time = 0.35f;
        sky_set_params(f.s, &p);
        sky_irradiance_sh sh;
        CHECK(sky_get_irradiance_sh(f.s, &sh) == SKY_OK, "%s: no SH", names[k]);
        const float *m = frames[k];
        CHECK(fabsf(sh.up[0] - m[3]) < 1e-6f && fabsf(sh.up[1] - m[4]) < 1e-6f && fabsf(sh.up[2] - m[5]) < 1e-6f,
              "%s: up (%g, %g, %g)", names[k], sh.up[0], sh.up[1], sh.up[2]);
        for (int n = 0; n < 4; n++) {
            const float *h = normals[n];
            float w[3] = {m[0] * h[0] + m[3] * h[1] + m[6] * h[2], m[1] * h[0] + m[4] * h[1] + m[7] * h[2],
                          m[2] * h[0] + m[5] * h[1] + m[8] * h[2]},
                  e[3];
            sky_irradiance_sh_eval(&sh, w, e);
            if (k == 0) memcpy(e_ref[n], e, sizeof e);
            CHECK(e[1] > 0.0f && fabsf(e[1] / e_ref[n][1] - 1.0f) < 1e-4f, "%s, normal %d: %g klx against %g",
                  names[k], n, e[1], e_ref[n][1]);
        }
        fixture_close(&f);
    }
}
