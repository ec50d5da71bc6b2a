/*
 * sky-game: the smallest honest game loop around libsky. The host owns the
 * window and the context (GLFW: OpenGL 3.3 core, or 2.0 with --gl compat)
 * and loads its own GL entry points through the loader it gives the sky.
 * Each frame it draws the sky first, then its own depth-tested world lit by
 * sky_get_lighting: the sun and moon as directional lights; the sky and the
 * ground it lights as ambient light (sky_get_irradiance_sh's 9 coefficients,
 * per normal); a glossy ball reflecting the sky (sky_capture_environment);
 * the air between the eye and every pixel (sky_aerial_glsl and
 * sky_aerial_bind: hills 2 to 20 km away fade into the horizon behind
 * them), and the sky's display stages (sky_display_glsl and
 * sky_display_bind: its exposure, night vision and tone map) so world and
 * sky share one brightness scale.
 * Without a display it renders the same frames headless through OSMesa.
 *
 *   sky-game [--time T] [--preset P] [--gl compat] [--frames N --screenshot FILE]   (--help)
 */
#define GLFW_INCLUDE_GLEXT /* GLchar, GLsizeiptr and the 2.0 enums */
#include "cli.h"
#include "osmesa_ctx.h"

#include <GLFW/glfw3.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Every GL call of the game goes through these pointers, loaded from the
 * context's own loader: a program linked with both -lGL and OSMesa would
 * otherwise send its calls to whichever library the linker bound. */
#define GAME_GL(X)                                                                   \
    X(void, Viewport, (GLint, GLint, GLsizei, GLsizei))                              \
    X(void, Clear, (GLbitfield))                                                     \
    X(void, Enable, (GLenum))                                                        \
    X(void, Disable, (GLenum))                                                       \
    X(void, DrawArrays, (GLenum, GLint, GLsizei))                                    \
    X(void, PixelStorei, (GLenum, GLint))                                            \
    X(void, ReadPixels, (GLint, GLint, GLsizei, GLsizei, GLenum, GLenum, void *))    \
    X(GLuint, CreateShader, (GLenum))                                                \
    X(void, ShaderSource, (GLuint, GLsizei, const GLchar *const *, const GLint *))   \
    X(void, CompileShader, (GLuint))                                                 \
    X(void, GetShaderiv, (GLuint, GLenum, GLint *))                                  \
    X(void, GetShaderInfoLog, (GLuint, GLsizei, GLsizei *, GLchar *))                \
    X(void, DeleteShader, (GLuint))                                                  \
    X(GLuint, CreateProgram, (void))                                                 \
    X(void, AttachShader, (GLuint, GLuint))                                          \
    X(void, BindAttribLocation, (GLuint, GLuint, const GLchar *))                    \
    X(void, LinkProgram, (GLuint))                                                   \
    X(void, GetProgramiv, (GLuint, GLenum, GLint *))                                 \
    X(void, GetProgramInfoLog, (GLuint, GLsizei, GLsizei *, GLchar *))               \
    X(void, DeleteProgram, (GLuint))                                                 \
    X(void, UseProgram, (GLuint))                                                    \
    X(GLint, GetUniformLocation, (GLuint, const GLchar *))                           \
    X(void, Uniform1f, (GLint, GLfloat))                                             \
    X(void, Uniform1i, (GLint, GLint))                                               \
    X(void, ActiveTexture, (GLenum))                                                 \
    X(void, BindTexture, (GLenum, GLuint))                                           \
    X(void, Uniform3fv, (GLint, GLsizei, const GLfloat *))                           \
    X(void, UniformMatrix4fv, (GLint, GLsizei, GLboolean, const GLfloat *))          \
    X(void, GenBuffers, (GLsizei, GLuint *))                                         \
    X(void, DeleteBuffers, (GLsizei, const GLuint *))                                \
    X(void, BindBuffer, (GLenum, GLuint))                                            \
    X(void, BufferData, (GLenum, GLsizeiptr, const void *, GLenum))                  \
    X(void, VertexAttribPointer, (GLuint, GLint, GLenum, GLboolean, GLsizei, const void *)) \
    X(void, EnableVertexAttribArray, (GLuint))                                       \
    X(void, DisableVertexAttribArray, (GLuint))
