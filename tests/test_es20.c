/*
 * The ES20 profile (OpenGL ES 2.0 / WebGL 1) on a native ES 2.0 context:
 * Mesa's surfaceless EGL with MESA_GLES_VERSION_OVERRIDE=2.0, so the
 * context says "OpenGL ES 2.0" and GLSL ES 1.00 as real ES 2.0 hardware
 * does. Every preset's picture against COMPAT20's, with the optional
 * extensions offered and withheld (a WebGL 1 device lacks what llvmpipe
 * offers); every atmosphere path under every layer; the host's state, set
 * by a client outside the library, the same after every public call.
 */
#include "test.h"
#include "cli.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>


/* A native ES 2.0 context, and one without any of the extensions the
 * profile can use (Mesa cannot withhold OES_vertex_array_object, which the
 * profile does not use). */
#define ES2 "MESA_GLES_VERSION_OVERRIDE=2.0 "
#define ES2_BARE                                                                                   \
    ES2 "MESA_EXTENSION_OVERRIDE='-GL_OES_standard_derivatives -GL_OES_texture_npot "             \
        "-GL_OES_texture_float -GL_OES_texture_float_linear -GL_OES_texture_half_float "          \
        "-GL_EXT_shader_texture_lod -GL_OES_element_index_uint' "

static const char *const scenes[] = {"--preset noon",     "--preset sunset --yaw 270 --pitch 10",
                                     "--preset starry",   "--preset overcast",
                                     "--preset moonlit",  "--preset eclipse",
                                     "--preset solar-eclipse", "--preset minimal"};

/* Renders the arguments' scene through env and --gl gl into png; returns the exit status
 * with the output (stats included) in out. */
static int render(const char *env, const char *gl, const char *args, const char *png, char *out, size_t out_len)
{
    char bin[512], cmd[2048];
    bin_path("sky-render", bin, sizeof bin);
    snprintf(cmd, sizeof cmd, "%s%s --size 320x180 %s --gl %s --out %s --stats 2>&1", env, bin, args, gl, png);
    return run_command(cmd, out, out_len);
}

/* PSNR of the arguments' scene under env + es20 against COMPAT20; -1 when a render or a
 * read failed (reported). */
static double es_against_compat(const char *env, const char *args, const char *what)
{
    char es_png[512], compat_png[512], out[8192];
    tmp_path("es.png", es_png, sizeof es_png);
    tmp_path("compat.png", compat_png, sizeof compat_png);
    int rc1 = render("", "compat", args, compat_png, out, sizeof out);
    CHECK(rc1 == 0, "%s: COMPAT20 render exits 0: %s", args, out);
    int rc2 = render(env, "es20", args, es_png, out, sizeof out);
    CHECK(rc2 == 0, "%s (%s): ES20 render exits 0: %s", args, what, out);
    CHECK(strstr(out, "\"profile\":\"es20\"") != NULL, "--stats reports the profile: %.200s", out);
    CHECK(strstr(out, "\"gl_version\":\"OpenGL ES 2.0") != NULL, "the context is ES 2.0: %.120s", out);
    double psnr = -1.0;
    image a, b;
    if (rc1 == 0 && rc2 == 0 && !image_load_png(es_png, &a)) {
        if (!image_load_png(compat_png, &b)) {
            psnr = image_psnr(&a, &b);
            image_free(&b);
        }
        image_free(&a);
    }
    remove(es_png);
    remove(compat_png);
    return psnr;
}

SLOW_TEST(es20_presets_match_compat20)
{
    for (size_t k = 0; k < sizeof scenes / sizeof scenes[0]; k++) {
        double psnr = es_against_compat(ES2, scenes[k], "every extension");
        NOTE("%s: ES20 vs COMPAT20 PSNR %.1f dB", scenes[k], psnr);
        CHECK(psnr >= 40.0, "%s: ES20 must match COMPAT20 within PSNR 40 dB (%.1f)", scenes[k], psnr);
    }
}

/* The weather's shading (deck, haze, the flash) under GLSL ES 1.00, with
 * and without the extensions: a storm at a flash and fog against COMPAT20. */
SLOW_TEST(es20_weather_matches_compat20)
{
    static const char *const weathers[] = {"--time 0.5 --weather fog", "--time 0.95 --weather storm --seconds 11.21",
                                           "--time 0.5 --weather showers"};
    for (size_t k = 0; k < sizeof weathers / sizeof weathers[0]; k++)
        for (int bare = 0; bare < 2; bare++) {
            double psnr = es_against_compat(bare ? ES2_BARE : ES2, weathers[k], bare ? "no extensions" : "every one");
            NOTE("%s%s: ES20 vs COMPAT20 PSNR %.1f dB", weathers[k], bare ? " (bare)" : "", psnr);
            CHECK(psnr >= 40.0, "%s: ES20 must match COMPAT20 within PSNR 40 dB (%.1f)", weathers[k], psnr);
        }
}

