/*
 * sky-render: the sky without a window. Renders through OSMesa into a PNG
 * (8-bit sRGB after exposure, tone map and dither) and/or a PFM (linear
 * float RGB, luminance in kcd/m^2), and prints statistics as JSON.
 * Exit status: 0 success, 2 bad arguments, 1 runtime failure.
 */
#include "cli.h"
#include "osmesa_ctx.h"

#include <GL/gl.h>
#ifdef _WIN32
#include <GL/glext.h> /* Windows' gl.h stops at OpenGL 1.1 */
#endif
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* --out-shadow: the clouds' shadow map of the last frame, --size pixels
 * over --shadow-extent, grey (white = full sun). */
static int write_shadow(sky *s, const sky_cli *cli)
{
    size_t n = (size_t)cli->width * (size_t)cli->height;
    unsigned char *grey = malloc(n), *rgb = malloc(3 * n);
    int rc = 1;
    if (!grey || !rgb)
        fprintf(stderr, "sky-render: out of memory for the shadow map\n");
    else if (sky_cloud_shadow_image(s, (float)(cli->shadow_extent_km * 1000.0), cli->width, cli->height, grey) < 0)
        fprintf(stderr, "sky-render: %s\n", sky_last_error(s));
    else {
        for (size_t i = 0; i < n; i++) rgb[3 * i] = rgb[3 * i + 1] = rgb[3 * i + 2] = grey[i];
        if (sky_write_png_rgb(cli->out_shadow, cli->width, cli->height, rgb))
            fprintf(stderr, "sky-render: cannot write %s: %s\n", cli->out_shadow, strerror(errno));
        else
            rc = 0;
    }
    free(grey);
    free(rgb);
    return rc;
}

/* FILE.png -> FILE_0007.png for frame 7 of several. */
static void frame_path(char *dst, size_t len, const char *path, int frame, int frames)
{
    if (frames <= 1) {
        snprintf(dst, len, "%s", path);
        return;
    }
    const char *dot = strrchr(path, '.');
    const char *slash = strrchr(path, '/');
    if (!dot || (slash && dot < slash)) dot = path + strlen(path);
    snprintf(dst, len, "%.*s_%04d%s", (int)(dot - path), path, frame, dot);
}

/* Renders all frames into one buffer kind; writes files; fills stats. */
static int render_pass(const sky_cli *cli, int hdr, const char *out, int print_stats)
{
    char err[512];
    sky_osmesa ctx;
    if (sky_osmesa_create(&ctx, cli->width, cli->height, cli->gl, hdr, err, sizeof err)) {
        fprintf(stderr, "sky-render: %s\n", err);
        return 1;
    }
    sky_config cfg = sky_cli_config(cli, sky_headless_loader(&ctx));
    cfg.output = hdr ? SKY_OUTPUT_HDR : SKY_OUTPUT_LDR;
    cfg.profile_layers = cli->stats;
    sky *s = sky_create(&cfg, err, sizeof err);
    if (!s) {
        fprintf(stderr, "sky-render: %s\n", err);
        sky_osmesa_destroy(&ctx);
        return 1;
    }
    int rc = 0;
    if (sky_cli_apply(s, cli) < 0) {
        fprintf(stderr, "sky-render: %s\n", sky_last_error(s));
        rc = 1;
    }
    float view[16], proj[16];
    sky_cli_camera(cli, view, proj);
    double *times = calloc((size_t)cli->frames, sizeof(double));
    if (!times) rc = 1;
    /* One untimed frame first: shader compilation happens on first use. */
    if (!rc && cli->stats) {
        sky_result r = cli->fisheye ? sky_draw_fisheye(s) : sky_draw(s, view, proj);
        if (r < 0) {
            fprintf(stderr, "sky-render: %s\n", sky_last_error(s));
            rc = 1;
        }
    }
    for (int f = 0; !rc && f < cli->frames; f++) {
        if (f > 0 && sky_update(s, 1.0 / 30.0) < 0) rc = 1;
        double t0 = sky_cli_now_ms();
        sky_result r = cli->fisheye ? sky_draw_fisheye(s) : sky_draw(s, view, proj);
        sky_osmesa_finish(&ctx);
        times[f] = sky_cli_now_ms() - t0;
        if (r < 0) {
            fprintf(stderr, "sky-render: %s\n", sky_last_error(s));
            rc = 1;
            break;
        }
        if (out) {
            char path[4096];
            frame_path(path, sizeof path, out, f + 1, cli->frames);
            char werr[4200];
            int w = hdr ? sky_osmesa_write_pfm(&ctx, path, werr, sizeof werr)
                        : sky_osmesa_write_png(&ctx, path, werr, sizeof werr);
            if (w) {
                fprintf(stderr, "sky-render: cannot write %s\n", werr);
                rc = 1;
                break; /* the next frames would fail alike */
            }
        }
        if (cli->frames > 1) fprintf(stderr, "\rsky-render: frame %d/%d", f + 1, cli->frames);
    }
    if (cli->frames > 1) fprintf(stderr, "\n");
    if (!rc && !hdr && cli->out_shadow) rc = write_shadow(s, cli);
    if (!rc && print_stats) {
        sky_cli_print_stats(stdout, s, sky_cli_median(times, cli->frames), cli->seconds);
    }
    free(times);
    sky_destroy(s);
    sky_osmesa_destroy(&ctx);
    return rc;
}

