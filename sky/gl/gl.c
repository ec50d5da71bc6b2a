/*
 * GL backend: function loading through the host's getProcAddress, profile
 * detection, program building with a version prologue, texture and buffer
 * helpers, and saving/restoring the host's GL state around sky_draw.
 */
/* open, fstat, O_NONBLOCK for the texture overrides (POSIX.1-2008) */
#if !defined(_WIN32) && !defined(_POSIX_C_SOURCE)
#define _POSIX_C_SOURCE 200809L
#endif
#include "gl.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#if !defined(_WIN32)
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#endif

/* Parses "M.m..." after any leading non-digits ("OpenGL ES 3.0", "4.5 (Core
 * Profile) Mesa"). Returns major*10+minor, or 0 when the string is unusable. */
static int parse_version(const char *v)
{
    if (!v) return 0;
    while (*v && (*v < '0' || *v > '9')) v++;
    int major = 0, minor = 0;
    if (sscanf(v, "%d.%d", &major, &minor) != 2 || major < 1 || minor < 0) return 0;
    if (minor > 9) minor = 9;
    return major * 10 + minor;
}

/* Reads and so clears the pending GL errors. GL keeps a few error flags,
 * each cleared when read, so a handful of calls drain them; but a lost
 * context (GL_CONTEXT_LOST, GL 4.5 / KHR_robustness) may report on every
 * call and never GL_NO_ERROR, so the reading stops after a bound. Returns
 * GL_NO_ERROR, or the error still reported after it. */
static GLenum drain_errors(const sky_gl *gl)
{
    enum { MAX_READS = 64 };
    GLenum e = GL_NO_ERROR;
    for (int i = 0; i < MAX_READS; i++)
        if ((e = gl->glGetError()) == GL_NO_ERROR) break;
    return e;
}

/* The message for errors that drain_errors could not clear. */
static int undrained(GLenum e, char *err, size_t err_len)
{
    sky_format(err, err_len, "glGetError keeps returning 0x%04x (a lost GL context?)", e);
    return -1;
}

/* Whether a compatibility context's extension string names ext (a whole
 * word of it). */
