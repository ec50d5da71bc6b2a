/*
 * The display stages for HDR hosts (issue "Dusk and night"): a host
 * program that includes sky_display_glsl and is bound by sky_display_bind
 * shows the sky's HDR frame as the library's own 8-bit frame shows it, by
 * day, at dusk (the partial adaptation and the first of the blue shift) and
 * at night (all of it), in both desktop profiles.
 */
#define GL_GLEXT_PROTOTYPES 1
#include "test.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { W = 16, H = 9 };

/* One frame's HDR and 8-bit pixels against the host program's. */
static double worst_difference(sky_gl_profile profile, float time, double *brightest)
{
    int core = profile == SKY_GL_CORE33;
    scene sc = scene_default();
    sc.cfg.features = SKY_SUN | SKY_MOON;
    sc.cfg.dome_divisor = 1; /* every pixel, as the HDR frame draws it */
    sc.params.time = time;
    sc.params.cover = 0.0f;
    sc.w = W;
    sc.h = H;
    if (time < 0.0f) { /* the night: a full moon 67 degrees up, looking north 30 degrees up */
        sc.has_observer = 1;
        memset(&sc.observer, 0, sizeof sc.observer);
        sc.observer.latitude_deg = 45.0;
        sc.observer.julian_day_utc = sky_julian_day(2024, 1, 26, 0, 0, 0.0);
        sc.yaw = 0.0;
        sc.pitch = 30.0;
    }
    image hdr, ldr;
    if (render_scene(&sc, 1, profile, &hdr) || render_scene(&sc, 0, profile, &ldr)) return -1.0;
    *brightest = 0.0;
    for (int i = 0; i < 3 * W * H; i++) *brightest = fmax(*brightest, ldr.px[i] * 255.0);
    /* the host: an HDR sky in its own float context, a program with the
     * snippet drawing one radiance into one pixel at a time */
    sky_config cfg = sc.cfg;
    cfg.output = SKY_OUTPUT_HDR;
    fixture f;
    double worst = -1.0;
    if (fixture_open_sized(&f, W, H, 1, profile, &cfg)) goto done;
    if (sc.has_observer) sky_set_observer(f.s, &sc.observer);
    sky_set_params(f.s, &sc.params);
    sky_update(f.s, 0.0);
    const char *body = "uniform vec3 radiance;\nvoid main() { FRAG = vec4(sky_display(radiance), 1.0); }\n";
    GLuint prog = test_snippet_program(core, sky_display_glsl(), body), vao, buf;
    test_fullscreen_triangle(core, &vao, &buf);
    glUseProgram(0);
    CHECK(sky_display_bind(f.s, prog) == SKY_OK, "bind: %s", sky_last_error(f.s));
    GLint now = -1;
    glGetIntegerv(GL_CURRENT_PROGRAM, &now);
    CHECK(now == 0, "sky_display_bind left program %d current, not the host's 0", now);
    glUseProgram(prog);
    GLint at = glGetUniformLocation(prog, "radiance");
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            glUniform3fv(at, 1, hdr.px + 3 * (y * W + x));
            glViewport(x, H - 1 - y, 1, 1); /* the images' rows are top first */
            glDrawArrays(GL_TRIANGLES, 0, 3);
        }
    float out[W * H * 4];
    glReadPixels(0, 0, W, H, GL_RGBA, GL_FLOAT, out);
    worst = 0.0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            for (int c = 0; c < 3; c++) {
                double mine = out[4 * ((H - 1 - y) * W + x) + c], theirs = ldr.px[3 * (y * W + x) + c];
                worst = fmax(worst, fabs(mine - theirs) * 255.0);
            }
    test_fullscreen_free(vao, buf);
    glDeleteProgram(prog);
    fixture_close(&f);
done:
    image_free(&hdr);
    image_free(&ldr);
    return worst;
}

/* The library's 8-bit frame is the snippet's values plus a dither of half
 * a step either way, quantised: within 1.5 steps of 255. */
TEST(display_glsl_matches_ldr)
{
    /* day, the sun 9 degrees down, a full-moon night (the observer's date) */
    static const float times[3] = {0.3f, 0.78f, -1.0f};
    static const char *const names[3] = {"day", "dusk", "full-moon night"};
    static const sky_gl_profile profiles[2] = {SKY_GL_CORE33, SKY_GL_COMPAT20};
    for (int g = 0; g < 2; g++)
        for (int t = 0; t < 3; t++) {
            double brightest = 0.0, worst = worst_difference(profiles[g], times[t], &brightest);
            NOTE("%s, %s: the host's sky_display within %.2f of 255 of the 8-bit frame (brightest %.0f)",
                 g ? "compat" : "core", names[t], worst, brightest);
            CHECK(worst >= 0.0 && worst <= 1.5, "%s, %s: %.2f of 255 apart", g ? "compat" : "core", names[t], worst);
            CHECK(brightest >= 20.0, "%s, %s: a frame too dark to compare (brightest %.0f)", g ? "compat" : "core",
                  names[t], brightest);
        }
}

TEST(display_bind_checks)
{
    CHECK(sky_display_bind(NULL, 1) == SKY_ERR_INVALID_ARGUMENT, "a NULL sky is refused");
    fixture f;
    if (fixture_open(&f, SKY_GL_AUTO, NULL)) {
        CHECK(0, "fixture");
        return;
    }
    CHECK(sky_display_bind(f.s, 0) == SKY_ERR_INVALID_ARGUMENT, "program 0 is refused");
    /* a name that is no program: refused, and no GL error left behind for
     * the host (glUseProgram would have left GL_INVALID_VALUE) */
    while (glGetError() != GL_NO_ERROR) {
    }
    CHECK(sky_display_bind(f.s, 54321u) == SKY_ERR_INVALID_ARGUMENT && strstr(sky_last_error(f.s), "54321"),
          "a name that is no program is refused by name: %s", sky_last_error(f.s));
    GLenum left = glGetError();
    CHECK(left == GL_NO_ERROR, "no GL error left pending (0x%04x)", left);
    CHECK(strstr(sky_display_glsl(), "vec3 sky_display(vec3") != NULL, "the snippet defines sky_display");
    fixture_close(&f);
}