/* Without OES_standard_derivatives the clouds' footprint fade and the
 * sun's edge use an estimate from the pixel's angle; without
 * OES_texture_npot the dome's image is a power of two. */
SLOW_TEST(es20_without_optional_extensions)
{
    for (size_t k = 0; k < sizeof scenes / sizeof scenes[0]; k++) {
        double psnr = es_against_compat(ES2_BARE, scenes[k], "no extensions");
        NOTE("%s: bare ES20 vs COMPAT20 PSNR %.1f dB", scenes[k], psnr);
        CHECK(psnr >= 40.0, "%s: bare ES20 must match COMPAT20 within PSNR 40 dB (%.1f)", scenes[k], psnr);
    }
}

/* Every path's programs with every layer build and draw under GLSL ES
 * 1.00, with and without the extensions, and agree with COMPAT20. */
SLOW_TEST(es20_every_path_with_every_layer)
{
    static const char *const paths[] = {"gradient", "preetham", "rayleigh", "hillaire", "blend",
                                        "blend --blend-partner preetham"};
    char args[512];
    for (size_t p = 0; p < sizeof paths / sizeof paths[0]; p++)
        for (int bare = 0; bare < 2; bare++) {
            snprintf(args, sizeof args,
                     "--time 0.3 --cover 0.5 --atmosphere %s --features "
                     "clouds,sun,moon,flicker,stars,starmap,eclipse,solar-eclipse,planets,airglow,zodiacal",
                     paths[p]);
            double psnr = es_against_compat(bare ? ES2_BARE : ES2, args, bare ? "no extensions" : "every extension");
            NOTE("--atmosphere %s%s: ES20 vs COMPAT20 PSNR %.1f dB", paths[p], bare ? " (no extensions)" : "", psnr);
            CHECK(psnr >= 40.0, "--atmosphere %s%s: PSNR %.1f dB", paths[p], bare ? " without extensions" : "", psnr);
        }
}

/* ---- the host's state, from a client outside the library ---------------------------- */

/* The ES 2.0 entry points the client uses, through EGL. */
typedef struct es_api {
    void (*GetIntegerv)(GLenum, GLint *);
    void (*GetFloatv)(GLenum, GLfloat *);
    void (*GetBooleanv)(GLenum, GLboolean *);
    GLboolean (*IsEnabled)(GLenum);
    void (*Enable)(GLenum);
    void (*ActiveTexture)(GLenum);
    void (*GenTextures)(GLsizei, GLuint *);
    void (*BindTexture)(GLenum, GLuint);
    void (*TexImage2D)(GLenum, GLint, GLint, GLsizei, GLsizei, GLint, GLenum, GLenum, const void *);
    void (*GenBuffers)(GLsizei, GLuint *);
    void (*BindBuffer)(GLenum, GLuint);
    void (*BufferData)(GLenum, GLsizeiptr, const void *, GLenum);
    void (*VertexAttribPointer)(GLuint, GLint, GLenum, GLboolean, GLsizei, const void *);
    void (*EnableVertexAttribArray)(GLuint);
    void (*GetVertexAttribiv)(GLuint, GLenum, GLint *);
    void (*GetVertexAttribPointerv)(GLuint, GLenum, void **);
    void (*GenFramebuffers)(GLsizei, GLuint *);
    void (*BindFramebuffer)(GLenum, GLuint);
    void (*FramebufferTexture2D)(GLenum, GLenum, GLenum, GLuint, GLint);
    void (*Viewport)(GLint, GLint, GLsizei, GLsizei);
    void (*Scissor)(GLint, GLint, GLsizei, GLsizei);
    void (*ClearColor)(GLfloat, GLfloat, GLfloat, GLfloat);
    void (*BlendFuncSeparate)(GLenum, GLenum, GLenum, GLenum);
    void (*BlendEquation)(GLenum);
    void (*DepthFunc)(GLenum);
    void (*DepthMask)(GLboolean);
    void (*ColorMask)(GLboolean, GLboolean, GLboolean, GLboolean);
    void (*PixelStorei)(GLenum, GLint);
    void (*UseProgram)(GLuint);
    GLuint (*CreateProgram)(void);
    GLuint (*CreateShader)(GLenum);
    void (*ShaderSource)(GLuint, GLsizei, const char *const *, const GLint *);
    void (*CompileShader)(GLuint);
    void (*AttachShader)(GLuint, GLuint);
    void (*LinkProgram)(GLuint);
    void (*GetShaderiv)(GLuint, GLenum, GLint *);
    void (*GetShaderInfoLog)(GLuint, GLsizei, GLsizei *, char *);
    void (*GetProgramiv)(GLuint, GLenum, GLint *);
    GLint (*GetUniformLocation)(GLuint, const char *);
    void (*Uniform1f)(GLint, GLfloat);
    void (*Uniform3fv)(GLint, GLsizei, const GLfloat *);
    void (*BindAttribLocation)(GLuint, GLuint, const char *);
    void (*DrawArrays)(GLenum, GLint, GLsizei);
    void (*Disable)(GLenum);
    void (*ReadPixels)(GLint, GLint, GLsizei, GLsizei, GLenum, GLenum, void *);
    GLenum (*GetError)(void);
} es_api;

