/*
 * The sky as a light for the host's scene (issue: the sky lights the
 * scene): the spherical-harmonic irradiance against a brute-force
 * integral of the same sky rendered in HDR into the six faces of a cube,
 * and the API's checks.
 */
#include "test.h"

#include "atmo_error.h"
#include "photometry.h"

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* test.h's path list and hemisphere (here, in the suite's own build:
 * the engine examples' test build has no tools) */
const sky_atmosphere_path test_paths[TEST_PATHS] = {SKY_ATMOSPHERE_GRADIENT, SKY_ATMOSPHERE_PREETHAM,
                                                     SKY_ATMOSPHERE_RAYLEIGH, SKY_ATMOSPHERE_HILLAIRE,
                                                     SKY_ATMOSPHERE_BLEND};
const char *const test_path_names[TEST_PATHS] = {"gradient", "preetham", "rayleigh", "hillaire", "blend"};

sky_atmo_hemisphere *hemisphere_open(sky_atmosphere_path path, unsigned features)
{
    sky_config cfg = sky_photometry_config(path);
    cfg.features = features;
    char err[256] = "";
    sky_atmo_hemisphere *h = sky_atmo_hemisphere_create(&cfg, err, sizeof err);
    if (!h) {
        const char *name = "?";
        for (int i = 0; i < TEST_PATHS; i++)
            if (test_paths[i] == path) name = test_path_names[i];
        CHECK(0, "%s: %s", name, err);
    }
    return h;
}

/* Issue target: the SH irradiance within 3 % of a brute-force integral of
 * the rendered sky on an upward, a horizontal and a downward normal, by
 * day, at sunset and at night, on every path (discs, stars and clouds
 * left out of both; the render's own sky is the SH's source). */
TEST(lighting_sh_irradiance_matches_render)
{
    static const double suns[3] = {30.0, 2.0, -20.0};
    static const char *const when[3] = {"day", "sunset", "night"};
    static const double normals[4][3] = {{0, 1, 0}, {1, 0, 0}, {0, 0, 1}, {0, -1, 0}};
    static const char *const facing[4] = {"up", "east (toward the sun)", "south", "down"};
    double worst = 0.0, worst9 = 0.0;
    for (int p = 0; p < TEST_PATHS; p++) {
        sky_atmo_hemisphere *h = hemisphere_open(test_paths[p], 0);
        if (!h) continue;
        char err[256] = "";
        for (int k = 0; k < 3; k++) {
            double el, az;
            if (sky_atmo_hemisphere_render(h, suns[k], &el, &az, err, sizeof err)) {
                CHECK(0, "%s: %s", test_path_names[p], err);
                break;
            }
            sky_irradiance_sh sh;
            CHECK(sky_get_irradiance_sh(sky_atmo_hemisphere_sky(h), &sh) == SKY_OK, "%s: no SH", test_path_names[p]);
            for (int n = 0; n < 4; n++) {
                /* rendered, from every coefficient, from the 9 of degree
                 * <= 2 alone (as a shader uses them) */
                double ly, ls, l9;
                sky_atmo_hemisphere_sh_check(h, normals[n], &ly, &ls, &l9);
                double rel = fabs(ls / ly - 1.0);
                worst = fmax(worst, rel);
                worst9 = fmax(worst9, fabs(l9 / ly - 1.0));
                if (n == 0 || n == 3)
                    NOTE("%s, %s (sun %.1f deg), facing %s: %.4g klx rendered, %.4g from the SH (%+.1f %%), %.4g "
                         "from its degree <= 2 (%+.1f %%)",
                         test_path_names[p], when[k], el, facing[n], ly, ls, 100.0 * (ls / ly - 1.0), l9,
                         100.0 * (l9 / ly - 1.0));
                CHECK(ly > 0.0 && rel <= 0.03, "%s, %s, facing %s: SH %.4g klx, rendered %.4g (%.1f %%, limit 3 %%)",
                      test_path_names[p], when[k], facing[n], ls, ly, 100.0 * rel);
            }
        }
        sky_atmo_hemisphere_destroy(h);
    }
    NOTE("worst difference %.2f %% (%.1f %% from the degree <= 2 coefficients alone)", 100.0 * worst,
         100.0 * worst9);
}

