/*
 * GL backend, state: the host's state saved and restored around every
 * public call that touches GL, and the state a frame sets for itself.
 */
#include "gl.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

void sky_gl_vertices_bind(sky_core *s, GLuint buffer, GLuint elements, const sky_gl_layout *layout)
{
    const sky_gl *gl = &s->gl;
    gl->glBindBuffer(GL_ARRAY_BUFFER, buffer);
    if (elements) gl->glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, elements);
    for (GLuint i = 0; i < 3; i++) {
        const sky_gl_attribute *a = &layout->attribute[i];
        if (a->size <= 0) {
            gl->glDisableVertexAttribArray(i);
            continue;
        }
        gl->glVertexAttribPointer(i, a->size, a->type, a->normalized, layout->stride, (const void *)a->offset);
        gl->glEnableVertexAttribArray(i);
    }
}

void sky_gl_draw_arrays(sky_core *s, GLenum mode, int first, int count) { s->gl.glDrawArrays(mode, first, count); }

void sky_gl_draw_elements(sky_core *s, GLenum mode, int first, int count)
{
    s->gl.glDrawElements(mode, count, GL_UNSIGNED_SHORT, (const void *)((size_t)first * sizeof(unsigned short)));
}

void sky_gl_finish(sky_core *s) { s->gl.glFinish(); }

GLenum sky_gl_error(sky_core *s) { return s->gl.glGetError(); }

int sky_gl_context_current(sky_core *s) { return s->gl.glGetString(GL_VERSION) != NULL; }

int sky_gl_is_program(sky_core *s, GLuint program) { return program && s->gl.glIsProgram(program) == GL_TRUE; }