/* Stores gpa's pointer into the member of its own type (the two are the
 * same size: sky.h's sky_gl_proc is a function pointer). */
static int load_one(void *member, sky_get_proc_address_fn gpa, const char *name)
{
    sky_gl_proc p = gpa(name);
    memcpy(member, &p, sizeof p);
    return p != NULL;
}

static int es_load(es_api *gl, sky_get_proc_address_fn gpa)
{
#define LOAD(name) load_one(&gl->name, gpa, "gl" #name)
    return LOAD(GetIntegerv) && LOAD(GetFloatv) && LOAD(GetBooleanv) && LOAD(IsEnabled) && LOAD(Enable) &&
           LOAD(ActiveTexture) && LOAD(GenTextures) && LOAD(BindTexture) && LOAD(TexImage2D) && LOAD(GenBuffers) &&
           LOAD(BindBuffer) && LOAD(BufferData) && LOAD(VertexAttribPointer) && LOAD(EnableVertexAttribArray) &&
           LOAD(GetVertexAttribiv) && LOAD(GetVertexAttribPointerv) && LOAD(GenFramebuffers) &&
           LOAD(BindFramebuffer) && LOAD(FramebufferTexture2D) && LOAD(Viewport) && LOAD(Scissor) &&
           LOAD(ClearColor) && LOAD(BlendFuncSeparate) && LOAD(BlendEquation) && LOAD(DepthFunc) &&
           LOAD(DepthMask) && LOAD(ColorMask) && LOAD(PixelStorei) && LOAD(UseProgram) && LOAD(CreateProgram) &&
           LOAD(CreateShader) && LOAD(ShaderSource) && LOAD(CompileShader) && LOAD(AttachShader) &&
           LOAD(LinkProgram) && LOAD(GetShaderiv) && LOAD(GetShaderInfoLog) && LOAD(GetProgramiv) &&
           LOAD(GetUniformLocation) && LOAD(Uniform1f) && LOAD(Uniform3fv) && LOAD(BindAttribLocation) &&
           LOAD(DrawArrays) && LOAD(Disable) && LOAD(ReadPixels) && LOAD(GetError);
#undef LOAD
}

/* What ES 2.0 lets a host set that sky_draw touches. */
typedef struct es_snapshot {
    GLint program, active, array_buffer, element_buffer, framebuffer, viewport[4], scissor_box[4], tex[4], cube[4];
    GLfloat clear_color[4];
    GLboolean blend, depth, cull, scissor, stencil, depth_mask, color_mask[4];
    GLint bsrc, bdst, bsrca, bdsta, beq, beqa, depth_func, unpack_alignment, pack_alignment;
    GLint attrib_enabled[3], attrib_size[3], attrib_stride[3], attrib_buffer[3];
    void *attrib_pointer[3];
} es_snapshot;

static void es_snap(const es_api *gl, es_snapshot *g)
{
    memset(g, 0, sizeof *g);
    gl->GetIntegerv(GL_CURRENT_PROGRAM, &g->program);
    gl->GetIntegerv(GL_ACTIVE_TEXTURE, &g->active);
    gl->GetIntegerv(GL_ARRAY_BUFFER_BINDING, &g->array_buffer);
    gl->GetIntegerv(GL_ELEMENT_ARRAY_BUFFER_BINDING, &g->element_buffer);
    gl->GetIntegerv(GL_FRAMEBUFFER_BINDING, &g->framebuffer);
    gl->GetIntegerv(GL_VIEWPORT, g->viewport);
    gl->GetIntegerv(GL_SCISSOR_BOX, g->scissor_box);
    gl->GetFloatv(GL_COLOR_CLEAR_VALUE, g->clear_color);
    for (int i = 0; i < 4; i++) {
        gl->ActiveTexture(GL_TEXTURE0 + (GLenum)i);
        gl->GetIntegerv(GL_TEXTURE_BINDING_2D, &g->tex[i]);
        gl->GetIntegerv(GL_TEXTURE_BINDING_CUBE_MAP, &g->cube[i]);
    }
    gl->ActiveTexture((GLenum)g->active);
    g->blend = gl->IsEnabled(GL_BLEND);
    g->depth = gl->IsEnabled(GL_DEPTH_TEST);
    g->cull = gl->IsEnabled(GL_CULL_FACE);
    g->scissor = gl->IsEnabled(GL_SCISSOR_TEST);
    g->stencil = gl->IsEnabled(GL_STENCIL_TEST);
    gl->GetBooleanv(GL_DEPTH_WRITEMASK, &g->depth_mask);
    gl->GetBooleanv(GL_COLOR_WRITEMASK, g->color_mask);
    gl->GetIntegerv(GL_BLEND_SRC_RGB, &g->bsrc);
    gl->GetIntegerv(GL_BLEND_DST_RGB, &g->bdst);
    gl->GetIntegerv(GL_BLEND_SRC_ALPHA, &g->bsrca);
    gl->GetIntegerv(GL_BLEND_DST_ALPHA, &g->bdsta);
    gl->GetIntegerv(GL_BLEND_EQUATION_RGB, &g->beq);
    gl->GetIntegerv(GL_BLEND_EQUATION_ALPHA, &g->beqa);
    gl->GetIntegerv(GL_DEPTH_FUNC, &g->depth_func);
    gl->GetIntegerv(GL_UNPACK_ALIGNMENT, &g->unpack_alignment);
    gl->GetIntegerv(GL_PACK_ALIGNMENT, &g->pack_alignment);
    for (GLuint i = 0; i < 3; i++) {
        gl->GetVertexAttribiv(i, GL_VERTEX_ATTRIB_ARRAY_ENABLED, &g->attrib_enabled[i]);
        gl->GetVertexAttribiv(i, GL_VERTEX_ATTRIB_ARRAY_SIZE, &g->attrib_size[i]);
        gl->GetVertexAttribiv(i, GL_VERTEX_ATTRIB_ARRAY_STRIDE, &g->attrib_stride[i]);
        gl->GetVertexAttribiv(i, GL_VERTEX_ATTRIB_ARRAY_BUFFER_BINDING, &g->attrib_buffer[i]);
        gl->GetVertexAttribPointerv(i, GL_VERTEX_ATTRIB_ARRAY_POINTER, &g->attrib_pointer[i]);
    }
}