static int has_extension(const sky_gl *gl, const char *ext)
{
    const char *all = (const char *)gl->glGetString(GL_EXTENSIONS);
    size_t n = strlen(ext);
    for (const char *p = all; p && (p = strstr(p, ext)) != NULL; p += n)
        if ((p == all || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return 1;
    return 0;
}

/* What beyond OpenGL 2.0 the sky may use. A 2004 GPU renders into a texture
 * through EXT_framebuffer_object, whose entry points may carry the EXT
 * suffix, and binds one framebuffer for drawing and reading alike; NPOT
 * textures need ARB_texture_non_power_of_two there. */
static GLenum detect_caps(sky_core *s, int gl_ver)
{
    sky_gl *gl = &s->gl;
    sky_gl_caps *caps = &s->caps;
    memset(caps, 0, sizeof *caps);
    if (s->profile == SKY_GL_CORE33) {
        caps->render_to_rgba8 = caps->npot = caps->separate_framebuffers = caps->pixel_buffers = 1;
        caps->framebuffer_srgb = caps->unpack_rows = caps->rasterizer_discard = caps->derivatives = 1;
        caps->vertex_arrays = caps->fragment_highp = 1;
        return GL_NO_ERROR;
    }
    if (s->profile == SKY_GL_ES20) {
        /* ES 2.0 has framebuffer objects in its core. Its spec allows
         * non-power-of-two textures clamped, linear and without mipmaps
         * (what the render images are), but Mesa without
         * OES_texture_npot samples them black: only ES 3.0, the
         * extension, or WebGL (whose conformance tests hold browsers to
         * them) is trusted with them. The rest arrived with ES 3.0. */
        caps->es = 1;
        caps->render_to_rgba8 = gl->glGenFramebuffers && gl->glDeleteFramebuffers && gl->glBindFramebuffer &&
                                gl->glFramebufferTexture2D && gl->glCheckFramebufferStatus;
        caps->npot = gl_ver >= 30 || has_extension(gl, "GL_OES_texture_npot") || strstr(s->gl_version, "WebGL");
        caps->separate_framebuffers = caps->pixel_buffers = caps->unpack_rows = caps->rasterizer_discard =
            gl_ver >= 30;
        caps->derivatives = has_extension(gl, "GL_OES_standard_derivatives");
        /* ES 2.0 need not have highp in the fragment stage (a Mali-400
         * has not); its query is core there */
        GLint range[2] = {0, 0}, bits = 0;
        if (gl->glGetShaderPrecisionFormat)
            gl->glGetShaderPrecisionFormat(GL_FRAGMENT_SHADER, GL_HIGH_FLOAT, range, &bits);
        caps->fragment_highp = !gl->glGetShaderPrecisionFormat || bits > 0;
        /* (a loader may hand out a stub for any name, so the version or
         * the extension says whether the entry points work) */
        if (gl_ver < 30 && has_extension(gl, "GL_OES_vertex_array_object")) {
            sky_get_proc_address_fn gpa = s->cfg.get_proc_address;
            gl->glGenVertexArrays = (void(SKY_APIENTRY *)(GLsizei, GLuint *))gpa("glGenVertexArraysOES");
            gl->glDeleteVertexArrays = (void(SKY_APIENTRY *)(GLsizei, const GLuint *))gpa("glDeleteVertexArraysOES");
            gl->glBindVertexArray = (void(SKY_APIENTRY *)(GLuint))gpa("glBindVertexArrayOES");
            caps->vertex_arrays = 1;
        }
        if (gl_ver >= 30) caps->vertex_arrays = 1;
        caps->vertex_arrays = caps->vertex_arrays && gl->glGenVertexArrays && gl->glDeleteVertexArrays &&
                              gl->glBindVertexArray;
        return drain_errors(gl);
    }
    caps->unpack_rows = caps->derivatives = caps->fragment_highp = 1;
    caps->rasterizer_discard = gl_ver >= 30;
    caps->pixel_buffers = gl_ver >= 21 || has_extension(gl, "GL_ARB_pixel_buffer_object");
    caps->framebuffer_srgb = gl_ver >= 30 || has_extension(gl, "GL_ARB_framebuffer_sRGB") ||
                             has_extension(gl, "GL_EXT_framebuffer_sRGB");
    int arb_fbo = gl_ver >= 30 || has_extension(gl, "GL_ARB_framebuffer_object");
    int ext_fbo = has_extension(gl, "GL_EXT_framebuffer_object");
    if (!arb_fbo && ext_fbo && !gl->glGenFramebuffers) {
        sky_get_proc_address_fn gpa = s->cfg.get_proc_address;
#define SKY_GL_LOAD_EXT(name, params) gl->name = (void(SKY_APIENTRY *) params)gpa(#name "EXT");
        SKY_GL_LOAD_EXT(glGenFramebuffers, (GLsizei n, GLuint *f))
        SKY_GL_LOAD_EXT(glDeleteFramebuffers, (GLsizei n, const GLuint *f))
        SKY_GL_LOAD_EXT(glBindFramebuffer, (GLenum target, GLuint f))
        SKY_GL_LOAD_EXT(glFramebufferTexture2D, (GLenum target, GLenum att, GLenum textarget, GLuint t, GLint level))
#undef SKY_GL_LOAD_EXT
        gl->glCheckFramebufferStatus = (GLenum(SKY_APIENTRY *)(GLenum))gpa("glCheckFramebufferStatusEXT");
    }
    caps->render_to_rgba8 = (arb_fbo || ext_fbo) && gl->glGenFramebuffers && gl->glDeleteFramebuffers &&
                            gl->glBindFramebuffer && gl->glFramebufferTexture2D && gl->glCheckFramebufferStatus;
    caps->separate_framebuffers = arb_fbo || has_extension(gl, "GL_EXT_framebuffer_blit");
    caps->npot = gl_ver >= 30 || has_extension(gl, "GL_ARB_texture_non_power_of_two");
    return drain_errors(gl);
}

/* Settles the profile and what the context offers it. */
static int choose_profile(sky_core *s, sky_gl_profile profile, int gl_ver, char *err, size_t err_len)
{
    if (profile != SKY_GL_CORE33) {
        GLint units = 0;
        s->gl.glGetIntegerv(GL_MAX_TEXTURE_IMAGE_UNITS, &units);
        if (units < 4) {
            sky_format(err, err_len, "the context has %d texture units; libsky needs 4", (int)units);
            return -1;
        }
    }
    s->profile = profile;
    GLenum e = detect_caps(s, gl_ver);
    return e == GL_NO_ERROR ? 0 : undrained(e, err, err_len);
}

int sky_gl_init(sky_core *s, char *err, size_t err_len)
{
    sky_get_proc_address_fn gpa = s->cfg.get_proc_address;
    /* Every pointer is stored through its own member type; a missing entry
     * point is reported by name. */
#define SKY_GL_LOAD(ret, name, params)                                                   \
    s->gl.name = (ret(SKY_APIENTRY *) params)gpa(#name);                                 \
    if (!s->gl.name) {                                                                   \
        sky_format(err, err_len, "the GL context lacks %s (OpenGL 2.0 is the minimum)", #name); \
        return -1;                                                                       \
    }
    SKY_GL_FUNCS_20(SKY_GL_LOAD)
#define SKY_GL_LOAD_OPT(ret, name, params) s->gl.name = (ret(SKY_APIENTRY *) params)gpa(#name);
    SKY_GL_FUNCS_30(SKY_GL_LOAD_OPT)
#undef SKY_GL_LOAD_OPT

    const sky_gl *gl = &s->gl;
    GLenum e = drain_errors(gl); /* the host's old errors are not ours */
    if (e != GL_NO_ERROR) return undrained(e, err, err_len);
    const char *version = (const char *)gl->glGetString(GL_VERSION);
    int gl_ver = parse_version(version);
    if (gl_ver == 0) {
        sky_format(err, err_len, "no usable GL context is current (GL_VERSION is %s)", version ? version : "NULL");
        return -1;
    }
    if (gl_ver < 20) {
        sky_format(err, err_len, "OpenGL %s is too old: libsky needs at least 2.0", version);
        return -1;
    }
    snprintf(s->gl_version, sizeof s->gl_version, "%s", version);
    /* ES says so at the start of its version string ("OpenGL ES 2.0 Mesa",
     * WebGL's "OpenGL ES 2.0 (WebGL 1.0 ...)"), and then runs ES20 alone */
    int is_es = strncmp(version, "OpenGL ES", 9) == 0;
    sky_gl_profile want = s->cfg.gl_profile;
    if (is_es || want == SKY_GL_ES20) {
        if (!is_es) {
            sky_format(err, err_len, "ES20 asked for, but the context is desktop OpenGL %s (ES20 needs an OpenGL ES "
                       "2.0 or later context)", version);
            return -1;
        }
        if (want != SKY_GL_AUTO && want != SKY_GL_ES20) {
            sky_format(err, err_len, "%s asked for, but the context is %s: an ES context runs the ES20 profile",
                       want == SKY_GL_CORE33 ? "CORE33" : "COMPAT20", version);
            return -1;
        }
        return choose_profile(s, SKY_GL_ES20, gl_ver, err, err_len);
    }
    SKY_GL_FUNCS_DESKTOP(SKY_GL_LOAD)
#undef SKY_GL_LOAD
    /* Only a 3.3 context can run GLSL 330, so below that the string is not
     * asked for (Mesa under version overrides complains on stderr when it
     * is). Some drivers without GLSL return NULL: treated as GLSL 1.10. */
    int glsl_ver = gl_ver >= 33 ? parse_version((const char *)gl->glGetString(GL_SHADING_LANGUAGE_VERSION)) : 11;
    if ((e = drain_errors(gl)) != GL_NO_ERROR) return undrained(e, err, err_len);

    int is_core_context = 0;
    if (gl_ver >= 32) {
        GLint mask = 0;
        gl->glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &mask);
        is_core_context = (mask & GL_CONTEXT_CORE_PROFILE_BIT) != 0;
        if ((e = drain_errors(gl)) != GL_NO_ERROR) return undrained(e, err, err_len);
    }
    int can_core = gl_ver >= 33 && glsl_ver >= 33 && gl->glGenVertexArrays && gl->glBindVertexArray &&
                   gl->glDeleteVertexArrays && gl->glGenFramebuffers && gl->glBindFramebuffer &&
                   gl->glFramebufferTexture2D && gl->glCheckFramebufferStatus && gl->glDeleteFramebuffers;

    if (want == SKY_GL_AUTO) want = can_core ? SKY_GL_CORE33 : SKY_GL_COMPAT20;
    if (want == SKY_GL_CORE33 && !can_core) {
        sky_format(err, err_len, "CORE33 asked for, but the context offers OpenGL %s with GLSL %d.%d", version,
                glsl_ver / 10, glsl_ver % 10);
        return -1;
    }
    if (want == SKY_GL_COMPAT20 && is_core_context) {
        /* a core context that could not run CORE33: say what it lacked */
        const char *missing = NULL;
#define SKY_GL_FIRST_MISSING(ret, name, params) \
        if (!missing && !s->gl.name) missing = #name;
        if (s->cfg.gl_profile == SKY_GL_AUTO) {
            SKY_GL_FUNCS_30(SKY_GL_FIRST_MISSING)
        }
#undef SKY_GL_FIRST_MISSING
        if (missing)
            sky_format(err, err_len, "the %s core context lacks %s, which CORE33 needs (and COMPAT20 needs a "
                       "compatibility context)", version, missing);
        else
            sky_format(err, err_len, "COMPAT20 needs a compatibility context; this one is a %s core profile", version);
        return -1;
    }
    return choose_profile(s, want, gl_ver, err, err_len);
}

/* ---- programs ------------------------------------------------------------ */

static const sky_uniform_desc common_uniforms[] = {
    SKY_UF("sky_display_exposure", SKY_U_F1, shader_exposure),
    SKY_UF("u_output_hdr", SKY_U_F1, output_hdr),
    SKY_UF("u_fisheye", SKY_U_F1, fisheye),
    SKY_UF("u_aspect", SKY_U_F2, aspect),
    SKY_UF("u_sun_dir", SKY_U_F3, sun_dir),
    SKY_UF("u_moon_dir", SKY_U_F3, moon_dir),
    SKY_UF("u_view_proj", SKY_U_M4, view_proj),
    SKY_UF("u_viewport", SKY_U_F4, viewport),
    SKY_UF("u_pixel_angle", SKY_U_F1, pixel_angle),
    SKY_UF("u_far_z", SKY_U_F1, far_z),
    SKY_UF("sky_display_rods", SKY_U_F1, night_shift),
    SKY_UF("sky_display_cd", SKY_U_F1, display_cd),
    SKY_UF("u_refraction_pressure", SKY_U_F1, refraction_pressure),
};
/* (display.glsl, the display stages hosts can include too, comes first) */
const sky_snippet sky_common_snippet = {NULL, "common.glsl", common_uniforms,
                                        SKY_UNIFORM_COUNT(common_uniforms), NULL};


/* The version prologue: one GLSL source per stage serves every profile.
 * GLSL ES 1.00 wants a default float precision in the fragment stage:
 * highp where the stage has it (caps.fragment_highp: the sky's light spans
 * far more than mediump's 2^14, and the uniforms are kept within it
 * without), and its fwidth through OES_standard_derivatives. */
#define SKY_ES_MACROS "#define SKY_ES 1\n#define SKY_TEX2D texture2D\n#define SKY_TEXCUBE textureCube\n"
#define SKY_ES_FRAGMENT "#define SKY_FRAGMENT 1\n#define SKY_IN varying\n#define SKY_FRAG_COLOR gl_FragColor\n"
#define SKY_ES_DERIVATIVES "#extension GL_OES_standard_derivatives : enable\n"
#define SKY_ES_HIGHP "precision highp float;\n#define SKY_UP\n"
/* Without highp in the fragment stage the uniforms both stages declare
 * are mediump in both (GLSL ES 1.00 links them only at one precision):
 * SKY_UP qualifies every uniform; the vertex stage's own values stay highp. */
#define SKY_ES_MEDIUMP "precision mediump float;\n#define SKY_MEDIUMP 1\n#define SKY_UP mediump\n"
static const char *prologue(const sky_core *s, int fragment)
{
    if (s->profile == SKY_GL_ES20) {
        static const char *const fragment_stage[2][2] = { /* [derivatives][highp] */
            {"#version 100\n" SKY_ES_MEDIUMP SKY_ES_MACROS "#define SKY_NO_DERIVATIVES 1\n" SKY_ES_FRAGMENT,
             "#version 100\n" SKY_ES_HIGHP SKY_ES_MACROS "#define SKY_NO_DERIVATIVES 1\n" SKY_ES_FRAGMENT},
            {"#version 100\n" SKY_ES_DERIVATIVES SKY_ES_MEDIUMP SKY_ES_MACROS SKY_ES_FRAGMENT,
             "#version 100\n" SKY_ES_DERIVATIVES SKY_ES_HIGHP SKY_ES_MACROS SKY_ES_FRAGMENT}};
        if (!fragment)
            return s->caps.fragment_highp
                       ? "#version 100\n" SKY_ES_HIGHP SKY_ES_MACROS "#define SKY_ATTR attribute\n#define SKY_OUT varying\n"
                       : "#version 100\nprecision highp float;\n#define SKY_UP mediump\n" SKY_ES_MACROS
                         "#define SKY_ATTR attribute\n#define SKY_OUT varying\n";
        return fragment_stage[s->caps.derivatives != 0][s->caps.fragment_highp != 0];
    }
    if (s->profile == SKY_GL_CORE33)
        return fragment ? "#version 330 core\n#define SKY_UP\n#define SKY_CORE 1\n#define SKY_FRAGMENT 1\n#define SKY_IN in\n"
                          "#define SKY_TEX2D texture\n#define SKY_TEXCUBE texture\nout vec4 sky_frag_color;\n"
                          "#define SKY_FRAG_COLOR sky_frag_color\n"
                        : "#version 330 core\n#define SKY_UP\n#define SKY_CORE 1\n#define SKY_ATTR in\n#define SKY_OUT out\n";
    return fragment ? "#version 110\n#define SKY_UP\n#define SKY_FRAGMENT 1\n#define SKY_IN varying\n#define SKY_TEX2D texture2D\n"
                      "#define SKY_TEXCUBE textureCube\n"
                      "#define SKY_FRAG_COLOR gl_FragColor\n"
                    : "#version 110\n#define SKY_UP\n#define SKY_ATTR attribute\n#define SKY_OUT varying\n";
}

static GLuint compile(sky_core *s, GLenum type, const char *const *parts, int count, char *err, size_t err_len)
{
    const sky_gl *gl = &s->gl;
    GLuint sh = gl->glCreateShader(type);
    if (!sh) {
        sky_format(err, err_len, "glCreateShader failed");
        return 0;
    }
    gl->glShaderSource(sh, count, parts, NULL);
    gl->glCompileShader(sh);
    GLint ok = 0;
    gl->glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[512] = "";
        gl->glGetShaderInfoLog(sh, (GLsizei)sizeof log, NULL, log);
        sky_format(err, err_len, "%s shader failed to compile: %s", type == GL_VERTEX_SHADER ? "vertex" : "fragment",
                log);
        gl->glDeleteShader(sh);
        return 0;
    }
    return sh;
}

static const char *blob_text(const char *name, char *err, size_t err_len)
{
    const sky_blob *b = sky_find_blob(name);
    if (!b) sky_format(err, err_len, "embedded shader %s is missing from this build", name);
    return b ? (const char *)b->data : NULL;
}

int sky_program_build(sky_core *s, sky_program *p, const char *vert_main, const char *frag_main,
                      const sky_snippet *const *snippets, int snippet_count, char *err, size_t err_len)
{
    const sky_gl *gl = &s->gl;
    memset(p, 0, sizeof *p);
    if (snippet_count > SKY_MAX_SNIPPETS) {
        sky_format(err, err_len, "too many shader snippets (%d)", snippet_count);
        return -1;
    }
    /* prologue, feature defines, display and common code, snippets, main */
    const char *parts[4 + SKY_MAX_SNIPPETS + 1];
    /* the tone map (display.glsl), then the snippets' defines */
    static const char *const tone_maps[3] = {"", "#define SKY_TONE_MAP_FILMIC 1\n", "#define SKY_TONE_MAP_NEUTRAL 1\n"};
    char defines[64 + 48 * SKY_MAX_SNIPPETS];
    size_t used = (size_t)snprintf(defines, sizeof defines, "%s", tone_maps[s->cfg.tone_map]);
    for (int i = 0; i < snippet_count; i++)
        if (snippets[i]->define) {
            int n = snprintf(defines + used, sizeof defines - used, "#define %s 1\n", snippets[i]->define);
            if (n < 0 || (size_t)n >= sizeof defines - used) { /* a define dropped would build another shader */
                sky_format(err, err_len, "shader defines overflow at %s", snippets[i]->define);
                return -1;
            }
            used += (size_t)n;
        }
    GLuint shaders[2] = {0, 0};
    for (int stage = 0; stage < 2; stage++) {
        int n = 0;
        parts[n++] = prologue(s, stage);
        parts[n++] = defines;
        if (!(parts[n++] = blob_text("display.glsl", err, err_len))) goto fail;
        if (!(parts[n++] = blob_text(sky_common_snippet.source, err, err_len))) goto fail;
        for (int i = 0; i < snippet_count; i++) {
            const char *source = stage ? snippets[i]->source : snippets[i]->vertex_source;
            if (source && !(parts[n++] = blob_text(source, err, err_len))) goto fail;
        }
        if (!(parts[n++] = blob_text(stage ? frag_main : vert_main, err, err_len))) goto fail;
        shaders[stage] = compile(s, stage ? GL_FRAGMENT_SHADER : GL_VERTEX_SHADER, parts, n, err, err_len);
        if (!shaders[stage]) goto fail;
    }
    p->id = gl->glCreateProgram();
    gl->glAttachShader(p->id, shaders[0]);
    gl->glAttachShader(p->id, shaders[1]);
    gl->glBindAttribLocation(p->id, 0, "a_pos");
    gl->glBindAttribLocation(p->id, 1, "a_dir");
    gl->glBindAttribLocation(p->id, 2, "a_color");
    /* a program with more outputs (multiscatter_build.frag) places the
     * others explicitly; the common one is always colour 0 */
    if (s->profile == SKY_GL_CORE33) gl->glBindFragDataLocation(p->id, 0, "sky_frag_color");
    gl->glLinkProgram(p->id);
    gl->glDeleteShader(shaders[0]); /* flagged; freed with the program */
    gl->glDeleteShader(shaders[1]);
    shaders[0] = shaders[1] = 0;
    GLint ok = 0;
    gl->glGetProgramiv(p->id, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[512] = "";
        gl->glGetProgramInfoLog(p->id, (GLsizei)sizeof log, NULL, log);
        sky_format(err, err_len, "shader program failed to link: %s", log);
        goto fail;
    }
    /* Uniform rows: common first, then each snippet's. Rows the compiler
     * optimised away get location -1 and are skipped by glUniform. */
    const sky_snippet *all[SKY_MAX_SNIPPETS + 1];
    all[0] = &sky_common_snippet;
    for (int i = 0; i < snippet_count; i++) all[i + 1] = snippets[i];
    for (int i = 0; i <= snippet_count; i++)
        for (int u = 0; u < all[i]->uniform_count; u++) {
            if (p->uniform_count == SKY_MAX_UNIFORMS) {
                sky_format(err, err_len, "too many uniforms in one program");
                goto fail;
            }
            p->uniforms[p->uniform_count] = &all[i]->uniforms[u];
            p->locations[p->uniform_count] = gl->glGetUniformLocation(p->id, all[i]->uniforms[u].name);
            p->uniform_count++;
        }
    s->program_count++;
    if (!s->identity_program) s->identity_program = p->id;
    return 0;
fail:
    for (int i = 0; i < 2; i++)
        if (shaders[i]) gl->glDeleteShader(shaders[i]);
    if (p->id) gl->glDeleteProgram(p->id);
    memset(p, 0, sizeof *p);
    return -1;
}

void sky_program_destroy(sky_core *s, sky_program *p)
{
    if (p->id) {
        s->gl.glDeleteProgram(p->id);
        s->program_count--;
    }
    memset(p, 0, sizeof *p);
}

void sky_program_apply(sky_core *s, const sky_program *p)
{
    const sky_gl *gl = &s->gl;
    const unsigned char *base = (const unsigned char *)&s->frame;
    int unit = 0;
    gl->glUseProgram(p->id);
    for (int i = 0; i < p->uniform_count; i++) {
        const sky_uniform_desc *u = p->uniforms[i];
        GLint loc = p->locations[i];
        if (loc < 0) continue;
        const float *v = (const float *)(const void *)(base + u->offset);
        float scaled[4];
        if (u->light && s->frame.light_scale != 1.0f && u->type <= SKY_U_F4) {
            /* mediump's range: the exposure brings night light up from
             * below 2^-14, and what it takes past 2^14 is far past white
             * (the tone map whitens from 8) */
            for (int k = 0; k <= (int)(u->type - SKY_U_F1); k++)
                scaled[k] = u->light & (1u << k) ? sky_clampf(v[k] * s->frame.light_scale, -16384.0f, 16384.0f) : v[k];
            v = scaled;
        }
        switch (u->type) {
        case SKY_U_F1: gl->glUniform1f(loc, v[0]); break;
        case SKY_U_F2: gl->glUniform2f(loc, v[0], v[1]); break;
        case SKY_U_F3: gl->glUniform3f(loc, v[0], v[1], v[2]); break;
        case SKY_U_F4: gl->glUniform4f(loc, v[0], v[1], v[2], v[3]); break;
        case SKY_U_M4: gl->glUniformMatrix4fv(loc, 1, GL_FALSE, v); break;
        case SKY_U_F1V: gl->glUniform1fv(loc, u->count, v); break;
        case SKY_U_TEX:
            gl->glActiveTexture(GL_TEXTURE0 + (GLenum)unit);
            gl->glBindTexture(s->textures[u->offset].target, s->textures[u->offset].id);
            gl->glUniform1i(loc, unit);
            unit++;
            break;
        }
    }
}

/* ---- textures and buffers ------------------------------------------------- */

static int is_pow2(int v) { return v > 0 && (v & (v - 1)) == 0; }

/* The texture bound to target on unit 0, after its upload: one level (no
 * mipmap chain: it would cost a third more memory and take the minimal
 * path past its 1.5 MiB budget; the cloud shader fades detail by its
 * screen-space footprint instead), its filter and wrap, unbound, and
 * recorded with its bytes and owner; or, on a GL error, deleted. */
static int finish_texture(sky_core *s, sky_texture *t, GLenum target, GLint filter, GLint wrap, int w, int h,
                          size_t bytes, sky_layer owner, const char *what, int check, char *err, size_t err_len)
{
    const sky_gl *gl = &s->gl;
    /* (ES 2.0 has no MAX_LEVEL: a texture without mipmaps filtered by
     * GL_LINEAR or GL_NEAREST is complete there anyway) */
    if (!s->caps.es) gl->glTexParameteri(target, GL_TEXTURE_MAX_LEVEL, 0);
    gl->glTexParameteri(target, GL_TEXTURE_MIN_FILTER, filter);
    gl->glTexParameteri(target, GL_TEXTURE_MAG_FILTER, filter);
    gl->glTexParameteri(target, GL_TEXTURE_WRAP_S, wrap);
    gl->glTexParameteri(target, GL_TEXTURE_WRAP_T, wrap);
    gl->glBindTexture(target, 0);
    GLenum e = check ? gl->glGetError() : GL_NO_ERROR;
    if (e != GL_NO_ERROR) {
        gl->glDeleteTextures(1, &t->id);
        t->id = 0;
        sky_format(err, err_len, "creating a %dx%d %s failed (GL error 0x%04x)", w, h, what, e);
        return -1;
    }
    t->target = target;
    t->width = w;
    t->height = h;
    t->bytes = bytes;
    t->owner = owner;
    return 0;
}

/* Uploads read client memory as tightly packed rows: the host's unpack
 * state (alignment, row length, skips, a bound pixel-unpack buffer) is set
 * aside around each, and put back after it. */
typedef struct unpack_state {
    GLint store[4], buffer;
} unpack_state;
static const GLenum unpack_names[4] = {GL_UNPACK_ALIGNMENT, GL_UNPACK_ROW_LENGTH, GL_UNPACK_SKIP_ROWS,
                                       GL_UNPACK_SKIP_PIXELS};

/* (ES 2.0 has the alignment alone) */
static int unpack_count(const sky_core *s) { return s->caps.unpack_rows ? 4 : 1; }

static void unpack_begin(sky_core *s, unpack_state *u)
{
    const sky_gl *gl = &s->gl;
    for (int i = 0; i < unpack_count(s); i++) {
        gl->glGetIntegerv(unpack_names[i], &u->store[i]);
        gl->glPixelStorei(unpack_names[i], i == 0 ? 1 : 0);
    }
    u->buffer = 0;
    if (s->caps.pixel_buffers) {
        gl->glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &u->buffer);
        gl->glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    }
}

static void unpack_end(sky_core *s, const unpack_state *u)
{
    const sky_gl *gl = &s->gl;
    for (int i = 0; i < unpack_count(s); i++) gl->glPixelStorei(unpack_names[i], u->store[i]);
    if (s->caps.pixel_buffers) gl->glBindBuffer(GL_PIXEL_UNPACK_BUFFER, (GLuint)u->buffer);
}

/* The internal format of an 8-bit texture of fmt (GL_RGB or GL_RGBA):
 * sized on desktop GL, the format itself on ES (ES 2.0 takes nothing
 * else, and ES 3.0 maps it to the sized one). */
static GLint internal_8bit(const sky_core *s, GLenum fmt)
{
    if (s->caps.es) return (GLint)fmt;
    return fmt == GL_RGB ? GL_RGB8 : GL_RGBA8;
}

/* A new texture name for id, bound to target on unit 0 (where every
 * upload happens) for its creation. */
static sky_texture *new_texture(sky_core *s, sky_texture_id id, GLenum target)
{
    sky_texture *t = &s->textures[id];
    s->gl.glGenTextures(1, &t->id);
    s->gl.glActiveTexture(GL_TEXTURE0);
    s->gl.glBindTexture(target, t->id);
    return t;
}

/* An 8-bit 2D texture of 3 or 4 channels, linear; pixels may be NULL. */
static int create_2d(sky_core *s, sky_texture_id id, sky_layer owner, const unsigned char *pixels, int channels,
                     int w, int h, GLint wrap, const char *what, int check, char *err, size_t err_len)
{
    const sky_gl *gl = &s->gl;
    sky_texture *t = new_texture(s, id, GL_TEXTURE_2D);
    unpack_state unpack;
    unpack_begin(s, &unpack);
    GLenum fmt = channels == 3 ? GL_RGB : GL_RGBA;
    gl->glTexImage2D(GL_TEXTURE_2D, 0, internal_8bit(s, fmt), w, h, 0, fmt, GL_UNSIGNED_BYTE, pixels);
    unpack_end(s, &unpack);
    return finish_texture(s, t, GL_TEXTURE_2D, GL_LINEAR, wrap, w, h, (size_t)w * (size_t)h * (size_t)channels,
                          owner, what, check, err, err_len);
}

int sky_texture_create(sky_core *s, sky_texture_id id, sky_layer owner, const unsigned char *pixels, int channels,
                       int w, int h, int repeat, char *err, size_t err_len)
{
    if (!is_pow2(w) || !is_pow2(h)) {
        /* COMPAT20 has no NPOT textures; keeping one rule for both profiles
         * makes the compat path the tested path. */
        sky_format(err, err_len, "texture %dx%d is not a power of two", w, h);
        return -1;
    }
    return create_2d(s, id, owner, pixels, channels, w, h, repeat ? GL_REPEAT : GL_CLAMP_TO_EDGE, "texture", 1, err,
                     err_len);
}

int sky_texture_resize_image(sky_core *s, sky_texture_id id, int w, int h)
{
    sky_texture old = s->textures[id];
    char err[8];
    if (sky_texture_create_image(s, id, old.owner, w, h, err, sizeof err)) {
        s->textures[id] = old;
        return -1;
    }
    if (old.id) s->gl.glDeleteTextures(1, &old.id);
    return 0;
}

int sky_texture_create_image(sky_core *s, sky_texture_id id, sky_layer owner, int w, int h, char *err,
                             size_t err_len)
{
    if (!s->caps.npot && (!is_pow2(w) || !is_pow2(h))) {
        sky_format(err, err_len, "image %dx%d is not a power of two, and the context has no NPOT textures", w, h);
        return -1;
    }
    /* at draw time (a resize) the host's pending errors are the host's: no
     * glGetError unless it asked for checks */
    int check = !s->drawing || s->cfg.check_gl_errors;
    return create_2d(s, id, owner, NULL, 4, w, h, GL_CLAMP_TO_EDGE, "render image", check, err, err_len);
}

int sky_texture_create_cube(sky_core *s, sky_texture_id id, sky_layer owner, const unsigned char *faces, int size,
                            int is_float, char *err, size_t err_len)
{
    const sky_gl *gl = &s->gl;
    sky_texture *t = new_texture(s, id, GL_TEXTURE_CUBE_MAP);
    unpack_state unpack;
    unpack_begin(s, &unpack);
    size_t face_bytes = (size_t)size * (size_t)size * (is_float ? 16u : 4u);
    for (int f = 0; f < 6; f++)
        gl->glTexImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + (GLenum)f, 0, is_float ? GL_RGBA32F : internal_8bit(s, GL_RGBA), size, size, 0,
                         GL_RGBA, is_float ? GL_FLOAT : GL_UNSIGNED_BYTE,
                         faces ? faces + (size_t)f * face_bytes : NULL);
    unpack_end(s, &unpack);
    return finish_texture(s, t, GL_TEXTURE_CUBE_MAP, GL_LINEAR, GL_CLAMP_TO_EDGE, size, size, 6u * face_bytes, owner,
                          "cube map", 1, err, err_len);
}

