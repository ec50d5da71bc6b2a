/*
 * GL backend, render targets: rendering into the sky's textures (the
 * lookup tables, the dome's image, the froxel volume) and reading them
 * back.
 */
#include "gl.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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
    sky_gl_framebuffers_get(s, &t->draw, &t->read);
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
    sky_gl_framebuffers_set(s, t->draw, t->read);
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
    GLenum e = sky_gl_drain_errors(gl); /* an error that never clears: no read-back to trust */
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

void sky_gl_framebuffers_get(sky_core *s, GLint *draw, GLint *read)
{
    s->gl.glGetIntegerv(GL_FRAMEBUFFER_BINDING, draw);
    *read = *draw;
    if (s->caps.separate_framebuffers) s->gl.glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, read);
}

void sky_gl_framebuffers_set(sky_core *s, GLint draw, GLint read)
{
    if (s->caps.separate_framebuffers) {
        s->gl.glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)draw);
        s->gl.glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)read);
    } else {
        s->gl.glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)draw);
    }
}

GLuint sky_gl_framebuffer_create(sky_core *s)
{
    GLuint fbo = 0;
    s->gl.glGenFramebuffers(1, &fbo);
    return fbo;
}

GLenum sky_gl_target_cube_face(sky_core *s, GLuint fbo, GLuint texture, int face)
{
    const sky_gl *gl = &s->gl;
    gl->glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    gl->glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_CUBE_MAP_POSITIVE_X + (GLenum)face,
                               texture, 0);
    return texture ? gl->glCheckFramebufferStatus(GL_FRAMEBUFFER) : (GLenum)GL_FRAMEBUFFER_COMPLETE;
}

int sky_gl_cube_size_max(sky_core *s)
{
    GLint limit = 0;
    s->gl.glGetIntegerv(GL_MAX_CUBE_MAP_TEXTURE_SIZE, &limit);
    return (int)limit;
}

int sky_gl_cube_width(sky_core *s, GLuint texture)
{
    GLint w = 0;
    s->gl.glActiveTexture(GL_TEXTURE0);
    s->gl.glBindTexture(GL_TEXTURE_CUBE_MAP, texture);
    s->gl.glGetTexLevelParameteriv(GL_TEXTURE_CUBE_MAP_POSITIVE_X, 0, GL_TEXTURE_WIDTH, &w);
    return (int)w;
}

void sky_gl_cube_copy_face(sky_core *s, GLuint texture, int face, int x, int y, int size)
{
    s->gl.glActiveTexture(GL_TEXTURE0);
    s->gl.glBindTexture(GL_TEXTURE_CUBE_MAP, texture);
    s->gl.glCopyTexSubImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + (GLenum)face, 0, 0, 0, x, y, size, size);
}

void sky_gl_viewport_get(sky_core *s, GLint viewport[4]) { s->gl.glGetIntegerv(GL_VIEWPORT, viewport); }

void sky_gl_viewport_set(sky_core *s, int x, int y, int w, int h) { s->gl.glViewport(x, y, w, h); }

GLuint sky_gl_volume_binding(sky_core *s)
{
    GLint volume = 0;
    s->gl.glActiveTexture(GL_TEXTURE0);
    s->gl.glGetIntegerv(GL_TEXTURE_BINDING_3D, &volume);
    return (GLuint)volume;
}

void sky_gl_volume_bind(sky_core *s, GLuint texture)
{
    s->gl.glActiveTexture(GL_TEXTURE0);
    s->gl.glBindTexture(GL_TEXTURE_3D, texture);
}
