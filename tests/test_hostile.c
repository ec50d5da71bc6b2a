/*
 * Hostile hosts (issue "Reliability II", items 4, 5, 6, 8): a GL loader
 * missing an entry point, a context whose glGetError never drains, texture
 * overrides that are a FIFO or a directory, and a paletted PNG indexing
 * past its palette.
 */
#include "test.h"
#include "sky_internal.h"

#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

/* The wrapping loaders' settings: a loader is a bare function pointer, so
 * what it drops or fakes lives here (test program state, not library). */
static const char *hidden_name;
static sky_get_proc_address_fn hiding_from; /* the context's own loader */
static long lost_calls;

static sky_gl_proc loader_hiding_one(const char *name)
{
    if (hidden_name && !strcmp(name, hidden_name)) return NULL;
    return hiding_from(name);
}

/* GL_CONTEXT_LOST forever, as a lost context reports it; after a million
 * calls it gives in, so that a library looping on it fails the test
 * instead of hanging the suite. */
static GLenum fake_get_error_lost(void)
{
    return ++lost_calls > 1000000 ? GL_NO_ERROR : 0x0507;
}

static sky_gl_proc loader_context_lost(const char *name)
{
    if (!strcmp(name, "glGetError")) return (sky_gl_proc)fake_get_error_lost;
    return hiding_from(name);
}

TEST(hostile_missing_gl_entry_point)
{
    /* every name sky_gl_init requires, in its loading order: an ES
     * context needs all but desktop GL's own */
#define NAME_OF(ret, name, params) #name,
    static const char *const required[] = {SKY_GL_FUNCS_20(NAME_OF) SKY_GL_FUNCS_DESKTOP(NAME_OF)};
    static const char *const desktop_only[] = {SKY_GL_FUNCS_DESKTOP(NAME_OF)};
#undef NAME_OF
    static const sky_gl_profile kinds[3] = {SKY_GL_CORE33, SKY_GL_COMPAT20, SKY_GL_ES20};
    static const char *const kind_names[3] = {"core", "compat", "es20"};
    char err[512];
    for (int k = 0; k < 3; k++) {
        sky_osmesa ctx;
        if (sky_osmesa_create(&ctx, 16, 16, kinds[k], 0, err, sizeof err)) {
            CHECK(0, "%s", err);
            return;
        }
        hiding_from = sky_headless_loader(&ctx);
        size_t count = sizeof required / sizeof required[0];
        if (kinds[k] == SKY_GL_ES20) count -= sizeof desktop_only / sizeof desktop_only[0];
        int bad = 0;
        for (size_t i = 0; i < count; i++) {
            hidden_name = required[i];
            sky_config cfg;
            memset(&cfg, 0, sizeof cfg);
            cfg.get_proc_address = loader_hiding_one;
            err[0] = '\0';
            sky *s = sky_create(&cfg, err, sizeof err);
            if (s || !strstr(err, required[i])) bad++;
            CHECK(s == NULL && strstr(err, required[i]), "%s context without %s: %s", kind_names[k], required[i],
                  s ? "created" : err);
            sky_destroy(s);
        }
        hidden_name = NULL;
        NOTE("%s context: %zu loaders each missing one entry point: %d wrong", kind_names[k], count, bad);
        sky_osmesa_destroy(&ctx);
    }
}

TEST(hostile_context_lost)
{
    static const sky_gl_profile kinds[2] = {SKY_GL_AUTO, SKY_GL_ES20};
    for (int k = 0; k < 2; k++) {
        char err[512];
        sky_osmesa ctx;
        if (sky_osmesa_create(&ctx, 16, 16, kinds[k], 0, err, sizeof err)) {
            CHECK(0, "%s", err);
            return;
        }
        hiding_from = sky_headless_loader(&ctx);
        sky_config cfg;
        memset(&cfg, 0, sizeof cfg);
        cfg.get_proc_address = loader_context_lost;
        lost_calls = 0;
        err[0] = '\0';
        sky *s = sky_create(&cfg, err, sizeof err);
        NOTE("%s: glGetError called %ld times -> %s", k ? "ES" : "desktop", lost_calls, s ? "created?!" : err);
        CHECK(s == NULL, "a context whose errors never drain is refused");
        CHECK(strstr(err, "0x0507") != NULL, "the message names the error: %s", err);
        CHECK(lost_calls <= 1000, "glGetError is asked a bounded number of times, not %ld", lost_calls);
        sky_destroy(s);
        sky_osmesa_destroy(&ctx);
    }
}

/* sky_create with texture_dir = dir; returns the sky (NULL on failure,
 * err set) and the time it took. */
