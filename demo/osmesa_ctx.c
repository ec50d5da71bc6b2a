/* Headless GL through OSMesa; see osmesa_ctx.h. */
#include "osmesa_ctx.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/osmesa.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A 3.3 core context, or any legacy one (asking for 1.0 takes whatever
 * the driver offers, so the library itself judges an old version). */
static OSMesaContext make_context(int core)
{
    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_PROFILE,
                           core ? OSMESA_CORE_PROFILE : OSMESA_COMPAT_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION,
                           core ? 3 : 1, OSMESA_CONTEXT_MINOR_VERSION, core ? 3 : 0, 0};
    return OSMesaCreateContextAttribs(attribs, NULL);
}

/* GL's entry points in an EGL context (core names included, as Mesa's
 * EGL gives them). */
static sky_gl_proc egl_loader(const char *name) { return (sky_gl_proc)eglGetProcAddress(name); }

/* ES's float colour target: an RGBA32F texture behind a framebuffer,
 * where ES 3.0 and EXT_color_buffer_float allow it. Returns NULL or why
 * not. */
static const char *egl_float_target(const sky_osmesa *o)
{
    const GLubyte *(*get_string)(GLenum) = (const GLubyte *(*)(GLenum))egl_loader("glGetString");
    void (*gen_textures)(GLsizei, GLuint *) = (void (*)(GLsizei, GLuint *))egl_loader("glGenTextures");
    void (*bind_texture)(GLenum, GLuint) = (void (*)(GLenum, GLuint))egl_loader("glBindTexture");
    void (*tex_image)(GLenum, GLint, GLint, GLsizei, GLsizei, GLint, GLenum, GLenum, const void *) =
        (void (*)(GLenum, GLint, GLint, GLsizei, GLsizei, GLint, GLenum, GLenum, const void *))egl_loader(
            "glTexImage2D");
    void (*gen_framebuffers)(GLsizei, GLuint *) = (void (*)(GLsizei, GLuint *))egl_loader("glGenFramebuffers");
    void (*bind_framebuffer)(GLenum, GLuint) = (void (*)(GLenum, GLuint))egl_loader("glBindFramebuffer");
    void (*attach)(GLenum, GLenum, GLenum, GLuint, GLint) =
        (void (*)(GLenum, GLenum, GLenum, GLuint, GLint))egl_loader("glFramebufferTexture2D");
    GLenum (*status)(GLenum) = (GLenum(*)(GLenum))egl_loader("glCheckFramebufferStatus");
    if (!get_string || !gen_textures || !bind_texture || !tex_image || !gen_framebuffers || !bind_framebuffer ||
        !attach || !status)
        return "the context lacks framebuffer entry points";
    const char *version = (const char *)get_string(GL_VERSION), *ext = (const char *)get_string(GL_EXTENSIONS);
    if (!version || strncmp(version, "OpenGL ES 3", 11) || !ext || !strstr(ext, "GL_EXT_color_buffer_float"))
        return "a float target needs OpenGL ES 3.0 with EXT_color_buffer_float";
    GLuint tex = 0, fbo = 0;
    gen_textures(1, &tex);
    bind_texture(GL_TEXTURE_2D, tex);
    tex_image(GL_TEXTURE_2D, 0, 0x8814 /* GL_RGBA32F */, o->width, o->height, 0, GL_RGBA, GL_FLOAT, NULL);
    bind_texture(GL_TEXTURE_2D, 0);
    gen_framebuffers(1, &fbo);
    bind_framebuffer(0x8D40 /* GL_FRAMEBUFFER */, fbo);
    attach(0x8D40, 0x8CE0 /* GL_COLOR_ATTACHMENT0 */, GL_TEXTURE_2D, tex, 0);
    /* (both go with the context) */
    return status(0x8D40) == 0x8CD5 /* GL_FRAMEBUFFER_COMPLETE */ ? NULL : "the RGBA32F framebuffer is incomplete";
}

/* An OpenGL ES 2 context on Mesa's surfaceless EGL platform, drawing into
 * a pbuffer of the image's size (or, is_float, the float target). */
static int egl_create(sky_osmesa *o, int width, int height, int is_float, char *err, size_t err_len)
{
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    EGLDisplay dpy = get_display ? get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL)
                                 : EGL_NO_DISPLAY;
    if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, NULL, NULL)) {
        snprintf(err, err_len, "EGL: no surfaceless Mesa display (libegl-mesa0 installed?)");
        return -1;
    }
    const EGLint config_attribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_ES2_BIT,
                                     EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_ALPHA_SIZE, 8,
                                     EGL_DEPTH_SIZE, 24, EGL_NONE};
    const EGLint surface_attribs[] = {EGL_WIDTH, width, EGL_HEIGHT, height, EGL_NONE};
    const EGLint context_attribs[] = {EGL_CONTEXT_CLIENT_VERSION, 2, EGL_NONE};
    EGLConfig config;
    EGLint n = 0;
    EGLSurface surface = EGL_NO_SURFACE;
    EGLContext ctx = EGL_NO_CONTEXT;
    const char *failed = NULL;
    if (!eglBindAPI(EGL_OPENGL_ES_API) || !eglChooseConfig(dpy, config_attribs, &config, 1, &n) || n < 1)
        failed = "no RGBA8 pbuffer configuration for OpenGL ES 2";
    else if ((surface = eglCreatePbufferSurface(dpy, config, surface_attribs)) == EGL_NO_SURFACE)
        failed = "eglCreatePbufferSurface failed";
    else if ((ctx = eglCreateContext(dpy, config, EGL_NO_CONTEXT, context_attribs)) == EGL_NO_CONTEXT)
        failed = "eglCreateContext (OpenGL ES 2) failed";
    else if (!eglMakeCurrent(dpy, surface, surface, ctx))
        failed = "eglMakeCurrent failed";
    o->width = width;
    o->height = height;
    o->pixels = failed ? NULL : calloc((size_t)width * (size_t)height * 4u, is_float ? sizeof(float) : 1u);
    if (!failed && !o->pixels) failed = "out of memory for the image";
    if (!failed && is_float) failed = egl_float_target(o);
    if (failed) {
        snprintf(err, err_len, "EGL: %s (0x%04x)", failed, (unsigned)eglGetError());
        free(o->pixels);
        o->pixels = NULL;
        eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (ctx != EGL_NO_CONTEXT) eglDestroyContext(dpy, ctx);
        if (surface != EGL_NO_SURFACE) eglDestroySurface(dpy, surface);
        eglTerminate(dpy);
        return -1;
    }
    o->ctx = ctx;
    o->egl_display = dpy;
    o->egl_surface = surface;
    o->is_es = 1;
    o->is_float = is_float;
    return 0;
}

