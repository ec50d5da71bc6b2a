/*
 * Aerial perspective (issue: the sky lights the scene): the CPU function
 * against the sky it must fade into and against the spectral reference,
 * its checks, its world frame; the GLSL snippet against the CPU function
 * in both profiles, and the host state its binder leaves.
 */
#define GL_GLEXT_PROTOTYPES 1
#include "test.h"

#include "atmo_error.h"
#include "cli.h"
#include "atmosphere/reference.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static double luminance(const double c[3]) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

static void horizon_dir(double el_deg, double az_deg, double d[3])
{
    double el = el_deg * M_PI / 180.0, az = az_deg * M_PI / 180.0;
    d[0] = cos(el) * sin(az);
    d[1] = sin(el);
    d[2] = -cos(el) * cos(az);
}

static int aerial(sky *s, const double d[3], double m, double in[3], double tr[3])
{
    float df[3] = {(float)d[0], (float)d[1], (float)d[2]};
    sky_aerial a;
    if (sky_get_aerial_perspective(s, df, (float)m, &a) != SKY_OK) return -1;
    for (int c = 0; c < 3; c++) in[c] = a.inscatter[c], tr[c] = a.transmittance[c];
    return 0;
}

/* Issue target: at d = 0 the identity; at d -> infinity the sky drawn in
 * that direction (the horizon's colour for a level view), read from the
 * HDR render of the same sky; in between, light that grows and
 * transmittance that falls with distance. Every path, by day, at sunset
 * and at night. */
TEST(aerial_meets_the_sky)
{
    static const double suns[3] = {30.0, 2.0, -20.0};
    static const double views[4][2] = {{0.5, 0.0}, {0.5, 90.0}, {0.5, 180.0}, {20.0, 60.0}}; /* el, az from the sun */
    static const double metres[6] = {100.0, 1000.0, 5000.0, 20000.0, 100000.0, 1e6};
    double worst_end = 0.0;
    for (int p = 0; p < TEST_PATHS; p++) {
        sky_atmo_hemisphere *h = hemisphere_open(test_paths[p], 0);
        if (!h) continue;
        char err[256] = "";
        sky *s = sky_atmo_hemisphere_sky(h);
        for (int k = 0; k < 3; k++) {
            double el, az;
            if (sky_atmo_hemisphere_render(h, suns[k], &el, &az, err, sizeof err)) {
                CHECK(0, "%s: %s", test_path_names[p], err);
                break;
            }
            for (int v = 0; v < 4; v++) {
                double d[3], in[3], tr[3], prev_in = 0.0, prev_tr = 1.0, sky_rgb[3];
                horizon_dir(views[v][0], az + views[v][1], d);
                CHECK(aerial(s, d, 0.0, in, tr) == 0 && in[0] == 0.0 && in[1] == 0.0 && in[2] == 0.0 &&
                          tr[0] == 1.0 && tr[1] == 1.0 && tr[2] == 1.0,
                      "%s, sun %.0f: 0 m is not the identity (%g, %g)", test_path_names[p], suns[k], in[1], tr[1]);
                for (int m = 0; m < 6; m++) {
                    aerial(s, d, metres[m], in, tr);
                    double y = luminance(in);
                    CHECK(y >= prev_in * (1.0 - 1e-6) && tr[1] <= prev_tr + 1e-6 && tr[1] >= 0.0,
                          "%s, sun %.0f, view %d: at %.0f m light %g (before %g), transmittance %g (before %g)",
                          test_path_names[p], suns[k], v, metres[m], y, prev_in, tr[1], prev_tr);
                    prev_in = y;
                    prev_tr = tr[1];
                }
                aerial(s, d, INFINITY, in, tr);
                sky_atmo_hemisphere_read(h, d, sky_rgb);
                double rel = fabs(luminance(in) / luminance(sky_rgb) - 1.0);
                worst_end = fmax(worst_end, rel);
                CHECK(rel <= 0.03 && tr[1] < 0.8, "%s, sun %.0f, view el %.1f az %+.0f from the sun: at infinity "
                      "%.4g kcd/m^2 (transmittance %.3g), the sky drawn there %.4g (%+.1f %%, limit 3 %%)",
                      test_path_names[p], suns[k], views[v][0], views[v][1], luminance(in), tr[1], luminance(sky_rgb),
                      100.0 * (luminance(in) / luminance(sky_rgb) - 1.0));
            }
        }
        sky_atmo_hemisphere_destroy(h);
    }
    NOTE("at infinity the light is within %.2f %% of the rendered sky", 100.0 * worst_end);
}

