/*
 * GL backend, programs: the version prologue, compiling and linking a
 * program from its snippets, and its uniform table applied each draw.
 */
#include "gl.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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
                                        SKY_UNIFORM_COUNT(common_uniforms), NULL, NULL, NULL};


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

int sky_snippet_bind(sky_core *s, const sky_snippet *snippet, const void *state)
{
    if (s->snippet_binding_count == s->snippet_binding_capacity) {
        int capacity = s->snippet_binding_capacity ? 2 * s->snippet_binding_capacity : 16;
        sky_snippet_binding *grown = realloc(s->snippet_bindings, (size_t)capacity * sizeof *grown);
        if (!grown) return -1;
        s->snippet_bindings = grown;
        s->snippet_binding_capacity = capacity;
    }
    s->snippet_bindings[s->snippet_binding_count].snippet = snippet;
    s->snippet_bindings[s->snippet_binding_count].state = state;
    s->snippet_binding_count++;
    return 0;
}

/* The state a snippet's in_state rows read from, NULL if none is bound. */
static const void *snippet_state(const sky_core *s, const sky_snippet *snippet)
{
    for (int i = 0; i < s->snippet_binding_count; i++)
        if (s->snippet_bindings[i].snippet == snippet) return s->snippet_bindings[i].state;
    return NULL;
}

/* The uniform rows of the common snippet and then each snippet's, with
 * their locations in the linked program p->id. */
static int collect_uniforms(sky_core *s, sky_program *p, const sky_snippet *const *snippets, int snippet_count,
                            char *err, size_t err_len)
{
    int rows = sky_common_snippet.uniform_count;
    for (int i = 0; i < snippet_count; i++) rows += snippets[i]->uniform_count;
    p->uniforms = malloc(sizeof *p->uniforms * (size_t)(rows ? rows : 1));
    p->states = malloc(sizeof *p->states * (size_t)(rows ? rows : 1));
    p->locations = malloc(sizeof *p->locations * (size_t)(rows ? rows : 1));
    if (!p->uniforms || !p->states || !p->locations) {
        sky_format(err, err_len, "out of memory for a program's uniforms");
        return -1;
    }
    /* Rows the compiler optimised away get location -1 and are skipped. */
    for (int i = -1; i < snippet_count; i++) {
        const sky_snippet *sn = i < 0 ? &sky_common_snippet : snippets[i];
        const void *state = snippet_state(s, sn);
        for (int u = 0; u < sn->uniform_count; u++) {
            const sky_uniform_desc *row = &sn->uniforms[u];
            if (row->in_state && !state) {
                sky_format(err, err_len, "uniform %s reads a layer's state, but its snippet is not bound to one",
                           row->name);
                return -1;
            }
            p->uniforms[p->uniform_count] = row;
            p->states[p->uniform_count] = row->in_state ? state : NULL;
            p->locations[p->uniform_count] = s->gl.glGetUniformLocation(p->id, row->name);
            p->uniform_count++;
        }
    }
    return 0;
}

/* Writes vec3 NAME(vec3 d), the sum of the snippets' functions of one
 * kind (the glows': sky_night_glows; the front lights': sky_front_lights)
 * in their order, into out (len bytes; out NULL: nothing written), or ""
 * when no snippet has one. Returns the length of the whole text. */
static size_t light_sum(const sky_snippet *const *snippets, int count, int front, char *out, size_t len)
{
    static const char tail[] = "    return sum;\n}\n";
    const char *name = front ? "sky_front_lights" : "sky_night_glows";
    size_t need = 0;
    int any = 0;
    for (int i = 0; i < count; i++) {
        const char *f = front ? snippets[i]->front_function : snippets[i]->glow_function;
        if (f) need += strlen(f) + 20, any = 1;
    }
    need = any ? need + strlen(name) + 64 + sizeof tail : 0;
    if (!out) return need;
    out[0] = '\0';
    if (!any) return 0;
    size_t used = (size_t)snprintf(out, len, "vec3 %s(vec3 d)\n{\n    vec3 sum = vec3(0.0);\n", name);
    for (int i = 0; i < count; i++) {
        const char *f = front ? snippets[i]->front_function : snippets[i]->glow_function;
        if (f) used += (size_t)snprintf(out + used, len - used, "    sum += %s(d);\n", f);
    }
    snprintf(out + used, len - used, "%s", tail);
    return need;
}