/* a 3.3 core context draws nothing without a vertex array object; 2.0 has none */
#define GAME_GL_CORE(X)                                 \
    X(void, GenVertexArrays, (GLsizei, GLuint *))       \
    X(void, BindVertexArray, (GLuint))                  \
    X(void, DeleteVertexArrays, (GLsizei, const GLuint *))

typedef struct game_gl {
#define FIELD(ret, name, args) ret(APIENTRY *name) args;
    GAME_GL(FIELD)
    GAME_GL_CORE(FIELD)
#undef FIELD
} game_gl;

/* Returns 0, or -1 naming the first entry point missing. */
static int load_gl(game_gl *gl, sky_get_proc_address_fn loader, int core)
{
    memset(gl, 0, sizeof *gl);
#define LOAD(ret, name, args)                                          \
    if (!(gl->name = (ret(APIENTRY *) args)loader("gl" #name))) {       \
        fprintf(stderr, "sky-game: the context has no gl%s\n", #name); \
        return -1;                                                     \
    }
    GAME_GL(LOAD)
    if (core) {
        GAME_GL_CORE(LOAD)
    }
#undef LOAD
    return 0;
}

/* One source for both profiles: a prologue per profile defines how
 * attributes, varyings and the output are spelled. */
static const char *const vs_core = "#version 330 core\n#define ATTR in\n#define VARY out\n";
static const char *const fs_core =
    "#version 330 core\n#define VARY in\nout vec4 frag;\n#define FRAG frag\n#define CUBE texture\n";
static const char *const vs_compat = "#version 110\n#define ATTR attribute\n#define VARY varying\n";
static const char *const fs_compat =
    "#version 110\n#define VARY varying\n#define FRAG gl_FragColor\n#define CUBE textureCube\n";

static const char *const vs =
    "ATTR vec3 pos;\nATTR vec3 nrm;\nuniform mat4 mvp;\nVARY vec3 n;\nVARY vec3 world;\n"
    "void main() { n = nrm; world = pos; gl_Position = mvp * vec4(pos, 1.0); }\n";
/* Luminance = albedo / pi * illuminance (kcd/m^2 from klx), seen through
 * the air to the eye (sky_aerial_apply, from the sky_aerial_glsl source
 * compiled in front of this one; per pixel: per vertex, the ground's far
 * corners would lend all of it their haze). Then the sky's own display
 * stages (sky_display, from sky_display_glsl: the exposure with its
 * partial adaptation at dusk and night, the rods' blue shift, the default
 * tone map), so a wall and the sky behind it are judged on one scale. */
static const char *const fs =
    "VARY vec3 n;\nVARY vec3 world;\n"
    "uniform vec3 eye, sun_dir, sun_col, moon_dir, moon_col, flash_dir, flash_col;\nuniform vec3 sky_sh[9];\n"
    "uniform samplerCube sky_env;\nuniform vec3 ball;\n"
    "const vec3 grass = vec3(0.20, 0.30, 0.12), stone = vec3(0.45, 0.40, 0.35);\n"
    "void main() {\n"
    "  vec3 nn = normalize(n);\n"
    "  vec3 albedo = world.y < 0.01 ? grass : stone;\n"
    /* a surface sees the sky above its horizon and the lit ground below
     * it (sky_get_irradiance_sh: the sky's radiance as 9 spherical
     * harmonics, evaluated for the surface's normal as engines do,
     * Ramamoorthi & Hanrahan's A_l folded in): at night a wall turned
     * from the moon is lit by the moonlit ground and the sky, as dark as
     * they make it but not black */
    "  vec3 sky = 3.14159 * 0.282095 * sky_sh[0]\n"
    "      + 2.0944 * 0.488603 * (sky_sh[1] * nn.y + sky_sh[2] * nn.z + sky_sh[3] * nn.x)\n"
    "      + 0.785398 * (1.092548 * (sky_sh[4] * nn.x * nn.y + sky_sh[5] * nn.y * nn.z + sky_sh[7] * nn.x * nn.z)\n"
    "                    + 0.315392 * sky_sh[6] * (3.0 * nn.z * nn.z - 1.0) + 0.546274 * sky_sh[8] * (nn.x * nn.x - nn.y * nn.y));\n"
    /* the sun's beam where the clouds let it through (sky_cloud_shadow,
     * from sky_cloud_shadow_glsl: the drawn clouds' shadows, drifting with
     * them; the observer stands at the world's origin, a unit a metre),
     * and lightning's flash while one lights the scene */
    "  vec3 E = sun_col * sky_cloud_shadow(world) * max(dot(nn, sun_dir), 0.0)\n"
    "      + moon_col * max(dot(nn, moon_dir), 0.0) + flash_col * max(dot(nn, flash_dir), 0.0)\n"
    "      + max(sky, vec3(0.0));\n"
    "  vec3 L = sky_aerial_apply(albedo / 3.14159 * E, world - eye, length(world - eye));\n"
    "  vec3 c = sky_display(L);\n"
    /* the glossy ball: the captured sky (sky_capture_environment, 8-bit
     * and tone-mapped as the screen is) reflected about its normal, by
     * Schlick's Fresnel over a dark base */
    "  if (length(world - ball.xyz) < 2.6) {\n"
    /* the sphere's own normal, not the mesh's interpolated one (its
     * triangles would show in the reflection) */
    "    nn = normalize(world - ball);\n"
    "    vec3 v = normalize(world - eye), r = reflect(v, nn);\n"
    "    float f = 0.04 + 0.96 * pow(1.0 - max(dot(-v, nn), 0.0), 5.0);\n"
    "    c = mix(c * 0.3, CUBE(sky_env, r).rgb, 0.35 + 0.65 * f);\n"
    "  }\n"
    "  FRAG = vec4(c, 1.0);\n"
    "}\n";

/* The eye stands 1.7 m above the ground at the origin (--eye M raises it:
 * from a tower or an aircraft the clouds' shadows show across the plain,
 * which from 1.7 m lie within a degree of the horizon beyond 100 m). */
static const float eye_height_default = 1.7f;

/* the glossy ball's centre */
static const float ball[3] = {6.0f, 2.5f, 18.0f};

/* A ground plane 60 km across, five boxes near the eye, six hills 2 to
 * 20 km away and a ball: position and normal per vertex. */
enum { BOXES = 11 };
static int build_world(float *v)
{
    int n = 0;
#define VERT(x, y, z, a, b, c) (v[n * 6 + 0] = x, v[n * 6 + 1] = y, v[n * 6 + 2] = z, v[n * 6 + 3] = a, \
                                v[n * 6 + 4] = b, v[n * 6 + 5] = c, n++)
    const float g = 30000.0f;
    VERT(-g, 0, -g, 0, 1, 0), VERT(g, 0, -g, 0, 1, 0), VERT(g, 0, g, 0, 1, 0);
    VERT(-g, 0, -g, 0, 1, 0), VERT(g, 0, g, 0, 1, 0), VERT(-g, 0, g, 0, 1, 0);
    /* to the south (+z), where the default camera looks: centre x, z,
     * half width, height (m) */
    static const float boxes[BOXES][4] = {
        {-12, 40, 4, 6}, {10, 30, 3, 10}, {0, 60, 8, 4}, {25, 55, 5, 14}, {-30, 25, 3, 3},
        /* hills 2, 4, 7, 11, 15 and 20 km away, where the boxes and the
         * ball hide none of them */
        {-1064, 2000, 120, 90}, {2906, 4000, 300, 260}, {-5086, 7000, 400, 420}, {9562, 11000, 700, 700},
        {-1312, 15000, 1200, 2000}, {2811, 20000, 1800, 2500}};
    for (int b = 0; b < BOXES; b++) {
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
    /* the glossy ball, 2.5 m across its radius, a UV sphere */
    enum { RINGS = 16, SEGS = 32 };
    for (int i = 0; i < RINGS; i++)
        for (int j = 0; j < SEGS; j++) {
            float p[4][3];
            for (int k = 0; k < 4; k++) {
                double th = 3.14159265 * (i + (k >= 2)) / RINGS, ph = 2.0 * 3.14159265 * (j + (k == 1 || k == 2)) / SEGS;
                p[k][0] = (float)(sin(th) * cos(ph)), p[k][1] = (float)cos(th), p[k][2] = (float)(sin(th) * sin(ph));
            }
            static const int tri[6] = {0, 1, 2, 0, 2, 3};
            for (int k = 0; k < 6; k++) {
                const float *q = p[tri[k]];
                VERT(ball[0] + 2.5f * q[0], ball[1] + 2.5f * q[1], ball[2] + 2.5f * q[2], q[0], q[1], q[2]);
            }
        }
#undef VERT
    return n;
}

/* The host's world: its GL entry points, program and buffers. */
typedef struct world {
    game_gl gl;
    GLuint prog, vbo, vao; /* vao: core profile only */
    int count;
    int frames;            /* drawn so far: which face of the sky to capture */
    float eye[3];          /* the eye: over the origin, metres (a unit a metre) */
} world;

/* prologue, then the library's snippets (or NULL), then body */
static GLuint compile(const game_gl *gl, GLenum type, const char *prologue, const char *snippet,
                      const char *snippet2, const char *snippet3, const char *body)
{
    const char *src[5] = {prologue, snippet ? snippet : "", snippet2 ? snippet2 : "", snippet3 ? snippet3 : "", body};
    GLuint s = gl->CreateShader(type);
    gl->ShaderSource(s, 5, src, NULL);
    gl->CompileShader(s);
    GLint ok = 0;
    gl->GetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[1024] = "";
        gl->GetShaderInfoLog(s, sizeof log, NULL, log);
        fprintf(stderr, "sky-game: the world's %s shader: %s\n", type == GL_VERTEX_SHADER ? "vertex" : "fragment", log);
    }
    return s;
}

/* In the current context. Returns 0, or -1 after saying why. */
static int world_create(world *w, sky_get_proc_address_fn loader, int core, float eye_height)
{
    memset(w, 0, sizeof *w);
    w->eye[1] = eye_height;
    game_gl *gl = &w->gl;
    if (load_gl(gl, loader, core)) return -1;
    static float verts[(6 + BOXES * 6 * 5 + 16 * 32 * 6) * 6];
    w->count = build_world(verts);
    GLuint v = compile(gl, GL_VERTEX_SHADER, core ? vs_core : vs_compat, NULL, NULL, NULL, vs);
    GLuint f = compile(gl, GL_FRAGMENT_SHADER, core ? fs_core : fs_compat, sky_display_glsl(), sky_aerial_glsl(),
                       sky_cloud_shadow_glsl(), fs);
    w->prog = gl->CreateProgram();
    gl->AttachShader(w->prog, v);
    gl->AttachShader(w->prog, f);
    gl->BindAttribLocation(w->prog, 0, "pos");
    gl->BindAttribLocation(w->prog, 1, "nrm");
    gl->LinkProgram(w->prog);
    gl->DeleteShader(v);
    gl->DeleteShader(f);
    GLint linked = 0;
    gl->GetProgramiv(w->prog, GL_LINK_STATUS, &linked);
    if (!linked) {
        char log[1024] = "";
        gl->GetProgramInfoLog(w->prog, sizeof log, NULL, log);
        fprintf(stderr, "sky-game: the world's program: %s\n", log);
        gl->DeleteProgram(w->prog);
        return -1;
    }
    if (core) gl->GenVertexArrays(1, &w->vao);
    gl->GenBuffers(1, &w->vbo);
    gl->BindBuffer(GL_ARRAY_BUFFER, w->vbo);
    gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof(float) * 6 * (size_t)w->count), verts, GL_STATIC_DRAW);
    gl->BindBuffer(GL_ARRAY_BUFFER, 0);
    return 0;
}