static int es_same(const es_snapshot *a, const es_snapshot *b, const char *when)
{
    if (!memcmp(a, b, sizeof *a)) return 1;
    const unsigned char *x = (const unsigned char *)a, *y = (const unsigned char *)b;
    for (size_t i = 0; i + 4 <= sizeof *a; i += 4)
        if (memcmp(x + i, y + i, 4)) NOTE("%s: bytes %zu..%zu differ", when, i, i + 3);
    return 0;
}

/* An ES 2.0 context (as on real ES 2.0 hardware: Mesa reads the override
 * when the display is initialised) and its entry points. Returns 0, or -1
 * after a failed CHECK. */
static int es2_open(sky_osmesa *ctx, int w, int h, es_api *gl)
{
    const char *override = "MESA_GLES_VERSION_OVERRIDE";
    char *old = getenv(override) ? strdup(getenv(override)) : NULL;
    setenv(override, "2.0", 1);
    char err[256];
    int made = sky_osmesa_create(ctx, w, h, SKY_GL_ES20, 0, err, sizeof err) == 0;
    if (old)
        setenv(override, old, 1);
    else
        unsetenv(override);
    free(old);
    if (!made) {
        CHECK(0, "%s", err);
        return -1;
    }
    if (!es_load(gl, sky_headless_loader(ctx))) {
        CHECK(0, "the client's ES 2.0 entry points load through EGL");
        sky_osmesa_destroy(ctx);
        return -1;
    }
    return 0;
}

/* A client with its own framebuffer, program, textures on four units,
 * buffers, a client-memory vertex array (ES 2.0 has them), blending,
 * depth, culling, masks and pixel store: every value the same after
 * sky_create, sky_draw (twice: the tables uploaded, the image made),
 * sky_draw_fisheye, a capture and sky_destroy, on the Hillaire path. */
/* The EGL loader without OES_vertex_array_object's entry points: the
 * profile then saves the host's attribute arrays one by one (Mesa cannot
 * withhold the extension itself). */
static sky_get_proc_address_fn vao_hidden_from;
static sky_gl_proc loader_without_vao(const char *name)
{
    return strstr(name, "VertexArray") && strstr(name, "OES") ? NULL : vao_hidden_from(name);
}

