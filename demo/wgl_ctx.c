/*
 * Headless GL on Windows, behind osmesa_ctx.h's interface: a WGL context
 * of a window that is never shown, drawing into a framebuffer object of
 * the image's size (a hidden window's own pixels belong to no one), read
 * back by sky_osmesa_finish bottom row first, as OSMesa's buffer is.
 * What sky-render.exe and the Windows test runner (make test-windows,
 * under Wine) draw into. OpenGL ES contexts are Linux's (EGL) only.
 */
#include "osmesa_ctx.h"

#include <windows.h>

#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/wglext.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* What a GLFW- or SDL-style loader does: wglGetProcAddress knows the
 * extensions and everything after OpenGL 1.1, and answers NULL (or 1, 2,
 * 3, -1) for 1.1's own functions, which opengl32.dll exports. */
static sky_gl_proc wgl_loader(const char *name)
{
    PROC p = wglGetProcAddress(name);
    intptr_t v = (intptr_t)p;
    if (v == 0 || v == 1 || v == 2 || v == 3 || v == -1) {
        HMODULE gl = GetModuleHandleA("opengl32.dll");
        p = gl ? GetProcAddress(gl, name) : NULL;
    }
    return (sky_gl_proc)p;
}

sky_get_proc_address_fn sky_osmesa_loader(void) { return wgl_loader; }
sky_get_proc_address_fn sky_headless_loader(const sky_osmesa *o)
{
    (void)o;
    return wgl_loader;
}

static const char window_class[] = "libsky-headless";

/* The framebuffer object every frame goes to: an RGBA8 (or RGBA32F)
 * colour and a 24-bit depth renderbuffer, as OSMesa's buffer has. Returns
 * NULL or what failed. */
static const char *make_target(const sky_osmesa *o)
{
    PFNGLGENFRAMEBUFFERSPROC gen_framebuffers = (PFNGLGENFRAMEBUFFERSPROC)wgl_loader("glGenFramebuffers");
    PFNGLBINDFRAMEBUFFERPROC bind_framebuffer = (PFNGLBINDFRAMEBUFFERPROC)wgl_loader("glBindFramebuffer");
    PFNGLGENRENDERBUFFERSPROC gen_renderbuffers = (PFNGLGENRENDERBUFFERSPROC)wgl_loader("glGenRenderbuffers");
    PFNGLBINDRENDERBUFFERPROC bind_renderbuffer = (PFNGLBINDRENDERBUFFERPROC)wgl_loader("glBindRenderbuffer");
    PFNGLRENDERBUFFERSTORAGEPROC storage = (PFNGLRENDERBUFFERSTORAGEPROC)wgl_loader("glRenderbufferStorage");
    PFNGLFRAMEBUFFERRENDERBUFFERPROC attach =
        (PFNGLFRAMEBUFFERRENDERBUFFERPROC)wgl_loader("glFramebufferRenderbuffer");
    PFNGLCHECKFRAMEBUFFERSTATUSPROC status = (PFNGLCHECKFRAMEBUFFERSTATUSPROC)wgl_loader("glCheckFramebufferStatus");
    if (!gen_framebuffers || !bind_framebuffer || !gen_renderbuffers || !bind_renderbuffer || !storage || !attach ||
        !status)
        return "the context has no framebuffer objects";
    GLuint fbo = 0, rb[2] = {0, 0};
    gen_framebuffers(1, &fbo);
    bind_framebuffer(GL_FRAMEBUFFER, fbo);
    gen_renderbuffers(2, rb);
    bind_renderbuffer(GL_RENDERBUFFER, rb[0]);
    storage(GL_RENDERBUFFER, o->is_float ? GL_RGBA32F : GL_RGBA8, o->width, o->height);
    attach(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb[0]);
    bind_renderbuffer(GL_RENDERBUFFER, rb[1]);
    storage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, o->width, o->height);
    attach(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, rb[1]);
    bind_renderbuffer(GL_RENDERBUFFER, 0);
    /* (the objects go with the context) */
    if (status(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) return "the framebuffer object is incomplete";
    glViewport(0, 0, o->width, o->height); /* a new context's is the window's */
    return NULL;
}