static sky *create_with_dir(const char *dir, char *err, size_t err_len, sky_osmesa *ctx, double *seconds)
{
    if (sky_osmesa_create(ctx, 16, 16, SKY_GL_AUTO, 0, err, err_len)) {
        CHECK(0, "%s", err);
        ctx->ctx = NULL;
        return NULL;
    }
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.texture_dir = dir;
    cfg.get_proc_address = sky_osmesa_loader();
    err[0] = '\0';
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    sky *s = sky_create(&cfg, err, err_len);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    *seconds = (double)(t1.tv_sec - t0.tv_sec) + (double)(t1.tv_nsec - t0.tv_nsec) * 1e-9;
    return s;
}

TEST(hostile_fifo_override)
{
    char dir[] = "/tmp/sky-fifo-XXXXXX";
    if (!mkdtemp(dir)) {
        CHECK(0, "mkdtemp");
        return;
    }
    char path[128];
    snprintf(path, sizeof path, "%s/clouds.png", dir);
    if (mkfifo(path, 0600)) {
        CHECK(0, "mkfifo %s", path);
        rmdir(dir);
        return;
    }
    /* A library that blocks opening the FIFO would hang the suite: a
     * child (no GL in it) opens the write end after 5 s, which releases
     * such an open, and the time taken then fails the test. */
    pid_t writer = fork();
    if (writer == 0) {
        sleep(5);
        int fd = open(path, O_WRONLY | O_NONBLOCK);
        if (fd >= 0) close(fd);
        _exit(0);
    }
    char err[512];
    sky_osmesa ctx;
    double seconds = 0.0;
    sky *s = create_with_dir(dir, err, sizeof err, &ctx, &seconds);
    NOTE("FIFO override: %.2f s -> %s", seconds, s ? "created?!" : err);
    CHECK(s == NULL && strstr(err, "clouds.png"), "a FIFO override is refused, naming it: %s", err);
    CHECK(seconds < 2.0, "sky_create returns promptly, not after %.1f s", seconds);
    sky_destroy(s);
    if (ctx.ctx) sky_osmesa_destroy(&ctx);
    if (writer > 0) {
        kill(writer, SIGKILL);
        waitpid(writer, NULL, 0);
    }
    remove(path);
    rmdir(dir);
}

TEST(hostile_directory_override)
{
    char dir[] = "/tmp/sky-dir-XXXXXX";
    if (!mkdtemp(dir)) {
        CHECK(0, "mkdtemp");
        return;
    }
    char path[128];
    snprintf(path, sizeof path, "%s/clouds.png", dir);
    CHECK(mkdir(path, 0700) == 0, "mkdir %s", path);
    char err[512];
    sky_osmesa ctx;
    double seconds = 0.0;
    sky *s = create_with_dir(dir, err, sizeof err, &ctx, &seconds);
    NOTE("directory override -> %s", s ? "created?!" : err);
    CHECK(s == NULL && strstr(err, "clouds.png") && strstr(err, "directory"),
          "a directory named clouds.png is reported as one: %s", err);
    sky_destroy(s);
    if (ctx.ctx) sky_osmesa_destroy(&ctx);
    /* a dangling symlink was meant as an override: reported as missing, not
     * silently replaced by the embedded texture */
    rmdir(path);
    CHECK(symlink("/nonexistent/sky-no-such-file.png", path) == 0, "symlink");
    s = create_with_dir(dir, err, sizeof err, &ctx, &seconds);
    NOTE("dangling symlink -> %s", s ? "created?!" : err);
    CHECK(s == NULL && strstr(err, "clouds.png") && strstr(err, "missing"), "a dangling symlink is reported: %s",
          s ? "created" : err);
    sky_destroy(s);
    if (ctx.ctx) sky_osmesa_destroy(&ctx);
    remove(path);
    rmdir(dir);
}

/* ---- a paletted PNG written by hand ------------------------------------- */

static size_t put32(unsigned char *p, unsigned long v)
{
    p[0] = (unsigned char)(v >> 24);
    p[1] = (unsigned char)(v >> 16);
    p[2] = (unsigned char)(v >> 8);
    p[3] = (unsigned char)v;
    return 4;
}

static size_t put_chunk(unsigned char *out, const char *type, const unsigned char *data, size_t len)
{
    size_t n = put32(out, (unsigned long)len);
    memcpy(out + n, type, 4);
    if (len) memcpy(out + n + 4, data, len);
    n += 4 + len;
    n += put32(out + n, sky_png_crc32(out + 4, 4 + len));
    return n;
}

