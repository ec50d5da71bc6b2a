/*
 * An engine's conventions (sky.h, Conventions): handedness stated by
 * horizon_to_world, the warning when it is not, and the version a host
 * compiled against.
 */
#include "test.h"
#include "sky_internal.h"
#include "cli.h"

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* One LDR frame of a default sky (cover 0.4, mid-morning, the sun in view)
 * drawn with view and proj into a 96x64 buffer; its bytes into out. */
static sky_result frame(const float h2w[9], const float view[16], const float proj[16], unsigned char *out)
{
    enum { W = 96, H = 64 };
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    if (h2w) memcpy(cfg.horizon_to_world, h2w, sizeof cfg.horizon_to_world);
    fixture f;
    if (fixture_open_sized(&f, W, H, 0, SKY_GL_AUTO, &cfg)) return SKY_ERR_GL;
    sky_params p = sky_default_params();
    p.cover = 0.4f;
    p.time = 0.4f;
    sky_set_params(f.s, &p);
    sky_result rc = sky_draw(f.s, view, proj);
    sky_osmesa_finish(&f.ctx);
    memcpy(out, f.ctx.pixels, (size_t)W * H * 4);
    fixture_close(&f);
    return rc;
}

/* S = diag(1, 1, -1, 1): an engine's left-handed matrices are S V S and
 * P S of a right-handed host's V and P looking the same way (sky.h). */
TEST(conventions_left_handed_host)
{
    enum { W = 96, H = 64, N = W * H * 4 };
    scene sc = scene_default();
    sc.w = W;
    sc.h = H;
    sc.yaw = 120.0; /* toward the morning sun */
    sc.pitch = 25.0;
    float view[16], proj[16], lh_view[16], lh_proj[16];
    scene_camera(&sc, view, proj);
    const float s[4] = {1.0f, 1.0f, -1.0f, 1.0f};
    for (int col = 0; col < 4; col++)
        for (int row = 0; row < 4; row++) {
            lh_view[col * 4 + row] = s[row] * view[col * 4 + row] * s[col];
            lh_proj[col * 4 + row] = proj[col * 4 + row] * s[col];
        }
    static unsigned char right[N], left[N], mirrored[N];
    const float reflect[9] = {1, 0, 0, 0, 1, 0, 0, 0, -1};
    sky_result r0 = frame(NULL, view, proj, right);
    sky_result r1 = frame(reflect, lh_view, lh_proj, left);
    sky_result r2 = frame(NULL, lh_view, lh_proj, mirrored);
    CHECK(r0 == SKY_OK && r1 == SKY_OK, "right-handed %d, left-handed with a reflection %d: plain success", r0, r1);
    int worst = 0, differ = 0;
    for (int i = 0; i < N; i++) {
        if (i % 4 == 3) continue;
        int d = abs(right[i] - left[i]);
        worst = d > worst ? d : worst;
        differ += abs(right[i] - mirrored[i]) > 8;
    }
    NOTE("left-handed host with a reflecting horizon_to_world: worst byte %d off the right-handed frame; without "
         "it %d bytes differ by more than 8 and the result is %d",
         worst, differ, r2);
    CHECK(worst <= 1, "a left-handed host stating its handedness sees the right-handed host's sky (%d)", worst);
    CHECK(r2 == SKY_WARN_MIRRORED && differ > N / 20, "without the reflection: a mirrored sky and the warning (%d)", r2);
    /* a matrix that is neither rotation nor reflection is refused, by name */
    const float skew[9] = {1, 0, 0, 0.3f, 1, 0, 0, 0, 1};
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    memcpy(cfg.horizon_to_world, skew, sizeof skew);
    cfg.get_proc_address = sky_osmesa_loader();
    char err[256];
    CHECK(sky_create(&cfg, err, sizeof err) == NULL && strstr(err, "horizon_to_world"),
          "a skewed horizon_to_world is refused naming the field: %s", err);
}

/* sky_version() is what sky.h says; the shared library's soname and the
 * installed sky.pc follow it. */