/* Reads an override file with a hard size cap: hostile files never cause a
 * large allocation. Returns NULL if absent (no such name, or a dangling
 * symlink: both mean "no override"), or NULL with *failed set and a
 * message naming the file. */
static unsigned char *read_override(const char *dir, const char *name, size_t *size, char *err, size_t err_len,
                                    int *failed)
{
    enum { MAX_FILE = 16 << 20 };
    char path[1024];
    *failed = 0;
    if (!dir) return NULL;
    int n = snprintf(path, sizeof path, "%s/%s", dir, name);
    if (n < 0 || (size_t)n >= sizeof path) {
        sky_format(err, err_len, "texture override path too long: %s/%s", dir, name);
        *failed = 1;
        return NULL;
    }
#if defined(_WIN32)
    FILE *f = fopen(path, "rb");
    if (!f) return NULL; /* no override for this one */
    unsigned char *buf = malloc(MAX_FILE);
    size_t got = buf ? fread(buf, 1, MAX_FILE, f) : 0;
    int too_big = buf && got == MAX_FILE && fgetc(f) != EOF;
    int read_error = ferror(f);
    fclose(f);
#else
    /* Non-blocking: opening a FIFO for reading otherwise waits for a
     * writer, which may never come (sky_create hung on one). Whatever is
     * not a regular file (FIFO, directory, device) is refused by fstat
     * before a byte is read. */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        /* no file of that name: no override for this one; but a name that
         * is there and leads nowhere (a dangling symbolic link) was meant
         * as one, and is reported */
        struct stat link;
        if (errno == ENOENT && lstat(path, &link) == 0 && S_ISLNK(link.st_mode)) {
            sky_format(err, err_len, "%s: a symbolic link to a file that is missing", path);
            *failed = 1;
            return NULL;
        }
        if (errno == ENOENT || errno == ENOTDIR) return NULL;
        sky_format(err, err_len, "%s: cannot open: %s", path, strerror(errno));
        *failed = 1;
        return NULL;
    }
    struct stat st;
    int stat_failed = fstat(fd, &st) != 0;
    if (stat_failed || !S_ISREG(st.st_mode)) {
        sky_format(err, err_len, "%s: %s, not a PNG file", path,
                   stat_failed            ? "cannot be examined (fstat failed)"
                   : S_ISDIR(st.st_mode)  ? "a directory"
                   : S_ISFIFO(st.st_mode) ? "a FIFO"
                                          : "not a regular file");
        close(fd);
        *failed = 1;
        return NULL;
    }
    unsigned char *buf = st.st_size <= MAX_FILE ? malloc(MAX_FILE) : NULL;
    size_t got = 0;
    int too_big = st.st_size > MAX_FILE, read_error = 0;
    while (buf && got < MAX_FILE) {
        ssize_t r = read(fd, buf + got, MAX_FILE - got);
        if (r < 0 && errno == EINTR) continue;
        if (r < 0) read_error = 1;
        if (r <= 0) break;
        got += (size_t)r;
    }
    /* a file grown past the cap since fstat */
    unsigned char extra;
    if (buf && got == MAX_FILE && read(fd, &extra, 1) == 1) too_big = 1;
    close(fd);