/* Issue target: the SH carries the clouds' dimming. The clouds drawn are
 * one moment of a drifting texture, the SH their mean over it
 * (sky_clouds_mean_at), so the measure is the irradiance with clouds
 * against the render with the same clouds (512^2 faces), cover 0.3 to
 * 0.9, day and sunset, facing up, the sun and the side: within 5 %
 * (measured: 2.8 %), and on an upward surface closer than the cloudless
 * SH (which is 6 to 61 % off). One case is held to 12 %: a surface
 * facing a sun on the horizon (measured -6 and -10 % at cover 0.6 and
 * 0.9), where the drawn clouds fade into the bright horizon glow by
 * their footprint (clouds.glsl) and the mean does not. */
SLOW_TEST(lighting_sh_with_clouds)
{
    static const sky_atmosphere_path paths[2] = {SKY_ATMOSPHERE_GRADIENT, SKY_ATMOSPHERE_HILLAIRE};
    static const char *const names[2] = {"gradient", "hillaire"};
    static const float covers[3] = {0.3f, 0.6f, 0.9f};
    static const double suns[2] = {30.0, 2.0};
    static const double normals[3][3] = {{0, 1, 0}, {1, 0, 0}, {0, 0, 1}};
    double worst = 0.0, worst_clear = 0.0;
    for (int p = 0; p < 2; p++) {
        sky_atmo_hemisphere *h = hemisphere_open(paths[p], SKY_CLOUDS);
        if (!h) continue;
        char err[256] = "";
        for (int k = 0; k < 2; k++) {
            double clear[3], el, az;
            sky_atmo_hemisphere_clouds(h, 0.0f, 0.5f);
            if (sky_atmo_hemisphere_render(h, suns[k], &el, &az, err, sizeof err)) break;
            for (int n = 0; n < 3; n++) {
                double ly, l9;
                sky_atmo_hemisphere_sh_check(h, normals[n], &ly, &clear[n], &l9);
            }
            for (int c = 0; c < 3; c++) {
                sky_atmo_hemisphere_clouds(h, covers[c], 0.5f);
                if (sky_atmo_hemisphere_render(h, suns[k], &el, &az, err, sizeof err)) break;
                for (int n = 0; n < 3; n++) {
                    double ly, ls, l9;
                    sky_atmo_hemisphere_sh_check(h, normals[n], &ly, &ls, &l9);
                    double rel = fabs(ls / ly - 1.0), rel_clear = fabs(clear[n] / ly - 1.0);
                    int glow = k == 1 && n == 1;
                    if (!glow) worst = fmax(worst, rel);
                    worst_clear = fmax(worst_clear, rel_clear);
                    CHECK(rel <= (glow ? 0.12 : 0.05) && (n != 0 || rel < rel_clear),
                          "%s, sun %.0f, cover %.1f, normal %d: SH %.4g klx, rendered %.4g (%+.1f %%; cloudless "
                          "%+.1f %%)", names[p], suns[k], covers[c], n, ls, ly, 100.0 * (ls / ly - 1.0),
                          100.0 * (clear[n] / ly - 1.0));
                    NOTE("%s, sun %.0f, cover %.1f, normal %d: rendered %.4g klx, SH %.4g (%+.1f %%), cloudless SH "
                         "%+.1f %%", names[p], suns[k], covers[c], n, ly, ls, 100.0 * (ls / ly - 1.0),
                         100.0 * (clear[n] / ly - 1.0));
                }
            }
        }
        sky_atmo_hemisphere_destroy(h);
    }
    NOTE("worst %.1f %% with the clouds' mean (a surface facing a sun on the horizon apart), %.1f %% without",
         100.0 * worst, 100.0 * worst_clear);
}

/* Issue target: the SH irradiance on an upward surface against a
 * brute-force integral of the all-sky fisheye HDR render (sky_draw_fisheye,
 * equidistant: a pixel at ndc radius r sees zenith angle r 90 deg and
 * spans sin(theta) (pi / 2) (2 / N)^2 / r sr): within 3 % on every path,
 * by day, at sunset and at night. */
