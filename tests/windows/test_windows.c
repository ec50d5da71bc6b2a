/*
 * The Windows runner's own tests (make test-windows: MinGW-w64's build of
 * the library and of these tests, run under Wine and Xvfb, whose WGL is
 * Mesa's llvmpipe). Beside them the runner holds the portable tests of
 * test_api.c, test_validation.c, test_stability.c and test_planets.c.
 *
 * SKY_BIN names build/windows/bin (sky-render.exe, sky-render-dll.exe
 * linked against sky.dll, sky-render-amalgamation.exe built on the
 * amalgamation); SKY_WINDOWS_REFERENCE the Linux frames of the
 * same command lines, rendered by Linux's sky-render through OSMesa, and
 * SKY_WINDOWS_PRESETS their presets, as sky-render --help lists them
 * (tests/windows/run.sh).
 */
#include "test.h"
#include "cli.h"

#include <windows.h>

#include <stdint.h>
#include <stdlib.h>
#include <string.h>


/* A program of SKY_BIN as cmd.exe wants its name: with backslashes. */
static const char *program(const char *name, char *buf, size_t len)
{
    bin_path(name, buf, len);
    for (char *c = buf; *c; c++)
        if (*c == '/') *c = '\\';
    return buf;
}

/* Renders a preset through sky-render.exe (a hidden WGL window) into
 * path; the exit status, output in log. */
static int render_preset(const char *exe, const char *preset, const char *gl, const char *path, char *log,
                         size_t log_len)
{
    char prog[512], cmd[1400];
    snprintf(cmd, sizeof cmd, "%s --preset %s --gl %s --out %s 2>&1", program(exe, prog, sizeof prog), preset, gl,
             path);
    return run_command(cmd, log, log_len);
}

/* Each preset's frame through WGL against Linux's through OSMesa: the same
 * command line, the same library, another platform's GL and C runtime. */
static void frames_match_linux(const char *gl)
{
    const char *ref_dir = getenv("SKY_WINDOWS_REFERENCE"), *list = getenv("SKY_WINDOWS_PRESETS");
    if (!ref_dir || !list) {
        SKIP("SKY_WINDOWS_REFERENCE and SKY_WINDOWS_PRESETS name no Linux frames (tests/windows/run.sh makes them)");
        return;
    }
    int compared = 0;
    for (const char *p = list; *p;) {
        size_t n = strcspn(p, " ");
        char preset[64], out[512], ref[512], log[2048], name[128];
        snprintf(preset, sizeof preset, "%.*s", (int)(n < 63 ? n : 63), p);
        p += n;
        p += strspn(p, " ");
        if (!*preset) continue;
        snprintf(name, sizeof name, "%s-%s.png", preset, gl);
        tmp_path(name, out, sizeof out);
        snprintf(ref, sizeof ref, "%s/%s", ref_dir, name);
        int rc = render_preset("sky-render.exe", preset, gl, out, log, sizeof log);
        CHECK(rc == 0, "sky-render.exe --preset %s --gl %s exited %d: %s", preset, gl, rc, log);
        image a, b;
        if (rc || image_load_png(out, &a)) continue;
        if (image_load_png(ref, &b)) {
            CHECK(0, "no Linux frame %s", ref);
            image_free(&a);
            continue;
        }
        CHECK(a.w == b.w && a.h == b.h, "%s: %dx%d on Windows, %dx%d on Linux", name, a.w, a.h, b.w, b.h);
        if (a.w == b.w && a.h == b.h) {
            double psnr = image_psnr(&a, &b);
            if (!memcmp(a.px, b.px, sizeof(float) * 3u * (size_t)a.w * (size_t)a.h))
                NOTE("%-13s %s: identical to Linux's frame", preset, gl);
            else
                NOTE("%-13s %s: PSNR %.1f dB against Linux", preset, gl, psnr);
            CHECK(psnr >= 40.0, "%s under Wine against Linux: %.1f dB, under 40", name, psnr);
            compared++;
        }
        image_free(&a);
        image_free(&b);
        remove(out);
    }
    CHECK(compared >= 8, "%d presets compared (sky-render has eight)", compared);
}

TEST(windows_frames_match_linux_core) { frames_match_linux("core"); }
TEST(windows_frames_match_linux_compat) { frames_match_linux("compat"); }

/* ---- the loader: what a bare wglGetProcAddress gives --------------------- */