int sky_osmesa_create(sky_osmesa *o, int width, int height, sky_gl_profile want, int is_float, char *err,
                      size_t err_len)
{
    memset(o, 0, sizeof *o);
    if (want == SKY_GL_ES20) return egl_create(o, width, height, is_float, err, err_len);
    OSMesaContext ctx = NULL;
    if (want != SKY_GL_COMPAT20) {
        ctx = make_context(1);
        o->is_core = ctx != NULL;
    }
    if (!ctx && want != SKY_GL_CORE33) ctx = make_context(0);
    if (!ctx) {
        snprintf(err, err_len, "OSMesa could not create a%s GL context",
                 want == SKY_GL_CORE33 ? " 3.3 core" : want == SKY_GL_COMPAT20 ? " compatibility" : "ny");
        return -1;
    }
    size_t px = (size_t)width * (size_t)height * 4u;
    o->pixels = calloc(px, is_float ? sizeof(float) : 1u);
    if (!o->pixels) {
        OSMesaDestroyContext(ctx);
        snprintf(err, err_len, "out of memory for a %dx%d image", width, height);
        return -1;
    }
    if (!OSMesaMakeCurrent(ctx, o->pixels, is_float ? GL_FLOAT : GL_UNSIGNED_BYTE, width, height)) {
        OSMesaDestroyContext(ctx);
        free(o->pixels);
        o->pixels = NULL;
        snprintf(err, err_len, "OSMesaMakeCurrent failed for a %dx%d %s buffer", width, height,
                 is_float ? "float" : "8-bit");
        return -1;
    }
    o->ctx = ctx;
    o->width = width;
    o->height = height;
    o->is_float = is_float;
    return 0;
}

void sky_osmesa_destroy(sky_osmesa *o)
{
    if (o->is_es) {
        eglMakeCurrent(o->egl_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(o->egl_display, o->ctx);
        eglDestroySurface(o->egl_display, o->egl_surface);
        eglTerminate(o->egl_display);
    } else if (o->ctx) {
        OSMesaDestroyContext((OSMesaContext)o->ctx);
    }
    free(o->pixels);
    memset(o, 0, sizeof *o);
}

/* OSMesaGetProcAddress returns an unprototyped void (*)(), which is
 * compatible with sky_gl_proc; the wrapper keeps the types exact. */
static sky_gl_proc loader(const char *name) { return (sky_gl_proc)OSMesaGetProcAddress(name); }
sky_get_proc_address_fn sky_osmesa_loader(void) { return loader; }

void sky_osmesa_make_current(const sky_osmesa *o)
{
    if (o->is_es)
        eglMakeCurrent(o->egl_display, o->egl_surface, o->egl_surface, o->ctx);
    else
        OSMesaMakeCurrent((OSMesaContext)o->ctx, o->pixels, o->is_float ? GL_FLOAT : GL_UNSIGNED_BYTE, o->width,
                          o->height);
}

void sky_osmesa_release_current(void) { OSMesaMakeCurrent(NULL, NULL, 0, 0, 0); }

sky_get_proc_address_fn sky_headless_loader(const sky_osmesa *o) { return o->is_es ? egl_loader : loader; }

/* glFinish through OSMesa's own table: a program that also links -lGL
 * (sky-demo, sky-game) would otherwise bind the symbol to GLVND's libGL,
 * whose glFinish without a current GLX context does nothing, and llvmpipe
 * would never render into the buffer before it is read. */
void sky_osmesa_finish(sky_osmesa *o)
{
    sky_get_proc_address_fn gpa = sky_headless_loader(o);
    void (*finish)(void) = (void (*)(void))gpa("glFinish");
    if (finish) finish();
    if (!o->is_es) return;
    /* EGL draws into its own surface (or the float target): the image is
     * read back, RGBA8 (what every ES 2.0 context reads) or RGBA32F,
     * bottom row first as OSMesa's */
    void (*pixel_store)(GLenum, GLint) = (void (*)(GLenum, GLint))gpa("glPixelStorei");
    void (*read_pixels)(GLint, GLint, GLsizei, GLsizei, GLenum, GLenum, void *) =
        (void (*)(GLint, GLint, GLsizei, GLsizei, GLenum, GLenum, void *))gpa("glReadPixels");
    if (pixel_store && read_pixels) {
        pixel_store(GL_PACK_ALIGNMENT, 4);
        read_pixels(0, 0, o->width, o->height, GL_RGBA, o->is_float ? GL_FLOAT : GL_UNSIGNED_BYTE, o->pixels);
    }
}
