/* Headless GL through OSMesa; see osmesa_ctx.h. */
#include "osmesa_ctx.h"

#include <GL/osmesa.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-prototypes"
#endif
#include <stb/stb_image_write.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

/* A 3.3 core context, or any legacy one (asking for 1.0 takes whatever
 * the driver offers, so the library itself judges an old version). */
static OSMesaContext make_context(int core)
{
    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_PROFILE,
                           core ? OSMESA_CORE_PROFILE : OSMESA_COMPAT_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION,
                           core ? 3 : 1, OSMESA_CONTEXT_MINOR_VERSION, core ? 3 : 0, 0};
    return OSMesaCreateContextAttribs(attribs, NULL);
}

int sky_osmesa_create(sky_osmesa *o, int width, int height, sky_gl_profile want, int is_float, char *err,
                      size_t err_len)
{
    memset(o, 0, sizeof *o);
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
    if (o->ctx) OSMesaDestroyContext((OSMesaContext)o->ctx);
    free(o->pixels);
    memset(o, 0, sizeof *o);
}

/* OSMesaGetProcAddress returns an unprototyped void (*)(), which is
 * compatible with sky_gl_proc; the wrapper keeps the types exact. */
static sky_gl_proc loader(const char *name) { return (sky_gl_proc)OSMesaGetProcAddress(name); }
sky_get_proc_address_fn sky_osmesa_loader(void) { return loader; }

/* glFinish through OSMesa's own table: a program that also links -lGL
 * (sky-demo, sky-game) would otherwise bind the symbol to GLVND's libGL,
 * whose glFinish without a current GLX context does nothing, and llvmpipe
 * would never render into the buffer before it is read. */
void sky_osmesa_finish(sky_osmesa *o)
{
    (void)o;
    void (*finish)(void) = (void (*)(void))loader("glFinish");
    if (finish) finish();
}

int sky_osmesa_write_png(const sky_osmesa *o, const char *path)
{
    size_t row = (size_t)o->width * 4u;
    unsigned char *img = malloc(row * (size_t)o->height);
    if (!img) return -1;
    for (int y = 0; y < o->height; y++) {
        unsigned char *dst = img + row * (size_t)(o->height - 1 - y);
        if (o->is_float) {
            const float *src = (const float *)o->pixels + (size_t)y * row;
            for (size_t i = 0; i < row; i++) {
                float v = src[i] < 0.0f ? 0.0f : src[i] > 1.0f ? 1.0f : src[i];
                dst[i] = (unsigned char)(v * 255.0f + 0.5f);
            }
        } else {
            memcpy(dst, (const unsigned char *)o->pixels + (size_t)y * row, row);
        }
        for (int x = 0; x < o->width; x++) dst[4 * x + 3] = 255; /* opaque */
    }
    int ok = stbi_write_png(path, o->width, o->height, 4, img, (int)row);
    free(img);
    if (!ok) remove(path); /* no partial file left behind */
    return ok ? 0 : -1;
}

int sky_osmesa_write_pfm(const sky_osmesa *o, const char *path)
{
    if (!o->is_float) return -1;
    FILE *f = fopen(path, "wb");
    if (!f) return -1;
    /* floats are written natively; the sign of the scale says which byte
     * order that is (negative = little endian) */
    const float one = 1.0f;
    unsigned char first_byte;
    memcpy(&first_byte, &one, 1);
    int ok = fprintf(f, "PF\n%d %d\n%s\n", o->width, o->height, first_byte == 0 ? "-1.0" : "1.0") > 0;
    const float *px = o->pixels;
    for (int y = 0; ok && y < o->height; y++)
        for (int x = 0; ok && x < o->width; x++) {
            const float *p = px + ((size_t)y * (size_t)o->width + (size_t)x) * 4u;
            ok = fwrite(p, sizeof(float), 3, f) == 3;
        }
    if (fclose(f) != 0) ok = 0;
    if (!ok) remove(path);
    return ok ? 0 : -1;
}

int sky_write_png_rgb(const char *path, int width, int height, const unsigned char *rgb)
{
    if (!path || !rgb || width <= 0 || height <= 0) return -1;
    int ok = stbi_write_png(path, width, height, 3, rgb, width * 3);
    if (!ok) remove(path);
    return ok ? 0 : -1;
}
