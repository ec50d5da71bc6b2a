/*
 * libsky in an SDL2 + OpenGL 3.3 game: a right-handed, Y-up world with our
 * own maths, the sky drawn after the opaque scene on the far plane (so the
 * pixels the scene covers cost the sky nothing), in any depth convention.
 * Options: examples/README.md. Built outside this tree with:
 *   cc -std=c11 sdl2.c $(pkg-config --cflags --libs sky sdl2) -lGL -lstb -lm
 * (Mesa's libGL exports every GL function, hence GL_GLEXT_PROTOTYPES; on
 * other platforms load them with a loader such as glad.)
 */
#define GL_GLEXT_PROTOTYPES
#include <SDL2/SDL.h>
#include <SDL2/SDL_opengl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <stb/stb_image_write.h>

#include "sky.h"

#define DEG (3.14159265f / 180.0f)
enum { FAR_ONE, REVERSED_Z, REVERSED_Z_CLIP01 };

static sky_gl_proc load(const char *name)
{
    void *p = SDL_GL_GetProcAddress(name);
    sky_gl_proc f;
    memcpy(&f, &p, sizeof f); /* a data pointer to a function pointer: POSIX guarantees it */
    return f;
}

/* The projection for each depth convention, column-major, infinite far
 * plane. Far-one: OpenGL's own, depth 0 near .. 1 far. Reversed-Z puts
 * the far plane at depth 0 (clip z = -w there), which spends the float
 * depth buffer's precision where it is needed; with glClipControl's 0..1
 * range, clip z = near plane distance gives depth 1 at the near plane. */
static void projection(float p[16], float fovy, float aspect, float znear, int depth)
{
    float f = 1.0f / tanf(fovy * 0.5f);
    memset(p, 0, 16 * sizeof(float));
    p[0] = f / aspect;
    p[5] = f;
    p[11] = -1.0f; /* clip w = -z: right-handed, looking down -z */
    p[10] = depth == FAR_ONE ? -1.0f : depth == REVERSED_Z ? 1.0f : 0.0f;
    p[14] = depth == REVERSED_Z_CLIP01 ? znear : depth == REVERSED_Z ? 2.0f * znear : -2.0f * znear;
}

/* A camera at eye turned to compass yaw (0 north = -z, 90 east = +x) and
 * pitched up by pitch: its view matrix, whose rows are the camera's right,
 * up and backward axes, column-major. */
static void look(float v[16], const float eye[3], float yaw, float pitch)
{
    float sy = sinf(yaw), cy = cosf(yaw), sp = sinf(pitch), cp = cosf(pitch);
    const float rotation[16] = {cy, -sy * sp, -sy * cp, 0, 0, cp, -sp, 0, sy, cy * sp, cy * cp, 0, 0, 0, 0, 1};
    memcpy(v, rotation, sizeof rotation);
    for (int row = 0; row < 3; row++) v[12 + row] = -(v[row] * eye[0] + v[4 + row] * eye[1] + v[8 + row] * eye[2]);
}

/* A box (the ground is a 400 m wide one): 6 floats a vertex, position and
 * normal, two triangles a face. */
static int box(float *v, const float lo[3], const float hi[3])
{
    int n = 0;
    for (int axis = 0; axis < 3; axis++)
        for (int side = 0; side < 2; side++) {
            int a = (axis + 1) % 3, b = (axis + 2) % 3;
            static const int corner[6][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}};
            for (int k = 0; k < 6; k++, n++) {
                float *p = v + n * 6;
                p[axis] = side ? hi[axis] : lo[axis];
                p[a] = corner[k][0] ? hi[a] : lo[a];
                p[b] = corner[k][1] ? hi[b] : lo[b];
                p[3] = p[4] = p[5] = 0.0f;
                p[3 + axis] = side ? 1.0f : -1.0f;
            }
        }
    return n;
}