static void es_state_restored(int hide_vao)
{
    char err[256];
    sky_osmesa ctx;
    es_api gl;
    if (es2_open(&ctx, 64, 64, &gl)) return;
    vao_hidden_from = sky_headless_loader(&ctx);
    GLuint fbo, color, tex[4], cube, buf, ebo;
    gl.GenTextures(1, &color);
    gl.BindTexture(GL_TEXTURE_2D, color);
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 64, 64, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    gl.GenFramebuffers(1, &fbo);
    gl.BindFramebuffer(GL_FRAMEBUFFER, fbo);
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color, 0);
    static const char *const sources[2] = {"attribute vec4 p;\nvoid main() { gl_Position = p; }\n",
                                           "void main() { gl_FragColor = vec4(1.0); }\n"};
    GLuint prog = gl.CreateProgram();
    for (int i = 0; i < 2; i++) {
        GLuint sh = gl.CreateShader(i ? GL_FRAGMENT_SHADER : GL_VERTEX_SHADER);
        gl.ShaderSource(sh, 1, &sources[i], NULL);
        gl.CompileShader(sh);
        gl.AttachShader(prog, sh);
    }
    gl.LinkProgram(prog);
    gl.GenTextures(4, tex);
    gl.GenTextures(1, &cube);
    for (int i = 0; i < 4; i++) {
        gl.ActiveTexture(GL_TEXTURE0 + (GLenum)i);
        gl.BindTexture(GL_TEXTURE_2D, tex[i]);
    }
    gl.BindTexture(GL_TEXTURE_CUBE_MAP, cube);
    gl.ActiveTexture(GL_TEXTURE2);
    gl.GenBuffers(1, &buf);
    gl.BindBuffer(GL_ARRAY_BUFFER, buf);
    gl.BufferData(GL_ARRAY_BUFFER, 64, NULL, GL_STATIC_DRAW);
    gl.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 12, (const void *)0);
    gl.EnableVertexAttribArray(0);
    gl.BindBuffer(GL_ARRAY_BUFFER, 0);
    static const float client_array[16];
    gl.VertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, 8, client_array);
    gl.EnableVertexAttribArray(1);
    gl.BindBuffer(GL_ARRAY_BUFFER, buf);
    gl.GenBuffers(1, &ebo);
    gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo);
    gl.Viewport(3, 4, 50, 40);
    gl.Scissor(1, 2, 30, 20);
    gl.Enable(GL_SCISSOR_TEST);
    gl.ClearColor(0.25f, 0.5f, 0.75f, 0.125f);
    gl.Enable(GL_BLEND);
    gl.BlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ZERO);
    gl.BlendEquation(0x800B /* GL_FUNC_REVERSE_SUBTRACT */);
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(0x0204 /* GL_GREATER */);
    gl.DepthMask(GL_TRUE);
    gl.Enable(GL_CULL_FACE);
    gl.ColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 2);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 8);
    gl.UseProgram(prog);
    CHECK(gl.GetError() == GL_NO_ERROR, "the client's own setup is valid ES 2.0");
    es_snapshot before, after;
    es_snap(&gl, &before);

    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.atmosphere = SKY_ATMOSPHERE_HILLAIRE;
    cfg.features = SKY_FEATURES_AVAILABLE;
    cfg.check_gl_errors = 1;
    cfg.get_proc_address = hide_vao ? loader_without_vao : sky_headless_loader(&ctx);
    NOTE("%s", hide_vao ? "without OES_vertex_array_object's entry points" : "with OES_vertex_array_object");
    sky *s = sky_create(&cfg, err, sizeof err);
    CHECK(s != NULL, "sky_create: %s", err);
    es_snap(&gl, &after);
    CHECK(es_same(&before, &after, "sky_create"), "ES state differs after sky_create");
    if (s) {
        sky_stats st;
        CHECK(sky_get_stats(s, &st) == SKY_OK && st.profile == SKY_GL_ES20, "AUTO picks ES20 on an ES context");
        float view[16], proj[16];
        sky_cli_camera_at(0.0, 10.0, 60.0, 64, 64, view, proj);
        for (int k = 0; k < 2; k++) {
            CHECK(sky_draw(s, view, proj) == SKY_OK, "draw: %s", sky_last_error(s));
            es_snap(&gl, &after);
            CHECK(es_same(&before, &after, "sky_draw"), "ES state differs after sky_draw");
        }
        CHECK(sky_draw_fisheye(s) == SKY_OK, "fisheye: %s", sky_last_error(s));
        es_snap(&gl, &after);
        CHECK(es_same(&before, &after, "sky_draw_fisheye"), "ES state differs after sky_draw_fisheye");
        CHECK(sky_capture_environment(s, 0, 16, SKY_CAPTURE_ALL_FACES, 0) == SKY_OK, "capture: %s",
              sky_last_error(s));
        es_snap(&gl, &after);
        CHECK(es_same(&before, &after, "sky_capture_environment"), "ES state differs after a capture");
        sky_destroy(s);
        es_snap(&gl, &after);
        CHECK(es_same(&before, &after, "sky_destroy"), "ES state differs after sky_destroy");
    }
    CHECK(gl.GetError() == GL_NO_ERROR, "no GL error");
    sky_osmesa_destroy(&ctx);
}

TEST(es20_state_restored)
{
    es_state_restored(0);
    es_state_restored(1);
}

/* An ES context runs ES20 alone, and ES20 needs one: each mismatch is an
 * error that says so, before anything is created. */
