/* sky-demo's overlay; see ui.h. */
#define GL_GLEXT_PROTOTYPES 1
#include "ui.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wmissing-prototypes"
#endif
#include <stb/stb_easy_font.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

static const char *const names[6] = {"cover", "height", "density", "sunset", "speed", "time"};

struct ui {
    int core;
    GLuint prog, vao, vbo;
    int dragging; /* slider index + 1 */
    float *verts; /* x, y, r, g, b, a */
    int count, cap;
};

static void push(ui *u, float x, float y, const float c[4])
{
    if (u->count == u->cap) {
        u->cap = u->cap ? 2 * u->cap : 4096;
        u->verts = realloc(u->verts, sizeof(float) * 6 * (size_t)u->cap);
    }
    float *v = u->verts + 6 * u->count++;
    v[0] = x, v[1] = y, v[2] = c[0], v[3] = c[1], v[4] = c[2], v[5] = c[3];
}

static void rect(ui *u, float x, float y, float w, float h, const float c[4])
{
    push(u, x, y, c), push(u, x + w, y, c), push(u, x + w, y + h, c);
    push(u, x, y, c), push(u, x + w, y + h, c), push(u, x, y + h, c);
}

static void text(ui *u, float x, float y, const char *s, const float c[4])
{
    static char buf[60000];
    int quads = stb_easy_font_print(x, y, (char *)s, NULL, buf, sizeof buf);
    for (int q = 0; q < quads; q++) {
        const float *v = (const float *)(buf + q * 64); /* 4 vertices of x, y, z, rgba8 */
        float p[4][2];
        for (int k = 0; k < 4; k++) p[k][0] = v[k * 4], p[k][1] = v[k * 4 + 1];
        static const int tri[6] = {0, 1, 2, 0, 2, 3};
        for (int k = 0; k < 6; k++) push(u, p[tri[k]][0], p[tri[k]][1], c);
    }
}

ui *ui_create(int kind)
{
    ui *u = calloc(1, sizeof *u);
    if (!u) return NULL;
    int core = u->core = kind == UI_CORE33;
    static const char *const versions[3][2] = {
        {"#version 110\n", "#version 110\n"},
        {"#version 330 core\n", "#version 330 core\n"},
        {"#version 100\n", "#version 100\nprecision mediump float;\n"}};
    const char *vs_body = core ? "in vec2 p;\nin vec4 c;\nout vec4 vc;\nuniform vec2 size;\n"
                                 "void main(){vc=c;gl_Position=vec4(p/size*vec2(2.0,-2.0)+vec2(-1.0,1.0),0.0,1.0);}\n"
                               : "attribute vec2 p;\nattribute vec4 c;\nvarying vec4 vc;\nuniform vec2 size;\n"
                                 "void main(){vc=c;gl_Position=vec4(p/size*vec2(2.0,-2.0)+vec2(-1.0,1.0),0.0,1.0);}\n";
    const char *fs_body = core ? "in vec4 vc;\nout vec4 o;\nvoid main(){o=vc;}\n"
                               : "varying vec4 vc;\nvoid main(){gl_FragColor=vc;}\n";
    const char *vs[2] = {versions[kind][0], vs_body}, *fs[2] = {versions[kind][1], fs_body};
    GLuint v = glCreateShader(GL_VERTEX_SHADER), f = glCreateShader(GL_FRAGMENT_SHADER);
    glShaderSource(v, 2, vs, NULL);
    glShaderSource(f, 2, fs, NULL);
    glCompileShader(v);
    glCompileShader(f);
    u->prog = glCreateProgram();
    glAttachShader(u->prog, v);
    glAttachShader(u->prog, f);
    glBindAttribLocation(u->prog, 0, "p");
    glBindAttribLocation(u->prog, 1, "c");
    glLinkProgram(u->prog);
    glDeleteShader(v);
    glDeleteShader(f);
    if (core) glGenVertexArrays(1, &u->vao);
    glGenBuffers(1, &u->vbo);
    return u;
}