static void world_destroy(world *w)
{
    const game_gl *gl = &w->gl;
    gl->DeleteProgram(w->prog);
    gl->DeleteBuffers(1, &w->vbo);
    if (w->vao) gl->DeleteVertexArrays(1, &w->vao);
}

/* One frame into the current w x h framebuffer: the sky, then the world. */
static void draw_frame(world *w, sky *s, sky_cli *cli, int width, int height)
{
    const game_gl *gl = &w->gl;
    /* 0. the sky for the ball's reflection: all six faces the first time,
     * then one face a frame (the cost spread over six frames) */
    if (sky_capture_environment(s, 0, 64, w->frames ? w->frames % 6 : SKY_CAPTURE_ALL_FACES, 0) < 0 && !w->frames)
        fprintf(stderr, "sky-game: no reflections: %s\n", sky_last_error(s));
    w->frames++;
    gl->Viewport(0, 0, width, height);
    gl->Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    cli->width = width, cli->height = height;
    float view[16], proj[16], mvp[16];
    sky_cli_camera(cli, view, proj);
    /* 1. the sky: first, it writes no depth and restores what it touched */
    if (sky_draw(s, view, proj) != SKY_OK) fprintf(stderr, "sky-game: %s\n", sky_last_error(s));
    /* 2. the world, lit by the sky, seen from the eye; its own depth range,
     * from 0.5 m to past the farthest hill (20 km) */
    sky_lighting l;
    sky_get_lighting(s, &l);
    sky_irradiance_sh sh;
    sky_get_irradiance_sh(s, &sh); /* cached while the sun and sliders stay */
    const float zn = 0.5f, zf = 45000.0f;
    proj[10] = (zf + zn) / (zn - zf);
    proj[14] = 2.0f * zf * zn / (zn - zf);
    for (int r = 0; r < 3; r++) view[12 + r] -= w->eye[1] * view[4 + r]; /* -R * eye, eye = (0, y, 0) */
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++) {
            mvp[c * 4 + r] = 0;
            for (int k = 0; k < 4; k++) mvp[c * 4 + r] += proj[k * 4 + r] * view[c * 4 + k];
        }
    gl->Enable(GL_DEPTH_TEST);
    gl->UseProgram(w->prog);
    gl->UniformMatrix4fv(gl->GetUniformLocation(w->prog, "mvp"), 1, GL_FALSE, mvp);
    gl->Uniform3fv(gl->GetUniformLocation(w->prog, "eye"), 1, w->eye);
    gl->Uniform3fv(gl->GetUniformLocation(w->prog, "sun_dir"), 1, l.sun_direction);
    gl->Uniform3fv(gl->GetUniformLocation(w->prog, "sun_col"), 1, l.sun_color);
    gl->Uniform3fv(gl->GetUniformLocation(w->prog, "moon_dir"), 1, l.moon_direction);
    gl->Uniform3fv(gl->GetUniformLocation(w->prog, "moon_col"), 1, l.moon_color);
    gl->Uniform3fv(gl->GetUniformLocation(w->prog, "flash_dir"), 1, l.flash_direction);
    gl->Uniform3fv(gl->GetUniformLocation(w->prog, "flash_col"), 1, l.flash_color);
    gl->Uniform3fv(gl->GetUniformLocation(w->prog, "sky_sh"), 9, &sh.radiance[0][0]);
    gl->Uniform3fv(gl->GetUniformLocation(w->prog, "ball"), 1, ball);
    gl->Uniform1i(gl->GetUniformLocation(w->prog, "sky_env"), 0);
    /* the air's table on unit 1 and its uniforms (the cube map is on 0) */
    if (sky_display_bind(s, w->prog) != SKY_OK && w->frames == 1)
        fprintf(stderr, "sky-game: no display stages: %s\n", sky_last_error(s));
    if (sky_aerial_bind(s, w->prog, 1) != SKY_OK && w->frames == 1)
        fprintf(stderr, "sky-game: no aerial perspective: %s\n", sky_last_error(s));
    /* the clouds' shadows on unit 2: this frame's map over 8 km around the
     * observer, a game unit a metre */
    sky_cloud_shadow shadow;
    if ((sky_get_cloud_shadow(s, 1.0f, 8000.0f, &shadow) != SKY_OK || sky_cloud_shadow_bind(s, w->prog, 2) != SKY_OK) &&
        w->frames == 1)
        fprintf(stderr, "sky-game: no cloud shadows: %s\n", sky_last_error(s));
    gl->ActiveTexture(GL_TEXTURE0);
    gl->BindTexture(GL_TEXTURE_CUBE_MAP, sky_environment_texture(s));
    if (w->vao) gl->BindVertexArray(w->vao);
    gl->BindBuffer(GL_ARRAY_BUFFER, w->vbo);
    gl->VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 24, (void *)0);
    gl->VertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 24, (void *)12);
    gl->EnableVertexAttribArray(0);
    gl->EnableVertexAttribArray(1);
    gl->DrawArrays(GL_TRIANGLES, 0, w->count);
    /* left as found, so the next frame's sky_draw meets no stray arrays */
    gl->BindTexture(GL_TEXTURE_CUBE_MAP, 0);
    gl->ActiveTexture(GL_TEXTURE1);
    gl->BindTexture(GL_TEXTURE_2D, 0);
    gl->ActiveTexture(GL_TEXTURE2);
    gl->BindTexture(GL_TEXTURE_2D, 0);
    gl->ActiveTexture(GL_TEXTURE0);
    gl->DisableVertexAttribArray(0);
    gl->DisableVertexAttribArray(1);
    gl->BindBuffer(GL_ARRAY_BUFFER, 0);
    if (w->vao) gl->BindVertexArray(0);
    gl->UseProgram(0);
    gl->Disable(GL_DEPTH_TEST);
}