TEST(es20_profile_mismatch_is_an_error)
{
    char err[256];
    sky_osmesa ctx;
    if (sky_osmesa_create(&ctx, 16, 16, SKY_GL_ES20, 0, err, sizeof err)) {
        CHECK(0, "%s", err);
        return;
    }
    static const sky_gl_profile desktop[2] = {SKY_GL_CORE33, SKY_GL_COMPAT20};
    for (int k = 0; k < 2; k++) {
        sky_config cfg;
        memset(&cfg, 0, sizeof cfg);
        cfg.gl_profile = desktop[k];
        cfg.get_proc_address = sky_headless_loader(&ctx);
        err[0] = '\0';
        sky *s = sky_create(&cfg, err, sizeof err);
        CHECK(s == NULL && strstr(err, "ES20"), "%s on an ES context is refused, naming ES20: %s",
              k ? "COMPAT20" : "CORE33", s ? "created" : err);
        sky_destroy(s);
    }
    sky_osmesa_destroy(&ctx);
    if (sky_osmesa_create(&ctx, 16, 16, SKY_GL_COMPAT20, 0, err, sizeof err)) {
        CHECK(0, "%s", err);
        return;
    }
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.gl_profile = SKY_GL_ES20;
    cfg.get_proc_address = sky_headless_loader(&ctx);
    sky *s = sky_create(&cfg, err, sizeof err);
    CHECK(s == NULL && strstr(err, "ES20") && strstr(err, "desktop"), "ES20 on a desktop context is refused: %s",
          s ? "created" : err);
    sky_destroy(s);
    sky_osmesa_destroy(&ctx);
}

/* The host's aerial perspective on ES 2.0 (ISSUE-NOTES: the CPU function
 * and the GLSL snippet there): sky_aerial_glsl() compiles in a GLSL ES
 * 1.00 shader with the host's highp, sky_aerial_bind binds it, and what it
 * draws (8-bit: transmittance, and the light over the brightest) is the
 * CPU function's within 2 levels plus 2 %. */
TEST(es20_aerial_snippet)
{
    enum { DIRS = 8, DISTS = 5 };
    sky_osmesa ctx;
    es_api gl;
    if (es2_open(&ctx, DIRS * DISTS, 2, &gl)) return;
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.atmosphere = SKY_ATMOSPHERE_HILLAIRE;
    cfg.get_proc_address = sky_headless_loader(&ctx);
    char err[256];
    sky *s = sky_create(&cfg, err, sizeof err);
    if (!s) {
        CHECK(0, "sky_create: %s", err);
        sky_osmesa_destroy(&ctx);
        return;
    }
    sky_params p = sky_default_params();
    p.time = 0.3f;
    sky_set_params(s, &p);
    sky_update(s, 0.0);
    const char *vs = "#version 100\nattribute vec4 p;\nvoid main() { gl_Position = p; }\n";
    const char *fs[3] = {"#version 100\nprecision highp float;\n", sky_aerial_glsl(),
                         "uniform vec3 dir;\nuniform float dist, scale;\nvoid main() {\n  vec3 t, l;\n"
                         "  sky_aerial(dir, dist, t, l);\n"
                         "  gl_FragColor = vec4(gl_FragCoord.y < 1.0 ? t : l / scale, 1.0);\n}\n"};
    GLuint v = gl.CreateShader(GL_VERTEX_SHADER), f = gl.CreateShader(GL_FRAGMENT_SHADER), prog = gl.CreateProgram();
    gl.ShaderSource(v, 1, &vs, NULL);
    gl.ShaderSource(f, 3, fs, NULL);
    gl.CompileShader(v);
    gl.CompileShader(f);
    GLint ok = 0;
    gl.GetShaderiv(f, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[2048] = "";
        gl.GetShaderInfoLog(f, sizeof log, NULL, log);
        CHECK(0, "the snippet does not compile as GLSL ES 1.00: %s", log);
    }
    gl.AttachShader(prog, v);
    gl.AttachShader(prog, f);
    gl.BindAttribLocation(prog, 0, "p");
    gl.LinkProgram(prog);
    gl.GetProgramiv(prog, GL_LINK_STATUS, &ok);
    CHECK(ok, "the snippet's program links");
    static const float tri[6] = {-1, -1, 3, -1, -1, 3};
    gl.VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, tri); /* a client array: ES 2.0 has them */
    gl.EnableVertexAttribArray(0);
    CHECK(sky_aerial_bind(s, prog, 3) == SKY_OK, "bind: %s", sky_last_error(s));
    gl.UseProgram(prog);
    static const float dists[DISTS] = {400.0f, 2500.0f, 9000.0f, 30000.0f, 4e5f};
    float cpu[DIRS * DISTS][6], brightest = 0.0f;
    /* views 1 and 20 degrees up, toward four azimuths; the CPU's first, for
     * the light's scale */
    float dirs[DIRS][3];
    for (int k = 0; k < DIRS; k++) {
        double el = (k < 4 ? 1.0 : 20.0) * M_PI / 180.0, az = (k % 4) * M_PI / 2.0;
        dirs[k][0] = (float)(cos(el) * sin(az));
        dirs[k][1] = (float)sin(el);
        dirs[k][2] = (float)(-cos(el) * cos(az));
    }
    for (int i = 0; i < DIRS * DISTS; i++) {
        sky_aerial a;
        sky_get_aerial_perspective(s, dirs[i / DISTS], dists[i % DISTS], &a);
        for (int c = 0; c < 3; c++) {
            cpu[i][c] = a.transmittance[c];
            cpu[i][3 + c] = a.inscatter[c];
            if (a.inscatter[c] > brightest) brightest = a.inscatter[c];
        }
    }
    gl.Uniform1f(gl.GetUniformLocation(prog, "scale"), brightest);
    for (int i = 0; i < DIRS * DISTS; i++) {
        const float *d = dirs[i / DISTS];
        gl.Uniform3fv(gl.GetUniformLocation(prog, "dir"), 1, d);
        gl.Uniform1f(gl.GetUniformLocation(prog, "dist"), dists[i % DISTS]);
        gl.Viewport(i, 0, 1, 2);
        gl.DrawArrays(GL_TRIANGLES, 0, 3);
    }
    unsigned char px[2][DIRS * DISTS][4];
    gl.ReadPixels(0, 0, DIRS * DISTS, 2, GL_RGBA, GL_UNSIGNED_BYTE, px);
    double worst_t = 0.0, worst_l = 0.0;
    for (int i = 0; i < DIRS * DISTS; i++)
        for (int c = 0; c < 3; c++) {
            double t = px[0][i][c] / 255.0, l = px[1][i][c] / 255.0 * brightest;
            worst_t = fmax(worst_t, fabs(t - cpu[i][c]));
            worst_l = fmax(worst_l, fabs(l - cpu[i][3 + c]) / brightest);
            CHECK(fabs(t - cpu[i][c]) <= 2.0 / 255.0 + 0.02 && fabs(l - cpu[i][3 + c]) <= (2.0 / 255.0 + 0.02) * brightest,
                  "view %d at %.0f m, channel %d: shader T %.3f light %.4g, CPU T %.3f light %.4g", i / DISTS,
                  (double)dists[i % DISTS], c, t, l, (double)cpu[i][c], (double)cpu[i][3 + c]);
        }
    NOTE("ES 2.0 snippet against the CPU: transmittance within %.4f, light within %.4f of the brightest", worst_t,
         worst_l);
    CHECK(gl.GetError() == GL_NO_ERROR, "no GL error");
    sky_destroy(s);
    sky_osmesa_destroy(&ctx);
}

