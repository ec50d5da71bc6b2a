/*
 * sky-bench: what the sky costs, as medians and as ratios to a baseline
 * measured in the same run — a full-screen quad with one texture fetch,
 * the cheapest thing a sky could possibly be.
 *
 *   sky-bench [--json | --markdown] [--size WxH] [--frames N] [--rounds R] [--reference FILE]
 *             [--only-atmosphere | --only-presets | --only-colour | --only-photometry | --only-lighting |
 *              --only-night]
 *             [--tone-map NAME] [--plot FILE.png]
 *   sky-bench --stability [--json | --markdown]
 *   sky-bench --make-reference FILE [--paths N]
 *
 * --markdown writes the same tables as a Markdown document with a header
 * saying which command wrote it, when, on what machine and renderer:
 * docs/benchmarks.md is `sky-bench --markdown` (make bench writes it).
 *
 * Prints, per scene preset and GL profile: GPU bytes, textures, programs,
 * draws, frame ms and its ratio to the baseline of the same profile, and
 * the CPU cost of sky_update while the time slider moves; next to them,
 * Roden & Parberry's cloud shader as their paper prints it and packed into
 * one texture. Then, per atmosphere path, setting and profile: frame ms of
 * the sky (atmosphere + sun), its ratio to the baseline, LUT build ms, and
 * its error against the cached CPU reference (tools/atmo_error.c). Last,
 * the colour section: per path, sun height and view, what the 8-bit
 * output keeps of the sky's hue and saturation (tools/colour.c).
 *
 * Frame times are interleaved: R rounds; in each, every row is measured
 * right after a measurement of the baseline (median of N frames each), so
 * that a ratio compares two figures taken a fraction of a second apart. A
 * row's frame ms and ratio are medians over the rounds. The reason: on a
 * machine of two cores, llvmpipe's speed depends on what else runs. With
 * the cores to itself the baseline takes 2.1 ms at 1280x720; while another
 * process keeps one core busy it takes 4.0 ms (this process then gets one
 * CPU's worth of time, as LP_NUM_THREADS=1 does), for as long as that
 * process runs, seconds or minutes. Neither warm-up nor more frames
 * change that; the rounds print the CPUs that other processes used.
 */
#define GL_GLEXT_PROTOTYPES 1
#include "atmo_error.h"
#include "cli.h"
#include "colour.h"
#include "osmesa_ctx.h"
#include "photometry.h"
#include "plot.h"
#include "sharpness.h"
#include "stability.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <sys/utsname.h>
#include <unistd.h>

enum { MAX_ROUNDS = 50, MAX_SUBJECTS = 24 };

/* ---- the GL calls of sky-bench's own drawing ---------------------------------------------------
 * They go through the current context's loader, as the library's do:
 * OSMesa's exported symbols serve only OSMesa's contexts, and an ES 2.0
 * context comes through EGL. bench_gl_use switches the table with the
 * context (make_current does it). */
#define BENCH_GL_FUNCS(X)                                                                                  \
    X(void, ActiveTexture, (GLenum))                                                                       \
    X(void, AttachShader, (GLuint, GLuint))                                                                \
    X(void, BindAttribLocation, (GLuint, GLuint, const GLchar *))                                          \
    X(void, BindBuffer, (GLenum, GLuint))                                                                  \
    X(void, BindTexture, (GLenum, GLuint))                                                                 \
    X(void, BindVertexArray, (GLuint))                                                                     \
    X(void, BufferData, (GLenum, GLsizeiptr, const void *, GLenum))                                        \
    X(void, Clear, (GLbitfield))                                                                           \
    X(void, CompileShader, (GLuint))                                                                       \
    X(GLuint, CreateProgram, (void))                                                                       \
    X(GLuint, CreateShader, (GLenum))                                                                      \
    X(void, DeleteBuffers, (GLsizei, const GLuint *))                                                      \
    X(void, DeleteProgram, (GLuint))                                                                       \
    X(void, DeleteShader, (GLuint))                                                                        \
    X(void, DeleteTextures, (GLsizei, const GLuint *))                                                     \
    X(void, DeleteVertexArrays, (GLsizei, const GLuint *))                                                 \
    X(void, DepthFunc, (GLenum))                                                                           \
    X(void, DepthMask, (GLboolean))                                                                        \
    X(void, Disable, (GLenum))                                                                             \
    X(void, DrawArrays, (GLenum, GLint, GLsizei))                                                          \
    X(void, Enable, (GLenum))                                                                              \
    X(void, EnableVertexAttribArray, (GLuint))                                                             \
    X(void, Finish, (void))                                                                                \
    X(void, GenBuffers, (GLsizei, GLuint *))                                                               \
    X(void, GenTextures, (GLsizei, GLuint *))                                                              \
    X(void, GenVertexArrays, (GLsizei, GLuint *))                                                          \
    X(void, GetProgramiv, (GLuint, GLenum, GLint *))                                                       \
    X(void, GetShaderInfoLog, (GLuint, GLsizei, GLsizei *, GLchar *))                                      \
    X(void, GetShaderiv, (GLuint, GLenum, GLint *))                                                        \
    X(const GLubyte *, GetString, (GLenum))                                                                \
    X(GLint, GetUniformLocation, (GLuint, const GLchar *))                                                 \
    X(void, LinkProgram, (GLuint))                                                                         \
    X(void, ShaderSource, (GLuint, GLsizei, const GLchar *const *, const GLint *))                         \
    X(void, TexImage2D, (GLenum, GLint, GLint, GLsizei, GLsizei, GLint, GLenum, GLenum, const void *))     \
    X(void, TexParameteri, (GLenum, GLenum, GLint))                                                        \
    X(void, Uniform1f, (GLint, GLfloat))                                                                   \
    X(void, Uniform1i, (GLint, GLint))                                                                     \
    X(void, UseProgram, (GLuint))                                                                          \
    X(void, VertexAttribPointer, (GLuint, GLint, GLenum, GLboolean, GLsizei, const void *))

#define BENCH_GL_MEMBER(ret, name, params) ret(*name) params;
static struct bench_gl {
    BENCH_GL_FUNCS(BENCH_GL_MEMBER)
} bench_gl;
#undef BENCH_GL_MEMBER

static void bench_gl_use(const sky_osmesa *o)
{
    sky_get_proc_address_fn gpa = sky_headless_loader(o);
#define BENCH_GL_LOAD(ret, name, params)                                                                   \
    {                                                                                                      \
        sky_gl_proc p = gpa("gl" #name);                                                                   \
        memcpy(&bench_gl.name, &p, sizeof p);                                                              \
    }
    BENCH_GL_FUNCS(BENCH_GL_LOAD)
#undef BENCH_GL_LOAD
}

/* The calls below are the table's. */
#define glActiveTexture bench_gl.ActiveTexture
#define glAttachShader bench_gl.AttachShader
#define glBindAttribLocation bench_gl.BindAttribLocation
#define glBindBuffer bench_gl.BindBuffer
#define glBindTexture bench_gl.BindTexture
#define glBindVertexArray bench_gl.BindVertexArray
#define glBufferData bench_gl.BufferData
#define glClear bench_gl.Clear
#define glCompileShader bench_gl.CompileShader
#define glCreateProgram bench_gl.CreateProgram
#define glCreateShader bench_gl.CreateShader
#define glDeleteBuffers bench_gl.DeleteBuffers
#define glDeleteProgram bench_gl.DeleteProgram
#define glDeleteShader bench_gl.DeleteShader
#define glDeleteTextures bench_gl.DeleteTextures
#define glDeleteVertexArrays bench_gl.DeleteVertexArrays
#define glDepthFunc bench_gl.DepthFunc
#define glDepthMask bench_gl.DepthMask
#define glDisable bench_gl.Disable
#define glDrawArrays bench_gl.DrawArrays
#define glEnable bench_gl.Enable
#define glEnableVertexAttribArray bench_gl.EnableVertexAttribArray
#define glFinish bench_gl.Finish
#define glGenBuffers bench_gl.GenBuffers
#define glGenTextures bench_gl.GenTextures
#define glGenVertexArrays bench_gl.GenVertexArrays
#define glGetProgramiv bench_gl.GetProgramiv
#define glGetShaderInfoLog bench_gl.GetShaderInfoLog
#define glGetShaderiv bench_gl.GetShaderiv
#define glGetString bench_gl.GetString
#define glGetUniformLocation bench_gl.GetUniformLocation
#define glLinkProgram bench_gl.LinkProgram
#define glShaderSource bench_gl.ShaderSource
#define glTexImage2D bench_gl.TexImage2D
#define glTexParameteri bench_gl.TexParameteri
#define glUniform1f bench_gl.Uniform1f
#define glUniform1i bench_gl.Uniform1i
#define glUseProgram bench_gl.UseProgram
#define glVertexAttribPointer bench_gl.VertexAttribPointer

/* ---- full-screen draws of our own: the baseline and Roden & Parberry's shader ---------------- */

/* One full-screen triangle strip with its program, textures and vertices,
 * kept in a context of its own across the rounds (so nothing else changes
 * its state between them). */
/* What a quad's context is: OpenGL 2.0 (GLSL 1.10), 3.3 core (GLSL 330, a
 * VAO) or ES 2.0 (GLSL ES 1.00, unsized formats). */
enum { KIND_GL20, KIND_CORE, KIND_ES, KINDS };
static int kind_of(sky_gl_profile gl) { return gl == SKY_GL_CORE33 ? KIND_CORE : gl == SKY_GL_ES20 ? KIND_ES : KIND_GL20; }
static const char *const kind_names[KINDS] = {"compat", "core", "es20"};

typedef struct quad {
    GLuint prog, buf, vao, tex[4];
    int ntex, core, es;
    size_t bytes; /* textures and vertices */
} quad;

static GLuint shader(GLenum type, const char *const *src, int n)
{
    GLuint sh = glCreateShader(type);
    glShaderSource(sh, n, src, NULL);
    glCompileShader(sh);
    GLint ok = 0;
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[1024] = "";
        glGetShaderInfoLog(sh, sizeof log, NULL, log);
        fprintf(stderr, "sky-bench: %s shader: %s\n", type == GL_VERTEX_SHADER ? "vertex" : "fragment", log);
    }
    return sh;
}

/* A program from sources given in parts (a version prologue first);
 * attribute i is bound to attribs[i]. 0 if it does not link. */
static GLuint program(const char *const *vs, int nvs, const char *const *fs, int nfs, const char *const *attribs,
                      int nattribs)
{
    GLuint v = shader(GL_VERTEX_SHADER, vs, nvs), f = shader(GL_FRAGMENT_SHADER, fs, nfs), p = glCreateProgram();
    glAttachShader(p, v);
    glAttachShader(p, f);
    for (int i = 0; i < nattribs; i++) glBindAttribLocation(p, (GLuint)i, attribs[i]);
    glLinkProgram(p);
    glDeleteShader(v); /* flagged: they go with the program */
    glDeleteShader(f);
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        glDeleteProgram(p);
        return 0;
    }
    return p;
}

/* A 512x512 RGBA8 texture, linear, repeating, no mipmaps (as the
 * library's and the baseline's). */
static GLuint texture_512(const unsigned char *texels, int es)
{
    GLuint tex;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexImage2D(GL_TEXTURE_2D, 0, es ? GL_RGBA : GL_RGBA8, 512, 512, 0, GL_RGBA, GL_UNSIGNED_BYTE, texels);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    if (!es) glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0); /* (no such thing in ES 2.0) */
    return tex;
}

/* The vertices (floats, stride floats each, the position first) into a
 * buffer, attribute i taking sizes[i] floats; the program in use. */
static void quad_vertices(quad *q, const float *v, int stride, const int *sizes, int nattribs)
{
    if (q->core) {
        glGenVertexArrays(1, &q->vao);
        glBindVertexArray(q->vao);
    }
    glGenBuffers(1, &q->buf);
    glBindBuffer(GL_ARRAY_BUFFER, q->buf);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof(float) * 4 * (size_t)stride), v, GL_STATIC_DRAW);
    q->bytes += sizeof(float) * 4 * (size_t)stride;
    for (int i = 0, at = 0; i < nattribs; at += sizes[i++]) {
        glVertexAttribPointer((GLuint)i, sizes[i], GL_FLOAT, GL_FALSE, (GLsizei)(sizeof(float) * (size_t)stride),
                              (const void *)(sizeof(float) * (size_t)at));
        glEnableVertexAttribArray((GLuint)i);
    }
    glUseProgram(q->prog);
}

static void quad_destroy(quad *q)
{
    glDeleteBuffers(1, &q->buf);
    if (q->core) glDeleteVertexArrays(1, &q->vao);
    glDeleteTextures(q->ntex, q->tex);
    glDeleteProgram(q->prog);
    memset(q, 0, sizeof *q);
}

/* The baseline: one full-screen triangle strip, one RGBA8 512x512 texture
 * fetch per pixel, written straight out. What it draws is fixed: every
 * ratio that sky-bench has ever printed divides by it. */
static int baseline_create(quad *q, int kind, int at_far)
{
    /* at_far: the same quad on the far plane (z = w), for drawing it after
     * a scene with the depth test, as an engine draws its sky */
    static const char *const vs_head[KINDS] = {"#version 110\nattribute vec2 p;\nvarying vec2 uv;\n",
                                               "#version 330 core\nin vec2 p;\nout vec2 uv;\n",
                                               "#version 100\nattribute vec2 p;\nvarying vec2 uv;\n"};
    static const char *const fs[KINDS] = {
        "#version 110\nvarying vec2 uv;\nuniform sampler2D t;\nvoid main(){gl_FragColor=texture2D(t,uv*3.0);}\n",
        "#version 330 core\nin vec2 uv;\nuniform sampler2D t;\nout vec4 c;\nvoid main(){c=texture(t,uv*3.0);}\n",
        ("#version 100\nprecision highp float;\nvarying vec2 uv;\nuniform sampler2D t;\n"
         "void main(){gl_FragColor=texture2D(t,uv*3.0);}\n")};
    const char *vs[3] = {vs_head[kind], at_far ? "const float z = 1.0;\n" : "const float z = 0.0;\n",
                         "void main(){uv=p*0.5+0.5;gl_Position=vec4(p,z,1.0);}\n"};
    static const char *const attribs[1] = {"p"};
    memset(q, 0, sizeof *q);
    q->core = kind == KIND_CORE;
    q->es = kind == KIND_ES;
    q->prog = program(vs, 3, &fs[kind], 1, attribs, 1);
    if (!q->prog) return -1;
    unsigned char *texels = malloc(512 * 512 * 4);
    if (!texels) return -1;
    for (int i = 0; i < 512 * 512 * 4; i++) texels[i] = (unsigned char)(i * 2654435761u >> 24);
    q->tex[q->ntex++] = texture_512(texels, q->es);
    q->bytes += 512 * 512 * 4;
    free(texels);
    static const float strip[8] = {-1, -1, 1, -1, -1, 1, 1, 1};
    static const int sizes[1] = {2};
    quad_vertices(q, strip, 2, sizes, 1);
    glUniform1i(glGetUniformLocation(q->prog, "t"), 0);
    return 0;
}

/* Roden & Parberry 2005, section 3.1, lines 10-28 of their HLSL, in our
 * own GLSL: two cloud layers, cover, detail, density, the sunset gradient
 * and the sunlight; then what their application did with the result: the
 * cloud dome over the sky dome (here the sky colour interpolated from the
 * vertices, blended by the cloud's alpha in the same pass) and a tone map
 * of the period (exponential exposure, gamma 2.2). The textures are
 * monochrome: each fetch is read as the same value in all four channels,
 * except the sunset gradient's colour and strength. */
static const char rp_maths[] =
    "uniform float cover, sunset_amount, density, amount_sunlight, exposure;\n"
    "vec4 rp_clouds(vec4 cloud1, vec4 cloud2, vec4 sunset, vec4 detail)\n"
    "{\n"
    "    vec4 c = cloud1 + cloud2 * (1.0 - cloud1);\n"
    "    c.a -= 1.0 - cover;\n"
    "    float k = clamp(cover, 0.05, 1.0);\n" /* a uniform cannot be assigned */
    "    c.a *= 1.0 / k;\n"
    "    c.rgb += detail.rgb * (1.0 - c.rgb);\n"
    "    c.a *= mix(detail.a, 1.0, density);\n"
    "    if (c.a > 0.0) {\n"
    "        c += density * c.a * 2.0;\n"
    "        if (c.r > 1.0) c.rgb = vec3(1.0 - (c.r - 1.0) * 0.5);\n"
    "    }\n"
    "    c = clamp(c, 0.0, 1.0);\n"
    "    sunset.a *= sunset_amount;\n"
    "    c.rgb = c.rgb * (1.0 - sunset.a) + sunset.rgb * sunset.a;\n"
    "    c.rgb *= amount_sunlight;\n"
    "    return c;\n"
    "}\n"
    "vec4 rp_over_sky(vec3 sky, vec4 c)\n"
    "{\n"
    "    vec3 x = mix(sky, c.rgb, c.a);\n"
    "    x = 1.0 - exp(-x * exposure);\n"
    "    return vec4(pow(x, vec3(1.0 / 2.2)), 1.0);\n"
    "}\n";