static const char *const vs_src =
    "#version 330 core\nlayout(location = 0) in vec3 pos;\nlayout(location = 1) in vec3 nrm;\n"
    "uniform mat4 proj, view;\nout vec3 n, world;\n"
    "void main() { n = nrm; world = pos; gl_Position = proj * (view * vec4(pos, 1.0)); }\n";
/* Luminance = albedo / pi * illuminance; times the sky's exposure it is on
 * the sky's scale; a simple curve to 8 bits (the sky's own is richer). */
static const char *const fs_src =
    "#version 330 core\nin vec3 n, world;\nout vec4 colour;\n"
    "uniform vec3 eye, sun_dir, sun_col, ambient, fog;\nuniform float exposure;\n"
    "void main() {\n"
    "  vec3 albedo = world.y < 0.01 ? vec3(0.20, 0.30, 0.12) : vec3(0.45, 0.38, 0.30);\n"
    "  vec3 nn = normalize(n);\n"
    "  vec3 E = sun_col * max(dot(nn, sun_dir), 0.0) + ambient * (0.6 + 0.4 * nn.y);\n"
    "  vec3 L = mix(albedo / 3.14159 * E, fog, 1.0 - exp(-length(world - eye) / 500.0)) * exposure;\n"
    "  colour = vec4(pow(L / (1.0 + L), vec3(1.0 / 2.2)), 1.0);\n"
    "}\n";

static GLuint program(void)
{
    GLuint p = glCreateProgram(), s[2] = {glCreateShader(GL_VERTEX_SHADER), glCreateShader(GL_FRAGMENT_SHADER)};
    glShaderSource(s[0], 1, &vs_src, NULL);
    glShaderSource(s[1], 1, &fs_src, NULL);
    for (int i = 0; i < 2; i++) {
        glCompileShader(s[i]);
        glAttachShader(p, s[i]);
        glDeleteShader(s[i]);
    }
    glLinkProgram(p);
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    return ok ? p : 0;
}

static int save_png(const char *path, int w, int h)
{
    unsigned char *px = malloc((size_t)w * (size_t)h * 3);
    char tmp[4096];
    if (!px || snprintf(tmp, sizeof tmp, "%s.tmp", path) >= (int)sizeof tmp) return free(px), -1;
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGB, GL_UNSIGNED_BYTE, px);
    /* GL's rows run bottom to top: hand stb the last row and a negative stride */
    int ok = stbi_write_png(tmp, w, h, 3, px + (size_t)(h - 1) * (size_t)w * 3, -w * 3);
    free(px);
    if (!ok || rename(tmp, path)) return remove(tmp), -1;
    return 0;
}

static int named(const char *s, const char *const *names, int n)
{
    while (n-- > 0 && strcmp(s, names[n])) {}
    return n;
}

static int number(const char *s, float lo, float hi, float *out)
{
    char *end;
    double x = strtod(s, &end);
    if (end == s || *end || !(x >= lo && x <= hi)) return -1;
    *out = (float)x;
    return 0;
}