TEST(lighting_sh_matches_fisheye)
{
    enum { N = 512 };
    static const double suns[3] = {30.0, 2.0, -20.0};
    double worst = 0.0;
    for (int p = 0; p < TEST_PATHS; p++) {
        sky_config cfg;
        memset(&cfg, 0, sizeof cfg);
        cfg.atmosphere = test_paths[p];
        cfg.output = SKY_OUTPUT_HDR;
        cfg.features = SKY_FEATURES_NONE;
        fixture f;
        if (fixture_open_sized(&f, N, N, 1, SKY_GL_CORE33, &cfg)) {
            CHECK(0, "%s: no sky", test_path_names[p]);
            continue;
        }
        sky_observer o = equator_equinox();
        sky_set_observer(f.s, &o);
        for (int k = 0; k < 3; k++) {
            sky_params prm = sky_default_params();
            prm.cover = 0.0f;
            prm.time = (float)sky_atmo_time_for_altitude(&o, suns[k]);
            sky_set_params(f.s, &prm);
            glClearColor(0, 0, 0, 0);
            glClear(GL_COLOR_BUFFER_BIT);
            CHECK(sky_draw_fisheye(f.s) == SKY_OK, "%s: fisheye: %s", test_path_names[p], sky_last_error(f.s));
            sky_osmesa_finish(&f.ctx);
            const float *px = f.ctx.pixels;
            double e[3] = {0, 0, 0};
            for (int y = 0; y < N; y++)
                for (int x = 0; x < N; x++) {
                    double u = (x + 0.5) / N * 2.0 - 1.0, v = (y + 0.5) / N * 2.0 - 1.0, r = sqrt(u * u + v * v);
                    if (r >= 1.0) continue;
                    double th = r * 0.5 * M_PI, w = cos(th) * sin(th) * 0.5 * M_PI * (2.0 / N) * (2.0 / N) / r;
                    for (int c = 0; c < 3; c++) e[c] += w * px[4 * (y * N + x) + c];
                }
            sky_irradiance_sh sh;
            sky_get_irradiance_sh(f.s, &sh);
            float up[3] = {0.0f, 1.0f, 0.0f}, es[3];
            sky_irradiance_sh_eval(&sh, up, es);
            double ly = 0.2126 * e[0] + 0.7152 * e[1] + 0.0722 * e[2], ls = 0.2126 * es[0] + 0.7152 * es[1] + 0.0722 * es[2];
            double rel = fabs(ls / ly - 1.0);
            worst = fmax(worst, rel);
            CHECK(ly > 0.0 && rel <= 0.03, "%s, sun %.0f: SH %.4g klx on an upward surface, the fisheye %.4g (%+.1f %%)",
                  test_path_names[p], suns[k], ls, ly, 100.0 * (ls / ly - 1.0));
        }
        fixture_close(&f);
    }
    NOTE("upward irradiance: SH within %.2f %% of the fisheye render", 100.0 * worst);
}

TEST(lighting_sh_checks_its_input)
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
TEST(lighting_sh_in_the_world_frame)
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

/* Issue target: each captured face is what sky_draw draws with the face's
 * camera (the same pixels: the same pipeline, dither included), in both
 * profiles, clouds and sun disc included; and the faces meet without
 * seams: the pixels along a shared edge differ by no more than pixels one
 * apart inside a face. */
enum { CAP = 64 };
static int face_pixels(GLuint tex, int face, unsigned char *out)
{
    glBindTexture(GL_TEXTURE_CUBE_MAP, tex);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTexImage(GL_TEXTURE_CUBE_MAP_POSITIVE_X + (GLenum)face, 0, GL_RGBA, GL_UNSIGNED_BYTE, out);
    glBindTexture(GL_TEXTURE_CUBE_MAP, 0);
    return glGetError() == GL_NO_ERROR ? 0 : -1;
}