/* Saves the framebuffer's w x h pixels. Returns 0, or 1 after saying why
 * (the exit status: a script must see that its image is missing). */
static int save_frame(const world *w, int width, int height, const char *path)
{
    sky_osmesa shot = {0};
    shot.width = width, shot.height = height;
    shot.pixels = malloc((size_t)width * (size_t)height * 4u);
    int rc = -1;
    if (shot.pixels) {
        w->gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
        w->gl.ReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, shot.pixels);
        rc = sky_osmesa_write_png(&shot, path, NULL, 0);
    }
    free(shot.pixels);
    if (rc) fprintf(stderr, "sky-game: cannot write %s\n", path);
    return rc ? 1 : 0;
}

/* The sky for the host's context, set up from the command line. */
static sky *make_sky(const sky_cli *cli, sky_get_proc_address_fn loader)
{
    char err[512];
    sky_config cfg = sky_cli_config(cli, loader);
    if (!cfg.features) cfg.features = SKY_CLOUDS | SKY_SUN | SKY_MOON | SKY_STARS | SKY_STARMAP | SKY_WEATHER;
    sky *s = sky_create(&cfg, err, sizeof err);
    if (!s) {
        fprintf(stderr, "sky-game: %s\n", err);
        return NULL;
    }
    sky_cli_apply(s, cli);
    return s;
}