int main(int argc, char **argv)
{
    float frames = 0, held_time = -1, cover = 0.35f;
    int depth = FAR_ONE, sky_first = 0, face_sun = 0, no_sky = 0;
    const char *shot = NULL;
    static const char *const depth_names[3] = {"far-one", "reversed-z", "reversed-z-clip01"};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : "";
        if (!strcmp(a, "--sky-first")) sky_first = 1;
        else if (!strcmp(a, "--face-sun")) face_sun = 1;
        else if (!strcmp(a, "--no-sky")) no_sky = 1;
        else if (!strcmp(a, "--screenshot") && *v) shot = argv[++i];
        else if (!strcmp(a, "--frames") && !number(v, 1, 100000, &frames)) i++;
        else if (!strcmp(a, "--time") && !number(v, 0, 1, &held_time)) i++;
        else if (!strcmp(a, "--cover") && !number(v, 0, 1, &cover)) i++;
        else if (!strcmp(a, "--depth") && (depth = named(v, depth_names, 3)) >= 0) i++;
        else return fprintf(stderr, "sky-sdl2: bad option %s %s (see examples/README.md)\n", a, v), 2;
    }
    int headless = frames > 0, w = headless ? 640 : 1280, h = headless ? 360 : 720;
    if (SDL_Init(SDL_INIT_VIDEO)) return fprintf(stderr, "sky-sdl2: %s\n", SDL_GetError()), 1;
    SDL_GL_SetAttribute(SDL_GL_CONTEXT_MAJOR_VERSION, 3);
    SDL_GL_SetAttribute(SDL_GL_CONTEXT_MINOR_VERSION, 3);
    SDL_GL_SetAttribute(SDL_GL_CONTEXT_PROFILE_MASK, SDL_GL_CONTEXT_PROFILE_CORE);
    SDL_GL_SetAttribute(SDL_GL_DEPTH_SIZE, 24);
    SDL_Window *win = SDL_CreateWindow("libsky in SDL2", SDL_WINDOWPOS_CENTERED, SDL_WINDOWPOS_CENTERED, w, h,
                                       SDL_WINDOW_OPENGL);
    SDL_GLContext gl = win ? SDL_GL_CreateContext(win) : NULL;
    if (!gl) return fprintf(stderr, "sky-sdl2: %s\n", SDL_GetError()), 1;
    SDL_GL_SetSwapInterval(headless ? 0 : 1);
    if (depth == REVERSED_Z_CLIP01) { /* OpenGL 4.5's, and the extension's */
        if (!SDL_GL_ExtensionSupported("GL_ARB_clip_control"))
            return fprintf(stderr, "sky-sdl2: this context has no glClipControl\n"), 3;
        glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    }

    /* the sky: after the scene on the far plane, or first with no depth */
    sky_config cfg = {0};
    cfg.get_proc_address = load;
    static const sky_depth conventions[3] = {SKY_DEPTH_FAR_ONE, SKY_DEPTH_FAR_ZERO, SKY_DEPTH_FAR_ZERO_CLIP01};
    cfg.depth = sky_first ? SKY_DEPTH_NONE : conventions[depth];
    char err[256];
    sky *s = sky_create(&cfg, err, sizeof err);
    if (!s) return fprintf(stderr, "sky-sdl2: %s\n", err), 1;
    sky_params params = sky_default_params();
    params.cover = cover;
    params.time = held_time >= 0 ? held_time : 7.0f / 24.0f;
    sky_set_params(s, &params);

    static float world[6 * 6 * 4 * 6];
    static const float boxes[4][6] = {{-200, -1, -200, 200, 0, 200}, {-9, 0, 22, -3, 5, 30},
                                      {4, 0, 39, 10, 12, 45}, {-22, 0, 50, -14, 3, 60}};
    int nverts = 0;
    for (int b = 0; b < 4; b++) nverts += box(world + nverts * 6, boxes[b], boxes[b] + 3);
    GLuint prog = program(), vao, vbo;
    if (!prog) return fprintf(stderr, "sky-sdl2: the scene's shader did not link\n"), 1;
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glGenBuffers(1, &vbo);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof(float) * 6 * (size_t)nverts), world, GL_STATIC_DRAW);
    for (GLuint a = 0; a < 2; a++) { /* position, normal */
        glVertexAttribPointer(a, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), (void *)(a * 3 * sizeof(float)));
        glEnableVertexAttribArray(a);
    }

    const float eye[3] = {0.0f, 1.7f, 0.0f};
    float yaw = 180.0f * DEG, pitch = 8.0f * DEG, view[16], proj[16];
    sky_lighting light;
    sky_result drawn = SKY_OK;
    Uint64 last = SDL_GetPerformanceCounter();
    for (int frame = 0, running = 1; running && (!headless || frame < (int)frames); frame++) {
        for (SDL_Event e; SDL_PollEvent(&e);)
            if (e.type == SDL_QUIT || (e.type == SDL_KEYDOWN && e.key.keysym.sym == SDLK_ESCAPE)) running = 0;
        Uint64 now = SDL_GetPerformanceCounter();
        /* headless runs step a fixed 1/60 s: the same frames every run */
        double dt = headless ? 1.0 / 60.0 : (double)(now - last) / (double)SDL_GetPerformanceFrequency();
        last = now;
        if (held_time < 0) { /* a day in two minutes */
            params.time = fmodf(params.time + (float)(dt / 120.0), 1.0f);
            sky_set_params(s, &params);
        }
        sky_update(s, dt);
        sky_get_lighting(s, &light);
        const float *d = light.sun_direction;
        if (face_sun) { /* 15 degrees clockwise of the sun: it stands left of the centre */
            yaw = atan2f(d[0], -d[2]) + 15.0f * DEG;
            pitch = asinf(fmaxf(-1.0f, fminf(1.0f, d[1]))) - 10.0f * DEG;
        }
        look(view, eye, yaw, pitch);
        projection(proj, 60.0f * DEG, (float)w / (float)h, 0.1f, depth);

        glViewport(0, 0, w, h);
        glClearColor(0, 0, 0, 1);
        glClearDepth(depth == FAR_ONE ? 1.0 : 0.0);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        if (sky_first && !no_sky) drawn = sky_draw(s, view, proj);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(depth == FAR_ONE ? GL_LESS : GL_GREATER);
        glUseProgram(prog);
        glBindVertexArray(vao);
        glUniformMatrix4fv(glGetUniformLocation(prog, "proj"), 1, GL_FALSE, proj);
        glUniformMatrix4fv(glGetUniformLocation(prog, "view"), 1, GL_FALSE, view);
        glUniform3fv(glGetUniformLocation(prog, "eye"), 1, eye);
        const char *const names[4] = {"sun_dir", "sun_col", "ambient", "fog"};
        const float *values[4] = {light.sun_direction, light.sun_color, light.ambient_color, light.fog_color};
        for (int u = 0; u < 4; u++) glUniform3fv(glGetUniformLocation(prog, names[u]), 1, values[u]);
        glUniform1f(glGetUniformLocation(prog, "exposure"), light.exposure);
        glDrawArrays(GL_TRIANGLES, 0, nverts);
        /* the engines' order: the opaque scene, then the sky where the depth
         * buffer still holds the far plane; it tests depth and writes none */
        if (!sky_first && !no_sky) drawn = sky_draw(s, view, proj);
        if (drawn < 0) return fprintf(stderr, "sky-sdl2: %s\n", sky_last_error(s)), 1;
        if (headless && frame + 1 == (int)frames && shot && save_png(shot, w, h))
            return fprintf(stderr, "sky-sdl2: cannot write %s\n", shot), 1;
        SDL_GL_SwapWindow(win);
    }

    /* where the camera puts the sun: its direction in eye space (the view's
     * rotation), through the projection (clip w = -z) */
    const float *d = light.sun_direction;
    float e[3];
    for (int r = 0; r < 3; r++) e[r] = view[r] * d[0] + view[4 + r] * d[1] + view[8 + r] * d[2];
    float x = (proj[0] * e[0] / -e[2] * 0.5f + 0.5f) * (float)w, y = (0.5f - proj[5] * e[1] / -e[2] * 0.5f) * (float)h;
    printf("size %d %d\n", w, h);
    if (e[2] < 0.0f && x >= 0 && x < (float)w && y >= 0 && y < (float)h) printf("sun_pixel %.2f %.2f\n", x, y);
    else printf("sun_pixel none\n");
    printf("sky_draw %d\n", (int)drawn);
    sky_destroy(s); /* while its context is current */
    SDL_GL_DeleteContext(gl);
    SDL_DestroyWindow(win);
    SDL_Quit();
    return 0;
}