#endif
    if (!buf || too_big || read_error || got == 0) {
        sky_format(err, err_len, "%s: %s", path,
                   too_big ? "larger than 16 MiB" : !buf ? "out of memory" : read_error ? "read error" : "empty file");
        free(buf);
        *failed = 1;
        return NULL;
    }
    *size = got;
    return buf;
}

int sky_asset_load_rgba(sky_core *s, const char *name, int expect_w, int expect_h, unsigned char **rgba_out, char *err,
                        size_t err_len)
{
    size_t size = 0;
    int failed = 0;
    *rgba_out = NULL;
    unsigned char *file = read_override(s->cfg.texture_dir, name, &size, err, err_len, &failed);
    if (failed) return -1;
    const unsigned char *data = file;
    if (!file) {
        const sky_blob *b = sky_find_blob(name);
        if (!b) {
            sky_format(err, err_len, "asset %s is not embedded in this build", name);
            return -1;
        }
        data = b->data;
        size = b->size;
    }
    char label[160];
    snprintf(label, sizeof label, "%s asset %s", file ? "override" : "embedded", name);
    int rc = sky_image_decode(data, size, expect_w, expect_h, rgba_out, label, err, err_len);
    free(file);
    return rc;
}

int sky_texture_load(sky_core *s, sky_texture_id id, sky_layer owner, const char *name, int expect_w, int expect_h,
                     int repeat, char *err, size_t err_len)
{
    unsigned char *rgba = NULL;
    if (sky_asset_load_rgba(s, name, expect_w, expect_h, &rgba, err, err_len)) return -1;
    int rc = sky_texture_create(s, id, owner, rgba, 4, expect_w, expect_h, repeat, err, err_len);
    sky_png_free(rgba);
    return rc;
}