/* One source per stage serves GLSL 1.10, 3.30 core and ES 1.00 through these. */
static const char *const rp_vs_prologue[KINDS] = {"#version 110\n#define ATTR attribute\n#define VARY varying\n",
                                                  "#version 330 core\n#define ATTR in\n#define VARY out\n",
                                                  "#version 100\n#define ATTR attribute\n#define VARY varying\n"};
static const char *const rp_fs_prologue[KINDS] = {
    "#version 110\n#define VARY varying\n#define TEX texture2D\n#define FRAG gl_FragColor\n",
    "#version 330 core\n#define VARY in\n#define TEX texture\nout vec4 frag_out;\n#define FRAG frag_out\n",
    "#version 100\nprecision highp float;\n#define VARY varying\n#define TEX texture2D\n#define FRAG gl_FragColor\n"};

/* As printed: four textures at four coordinates, all computed per vertex
 * by the application. */
static const char rp_printed_vs[] =
    "ATTR vec2 p;\nATTR vec3 sky;\nATTR vec2 a_tc0, a_tc1, a_tc2, a_tc3;\n"
    "VARY vec3 v_sky;\nVARY vec2 tc0, tc1, tc2, tc3;\n"
    "void main(){v_sky=sky;tc0=a_tc0;tc1=a_tc1;tc2=a_tc2;tc3=a_tc3;gl_Position=vec4(p,0.0,1.0);}\n";
static const char rp_printed_fs[] =
    "VARY vec3 v_sky;\nVARY vec2 tc0, tc1, tc2, tc3;\n"
    "uniform sampler2D photo_tex, noise_tex, sunset_tex, detail_tex;\n"
    "void main(){FRAG=rp_over_sky(v_sky, rp_clouds(TEX(photo_tex,tc0), TEX(noise_tex,tc1), TEX(sunset_tex,tc2),"
    " TEX(detail_tex,tc3)));}\n";
/* Packed as the paper's section 3 suggests: the photo, noise and detail
 * in the channels of one texture, fetched twice (photo and detail at tc0,
 * noise at tc1); the sunset gradient, a smooth function of the direction,
 * interpolated from the vertices. */
static const char rp_packed_vs[] =
    "ATTR vec2 p;\nATTR vec3 sky;\nATTR vec2 a_tc0, a_tc1;\nATTR vec4 sunset;\n"
    "VARY vec3 v_sky;\nVARY vec2 tc0, tc1;\nVARY vec4 v_sunset;\n"
    "void main(){v_sky=sky;tc0=a_tc0;tc1=a_tc1;v_sunset=sunset;gl_Position=vec4(p,0.0,1.0);}\n";
static const char rp_packed_fs[] =
    "VARY vec3 v_sky;\nVARY vec2 tc0, tc1;\nVARY vec4 v_sunset;\n"
    "uniform sampler2D clouds_tex;\n"
    "void main(){vec4 a=TEX(clouds_tex,tc0), b=TEX(clouds_tex,tc1);\n"
    "FRAG=rp_over_sky(v_sky, rp_clouds(vec4(a.r), vec4(b.g), v_sunset, vec4(a.b)));}\n";

/* Tileable value noise with period cells across the 512 texels, summed
 * over octaves: plausible clouds (the cost does not depend on content). */
static float lattice(int x, int y, unsigned seed)
{
    unsigned h = (unsigned)x * 374761393u + (unsigned)y * 668265263u + seed * 2246822519u;
    h = (h ^ (h >> 13)) * 1274126177u;
    return (float)((h ^ (h >> 16)) & 0xffffu) / 65535.0f;
}

static float fbm(int px, int py, int cells, int octaves, unsigned seed)
{
    float sum = 0.0f, amp = 0.5f, norm = 0.0f;
    for (int o = 0; o < octaves; o++, cells *= 2, amp *= 0.5f) {
        float fx = (float)px * (float)cells / 512.0f, fy = (float)py * (float)cells / 512.0f;
        int x0 = (int)fx, y0 = (int)fy;
        float tx = fx - (float)x0, ty = fy - (float)y0;
        tx = tx * tx * (3.0f - 2.0f * tx), ty = ty * ty * (3.0f - 2.0f * ty);
        int x1 = (x0 + 1) % cells, y1 = (y0 + 1) % cells;
        unsigned s = seed + (unsigned)o * 7919u;
        float a = lattice(x0, y0, s) + (lattice(x1, y0, s) - lattice(x0, y0, s)) * tx;
        float b = lattice(x0, y1, s) + (lattice(x1, y1, s) - lattice(x0, y1, s)) * tx;
        sum += amp * (a + (b - a) * ty);
        norm += amp;
    }
    return sum / norm;
}

static unsigned char byte01(float v) { return (unsigned char)(v <= 0.0f ? 0 : v >= 1.0f ? 255 : v * 255.0f + 0.5f); }

/* The sunset gradient at (x, y) in [0, 1]: red-orange near the sun's side
 * and the horizon, its strength in alpha. */
static void sunset_at(float x, float y, float out[4])
{
    out[0] = 1.0f, out[1] = 0.35f + 0.3f * y, out[2] = 0.15f + 0.25f * y;
    out[3] = (1.0f - y) * (0.4f + 0.6f * (1.0f - x));
}

/* The four monochrome images of the paper's figure 3 as texels: photo,
 * noise, detail, sunset strength. */
static void rp_images(unsigned char *photo, unsigned char *noise, unsigned char *detail, unsigned char *sunset)
{
    for (int y = 0; y < 512; y++)
        for (int x = 0; x < 512; x++) {
            int i = y * 512 + x;
            float ph = fbm(x, y, 4, 6, 1u), no = fbm(x, y, 8, 5, 2u), de = fbm(x, y, 32, 3, 3u), s[4];
            /* a contrast stretch: thin clouds with gaps, as the photo */
            photo[i] = byte01((ph - 0.35f) * 2.5f);
            noise[i] = byte01((no - 0.3f) * 2.0f);
            detail[i] = byte01(de);
            sunset_at((float)x / 511.0f, (float)y / 511.0f, s);
            for (int c = 0; c < 4; c++) sunset[4 * i + c] = byte01(s[c]);
        }
}

/* The application's per-vertex work: the sky colour and the texture
 * coordinates of each corner (drift, the second layer turned and scaled,
 * the gradient's coordinate, the detail at three times the scale).
 * Writes 4 vertices of 13 floats. */
static void rp_vertices(int packed, float *v)
{
    static const float corner[4][2] = {{-1, -1}, {1, -1}, {-1, 1}, {1, 1}};
    const float drift = 0.13f, turn = 0.5f, scale = 1.7f;
    for (int k = 0; k < 4; k++, v += 13) {
        float u = corner[k][0] * 0.5f + 0.5f, w = corner[k][1] * 0.5f + 0.5f;
        v[0] = corner[k][0], v[1] = corner[k][1];
        /* horizon to zenith, in the linear units the tone map expects */
        v[2] = 0.60f - 0.42f * w, v[3] = 0.72f - 0.36f * w, v[4] = 0.90f - 0.10f * w;
        v[5] = u + drift, v[6] = w + 0.5f * drift;
        v[7] = scale * (cosf(turn) * u - sinf(turn) * w) + 2.0f * drift;
        v[8] = scale * (sinf(turn) * u + cosf(turn) * w);
        if (packed)
            sunset_at(u, w, v + 9);
        else
            v[9] = u, v[10] = w, v[11] = 3.0f * u, v[12] = 3.0f * w;
    }
}

/* The cloud shader's row: as printed (four textures) or packed (one). */
static int rp_create(quad *q, int kind, int packed)
{
    memset(q, 0, sizeof *q);
    q->core = kind == KIND_CORE;
    q->es = kind == KIND_ES;
    const char *vs[3] = {rp_vs_prologue[kind], packed ? rp_packed_vs : rp_printed_vs};
    const char *fs[3] = {rp_fs_prologue[kind], rp_maths, packed ? rp_packed_fs : rp_printed_fs};
    static const char *const printed_attribs[6] = {"p", "sky", "a_tc0", "a_tc1", "a_tc2", "a_tc3"};
    static const char *const packed_attribs[5] = {"p", "sky", "a_tc0", "a_tc1", "sunset"};
    q->prog = program(vs, 2, fs, 3, packed ? packed_attribs : printed_attribs, packed ? 5 : 6);
    if (!q->prog) return -1;
    unsigned char *img = malloc(512 * 512 * 7), *rgba = malloc(512 * 512 * 4);
    if (!img || !rgba) {
        free(img);
        free(rgba);
        return -1;
    }
    unsigned char *photo = img, *noise = img + 512 * 512, *detail = img + 2 * 512 * 512, *sunset = img + 3 * 512 * 512;
    rp_images(photo, noise, detail, sunset);
    glUseProgram(q->prog);
    if (packed) {
        for (int i = 0; i < 512 * 512; i++)
            rgba[4 * i] = photo[i], rgba[4 * i + 1] = noise[i], rgba[4 * i + 2] = detail[i],
            rgba[4 * i + 3] = sunset[4 * i + 3];
        q->tex[q->ntex++] = texture_512(rgba, q->es);
        glUniform1i(glGetUniformLocation(q->prog, "clouds_tex"), 0);
    } else {
        const unsigned char *mono[3] = {photo, noise, detail};
        static const char *const names[4] = {"photo_tex", "noise_tex", "sunset_tex", "detail_tex"};
        for (int t = 0; t < 4; t++) {
            if (t == 2)
                memcpy(rgba, sunset, 512 * 512 * 4);
            else
                for (int i = 0; i < 512 * 512; i++) memset(rgba + 4 * i, mono[t < 2 ? t : 2][i], 4);
            glActiveTexture(GL_TEXTURE0 + (GLenum)t);
            q->tex[q->ntex++] = texture_512(rgba, q->es);
            glUniform1i(glGetUniformLocation(q->prog, names[t]), t);
        }
        glActiveTexture(GL_TEXTURE0);
    }
    q->bytes += (size_t)q->ntex * 512 * 512 * 4;
    free(img);
    free(rgba);
    /* mid-morning sliders: half cover, some density and sunset */
    glUniform1f(glGetUniformLocation(q->prog, "cover"), 0.5f);
    glUniform1f(glGetUniformLocation(q->prog, "density"), 0.3f);
    glUniform1f(glGetUniformLocation(q->prog, "sunset_amount"), 0.4f);
    glUniform1f(glGetUniformLocation(q->prog, "amount_sunlight"), 1.0f);
    glUniform1f(glGetUniformLocation(q->prog, "exposure"), 1.5f);
    float v[4 * 13];
    rp_vertices(packed, v);
    static const int printed_sizes[6] = {2, 3, 2, 2, 2, 2}, packed_sizes[5] = {2, 3, 2, 2, 4};
    quad_vertices(q, v, 13, packed ? packed_sizes : printed_sizes, packed ? 5 : 6);
    return 0;
}

/* Median ms of frames draws of the current context's quad (its context
 * holds its program, buffers and textures), each waited for; the first
 * draw of the call is not counted. */
static double quad_time(int frames)
{
    double *t = malloc(sizeof(double) * (size_t)frames);
    if (!t) return -1.0;
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glFinish();
    for (int i = 0; i < frames; i++) {
        double t0 = sky_cli_now_ms();
        glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
        glFinish();
        t[i] = sky_cli_now_ms() - t0;
    }
    double m = sky_cli_median(t, frames);
    free(t);
    return m;
}

/* ---- skies ------------------------------------------------------------------------------------ */

/* The layers a row times, by stats index: this build has sky_layer_count()
 * (ten before 0.6, more as layers are added); past this many the rest go
 * untimed. */
#define BENCH_LAYERS 32

typedef struct row {
    const char *preset;
    const char *profile;
    double frame_ms, ratio;
    double ratio_min, ratio_max; /* over the rounds */
    double update_us;            /* sky_set_params + sky_update, time slider moving; -1: not measured */
    int fetches;                 /* a quad of our own: texture fetches per pixel; 0: a sky */
    double layer_ms[BENCH_LAYERS]; /* by stats index (sky_get_layer_stats): medians with profile_layers,
                                      -1 if never drawn alone */
    double lut_start_ms, lut_rebuild_ms; /* tables built by creation; a rebuild after the sun moved */
    sky_stats st;
} row;

/* Something timed in the rounds: a quad of our own or a sky, each in a
 * context of its own (the library allows one sky per context). */
typedef struct subject {
    sky_osmesa ctx;
    quad q;
    sky *s;
    sky_cli cli;
    float view[16], proj[16];
    row r;
    double ms[MAX_ROUNDS], ratio[MAX_ROUNDS];
} subject;

static void make_current(const sky_osmesa *o)
{
    sky_osmesa_make_current(o);
    bench_gl_use(o);
}

/* A sky described by command-line style options, in a new context. With
 * extras, also the per-layer GPU times and a table rebuild, measured on a
 * profiling sky that is gone before the measured one is made. */
/* A host's opaque scene over the left half of the frame: depth 0.75
 * (clip z 0.5), written once; the sky never writes depth, so it stays for
 * every frame timed after it. */
static void cover_left_half(int kind)
{
    static const char *const vs[KINDS] = {
        "#version 110\nattribute vec2 p;\nvoid main(){gl_Position=vec4(p,0.5,1.0);}\n",
        "#version 330 core\nin vec2 p;\nvoid main(){gl_Position=vec4(p,0.5,1.0);}\n",
        "#version 100\nattribute vec2 p;\nvoid main(){gl_Position=vec4(p,0.5,1.0);}\n"};
    static const char *const fs[KINDS] = {"#version 110\nvoid main(){gl_FragColor=vec4(0.2);}\n",
                                          "#version 330 core\nout vec4 c;\nvoid main(){c=vec4(0.2);}\n",
                                          "#version 100\nvoid main(){gl_FragColor=vec4(0.2);}\n"};
    static const char *const attribs[1] = {"p"};
    quad q;
    memset(&q, 0, sizeof q);
    q.core = kind == KIND_CORE;
    q.prog = program(&vs[kind], 1, &fs[kind], 1, attribs, 1);
    if (!q.prog) return;
    static const float v[8] = {-1, -1, 0, -1, -1, 1, 0, 1};
    static const int sizes[1] = {2};
    quad_vertices(&q, v, 2, sizes, 1);
    glUseProgram(q.prog);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glDisable(GL_DEPTH_TEST);
    glFinish();
    quad_destroy(&q);
}

/* Rows named "PRESET [OPTIONS] + scene over half, sky first|after": the
 * scene drawn first, then the sky without (first) or with (after) the
 * depth test. Returns the depth mode and cuts the name at the " + ". */
static sky_depth scene_row(char *words, int *covered)
{
    char *plus = strstr(words, " + ");
    *covered = plus != NULL;
    if (!plus) return SKY_DEPTH_NONE;
    *plus = '\0';
    return strstr(plus + 1, "after") ? SKY_DEPTH_FAR_ONE : SKY_DEPTH_NONE;
}