void ui_destroy(ui *u)
{
    if (!u) return;
    glDeleteProgram(u->prog);
    glDeleteBuffers(1, &u->vbo);
    if (u->core) glDeleteVertexArrays(1, &u->vao);
    free(u->verts);
    free(u);
}

static int slider_at(double x, double y)
{
    for (int i = 0; i < 6; i++) {
        float top = UI_SLIDER_Y0 + i * UI_SLIDER_DY;
        if (x >= UI_SLIDER_X - 4 && x <= UI_SLIDER_X + UI_SLIDER_W + 4 && y >= top - 4 && y <= top + UI_SLIDER_H + 4)
            return i;
    }
    return -1;
}

static float value_at(double x)
{
    float v = (float)((x - UI_SLIDER_X) / UI_SLIDER_W);
    return v < 0.0f ? 0.0f : v > 1.0f ? 1.0f : v;
}

int ui_mouse_button(ui *u, int pressed, double x, double y, float values[6], int *selected)
{
    if (!pressed) {
        int was = u->dragging;
        u->dragging = 0;
        return was != 0;
    }
    int i = slider_at(x, y);
    if (i < 0) return 0;
    u->dragging = i + 1;
    *selected = i;
    values[i] = value_at(x);
    return 1;
}

int ui_mouse_move(ui *u, double x, double y, float values[6])
{
    (void)y;
    if (!u->dragging) return 0;
    values[u->dragging - 1] = value_at(x);
    return 1;
}

void ui_draw(ui *u, int w, int h, const float values[6], int selected, const char *lines)
{
    static const float panel[4] = {0.0f, 0.0f, 0.0f, 0.45f}, bar[4] = {0.35f, 0.38f, 0.45f, 0.9f},
                       fill[4] = {0.55f, 0.75f, 1.0f, 0.95f}, sel[4] = {1.0f, 0.85f, 0.4f, 1.0f},
                       white[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    u->count = 0;
    rect(u, 8, 10, UI_SLIDER_X + UI_SLIDER_W + 60, 6 * UI_SLIDER_DY + 12, panel);
    for (int i = 0; i < 6; i++) {
        float top = UI_SLIDER_Y0 + i * UI_SLIDER_DY;
        char label[32];
        snprintf(label, sizeof label, "%d %s", i + 1, names[i]);
        text(u, 16, top + 2, label, i == selected ? sel : white);
        rect(u, UI_SLIDER_X, top, UI_SLIDER_W, UI_SLIDER_H, bar);
        rect(u, UI_SLIDER_X, top, UI_SLIDER_W * values[i], UI_SLIDER_H, i == selected ? sel : fill);
        snprintf(label, sizeof label, "%.2f", (double)values[i]);
        text(u, UI_SLIDER_X + UI_SLIDER_W + 8, top + 2, label, white);
    }
    /* the text panel, top right */
    float y = 14;
    for (const char *l = lines; l && *l; l += strlen(l) + 1) {
        float x = (float)w - 12 - (float)stb_easy_font_width((char *)l);
        text(u, x, y, l, white);
        y += 12;
    }
    glUseProgram(u->prog);
    glUniform2f(glGetUniformLocation(u->prog, "size"), (float)w, (float)h);
    if (u->core) glBindVertexArray(u->vao);
    glBindBuffer(GL_ARRAY_BUFFER, u->vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof(float) * 6 * (size_t)u->count), u->verts, GL_STREAM_DRAW);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 24, (void *)0);
    glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, 24, (void *)8);
    glEnableVertexAttribArray(0);
    glEnableVertexAttribArray(1);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glDrawArrays(GL_TRIANGLES, 0, u->count);
    glDisable(GL_BLEND);
    glDisableVertexAttribArray(0);
    glDisableVertexAttribArray(1);
}