/* No display: the same frames, 1/30 s apart, into an OSMesa buffer. */
static int headless(sky_cli *cli, const char *out, float eye_height)
{
    char err[512];
    sky_osmesa ctx;
    if (sky_osmesa_create(&ctx, cli->width, cli->height, cli->gl, 0, err, sizeof err)) {
        fprintf(stderr, "sky-game: %s\n", err);
        return 1;
    }
    world w;
    sky *s = NULL;
    int status = 1;
    if (!world_create(&w, sky_osmesa_loader(), ctx.is_core, eye_height)) {
        s = make_sky(cli, sky_osmesa_loader());
        if (s) {
            int width = cli->width, height = cli->height;
            for (int frame = 0; frame < cli->frames; frame++) {
                if (frame) sky_update(s, 1.0 / 30.0);
                draw_frame(&w, s, cli, width, height);
            }
            status = save_frame(&w, width, height, out);
            if (!status) printf("sky-game: no display; rendered %s headless\n", out);
            sky_destroy(s);
        }
        world_destroy(&w);
    }
    sky_osmesa_destroy(&ctx);
    return status;
}

static void on_key(GLFWwindow *win, int key, int scancode, int action, int mods)
{
    (void)scancode;
    (void)mods;
    if (key == GLFW_KEY_ESCAPE && action == GLFW_PRESS) glfwSetWindowShouldClose(win, 1);
}