int sky_texture_create_lut(sky_core *s, sky_texture_id id, sky_layer owner, int w, int h, int is_float, char *err,
                           size_t err_len)
{
    const sky_gl *gl = &s->gl;
    if (!is_pow2(w) || !is_pow2(h)) {
        sky_format(err, err_len, "lookup texture %dx%d is not a power of two", w, h);
        return -1;
    }
    sky_texture *t = new_texture(s, id, GL_TEXTURE_2D);
    /* float (CORE33): RGBA32F, the precision twilight needs (16F would
     * lose the darkest tables' low bits) and a format every GL 3.3 can
     * render into; else RGBA8 for an encoding */
    unpack_state unpack; /* NULL means no data only without a bound unpack buffer */
    unpack_begin(s, &unpack);
    if (is_float)
        gl->glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, w, h, 0, GL_RGBA, GL_FLOAT, NULL);
    else
        gl->glTexImage2D(GL_TEXTURE_2D, 0, internal_8bit(s, GL_RGBA), w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    unpack_end(s, &unpack);
    /* an encoded table is decoded before it is blended: no filtering */
    return finish_texture(s, t, GL_TEXTURE_2D, is_float ? GL_LINEAR : GL_NEAREST, GL_CLAMP_TO_EDGE, w, h,
                          (size_t)w * (size_t)h * (is_float ? 16u : 4u), owner,
                          is_float ? "float lookup texture" : "RGBA8 lookup texture", 1, err, err_len);
}

