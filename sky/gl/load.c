/*
 * GL backend, loading: the function table through the host's
 * getProcAddress, the context's version and capabilities, and the profile
 * the sky uses in it.
 */
#include "gl.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* An entry point from the host's loader; on Windows, what it answers NULL
 * for (or 1, 2, 3, -1: wglGetProcAddress's failures, as for every OpenGL
 * 1.1 function) from opengl32.dll, the system's own GL library, as GLFW's
 * and SDL's loaders do (gl/win32.c). */
static sky_gl_proc gl_proc(const sky_core *s, const char *name)
{
    sky_gl_proc p = s->cfg.get_proc_address(name);
#if defined(_WIN32)
    intptr_t v = (intptr_t)p;
    if (v == 0 || v == 1 || v == 2 || v == 3 || v == -1) p = sky_gl_system_proc(name);
#endif
    return p;
}

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
GLenum sky_gl_drain_errors(const sky_gl *gl)
{
    enum { MAX_READS = 64 };
    GLenum e = GL_NO_ERROR;
    for (int i = 0; i < MAX_READS; i++)
        if ((e = gl->glGetError()) == GL_NO_ERROR) break;
    return e;
}

/* The message for errors that sky_gl_drain_errors could not clear. */
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
            gl->glGenVertexArrays = (void(SKY_APIENTRY *)(GLsizei, GLuint *))gl_proc(s, "glGenVertexArraysOES");
            gl->glDeleteVertexArrays = (void(SKY_APIENTRY *)(GLsizei, const GLuint *))gl_proc(s, "glDeleteVertexArraysOES");
            gl->glBindVertexArray = (void(SKY_APIENTRY *)(GLuint))gl_proc(s, "glBindVertexArrayOES");
            caps->vertex_arrays = 1;
        }
        if (gl_ver >= 30) caps->vertex_arrays = 1;
        caps->vertex_arrays = caps->vertex_arrays && gl->glGenVertexArrays && gl->glDeleteVertexArrays &&
                              gl->glBindVertexArray;
        return sky_gl_drain_errors(gl);
    }
    caps->unpack_rows = caps->derivatives = caps->fragment_highp = 1;
    caps->rasterizer_discard = gl_ver >= 30;
    caps->pixel_buffers = gl_ver >= 21 || has_extension(gl, "GL_ARB_pixel_buffer_object");
    caps->framebuffer_srgb = gl_ver >= 30 || has_extension(gl, "GL_ARB_framebuffer_sRGB") ||
                             has_extension(gl, "GL_EXT_framebuffer_sRGB");
    int arb_fbo = gl_ver >= 30 || has_extension(gl, "GL_ARB_framebuffer_object");
    int ext_fbo = has_extension(gl, "GL_EXT_framebuffer_object");
    if (!arb_fbo && ext_fbo && !gl->glGenFramebuffers) {
#define SKY_GL_LOAD_EXT(name, params) gl->name = (void(SKY_APIENTRY *) params)gl_proc(s, #name "EXT");
        SKY_GL_LOAD_EXT(glGenFramebuffers, (GLsizei n, GLuint *f))
        SKY_GL_LOAD_EXT(glDeleteFramebuffers, (GLsizei n, const GLuint *f))
        SKY_GL_LOAD_EXT(glBindFramebuffer, (GLenum target, GLuint f))
        SKY_GL_LOAD_EXT(glFramebufferTexture2D, (GLenum target, GLenum att, GLenum textarget, GLuint t, GLint level))
#undef SKY_GL_LOAD_EXT
        gl->glCheckFramebufferStatus = (GLenum(SKY_APIENTRY *)(GLenum))gl_proc(s, "glCheckFramebufferStatusEXT");
    }
    caps->render_to_rgba8 = (arb_fbo || ext_fbo) && gl->glGenFramebuffers && gl->glDeleteFramebuffers &&
                            gl->glBindFramebuffer && gl->glFramebufferTexture2D && gl->glCheckFramebufferStatus;
    caps->separate_framebuffers = arb_fbo || has_extension(gl, "GL_EXT_framebuffer_blit");
    caps->npot = gl_ver >= 30 || has_extension(gl, "GL_ARB_texture_non_power_of_two");
    return sky_gl_drain_errors(gl);
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
    /* Every pointer is stored through its own member type; a missing entry
     * point is reported by name. */
#define SKY_GL_LOAD(ret, name, params)                                                   \
    s->gl.name = (ret(SKY_APIENTRY *) params)gl_proc(s, #name);                                 \
    if (!s->gl.name) {                                                                   \
        sky_format(err, err_len, "the GL context lacks %s (OpenGL 2.0 is the minimum)", #name); \
        return -1;                                                                       \
    }
    SKY_GL_FUNCS_20(SKY_GL_LOAD)
#define SKY_GL_LOAD_OPT(ret, name, params) s->gl.name = (ret(SKY_APIENTRY *) params)gl_proc(s, #name);
    SKY_GL_FUNCS_30(SKY_GL_LOAD_OPT)
#undef SKY_GL_LOAD_OPT

    const sky_gl *gl = &s->gl;
    GLenum e = sky_gl_drain_errors(gl); /* the host's old errors are not ours */
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
    if ((e = sky_gl_drain_errors(gl)) != GL_NO_ERROR) return undrained(e, err, err_len);

    int is_core_context = 0;
    if (gl_ver >= 32) {
        GLint mask = 0;
        gl->glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &mask);
        is_core_context = (mask & GL_CONTEXT_CORE_PROFILE_BIT) != 0;
        if ((e = sky_gl_drain_errors(gl)) != GL_NO_ERROR) return undrained(e, err, err_len);
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