TEST(lighting_capture_faces_are_sky_draw)
{
    static const sky_gl_profile profiles[2] = {SKY_GL_CORE33, SKY_GL_COMPAT20};
    for (int q = 0; q < 2; q++) {
        fixture f;
        sky_config cfg;
        memset(&cfg, 0, sizeof cfg);
        cfg.dome_divisor = 1; /* what a capture draws: every pixel */
        if (fixture_open_sized(&f, CAP, CAP, 0, profiles[q], &cfg)) {
            CHECK(0, "no sky");
            continue;
        }
        sky_params p = sky_default_params();
        p.time = 0.3f;
        p.cover = 0.5f;
        sky_set_params(f.s, &p);
        sky_result rc = sky_capture_environment(f.s, 0, CAP, SKY_CAPTURE_ALL_FACES, SKY_CAPTURE_SUN_DISC);
        CHECK(rc == SKY_OK, "profile %d: capture: %s", q, sky_last_error(f.s));
        GLuint tex = sky_environment_texture(f.s);
        CHECK(tex != 0, "profile %d: no texture", q);
        static unsigned char face[6][CAP * CAP * 4], drawn[CAP * CAP * 4];
        int worst = 0;
        for (int k = 0; k < 6 && rc == SKY_OK; k++) {
            CHECK(face_pixels(tex, k, face[k]) == 0, "profile %d: face %d not read", q, k);
            float view[16], proj[16];
            sky_capture_face_matrices(k, view, proj);
            CHECK(sky_draw(f.s, view, proj) == SKY_OK, "profile %d: sky_draw: %s", q, sky_last_error(f.s));
            glReadPixels(0, 0, CAP, CAP, GL_RGBA, GL_UNSIGNED_BYTE, drawn);
            for (int i = 0; i < CAP * CAP * 4; i++)
                if (i % 4 != 3) worst = abs(face[k][i] - drawn[i]) > worst ? abs(face[k][i] - drawn[i]) : worst;
        }
        NOTE("profile %d: faces against sky_draw, largest difference %d levels", q, worst);
        /* orientation: where GL's cube-map addressing puts the sun's disc
         * (the centroid of its white pixels) is where sky_get_lighting says */
        double sum[3] = {0, 0, 0};
        int white = 0;
        for (int k = 0; k < 6; k++)
            for (int j = 0; j < CAP; j++)
                for (int i = 0; i < CAP; i++) {
                    const unsigned char *px = &face[k][4 * (j * CAP + i)];
                    if (px[0] < 250 || px[1] < 250 || px[2] < 250) continue;
                    double sc = (i + 0.5) / CAP * 2.0 - 1.0, tc = (j + 0.5) / CAP * 2.0 - 1.0, d[3];
                    switch (k) {
                    case 0: d[0] = 1, d[1] = -tc, d[2] = -sc; break;
                    case 1: d[0] = -1, d[1] = -tc, d[2] = sc; break;
                    case 2: d[0] = sc, d[1] = 1, d[2] = tc; break;
                    case 3: d[0] = sc, d[1] = -1, d[2] = -tc; break;
                    case 4: d[0] = sc, d[1] = -tc, d[2] = 1; break;
                    default: d[0] = -sc, d[1] = -tc, d[2] = -1; break;
                    }
                    double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
                    for (int a = 0; a < 3; a++) sum[a] += d[a] / len;
                    white++;
                }
        sky_lighting l;
        sky_get_lighting(f.s, &l);
        double len = sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
        double cosang = len > 0.0 ? (sum[0] * l.sun_direction[0] + sum[1] * l.sun_direction[1] +
                                     sum[2] * l.sun_direction[2]) / len
                                  : -1.0;
        double ang = acos(fmin(fmax(cosang, -1.0), 1.0)) * 180.0 / 3.14159265358979;
        NOTE("profile %d: %d white pixels, their centre %.2f deg from the sun's direction", q, white, ang);
        CHECK(white > 0 && ang < 3.0, "profile %d: the captured sun is %.1f deg from sky_get_lighting's", q, ang);
        CHECK(worst <= 1, "profile %d: a face differs from sky_draw by %d levels", q, worst);
        /* seams: +X's right column against -Z's left column (both with
         * -Y up, rows aligned), against the step over the same distance
         * inside each (the dome's image is a quarter of the face or less,
         * so neighbouring pixels inside are often equal: the step over
         * four of them is the sky's own gradient there) */
        double seam = 0.0, inside = 0.0;
        for (int y = 0; y < CAP; y++)
            for (int c = 0; c < 3; c++) {
                int a = face[0][4 * (y * CAP + CAP - 1) + c], b = face[5][4 * (y * CAP) + c],
                    a4 = face[0][4 * (y * CAP + CAP - 5) + c], b4 = face[5][4 * (y * CAP + 4) + c];
                seam += abs(a - b);
                inside += 0.5 * (abs(a - a4) + abs(b - b4)) / 4.0;
            }
        seam /= 3.0 * CAP;
        inside /= 3.0 * CAP;
        NOTE("profile %d: mean step across the +X/-Z edge %.2f levels, a pixel inside %.2f", q, seam, inside);
        CHECK(seam <= 2.0 * inside + 1.5, "profile %d: a seam: %.2f levels across the edge, %.2f a pixel inside",
              q, seam, inside);
        fixture_close(&f);
    }
}

/* The host's framebuffer, viewport and texture bindings come back; bad
 * sizes, faces, flags and foreign textures are refused with a message. */