/* --capture N: the environment cube map (sky_capture_environment) read
 * back face by face into a 4N x 3N cross, written as one PNG: +Y above
 * +Z; -X, +Z, +X, -Z across; -Y below; each face with its first row (GL's
 * t = 0) at the top, so that neighbouring faces meet edge to edge. */
/* ES 2.0 has no glGetTexImage: face f of cube map tex is read through a
 * framebuffer it is attached to (rows from t = 0, as glGetTexImage gives
 * them). The entry points come from the context's loader: the EGL
 * context's are not the symbols this program links. Returns 0 or -1. */
static int read_face_es(const sky_osmesa *ctx, unsigned tex, int f, int n, unsigned char *face)
{
    sky_get_proc_address_fn gpa = sky_headless_loader(ctx);
    void (*gen)(GLsizei, GLuint *) = (void (*)(GLsizei, GLuint *))gpa("glGenFramebuffers");
    void (*del)(GLsizei, const GLuint *) = (void (*)(GLsizei, const GLuint *))gpa("glDeleteFramebuffers");
    void (*bind)(GLenum, GLuint) = (void (*)(GLenum, GLuint))gpa("glBindFramebuffer");
    void (*attach)(GLenum, GLenum, GLenum, GLuint, GLint) =
        (void (*)(GLenum, GLenum, GLenum, GLuint, GLint))gpa("glFramebufferTexture2D");
    void (*pack)(GLenum, GLint) = (void (*)(GLenum, GLint))gpa("glPixelStorei");
    void (*read)(GLint, GLint, GLsizei, GLsizei, GLenum, GLenum, void *) =
        (void (*)(GLint, GLint, GLsizei, GLsizei, GLenum, GLenum, void *))gpa("glReadPixels");
    GLenum (*error)(void) = (GLenum(*)(void))gpa("glGetError");
    if (!gen || !del || !bind || !attach || !pack || !read || !error) return -1;
    GLuint fbo = 0;
    gen(1, &fbo);
    bind(0x8D40 /* GL_FRAMEBUFFER */, fbo);
    attach(0x8D40, 0x8CE0 /* GL_COLOR_ATTACHMENT0 */, GL_TEXTURE_CUBE_MAP_POSITIVE_X + (GLenum)f, tex, 0);
    pack(GL_PACK_ALIGNMENT, 1);
    read(0, 0, n, n, GL_RGBA, GL_UNSIGNED_BYTE, face);
    bind(0x8D40, 0);
    del(1, &fbo);
    return error() == GL_NO_ERROR ? 0 : -1;
}

