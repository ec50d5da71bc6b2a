/*
 * The browser's column of sky-bench's preset table (make bench-web): in
 * one WebGL 1 canvas, the pinned baseline (the one-texture full-screen
 * quad exactly as sky-bench draws it: a 512x512 RGBA8 noise texture,
 * linear, coordinates x3) and each preset as sky-bench builds it, every
 * frame waited for with glFinish and a one-pixel glReadPixels (SwiftShader
 * has no timer queries). web/bench.html calls these in interleaved rounds
 * and times three.js's Sky beside them.
 */
#include "cli.h"

#include <GLES2/gl2.h>
#include <GLFW/glfw3.h>
#include <emscripten.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int web_bench_open(int width, int height);
double web_bench_quad(int frames);
double web_bench_preset(const char *preset, int frames);

static GLFWwindow *window;
static int canvas_w, canvas_h;
static GLuint quad_program, quad_buffer, quad_texture;

/* Waits for the frame: glFinish, and a pixel read back to be sure. */
static void wait_for_gpu(void)
{
    unsigned char px[4];
    glFinish();
    glReadPixels(0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
}

static GLuint compile(GLenum type, const char *src)
{
    GLuint sh = glCreateShader(type);
    glShaderSource(sh, 1, &src, NULL);
    glCompileShader(sh);
    return sh;
}

/* The canvas and the baseline's program, buffer and texture. Returns 0 or -1. */
EMSCRIPTEN_KEEPALIVE int web_bench_open(int width, int height)
{
    if (!glfwInit()) return -1;
    glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_ES_API);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 2);
    window = glfwCreateWindow(width, height, "libsky bench", NULL, NULL);
    if (!window) return -1;
    glfwMakeContextCurrent(window);
    canvas_w = width;
    canvas_h = height;
    GLuint v = compile(GL_VERTEX_SHADER, "#version 100\nattribute vec2 p;\nvarying vec2 uv;\nconst float z = 0.0;\n"
                                         "void main(){uv=p*0.5+0.5;gl_Position=vec4(p,z,1.0);}\n");
    GLuint f = compile(GL_FRAGMENT_SHADER, "#version 100\nprecision highp float;\nvarying vec2 uv;\n"
                                           "uniform sampler2D t;\nvoid main(){gl_FragColor=texture2D(t,uv*3.0);}\n");
    quad_program = glCreateProgram();
    glAttachShader(quad_program, v);
    glAttachShader(quad_program, f);
    glBindAttribLocation(quad_program, 0, "p");
    glLinkProgram(quad_program);
    unsigned char *texels = malloc(512 * 512 * 4);
    if (!texels) return -1;
    for (int i = 0; i < 512 * 512 * 4; i++) texels[i] = (unsigned char)(i * 2654435761u >> 24);
    glGenTextures(1, &quad_texture);
    glBindTexture(GL_TEXTURE_2D, quad_texture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 512, 512, 0, GL_RGBA, GL_UNSIGNED_BYTE, texels);
    free(texels);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    static const float strip[8] = {-1, -1, 1, -1, -1, 1, 1, 1};
    glGenBuffers(1, &quad_buffer);
    glBindBuffer(GL_ARRAY_BUFFER, quad_buffer);
    glBufferData(GL_ARRAY_BUFFER, sizeof strip, strip, GL_STATIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    return glGetError() == GL_NO_ERROR ? 0 : -1;
}

/* Median ms of frames draws of the baseline (the first not counted). */
EMSCRIPTEN_KEEPALIVE double web_bench_quad(int frames)
{
    double t[256];
    if (frames < 1 || frames > 256) return -1.0;
    glViewport(0, 0, canvas_w, canvas_h);
    glUseProgram(quad_program);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, quad_texture);
    glUniform1i(glGetUniformLocation(quad_program, "t"), 0);
    glBindBuffer(GL_ARRAY_BUFFER, quad_buffer);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, 0);
    glEnableVertexAttribArray(0);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    wait_for_gpu();
    for (int i = 0; i < frames; i++) {
        double t0 = emscripten_get_now();
        glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
        wait_for_gpu();
        t[i] = emscripten_get_now() - t0;
    }
    glDisableVertexAttribArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glUseProgram(0);
    return sky_cli_median(t, frames);
}

/* Median ms of frames frames of a preset as sky-bench builds it (the
 * preset's sliders, date and features, its camera, sky_update(1/60) each
 * frame), in a sky made for the call; -1 if it cannot be made. The preset's
 * name may be followed by sky-render's options, separated by spaces
 * ("starry --features stars"), to time a layer or a setting apart; a
 * --size within the canvas draws into that corner of it. */
EMSCRIPTEN_KEEPALIVE double web_bench_preset(const char *preset, int frames)
{
    double t[256];
    if (frames < 1 || frames > 256) return -1.0;
    char size[32], err[256], words[256];
    snprintf(size, sizeof size, "%dx%d", canvas_w, canvas_h);
    snprintf(words, sizeof words, "%s", preset);
    char *args[32] = {"sky-bench", "--preset"};
    int argc = 2;
    for (char *w = strtok(words, " "); w && argc < 29; w = strtok(NULL, " ")) args[argc++] = w;
    if (!strstr(preset, "--size")) {
        args[argc++] = "--size";
        args[argc++] = size;
    }
    args[argc] = NULL;
    sky_cli cli;
    if (sky_cli_parse(&cli, argc, args, 0, err, sizeof err)) {
        fprintf(stderr, "web-bench: %s\n", err);
        return -1.0;
    }
    cli.gl = SKY_GL_ES20;
    sky_config cfg = sky_cli_config(&cli, glfwGetProcAddress);
    sky *s = sky_create(&cfg, err, sizeof err);
    if (!s) {
        fprintf(stderr, "web-bench: %s: %s\n", preset, err);
        return -1.0;
    }
    sky_set_params(s, &cli.params);
    sky_set_observer(s, &cli.observer);
    float view[16], proj[16];
    sky_cli_camera(&cli, view, proj);
    /* the canvas, or the size the options ask for ("starry --size 16x9":
     * what a frame costs besides its pixels) */
    glViewport(0, 0, cli.width < canvas_w ? cli.width : canvas_w, cli.height < canvas_h ? cli.height : canvas_h);
    sky_update(s, 1.0 / 60.0);
    sky_draw(s, view, proj); /* shader compilation */
    wait_for_gpu();
    for (int i = 0; i < frames; i++) {
        sky_update(s, 1.0 / 60.0);
        double t0 = emscripten_get_now();
        sky_draw(s, view, proj);
        wait_for_gpu();
        t[i] = emscripten_get_now() - t0;
    }
    sky_destroy(s);
    return sky_cli_median(t, frames);
}

int main(void) { return 0; }