/* Issue target: against the spectral reference (the default Earth, the
 * Hillaire path) along level and slant (30 deg) views of 1, 10 and 100
 * km toward, across and away from the sun: the light within 10 %, the
 * green transmittance within 10 % or 0.01. The reference's orders >= 2
 * are Monte Carlo: each view gets the paths that take its standard error
 * (sigma) to REF_REL_ERR, and the light's limit is widened by 2 sigma.
 * The multiple-scattering table carries three orders one by one (and
 * the first bounce's aureole to degree 4): Hillaire's isotropic orders
 * beyond the second were 25 % short near the ground under a low sun, and
 * the sun 5 degrees up with the view across its azimuth was 14-17 % off. */
#define REF_REL_ERR 0.015
#define REF_MAX_PATHS 16384.0
/* the reference's standard error relative to its light */
static double reference_sigma(const sky_ref_result *r)
{
    return r->luminance_std_err / fmax(luminance(r->rgb), 1e-12);
}
SLOW_TEST(aerial_against_reference)
{
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.gl_profile = SKY_GL_CORE33;
    cfg.atmosphere = SKY_ATMOSPHERE_HILLAIRE;
    char err[256] = "";
    sky_atmo_hemisphere *h = sky_atmo_hemisphere_create(&cfg, err, sizeof err);
    if (!h) {
        CHECK(0, "%s", err);
        return;
    }
    sky *s = sky_atmo_hemisphere_sky(h);
    sky_atmosphere_params earth;
    sky_atmosphere_get_preset(SKY_ATMOSPHERE_PRESET_EARTH, &earth);
    static const double suns[2] = {30.0, 5.0}, els[2] = {0.0, 30.0}, azs[3] = {0.0, 90.0, 180.0};
    static const double km[3] = {1.0, 10.0, 100.0};
    double worst = 0.0, worst_tr = 0.0, worst_ref = 0.0;
    for (int k = 0; k < 2; k++) {
        double el, az;
        if (sky_atmo_hemisphere_render(h, suns[k], &el, &az, err, sizeof err)) {
            CHECK(0, "%s", err);
            break;
        }
        sky_lighting l;
        sky_get_lighting(s, &l);
        double sun[3] = {l.sun_direction[0], l.sun_direction[1], l.sun_direction[2]};
        for (int e = 0; e < 2; e++)
            for (int a = 0; a < 3; a++)
                for (int i = 0; i < 3; i++) {
                    double d[3], in[3], tr[3];
                    horizon_dir(els[e], az + azs[a], d);
                    aerial(s, d, km[i] * 1000.0, in, tr);
                    sky_ref_options o;
                    memset(&o, 0, sizeof o);
                    o.paths = 384;
                    o.max_distance_km = km[i];
                    sky_ref_result r;
                    if (sky_ref_radiance(&earth, 0.0, d, sun, &o, &r)) {
                        CHECK(0, "the reference failed");
                        continue;
                    }
                    /* A dim view's Monte Carlo orders carry a standard
                     * error of up to 8 % at 384 paths: more paths (the
                     * error falls as 1 / sqrt(paths)) until it is
                     * REF_REL_ERR, and the check allows two of it */
                    for (int tries = 0; tries < 3; tries++) {
                        double rel_err = reference_sigma(&r);
                        if (rel_err <= REF_REL_ERR || o.paths >= REF_MAX_PATHS) break;
                        double more = 1.3 * o.paths * (rel_err / REF_REL_ERR) * (rel_err / REF_REL_ERR);
                        o.paths = (int)fmin(ceil(more), REF_MAX_PATHS);
                        if (sky_ref_radiance(&earth, 0.0, d, sun, &o, &r)) break;
                    }
                    double sigma = reference_sigma(&r);
                    worst_ref = fmax(worst_ref, sigma);
                    double rel = luminance(in) / luminance(r.rgb) - 1.0;
                    double dt = tr[1] - r.transmittance_rgb[1];
                    worst = fmax(worst, fabs(rel));
                    worst_tr = fmax(worst_tr, fabs(dt));
                    if (i == 0 || fabs(rel) > 0.05)
                        NOTE("sun %.0f, view el %.0f az %+.0f from the sun, %.0f km: %.4g kcd/m^2, reference %.4g "
                             "+- %.1f %% (%+.1f %%); transmittance %.4f, reference %.4f",
                             suns[k], els[e], azs[a], km[i], luminance(in), luminance(r.rgb), 100.0 * sigma,
                             100.0 * rel, tr[1], r.transmittance_rgb[1]);
                    double limit = 0.10 + 2.0 * sigma;
                    CHECK(fabs(rel) <= limit, "sun %.0f, view el %.0f az %+.0f, %.0f km: light %+.1f %% from the "
                          "reference (limit %.0f %%)", suns[k], els[e], azs[a], km[i], 100.0 * rel, 100.0 * limit);
                    CHECK(fabs(dt) <= fmax(0.01, 0.1 * r.transmittance_rgb[1]), "sun %.0f, view el %.0f az %+.0f, "
                          "%.0f km: transmittance %.4f, reference %.4f", suns[k], els[e], azs[a], km[i], tr[1],
                          r.transmittance_rgb[1]);
                }
    }
    NOTE("worst: light %.1f %%, green transmittance %.4f; the reference's standard error at most %.1f %%",
         100.0 * worst, worst_tr, 100.0 * worst_ref);
    CHECK(worst_ref <= 2.0 * REF_REL_ERR, "the reference's standard error reached %.1f %%", 100.0 * worst_ref);
    sky_atmo_hemisphere_destroy(h);
}