/* sky-render --capture under ES20: the faces read back through a
 * framebuffer (ES 2.0 has no glGetTexImage), the cross COMPAT20's. */
TEST(es20_capture_cross)
{
    char bin[512], es_png[512], compat_png[512], cmd[2048], out[4096];
    bin_path("sky-render", bin, sizeof bin);
    tmp_path("cross-es.png", es_png, sizeof es_png);
    tmp_path("cross-compat.png", compat_png, sizeof compat_png);
    snprintf(cmd, sizeof cmd, ES2 "%s --gl es20 --capture 32 --preset sunset --time 0.7 --out %s 2>&1", bin, es_png);
    int rc1 = run_command(cmd, out, sizeof out);
    CHECK(rc1 == 0, "the ES20 capture exits 0: %s", out);
    snprintf(cmd, sizeof cmd, "%s --gl compat --capture 32 --preset sunset --time 0.7 --out %s 2>&1", bin, compat_png);
    int rc2 = run_command(cmd, out, sizeof out);
    CHECK(rc2 == 0, "the COMPAT20 capture exits 0: %s", out);
    image a, b;
    if (rc1 || rc2 || image_load_png(es_png, &a)) return;
    if (!image_load_png(compat_png, &b)) {
        double psnr = image_psnr(&a, &b);
        NOTE("the cube cross: ES20 against COMPAT20 PSNR %.1f dB", psnr);
        CHECK(a.w == 128 && a.h == 96 && psnr >= 40.0, "%dx%d cross, PSNR %.1f dB", a.w, a.h, psnr);
        image_free(&b);
    }
    image_free(&a);
    remove(es_png);
    remove(compat_png);
}

/* A fragment stage without highp (a Mali-400's): the loader says so
 * through glGetShaderPrecisionFormat; every layer's shaders then compile
 * and link at mediump (the uniforms both stages declare at one precision),
 * and what reaches that stage stays within mediump's +-2^14: the light
 * already times the exposure, the sun's irradiance over a power of two,
 * no km^2. llvmpipe honours mediump there (a uniform or a constant past
 * its range becomes infinity or 0), so each path's day, twilight and
 * night are held to the highp picture. */
static sky_get_proc_address_fn lowp_from;
static void (*real_precision)(GLenum, GLenum, GLint *, GLint *);
static void no_highp(GLenum stage, GLenum precision, GLint *range, GLint *bits)
{
    real_precision(stage, precision, range, bits);
    if (stage == GL_FRAGMENT_SHADER && precision == 0x8DF2 /* GL_HIGH_FLOAT */) range[0] = range[1] = *bits = 0;
}
static sky_gl_proc loader_without_highp(const char *name)
{
    if (!strcmp(name, "glGetShaderPrecisionFormat")) {
        sky_gl_proc p = lowp_from(name);
        memcpy(&real_precision, &p, sizeof p);
        return (sky_gl_proc)no_highp;
    }
    return lowp_from(name);
}