/* A texture of d layers or slices w x h (CORE33), linear, clamped on
 * every axis, its contents data (RGBA of type) or none (NULL);
 * texel_bytes of ifmt's size. */
static int create_3d(sky_core *s, sky_texture_id id, sky_layer owner, GLenum target, GLint ifmt, GLenum type,
                     size_t texel_bytes, int w, int h, int d, const void *data, const char *what, char *err,
                     size_t err_len)
{
    const sky_gl *gl = &s->gl;
    sky_texture *t = new_texture(s, id, target);
    unpack_state unpack;
    unpack_begin(s, &unpack);
    gl->glTexImage3D(target, 0, ifmt, w, h, d, 0, GL_RGBA, type, data);
    unpack_end(s, &unpack);
    if (target == GL_TEXTURE_3D) gl->glTexParameteri(target, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    return finish_texture(s, t, target, GL_LINEAR, GL_CLAMP_TO_EDGE, w, h, (size_t)w * (size_t)h * (size_t)d * texel_bytes,
                          owner, what, 1, err, err_len);
}

int sky_texture_create_lut_layers(sky_core *s, sky_texture_id id, sky_layer owner, int w, int h, int layers,
                                  const float *rgba, char *err, size_t err_len)
{
    return create_3d(s, id, owner, GL_TEXTURE_2D_ARRAY, GL_RGBA32F, GL_FLOAT, 16u, w, h, layers, rgba,
                     "float lookup texture array", err, err_len);
}

int sky_texture_create_volume(sky_core *s, sky_texture_id id, sky_layer owner, int w, int h, int d, char *err,
                              size_t err_len)
{
    return create_3d(s, id, owner, GL_TEXTURE_3D, GL_RGBA16F, GL_HALF_FLOAT, 8u, w, h, d, NULL, "half-float volume",
                     err, err_len);
}

void sky_texture_update_lut(sky_core *s, sky_texture_id id, int w, int h, const unsigned char *rgba8, const float *rgb32f)
{
    const sky_gl *gl = &s->gl;
    gl->glActiveTexture(GL_TEXTURE0);
    gl->glBindTexture(GL_TEXTURE_2D, s->textures[id].id);
    unpack_state unpack;
    unpack_begin(s, &unpack);
    if (rgba8)
        gl->glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba8);
    else
        gl->glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, w, h, GL_RGB, GL_FLOAT, rgb32f);
    unpack_end(s, &unpack);
    gl->glBindTexture(GL_TEXTURE_2D, 0);
}

void sky_texture_destroy(sky_core *s, sky_texture_id id)
{
    sky_texture *t = &s->textures[id];
    if (t->id) s->gl.glDeleteTextures(1, &t->id);
    memset(t, 0, sizeof *t);
}

GLuint sky_buffer_create(sky_core *s, GLenum target, const void *data, size_t bytes, GLenum usage)
{
    const sky_gl *gl = &s->gl;
    GLuint b = 0;
    gl->glGenBuffers(1, &b);
    if (!b) return 0;
    gl->glBindBuffer(target, b);
    gl->glBufferData(target, (GLsizeiptr)bytes, data, usage);
    gl->glBindBuffer(target, 0);
    s->buffer_count++;
    s->buffer_bytes += bytes;
    return b;
}

void sky_buffer_update(sky_core *s, GLenum target, GLuint buffer, const void *data, size_t bytes, GLenum usage)
{
    const sky_gl *gl = &s->gl;
    gl->glBindBuffer(target, buffer);
    gl->glBufferData(target, (GLsizeiptr)bytes, data, usage);
}

void sky_buffers_destroy(sky_core *s, const GLuint *buffers, const size_t *bytes, int count)
{
    for (int i = 0; i < count; i++)
        if (buffers[i]) {
            s->gl.glDeleteBuffers(1, &buffers[i]);
            s->buffer_count--;
            s->buffer_bytes -= bytes[i];
        }
}

/* ---- host state ------------------------------------------------------------ */

void sky_gl_state_save(sky_core *s, sky_gl_state *st)
{
    const sky_gl *gl = &s->gl;
    memset(st, 0, sizeof *st);
    gl->glGetIntegerv(GL_CURRENT_PROGRAM, &st->program);
    gl->glGetIntegerv(GL_ACTIVE_TEXTURE, &st->active_texture);
    for (int i = 0; i < 4; i++) {
        gl->glActiveTexture(GL_TEXTURE0 + (GLenum)i);
        gl->glGetIntegerv(GL_TEXTURE_BINDING_2D, &st->textures[i]);
        gl->glGetIntegerv(GL_TEXTURE_BINDING_CUBE_MAP, &st->cube_textures[i]);
        if (s->profile == SKY_GL_CORE33) gl->glGetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &st->array_textures[i]);
    }
    gl->glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &st->array_buffer);
    if (s->caps.vertex_arrays) gl->glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &st->vao);
    gl->glGetIntegerv(GL_VIEWPORT, st->viewport);
    st->blend = gl->glIsEnabled(GL_BLEND);
    st->depth_test = gl->glIsEnabled(GL_DEPTH_TEST);
    st->cull_face = gl->glIsEnabled(GL_CULL_FACE);
    st->scissor_test = gl->glIsEnabled(GL_SCISSOR_TEST);
    st->stencil_test = gl->glIsEnabled(GL_STENCIL_TEST);
    if (!s->caps.es) {
        st->program_point_size = gl->glIsEnabled(GL_PROGRAM_POINT_SIZE);
        gl->glGetIntegerv(GL_POLYGON_MODE, st->polygon_mode);
    }
    if (s->caps.framebuffer_srgb) st->framebuffer_srgb = gl->glIsEnabled(GL_FRAMEBUFFER_SRGB);
    /* Queries a browser answers only by a round trip to its GPU process
     * (about 0.1 ms each in Chromium) are made only for state the frame
     * changes: the depth mask and function only where the sky is drawn
     * with the depth test (without it no depth is written); the scissor
     * box and clear colour in sky_gl_clear_viewport, their one user. */
    if (s->cfg.depth != SKY_DEPTH_NONE) {
        gl->glGetBooleanv(GL_DEPTH_WRITEMASK, &st->depth_mask);
        gl->glGetIntegerv(GL_DEPTH_FUNC, &st->depth_func);
    }
    gl->glGetBooleanv(GL_COLOR_WRITEMASK, st->color_mask);
    gl->glGetIntegerv(GL_BLEND_SRC_RGB, &st->blend_src_rgb);
    gl->glGetIntegerv(GL_BLEND_DST_RGB, &st->blend_dst_rgb);
    gl->glGetIntegerv(GL_BLEND_SRC_ALPHA, &st->blend_src_alpha);
    gl->glGetIntegerv(GL_BLEND_DST_ALPHA, &st->blend_dst_alpha);
    gl->glGetIntegerv(GL_BLEND_EQUATION_RGB, &st->blend_eq_rgb);
    gl->glGetIntegerv(GL_BLEND_EQUATION_ALPHA, &st->blend_eq_alpha);
    if (!s->caps.vertex_arrays) {
        /* No VAO of ours: the attribute arrays we use are global state (or
         * the state of a host's VAO left bound, put back into it). */
        gl->glGetIntegerv(GL_ELEMENT_ARRAY_BUFFER_BINDING, &st->element_buffer);
        for (GLuint i = 0; i < SKY_ATTRIBS; i++) {
            gl->glGetVertexAttribiv(i, GL_VERTEX_ATTRIB_ARRAY_ENABLED, &st->attrib_enabled[i]);
            gl->glGetVertexAttribiv(i, GL_VERTEX_ATTRIB_ARRAY_SIZE, &st->attrib_size[i]);
            gl->glGetVertexAttribiv(i, GL_VERTEX_ATTRIB_ARRAY_TYPE, &st->attrib_type[i]);
            gl->glGetVertexAttribiv(i, GL_VERTEX_ATTRIB_ARRAY_NORMALIZED, &st->attrib_norm[i]);
            gl->glGetVertexAttribiv(i, GL_VERTEX_ATTRIB_ARRAY_STRIDE, &st->attrib_stride[i]);
            gl->glGetVertexAttribiv(i, GL_VERTEX_ATTRIB_ARRAY_BUFFER_BINDING, &st->attrib_buffer[i]);
            gl->glGetVertexAttribPointerv(i, GL_VERTEX_ATTRIB_ARRAY_POINTER, &st->attrib_pointer[i]);
        }
    }
}

