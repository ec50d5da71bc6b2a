/*
 * sky-game: the smallest honest game loop around libsky. The host owns the
 * window and the context (GLFW, OpenGL 3.3 core), draws the sky first each
 * frame, then its own depth-tested world lit by sky_get_lighting: the sun
 * and moon as directional lights, the sky as ambient light, its horizon as
 * fog, and the sky's exposure so world and sky share one brightness scale.
 *
 *   sky-game [--time T] [--date ... --lat ... --lon ...] [--frames N --screenshot FILE]
 */
#define GL_GLEXT_PROTOTYPES 1
#include "cli.h"
#include "osmesa_ctx.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <GLFW/glfw3.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *vs = "#version 330 core\n"
                        "layout(location = 0) in vec3 pos;\nlayout(location = 1) in vec3 nrm;\n"
                        "uniform mat4 mvp;\nout vec3 n;\nout float dist;\n"
                        "void main() { n = nrm; dist = length(pos.xz); gl_Position = mvp * vec4(pos, 1.0); }\n";
/* luminance = albedo / pi * illuminance (kcd/m^2 from klx); fog toward the
 * horizon sky; then the sky's exposure and the same filmic curve it uses */
static const char *fs =
    "#version 330 core\nin vec3 n;\nin float dist;\nout vec4 color;\n"
    "uniform vec3 sun_dir, sun_col, moon_dir, moon_col, ambient, fog;\nuniform float exposure;\n"
    "void main() {\n"
    "  vec3 albedo = n.y > 0.9 ? vec3(0.20, 0.30, 0.12) : vec3(0.45, 0.40, 0.35);\n"
    "  vec3 E = sun_col * max(dot(n, sun_dir), 0.0) + moon_col * max(dot(n, moon_dir), 0.0) + ambient * (0.6 + 0.4 * n.y);\n"
    "  vec3 L = mix(albedo / 3.14159 * E, fog, 1.0 - exp(-dist / 400.0));\n"
    "  vec3 x = max(L * exposure - 0.004, vec3(0.0));\n"
    "  color = vec4((x * (6.2 * x + 0.5)) / (x * (6.2 * x + 1.7) + 0.06), 1.0);\n}\n";

static GLuint shader(GLenum type, const char *src)
{
    GLuint s = glCreateShader(type);
    glShaderSource(s, 1, &src, NULL);
    glCompileShader(s);
    return s;
}

/* A ground plane and five boxes: position and normal per vertex. */
static int build_world(float *v)
{
    int n = 0;
#define VERT(x, y, z, a, b, c) (v[n * 6 + 0] = x, v[n * 6 + 1] = y, v[n * 6 + 2] = z, v[n * 6 + 3] = a, \
                                v[n * 6 + 4] = b, v[n * 6 + 5] = c, n++)
    const float g = 2000.0f;
    VERT(-g, 0, -g, 0, 1, 0), VERT(g, 0, -g, 0, 1, 0), VERT(g, 0, g, 0, 1, 0);
    VERT(-g, 0, -g, 0, 1, 0), VERT(g, 0, g, 0, 1, 0), VERT(-g, 0, g, 0, 1, 0);
    /* to the south (+z), where the default camera looks */
    static const float boxes[5][4] = {{-12, 40, 4, 6}, {10, 30, 3, 10}, {0, 60, 8, 4}, {25, 55, 5, 14}, {-30, 25, 3, 3}};
    for (int b = 0; b < 5; b++) {
        float cx = boxes[b][0], cz = boxes[b][1], r = boxes[b][2], h = boxes[b][3];
        /* four walls and a roof, two triangles each */
        static const float faces[5][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 0, 1}, {0, 0, -1}, {0, 1, 0}};
        for (int f = 0; f < 5; f++) {
            const float *nn = faces[f];
            float c[4][3];
            for (int k = 0; k < 4; k++) {
                float s = (k == 1 || k == 2) ? 1.0f : -1.0f, t = k >= 2 ? 1.0f : -1.0f;
                if (nn[1] > 0) c[k][0] = cx + s * r, c[k][1] = h, c[k][2] = cz + t * r;
                else if (nn[0] != 0) c[k][0] = cx + nn[0] * r, c[k][1] = (t + 1) * h / 2, c[k][2] = cz + s * r;
                else c[k][0] = cx + s * r, c[k][1] = (t + 1) * h / 2, c[k][2] = cz + nn[2] * r;
            }
            static const int tri[6] = {0, 1, 2, 0, 2, 3};
            for (int k = 0; k < 6; k++) VERT(c[tri[k]][0], c[tri[k]][1], c[tri[k]][2], nn[0], nn[1], nn[2]);
        }
    }
#undef VERT
    return n;
}

