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

void test_hostile_missing_gl_entry_point(void);
void test_hostile_context_lost(void);
void test_hostile_fifo_override(void);
void test_hostile_directory_override(void);

/* The wrapping loaders' settings: a loader is a bare function pointer, so
 * what it drops or fakes lives here (test program state, not library). */
static const char *hidden_name;
static long lost_calls;

static sky_gl_proc loader_hiding_one(const char *name)
{
    if (hidden_name && !strcmp(name, hidden_name)) return NULL;
    return sky_osmesa_loader()(name);
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
    return sky_osmesa_loader()(name);
}

void test_hostile_missing_gl_entry_point(void)
{
    /* every name sky_gl_init requires, in its loading order */
#define NAME_OF(ret, name, params) #name,
    static const char *const required[] = {SKY_GL_FUNCS_20(NAME_OF)};
#undef NAME_OF
    static const sky_gl_profile kinds[2] = {SKY_GL_CORE33, SKY_GL_COMPAT20};
    char err[512];
    for (int k = 0; k < 2; k++) {
        sky_osmesa ctx;
        if (sky_osmesa_create(&ctx, 16, 16, kinds[k], 0, err, sizeof err)) {
            CHECK(0, "%s", err);
            return;
        }
        int bad = 0;
        for (size_t i = 0; i < sizeof required / sizeof required[0]; i++) {
            hidden_name = required[i];
            sky_config cfg;
            memset(&cfg, 0, sizeof cfg);
            cfg.get_proc_address = loader_hiding_one;
            err[0] = '\0';
            sky *s = sky_create(&cfg, err, sizeof err);
            if (s || !strstr(err, required[i])) bad++;
            CHECK(s == NULL && strstr(err, required[i]), "%s context without %s: %s", k ? "compat" : "core",
                  required[i], s ? "created" : err);
            sky_destroy(s);
        }
        hidden_name = NULL;
        NOTE("%s context: %zu loaders each missing one entry point: %d wrong", k ? "compat" : "core",
             sizeof required / sizeof required[0], bad);
        sky_osmesa_destroy(&ctx);
    }
}

void test_hostile_context_lost(void)
{
    char err[512];
    sky_osmesa ctx;
    if (sky_osmesa_create(&ctx, 16, 16, SKY_GL_AUTO, 0, err, sizeof err)) {
        CHECK(0, "%s", err);
        return;
    }
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.get_proc_address = loader_context_lost;
    lost_calls = 0;
    err[0] = '\0';
    sky *s = sky_create(&cfg, err, sizeof err);
    NOTE("glGetError called %ld times -> %s", lost_calls, s ? "created?!" : err);
    CHECK(s == NULL, "a context whose errors never drain is refused");
    CHECK(strstr(err, "0x0507") != NULL, "the message names the error: %s", err);
    CHECK(lost_calls <= 1000, "glGetError is asked a bounded number of times, not %ld", lost_calls);
    sky_destroy(s);
    sky_osmesa_destroy(&ctx);
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

void test_hostile_fifo_override(void)
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

void test_hostile_directory_override(void)
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
    /* a dangling symlink is an absent override: the embedded one is used */
    rmdir(path);
    CHECK(symlink("/nonexistent/sky-no-such-file.png", path) == 0, "symlink");
    s = create_with_dir(dir, err, sizeof err, &ctx, &seconds);
    CHECK(s != NULL, "a dangling symlink falls back to the embedded texture: %s", err);
    sky_destroy(s);
    if (ctx.ctx) sky_osmesa_destroy(&ctx);
    remove(path);
    rmdir(dir);
}