/* PSNR of a frame of path at time of day t drawn with the mediump fragment
 * stage against the highp one, in the ES 2.0 context ctx, looking at
 * (yaw, pitch); -1 if a sky failed. */
static double mediump_against_highp(sky_osmesa *ctx, es_api *gl, sky_atmosphere_path path, float t, double yaw,
                                    double pitch)
{
    enum { W = 160, H = 90 };
    static unsigned char px[2][W * H * 4];
    lowp_from = sky_headless_loader(ctx);
    for (int k = 0; k < 2; k++) {
        sky_config cfg;
        memset(&cfg, 0, sizeof cfg);
        cfg.features = SKY_FEATURES_AVAILABLE;
        cfg.atmosphere = path;
        cfg.get_proc_address = k ? loader_without_highp : lowp_from;
        char err[512];
        sky *s = sky_create(&cfg, err, sizeof err);
        CHECK(s != NULL, "%s: sky_create: %s", k ? "mediump" : "highp", err);
        if (!s) return -1.0;
        sky_params p = sky_default_params();
        p.time = t;
        sky_set_params(s, &p);
        float view[16], proj[16];
        sky_cli_camera_at(yaw, pitch, 90.0, W, H, view, proj);
        gl->Viewport(0, 0, W, H);
        CHECK(sky_draw(s, view, proj) == SKY_OK, "draw: %s", sky_last_error(s));
        gl->ReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, px[k]);
        sky_destroy(s);
    }
    double se = 0.0;
    for (int i = 0; i < W * H * 4; i++)
        if (i % 4 != 3) se += (px[0][i] - px[1][i]) * (double)(px[0][i] - px[1][i]);
    double mse = se / (W * H * 3);
    return mse > 0.0 ? 10.0 * log10(255.0 * 255.0 / mse) : 99.0;
}

SLOW_TEST(es20_mediump_fragment_stage)
{
    sky_osmesa ctx;
    es_api gl;
    if (es2_open(&ctx, 160, 90, &gl)) return;
    static const struct { sky_atmosphere_path path; const char *name; } paths[] = {
        {SKY_ATMOSPHERE_GRADIENT, "gradient"}, {SKY_ATMOSPHERE_PREETHAM, "preetham"},
        {SKY_ATMOSPHERE_RAYLEIGH, "rayleigh"}, {SKY_ATMOSPHERE_HILLAIRE, "hillaire"},
        {SKY_ATMOSPHERE_BLEND, "blend"}};
    /* the day with the sun in view; a twilight (the sun near -5 degrees:
     * the air's light per unit of the sun's irradiance near 2^-20); a
     * moonless night with every layer */
    static const struct { float t; double yaw, pitch; const char *name; } times[] = {
        {0.4f, 120.0, 30.0, "day"}, {0.215f, 90.0, 10.0, "twilight"}, {0.02f, 120.0, 30.0, "night"}};
    for (size_t i = 0; i < sizeof paths / sizeof paths[0]; i++)
        for (size_t j = 0; j < sizeof times / sizeof times[0]; j++) {
            double psnr = mediump_against_highp(&ctx, &gl, paths[i].path, times[j].t, times[j].yaw, times[j].pitch);
            NOTE("%s, %s: mediump fragment stage against highp PSNR %.1f dB", paths[i].name, times[j].name, psnr);
            CHECK(psnr >= 40.0, "%s, %s: the mediump stage draws the highp picture (PSNR %.1f dB, target 40)",
                  paths[i].name, times[j].name, psnr);
        }
    sky_osmesa_destroy(&ctx);
}

/* The cloud shadow snippet compiles as GLSL ES 1.00 (the desktop dialects
 * are test_weather.c's, where it also reads the map). */
TEST(es20_cloud_shadow_snippet)
{
    sky_osmesa ctx;
    es_api gl;
    if (es2_open(&ctx, 4, 4, &gl)) return;
    const char *fs[3] = {"#version 100\nprecision mediump float;\n", sky_cloud_shadow_glsl(),
                         "uniform vec3 where;\nvoid main() { gl_FragColor = vec4(sky_cloud_shadow(where)); }\n"};
    GLuint f = gl.CreateShader(GL_FRAGMENT_SHADER);
    gl.ShaderSource(f, 3, fs, NULL);
    gl.CompileShader(f);
    GLint ok = 0;
    gl.GetShaderiv(f, GL_COMPILE_STATUS, &ok);
    char log[2048] = "";
    if (!ok) gl.GetShaderInfoLog(f, sizeof log, NULL, log);
    CHECK(ok, "the cloud shadow snippet does not compile as GLSL ES 1.00: %s", log);
    CHECK(strstr(fs[1], "sky_cloud_shadow("), "the build has the snippet");
    sky_osmesa_destroy(&ctx);
}
