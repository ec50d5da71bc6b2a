/*
 * GL backend, textures and buffers: every kind of texture the sky makes
 * (8-bit images, render images, lookup tables, arrays, volumes, cube
 * maps), the host's unpack state set aside around uploads, and the
 * vertex buffers with their byte counts.
 */
#include "gl.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

int sky_texture_register(sky_core *s)
{
    if (s->texture_count == s->texture_capacity) {
        int capacity = s->texture_capacity ? 2 * s->texture_capacity : SKY_TEX_COUNT + 4;
        sky_texture *grown = realloc(s->textures, (size_t)capacity * sizeof *grown);
        if (!grown) return -1;
        memset(grown + s->texture_capacity, 0, (size_t)(capacity - s->texture_capacity) * sizeof *grown);
        s->textures = grown;
        s->texture_capacity = capacity;
    }
    return s->texture_count++;
}