/* Windows' own loader and nothing else, as a host that hands the library
 * wglGetProcAddress itself would: NULL for OpenGL 1.1's functions. */
static sky_gl_proc bare_wgl(const char *name) { return (sky_gl_proc)(void (*)(void))wglGetProcAddress(name); }

/* The same, answering with the other values Windows' drivers give for a
 * function they do not know (1, 2, 3 and -1) in turn. */
static int sentinel_turn;
static sky_gl_proc sentinel_wgl(const char *name)
{
    sky_gl_proc p = bare_wgl(name);
    if (p) return p;
    static const intptr_t sentinels[] = {1, 2, 3, -1};
    return (sky_gl_proc)(void (*)(void))sentinels[sentinel_turn++ % 4];
}

/* One noon frame at 160x90 through the given loader into px (RGBA);
 * 0 or -1 with the reason printed. */
static int frame_with_loader(sky_get_proc_address_fn loader, sky_gl_profile profile, unsigned char *px)
{
    char err[512];
    sky_osmesa ctx;
    if (sky_osmesa_create(&ctx, 160, 90, profile, 0, err, sizeof err)) {
        printf("    %s\n", err);
        return -1;
    }
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.get_proc_address = loader;
    cfg.gl_profile = profile;
    cfg.features = SKY_CLOUDS | SKY_SUN;
    sky *s = sky_create(&cfg, err, sizeof err);
    int rc = -1;
    if (s) {
        float view[16], proj[16];
        sky_cli_camera_at(180.0, 20.0, 60.0, 160, 90, view, proj);
        rc = sky_draw(s, view, proj) == SKY_OK ? 0 : -1;
        if (rc) printf("    sky_draw: %s\n", sky_last_error(s));
        sky_osmesa_finish(&ctx);
        memcpy(px, ctx.pixels, 160u * 90u * 4u);
        sky_destroy(s);
    } else {
        printf("    sky_create: %s\n", err);
    }
    sky_osmesa_destroy(&ctx);
    return rc;
}

/* The library takes from opengl32.dll what the host's loader does not
 * give: with a bare wglGetProcAddress (or one answering 1, 2, 3, -1) it
 * draws the very frame a GLFW-style loader gets. */
TEST(windows_bare_wgl_loader_draws)
{
    static const sky_gl_profile profiles[2] = {SKY_GL_CORE33, SKY_GL_COMPAT20};
    for (int k = 0; k < 2; k++) {
        static unsigned char full[160 * 90 * 4], bare[160 * 90 * 4], sentinel[160 * 90 * 4];
        char err[256];
        sky_osmesa probe;
        if (sky_osmesa_create(&probe, 16, 16, profiles[k], 0, err, sizeof err)) {
            CHECK(0, "no context: %s", err);
            return;
        }
        /* the test means something only if the bare loader really lacks
         * OpenGL 1.1 */
        intptr_t clear = (intptr_t)bare_wgl("glClear"), get_string = (intptr_t)bare_wgl("glGetString");
        CHECK((clear >= -1 && clear <= 3) && (get_string >= -1 && get_string <= 3),
              "wglGetProcAddress answers OpenGL 1.1's glClear (%p) or glGetString (%p)", (void *)clear,
              (void *)get_string);
        sky_osmesa_destroy(&probe);
        CHECK(frame_with_loader(sky_osmesa_loader(), profiles[k], full) == 0, "the full loader's frame");
        CHECK(frame_with_loader(bare_wgl, profiles[k], bare) == 0, "a bare wglGetProcAddress's frame");
        CHECK(frame_with_loader(sentinel_wgl, profiles[k], sentinel) == 0, "a loader answering 1, 2, 3, -1");
        CHECK(memcmp(full, bare, sizeof full) == 0, "the bare loader's frame differs from the full loader's");
        CHECK(memcmp(full, sentinel, sizeof full) == 0, "the sentinel loader's frame differs");
        double sum = 0.0;
        for (size_t i = 0; i < sizeof full; i++) sum += full[i];
        CHECK(sum / sizeof full > 40.0, "the frame is a sky, not black (mean %.1f)", sum / sizeof full);
    }
}

/* ---- the DLL ------------------------------------------------------------------ */