TEST(lighting_capture_checks_and_restores)
{
    fixture f;
    if (fixture_open_sized(&f, CAP, CAP, 0, SKY_GL_CORE33, NULL)) {
        CHECK(0, "no sky");
        return;
    }
    GLuint host_tex = 0, host_cube = 0;
    glGenTextures(1, &host_tex);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, host_tex);
    glViewport(3, 5, 17, 19);
    GLint vp[4], bound = 0, fbo = -1;
    CHECK(sky_capture_environment(f.s, 0, 16, 2, 0) == SKY_OK, "capture: %s", sky_last_error(f.s));
    glGetIntegerv(GL_VIEWPORT, vp);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &bound);
    glGetIntegerv(GL_FRAMEBUFFER_BINDING, &fbo);
    CHECK(vp[0] == 3 && vp[1] == 5 && vp[2] == 17 && vp[3] == 19, "viewport %d %d %d %d", vp[0], vp[1], vp[2], vp[3]);
    CHECK(bound == (GLint)host_tex && fbo == 0, "texture %d (host's %u), framebuffer %d", bound, host_tex, fbo);
    CHECK(sky_capture_environment(f.s, 0, 12, 0, 0) == SKY_ERR_INVALID_ARGUMENT &&
              strstr(sky_last_error(f.s), "power of two"),
          "a face of 12: '%s'", sky_last_error(f.s));
    CHECK(sky_capture_environment(f.s, 0, 16, 6, 0) == SKY_ERR_INVALID_ARGUMENT, "face 6 refused");
    CHECK(sky_capture_environment(f.s, 0, 16, -2, 0) == SKY_ERR_INVALID_ARGUMENT, "face -2 refused");
    CHECK(sky_capture_environment(f.s, 0, 16, 0, 8u) == SKY_ERR_INVALID_ARGUMENT, "flag 8 refused");
    CHECK(sky_capture_environment(NULL, 0, 16, 0, 0) == SKY_ERR_INVALID_ARGUMENT, "NULL sky refused");
    /* the host's own cube map, of the size asked or not */
    glGenTextures(1, &host_cube);
    glBindTexture(GL_TEXTURE_CUBE_MAP, host_cube);
    for (int k = 0; k < 6; k++)
        glTexImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + (GLenum)k, 0, GL_RGBA8, 32, 32, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    glBindTexture(GL_TEXTURE_CUBE_MAP, 0);
    CHECK(sky_capture_environment(f.s, host_cube, 32, SKY_CAPTURE_ALL_FACES, 0) == SKY_OK, "host's cube: %s",
          sky_last_error(f.s));
    CHECK(sky_capture_environment(f.s, host_cube, 64, 0, 0) == SKY_ERR_INVALID_ARGUMENT &&
              strstr(sky_last_error(f.s), "32 wide"),
          "a host cube of another size: '%s'", sky_last_error(f.s));
    static unsigned char px[32 * 32 * 4];
    CHECK(face_pixels(host_cube, 2, px) == 0 && (px[0] | px[1] | px[2]) != 0, "the host's +Y face was drawn");
    CHECK(glGetError() == GL_NO_ERROR, "a GL error left");
    glDeleteTextures(1, &host_cube);
    glDeleteTextures(1, &host_tex);
    fixture_close(&f);
}

/* A host's loader that hides the framebuffer objects (ARB, EXT and core
 * names alike): a COMPAT20 context of a GPU without them. */
static sky_gl_proc no_fbo_loader(const char *name)
{
    if (strstr(name, "Framebuffer") || strstr(name, "Renderbuffer")) return NULL;
    return sky_osmesa_loader()(name);
}

/* HDR output: the faces are float (RGBA32F), the same linear radiance
 * sky_draw writes into a float framebuffer, sun disc included, within
 * the 1 %. CORE33 into the library's own cube map; COMPAT20 into
 * the host's float cube map, through a framebuffer object and, without
 * them, from the float draw buffer (the library's own is refused there:
 * its textures are 8-bit). sky_draw renders where the capture did: into
 * the host's float framebuffer object, or the draw buffer. (Against the
 * draw buffer, a capture through a framebuffer object differs on a few
 * cloud pixels, up to 1.01 %: llvmpipe picks a texture's mipmap level
 * from a 2 x 2 quad's differences, and its draw buffer lies upside down
 * to a framebuffer object's, so their quads differ there.) */