/* A 256x1 8-bit paletted PNG whose pixels are the indices 0..255 and
 * whose PLTE has one entry (red): 255 of its pixels index past it. The
 * image data is a stored (uncompressed) deflate block. Returns its size;
 * out holds at least 512 bytes. */
static size_t palette_overrun_png(unsigned char *out)
{
    static const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    size_t n = 0;
    memcpy(out, sig, 8);
    n += 8;
    unsigned char ihdr[13] = {0, 0, 1, 0, 0, 0, 0, 1, 8, 3, 0, 0, 0};
    n += put_chunk(out + n, "IHDR", ihdr, sizeof ihdr);
    static const unsigned char plte[3] = {255, 0, 0};
    n += put_chunk(out + n, "PLTE", plte, sizeof plte);
    unsigned char raw[257];
    raw[0] = 0; /* filter: none */
    for (int i = 0; i < 256; i++) raw[1 + i] = (unsigned char)i;
    unsigned char z[2 + 5 + sizeof raw + 4];
    size_t zn = 0;
    z[zn++] = 0x78;
    z[zn++] = 0x01;
    z[zn++] = 0x01; /* final stored block */
    z[zn++] = (unsigned char)(sizeof raw & 0xff);
    z[zn++] = (unsigned char)(sizeof raw >> 8);
    z[zn++] = (unsigned char)(~sizeof raw & 0xff);
    z[zn++] = (unsigned char)((~sizeof raw >> 8) & 0xff);
    memcpy(z + zn, raw, sizeof raw);
    zn += sizeof raw;
    unsigned long a = 1, b = 0;
    for (size_t i = 0; i < sizeof raw; i++) {
        a = (a + raw[i]) % 65521UL;
        b = (b + a) % 65521UL;
    }
    zn += put32(z + zn, b << 16 | a);
    n += put_chunk(out + n, "IDAT", z, zn);
    n += put_chunk(out + n, "IEND", NULL, 0);
    return n;
}

/* Fills a stretch of stack with a pattern, so that a decoder reading a
 * palette it never wrote finds that pattern rather than chance zeros. */
static void dirty_stack(void)
{
    volatile unsigned char junk[64 * 1024];
    for (size_t i = 0; i < sizeof junk; i++) junk[i] = 0xa5;
}

TEST(hostile_palette_overrun)
{
    unsigned char png[512];
    size_t size = palette_overrun_png(png);
    dirty_stack();
    unsigned char *rgba = NULL;
    char err[256] = "";
    int rc = sky_image_decode(png, size, 256, 1, &rgba, "palette overrun", err, sizeof err);
    if (rc != 0) {
        /* refusing the file is also an answer the issue accepts */
        CHECK(rgba == NULL && err[0], "a refused file returns no pixels and a reason");
        NOTE("refused: %s", err);
        return;
    }
    CHECK(rgba[0] == 255 && rgba[1] == 0 && rgba[2] == 0 && rgba[3] == 255, "index 0 is the palette's red: %d %d %d %d",
          rgba[0], rgba[1], rgba[2], rgba[3]);
    int wrong = 0;
    for (int i = 1; i < 256; i++)
        if (rgba[4 * i] || rgba[4 * i + 1] || rgba[4 * i + 2] || rgba[4 * i + 3] != 255) wrong++;
    CHECK(wrong == 0, "%d of the 255 indices past the palette decode to something other than opaque black "
          "(pixel 1: %d %d %d %d)", wrong, rgba[4], rgba[5], rgba[6], rgba[7]);
    sky_png_free(rgba);
}

/* A core context whose loader lacks a 3.x entry point CORE33 needs cannot
 * fall back to COMPAT20 (a core profile runs no GLSL 1.10): the message
 * names the missing function, not only the profile. */
TEST(hostile_core_context_names_what_it_lacks)
{
    static const char *const names[2] = {"glGenVertexArrays", "glBindFramebuffer"};
    char err[512];
    sky_osmesa ctx;
    if (sky_osmesa_create(&ctx, 16, 16, SKY_GL_CORE33, 0, err, sizeof err)) {
        CHECK(0, "%s", err);
        return;
    }
    hiding_from = sky_headless_loader(&ctx);
    for (int i = 0; i < 2; i++) {
        hidden_name = names[i];
        sky_config cfg;
        memset(&cfg, 0, sizeof cfg);
        cfg.get_proc_address = loader_hiding_one;
        sky *s = sky_create(&cfg, err, sizeof err);
        NOTE("core context without %s: %s", names[i], s ? "created" : err);
        CHECK(s == NULL && strstr(err, names[i]), "the message names %s: %s", names[i], s ? "created" : err);
        sky_destroy(s);
    }
    hidden_name = NULL;
    sky_osmesa_destroy(&ctx);
}