TEST(aerial_checks_its_input)
{
    fixture f;
    if (fixture_open(&f, SKY_GL_CORE33, NULL)) {
        CHECK(0, "no sky");
        return;
    }
    sky_aerial a;
    float d[3] = {0.0f, 0.1f, -1.0f}, zero[3] = {0, 0, 0}, nan3[3] = {NAN, 0, 1}, inf3[3] = {0, INFINITY, 0};
    CHECK(sky_get_aerial_perspective(NULL, d, 10.0f, &a) == SKY_ERR_INVALID_ARGUMENT, "a NULL sky is refused");
    CHECK(sky_get_aerial_perspective(f.s, NULL, 10.0f, &a) == SKY_ERR_INVALID_ARGUMENT, "a NULL direction");
    CHECK(sky_get_aerial_perspective(f.s, d, 10.0f, NULL) == SKY_ERR_INVALID_ARGUMENT, "a NULL output");
    CHECK(sky_get_aerial_perspective(f.s, zero, 10.0f, &a) == SKY_ERR_INVALID_ARGUMENT, "a zero direction");
    CHECK(sky_get_aerial_perspective(f.s, nan3, 10.0f, &a) == SKY_ERR_INVALID_ARGUMENT, "a NaN direction");
    CHECK(sky_get_aerial_perspective(f.s, inf3, 10.0f, &a) == SKY_ERR_INVALID_ARGUMENT, "an infinite direction");
    CHECK(sky_get_aerial_perspective(f.s, d, -1.0f, &a) == SKY_ERR_INVALID_ARGUMENT &&
              a.transmittance[1] == 1.0f && a.inscatter[1] == 0.0f,
          "a negative distance is refused, the output left the identity");
    CHECK(sky_get_aerial_perspective(f.s, d, NAN, &a) == SKY_ERR_INVALID_ARGUMENT, "a NaN distance is refused");
    CHECK(strstr(sky_last_error(f.s), "distance") != NULL, "the message names the distance: %s",
          sky_last_error(f.s));
    /* huge and infinite distances, straight up and straight down */
    float up[3] = {0, 1, 0}, down[3] = {0, -1, 0};
    float dist[3] = {1e30f, INFINITY, 3.0e38f};
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 2; k++) {
            sky_result r = sky_get_aerial_perspective(f.s, k ? down : up, dist[i], &a);
            int finite = 1;
            for (int c = 0; c < 3; c++)
                finite &= isfinite(a.inscatter[c]) && a.inscatter[c] >= 0.0f && a.transmittance[c] >= 0.0f &&
                          a.transmittance[c] <= 1.0f;
            CHECK(r == SKY_OK && finite, "%s at %g m: %g, %g", k ? "down" : "up", (double)dist[i], a.inscatter[1],
                  a.transmittance[1]);
        }
    CHECK(sky_aerial_bind(NULL, 1, 0) == SKY_ERR_INVALID_ARGUMENT, "bind: a NULL sky is refused");
    CHECK(sky_aerial_bind(f.s, 0, 0) == SKY_ERR_INVALID_ARGUMENT, "bind: program 0 is refused");
    CHECK(sky_aerial_bind(f.s, 1, -1) == SKY_ERR_INVALID_ARGUMENT, "bind: unit -1 is refused");
    CHECK(sky_aerial_bind(f.s, 1, 100000) == SKY_ERR_INVALID_ARGUMENT, "bind: unit 100000 is refused");
    CHECK(strlen(sky_aerial_glsl()) > 100 && strstr(sky_aerial_glsl(), "sky_aerial_apply"), "the snippet is there");
    fixture_close(&f);
}