/* core: OpenGL 3.3 core; else 2.0 in a compatibility context (what
 * SKY_GL_COMPAT20 needs: a core context has no fixed legacy state). */
static GLFWwindow *open_window(const sky_cli *cli, int core)
{
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, core ? 3 : 2);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, core ? 3 : 0);
    glfwWindowHint(GLFW_OPENGL_PROFILE, core ? GLFW_OPENGL_CORE_PROFILE : GLFW_OPENGL_ANY_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_FALSE);
    GLFWwindow *win = glfwCreateWindow(cli->width, cli->height, "libsky game", NULL, NULL);
    if (win) glfwSetKeyCallback(win, on_key);
    return win;
}

static void usage(FILE *f)
{
    fprintf(f,
            "usage: sky-game [options]\n"
            "  --size WxH               window size (default 1280x720)\n"
            "  --cover F --height F --density F --sunset F --speed F --time F\n"
            "                           the sky's six sliders, each 0..1 (time: 0 midnight, 0.5 noon)\n"
            "  --preset noon|overcast|sunset|starry|moonlit|eclipse|solar-eclipse|minimal\n"
            "  --date YYYY-MM-DDTHH:MM:SSZ --lat DEG --lon DEG --alt M   where and when\n"
            "  --yaw DEG --pitch DEG --fov DEG   the eye's view\n"
            "  --eye M                  the eye's height above the ground, 0.5..20000 m (default 1.7)\n"
            "  --features LIST --atmosphere PATH --exposure STOPS --seconds S   the sky, as in sky-render\n"
            "  --weather NAME [--weather-to NAME --weather-seconds S] --seed N   the weather, as in\n"
            "                           sky-render (without them, the weather changes every minute)\n"
            "                           (also --turbidity --planet --luts --blend --moon-scale --dome-divisor)\n"
            "  --gl auto|core|compat    OpenGL 3.3 core, or 2.0 in a compatibility context\n"
            "  --frames N --screenshot FILE.png   draw N frames 1/30 s apart, save the last, quit\n"
            "  --out FILE.png           without a display: the image rendered headless (default\n"
            "                           sky-game.png; else --screenshot's file)\n"
            "keys: Esc quits\n");
}