int sky_program_build(sky_core *s, sky_program *p, const char *vert_main, const char *frag_main,
                      const sky_snippet *const *snippets, int snippet_count, char *err, size_t err_len)
{
    const sky_gl *gl = &s->gl;
    memset(p, 0, sizeof *p);
    /* prologue, feature defines, display and common code, snippets, main */
    const char **parts = malloc(sizeof *parts * (size_t)(7 + snippet_count));
    /* the tone map (display.glsl), then the snippets' defines */
    static const char *const tone_maps[3] = {"", "#define SKY_TONE_MAP_FILMIC 1\n", "#define SKY_TONE_MAP_NEUTRAL 1\n"};
    size_t defines_size = 192;
    char *sums[2] = {NULL, NULL}; /* sky_night_glows, sky_front_lights: if any snippet has one */
    for (int i = 0; i < snippet_count; i++)
        if (snippets[i]->define) defines_size += strlen(snippets[i]->define) + 16;
    char *defines = malloc(defines_size);
    GLuint shaders[2] = {0, 0};
    if (!parts || !defines) {
        sky_format(err, err_len, "out of memory for a program's sources");
        goto fail;
    }
    size_t used = (size_t)snprintf(defines, defines_size, "%s", tone_maps[s->cfg.tone_map]);
    /* the weather's shading, only in a sky that asked for it (its cost) */
    if (s->features & SKY_WEATHER) used += (size_t)snprintf(defines + used, defines_size - used, "#define SKY_HAS_WEATHER 1\n");
    for (int i = 0; i < snippet_count; i++)
        if (snippets[i]->define)
            used += (size_t)snprintf(defines + used, defines_size - used, "#define %s 1\n", snippets[i]->define);
    static const char *const sum_defines[2] = {"#define SKY_HAS_NIGHT_GLOWS 1\n", "#define SKY_HAS_FRONT_LIGHTS 1\n"};
    for (int k = 0; k < 2; k++) {
        size_t sum_len = light_sum(snippets, snippet_count, k, NULL, 0);
        if (sum_len) used += (size_t)snprintf(defines + used, defines_size - used, "%s", sum_defines[k]);
        if (!(sums[k] = malloc(sum_len + 1))) {
            sky_format(err, err_len, "out of memory for a program's sources");
            goto fail;
        }
        light_sum(snippets, snippet_count, k, sums[k], sum_len + 1);
    }
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
        for (int k = 0; k < 2; k++)
            if (stage && sums[k][0]) parts[n++] = sums[k];
        if (!(parts[n++] = blob_text(stage ? frag_main : vert_main, err, err_len))) goto fail;
        shaders[stage] = compile(s, stage ? GL_FRAGMENT_SHADER : GL_VERTEX_SHADER, parts, n, err, err_len);
        if (!shaders[stage]) goto fail;
    }
    free(parts);
    free(defines);
    free(sums[0]);
    free(sums[1]);
    parts = NULL;
    defines = NULL;
    sums[0] = sums[1] = NULL;
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
    if (collect_uniforms(s, p, snippets, snippet_count, err, err_len)) goto fail;
    s->program_count++;
    if (!s->identity_program) s->identity_program = p->id;
    return 0;
fail:
    free(parts);
    free(defines);
    free(sums[0]);
    free(sums[1]);
    for (int i = 0; i < 2; i++)
        if (shaders[i]) gl->glDeleteShader(shaders[i]);
    if (p->id) gl->glDeleteProgram(p->id);
    free(p->uniforms);
    free(p->states);
    free(p->locations);
    memset(p, 0, sizeof *p);
    return -1;
}

void sky_program_destroy(sky_core *s, sky_program *p)
{
    if (p->id) {
        s->gl.glDeleteProgram(p->id);
        s->program_count--;
    }
    free(p->uniforms);
    free(p->states);
    free(p->locations);
    memset(p, 0, sizeof *p);
}

void sky_program_apply(sky_core *s, const sky_program *p)
{
    const sky_gl *gl = &s->gl;
    int unit = 0;
    gl->glUseProgram(p->id);
    for (int i = 0; i < p->uniform_count; i++) {
        const sky_uniform_desc *u = p->uniforms[i];
        GLint loc = p->locations[i];
        if (loc < 0) continue;
        const unsigned char *base = p->states[i] ? (const unsigned char *)p->states[i]
                                                 : (const unsigned char *)&s->frame;
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
        case SKY_U_TEX: {
            /* the id itself, or a state's int holding one (registered at
             * run time) */
            int id = (int)u->offset;
            if (u->in_state) memcpy(&id, base + u->offset, sizeof id);
            gl->glActiveTexture(GL_TEXTURE0 + (GLenum)unit);
            gl->glBindTexture(s->textures[id].target, s->textures[id].id);
            gl->glUniform1i(loc, unit);
            unit++;
            break;
        }
        }
    }
}

void sky_gl_host_uniforms(sky_core *s, GLuint program, const sky_gl_host_uniform *u, int count, int texture_unit,
                          GLuint texture)
{
    const sky_gl *gl = &s->gl;
    GLint host_program = 0, host_unit = 0;
    gl->glGetIntegerv(GL_CURRENT_PROGRAM, &host_program);
    gl->glGetIntegerv(GL_ACTIVE_TEXTURE, &host_unit);
    gl->glUseProgram(program);
    if (texture) {
        gl->glActiveTexture(GL_TEXTURE0 + (GLenum)texture_unit);
        gl->glBindTexture(GL_TEXTURE_2D, texture);
    }
    for (int i = 0; i < count; i++) {
        GLint at = gl->glGetUniformLocation(program, u[i].name);
        const float *v = u[i].v;
        switch (u[i].n) {
        case 0: gl->glUniform1i(at, u[i].unit); break;
        case 1: gl->glUniform1f(at, v[0]); break;
        case 2: gl->glUniform2f(at, v[0], v[1]); break;
        case 3: gl->glUniform3f(at, v[0], v[1], v[2]); break;
        default: gl->glUniform4f(at, v[0], v[1], v[2], v[3]); break;
        }
    }
    gl->glActiveTexture((GLenum)host_unit);
    gl->glUseProgram((GLuint)host_program);
}

int sky_gl_texture_units(sky_core *s)
{
    GLint units = 0;
    s->gl.glGetIntegerv(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &units);
    return (int)units;
}