int main(int argc, char **argv)
{
    sky_cli cli;
    char err[512];
    int rc = sky_cli_parse(&cli, argc, argv, 1, err, sizeof err);
    if (rc == SKY_CLI_HELP) {
        sky_cli_usage(stdout, "sky-game", 1);
        return 0;
    }
    if (rc) {
        fprintf(stderr, "sky-game: %s\n", err);
        return 2;
    }
    if (!glfwInit()) {
        fprintf(stderr, "sky-game: no display (GLFW cannot initialise)\n");
        return 1;
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    GLFWwindow *win = glfwCreateWindow(cli.width, cli.height, "libsky game", NULL, NULL);
    if (!win) {
        fprintf(stderr, "sky-game: no OpenGL 3.3 window\n");
        glfwTerminate();
        return 1;
    }
    glfwMakeContextCurrent(win);
    /* the sky: the host's loader, its features, its sliders and observer */
    sky_config cfg = sky_cli_config(&cli, glfwGetProcAddress);
    if (!cfg.features) cfg.features = SKY_CLOUDS | SKY_SUN | SKY_MOON | SKY_STARS | SKY_STARMAP;
    sky *s = sky_create(&cfg, err, sizeof err);
    if (!s) {
        fprintf(stderr, "sky-game: %s\n", err);
        return 1;
    }
    sky_set_params(s, &cli.params);
    sky_set_observer(s, &cli.observer);
    /* the world: the host's own buffers and program */
    static float verts[(6 + 5 * 6 * 5) * 6];
    int count = build_world(verts);
    GLuint vao, vbo, prog = glCreateProgram();
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glGenBuffers(1, &vbo);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, sizeof(float) * 6 * (size_t)count, verts, GL_STATIC_DRAW);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 24, (void *)0);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 24, (void *)12);
    glEnableVertexAttribArray(0);
    glEnableVertexAttribArray(1);
    glAttachShader(prog, shader(GL_VERTEX_SHADER, vs));
    glAttachShader(prog, shader(GL_FRAGMENT_SHADER, fs));
    glLinkProgram(prog);
    int status = 0;
    for (int frame = 0; !glfwWindowShouldClose(win); frame++) {
        int w, h;
        glfwGetFramebufferSize(win, &w, &h);
        glViewport(0, 0, w, h);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        sky_update(s, 1.0 / 60.0);
        cli.width = w, cli.height = h;
        float view[16], proj[16], mvp[16];
        sky_cli_camera(&cli, view, proj);
        /* 1. the sky: first, it writes no depth and restores what it touched */
        if (sky_draw(s, view, proj) != SKY_OK) fprintf(stderr, "sky-game: %s\n", sky_last_error(s));
        /* 2. the world, lit by the sky; the eye stands 1.7 m up */
        sky_lighting l;
        sky_get_lighting(s, &l);
        for (int r = 0; r < 3; r++) view[12 + r] -= 1.7f * view[4 + r]; /* -R * eye, eye = (0, 1.7, 0) */
        for (int c = 0; c < 4; c++)
            for (int r = 0; r < 4; r++) {
                mvp[c * 4 + r] = 0;
                for (int k = 0; k < 4; k++) mvp[c * 4 + r] += proj[k * 4 + r] * view[c * 4 + k];
            }
        glEnable(GL_DEPTH_TEST);
        glUseProgram(prog);
        glBindVertexArray(vao);
        glUniformMatrix4fv(glGetUniformLocation(prog, "mvp"), 1, GL_FALSE, mvp);
        glUniform3fv(glGetUniformLocation(prog, "sun_dir"), 1, l.sun_direction);
        glUniform3fv(glGetUniformLocation(prog, "sun_col"), 1, l.sun_color);
        glUniform3fv(glGetUniformLocation(prog, "moon_dir"), 1, l.moon_direction);
        glUniform3fv(glGetUniformLocation(prog, "moon_col"), 1, l.moon_color);
        glUniform3fv(glGetUniformLocation(prog, "ambient"), 1, l.ambient_color);
        glUniform3fv(glGetUniformLocation(prog, "fog"), 1, l.fog_color);
        glUniform1f(glGetUniformLocation(prog, "exposure"), l.exposure);
        glDrawArrays(GL_TRIANGLES, 0, count);
        glDisable(GL_DEPTH_TEST);
        if (cli.screenshot && frame + 1 >= cli.frames) {
            sky_osmesa shot = {0};
            shot.width = w, shot.height = h;
            shot.pixels = malloc((size_t)w * (size_t)h * 4u);
            glPixelStorei(GL_PACK_ALIGNMENT, 1);
            if (shot.pixels) glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, shot.pixels);
            if (!shot.pixels || sky_osmesa_write_png(&shot, cli.screenshot)) {
                fprintf(stderr, "sky-game: cannot write %s\n", cli.screenshot);
                status = 1; /* a script must see that its image is missing */
            }
            free(shot.pixels);
            break;
        }
        glfwSwapBuffers(win);
        glfwPollEvents();
    }
    sky_destroy(s);
    glfwTerminate();
    return status;
}