static void set_cap(const sky_gl *gl, GLenum cap, GLboolean on)
{
    if (on)
        gl->glEnable(cap);
    else
        gl->glDisable(cap);
}

void sky_gl_state_restore(sky_core *s, const sky_gl_state *st)
{
    const sky_gl *gl = &s->gl;
    if (!s->caps.vertex_arrays) {
        gl->glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, (GLuint)st->element_buffer);
        for (GLuint i = 0; i < SKY_ATTRIBS; i++) {
            gl->glBindBuffer(GL_ARRAY_BUFFER, (GLuint)st->attrib_buffer[i]);
            /* A pointer set while no buffer was bound is a client-memory
             * pointer; GL accepts it back in compatibility and ES 2.0
             * contexts, which are where this path runs. */
            gl->glVertexAttribPointer(i, st->attrib_size[i], (GLenum)st->attrib_type[i],
                                      (GLboolean)st->attrib_norm[i], st->attrib_stride[i], st->attrib_pointer[i]);
            if (st->attrib_enabled[i])
                gl->glEnableVertexAttribArray(i);
            else
                gl->glDisableVertexAttribArray(i);
        }
    } else {
        gl->glBindVertexArray((GLuint)st->vao);
    }
    gl->glBindBuffer(GL_ARRAY_BUFFER, (GLuint)st->array_buffer);
    for (int i = 3; i >= 0; i--) {
        gl->glActiveTexture(GL_TEXTURE0 + (GLenum)i);
        gl->glBindTexture(GL_TEXTURE_2D, (GLuint)st->textures[i]);
        gl->glBindTexture(GL_TEXTURE_CUBE_MAP, (GLuint)st->cube_textures[i]);
        if (s->profile == SKY_GL_CORE33) gl->glBindTexture(GL_TEXTURE_2D_ARRAY, (GLuint)st->array_textures[i]);
    }
    gl->glActiveTexture((GLenum)st->active_texture);
    /* A host may delete its program while it is current: GL keeps it
     * alive only until another one is used, which sky_draw did. Putting
     * back a name that no longer exists would be an error; 0 is what GL
     * itself leaves then. */
    gl->glUseProgram(st->program && gl->glIsProgram((GLuint)st->program) ? (GLuint)st->program : 0u);
    gl->glViewport(st->viewport[0], st->viewport[1], st->viewport[2], st->viewport[3]);
    set_cap(gl, GL_BLEND, st->blend);
    set_cap(gl, GL_DEPTH_TEST, st->depth_test);
    set_cap(gl, GL_CULL_FACE, st->cull_face);
    set_cap(gl, GL_SCISSOR_TEST, st->scissor_test);
    set_cap(gl, GL_STENCIL_TEST, st->stencil_test);
    if (s->caps.framebuffer_srgb) set_cap(gl, GL_FRAMEBUFFER_SRGB, st->framebuffer_srgb);
    /* (ES has neither switch: points are always sized by the shader, and
     * polygons always filled) */
    if (!s->caps.es) {
        set_cap(gl, GL_PROGRAM_POINT_SIZE, st->program_point_size);
        if (st->polygon_mode[0] == st->polygon_mode[1] || s->profile == SKY_GL_CORE33) {
            gl->glPolygonMode(GL_FRONT_AND_BACK, (GLenum)st->polygon_mode[0]);
        } else { /* a compatibility context may draw the two faces apart */
            gl->glPolygonMode(GL_FRONT, (GLenum)st->polygon_mode[0]);
            gl->glPolygonMode(GL_BACK, (GLenum)st->polygon_mode[1]);
        }
    }
    if (s->cfg.depth != SKY_DEPTH_NONE) {
        gl->glDepthMask(st->depth_mask);
        gl->glDepthFunc((GLenum)st->depth_func);
    }
    gl->glColorMask(st->color_mask[0], st->color_mask[1], st->color_mask[2], st->color_mask[3]);
    gl->glBlendFuncSeparate((GLenum)st->blend_src_rgb, (GLenum)st->blend_dst_rgb, (GLenum)st->blend_src_alpha,
                            (GLenum)st->blend_dst_alpha);
    gl->glBlendEquationSeparate((GLenum)st->blend_eq_rgb, (GLenum)st->blend_eq_alpha);
}

/* ---- what a frame sets ------------------------------------------------------ */

GLuint sky_gl_vertex_array_create(sky_core *s)
{
    GLuint vao = 0;
    s->gl.glGenVertexArrays(1, &vao);
    s->gl.glBindVertexArray(vao);
    return vao;
}

void sky_gl_vertex_array_bind(sky_core *s, GLuint vao)
{
    if (s->caps.vertex_arrays) s->gl.glBindVertexArray(vao);
}

void sky_gl_vertex_array_destroy(sky_core *s, GLuint vao) { s->gl.glDeleteVertexArrays(1, &vao); }

void sky_gl_frame_begin(sky_core *s, GLuint vao)
{
    const sky_gl *gl = &s->gl;
    if (s->cfg.depth == SKY_DEPTH_NONE) {
        gl->glDisable(GL_DEPTH_TEST); /* (and so no depth written: the mask may stay the host's) */
    } else {
        gl->glEnable(GL_DEPTH_TEST);
        gl->glDepthFunc(s->cfg.depth == SKY_DEPTH_FAR_ONE ? GL_LEQUAL : GL_GEQUAL);
        gl->glDepthMask(GL_FALSE);
    }
    gl->glDisable(GL_CULL_FACE);
    gl->glDisable(GL_STENCIL_TEST);
    gl->glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl->glDisable(GL_BLEND);
    if (!s->caps.es) gl->glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    if (s->caps.framebuffer_srgb) gl->glDisable(GL_FRAMEBUFFER_SRGB);
    if (vao) gl->glBindVertexArray(vao);
}

void sky_gl_blend(sky_core *s, sky_blend mode)
{
    const sky_gl *gl = &s->gl;
    if (mode == SKY_BLEND_NONE) {
        gl->glDisable(GL_BLEND);
        return;
    }
    gl->glEnable(GL_BLEND);
    gl->glBlendEquation(GL_FUNC_ADD);
    gl->glBlendFunc(GL_ONE, mode == SKY_BLEND_ADD ? GL_ONE : GL_ONE_MINUS_SRC_ALPHA);
}

void sky_gl_program_point_size(sky_core *s, int on)
{
    if (s->caps.es) return; /* always on there */
    if (on)
        s->gl.glEnable(GL_PROGRAM_POINT_SIZE);
    else
        s->gl.glDisable(GL_PROGRAM_POINT_SIZE);
}