TEST(lighting_capture_hdr)
{
    static const char *const names[3] = {"CORE33", "COMPAT20", "COMPAT20 without framebuffer objects"};
    for (int q = 0; q < 3; q++) {
        sky_config cfg;
        memset(&cfg, 0, sizeof cfg);
        cfg.output = SKY_OUTPUT_HDR;
        cfg.dome_divisor = 1;
        cfg.atmosphere = SKY_ATMOSPHERE_HILLAIRE;
        cfg.check_gl_errors = 1;
        cfg.gl_profile = q ? SKY_GL_COMPAT20 : SKY_GL_CORE33;
        cfg.get_proc_address = q == 2 ? no_fbo_loader : sky_osmesa_loader();
        char err[512];
        sky_osmesa ctx;
        if (sky_osmesa_create(&ctx, CAP, CAP, cfg.gl_profile, 1, err, sizeof err)) {
            CHECK(0, "%s: %s", names[q], err);
            continue;
        }
        sky *s = sky_create(&cfg, err, sizeof err);
        if (!s) {
            CHECK(0, "%s: %s", names[q], err);
            sky_osmesa_destroy(&ctx);
            continue;
        }
        sky_params p = sky_default_params();
        p.time = 0.3f;
        sky_set_params(s, &p);
        GLuint cube = 0;
        if (q) {
            CHECK(sky_capture_environment(s, 0, CAP, 0, 0) == SKY_ERR_UNSUPPORTED, "%s: HDR into the library's "
                  "8-bit cube map is refused", names[q]);
            glGenTextures(1, &cube);
            glBindTexture(GL_TEXTURE_CUBE_MAP, cube);
            for (int k = 0; k < 6; k++)
                glTexImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + (GLenum)k, 0, GL_RGBA32F, CAP, CAP, 0, GL_RGBA, GL_FLOAT,
                             NULL);
            glBindTexture(GL_TEXTURE_CUBE_MAP, 0);
        }
        CHECK(sky_capture_environment(s, cube, CAP, SKY_CAPTURE_ALL_FACES, SKY_CAPTURE_SUN_DISC) == SKY_OK,
              "%s: capture: %s", names[q], sky_last_error(s));
        GLuint target = 0, fbo = 0;
        if (q < 2) { /* the host's float framebuffer object, for sky_draw */
            glGenTextures(1, &target);
            glBindTexture(GL_TEXTURE_2D, target);
            glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, CAP, CAP, 0, GL_RGBA, GL_FLOAT, NULL);
            glBindTexture(GL_TEXTURE_2D, 0);
            glGenFramebuffers(1, &fbo);
            glBindFramebuffer(GL_FRAMEBUFFER, fbo);
            glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, target, 0);
            CHECK(glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE, "%s: no float framebuffer",
                  names[q]);
            glViewport(0, 0, CAP, CAP);
        }
        static float face[CAP * CAP * 4], drawn[CAP * CAP * 4];
        double worst = 0.0;
        int differing = 0;
        for (int k = 0; k < 6; k++) {
            glBindTexture(GL_TEXTURE_CUBE_MAP, q ? cube : sky_environment_texture(s));
            glGetTexImage(GL_TEXTURE_CUBE_MAP_POSITIVE_X + (GLenum)k, 0, GL_RGBA, GL_FLOAT, face);
            glBindTexture(GL_TEXTURE_CUBE_MAP, 0);
            float view[16], proj[16];
            sky_capture_face_matrices(k, view, proj);
            sky_draw(s, view, proj);
            if (fbo) {
                glReadPixels(0, 0, CAP, CAP, GL_RGBA, GL_FLOAT, drawn);
            } else {
                sky_osmesa_finish(&ctx);
                memcpy(drawn, ctx.pixels, sizeof drawn); /* the float buffer, bottom row first like the face */
            }
            for (int i = 0; i < CAP * CAP * 4; i++)
                if (i % 4 != 3 && drawn[i] > 1e-6f) {
                    double d = fabs(face[i] / drawn[i] - 1.0);
                    worst = fmax(worst, d);
                    if (d > 1e-4) differing++;
                }
        }
        NOTE("%s: HDR faces against sky_draw: worst relative difference %.2g; %d of %d values over 1e-4", names[q],
             worst, differing, 6 * CAP * CAP * 3);
        CHECK(worst <= 0.01, "%s: an HDR face differs from sky_draw by %.3g", names[q], worst);
        CHECK(glGetError() == GL_NO_ERROR, "%s: a GL error left", names[q]);
        if (fbo) {
            glBindFramebuffer(GL_FRAMEBUFFER, 0);
            glDeleteFramebuffers(1, &fbo);
            glDeleteTextures(1, &target);
        }
        if (cube) glDeleteTextures(1, &cube);
        sky_destroy(s);
        sky_osmesa_destroy(&ctx);
    }
}