TEST(conventions_version_everywhere)
{
    unsigned v = sky_version();
    CHECK(v == ((unsigned)SKY_VERSION_MAJOR << 16 | (unsigned)SKY_VERSION_MINOR << 8 | (unsigned)SKY_VERSION_PATCH),
          "sky_version 0x%06x matches the header", v);
    char want[64], cmd[1024], out[4096], bin[512];
    const char *dir = getenv("SKY_BIN");
    snprintf(bin, sizeof bin, "%s", dir ? dir : "build/bin");
    if (SKY_VERSION_MAJOR == 0)
        snprintf(want, sizeof want, "libsky.so.0.%d", SKY_VERSION_MINOR);
    else
        snprintf(want, sizeof want, "libsky.so.%d", SKY_VERSION_MAJOR);
    snprintf(cmd, sizeof cmd, "readelf -d %s/../lib/libsky.so 2>&1 | grep SONAME", bin);
    int rc = run_command(cmd, out, sizeof out);
    NOTE("%s", out);
    CHECK(rc == 0 && strstr(out, want), "the shared library's soname is %s", want);
    snprintf(cmd, sizeof cmd,
             "d=$(mktemp -d) && make -s install PREFIX=/usr DESTDIR=$d >/dev/null 2>&1 && "
             "PKG_CONFIG_SYSROOT_DIR=$d PKG_CONFIG_PATH=$d/usr/lib/pkgconfig pkg-config --modversion sky; "
             "r=$?; rm -rf $d; exit $r");
    char version[64];
    snprintf(version, sizeof version, "%d.%d.%d", SKY_VERSION_MAJOR, SKY_VERSION_MINOR, SKY_VERSION_PATCH);
    rc = run_command(cmd, out, sizeof out);
    NOTE("installed sky.pc says %s", out);
    CHECK(rc == 0 && strstr(out, version), "sky.pc's version is %s", version);
}

/* A host's opaque white quad over the left half of the frame at clip z 0.5
 * (between near and far in every convention), writing depth. */
static void host_quad(void)
{
    GLuint prog = test_host_program(1);
    static const float quad[12] = {-1, -1, 0.5f, 0, -1, 0.5f, -1, 1, 0.5f, 0, 1, 0.5f};
    GLuint vao, buf;
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glGenBuffers(1, &buf);
    glBindBuffer(GL_ARRAY_BUFFER, buf);
    glBufferData(GL_ARRAY_BUFFER, sizeof quad, quad, GL_STATIC_DRAW);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, (const void *)0);
    glEnableVertexAttribArray(0);
    glUseProgram(prog);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glUseProgram(0);
    glDeleteProgram(prog);
    glDeleteBuffers(1, &buf);
    glDeleteVertexArrays(1, &vao);
}

/* Drawn after the opaque scene in each depth convention, the sky keeps
 * the scene's pixels and fills the rest: depth cleared to 1 with LESS,
 * reversed-Z cleared to 0 with GREATER, and reversed-Z with a 0..1 clip
 * range where the context has glClipControl. */
TEST(conventions_sky_after_the_scene)
{
    enum { W = 64, H = 48 };
    static const sky_depth modes[3] = {SKY_DEPTH_FAR_ONE, SKY_DEPTH_FAR_ZERO, SKY_DEPTH_FAR_ZERO_CLIP01};
    static const char *const names[3] = {"far at 1", "reversed-Z", "reversed-Z, 0..1 clip"};
    for (int k = 0; k < 3; k++) {
        sky_config cfg;
        memset(&cfg, 0, sizeof cfg);
        cfg.depth = modes[k];
        fixture f;
        if (fixture_open_sized(&f, W, H, 0, SKY_GL_CORE33, &cfg)) {
            CHECK(0, "fixture");
            return;
        }
        void (*clip_control)(GLenum, GLenum) = (void (*)(GLenum, GLenum))OSMesaGetProcAddress("glClipControl");
        if (k == 2 && !clip_control) {
            NOTE("no glClipControl here: %s skipped", names[k]);
            fixture_close(&f);
            continue;
        }
        if (k == 2) clip_control(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
        glViewport(0, 0, W, H);
        glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
        glClearDepth(k == 0 ? 1.0 : 0.0);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(k == 0 ? GL_LESS : GL_GREATER);
        host_quad();
        float view[16], proj[16];
        sky_cli_camera_at(180.0, 20.0, 60.0, W, H, view, proj);
        sky_result rc = sky_draw(f.s, view, proj);
        CHECK(rc == SKY_OK, "%s: %s", names[k], sky_last_error(f.s));
        sky_osmesa_finish(&f.ctx);
        const unsigned char *px = f.ctx.pixels;
        int scene_kept = 0, sky_drawn = 0;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                const unsigned char *p = px + 4 * (y * W + x);
                int white = p[0] == 255 && p[1] == 255 && p[2] == 255;
                if (x < W / 2) scene_kept += white;
                else sky_drawn += !white && (p[0] | p[1] | p[2]) != 0;
            }
        NOTE("%s: %d of %d scene pixels kept, %d of %d others the sky's", names[k], scene_kept, W * H / 2, sky_drawn,
             W * H / 2);
        CHECK(scene_kept == W * H / 2 && sky_drawn == W * H / 2, "%s: the sky behind the scene, everywhere else",
              names[k]);
        if (k == 2) clip_control(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
        glDisable(GL_DEPTH_TEST);
        fixture_close(&f);
    }
}