int sky_osmesa_create(sky_osmesa *o, int width, int height, sky_gl_profile want, int is_float, char *err,
                      size_t err_len)
{
    memset(o, 0, sizeof *o);
    if (want == SKY_GL_ES20) {
        snprintf(err, err_len, "OpenGL ES contexts are made through EGL, on Linux only");
        return -1;
    }
    HINSTANCE instance = GetModuleHandleA(NULL);
    WNDCLASSA wc;
    memset(&wc, 0, sizeof wc);
    wc.style = CS_OWNDC;
    wc.lpfnWndProc = DefWindowProcA;
    wc.hInstance = instance;
    wc.lpszClassName = window_class;
    if (!RegisterClassA(&wc) && GetLastError() != ERROR_CLASS_ALREADY_EXISTS) {
        snprintf(err, err_len, "RegisterClass failed (%lu)", (unsigned long)GetLastError());
        return -1;
    }
    HWND window = CreateWindowExA(0, window_class, "libsky", WS_OVERLAPPEDWINDOW, 0, 0, 64, 64, NULL, NULL,
                                  instance, NULL);
    HDC dc = window ? GetDC(window) : NULL;
    PIXELFORMATDESCRIPTOR pfd;
    memset(&pfd, 0, sizeof pfd);
    pfd.nSize = sizeof pfd;
    pfd.nVersion = 1;
    pfd.dwFlags = PFD_DRAW_TO_WINDOW | PFD_SUPPORT_OPENGL | PFD_DOUBLEBUFFER;
    pfd.iPixelType = PFD_TYPE_RGBA;
    pfd.cColorBits = 32;
    pfd.cDepthBits = 24;
    int format = dc ? ChoosePixelFormat(dc, &pfd) : 0;
    HGLRC legacy = format && SetPixelFormat(dc, format, &pfd) ? wglCreateContext(dc) : NULL;
    HGLRC ctx = NULL;
    const char *failed = NULL;
    if (!legacy || !wglMakeCurrent(dc, legacy)) {
        failed = "no WGL context for a hidden window";
    } else if (want != SKY_GL_COMPAT20) {
        /* a 3.3 core context needs WGL_ARB_create_context, found through
         * the legacy one */
        PFNWGLCREATECONTEXTATTRIBSARBPROC create_attribs =
            (PFNWGLCREATECONTEXTATTRIBSARBPROC)(void (*)(void))wglGetProcAddress("wglCreateContextAttribsARB");
        const int attribs[] = {WGL_CONTEXT_MAJOR_VERSION_ARB, 3, WGL_CONTEXT_MINOR_VERSION_ARB, 3,
                               WGL_CONTEXT_PROFILE_MASK_ARB, WGL_CONTEXT_CORE_PROFILE_BIT_ARB, 0};
        ctx = create_attribs ? create_attribs(dc, NULL, attribs) : NULL;
        if (ctx && wglMakeCurrent(dc, ctx)) {
            wglDeleteContext(legacy);
            legacy = NULL;
            o->is_core = 1;
        } else if (ctx) {
            wglDeleteContext(ctx);
            ctx = NULL;
        }
        if (!ctx && want == SKY_GL_CORE33) failed = "no 3.3 core WGL context";
    }
    if (!failed && !ctx) ctx = legacy, legacy = NULL;
    o->width = width;
    o->height = height;
    o->is_float = is_float;
    o->pixels = failed ? NULL : calloc((size_t)width * (size_t)height * 4u, is_float ? sizeof(float) : 1u);
    if (!failed && !o->pixels) failed = "out of memory for the image";
    if (!failed) failed = make_target(o);
    if (failed) {
        snprintf(err, err_len, "WGL: %s", failed);
        wglMakeCurrent(NULL, NULL);
        if (ctx) wglDeleteContext(ctx);
        if (legacy) wglDeleteContext(legacy);
        if (dc) ReleaseDC(window, dc);
        if (window) DestroyWindow(window);
        free(o->pixels);
        memset(o, 0, sizeof *o);
        return -1;
    }
    o->ctx = ctx;
    o->window = window;
    o->device = dc;
    return 0;
}

void sky_osmesa_destroy(sky_osmesa *o)
{
    if (o->ctx) {
        wglMakeCurrent(NULL, NULL);
        wglDeleteContext((HGLRC)o->ctx);
        ReleaseDC((HWND)o->window, (HDC)o->device);
        DestroyWindow((HWND)o->window);
    }
    free(o->pixels);
    memset(o, 0, sizeof *o);
}

void sky_osmesa_make_current(const sky_osmesa *o) { wglMakeCurrent((HDC)o->device, (HGLRC)o->ctx); }
void sky_osmesa_release_current(void) { wglMakeCurrent(NULL, NULL); }

/* The frame is read from the framebuffer object the context's draw
 * binding still names (the library restores the host's bindings). */
void sky_osmesa_finish(sky_osmesa *o)
{
    glFinish();
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, o->width, o->height, GL_RGBA, o->is_float ? GL_FLOAT : GL_UNSIGNED_BYTE, o->pixels);
}