float sky_gl_point_size_max(sky_core *s)
{
    GLfloat range[2] = {1.0f, 1.0f};
    s->gl.glGetFloatv(GL_ALIASED_POINT_SIZE_RANGE, range);
    return range[1] > 1.0f ? range[1] : 1.0f;
}

void sky_gl_clear_viewport(sky_core *s, const GLint viewport[4])
{
    const sky_gl *gl = &s->gl;
    GLint box[4];
    GLfloat colour[4];
    gl->glGetIntegerv(GL_SCISSOR_BOX, box);
    gl->glGetFloatv(GL_COLOR_CLEAR_VALUE, colour);
    gl->glEnable(GL_SCISSOR_TEST);
    gl->glScissor(viewport[0], viewport[1], viewport[2], viewport[3]);
    gl->glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl->glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    gl->glClear(GL_COLOR_BUFFER_BIT);
    gl->glDisable(GL_SCISSOR_TEST);
    gl->glScissor(box[0], box[1], box[2], box[3]);
    gl->glClearColor(colour[0], colour[1], colour[2], colour[3]);
}

void sky_gl_finish(sky_core *s) { s->gl.glFinish(); }

GLenum sky_gl_error(sky_core *s) { return s->gl.glGetError(); }

int sky_gl_context_current(sky_core *s) { return s->gl.glGetString(GL_VERSION) != NULL; }

int sky_gl_is_program(sky_core *s, GLuint program) { return program && s->gl.glIsProgram(program) == GL_TRUE; }

/* ---- render targets ------------------------------------------------------------ */

GLuint sky_gl_target_create(sky_core *s, sky_texture_id probe, char *err, size_t err_len)
{
    GLuint fbo = 0;
    s->gl.glGenFramebuffers(1, &fbo);
    sky_gl_target target;
    sky_gl_target_begin(s, fbo, probe, 1, 1, &target);
    GLenum status = s->gl.glCheckFramebufferStatus(GL_FRAMEBUFFER);
    sky_gl_target_end(s, &target);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        s->gl.glDeleteFramebuffers(1, &fbo);
        sky_format(err, err_len, "sky_create: the context cannot render into a float texture (status 0x%04x)", status);
        return 0;
    }
    return fbo;
}

void sky_gl_target_destroy(sky_core *s, GLuint fbo)
{
    if (fbo) s->gl.glDeleteFramebuffers(1, &fbo);
}

void sky_gl_target_begin(sky_core *s, GLuint fbo, sky_texture_id target, int w, int h, sky_gl_target *t)
{
    const sky_gl *gl = &s->gl;
    gl->glGetIntegerv(GL_FRAMEBUFFER_BINDING, &t->draw);
    t->read = t->draw;
    if (s->caps.separate_framebuffers) gl->glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &t->read);
    gl->glGetIntegerv(GL_VIEWPORT, t->viewport);
    t->scissor = gl->glIsEnabled(GL_SCISSOR_TEST);
    t->depth_test = gl->glIsEnabled(GL_DEPTH_TEST);
    t->discard = s->caps.rasterizer_discard && gl->glIsEnabled(GL_RASTERIZER_DISCARD);
    gl->glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    if (s->textures[target].target == GL_TEXTURE_2D_ARRAY || s->textures[target].target == GL_TEXTURE_3D)
        /* its first layer (CORE33) */
        gl->glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, s->textures[target].id, 0, 0);
    else
        gl->glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, s->textures[target].id, 0);
    gl->glViewport(0, 0, w, h);
    gl->glDisable(GL_SCISSOR_TEST);
    if (s->caps.rasterizer_discard) gl->glDisable(GL_RASTERIZER_DISCARD);
    gl->glDisable(GL_BLEND);
    gl->glDisable(GL_DEPTH_TEST);
    gl->glDisable(GL_STENCIL_TEST);
    gl->glDisable(GL_CULL_FACE);
    gl->glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

void sky_gl_target_begin_slices(sky_core *s, GLuint fbo, sky_texture_id volume, int first, int n, int w, int h,
                                sky_gl_target *t)
{
    const sky_gl *gl = &s->gl;
    GLenum bufs[8];
    if (n > 8) n = 8;
    sky_gl_target_begin(s, fbo, volume, w, h, t);
    for (int i = 0; i < n; i++) {
        bufs[i] = GL_COLOR_ATTACHMENT0 + (GLenum)i;
        gl->glFramebufferTextureLayer(GL_FRAMEBUFFER, bufs[i], s->textures[volume].id, 0, first + i);
    }
    gl->glDrawBuffers(n, bufs);
}

void sky_gl_target_end_slices(sky_core *s, int n, const sky_gl_target *t)
{
    const sky_gl *gl = &s->gl;
    static const GLenum first = GL_COLOR_ATTACHMENT0;
    if (n > 8) n = 8;
    for (int i = 0; i < n; i++) gl->glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + (GLenum)i, 0, 0, 0);
    gl->glDrawBuffers(1, &first);
    sky_gl_target_end(s, t);
}

void sky_gl_target_end(sky_core *s, const sky_gl_target *t)
{
    const sky_gl *gl = &s->gl;
    if (s->caps.separate_framebuffers) {
        gl->glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)t->draw);
        gl->glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)t->read);
    } else {
        gl->glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)t->draw);
    }
    gl->glViewport(t->viewport[0], t->viewport[1], t->viewport[2], t->viewport[3]);
    if (t->scissor) gl->glEnable(GL_SCISSOR_TEST);
    if (t->depth_test) gl->glEnable(GL_DEPTH_TEST); /* the sky drawn after the scene */
    if (t->discard) gl->glEnable(GL_RASTERIZER_DISCARD);
}

/* RGBA/FLOAT is the read-back every float framebuffer supports; the
 * host's pixel-pack state is set aside (a row length or a bound pack
 * buffer would send the pixels elsewhere). */
int sky_gl_read_rgba(sky_core *s, GLuint fbo, sky_texture_id source, int layer, int w, int h, float *rgba)
{
    const sky_gl *gl = &s->gl;
    GLint pack[4], pack_buffer = 0;
    static const GLenum pack_names[4] = {GL_PACK_ROW_LENGTH, GL_PACK_SKIP_ROWS, GL_PACK_SKIP_PIXELS, GL_PACK_ALIGNMENT};
    for (int i = 0; i < 4; i++) gl->glGetIntegerv(pack_names[i], &pack[i]);
    gl->glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &pack_buffer);
    for (int i = 0; i < 3; i++) gl->glPixelStorei(pack_names[i], 0);
    gl->glPixelStorei(GL_PACK_ALIGNMENT, 4);
    gl->glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    GLenum e = drain_errors(gl); /* an error that never clears: no read-back to trust */
    if (e == GL_NO_ERROR) {
        sky_gl_target t;
        sky_gl_target_begin(s, fbo, source, w, h, &t);
        if (layer > 0)
            gl->glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, s->textures[source].id, 0, layer);
        gl->glReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, rgba);
        e = gl->glGetError();
        sky_gl_target_end(s, &t);
    }
    for (int i = 0; i < 4; i++) gl->glPixelStorei(pack_names[i], pack[i]);
    gl->glBindBuffer(GL_PIXEL_PACK_BUFFER, (GLuint)pack_buffer);
    return e == GL_NO_ERROR ? 0 : -1;
}

int sky_gl_read_rgb(sky_core *s, GLuint fbo, sky_texture_id source, int w, int h, float *rgb)
{
    float *rgba = malloc(sizeof(float) * 4u * (size_t)w * (size_t)h);
    if (!rgba) return -1;
    int rc = sky_gl_read_rgba(s, fbo, source, -1, w, h, rgba);
    if (!rc)
        for (size_t i = 0; i < (size_t)w * (size_t)h; i++)
            for (int c = 0; c < 3; c++) rgb[3 * i + (size_t)c] = rgba[4 * i + (size_t)c];
    free(rgba);
    return rc;
}