/* sky.dll exports the public API and nothing of the library's inside. */
TEST(windows_dll_exports_only_the_api)
{
    char path[512];
    program("sky.dll", path, sizeof path);
    HMODULE dll = LoadLibraryA(path);
    CHECK(dll != NULL, "LoadLibrary(%s) failed (%lu)", path, (unsigned long)GetLastError());
    if (!dll) return;
    static const char *const api[] = {"sky_create", "sky_update", "sky_draw", "sky_destroy", "sky_get_lighting",
                                      "sky_default_params", "sky_compute_astronomy", "sky_last_error"};
    for (size_t i = 0; i < sizeof api / sizeof api[0]; i++)
        CHECK(GetProcAddress(dll, api[i]) != NULL, "sky.dll does not export %s", api[i]);
    static const char *const inside[] = {"sky_gl_system_proc", "sky_layer_table", "sky_layer_table_index"};
    for (size_t i = 0; i < sizeof inside / sizeof inside[0]; i++)
        CHECK(GetProcAddress(dll, inside[i]) == NULL, "sky.dll exports the internal %s", inside[i]);
    FreeLibrary(dll);
}

/* sky-render linked against sky.dll, and against the amalgamation compiled
 * by MinGW-w64, writes the static library's bytes. */
TEST(windows_dll_and_amalgamation_frames_match_static)
{
    static const char *const builds[2] = {"sky-render-dll.exe", "sky-render-amalgamation.exe"};
    char a[512], b[512], log[2048];
    tmp_path("static.png", a, sizeof a);
    int rc = render_preset("sky-render.exe", "sunset", "core", a, log, sizeof log);
    CHECK(rc == 0, "sky-render.exe exited %d: %s", rc, log);
    size_t na = 0;
    char *want = read_text_file(a, &na);
    for (int k = 0; k < 2; k++) {
        tmp_path("other.png", b, sizeof b);
        rc = render_preset(builds[k], "sunset", "core", b, log, sizeof log);
        CHECK(rc == 0, "%s exited %d: %s", builds[k], rc, log);
        size_t nb = 0;
        char *got = read_text_file(b, &nb);
        CHECK(want && got && na > 1000 && na == nb && memcmp(want, got, na) == 0,
              "%s's frame (%zu bytes) differs from the static library's (%zu bytes)", builds[k], nb, na);
        free(got);
        remove(b);
    }
    free(want);
    remove(a);
}

/* ---- the front end's files on Windows ---------------------------------------- */

/* rename over an existing file fails on Windows: the writer replaces it
 * (MoveFileEx), and a second render over the first succeeds. */
TEST(windows_render_replaces_an_existing_file)
{
    char out[512], log[2048];
    tmp_path("again.png", out, sizeof out);
    for (int run = 0; run < 2; run++) {
        int rc = render_preset("sky-render.exe", run ? "sunset" : "noon", "compat", out, log, sizeof log);
        CHECK(rc == 0, "render %d over %s exited %d: %s", run + 1, out, rc, log);
    }
    image im;
    CHECK(image_load_png(out, &im) == 0, "the replaced file is a PNG");
    if (im.px) image_free(&im);
    remove(out);
}

/* --out and --out-pfm naming one file are refused, where stat has no
 * inode numbers: by the file's volume and index (two hard links here). */
TEST(windows_out_and_pfm_one_file_refused)
{
    char prog[512], png[512], pfm[512], cmd[1600], log[2048];
    tmp_path("same.png", png, sizeof png);
    tmp_path("same.pfm", pfm, sizeof pfm);
    FILE *f = fopen(png, "wb");
    CHECK(f && fputs("an older image", f) >= 0 && fclose(f) == 0, "made %s", png);
    if (!CreateHardLinkA(pfm, png, NULL)) {
        CHECK(0, "CreateHardLink(%s, %s) failed (%lu)", pfm, png, (unsigned long)GetLastError());
        remove(png);
        return;
    }
    snprintf(cmd, sizeof cmd, "%s --preset noon --out %s --out-pfm %s 2>&1",
             program("sky-render.exe", prog, sizeof prog), png, pfm);
    int rc = run_command(cmd, log, sizeof log);
    CHECK(rc == 2 && strstr(log, "same file"), "--out %s --out-pfm %s (one file): exit %d, %s", png, pfm, rc, log);
    size_t n = 0;
    char *kept = read_text_file(png, &n);
    CHECK(kept && n == 14 && !memcmp(kept, "an older image", 14), "the refused run left the file as it was");
    free(kept);
    remove(pfm);
    remove(png);
}