static int subject_sky(subject *sub, int argc, char **argv, const char *name, sky_gl_profile gl, int w, int h,
                       int frames, int extras, sky_depth depth, int covered)
{
    char err[512];
    memset(sub, 0, sizeof *sub);
    row *out = &sub->r;
    if (sky_cli_parse(&sub->cli, argc, argv, 0, err, sizeof err)) {
        fprintf(stderr, "sky-bench: %s\n", err);
        return -1;
    }
    if (sky_osmesa_create(&sub->ctx, w, h, gl, 0, err, sizeof err)) {
        fprintf(stderr, "sky-bench: %s\n", err);
        return -1;
    }
    bench_gl_use(&sub->ctx);
    sky_cli *cli = &sub->cli;
    cli->gl = gl;
    cli->width = w;
    cli->height = h;
    sky_cli_camera(cli, sub->view, sub->proj);
    sky_config cfg = sky_cli_config(cli, sky_headless_loader(&sub->ctx));
    cfg.depth = depth;
    int layers = sky_layer_count() < BENCH_LAYERS ? sky_layer_count() : BENCH_LAYERS;
    for (int l = 0; l < BENCH_LAYERS; l++) out->layer_ms[l] = -1.0;
    out->update_us = -1.0;
    double *lt = extras ? malloc(sizeof(double) * (size_t)frames * (size_t)layers) : NULL;
    /* per-layer GPU time: a sky with profile_layers (it waits for the GPU
     * around each draw, so it is kept out of the frame timing) */
    sky_config pcfg = cfg;
    pcfg.profile_layers = 1;
    sky *ps = lt ? sky_create(&pcfg, err, sizeof err) : NULL;
    if (ps) {
        sky_cli_apply(ps, cli);
        sky_draw(ps, sub->view, sub->proj);
        int n[BENCH_LAYERS] = {0};
        for (int i = 0; i < frames; i++) {
            sky_draw(ps, sub->view, sub->proj);
            for (int l = 0; l < layers; l++) {
                sky_layer_stats ls;
                if (sky_get_layer_stats(ps, l, &ls) == SKY_OK && ls.ms >= 0.0) lt[l * frames + n[l]++] = ls.ms;
            }
        }
        for (int l = 0; l < layers; l++)
            if (n[l]) out->layer_ms[l] = sky_cli_median(lt + l * frames, n[l]);
        /* a table rebuild, on the profiling sky (its GPU builds are timed
         * to completion): the sun moved 0.36 degree a frame, past every
         * rebuild threshold; CPU builds happen in sky_set_params, GPU
         * builds in sky_draw */
        sky_params moved = cli->params;
        int nr = frames < 10 ? frames : 10;
        for (int i = 0; i < nr; i++) {
            moved.time = cli->params.time + 0.001f * (float)(i + 1);
            sky_set_params(ps, &moved);
            sky_draw(ps, sub->view, sub->proj);
            sky_stats st;
            sky_get_stats(ps, &st);
            lt[i] = st.lut_ms;
        }
        out->lut_rebuild_ms = sky_cli_median(lt, nr);
    }
    free(lt);
    sky_destroy(ps);
    sub->s = sky_create(&cfg, err, sizeof err);
    if (!sub->s) {
        fprintf(stderr, "sky-bench: %s: %s\n", name, err);
        return -1;
    }
    sky_cli_apply(sub->s, cli); /* sliders, observer, weather, running time */
    if (covered) cover_left_half(kind_of(gl));
    sky_draw(sub->s, sub->view, sub->proj); /* shader JIT */
    glFinish();
    /* lookup tables: what creation built (reported by the first draw) */
    sky_stats first;
    sky_get_stats(sub->s, &first);
    out->lut_start_ms = first.lut_ms;
    out->preset = name;
    out->profile = kind_names[kind_of(gl)];
    return 0;
}

/* A quad of our own (0 the baseline, 1 R-P as printed, 2 R-P packed) in
 * a new context. */
/* The quads of our own, timed in every preset round: the baseline, Roden
 * & Parberry's shader as printed and packed, and the baseline drawn as an
 * engine draws its sky, after a scene over half the frame on the far plane
 * with the depth test: the least that drawing after can cost here. */
enum { QUAD_BASELINE, QUAD_RP_PRINTED, QUAD_RP_PACKED, QUAD_BASELINE_AFTER, QUAD_KINDS };

static int subject_quad(subject *sub, int kind, sky_gl_profile gl, int w, int h)
{
    static const char *const names[QUAD_KINDS] = {"baseline", "R-P 2005 as printed", "R-P packed (2 fetches)",
                                                  "baseline + scene over half, after"};
    char err[512];
    memset(sub, 0, sizeof *sub);
    if (sky_osmesa_create(&sub->ctx, w, h, gl, 0, err, sizeof err)) {
        fprintf(stderr, "sky-bench: %s\n", err);
        return -1;
    }
    bench_gl_use(&sub->ctx);
    int ctx_kind = kind_of(gl);
    if (kind == QUAD_BASELINE_AFTER) cover_left_half(ctx_kind);
    if (kind == QUAD_RP_PRINTED || kind == QUAD_RP_PACKED ? rp_create(&sub->q, ctx_kind, kind == QUAD_RP_PACKED)
                               : baseline_create(&sub->q, ctx_kind, kind == QUAD_BASELINE_AFTER)) {
        fprintf(stderr, "sky-bench: the %s shader failed\n", names[kind]);
        return -1;
    }
    row *r = &sub->r;
    r->preset = names[kind];
    r->profile = kind_names[ctx_kind];
    r->update_us = -1.0;
    r->fetches = kind == QUAD_RP_PRINTED ? 4 : kind == QUAD_RP_PACKED ? 2 : 1;
    if (kind == QUAD_BASELINE_AFTER) { /* the sky's way of drawing after a scene (sky_depth FAR_ONE) */
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LEQUAL);
        glDepthMask(GL_FALSE);
    }
    r->st.gpu_bytes = sub->q.bytes;
    r->st.textures = sub->q.ntex;
    r->st.programs = 1;
    r->st.draws_per_frame = 1;
    return 0;
}

/* Median frame ms of a subject now, in its context. A sky's first frame
 * in each call is not counted, as the quad's. */
static double subject_time(subject *sub, int frames)
{
    make_current(&sub->ctx);
    if (!sub->s) return quad_time(frames);
    double *t = malloc(sizeof(double) * (size_t)frames);
    if (!t) return -1.0;
    sky_update(sub->s, 1.0 / 60.0);
    sky_draw(sub->s, sub->view, sub->proj);
    glFinish();
    for (int i = 0; i < frames; i++) {
        sky_update(sub->s, 1.0 / 60.0);
        double t0 = sky_cli_now_ms();
        sky_draw(sub->s, sub->view, sub->proj);
        glFinish();
        t[i] = sky_cli_now_ms() - t0;
    }
    double m = sky_cli_median(t, frames);
    free(t);
    sky_get_stats(sub->s, &sub->r.st);
    return m;
}

static void subject_close(subject *sub)
{
    if (!sub->ctx.ctx) return;
    make_current(&sub->ctx);
    if (sub->s) sky_destroy(sub->s);
    if (sub->q.prog) quad_destroy(&sub->q);
    sky_osmesa_destroy(&sub->ctx);
    sub->s = NULL;
}

/* CPU seconds spent by every process on the machine (/proc/stat), and by
 * this one: what others took during a round tells whether llvmpipe had
 * both cores. -1 where there is no /proc. */
static double machine_busy_s(void)
{
    FILE *f = fopen("/proc/stat", "r");
    if (!f) return -1.0;
    unsigned long long v[8];
    int n = fscanf(f, "cpu %llu %llu %llu %llu %llu %llu %llu %llu", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5], &v[6],
                   &v[7]);
    fclose(f);
    if (n != 8) return -1.0;
    /* user, nice, system, irq, softirq, steal; not idle or iowait */
    return (double)(v[0] + v[1] + v[2] + v[5] + v[6] + v[7]) / (double)sysconf(_SC_CLK_TCK);
}

static double own_busy_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

/* The rounds of one table: the baseline's figure and the CPUs that other
 * processes used, per round. */
typedef struct rounds_info {
    int n;
    double base_ms[MAX_ROUNDS], others_cpus[MAX_ROUNDS];
} rounds_info;

/* The interleaved rounds. In each, every row is measured right after a
 * measurement of the baseline (subs[0]), and its ratio for the round is
 * to that one: the two are a fraction of a second apart, while a whole
 * round takes seconds, time enough for another process to take a core
 * away or give it back. The round's baseline figure is the median of its
 * measurements. A row's frame ms and ratio are the medians over the
 * rounds of its figures. */
static int run_rounds(subject *subs, int n, int rounds, int frames, rounds_info *info)
{
    if (n < 2 || n > MAX_SUBJECTS) {
        fprintf(stderr, "sky-bench: %d rows in one round; at most %d\n", n, MAX_SUBJECTS);
        return -1;
    }
    info->n = rounds;
    for (int k = 0; k < rounds; k++) {
        double wall0 = sky_cli_now_ms(), busy0 = machine_busy_s(), own0 = own_busy_s();
        double base[MAX_SUBJECTS];
        for (int i = 1; i < n; i++) {
            base[i - 1] = subject_time(&subs[0], frames);
            subs[i].ms[k] = subject_time(&subs[i], frames);
            if (base[i - 1] <= 0.0 || subs[i].ms[k] <= 0.0) {
                fprintf(stderr, "sky-bench: %s: timing failed\n", subs[i].r.preset);
                return -1;
            }
            subs[i].ratio[k] = subs[i].ms[k] / base[i - 1];
        }
        subs[0].ms[k] = info->base_ms[k] = sky_cli_median(base, n - 1);
        subs[0].ratio[k] = 1.0;
        double busy1 = machine_busy_s(), wall = (sky_cli_now_ms() - wall0) * 1e-3;
        double others = (busy1 - busy0 - (own_busy_s() - own0)) / wall;
        info->others_cpus[k] = busy0 < 0.0 || busy1 < 0.0 ? -1.0 : fmax(0.0, others);
    }
    for (int i = 0; i < n; i++) {
        double ms[MAX_ROUNDS], ratio[MAX_ROUNDS];
        memcpy(ms, subs[i].ms, sizeof(double) * (size_t)rounds);
        memcpy(ratio, subs[i].ratio, sizeof(double) * (size_t)rounds);
        row *r = &subs[i].r;
        r->frame_ms = sky_cli_median(ms, rounds);
        r->ratio = sky_cli_median(ratio, rounds); /* which sorts them: */
        r->ratio_min = ratio[0];
        r->ratio_max = ratio[rounds - 1];
    }
    return 0;
}

/* Median frame ms of the scene described by command-line style options,
 * measured once (no rounds), with its per-layer and table figures. */
static int bench_args(int argc, char **argv, const char *name, sky_gl_profile gl, int w, int h, int frames, row *out)
{
    subject sub;
    int rc = subject_sky(&sub, argc, argv, name, gl, w, h, frames, 1, SKY_DEPTH_NONE, 0);
    if (!rc) {
        sub.r.frame_ms = subject_time(&sub, frames);
        *out = sub.r;
    }
    subject_close(&sub);
    return rc;
}

/* Microseconds per full astronomy update (sun, moon, phase, libration,
 * eclipse, star matrices) for an observer whose time slider sets the time
 * of day (two evaluations: the second corrects for the equation of time),
 * median over n updates at different times. */
static double astro_us(int n)
{
    double *t = malloc(sizeof(double) * (size_t)n);
    sky_observer o = {sky_julian_day(2024, 4, 8, 18, 0, 0.0), 40.0, -80.0, 200.0, 1};
    sky_astronomy a;
    double sink = 0.0;
    for (int i = 0; i < n; i++) {
        double t0 = sky_cli_now_ms();
        sky_compute_astronomy(&o, (float)(i % 100) / 100.0f, NULL, 0, NULL, &a, NULL, 0);
        t[i] = (sky_cli_now_ms() - t0) * 1000.0;
        sink += a.sun.alt_deg;
    }
    double m = sky_cli_median(t, n);
    free(t);
    return sink == sink ? m : -1.0; /* keeps the work from being optimised away */
}

/* What a host pays on the CPU each frame while the time slider moves, as
 * sky-demo does: sky_set_params with the time 1/7200 of a day further on
 * (a day in two minutes at 60 frames a second) and sky_update(1/60).
 * Median microseconds of n calls; no draw. The preset's sliders are put
 * back afterwards. */
enum { UPDATE_CALLS = 2000 };
static double update_us(sky *s, const sky_params *start, int n)
{
    double *t = malloc(sizeof(double) * (size_t)n);
    if (!t) return -1.0;
    sky_params p = *start;
    for (int i = 0; i < n; i++) {
        double day = (double)start->time + (double)(i + 1) / 7200.0;
        p.time = (float)(day - floor(day));
        double t0 = sky_cli_now_ms();
        sky_set_params(s, &p);
        sky_update(s, 1.0 / 60.0);
        t[i] = (sky_cli_now_ms() - t0) * 1000.0;
    }
    sky_set_params(s, start);
    double m = sky_cli_median(t, n);
    free(t);
    return m;
}

/* The preset table of one profile, interleaved: the baseline, the two R-P
 * rows and every preset in each round. Writes 2 + np rows and the
 * baseline's per-round figures. */
static int bench_presets(const char *const *presets, int np, sky_gl_profile gl, int w, int h, int frames, int rounds,
                         row *rows, double *base_ms, rounds_info *info)
{
    int n = QUAD_KINDS + np, rc = 0;
    subject *subs = calloc((size_t)n, sizeof *subs);
    if (!subs) return -1;
    for (int i = 0; i < n && !rc; i++)
        if (i < QUAD_KINDS)
            rc = subject_quad(&subs[i], i, gl, w, h);
        else {
            /* a row is a preset, perhaps with options after it
             * ("noon --atmosphere hillaire"): split at the spaces */
            char words[128], *argv[8] = {"sky-bench", "--preset"};
            int argc = 2, covered = 0;
            snprintf(words, sizeof words, "%s", presets[i - QUAD_KINDS]);
            sky_depth depth = scene_row(words, &covered);
            for (char *t = strtok(words, " "); t && argc < 7; t = strtok(NULL, " ")) argv[argc++] = t;
            argv[argc] = NULL;
            rc = subject_sky(&subs[i], argc, argv, presets[i - QUAD_KINDS], gl, w, h, frames, 0, depth, covered);
        }
    if (!rc) rc = run_rounds(subs, n, rounds, frames, info);
    if (!rc) {
        for (int i = QUAD_KINDS; i < n; i++) {
            make_current(&subs[i].ctx);
            subs[i].r.update_us = update_us(subs[i].s, &subs[i].cli.params, UPDATE_CALLS);
        }
        for (int i = 1; i < n; i++) rows[i - 1] = subs[i].r;
        *base_ms = subs[0].r.frame_ms;
    }
    for (int i = 0; i < n; i++) subject_close(&subs[i]);
    free(subs);
    return rc;
}

/* The night layers on their own: the frame with the layer minus the
 * frame without it. Stars, planets, star map, airglow and zodiacal light
 * on an August night with the Milky Way up, looking south (the planets
 * east, at Saturn: no planet in view is no draw); the moon (full,
 * 2024-06-22, looked at) at c_d 3 and 30. */
enum { NIGHT_NONE, NIGHT_STARS, NIGHT_STARMAP, NIGHT_PLANETS, NIGHT_AIRGLOW, NIGHT_ZODIACAL, NIGHT_MOON_NONE,
       NIGHT_MOON3, NIGHT_MOON30, NIGHT_COUNT };
/* the stars, the planets and the moon are draws of their own: their GPU
 * time is measured directly; the star map, airglow and zodiacal light live
 * in the dome pass: by difference */
static int bench_night(sky_gl_profile gl, int w, int h, int frames, double out_ms[NIGHT_COUNT])
{
    static const char *features[6] = {"none", "stars", "starmap", "planets", "airglow", "zodiacal"};
    row r;
    for (int i = 0; i < 6; i++) {
        char *argv[] = {"sky-bench", "--features", (char *)features[i], "--date", "2024-08-10T21:00:00Z",
                        "--lat", "45", "--yaw", i == NIGHT_PLANETS ? "105" : "180",
                        "--pitch", i == NIGHT_PLANETS ? "20" : "30", NULL};
        if (bench_args(11, argv, features[i], gl, w, h, frames, &r)) return -1;
        out_ms[i] = i == NIGHT_STARS ? r.layer_ms[SKY_LAYER_STARS]
                    : i == NIGHT_PLANETS ? r.layer_ms[SKY_LAYER_PLANETS]
                                         : r.frame_ms;
    }
    static const char *moon_features[3] = {"none", "moon", "moon"}, *scales[3] = {"3", "3", "30"};
    for (int i = 0; i < 3; i++) {
        char *argv[] = {"sky-bench", "--features", (char *)moon_features[i], "--moon-scale", (char *)scales[i],
                        "--date", "2024-06-22T00:00:00Z", "--lat", "-30", "--lon", "20", "--yaw", "30",
                        "--pitch", "40", NULL};
        if (bench_args(15, argv, moon_features[i], gl, w, h, frames, &r)) return -1;
        out_ms[NIGHT_MOON_NONE + i] = i ? r.layer_ms[SKY_LAYER_MOON] : r.frame_ms;
    }
    return 0;
}


/* ---- atmosphere paths: run time against error ------------------------------------------------ */

typedef struct atmo_setting {
    const char *path, *setting;
    const char *args[6];
} atmo_setting;

static const atmo_setting atmo_settings[] = {
    {"gradient", "default", {"--atmosphere", "gradient"}},
    {"preetham", "T 2.5 (default)", {"--atmosphere", "preetham"}},
    {"preetham", "T 2", {"--atmosphere", "preetham", "--turbidity", "2"}},
    {"rayleigh", "default", {"--atmosphere", "rayleigh"}},
    {"hillaire", "tables x0.5", {"--atmosphere", "hillaire", "--luts", "small"}},
    {"hillaire", "default", {"--atmosphere", "hillaire"}},
    {"hillaire", "tables x2", {"--atmosphere", "hillaire", "--luts", "large"}},
    {"blend", "automatic", {"--atmosphere", "blend"}},
};
enum { ATMO_SETTINGS = sizeof atmo_settings / sizeof atmo_settings[0] };