/* Issue target: capture works in COMPAT20 without framebuffer objects,
 * through the back buffer: every face the same picture as a capture
 * through a framebuffer object, within one level plus the dither's (its
 * pattern follows a pixel's place in the buffer, and the host's viewport
 * here starts at 4, 2), the pixels it drew into reported, the host's
 * viewport and textures back, a face larger than the viewport refused. */
TEST(lighting_capture_without_framebuffer_objects)
{
    char err[512];
    sky_osmesa ctx;
    if (sky_osmesa_create(&ctx, 80, 72, SKY_GL_COMPAT20, 0, err, sizeof err)) {
        CHECK(0, "%s", err);
        return;
    }
    sky_params p = sky_default_params();
    p.time = 0.3f;
    p.cover = 0.5f;
    static unsigned char faces[2][6][CAP * CAP * 4];
    int overwrote[2] = {0, 0}, rect[4] = {0, 0, 0, 0};
    for (int k = 0; k < 2; k++) {
        sky_config cfg;
        memset(&cfg, 0, sizeof cfg);
        cfg.gl_profile = SKY_GL_COMPAT20;
        cfg.check_gl_errors = 1;
        cfg.dome_divisor = 1;
        cfg.get_proc_address = k ? no_fbo_loader : sky_osmesa_loader();
        sky *s = sky_create(&cfg, err, sizeof err);
        if (!s) {
            CHECK(0, "sky_create: %s", err);
            continue;
        }
        sky_set_params(s, &p);
        glViewport(4, 2, 70, 66);
        GLuint host_tex = 0;
        glGenTextures(1, &host_tex);
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(GL_TEXTURE_2D, host_tex);
        if (k) {
            CHECK(sky_capture_environment(s, 0, 128, 0, 0) == SKY_ERR_INVALID_ARGUMENT &&
                      strstr(sky_last_error(s), "viewport"),
                  "a face larger than the viewport: '%s'", sky_last_error(s));
        }
        sky_result rc = sky_capture_environment(s, 0, CAP, SKY_CAPTURE_ALL_FACES, SKY_CAPTURE_SUN_DISC);
        CHECK(rc == SKY_OK, "%s: capture: %s", k ? "no FBO" : "FBO", sky_last_error(s));
        overwrote[k] = sky_capture_overwrote(s, k ? rect : NULL);
        GLint vp[4], bound = 0;
        glGetIntegerv(GL_VIEWPORT, vp);
        glGetIntegerv(GL_TEXTURE_BINDING_2D, &bound);
        CHECK(vp[0] == 4 && vp[1] == 2 && vp[2] == 70 && vp[3] == 66 && bound == (GLint)host_tex,
              "%s: the viewport %d %d %d %d, texture %d (host's %u)", k ? "no FBO" : "FBO", vp[0], vp[1], vp[2],
              vp[3], bound, host_tex);
        for (int f = 0; f < 6 && rc == SKY_OK; f++)
            CHECK(face_pixels(sky_environment_texture(s), f, faces[k][f]) == 0, "face %d not read", f);
        glDeleteTextures(1, &host_tex);
        sky_destroy(s);
    }
    CHECK(!overwrote[0] && overwrote[1] && rect[0] == 4 && rect[1] == 2 && rect[2] == CAP && rect[3] == CAP,
          "the pixels drawn into: FBO %d, no FBO %d at %d %d %d %d", overwrote[0], overwrote[1], rect[0], rect[1],
          rect[2], rect[3]);
    int worst = 0;
    for (int f = 0; f < 6; f++)
        for (int i = 0; i < CAP * CAP * 4; i++)
            if (i % 4 != 3) worst = abs(faces[0][f][i] - faces[1][f][i]) > worst ? abs(faces[0][f][i] - faces[1][f][i]) : worst;
    NOTE("COMPAT20 without framebuffer objects: faces within %d levels of the FBO capture", worst);
    CHECK(worst <= 2, "the back buffer's faces differ from the FBO's by %d levels", worst);
    sky_osmesa_destroy(&ctx);
}