static int render_capture(const sky_cli *cli)
{
    static const int cell[6][2] = {{2, 1}, {0, 1}, {1, 0}, {1, 2}, {1, 1}, {3, 1}}; /* +X -X +Y -Y +Z -Z */
    int n = cli->capture, w = 4 * n, h = 3 * n;
    char err[512];
    sky_osmesa ctx;
    if (sky_osmesa_create(&ctx, w, h, cli->gl, 0, err, sizeof err)) {
        fprintf(stderr, "sky-render: %s\n", err);
        return 1;
    }
    sky_config cfg = sky_cli_config(cli, sky_headless_loader(&ctx));
    sky *s = sky_create(&cfg, err, sizeof err);
    int rc = 0;
    unsigned char *face = malloc((size_t)n * (size_t)n * 4);
    if (!s || !face) {
        fprintf(stderr, "sky-render: %s\n", s ? "out of memory" : err);
        rc = 1;
    }
    if (!rc && (sky_cli_apply(s, cli) < 0 ||
                sky_capture_environment(s, 0, n, SKY_CAPTURE_ALL_FACES, SKY_CAPTURE_SUN_DISC) < 0)) {
        fprintf(stderr, "sky-render: %s\n", sky_last_error(s));
        rc = 1;
    }
    unsigned char *px = ctx.pixels; /* bottom row first */
    if (!rc) {
        memset(px, 0, (size_t)w * (size_t)h * 4);
        if (!ctx.is_es) {
            glBindTexture(GL_TEXTURE_CUBE_MAP, sky_environment_texture(s));
            glPixelStorei(GL_PACK_ALIGNMENT, 1);
        }
        for (int f = 0; f < 6 && !rc; f++) {
            if (ctx.is_es)
                rc = read_face_es(&ctx, sky_environment_texture(s), f, n, face);
            else
                glGetTexImage(GL_TEXTURE_CUBE_MAP_POSITIVE_X + (GLenum)f, 0, GL_RGBA, GL_UNSIGNED_BYTE, face);
            for (int t = 0; t < n; t++) {
                int row = h - 1 - (cell[f][1] * n + t);
                memcpy(px + ((size_t)row * (size_t)w + (size_t)cell[f][0] * (size_t)n) * 4, face + (size_t)t * n * 4,
                       (size_t)n * 4);
            }
        }
        if (!ctx.is_es) glBindTexture(GL_TEXTURE_CUBE_MAP, 0);
        if (rc || (!ctx.is_es && glGetError() != GL_NO_ERROR)) {
            fprintf(stderr, "sky-render: reading the cube map back failed\n");
            rc = 1;
        }
    }
    if (!rc) {
        char werr[4200];
        if (sky_osmesa_write_png(&ctx, cli->out_png, werr, sizeof werr)) {
            fprintf(stderr, "sky-render: cannot write %s\n", werr);
            rc = 1;
        }
    }
    free(face);
    sky_destroy(s);
    sky_osmesa_destroy(&ctx);
    return rc;
}

/* What --help, --query and --stats print is output like the images: if a
 * byte of it was not written (a full disk, a closed pipe, >/dev/full) the
 * run failed. stdout is fully buffered when redirected, so the error often
 * shows only at this final flush and close. */
static int finish(int rc)
{
    int bad = ferror(stdout);
    if (fclose(stdout) != 0) bad = 1;
    if (bad) {
        fprintf(stderr, "sky-render: cannot write standard output: %s\n", errno ? strerror(errno) : "write error");
        return rc ? rc : 1;
    }
    return rc;
}

static int run(int argc, char **argv)
{
    sky_cli cli;
    char err[512];
    int rc = sky_cli_parse(&cli, argc, argv, 0, err, sizeof err);
    if (rc == SKY_CLI_HELP) {
        sky_cli_usage(stdout, "sky-render", 0);
        return 0;
    }
    if (rc) {
        fprintf(stderr, "sky-render: %s\n", err);
        return 2;
    }
    if (cli.query) {
        sky_astronomy a;
        sky_star_place stars[64];
        char err2[512];
        if (sky_compute_astronomy(&cli.observer, cli.params.time, cli.hip, cli.hip_count, stars, &a, err2,
                                  sizeof err2) < 0) {
            fprintf(stderr, "sky-render: %s\n", err2);
            return 1;
        }
        sky_cli_print_query(stdout, &a, stars, cli.hip_count);
        return 0;
    }
    if (cli.capture) {
        if (!cli.out_png || cli.out_pfm || cli.frames > 1 || cli.fisheye) {
            fprintf(stderr, "sky-render: --capture writes one PNG: it needs --out FILE.png, and takes no --out-pfm, "
                            "--frames or --fisheye\n");
            return 2;
        }
        return render_capture(&cli);
    }
    /* The PFM needs a float buffer and a linear sky, the PNG an 8-bit one:
     * one pass each. Statistics come from the PNG pass when there is one.
     * With neither output, render anyway (a check that GL works, exit 0),
     * but say so first: a forgotten --out otherwise looked like success. */
    if (!cli.out_png && !cli.out_pfm && !cli.stats && !cli.out_shadow)
        fprintf(stderr, "sky-render: nothing will be written (no --out, --out-pfm or --stats): rendering once as a "
                        "check of GL; add --out FILE.png or --out-pfm FILE.pfm to keep the image\n");
    int png_pass = cli.out_png || !cli.out_pfm;
    if (cli.out_pfm && (rc = render_pass(&cli, 1, cli.out_pfm, cli.stats && !png_pass))) return rc;
    if (png_pass && (rc = render_pass(&cli, 0, cli.out_png, cli.stats))) return rc;
    return 0;
}

int main(int argc, char **argv) { return finish(run(argc, argv)); }