typedef struct atmo_row {
    const atmo_setting *setting;
    const char *profile;
    double frame_ms, ratio, ratio_min, ratio_max, lut_start_ms, lut_rebuild_ms;
    sky_atmo_errors err;
} atmo_row;

/* A setting's options after the given leading ones; returns argc. */
static int setting_argv(const atmo_setting *a, char **argv, int argc)
{
    for (int i = 0; i < 6 && a->args[i]; i++) argv[argc++] = (char *)a->args[i];
    return argc;
}

/* Every setting in one profile, interleaved with the baseline as the
 * presets are: the frame of the full sky's atmosphere and sun at the bench
 * size (the default camera of sky-render, morning sun). */
static int bench_atmosphere(sky_gl_profile gl, int w, int h, int frames, int rounds, atmo_row *out, double *base_ms,
                            rounds_info *info)
{
    int n = 1 + ATMO_SETTINGS;
    subject *subs = calloc((size_t)n, sizeof *subs);
    if (!subs) return -1;
    int rc = subject_quad(&subs[0], 0, gl, w, h);
    for (int a = 0; a < ATMO_SETTINGS && !rc; a++) {
        char *argv[12] = {"sky-bench", "--features", "sun", "--time", "0.35"};
        int argc = setting_argv(&atmo_settings[a], argv, 5);
        rc = subject_sky(&subs[1 + a], argc, argv, atmo_settings[a].path, gl, w, h, frames, 1, SKY_DEPTH_NONE, 0);
    }
    if (!rc) rc = run_rounds(subs, n, rounds, frames, info);
    for (int a = 0; a < ATMO_SETTINGS && !rc; a++) {
        const row *r = &subs[1 + a].r;
        out[a].setting = &atmo_settings[a];
        out[a].profile = r->profile;
        out[a].frame_ms = r->frame_ms;
        out[a].ratio = r->ratio;
        out[a].ratio_min = r->ratio_min;
        out[a].ratio_max = r->ratio_max;
        out[a].lut_start_ms = r->lut_start_ms;
        out[a].lut_rebuild_ms = r->lut_rebuild_ms;
    }
    if (!rc) *base_ms = subs[0].r.frame_ms;
    for (int i = 0; i < n; i++) subject_close(&subs[i]);
    free(subs);
    return rc;
}

/* The error of a row's all-sky image; with no context current (the
 * measurement makes its own float context). */
static int measure_atmosphere(atmo_row *out, const sky_atmo_reference *ref, sky_gl_profile gl)
{
    char *argv[8] = {"sky-bench"};
    int argc = setting_argv(out->setting, argv, 1);
    sky_cli cli;
    char err[512];
    if (sky_cli_parse(&cli, argc, argv, 0, err, sizeof err)) return -1;
    cli.gl = gl;
    sky_config cfg = sky_cli_config(&cli, sky_osmesa_loader());
    if (sky_atmo_measure(ref, &cfg, &out->err, err, sizeof err)) {
        fprintf(stderr, "sky-bench: %s: %s\n", out->setting->path, err);
        return -1;
    }
    return 0;
}

/* The reference's mean standard error relative to its luminance. */
static double reference_rel_std_err(const sky_atmo_reference *ref)
{
    double se = 0.0;
    for (int s = 0; s < SKY_ATMO_SUNS; s++)
        for (int k = 0; k < SKY_ATMO_DIRECTIONS; k++) {
            const double *c = ref->rgb[s][k];
            se += ref->std_err[s][k] / fmax(0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2], 1e-30);
        }
    return se / (SKY_ATMO_SUNS * SKY_ATMO_DIRECTIONS);
}