/* Issue target: the GLSL snippet (GLSL 1.10 and 3.30) gives what the CPU
 * function gives: a host program that includes sky_aerial_glsl writes
 * the transmittance and the light per direction and distance into a
 * float framebuffer, in a Z-up world. The table's interpolation allows
 * 0.02 in transmittance and 6 % (or 1 % of the brightest) in light.
 * sky_aerial_bind leaves the host's program and active unit as found. */
enum { GLSL_DIRS = 12, GLSL_DISTS = 7 };
static void glsl_matches(sky_gl_profile profile, sky_weather_state weather)
{
    int core = profile == SKY_GL_CORE33;
    char name[64];
    snprintf(name, sizeof name, "%s%s%s", core ? "CORE33" : "COMPAT20", weather ? ", " : "",
             weather ? sky_weather_name(weather) : "");
    static const float zup[9] = {1, 0, 0, 0, 0, 1, 0, -1, 0};
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    memcpy(cfg.horizon_to_world, zup, sizeof zup);
    cfg.atmosphere = SKY_ATMOSPHERE_HILLAIRE;
    fixture f;
    if (fixture_open_sized(&f, GLSL_DIRS * GLSL_DISTS, 2, 1, profile, &cfg)) {
        CHECK(0, "%s: no sky", name);
        return;
    }
    sky_params p = sky_default_params();
    p.time = 0.3f; /* a morning sun, some 20 degrees up */
    sky_set_params(f.s, &p);
    sky_update(f.s, 0.0);
    static const double els[3] = {0.5, 4.0, 25.0}, azs[4] = {0.0, 50.0, 100.0, 170.0};
    static const float dists[GLSL_DISTS] = {30.0f, 400.0f, 2500.0f, 9000.0f, 30000.0f, 70000.0f, 4e5f};
    sky_lighting l;
    sky_get_lighting(f.s, &l);
    /* the sun's azimuth in the horizon frame (Z-up world: horizon y is world z) */
    double sun_az = atan2(l.sun_direction[0], l.sun_direction[1]) * 180.0 / M_PI;
    /* The table's 8-bit steps are steps of the clear air's light, which a
     * weather only scales down (its own term is exact in both): the floor
     * of the light's tolerance is the clear air's brightest. */
    double brightest = 0.0;
    for (int i = 0; i < GLSL_DIRS; i++)
        for (int k = 0; k < GLSL_DISTS; k++) {
            double h[3];
            horizon_dir(els[i / 4], sun_az + azs[i % 4], h);
            float w[3] = {(float)h[0], (float)-h[2], (float)h[1]}; /* horizon -> Z-up world */
            sky_aerial a;
            sky_get_aerial_perspective(f.s, w, dists[k], &a);
            for (int c = 0; c < 3; c++) brightest = fmax(brightest, a.inscatter[c]);
        }
    if (weather) { /* its deck and haze over the table, in the shader and on the CPU alike */
        sky_weather w;
        sky_weather_preset(weather, &w);
        CHECK(sky_set_weather(f.s, &w, 0.0) == SKY_OK, "%s: %s", name, sky_last_error(f.s));
    }
    sky_update(f.s, 0.0);
    const char *body = "uniform vec3 dir;\nuniform float dist;\nvoid main() {\n"
                       "  vec3 t, l;\n  sky_aerial(dir, dist, t, l);\n"
                       "  FRAG = vec4(gl_FragCoord.y < 1.0 ? t : l, 1.0);\n}\n";
    GLuint prog = test_snippet_program(core, sky_aerial_glsl(), body), vao, buf;
    test_fullscreen_triangle(core, &vao, &buf);
    /* the host's own program and unit before the bind */
    GLuint other = test_host_program(core);
    glUseProgram(other);
    glActiveTexture(GL_TEXTURE2);
    CHECK(sky_aerial_bind(f.s, prog, 5) == SKY_OK, "%s: bind: %s", name, sky_last_error(f.s));
    GLint now_prog = 0, now_unit = 0, bound = 0;
    glGetIntegerv(GL_CURRENT_PROGRAM, &now_prog);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &now_unit);
    glActiveTexture(GL_TEXTURE5);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &bound);
    CHECK((GLuint)now_prog == other && now_unit == GL_TEXTURE2 && bound != 0,
          "%s: after the bind the program is %d (host's %u), the unit 0x%x (host's 0x%x), unit 5 holds %d", name,
          now_prog, other, now_unit, GL_TEXTURE2, bound);
    glUseProgram(prog);
    float cpu[GLSL_DIRS * GLSL_DISTS][6];
    for (int i = 0; i < GLSL_DIRS; i++) {
        double h[3];
        horizon_dir(els[i / 4], sun_az + azs[i % 4], h);
        float w[3] = {(float)h[0], (float)-h[2], (float)h[1]}; /* horizon -> Z-up world */
        glUniform3fv(glGetUniformLocation(prog, "dir"), 1, w);
        for (int k = 0; k < GLSL_DISTS; k++) {
            int x = i * GLSL_DISTS + k;
            glUniform1f(glGetUniformLocation(prog, "dist"), dists[k]);
            glViewport(x, 0, 1, 2);
            glDrawArrays(GL_TRIANGLES, 0, 3);
            sky_aerial a;
            sky_get_aerial_perspective(f.s, w, dists[k], &a);
            for (int c = 0; c < 3; c++) {
                cpu[x][c] = a.transmittance[c];
                cpu[x][3 + c] = a.inscatter[c];
            }
        }
    }
    sky_osmesa_finish(&f.ctx);
    const float *px = f.ctx.pixels;
    int w = GLSL_DIRS * GLSL_DISTS;
    double worst_t = 0.0, worst_l = 0.0;
    for (int x = 0; x < w; x++)
        for (int c = 0; c < 3; c++) {
            double gt = px[4 * x + c], gl_ = px[4 * (w + x) + c], ct = cpu[x][c], cl = cpu[x][3 + c];
            double dl = fabs(gl_ - cl) / fmax(cl, 1e-30);
            worst_t = fmax(worst_t, fabs(gt - ct));
            if (cl > 0.01 * brightest) worst_l = fmax(worst_l, dl);
            CHECK(fabs(gt - ct) <= 0.02 && (fabs(gl_ - cl) <= 0.06 * cl || fabs(gl_ - cl) <= 0.01 * brightest),
                  "%s: direction %d at %.0f m, channel %d: shader T %.4f light %.4g, CPU T %.4f light %.4g", name,
                  x / GLSL_DISTS, (double)dists[x % GLSL_DISTS], c, gt, gl_, ct, cl);
        }
    NOTE("%s: shader against CPU: transmittance within %.4f, light within %.1f %%", name, worst_t,
         100.0 * worst_l);
    glUseProgram(0);
    glDeleteProgram(prog);
    glDeleteProgram(other);
    test_fullscreen_free(vao, buf);
    fixture_close(&f);
}

