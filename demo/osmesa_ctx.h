/*
 * A headless GL context (on Windows, demo/wgl_ctx.c: a hidden window's
 * WGL context drawing into a framebuffer object; the rest of this
 * comment is Linux's), through OSMesa (Mesa's llvmpipe, or softpipe with
 * GALLIUM_DRIVER=softpipe): what sky-render, the tests and a display-less
 * sky-demo draw into. For the ES20 profile, an OpenGL ES 2.0 context
 * through EGL instead (Mesa's surfaceless platform, a pbuffer): set
 * MESA_GLES_VERSION_OVERRIDE=2.0 for the version string of real ES 2.0
 * hardware (Mesa offers ES 3.2 otherwise).
 */
#ifndef SKY_OSMESA_CTX_H
#define SKY_OSMESA_CTX_H

#include "sky.h"

#include <stddef.h>
#include <stdio.h>

typedef struct sky_osmesa {
    void *ctx;       /* OSMesaContext, or EGLContext when is_es */
    void *pixels;    /* w*h RGBA, bottom row first; bytes or floats (EGL:
                        read back by sky_osmesa_finish) */
    int width, height;
    int is_float;
    int is_core;     /* the context is a 3.3 core profile */
    int is_es;       /* an OpenGL ES context through EGL */
    void *egl_display, *egl_surface;
    void *window, *device; /* Windows: the hidden HWND and its HDC */
} sky_osmesa;

/* want: SKY_GL_CORE33 asks for a 3.3 core context, SKY_GL_COMPAT20 for a
 * legacy one, SKY_GL_AUTO tries core first, SKY_GL_ES20 an ES 2.0 context
 * through EGL. is_float: a float RGBA colour buffer (for linear HDR
 * output); with EGL, an RGBA32F texture bound as the draw framebuffer,
 * which needs an ES 3.0 context with EXT_color_buffer_float (not one
 * under MESA_GLES_VERSION_OVERRIDE=2.0). Returns 0, or -1 with err. */
int sky_osmesa_create(sky_osmesa *o, int width, int height, sky_gl_profile want, int is_float, char *err,
                      size_t err_len);
void sky_osmesa_destroy(sky_osmesa *o);
sky_get_proc_address_fn sky_osmesa_loader(void);
/* Makes o's context current again (after another one was). */
void sky_osmesa_make_current(const sky_osmesa *o);
/* Leaves the thread with no current context. */
void sky_osmesa_release_current(void);
/* The loader for o's kind of context (OSMesa's, or EGL's). */
sky_get_proc_address_fn sky_headless_loader(const sky_osmesa *o);
/* Waits for rendering to finish (and with EGL reads the pixels back). */
void sky_osmesa_finish(sky_osmesa *o);

/* The writers below put the image in a temporary file beside path and
 * rename it over path only when every byte was written: a failure leaves
 * path as it was. A path that exists and is not a regular file (a
 * directory, a device) is refused and left untouched. */
/* Writes the buffer as an 8-bit PNG (top row first). Returns 0, or -1 with
 * err (which may be NULL). */
int sky_osmesa_write_png(const sky_osmesa *o, const char *path, char *err, size_t err_len);
/* Writes a float buffer as a PFM (RGB, little-endian, bottom row first as
 * the format wants). Returns 0, or -1 with err (which may be NULL). */
int sky_osmesa_write_pfm(const sky_osmesa *o, const char *path, char *err, size_t err_len);
/* Writes an 8-bit RGB image (top row first) as a PNG. Returns 0 or -1. */
int sky_write_png_rgb(const char *path, int width, int height, const unsigned char *rgb);
/* Encodes a PNG of comp 8-bit channels into f, checking every write and a
 * final fflush. Returns 0, or -1 with errno. f stays open. */
int sky_write_png_file(FILE *f, int width, int height, int comp, const unsigned char *px, int stride);

#endif