static void print_atmosphere_table(const atmo_row *rows, int n, const sky_atmo_reference *ref)
{
    printf("\nAtmosphere paths against the CPU reference (spectral, %d Monte Carlo paths per wavelength for orders\n"
           ">= 2; mean relative standard error %.2f %%), Earth preset. Frame: atmosphere + sun at the size above.\n"
           "Errors over an equal-area all-sky grid; day: sun >= 0 deg, twilight: -6 <= sun < 0 deg.\n\n",
           ref->paths, 100.0 * reference_rel_std_err(ref));
    printf("| path | setting | profile | frame ms | x baseline | x baseline, rounds min-max | LUT ms at start | "
           "sky-view rebuild ms | "
           "mean rel err day | max rel err day | mean rel err twilight | mean dE2000 day |\n"
           "|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (int i = 0; i < n; i++)
        printf("| %s | %s | %s | %.2f | %.2f | %.2f-%.2f | %.1f | %.1f | %.1f %% | %.0f %% | %.0f %% | %.1f |\n",
               rows[i].setting->path, rows[i].setting->setting, rows[i].profile, rows[i].frame_ms, rows[i].ratio,
               rows[i].ratio_min, rows[i].ratio_max,
               rows[i].lut_start_ms, rows[i].lut_rebuild_ms,
               100.0 * rows[i].err.mean_rel_day, 100.0 * rows[i].err.max_rel_day,
               100.0 * rows[i].err.mean_rel_twilight, rows[i].err.mean_de2000_day);
    printf("\nMean relative luminance error by sun elevation (core profile):\n\n| path | setting |");
    for (int s = 0; s < SKY_ATMO_SUNS; s++) printf(" %+.0f |", sky_atmo_sun_elevations[s]);
    printf("\n|---|---|");
    for (int s = 0; s < SKY_ATMO_SUNS; s++) printf("---|");
    printf("\n");
    for (int i = 0; i < n; i++) {
        if (strcmp(rows[i].profile, "core")) continue;
        printf("| %s | %s |", rows[i].setting->path, rows[i].setting->setting);
        for (int s = 0; s < SKY_ATMO_SUNS; s++) printf(" %.0f %% |", 100.0 * rows[i].err.mean_rel[s]);
        printf("\n");
    }
}

/* The chart of error against cost, one colour per path. */
static int plot_atmosphere(const char *path, const atmo_row *rows, int n)
{
    static const char *const paths[] = {"gradient", "preetham", "rayleigh", "hillaire", "blend"};
    plot_point pts[64];
    int m = 0;
    for (int i = 0; i < n && m < 64; i++) {
        int series = 0;
        for (int k = 0; k < 5; k++)
            if (!strcmp(rows[i].setting->path, paths[k])) series = k;
        pts[m].cost = rows[i].ratio;
        pts[m].error = rows[i].err.mean_rel_day;
        pts[m].series = series;
        pts[m].hollow = strcmp(rows[i].profile, "core") != 0;
        m++;
    }
    if (plot_pareto(path, pts, m, paths, 5, "frame time / one-texture baseline",
                    "mean relative luminance error, sun >= 0", "atmosphere paths: error against run time")) {
        fprintf(stderr, "sky-bench: cannot write %s\n", path);
        return -1;
    }
    return 0;
}

/* sky-bench --stability: the stability suite's table (tools/stability.c).
 * Exit 0 when every case passes, 1 otherwise. */
static int stability_table(int json)
{
    sky_stability_row rows[SKY_STABILITY_MAX_ROWS];
    char err[512];
    int n = sky_stability_run(1, rows, err, sizeof err);
    if (n < 0) {
        fprintf(stderr, "sky-bench: %s\n", err);
        return 1;
    }
    int failed = 0;
    if (json) printf("{\"stability\": [\n");
    else
        printf("| case | property | worst | tolerance | samples | pass |\n|---|---|---|---|---|---|\n");
    for (int i = 0; i < n; i++) {
        const sky_stability_row *r = &rows[i];
        failed += !r->pass;
        if (json) {
            /* JSON has no infinity: a non-finite worst is written as null */
            char worst[32] = "null";
            if (isfinite(r->worst)) snprintf(worst, sizeof worst, "%.6g", r->worst);
            printf("  {\"case\":\"%s\", \"property\":\"%s\", \"unit\":\"%s\", \"worst\":%s, "
                   "\"tolerance\":%.6g, \"samples\":%ld, \"pass\":%s}%s\n",
                   r->name, r->property, r->unit, worst, r->tolerance, r->samples, r->pass ? "true" : "false",
                   i + 1 < n ? "," : "");
        } else
            printf("| %s | %s | %.3g%s%s | %.3g%s%s | %ld | %s |\n", r->name, r->property, r->worst,
                   r->unit[0] ? " " : "", r->unit, r->tolerance, r->unit[0] ? " " : "", r->unit, r->samples,
                   r->pass ? "yes" : "**no**");
    }
    if (json) printf("], \"failed\": %d}\n", failed);
    return failed ? 1 : 0;
}


/* Both profiles' rows, each profile's R-P rows first. */
static void print_preset_table(const row *rows, int nrows)
{
    printf("| preset | profile | GPU bytes | textures | programs | draws | frame ms | x baseline | "
           "x baseline, rounds min-max | sky_update us |\n");
    printf("|---|---|---|---|---|---|---|---|---|---|\n");
    for (int i = 0; i < nrows; i++) {
        const row *r = &rows[i];
        char us[32] = "-";
        if (r->update_us >= 0.0) snprintf(us, sizeof us, "%.1f", r->update_us);
        printf("| %s | %s | %zu | %d | %d | %d | %.2f | %.2f | %.2f-%.2f | %s |\n", r->preset, r->profile,
               r->st.gpu_bytes, r->st.textures, r->st.programs, r->st.draws_per_frame, r->frame_ms, r->ratio,
               r->ratio_min, r->ratio_max, us);
    }
    printf("\nsky_update us: median of %d calls of sky_set_params, the time slider 1/7200 of a day further on\n"
           "each call, and sky_update(1/60), CPU only (no draw); target <= 20 us. The presets with a date of\n"
           "their own (moonlit, eclipse, solar-eclipse) keep it: there the slider does not move the clock.\n"
           "R-P rows: Roden & Parberry's cloud shader (2005, section 3.1) over a per-vertex sky with a tone\n"
           "map, as printed (4 textures, 4 fetches) and packed into one texture (2 fetches, the sunset\n"
           "gradient per vertex). \"baseline + scene over half, after\": the baseline on the far plane, drawn\n"
           "after a scene over the left half with the depth test as an engine draws its sky: what a pixel the\n"
           "scene covers still costs this rasterizer (compare the \"sky after\" rows with it).\n",
           UPDATE_CALLS);
}

/* The profiles the preset and night tables run on (--gl), in order. */
enum { MAX_PROFS = 3 };
typedef struct profiles {
    int n;
    sky_gl_profile gl[MAX_PROFS];
} profiles;

static const char *prof_name(const profiles *pr, int i) { return kind_names[kind_of(pr->gl[i])]; }

/* ---- --markdown: the report as a document ----------------------------------------------------
 * docs/benchmarks.md is this output. Its header says what wrote it, so that
 * a reader can tell a run on llvmpipe from one on a GPU and knows which
 * checkout it measured; each table gets a "## " heading, whose anchor the
 * README and the other docs link to (tests/test_docs.c checks those links
 * and that the README's figures occur in the section they cite), so the
 * headings are part of the output's contract. */
static struct markdown {
    int on, argc;
    char **argv;
    const profiles *pr;
    int w, h, frames, rounds;
} md;

/* A section's heading; nothing in the plain report. */
static void heading(const char *title)
{
    if (md.on) printf("\n## %s\n\n", title);
}

/* The baseline's medians over the rounds, then per round its figure and
 * the CPUs that other processes were using meanwhile (a figure near 1 on
 * two cores: llvmpipe had one of them). */
static void print_baseline(const char *what, int w, int h, int frames, const profiles *pr, const double *base,
                           const rounds_info *info)
{
    printf("baseline (one-texture full-screen quad, %dx%d)%s:", w, h, what);
    for (int prof = 0; prof < pr->n; prof++) printf("%s %s %.2f ms", prof ? "," : "", prof_name(pr, prof), base[prof]);
    printf(", medians of %d interleaved rounds of %d frames\n", info[0].n, frames);
    for (int prof = 0; prof < pr->n; prof++) {
        printf(md.on ? "%s- %s, per round: ms" : "%s  %s, per round: ms", md.on && !prof ? "\n" : "",
               prof_name(pr, prof));
        for (int k = 0; k < info[prof].n; k++) printf(" %.2f", info[prof].base_ms[k]);
        printf("; other processes' CPUs");
        for (int k = 0; k < info[prof].n; k++) printf(" %.1f", info[prof].others_cpus[k]);
        printf("\n");
    }
}

/* The JSON of the preset table: the rows of real presets under "presets"
 * as always (with the rounds' spread and sky_update added), the R-P
 * shaders under "rp_rows". */
static void print_presets_json(const row *rows, int nrows)
{
    printf(" \"presets\": [\n");
    int first = 1;
    for (int i = 0; i < nrows; i++) {
        const row *r = &rows[i];
        if (r->fetches) continue;
        printf("%s  {\"preset\":\"%s\", \"profile\":\"%s\", \"gpu_bytes\":%zu, \"textures\":%d, \"programs\":%d, "
               "\"draws\":%d, \"frame_ms\":%.4f, \"ratio\":%.3f, \"ratio_min\":%.3f, \"ratio_max\":%.3f, "
               "\"sky_update_us\":%.3f}",
               first ? "" : ",\n", r->preset, r->profile, r->st.gpu_bytes, r->st.textures, r->st.programs,
               r->st.draws_per_frame, r->frame_ms, r->ratio, r->ratio_min, r->ratio_max, r->update_us);
        first = 0;
    }
    printf("\n ],\n \"rp_rows\": [\n");
    first = 1;
    for (int i = 0; i < nrows; i++) {
        const row *r = &rows[i];
        if (!r->fetches) continue;
        printf("%s  {\"name\":\"%s\", \"profile\":\"%s\", \"gpu_bytes\":%zu, \"textures\":%d, \"fetches\":%d, "
               "\"frame_ms\":%.4f, \"ratio\":%.3f, \"ratio_min\":%.3f, \"ratio_max\":%.3f}",
               first ? "" : ",\n", r->preset, r->profile, r->st.gpu_bytes, r->st.textures,
               r->fetches, r->frame_ms, r->ratio, r->ratio_min, r->ratio_max);
        first = 0;
    }
    printf("\n ]");
}

static void print_json_list(const char *name, const double *v, int n)
{
    printf("\"%s\":[", name);
    for (int k = 0; k < n; k++) printf("%.4f%s", v[k], k + 1 < n ? "," : "");
    printf("]");
}

/* "frame_ms" and "compat_frame_ms" as before, then the rounds. */
/* Keys by profile: core's bare ("frame_ms", as it always was), the
 * others' prefixed ("compat_frame_ms", "es20_frame_ms"). */
static void print_baseline_json(const char *key, const profiles *pr, const double *base, const rounds_info *info)
{
    printf(" \"%s\": {", key);
    for (int prof = 0; prof < pr->n; prof++) {
        char prefix[16] = "", name[48];
        if (pr->gl[prof] != SKY_GL_CORE33) snprintf(prefix, sizeof prefix, "%s_", prof_name(pr, prof));
        printf("%s\"%sframe_ms\":%.4f, ", prof ? ", " : "", prefix, base[prof]);
        snprintf(name, sizeof name, "%srounds_ms", prefix);
        print_json_list(name, info[prof].base_ms, info[prof].n);
        printf(", ");
        snprintf(name, sizeof name, "%sothers_cpus", prefix);
        print_json_list(name, info[prof].others_cpus, info[prof].n);
    }
    printf("}");
}

/* ---- soak: resident memory over a long run -------------------------------------------- */

/* The reliability issue's soak: 320x180, the gradient path and the default
 * features, the time slider running a day per 1000 frames; resident memory
 * at checkpoints, for the sky updated only (the library's own CPU side)
 * and updated and drawn (with llvmpipe's caches), each in a fresh process
 * image as far as one can be: the update-only run first. */
static int soak_table(int frames, sky_gl_profile gl)
{
    static const int marks[] = {0, 1000, 2000, 5000, 10000, 20000, 50000};
    enum { MARKS = sizeof marks / sizeof marks[0] };
    long rss[2][MARKS];
    for (int draw = 0; draw < 2; draw++) {
        char err[256];
        sky_osmesa ctx;
        if (sky_osmesa_create(&ctx, 320, 180, gl, 0, err, sizeof err)) {
            fprintf(stderr, "sky-bench: %s\n", err);
            return 1;
        }
        bench_gl_use(&ctx);
        sky_config cfg;
        memset(&cfg, 0, sizeof cfg);
        cfg.get_proc_address = sky_headless_loader(&ctx);
        cfg.gl_profile = gl;
        sky *s = sky_create(&cfg, err, sizeof err);
        if (!s) {
            fprintf(stderr, "sky-bench: %s\n", err);
            return 1;
        }
        float view[16], proj[16];
        sky_cli_camera_at(180.0, 20.0, 60.0, 320, 180, view, proj);
        sky_params p = sky_default_params();
        int m = 0;
        for (int f = 0; f <= frames; f++) {
            while (m < MARKS && marks[m] == f) rss[draw][m++] = sky_rss_kib();
            p.time = (float)fmod(f / 1000.0, 1.0);
            sky_set_params(s, &p);
            sky_update(s, 1.0 / 60.0);
            if (draw) sky_draw(s, view, proj);
        }
        if (draw) glFinish();
        for (; m < MARKS; m++) rss[draw][m] = -1;
        sky_destroy(s);
        sky_osmesa_destroy(&ctx);
    }
    printf("Soak: %d frames at 320x180, %s, gradient path, default features, the time slider a day per 1000\n"
           "frames; resident memory of the process (MiB) at each frame count:\n\n| run |",
           frames, gl == SKY_GL_CORE33 ? "CORE33" : "COMPAT20");
    for (int m = 0; m < MARKS && marks[m] <= frames; m++) printf(" %d |", marks[m]);
    printf("\n|---|");
    for (int m = 0; m < MARKS && marks[m] <= frames; m++) printf("---|");
    printf("\n");
    static const char *const runs[2] = {"sky_set_params + sky_update", "the same + sky_draw"};
    for (int draw = 0; draw < 2; draw++) {
        printf("| %s |", runs[draw]);
        for (int m = 0; m < MARKS && marks[m] <= frames; m++) printf(" %.1f |", rss[draw][m] / 1024.0);
        printf("\n");
    }
    return 0;
}

/* ---- colour: the 8-bit output against the sky's own (tools/colour.c) ---------------- */

#define COLOUR_PATHS 5
#define COLOUR_ROWS (COLOUR_PATHS * SKY_COLOUR_SUNS * 2)
static const char *const colour_path_names[COLOUR_PATHS] = {"gradient", "preetham", "rayleigh", "hillaire", "blend"};
static const sky_atmosphere_path colour_paths[COLOUR_PATHS] = {
    SKY_ATMOSPHERE_GRADIENT, SKY_ATMOSPHERE_PREETHAM, SKY_ATMOSPHERE_RAYLEIGH, SKY_ATMOSPHERE_HILLAIRE,
    SKY_ATMOSPHERE_BLEND};
static const char *const tone_map_names[3] = {"hue", "filmic", "neutral"};

/* Every path, sun height and view at 480x270, core profile. */
static int colour_rows(sky_tone_map tm, sky_colour_row *rows)
{
    char err[256];
    int n = 0;
    for (int p = 0; p < COLOUR_PATHS; p++)
        for (int k = 0; k < SKY_COLOUR_SUNS; k++)
            for (int toward = 1; toward >= 0; toward--)
                if (sky_colour_measure(colour_paths[p], tm, SKY_GL_AUTO, sky_colour_suns[k], toward, 480, 270,
                                       &rows[n++], err, sizeof err)) {
                    fprintf(stderr, "sky-bench: colour: %s\n", err);
                    return -1;
                }
    return 0;
}

static const char *colour_path_name(sky_atmosphere_path path)
{
    for (int p = 0; p < COLOUR_PATHS; p++)
        if (colour_paths[p] == path) return colour_path_names[p];
    return "?";
}

static void print_colour_table(const sky_colour_row *rows, int n)
{
    printf("| path | sun deg | view | pixels | saturation kept, median | p10 | hue shift deg, median | p90 | "
           "clipped %% | ground under sun / elsewhere | twilight ground / sky | targets |\n"
           "|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    int met = 0;
    for (int i = 0; i < n; i++) {
        const sky_colour_row *r = &rows[i];
        char why[128], pillar[16] = "-", ground[16] = "-";
        int ok = sky_colour_row_ok(r, why, sizeof why);
        met += ok;
        if (r->pillar >= 0.0) snprintf(pillar, sizeof pillar, "%.3f", r->pillar);
        if (r->ground_to_sky >= 0.0) snprintf(ground, sizeof ground, "%.3f", r->ground_to_sky);
        if (r->counted > 0)
            printf("| %s | %g | %s | %d | %.2f | %.2f | %.1f | %.1f | %.2f | %s | %s | %s |\n", colour_path_name(r->path),
                   r->sun_deg, r->toward ? "toward" : "away", r->counted, r->saturation_kept_median,
                   r->saturation_kept_p10, r->hue_shift_median, r->hue_shift_p90, 100.0 * r->clipped, pillar, ground,
                   ok ? "met" : why);
        else
            printf("| %s | %g | %s | 0 | - | - | - | - | %.2f | %s | %s | %s |\n", colour_path_name(r->path), r->sun_deg,
                   r->toward ? "toward" : "away", 100.0 * r->clipped, pillar, ground, ok ? "met" : why);
    }
    printf("\nTargets met in %d of %d rows. Pixels: sky pixels more than 3 degrees from the sun with a linear\n"
           "saturation above 0.15 and an 8-bit value (largest channel) of at least 25, at 480x270, 40 N 0 E on\n"
           "2026-06-21 (an evening sun), 60-degree field, facing the sun at pitch 8 or away at pitch 20. Targets\n"
           "(sun -4..60): hue shift median <= 3, p90 <= 8 degrees; saturation kept median >= 0.85, p10 >= 0.6;\n"
           "clipped <= 1 %% of the sky; the ground under a 0-8 degree sun <= 1.05x the ground elsewhere; the\n"
           "ground under a sun below the horizon >= 0.05 of the sky (HDR).\n",
           met, n);
}

/* The day's end (issue "Dusk and night"): the default path and
 * Hillaire's, the sky's display brightness over noon's as the sun sets. */
#define DUSK_PATHS 2
static const sky_atmosphere_path dusk_paths[DUSK_PATHS] = {SKY_ATMOSPHERE_GRADIENT, SKY_ATMOSPHERE_HILLAIRE};

/* and the night's two views on the same paths, [path][full moon] */
typedef struct night_rows {
    double rel[DUSK_PATHS][SKY_DUSK_SUNS];
    double noon[DUSK_PATHS];
    sky_night_view view[DUSK_PATHS][2];
    double moon_hue[DUSK_PATHS][2]; /* the full moon's disc: HDR, 8-bit */
} night_rows;

static int dusk_rows(night_rows *n)
{
    char err[256];
    for (int p = 0; p < DUSK_PATHS; p++) {
        if (sky_dusk_measure(dusk_paths[p], SKY_GL_AUTO, 480, 270, n->rel[p], err, sizeof err) ||
            sky_dusk_brightness(dusk_paths[p], SKY_GL_AUTO, 50.0, 480, 270, &n->noon[p], err, sizeof err)) {
            fprintf(stderr, "sky-bench: day's end: %s\n", err);
            return -1;
        }
        for (int m = 0; m < 2; m++)
            if (sky_night_measure(dusk_paths[p], SKY_GL_AUTO, m, 480, 270, &n->view[p][m], err, sizeof err)) {
                fprintf(stderr, "sky-bench: the night: %s\n", err);
                return -1;
            }
        if (sky_moon_disc_hues(dusk_paths[p], SKY_GL_AUTO, 160, 160, &n->moon_hue[p][0], &n->moon_hue[p][1], err,
                               sizeof err)) {
            fprintf(stderr, "sky-bench: the moon's disc: %s\n", err);
            return -1;
        }
    }
    return 0;
}

static void print_dusk_table(const night_rows *n)
{
    printf("| path |");
    for (int i = 0; i < SKY_DUSK_SUNS; i++) printf(i ? " %g |" : " noon (%g) |", sky_dusk_suns[i]);
    printf(" targets |\n|---|");
    for (int i = 0; i <= SKY_DUSK_SUNS; i++) printf("---|");
    printf("\n");
    for (int p = 0; p < DUSK_PATHS; p++) {
        char why[128];
        int ok = sky_dusk_ok(n->rel[p], why, sizeof why);
        printf("| %s |", colour_path_name(dusk_paths[p]));
        for (int i = 0; i < SKY_DUSK_SUNS; i++) printf(" %.3f |", n->rel[p][i]);
        printf(" %s |\n", ok ? "met" : why);
    }
    printf("\nThe mean display luminance (8-bit sRGB decoded to linear) of the sky more than 5 degrees up over\n"
           "noon's, averaged over a view toward the sun (pitch 10) and one away (pitch 20), 60-degree field,\n"
           "480x270, the default features with the clouds off, 40 N 0 E on 2026-03-20 (noon: the sun at 50),\n"
           "the sun at each height in the evening. Targets: <= 0.5 at -6, <= 0.2 at -12, <= 0.1 at -18; from\n"
           "4 degrees down no step more than 5 %% brighter than the one before; sunset (0) <= noon.\n");
    printf("\n| path | night | median sRGB | hue | b/r | mean / noon | targets |\n|---|---|---|---|---|---|---|\n");
    for (int p = 0; p < DUSK_PATHS; p++)
        for (int m = 1; m >= 0; m--) {
            const sky_night_view *v = &n->view[p][m];
            char why[128];
            int ok = sky_night_ok(v, m, n->noon[p], why, sizeof why);
            printf("| %s | %s | (%d, %d, %d) | %.0f | %.2f | %.3f | %s |\n", colour_path_name(dusk_paths[p]),
                   m ? "full moon" : "moonless", v->median[0], v->median[1], v->median[2], v->hue, v->b_over_r,
                   v->mean / n->noon[p], ok ? "met" : why);
        }
    printf("\nThe sky more than 10 degrees up in a 60-degree view, 480x270, the default features and the moon,\n"
           "clouds off: the full moon 67 degrees up (2024-01-26 00:00 UTC, 45 N 0 E, north at pitch 30) and a\n"
           "moonless sky (2024-01-11 22:00 UTC, 45 N 10 E, south at pitch 30). Targets: the full moon hue\n"
           "190-250, b/r >= 1.6, the brightest channel's median >= 40, <= 0.35 of noon; the moonless sky hue\n"
           "190-260, b/r >= 1.2, the brightest channel's median 8-40.\n");
    printf("\n");
    for (int p = 0; p < DUSK_PATHS; p++) {
        double shift = fabs(remainder(n->moon_hue[p][1] - n->moon_hue[p][0], 360.0));
        printf("%s: the full moon's disc, hue %.1f in HDR and %.1f in the 8-bit frame (target: within 12 degrees, %s)\n",
               colour_path_name(dusk_paths[p]), n->moon_hue[p][0], n->moon_hue[p][1], shift <= 12.0 ? "met" : "not met");
    }
}

static void print_dusk_json(const night_rows *n)
{
    printf(" \"day_end\": [\n");
    for (int p = 0; p < DUSK_PATHS; p++) {
        char why[128];
        int ok = sky_dusk_ok(n->rel[p], why, sizeof why);
        printf("  {\"path\":\"%s\", \"sun_deg\":[", colour_path_name(dusk_paths[p]));
        for (int i = 0; i < SKY_DUSK_SUNS; i++) printf("%g%s", sky_dusk_suns[i], i + 1 < SKY_DUSK_SUNS ? "," : "");
        printf("], \"over_noon\":[");
        for (int i = 0; i < SKY_DUSK_SUNS; i++) printf("%.4f%s", n->rel[p][i], i + 1 < SKY_DUSK_SUNS ? "," : "");
        printf("], \"targets_met\":%s}%s\n", ok ? "true" : "false", p + 1 < DUSK_PATHS ? "," : "");
    }
    printf(" ],\n \"night\": [\n");
    for (int p = 0; p < DUSK_PATHS; p++)
        for (int m = 1; m >= 0; m--) {
            const sky_night_view *v = &n->view[p][m];
            char why[128];
            int ok = sky_night_ok(v, m, n->noon[p], why, sizeof why);
            printf("  {\"path\":\"%s\", \"night\":\"%s\", \"median\":[%d,%d,%d], \"hue\":%.1f, \"b_over_r\":%.3f, "
                   "\"mean_over_noon\":%.4f, \"moon_disc_hue\":[%.1f,%.1f], \"targets_met\":%s}%s\n",
                   colour_path_name(dusk_paths[p]), m ? "full_moon" : "moonless", v->median[0], v->median[1],
                   v->median[2], v->hue, v->b_over_r, v->mean / n->noon[p], m ? n->moon_hue[p][0] : -1.0,
                   m ? n->moon_hue[p][1] : -1.0, ok ? "true" : "false", p + 1 < DUSK_PATHS || m ? "," : "");
        }
    printf(" ]");
}

static void print_colour_json(sky_tone_map tm, const sky_colour_row *rows, int n)
{
    printf(" \"colour\": {\"tone_map\":\"%s\", \"rows\": [\n", tone_map_names[tm]);
    for (int i = 0; i < n; i++) {
        const sky_colour_row *r = &rows[i];
        char why[128];
        int ok = sky_colour_row_ok(r, why, sizeof why);
        printf("  {\"path\":\"%s\", \"sun_deg\":%g, \"view\":\"%s\", \"pixels\":%d, \"saturation_kept_median\":%.4f, "
               "\"saturation_kept_p10\":%.4f, \"hue_shift_median\":%.3f, \"hue_shift_p90\":%.3f, \"clipped\":%.5f, "
               "\"pillar\":%.4f, \"twilight_ground_to_sky\":%.4f, \"targets_met\":%s}%s\n",
               colour_path_name(r->path), r->sun_deg, r->toward ? "toward" : "away", r->counted,
               r->saturation_kept_median, r->saturation_kept_p10, r->hue_shift_median, r->hue_shift_p90, r->clipped,
               r->pillar, r->ground_to_sky, ok ? "true" : "false", i + 1 < n ? "," : "");
    }
    printf(" ]}");
}

/* ---- photometry ------------------------------------------------------------------------------ */

/* The atmosphere paths whose photometry sky-bench prints (core profile). */
#define PHOT_PATHS 5
static const sky_atmosphere_path phot_paths[PHOT_PATHS] = {SKY_ATMOSPHERE_GRADIENT, SKY_ATMOSPHERE_PREETHAM,
                                                           SKY_ATMOSPHERE_RAYLEIGH, SKY_ATMOSPHERE_HILLAIRE,
                                                           SKY_ATMOSPHERE_BLEND};
static const char *const phot_names[PHOT_PATHS] = {"gradient", "preetham", "rayleigh", "hillaire", "blend"};

static int photometry_rows(sky_photometry out[PHOT_PATHS])
{
    for (int p = 0; p < PHOT_PATHS; p++) {
        char err[512];
        sky_config cfg = sky_photometry_config(phot_paths[p]);
        if (sky_photometry_measure(&cfg, &out[p], err, sizeof err)) {
            fprintf(stderr, "sky-bench: photometry of %s: %s\n", phot_names[p], err);
            return -1;
        }
    }
    return 0;
}

/* One row of the photometry table: a quantity, the published figure, and
 * each path's, printed with fmt. */
static void phot_row(const char *quantity, const char *published, const char *fmt, const sky_photometry *m,
                     size_t offset)
{
    printf("| %s | %s |", quantity, published);
    for (int p = 0; p < PHOT_PATHS; p++) {
        printf(" ");
        printf(fmt, *(const double *)((const char *)&m[p] + offset));
        printf(" |");
    }
    printf("\n");
}

static void print_photometry_table(const sky_photometry m[PHOT_PATHS])
{
    sky_photometry pub;
    sky_photometry_published(&pub);
    char buf[64];
    printf("| quantity | published |");
    for (int p = 0; p < PHOT_PATHS; p++) printf(" %s |", phot_names[p]);
    printf("\n|---|---|");
    for (int p = 0; p < PHOT_PATHS; p++) printf("---|");
    printf("\n| sky shape vs CIE clear sky (closest of types 11-13; median deviation, sun 10/30/50/70 deg) | - |");
    for (int p = 0; p < PHOT_PATHS; p++)
        printf(" %.0f / %.0f / %.0f / %.0f %% |", 100.0 * m[p].cie_median[0], 100.0 * m[p].cie_median[1],
               100.0 * m[p].cie_median[2], 100.0 * m[p].cie_median[3]);
    printf("\n");
    snprintf(buf, sizeof buf, "CIE 12: %.1f", pub.glow_ratio_30);
    phot_row("glow 5-8 deg around the sun, L/Lz, sun 30 deg", buf, "%.2f", m, offsetof(sky_photometry, glow_ratio_30));
    snprintf(buf, sizeof buf, "CIE 12: %.2f", pub.horizon_ratio_70);
    phot_row("horizon 80-85 deg opposite the sun, L/Lz, sun 70 deg", buf, "%.2f", m,
             offsetof(sky_photometry, horizon_ratio_70));
    snprintf(buf, sizeof buf, "gensky T 2.75: %.1f", pub.zenith_kcd_70);
    phot_row("zenith luminance, sun 70 deg, kcd/m^2", buf, "%.2f", m, offsetof(sky_photometry, zenith_kcd_70));
    snprintf(buf, sizeof buf, "IES: %.1f", pub.diffuse_klx_30);
    phot_row("diffuse horizontal illuminance, sun 30 deg, klx", buf, "%.1f", m, offsetof(sky_photometry, diffuse_klx_30));
    snprintf(buf, sizeof buf, "IES: %.0f", pub.direct_klx_10);
    phot_row("direct normal illuminance, sun 10 deg, klx", buf, "%.0f", m, offsetof(sky_photometry, direct_klx_10));
    phot_row("sky illuminance, sun -6 deg (civil twilight), lx", "Bond & Henderson: 3.4", "%.3g", m,
             offsetof(sky_photometry, civil_lx));
    phot_row("sky illuminance, sun -12 deg (nautical), lx", "Bond & Henderson: 0.008", "%.3g", m,
             offsetof(sky_photometry, nautical_lx));
    phot_row("night zenith, sun -30 deg, no moon, mag/arcsec^2", "Garstang; Benn & Ellison: 21.5-22", "%.1f", m,
             offsetof(sky_photometry, night_zenith_mag));
}

static void print_photometry_json(const sky_photometry m[PHOT_PATHS])
{
    sky_photometry pub;
    sky_photometry_published(&pub);
    printf(" \"photometry\": [\n");
    for (int p = 0; p <= PHOT_PATHS; p++) {
        const sky_photometry *r = p < PHOT_PATHS ? &m[p] : &pub;
        printf("  {\"path\":\"%s\", \"cie_median\":[%.4f,%.4f,%.4f,%.4f], \"cie_type\":[%d,%d,%d,%d], "
               "\"glow_ratio_30\":%.4f, \"horizon_ratio_70\":%.4f, \"zenith_kcd_70\":%.4f, \"diffuse_klx_30\":%.4f, "
               "\"direct_klx_10\":%.4f, \"civil_lx\":%.5g, \"nautical_lx\":%.5g, \"night_zenith_mag\":%.3f}%s\n",
               p < PHOT_PATHS ? phot_names[p] : "published", r->cie_median[0], r->cie_median[1], r->cie_median[2],
               r->cie_median[3], r->cie_type[0], r->cie_type[1], r->cie_type[2], r->cie_type[3], r->glow_ratio_30,
               r->horizon_ratio_70, r->zenith_kcd_70, r->diffuse_klx_30, r->direct_klx_10, r->civil_lx, r->nautical_lx,
               r->night_zenith_mag, p < PHOT_PATHS ? "," : "");
    }
    printf(" ]");
}

/* The chart of the sky's horizontal illuminance by sun altitude, every
 * path against the published: the IES clear sky by day, Bond & Henderson
 * in twilight. */
static int plot_photometry(const char *path)
{
    enum { ALTS = 37 };
    double alts[ALTS], lux[PHOT_PATHS][ALTS];
    for (int i = 0; i < ALTS; i++) alts[i] = -18.0 + 3.0 * i;
    plot_curve cv[PHOT_PATHS + 2];
    for (int p = 0; p < PHOT_PATHS; p++) {
        char err[512];
        sky_config cfg = sky_photometry_config(phot_paths[p]);
        if (sky_photometry_sky_lux(&cfg, alts, ALTS, lux[p], err, sizeof err)) {
            fprintf(stderr, "sky-bench: photometry of %s: %s\n", phot_names[p], err);
            return -1;
        }
        cv[p] = (plot_curve){alts, lux[p], ALTS, p, 0};
    }
    enum { DAY = 31 };
    double day_alt[DAY], day_lux[DAY];
    for (int i = 0; i < DAY; i++) day_alt[i] = 3.0 * i, day_lux[i] = 1000.0 * sky_ies_diffuse_klx(day_alt[i]);
    static const double tw_alt[2] = {-6.0, -12.0}, tw_lux[2] = {3.4, 0.008};
    cv[PHOT_PATHS] = (plot_curve){day_alt, day_lux, DAY, PHOT_PATHS, 0};
    cv[PHOT_PATHS + 1] = (plot_curve){tw_alt, tw_lux, 2, PHOT_PATHS, 1};
    static const char *const legend[PHOT_PATHS + 1] = {"gradient", "preetham", "rayleigh", "hillaire", "blend",
                                                       "IES, B.+H."};
    if (plot_curves(path, cv, PHOT_PATHS + 2, legend, PHOT_PATHS + 1, -18.0, 90.0, 18.0, "sun altitude, degrees",
                    "lx", "sky illuminance on a horizontal surface")) {
        fprintf(stderr, "sky-bench: cannot write %s\n", path);
        return -1;
    }
    return 0;
}

/* ---- scene lighting ---------------------------------------------------------------- */

/* sky_get_irradiance_sh for every path: what one projection costs (the
 * median over calls that each follow a move of the sun, the move itself
 * not timed), what a call costs when nothing moved (the cache), and how far
 * its irradiance is from a brute-force integral of the same sky rendered
 * in HDR into a cube (upward, horizontal and downward normals; sun 30, 2
 * and -20 deg), with all its coefficients and with the 9 of degree <= 2
 * alone (what a shader reading only those gets).
 * And aerial perspective: a sky_get_aerial_perspective call (a level view
 * 5 km long), its first call on the path (the tables the paths without
 * Hillaire's build then), the shader's table remade by sky_aerial_bind
 * after the sun moved (CPU build and upload), and Hillaire's froxel
 * volume built for a camera (GPU, with glFinish; -1 where there is
 * none); medians. */
typedef struct lighting_row {
    double project_us, cached_us, worst, worst9;
    double aerial_first_ms, aerial_call_us, aerial_table_ms, froxels_ms;
} lighting_row;

static int lighting_rows(lighting_row out[PHOT_PATHS])
{
    enum { CALLS = 41 };
    for (int p = 0; p < PHOT_PATHS; p++) {
        char err[512];
        sky_config cfg = sky_photometry_config(phot_paths[p]);
        sky_atmo_hemisphere *h = sky_atmo_hemisphere_create(&cfg, err, sizeof err);
        if (!h) {
            fprintf(stderr, "sky-bench: lighting of %s: %s\n", phot_names[p], err);
            return -1;
        }
        /* the host program below is compiled in the hemisphere's context
         * (--only-lighting has made no other) */
        bench_gl_use(sky_atmo_hemisphere_context(h));
        lighting_row *r = &out[p];
        r->worst = r->worst9 = 0.0;
        static const double suns[3] = {30.0, 2.0, -20.0}, normals[3][3] = {{0, 1, 0}, {1, 0, 0}, {0, -1, 0}};
        for (int k = 0; k < 3; k++) {
            double el, az;
            if (sky_atmo_hemisphere_render(h, suns[k], &el, &az, err, sizeof err)) {
                fprintf(stderr, "sky-bench: lighting of %s: %s\n", phot_names[p], err);
                sky_atmo_hemisphere_destroy(h);
                return -1;
            }
            for (int n = 0; n < 3; n++) {
                double ly, ls, l9;
                sky_atmo_hemisphere_sh_check(h, normals[n], &ly, &ls, &l9);
                r->worst = fmax(r->worst, fabs(ls / ly - 1.0));
                r->worst9 = fmax(r->worst9, fabs(l9 / ly - 1.0));
            }
        }
        /* the cost, the sun at 30 deg moving by 1/7200 of a day a call */
        sky *s = sky_atmo_hemisphere_sky(h);
        static const float level[3] = {0.6f, 0.0f, -0.8f};
        sky_aerial air;
        double t0 = sky_cli_now_ms();
        sky_get_aerial_perspective(s, level, 5000.0f, &air);
        r->aerial_first_ms = sky_cli_now_ms() - t0;
        /* a host program that reads the table */
        const char *vs[1] = {"#version 330 core\nin vec4 p;\nvoid main() { gl_Position = p; }\n"};
        const char *fs[3] = {"#version 330 core\nout vec4 c;\n", sky_aerial_glsl(),
                             "void main() { c = vec4(sky_aerial_apply(vec3(1.0), vec3(1.0, 0.1, 0.0), 1e4), 1.0); }\n"};
        const char *attribs[1] = {"p"};
        GLuint host = program(vs, 1, fs, 3, attribs, 1);
        sky_params prm;
        sky_get_params(s, &prm);
        double project[CALLS], cached[CALLS], call[CALLS], table[CALLS], froxels[CALLS];
        float view[16], proj[16];
        sky_cli_camera_at(180.0, 10.0, 60.0, 1280, 720, view, proj);
        unsigned volume = 0;
        int has_froxels = sky_aerial_froxels(s, view, proj, &volume) == SKY_OK;
        sky_irradiance_sh sh;
        for (int i = 0; i < CALLS; i++) {
            prm.time += 1.0f / 7200.0f;
            sky_set_params(s, &prm);
            double t1 = sky_cli_now_ms();
            sky_get_irradiance_sh(s, &sh);
            double t2 = sky_cli_now_ms();
            sky_get_irradiance_sh(s, &sh);
            double t3 = sky_cli_now_ms();
            sky_get_aerial_perspective(s, level, 5000.0f, &air);
            double t4 = sky_cli_now_ms();
            if (host) sky_aerial_bind(s, host, 1);
            glFinish();
            double t5 = sky_cli_now_ms();
            project[i] = (t2 - t1) * 1000.0;
            cached[i] = (t3 - t2) * 1000.0;
            call[i] = (t4 - t3) * 1000.0;
            table[i] = t5 - t4;
            if (has_froxels) sky_aerial_froxels(s, view, proj, &volume);
            glFinish();
            froxels[i] = sky_cli_now_ms() - t5;
        }
        if (host) glDeleteProgram(host);
        r->project_us = sky_cli_median(project, CALLS);
        r->cached_us = sky_cli_median(cached, CALLS);
        r->aerial_call_us = sky_cli_median(call, CALLS);
        r->aerial_table_ms = host ? sky_cli_median(table, CALLS) : -1.0;
        r->froxels_ms = has_froxels ? sky_cli_median(froxels, CALLS) : -1.0;
        sky_atmo_hemisphere_destroy(h);
    }
    return 0;
}

/* sky_capture_environment's cost against a frame: the noon preset (the
 * default gradient sky with clouds, core profile), a w x h frame drawn
 * and finished, against all six 128 x 128 faces and one face captured and
 * finished; medians of n. */
typedef struct capture_cost {
    double frame_ms, all_ms, one_ms;
    double shadow_ms; /* sky_get_cloud_shadow (64 x 64, made and uploaded) under fair weather */
} capture_cost;

static int capture_costs(int w, int h, int n, capture_cost *out)
{
    char err[512];
    sky_osmesa ctx;
    if (sky_osmesa_create(&ctx, w, h, SKY_GL_CORE33, 0, err, sizeof err)) {
        fprintf(stderr, "sky-bench: capture: %s\n", err);
        return -1;
    }
    bench_gl_use(&ctx);
    sky_cli cli;
    char *argv[] = {"sky-bench", "--preset", "noon", NULL};
    if (sky_cli_parse(&cli, 3, argv, 0, err, sizeof err)) {
        fprintf(stderr, "sky-bench: capture: %s\n", err);
        sky_osmesa_destroy(&ctx);
        return -1;
    }
    sky_config cfg = sky_cli_config(&cli, sky_headless_loader(&ctx));
    sky *s = sky_create(&cfg, err, sizeof err);
    if (!s) {
        fprintf(stderr, "sky-bench: capture: %s\n", err);
        sky_osmesa_destroy(&ctx);
        return -1;
    }
    sky_set_params(s, &cli.params);
    float view[16], proj[16];
    sky_cli_camera(&cli, view, proj);
    double *t[3];
    for (int k = 0; k < 3; k++) t[k] = malloc(sizeof(double) * (size_t)n);
    int rc = t[0] && t[1] && t[2] ? 0 : -1;
    /* the first of each: programs built and the cube map made */
    sky_draw(s, view, proj);
    sky_capture_environment(s, 0, 128, SKY_CAPTURE_ALL_FACES, 0);
    sky_osmesa_finish(&ctx);
    for (int i = 0; i < n && !rc; i++) {
        double t0 = sky_cli_now_ms();
        sky_draw(s, view, proj);
        sky_osmesa_finish(&ctx);
        double t1 = sky_cli_now_ms();
        rc |= sky_capture_environment(s, 0, 128, SKY_CAPTURE_ALL_FACES, 0) < 0;
        sky_osmesa_finish(&ctx);
        double t2 = sky_cli_now_ms();
        rc |= sky_capture_environment(s, 0, 128, i % 6, 0) < 0;
        sky_osmesa_finish(&ctx);
        double t3 = sky_cli_now_ms();
        t[0][i] = t1 - t0;
        t[1][i] = t2 - t1;
        t[2][i] = t3 - t2;
    }
    if (rc) fprintf(stderr, "sky-bench: capture: %s\n", sky_last_error(s));
    else {
        out->frame_ms = sky_cli_median(t[0], n);
        out->all_ms = sky_cli_median(t[1], n);
        out->one_ms = sky_cli_median(t[2], n);
        /* the cloud shadow map a host asks for each frame: fair weather's
         * broken clouds, the clock moving between calls */
        sky_weather fair;
        sky_weather_preset(SKY_WEATHER_FAIR, &fair);
        sky_set_weather(s, &fair, 0.0);
        sky_cloud_shadow map;
        for (int i = 0; i < n && !rc; i++) {
            sky_update(s, 1.0 / 60.0);
            double t0 = sky_cli_now_ms();
            rc |= sky_get_cloud_shadow(s, 1.0f, 10000.0f, &map) < 0;
            sky_osmesa_finish(&ctx);
            t[0][i] = sky_cli_now_ms() - t0;
        }
        if (rc) fprintf(stderr, "sky-bench: cloud shadow: %s\n", sky_last_error(s));
        out->shadow_ms = sky_cli_median(t[0], n);
    }
    for (int k = 0; k < 3; k++) free(t[k]);
    sky_destroy(s);
    sky_osmesa_destroy(&ctx);
    return rc;
}

static void print_lighting_table(const lighting_row r[PHOT_PATHS])
{
    printf("| path | SH projection us (the sun moved) | cached call us | worst irradiance error, all coefficients | "
           "the 9 of degree <= 2 alone |\n|---|---|---|---|---|\n");
    for (int p = 0; p < PHOT_PATHS; p++)
        printf("| %s | %.1f | %.3f | %.1f %% | %.1f %% |\n", phot_names[p], r[p].project_us, r[p].cached_us,
               100.0 * r[p].worst, 100.0 * r[p].worst9);
    printf("\nAerial perspective (core profile; the sun moving as above):\n\n"
           "| path | first call ms (tables made) | sky_get_aerial_perspective us | shader table remade ms | "
           "froxel volume ms |\n|---|---|---|---|---|\n");
    for (int p = 0; p < PHOT_PATHS; p++) {
        char froxels[32] = "-";
        if (r[p].froxels_ms >= 0.0) snprintf(froxels, sizeof froxels, "%.2f", r[p].froxels_ms);
        printf("| %s | %.1f | %.1f | %.2f | %s |\n", phot_names[p], r[p].aerial_first_ms, r[p].aerial_call_us,
               r[p].aerial_table_ms, froxels);
    }
}

static void print_capture(const capture_cost *c, int w, int h)
{
    printf("\nsky_capture_environment, the noon preset, 128 x 128 faces, against a %dx%d frame (core, GPU time\n"
           "with glFinish, medians):\n\n| what | ms | x a frame |\n|---|---|---|\n| a frame | %.2f | 1.00 |\n"
           "| six faces | %.2f | %.2f |\n| one face | %.2f | %.2f |\n"
           "| sky_get_cloud_shadow, 64 x 64 (fair weather) | %.3f | %.3f |\n",
           w, h, c->frame_ms, c->all_ms, c->all_ms / c->frame_ms, c->one_ms, c->one_ms / c->frame_ms, c->shadow_ms,
           c->shadow_ms / c->frame_ms);
}

static void print_lighting_json(const lighting_row r[PHOT_PATHS], const capture_cost *c, int w, int h)
{
    printf(" \"capture\": {\"frame_size\":\"%dx%d\", \"frame_ms\":%.3f, \"six_faces_128_ms\":%.3f, "
           "\"one_face_128_ms\":%.3f, \"cloud_shadow_ms\":%.4f},\n",
           w, h, c->frame_ms, c->all_ms, c->one_ms, c->shadow_ms);
    printf(" \"lighting\": [\n");
    for (int p = 0; p < PHOT_PATHS; p++)
        printf("  {\"path\":\"%s\", \"sh_project_us\":%.2f, \"sh_cached_us\":%.3f, \"sh_worst_error\":%.4f, "
               "\"sh9_worst_error\":%.4f, \"aerial_first_ms\":%.2f, \"aerial_call_us\":%.2f, "
               "\"aerial_table_ms\":%.3f, \"froxels_ms\":%.3f}%s\n",
               phot_names[p], r[p].project_us, r[p].cached_us, r[p].worst, r[p].worst9, r[p].aerial_first_ms,
               r[p].aerial_call_us, r[p].aerial_table_ms, r[p].froxels_ms, p + 1 < PHOT_PATHS ? "," : "");
    printf(" ]");
}

/* --gl: a comma list of core, compat and es20, each once. Returns 0 or -1. */
static int parse_profiles(const char *list, profiles *pr)
{
    profiles p = {0, {SKY_GL_AUTO}};
    char buf[64];
    snprintf(buf, sizeof buf, "%s", list);
    for (char *save = NULL, *w = strtok_r(buf, ",", &save); w; w = strtok_r(NULL, ",", &save)) {
        sky_gl_profile gl = !strcmp(w, "core") ? SKY_GL_CORE33 : !strcmp(w, "compat") ? SKY_GL_COMPAT20
                            : !strcmp(w, "es20") ? SKY_GL_ES20 : SKY_GL_AUTO;
        if (gl == SKY_GL_AUTO || p.n == MAX_PROFS) return -1;
        for (int i = 0; i < p.n; i++)
            if (p.gl[i] == gl) return -1;
        p.gl[p.n++] = gl;
    }
    if (!p.n) return -1;
    *pr = p;
    return 0;
}

static void bench_usage(FILE *out)
{
    fprintf(out,
            "usage: sky-bench [--json | --markdown] [--size WxH] [--frames N>=3] [--rounds 1..%d] [--reference FILE] "
            "[--only-atmosphere | --only-presets | --only-colour | --only-photometry | --only-lighting\n"
            "       | --only-night | --only-weather] [--gl LIST of core,compat,es20 (default core,compat; es20 with --only-presets\n"
            "       or --only-night or --only-sharpness)] [--only-sharpness] [--presets 'ROW;ROW...' (with --only-presets: these rows, each a preset and\n"
            "       sky-render's options, in place of the table's)]\n"
            "       [--tone-map hue|filmic|neutral] [--plot FILE.png] [--plot-photometry FILE.png]\n"
            "       sky-bench --stability [--json | --markdown]\n"
            "       (--markdown: the report as a Markdown page with a header naming the command, machine and\n"
            "       renderer; docs/benchmarks.md is `sky-bench --markdown`)\n"
            "       sky-bench --soak FRAMES (1000..50000: resident memory over a long run)\n"
            "       sky-bench --make-reference FILE [--paths N]\n",
            MAX_ROUNDS);
}

/* ---- sharpness: the default frame against the every-pixel frame ----------------------------- */

/* The presets' own cameras; each at both sizes in every profile asked. */
static const char *const sharp_presets[] = {"noon", "sunset", "overcast", "minimal", "starry", "moonlit"};
static const int sharp_sizes[][2] = {{1280, 720}, {1920, 1080}};
enum { SHARP_PRESETS = sizeof sharp_presets / sizeof sharp_presets[0],
       SHARP_SIZES = sizeof sharp_sizes / sizeof sharp_sizes[0] };

typedef struct sharp_row {
    const char *preset;
    sky_gl_profile gl;
    int w, h;
    sky_sharpness m;
} sharp_row;

/* Fills rows (SHARP_PRESETS x SHARP_SIZES per profile); returns how many,
 * or -1. */
static int sharpness_rows(const profiles *pr, sharp_row *rows)
{
    int n = 0;
    char err[512];
    for (int p = 0; p < pr->n; p++)
        for (int z = 0; z < SHARP_SIZES; z++)
            for (int i = 0; i < SHARP_PRESETS; i++, n++) {
                sharp_row *r = &rows[n];
                r->preset = sharp_presets[i];
                r->gl = pr->gl[p];
                r->w = sharp_sizes[z][0];
                r->h = sharp_sizes[z][1];
                if (sky_sharpness_measure(r->preset, NULL, r->gl, r->w, r->h, &r->m, err, sizeof err)) {
                    fprintf(stderr, "sky-bench: sharpness of %s: %s\n", r->preset, err);
                    return -1;
                }
            }
    return n;
}

static void print_sharpness_table(const sharp_row *rows, int n)
{
    printf("\nSharpness: each preset's own camera, the default frame against the every-pixel frame\n"
           "(--dome-divisor 1). Fine structure: the standard deviation of luminance (Rec. 709 weights on the\n"
           "8-bit sRGB values) minus its box blur of side 2k, over the sky rows (0-459 of 720); kept: the\n"
           "default frame's over the every-pixel frame's; PSNR over the whole frame.\n\n");
    printf("| preset | profile | size | kept, k = 2 px | kept, k = 5 px | PSNR dB |\n|---|---|---|---|---|---|\n");
    for (int i = 0; i < n; i++)
        printf("| %s | %s | %dx%d | %.3f | %.3f | %.1f |\n", rows[i].preset, kind_names[kind_of(rows[i].gl)],
               rows[i].w, rows[i].h, rows[i].m.kept2, rows[i].m.kept5, rows[i].m.psnr);
}

static void print_sharpness_json(const sharp_row *rows, int n)
{
    printf(" \"sharpness\": [\n");
    for (int i = 0; i < n; i++)
        printf("  {\"preset\":\"%s\", \"profile\":\"%s\", \"size\":\"%dx%d\", \"kept_k2\":%.4f, \"kept_k5\":%.4f, "
               "\"psnr_db\":%.2f}%s\n",
               rows[i].preset, kind_names[kind_of(rows[i].gl)], rows[i].w, rows[i].h, rows[i].m.kept2, rows[i].m.kept5,
               isfinite(rows[i].m.psnr) ? rows[i].m.psnr : 999.0, i + 1 < n ? "," : "");
    printf(" ]");
}

/* The night layers' table (bench_night), against the presets' baseline. */
static void print_night_table(const profiles *pr, double night[MAX_PROFS][NIGHT_COUNT], const double *base)
{
    printf("\nThe night layers: the stars', the planets' and the moon's own draw (GPU time around it), the star\n"
           "map, the airglow and the zodiacal light as what each adds to an atmosphere-only night frame (measured\n"
           "once, not in rounds):\n\n");
    printf("| layer | profile | ms | x baseline |\n|---|---|---|---|\n");
    static const char *names[NIGHT_COUNT] = {"", "the 8874 stars' draw, looking south", "star map",
                                             "5 planets, Saturn in view", "airglow",
                                             "zodiacal light", "", "moon, c_d 3", "moon, c_d 30"};
    /* -1: measured directly, else the frame it is the difference from */
    static const int from[NIGHT_COUNT] = {0, -1, NIGHT_NONE, -1, NIGHT_NONE, NIGHT_NONE, 0, -1, -1};
    for (int prof = 0; prof < pr->n; prof++)
        for (int k = 0; k < NIGHT_COUNT; k++) {
            if (!names[k][0]) continue;
            double ms = from[k] < 0 ? night[prof][k] : night[prof][k] - night[prof][from[k]];
            printf("| %s | %s | %.2f | %.2f |\n", names[k], prof_name(pr, prof), ms, ms / base[prof]);
        }
}

/* ---- --markdown: the header ---------------------------------------------------------------- */

/* The first line of a command's output, without its newline, or "". */
static void command_line_of(const char *cmd, char *out, size_t len)
{
    out[0] = '\0';
    FILE *p = popen(cmd, "r");
    if (!p) return;
    if (!fgets(out, (int)len, p)) out[0] = '\0';
    pclose(p);
    out[strcspn(out, "\r\n")] = '\0';
}

/* The CPU's model name from /proc/cpuinfo, or "". */
static void cpu_model(char *out, size_t len)
{
    out[0] = '\0';
    FILE *f = fopen("/proc/cpuinfo", "r");
    if (!f) return;
    char line[256];
    while (fgets(line, sizeof line, f)) {
        const char *colon = strchr(line, ':');
        if (strncmp(line, "model name", 10) || !colon) continue;
        snprintf(out, len, "%s", colon + 2 - (colon[1] != ' '));
        out[strcspn(out, "\r\n")] = '\0';
        break;
    }
    fclose(f);
}

/* What a profile's context reports: renderer and version strings, from a
 * small context of its own made for the purpose. */
static void renderer_of(sky_gl_profile gl, char *out, size_t len)
{
    sky_osmesa o;
    char err[256];
    snprintf(out, len, "(no context)");
    if (sky_osmesa_create(&o, 16, 16, gl, 0, err, sizeof err)) return;
    bench_gl_use(&o);
    const GLubyte *renderer = glGetString(GL_RENDERER), *version = glGetString(GL_VERSION);
    snprintf(out, len, "%s, %s", renderer ? (const char *)renderer : "?", version ? (const char *)version : "?");
    sky_osmesa_destroy(&o);
}

/* The header, once, before the first table (called where each report
 * starts printing, after its measurements: a run that fails prints none).
 * timed: 0 for reports of their own sizes, 1 for frames of the --size
 * asked, 2 for those timed in interleaved rounds. */
static void md_begin(int timed)
{
    static int done;
    if (!md.on || done) return;
    done = 1;
    time_t now = time(NULL);
    char when[64] = "?", checkout[128], cpu[160], gl[MAX_PROFS][256];
    struct tm tm;
    if (gmtime_r(&now, &tm)) strftime(when, sizeof when, "%Y-%m-%d %H:%M UTC", &tm);
    command_line_of("git describe --always --dirty 2>/dev/null", checkout, sizeof checkout);
    cpu_model(cpu, sizeof cpu);
    printf("# Benchmarks\n\nWritten by `sky-bench");
    for (int i = 1; i < md.argc; i++) {
        const char *a = md.argv[i];
        printf(strpbrk(a, " ;'\"*?$") ? " '%s'" : " %s", a);
    }
    printf("` on %s.\n`build/bin/sky-bench --markdown > docs/benchmarks.md` writes this page again (the full run\n"
           "takes minutes; `make bench` runs it). Times move from run to run on a shared machine; the ratios\n"
           "to the baseline measured in the same round move less.\n\n",
           when);
    struct utsname u;
    int have_u = uname(&u) == 0;
    printf("| | |\n|---|---|\n");
    unsigned v = sky_version();
    printf("| libsky | %u.%u.%u%s%s |\n", v >> 16, (v >> 8) & 255u, v & 255u, checkout[0] ? ", checkout " : "",
           checkout);
    printf("| machine | %s %s %s, %ld CPUs%s%s |\n", have_u ? u.sysname : "?", have_u ? u.release : "",
           have_u ? u.machine : "", sysconf(_SC_NPROCESSORS_ONLN), cpu[0] ? ", " : "", cpu);
    for (int p = 0; p < md.pr->n; p++) {
        renderer_of(md.pr->gl[p], gl[p], sizeof gl[p]);
        printf("| renderer, %s | %s |\n", prof_name(md.pr, p), gl[p]);
    }
    if (timed == 1) printf("| frames | %dx%d, median of %d frames a measurement |\n", md.w, md.h, md.frames);
    if (timed == 2)
        printf("| frames | %dx%d, median of %d frames a measurement, %d interleaved rounds |\n", md.w, md.h, md.frames,
               md.rounds);
}

int main(int argc, char **argv)
{
    int json = 0, w = 1280, h = 720, frames = 20, rounds = 5, stability = 0, paths = 1024, only_atmosphere = 0,
        only_presets = 0, only_colour = 0, only_photometry = 0, only_lighting = 0, only_night = 0, only_weather = 0,
        soak = 0,
        only_sharpness = 0;
    sky_tone_map tone_map = SKY_TONE_MAP_HUE;
    const char *make_reference = NULL, *reference = "tests/data/atmosphere_reference.txt", *plot = NULL,
               *plot_phot = NULL, *preset_list = NULL;
    profiles pr = {2, {SKY_GL_CORE33, SKY_GL_COMPAT20}};
    for (int i = 1; i < argc; i++) {
        /* asking for the usage is not a mistake: stdout, exit 0 */
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            bench_usage(stdout);
            return 0;
        } else if (!strcmp(argv[i], "--json"))
            json = 1;
        else if (!strcmp(argv[i], "--markdown"))
            md.on = 1;
        else if (!strcmp(argv[i], "--only-atmosphere"))
            only_atmosphere = 1;
        else if (!strcmp(argv[i], "--only-presets"))
            only_presets = 1;
        else if (!strcmp(argv[i], "--presets") && i + 1 < argc && argv[i + 1][0])
            preset_list = argv[++i];
        else if (!strcmp(argv[i], "--only-colour"))
            only_colour = 1;
        else if (!strcmp(argv[i], "--only-photometry"))
            only_photometry = 1;
        else if (!strcmp(argv[i], "--only-lighting"))
            only_lighting = 1;
        else if (!strcmp(argv[i], "--only-sharpness"))
            only_sharpness = 1;
        else if (!strcmp(argv[i], "--only-night"))
            only_night = 1;
        else if (!strcmp(argv[i], "--only-weather"))
            only_weather = 1;
        else if (!strcmp(argv[i], "--soak") && i + 1 < argc && (soak = atoi(argv[i + 1])) >= 1000 && soak <= 50000)
            i++;
        else if (!strcmp(argv[i], "--tone-map") && i + 1 < argc &&
                 (!strcmp(argv[i + 1], "hue") || !strcmp(argv[i + 1], "filmic") || !strcmp(argv[i + 1], "neutral")))
            tone_map = !strcmp(argv[++i], "hue") ? SKY_TONE_MAP_HUE
                       : !strcmp(argv[i], "filmic") ? SKY_TONE_MAP_FILMIC
                                                    : SKY_TONE_MAP_NEUTRAL;
        else if (!strcmp(argv[i], "--make-reference") && i + 1 < argc)
            make_reference = argv[++i];
        else if (!strcmp(argv[i], "--reference") && i + 1 < argc)
            reference = argv[++i];
        else if (!strcmp(argv[i], "--plot") && i + 1 < argc)
            plot = argv[++i];
        else if (!strcmp(argv[i], "--plot-photometry") && i + 1 < argc)
            plot_phot = argv[++i];
        else if (!strcmp(argv[i], "--paths") && i + 1 < argc && (paths = atoi(argv[i + 1])) >= 1 && paths <= 1000000)
            i++;
        else if (!strcmp(argv[i], "--stability"))
            stability = 1;
        else if (!strcmp(argv[i], "--size") && i + 1 < argc && sscanf(argv[i + 1], "%dx%d", &w, &h) == 2 && w > 0 &&
                 h > 0 && w <= 8192 && h <= 8192)
            i++;
        else if (!strcmp(argv[i], "--frames") && i + 1 < argc && (frames = atoi(argv[i + 1])) >= 3 && frames <= 10000)
            i++;
        else if (!strcmp(argv[i], "--rounds") && i + 1 < argc && (rounds = atoi(argv[i + 1])) >= 1 &&
                 rounds <= MAX_ROUNDS)
            i++;
        else if (!strcmp(argv[i], "--gl") && i + 1 < argc && !parse_profiles(argv[i + 1], &pr))
            i++;
        else {
            fprintf(stderr, "sky-bench: bad argument '%s'\n", argv[i]);
            bench_usage(stderr);
            return 2;
        }
    }
    if (json && md.on) {
        fprintf(stderr, "sky-bench: --json and --markdown are two forms of one report: choose one\n");
        return 2;
    }
    md.argc = argc;
    md.argv = argv;
    md.pr = &pr;
    md.w = w;
    md.h = h;
    md.frames = frames;
    md.rounds = rounds;
    if (stability) {
        md_begin(0);
        heading("Numerical stability");
        return stability_table(json);
    }
    int es = 0;
    for (int p = 0; p < pr.n; p++) es |= pr.gl[p] == SKY_GL_ES20;
    if (es && !only_presets && !only_night && !only_sharpness) {
        fprintf(stderr, "sky-bench: --gl es20 times the presets (--only-presets) or the night layers (--only-night), "
                "or measures the sharpness (--only-sharpness); "
                "the other tables need a desktop context\n");
        return 2;
    }
    /* ES20 on what an ES 2.0 device reports (Mesa offers ES 3.2 otherwise);
     * a value the user set stands */
    if (es) setenv("MESA_GLES_VERSION_OVERRIDE", "2.0", 0);
    if (soak) {
        md_begin(0);
        heading("Memory over a long run");
        return soak_table(soak, SKY_GL_CORE33);
    }
    static sharp_row sharp[MAX_PROFS * SHARP_PRESETS * SHARP_SIZES];
    int nsharp = 0;
    if (only_sharpness) {
        if ((nsharp = sharpness_rows(&pr, sharp)) < 0) return 1;
        if (json) {
            printf("{\n");
            print_sharpness_json(sharp, nsharp);
            printf("\n}\n");
        } else {
            md_begin(0);
            heading("Sharpness");
            print_sharpness_table(sharp, nsharp);
        }
        return 0;
    }
    static sky_colour_row colour[COLOUR_ROWS];
    static night_rows dusk;
    sky_photometry phot[PHOT_PATHS];
    if (only_photometry) {
        if (photometry_rows(phot)) return 1;
        if (plot_phot && plot_photometry(plot_phot)) return 1;
        if (json) {
            printf("{\n");
            print_photometry_json(phot);
            printf("\n}\n");
        } else {
            md_begin(0);
            heading("Photometry");
            printf("Photometry: the paths against published measurements of real skies (HDR, core profile):\n\n");
            print_photometry_table(phot);
        }
        return 0;
    }
    lighting_row lighting[PHOT_PATHS];
    capture_cost capture = {0, 0, 0, 0};
    if (only_lighting) {
        if (lighting_rows(lighting) || capture_costs(w, h, frames, &capture)) return 1;
        if (json) {
            printf("{\n");
            print_lighting_json(lighting, &capture, w, h);
            printf("\n}\n");
        } else {
            md_begin(1);
            heading("Scene lighting");
            printf("Scene lighting: sky_get_irradiance_sh (core profile):\n\n");
            print_lighting_table(lighting);
            print_capture(&capture, w, h);
        }
        return 0;
    }
    if (only_colour) {
        if (colour_rows(tone_map, colour) || dusk_rows(&dusk)) return 1;
        if (json) {
            printf("{\n");
            print_colour_json(tone_map, colour, COLOUR_ROWS);
            printf(",\n");
            print_dusk_json(&dusk);
            printf("\n}\n");
        } else {
            md_begin(0);
            heading("Colour");
            printf("Colour (tone map %s):\n\n", tone_map_names[tone_map]);
            print_colour_table(colour, COLOUR_ROWS);
            heading("The day's end and the night");
            printf("\nThe day's end and the night:\n\n");
            print_dusk_table(&dusk);
        }
        return 0;
    }
    if (make_reference) {
        char err[512];
        fprintf(stderr, "sky-bench: computing the reference sky (%d x %d directions, %d paths), minutes\n",
                SKY_ATMO_SUNS, SKY_ATMO_DIRECTIONS, paths);
        if (sky_atmo_reference_make(make_reference, paths, 2, stderr, err, sizeof err)) {
            fprintf(stderr, "sky-bench: %s\n", err);
            return 1;
        }
        return 0;
    }
    static sky_atmo_reference ref;
    if (!only_presets && !only_night && !only_weather) {
        char ref_err[512];
        if (sky_atmo_reference_load(reference, &ref, ref_err, sizeof ref_err)) {
            fprintf(stderr, "sky-bench: %s\n", ref_err);
            return 1;
        }
    }
    atmo_row atmo[2 * ATMO_SETTINGS];
    int natmo = 0;
    /* the presets; noon's clouds over the physical paths; noon's dome at
     * every pixel and at half the resolution (the cost of sharper clouds);
     * noon drawn before and after a scene covering half the frame */
    static const char *const table_presets[] = {"minimal", "noon",    "overcast", "sunset",
                                                "starry",  "moonlit", "eclipse",  "solar-eclipse",
                                                "noon --atmosphere hillaire", "noon --atmosphere preetham",
                                                "noon --dome-divisor 1", "noon --dome-divisor 2",
                                                "noon + scene over half, sky first", "noon + scene over half, sky after",
                                                "noon --dome-divisor 1 + scene over half, sky first",
                                                "noon --dome-divisor 1 + scene over half, sky after"};
    /* the weather's states at noon, and the storm at a flash (seed 0's
     * first strike, 11.20 s); the optics where they show (issue: Rainbows,
     * halos and the aurora), each beside the same view without them: a
     * rainbow after a shower and a fogbow (the sun 20 degrees up behind
     * the viewer), a halo with parhelia in cirrus (the sun 29 degrees up,
     * looking at it), the aurora over Tromso at Kp 6 on the starry
     * preset's night layers. A table of their own (a round holds at most
     * MAX_SUBJECTS rows). */
#define BOW_VIEW " --time 0.3275 --yaw 288 --pitch 12"
#define HALO_VIEW " --weather cirrus --time 0.3625 --yaw 118 --pitch 28"
#define AURORA_VIEW " --date 2024-01-11T22:00:00Z --lat 69.65 --lon 18.96 --yaw 0 --pitch 20 --cover 0"
#define AURORA_FEATURES " --features stars,planets,starmap,airglow,zodiacal,clouds,solar-eclipse"
    static const char *const weather_rows[] = {
        "noon --weather clear", "noon --weather fair", "noon --weather cirrus", "noon --weather cloudy",
        "noon --weather overcast", "noon --weather rain", "noon --weather showers", "noon --weather storm",
        "noon --weather fog", "noon --weather snow", "noon --weather storm --seconds 11.21",
        "noon --weather showers" BOW_VIEW, "noon --weather showers --features clouds,sun,weather,rainbow" BOW_VIEW,
        "noon --weather fog --features clouds,sun,weather,rainbow" BOW_VIEW, "noon" HALO_VIEW,
        "noon --features clouds,sun,weather,halo" HALO_VIEW, "starry" AURORA_FEATURES AURORA_VIEW,
        "starry" AURORA_FEATURES ",aurora --kp 6" AURORA_VIEW};
#undef BOW_VIEW
#undef HALO_VIEW
#undef AURORA_VIEW
#undef AURORA_FEATURES
    enum { WEATHER_ROWS = sizeof weather_rows / sizeof weather_rows[0] };
    static row wrows[MAX_PROFS * (WEATHER_ROWS + QUAD_KINDS - 1)];
    double base_w[MAX_PROFS] = {0};
    static rounds_info winfo[MAX_PROFS];
    int nw = 0;
    enum { TABLE_PRESETS = sizeof table_presets / sizeof table_presets[0], MAX_PRESETS = 32 };
    const char *presets[MAX_PRESETS];
    char list_copy[1024];
    int np = 0;
    if (preset_list) { /* --presets: rows separated by ';' */
        if (!only_presets || strlen(preset_list) >= sizeof list_copy) {
            fprintf(stderr, "sky-bench: --presets goes with --only-presets, and is at most %zu characters\n",
                    sizeof list_copy - 1);
            return 2;
        }
        snprintf(list_copy, sizeof list_copy, "%s", preset_list);
        for (char *save = NULL, *t = strtok_r(list_copy, ";", &save); t && np < MAX_PRESETS;
             t = strtok_r(NULL, ";", &save))
            presets[np++] = t;
    } else
        for (int i = 0; i < TABLE_PRESETS; i++) presets[np++] = table_presets[i];
    static row rows[MAX_PROFS * (MAX_PRESETS + QUAD_KINDS - 1)]; /* (static: gcc cannot see the loops fill it) */
    /* the baseline's medians over the rounds of the preset table and of
     * the atmosphere table, and its per-round figures in the first */
    double base[MAX_PROFS] = {0}, base_atmo[MAX_PROFS] = {0}, night[MAX_PROFS][NIGHT_COUNT];
    static rounds_info pinfo[MAX_PROFS], ainfo[MAX_PROFS];
    int nrows = 0;
    for (int prof = 0; prof < pr.n; prof++) {
        sky_gl_profile gl = pr.gl[prof];
        if (!only_atmosphere && !only_weather) {
            if (bench_presets(presets, np, gl, w, h, frames, rounds, &rows[nrows], &base[prof], &pinfo[prof]))
                return 1;
            nrows += np + QUAD_KINDS - 1;
        }
        if (only_weather || (!only_atmosphere && !only_presets && !only_night)) {
            if (bench_presets(weather_rows, WEATHER_ROWS, gl, w, h, frames, rounds, &wrows[nw], &base_w[prof],
                              &winfo[prof]))
                return 1;
            nw += WEATHER_ROWS + QUAD_KINDS - 1;
        }
        if (only_presets || only_weather) continue;
        if (!only_atmosphere && bench_night(gl, w, h, frames, night[prof])) return 1;
        if (only_night) continue;
        if (bench_atmosphere(gl, w, h, frames, rounds, &atmo[natmo], &base_atmo[prof], &ainfo[prof])) return 1;
        /* with no context current: each measurement makes its own */
        for (int a = 0; a < ATMO_SETTINGS; a++)
            if (measure_atmosphere(&atmo[natmo + a], &ref, gl)) return 1;
        natmo += ATMO_SETTINGS;
    }
    /* the sharpness section beside the preset table (not beside a list
     * of one's own) */
    if (!only_atmosphere && !only_night && !only_weather && !preset_list && (nsharp = sharpness_rows(&pr, sharp)) < 0)
        return 1;
    if (only_weather) {
        md_begin(2);
        heading("Weather");
        print_baseline("", w, h, frames, &pr, base_w, winfo);
        printf("\n");
        print_preset_table(wrows, nw);
        return 0;
    }
    if (only_presets && json) {
        printf("{\"size\":\"%dx%d\", \"frames\":%d, \"rounds\":%d,\n", w, h, frames, rounds);
        print_baseline_json("baseline", &pr, base, pinfo);
        printf(",\n");
        print_presets_json(rows, nrows);
        if (nsharp) {
            printf(",\n");
            print_sharpness_json(sharp, nsharp);
        }
        printf("}\n");
        return 0;
    }
    if (only_presets) {
        md_begin(2);
        heading("Presets");
        print_baseline("", w, h, frames, &pr, base, pinfo);
        printf("\n");
        print_preset_table(rows, nrows);
        if (nsharp) {
            heading("Sharpness");
            print_sharpness_table(sharp, nsharp);
        }
        return 0;
    }
    if (only_night) {
        md_begin(2);
        heading("Night layers");
        print_baseline("", w, h, frames, &pr, base, pinfo);
        print_night_table(&pr, night, base);
        return 0;
    }
    if (only_atmosphere) {
        if (plot && plot_atmosphere(plot, atmo, natmo)) return 1;
        md_begin(2);
        heading("Atmosphere paths");
        print_baseline("", w, h, frames, &pr, base_atmo, ainfo);
        print_atmosphere_table(atmo, natmo, &ref);
        return 0;
    }
    if (plot && plot_atmosphere(plot, atmo, natmo)) return 1;
    double astro = astro_us(2000);
    if (colour_rows(tone_map, colour) || dusk_rows(&dusk)) return 1;
    if (photometry_rows(phot)) return 1;
    if (plot_phot && plot_photometry(plot_phot)) return 1;
    if (lighting_rows(lighting) || capture_costs(w, h, frames, &capture)) return 1;
    if (json) {
        printf("{\"size\":\"%dx%d\", \"frames\":%d, \"rounds\":%d, \"astro_update_us\":%.2f,\n", w, h, frames,
               rounds, astro);
        print_baseline_json("baseline", &pr, base, pinfo);
        printf(",\n");
        print_baseline_json("atmosphere_baseline", &pr, base_atmo, ainfo);
        printf(",\n");
        print_presets_json(rows, nrows);
        printf(",\n");
        print_sharpness_json(sharp, nsharp);
        printf(",\n \"night_layers\": [\n");
        for (int prof = 0; prof < pr.n; prof++)
            printf("  {\"profile\":\"%s\", \"stars_ms\":%.4f, \"starmap_ms\":%.4f, \"planets_ms\":%.4f, "
                   "\"airglow_ms\":%.4f, \"zodiacal_ms\":%.4f, \"moon_cd3_ms\":%.4f, \"moon_cd30_ms\":%.4f}%s\n",
                   prof_name(&pr, prof), night[prof][NIGHT_STARS], night[prof][NIGHT_STARMAP] - night[prof][NIGHT_NONE],
                   night[prof][NIGHT_PLANETS], night[prof][NIGHT_AIRGLOW] - night[prof][NIGHT_NONE],
                   night[prof][NIGHT_ZODIACAL] - night[prof][NIGHT_NONE], night[prof][NIGHT_MOON3],
                   night[prof][NIGHT_MOON30], prof + 1 < pr.n ? "," : "");
        printf(" ],\n \"reference\": {\"method\":\"spectral, 16 wavelengths; single scattering by quadrature, orders >= 2 "
               "by Monte Carlo\", \"paths\":%d, \"std_err\":%.6g},\n \"rows\": [\n",
               ref.paths, reference_rel_std_err(&ref));
        for (int i = 0; i < natmo; i++) {
            const atmo_row *r = &atmo[i];
            printf("  {\"path\":\"%s\", \"setting\":\"%s\", \"profile\":\"%s\", \"frame_ms\":%.4f, \"ratio\":%.3f, "
                   "\"ratio_min\":%.3f, \"ratio_max\":%.3f, "
                   "\"lut_ms\":%.4f, \"lut_rebuild_ms\":%.4f, \"mean_rel_err_day\":%.5f, \"max_rel_err_day\":%.5f, "
                   "\"mean_rel_err_twilight\":%.5f, \"mean_de2000_day\":%.4f, \"mean_rel_err_by_elevation\":[",
                   r->setting->path, r->setting->setting, r->profile, r->frame_ms, r->ratio, r->ratio_min,
                   r->ratio_max, r->lut_start_ms, r->lut_rebuild_ms,
                   r->err.mean_rel_day, r->err.max_rel_day, r->err.mean_rel_twilight, r->err.mean_de2000_day);
            for (int s = 0; s < SKY_ATMO_SUNS; s++) printf("%.5f%s", r->err.mean_rel[s], s + 1 < SKY_ATMO_SUNS ? "," : "");
            printf("]}%s\n", i + 1 < natmo ? "," : "");
        }
        printf(" ],\n");
        print_colour_json(tone_map, colour, COLOUR_ROWS);
        printf(",\n");
        print_dusk_json(&dusk);
        printf(",\n");
        print_photometry_json(phot);
        printf(",\n");
        print_lighting_json(lighting, &capture, w, h);
        printf("\n}\n");
        return 0;
    }
    md_begin(2);
    if (!md.on) /* (the Markdown header says this in its table) */
        printf("sky-bench: %dx%d, median of %d frames per measurement, %d interleaved rounds (the baseline, then "
               "each\nrow; a row's figures are medians over the rounds), llvmpipe or whatever GL OSMesa provides\n",
               w, h, frames, rounds);
    heading("Presets");
    print_baseline(" in the preset rounds", w, h, frames, &pr, base, pinfo);
    if (!md.on) printf("astronomy: %.1f us of CPU per full update (median of 2000; time slider mode)\n", astro);
    printf("\n");
    print_preset_table(rows, nrows);
    heading("Sharpness");
    print_sharpness_table(sharp, nsharp);
    heading("Weather");
    print_baseline(" in the weather's rounds", w, h, frames, &pr, base_w, winfo);
    printf("\n");
    print_preset_table(wrows, nw);
    heading("Night layers");
    print_night_table(&pr, night, base);
    if (md.on) { /* a section of its own, which docs/validation.md cites */
        heading("Astronomy");
        printf("Astronomy: %.1f us of CPU per full update (`sky_compute_astronomy`, the planets' series included;\n"
               "median of 2000 calls, time slider mode).\n",
               astro);
    }
    heading("Atmosphere paths");
    printf("\n");
    print_baseline(" in the atmosphere rounds", w, h, frames, &pr, base_atmo, ainfo);
    print_atmosphere_table(atmo, natmo, &ref);
    heading("Colour");
    printf("\nColour: what the 8-bit output (tone map %s) keeps of the sky's own, per pixel against the HDR\n"
           "frame (the atmosphere and the sun):\n\n",
           tone_map_names[tone_map]);
    print_colour_table(colour, COLOUR_ROWS);
    heading("The day's end and the night");
    printf("\nThe day's end and the night: the sky's display brightness over noon's as the sun sets, and two\n"
           "nights' colours:\n\n");
    print_dusk_table(&dusk);
    heading("Photometry");
    printf("\nPhotometry: the paths against published measurements of real skies (HDR, core profile):\n\n");
    print_photometry_table(phot);
    heading("Scene lighting");
    printf("\nScene lighting: sky_get_irradiance_sh (core profile):\n\n");
    print_lighting_table(lighting);
    print_capture(&capture, w, h);
    return 0;
}