/* --eye M at argv[*i]: 1 taken (*i past its value), 0 not --eye, -1
 * after saying what is wrong with the value. */
static int take_eye(int *i, int argc, char **argv, float *eye_height)
{
    if (strcmp(argv[*i], "--eye")) return 0;
    const char *val = *i + 1 < argc ? argv[*i + 1] : NULL;
    char *end = NULL;
    double m = val ? strtod(val, &end) : NAN;
    if (!val || end == val || *end || !(m >= 0.5 && m <= 20000.0)) {
        fprintf(stderr, "sky-game: --eye: expected a height of 0.5..20000 m, got '%s'\n", val ? val : "(nothing)");
        return -1;
    }
    *eye_height = (float)m;
    (*i)++;
    return 1;
}

int main(int argc, char **argv)
{
    /* --out and --eye are the game's own options: taken out before the
     * shared parse */
    const char *out = NULL;
    float eye_height = eye_height_default;
    char *args[64];
    int n = 0;
    for (int i = 0; i < argc && n < 64; i++) {
        int took = sky_cli_take_out(&i, argc, argv, "sky-game", &out);
        if (!took) took = take_eye(&i, argc, argv, &eye_height);
        if (took < 0) return 2;
        if (took) continue;
        args[n++] = argv[i];
    }
    sky_cli cli;
    char err[512];
    int rc = sky_cli_parse(&cli, n, args, 1, err, sizeof err);
    if (rc == SKY_CLI_HELP) {
        usage(stdout);
        return 0;
    }
    if (rc) {
        fprintf(stderr, "sky-game: %s\n", err);
        return 2;
    }
    /* the world has a perspective camera and the sky's default curve */
    if (cli.fisheye || cli.tone_map != SKY_TONE_MAP_HUE) {
        fprintf(stderr, "sky-game: --fisheye and --tone-map are sky-render's options, not the game's (see --help)\n");
        return 2;
    }
    if (!out) out = cli.screenshot ? cli.screenshot : "sky-game.png";
    if (!getenv("DISPLAY") && !getenv("WAYLAND_DISPLAY")) {
        fprintf(stderr, "sky-game: no display found (DISPLAY is unset)\n");
        return headless(&cli, out, eye_height);
    }
    if (!glfwInit()) {
        fprintf(stderr, "sky-game: GLFW cannot open the display\n");
        return headless(&cli, out, eye_height);
    }
    int core = cli.gl != SKY_GL_COMPAT20;
    GLFWwindow *win = open_window(&cli, core);
    if (!win && cli.gl == SKY_GL_AUTO) win = open_window(&cli, core = 0);
    if (!win) {
        fprintf(stderr, "sky-game: no OpenGL %s window\n", core ? "3.3 core" : "2.0");
        glfwTerminate();
        return 1;
    }
    glfwMakeContextCurrent(win);
    world w;
    if (world_create(&w, glfwGetProcAddress, core, eye_height)) {
        glfwTerminate();
        return 1;
    }
    /* the sky: the host's loader, its features, its sliders and observer */
    sky *s = make_sky(&cli, glfwGetProcAddress);
    if (!s) {
        world_destroy(&w);
        glfwTerminate();
        return 1;
    }
    /* --screenshot runs step 1/30 s a frame, as --frames promises, so
     * their pictures do not depend on the machine's speed */
    int automated = cli.screenshot != NULL;
    int status = 0;
    double last = glfwGetTime(), weather_since = last - 50.0; /* the first change after ten seconds */
    int weather_step = 0;
    for (int frame = 0; !glfwWindowShouldClose(win); frame++) {
        int width, height;
        glfwGetFramebufferSize(win, &width, &height);
        if (width <= 0 || height <= 0) { /* minimised: no view to draw */
            glfwWaitEvents();
            last = glfwGetTime();
            continue;
        }
        /* the real time since the last frame, but never more than a
         * quarter second: a stall (a dragged window, a debugger) must not
         * fling the clouds across the sky */
        double now = glfwGetTime(), dt = now - last;
        last = now;
        if (frame) sky_update(s, automated ? 1.0 / 30.0 : dt < 0.0 ? 0.0 : dt > 0.25 ? 0.25 : dt);
        /* the game's day changes its weather: every minute the next state
         * (fair, cloudy, showers, storm, rain, overcast, clear, ...) over
         * twenty seconds, unless the command line set one */
        if (!automated && cli.weather < 0 && cli.weather_to < 0 && now - weather_since > 60.0) {
            static const sky_weather_state cycle[] = {SKY_WEATHER_FAIR,  SKY_WEATHER_CLOUDY,   SKY_WEATHER_SHOWERS,
                                                      SKY_WEATHER_STORM, SKY_WEATHER_RAIN,     SKY_WEATHER_OVERCAST,
                                                      SKY_WEATHER_FOG,   SKY_WEATHER_CIRRUS,   SKY_WEATHER_CLEAR};
            sky_weather next;
            sky_weather_preset(cycle[weather_step++ % (int)(sizeof cycle / sizeof cycle[0])], &next);
            sky_set_weather(s, &next, 20.0);
            weather_since = now;
        }
        draw_frame(&w, s, &cli, width, height);
        if (automated && frame + 1 >= cli.frames) {
            status = save_frame(&w, width, height, cli.screenshot);
            break;
        }
        glfwSwapBuffers(win);
        glfwPollEvents();
    }
    sky_destroy(s);
    world_destroy(&w);
    glfwTerminate();
    return status;
}