TEST(aerial_glsl_matches_cpu)
{
    glsl_matches(SKY_GL_CORE33, SKY_WEATHER_CLEAR);
    glsl_matches(SKY_GL_COMPAT20, SKY_WEATHER_CLEAR);
    glsl_matches(SKY_GL_CORE33, SKY_WEATHER_RAIN);
}

/* Issue target: Hillaire's froxel volume (CORE33): each froxel is the air
 * between the observer and (k + 1) km along its column's view, the CPU
 * function's within 5 % in light (or 1 % of the volume's brightest) and
 * 0.01 in mean transmittance, by day, at sunset and in the rain; the host's state
 * back; refused off the Hillaire paths and in COMPAT20. */
TEST(aerial_froxels_match_cpu)
{
    enum { N = 32 };
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.atmosphere = SKY_ATMOSPHERE_HILLAIRE;
    fixture f;
    if (fixture_open_sized(&f, 320, 180, 0, SKY_GL_CORE33, &cfg)) {
        CHECK(0, "no sky");
        return;
    }
    float view[16], proj[16];
    sky_cli_camera_at(120.0, 6.0, 60.0, 320, 180, view, proj);
    static float volume[N * N * N * 4];
    /* by day, at sunset, and by day in the rain (its deck and haze) */
    static const float times[3] = {0.3f, 0.245f, 0.3f};
    double worst_l = 0.0, worst_t = 0.0;
    for (int q = 0; q < 3; q++) {
        sky_params p = sky_default_params();
        p.time = times[q];
        sky_set_params(f.s, &p);
        if (q == 2) {
            sky_weather rain;
            CHECK(sky_weather_preset(SKY_WEATHER_RAIN, &rain) == SKY_OK && sky_set_weather(f.s, &rain, 0.0) == SKY_OK,
                  "rain: %s", sky_last_error(f.s));
        }
        sky_update(f.s, 0.0);
        GLuint host_prog = test_host_program(1), tex = 0;
        glUseProgram(host_prog);
        glViewport(7, 9, 100, 50);
        CHECK(sky_aerial_froxels(f.s, view, proj, &tex) == SKY_OK && tex != 0, "froxels: %s", sky_last_error(f.s));
        GLint prog = 0, vp[4], fbo = -1;
        glGetIntegerv(GL_CURRENT_PROGRAM, &prog);
        glGetIntegerv(GL_VIEWPORT, vp);
        glGetIntegerv(GL_FRAMEBUFFER_BINDING, &fbo);
        CHECK((GLuint)prog == host_prog && vp[0] == 7 && vp[3] == 50 && fbo == 0,
              "the host's program %d (%u), viewport %d .. %d, framebuffer %d", prog, host_prog, vp[0], vp[3], fbo);
        glUseProgram(0);
        glDeleteProgram(host_prog);
        glBindTexture(GL_TEXTURE_3D, tex);
        glGetTexImage(GL_TEXTURE_3D, 0, GL_RGBA, GL_FLOAT, volume);
        glBindTexture(GL_TEXTURE_3D, 0);
        double brightest = 0.0;
        for (int i = 0; i < N * N * N * 4; i++)
            if (i % 4 != 3) brightest = fmax(brightest, volume[i]);
        static const int cols[4] = {2, 11, 20, 29}, slices[4] = {0, 3, 9, 31};
        for (int a = 0; a < 4; a++)
            for (int b = 0; b < 4; b++)
                for (int c = 0; c < 4; c++) {
                    int i = cols[a], j = cols[b], k = slices[c];
                    /* the column's view in the eye frame, then the world's (view's rows) */
                    double e[3] = {((i + 0.5) / N * 2.0 - 1.0) / proj[0], ((j + 0.5) / N * 2.0 - 1.0) / proj[5], -1.0};
                    float w[3];
                    for (int r = 0; r < 3; r++) w[r] = (float)(view[r * 4] * e[0] + view[r * 4 + 1] * e[1] + view[r * 4 + 2] * e[2]);
                    sky_aerial air;
                    sky_get_aerial_perspective(f.s, w, (k + 1) * 1000.0f, &air);
                    const float *v = &volume[4 * ((k * N + j) * N + i)];
                    double t_cpu = (air.transmittance[0] + air.transmittance[1] + air.transmittance[2]) / 3.0;
                    worst_t = fmax(worst_t, fabs(v[3] - t_cpu));
                    CHECK(fabs(v[3] - t_cpu) <= 0.01, "time %.3f, froxel %d %d %d: transmittance %.4f, CPU %.4f",
                          (double)times[q], i, j, k, v[3], t_cpu);
                    for (int ch = 0; ch < 3; ch++) {
                        double d = fabs(v[ch] - air.inscatter[ch]);
                        if (air.inscatter[ch] > 0.01 * brightest) worst_l = fmax(worst_l, d / air.inscatter[ch]);
                        CHECK(d <= 0.05 * air.inscatter[ch] || d <= 0.01 * brightest, "time %.3f, froxel %d %d %d, "
                              "channel %d: %.4g kcd/m^2, CPU %.4g", (double)times[q], i, j, k, ch, v[ch],
                              air.inscatter[ch]);
                    }
                }
    }
    NOTE("froxels against the CPU: light within %.1f %%, mean transmittance within %.4f", 100.0 * worst_l, worst_t);
    unsigned tex = 1;
    CHECK(sky_aerial_froxels(f.s, NULL, proj, &tex) == SKY_ERR_INVALID_ARGUMENT && tex == 0, "a NULL view");
    float flat[16] = {0};
    CHECK(sky_aerial_froxels(f.s, view, flat, &tex) == SKY_ERR_INVALID_ARGUMENT, "a singular projection");
    fixture_close(&f);
    fixture g;
    if (fixture_open_sized(&g, 64, 64, 0, SKY_GL_COMPAT20, &cfg) == 0) {
        CHECK(sky_aerial_froxels(g.s, view, proj, &tex) == SKY_ERR_UNSUPPORTED, "COMPAT20 refuses the volume");
        fixture_close(&g);
    }
}
