/*
 * sky-bench: what the sky costs, as medians and as ratios to a baseline
 * measured in the same run — a full-screen quad with one texture fetch,
 * the cheapest thing a sky could possibly be.
 *
 *   sky-bench [--json] [--size WxH] [--frames N] [--reference FILE] [--only-atmosphere | --only-presets]
 *             [--plot FILE.png]
 *   sky-bench --stability [--json]
 *   sky-bench --make-reference FILE [--paths N]
 *
 * Prints, per scene preset and GL profile: GPU bytes, textures, programs,
 * draws, frame ms (median of N) and its ratio to the baseline of the same
 * profile; then, per atmosphere path, setting and profile: frame ms of the
 * sky (atmosphere + sun), its ratio to the baseline, LUT build ms, and its
 * error against the cached CPU reference (tools/atmo_error.c).
 */
#define GL_GLEXT_PROTOTYPES 1
#include "atmo_error.h"
#include "cli.h"
#include "osmesa_ctx.h"
#include "plot.h"
#include "stability.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The baseline: one full-screen triangle strip, one RGBA8 512x512 texture
 * fetch per pixel, written straight out. */
static double baseline_ms(int core, int frames)
{
    const char *vs = core ? "#version 330 core\nin vec2 p;\nout vec2 uv;\n"
                            "void main(){uv=p*0.5+0.5;gl_Position=vec4(p,0.0,1.0);}\n"
                          : "#version 110\nattribute vec2 p;\nvarying vec2 uv;\n"
                            "void main(){uv=p*0.5+0.5;gl_Position=vec4(p,0.0,1.0);}\n";
    const char *fs = core ? "#version 330 core\nin vec2 uv;\nuniform sampler2D t;\nout vec4 c;\n"
                            "void main(){c=texture(t,uv*3.0);}\n"
                          : "#version 110\nvarying vec2 uv;\nuniform sampler2D t;\n"
                            "void main(){gl_FragColor=texture2D(t,uv*3.0);}\n";
    GLuint v = glCreateShader(GL_VERTEX_SHADER), f = glCreateShader(GL_FRAGMENT_SHADER), p = glCreateProgram();
    glShaderSource(v, 1, &vs, NULL);
    glShaderSource(f, 1, &fs, NULL);
    glCompileShader(v);
    glCompileShader(f);
    glAttachShader(p, v);
    glAttachShader(p, f);
    glBindAttribLocation(p, 0, "p");
    glLinkProgram(p);
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) return -1.0;
    unsigned char *texels = malloc(512 * 512 * 4);
    for (int i = 0; i < 512 * 512 * 4; i++) texels[i] = (unsigned char)(i * 2654435761u >> 24);
    GLuint tex, buf, vao = 0;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 512, 512, 0, GL_RGBA, GL_UNSIGNED_BYTE, texels);
    free(texels);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    if (core) {
        glGenVertexArrays(1, &vao);
        glBindVertexArray(vao);
    }
    static const float quad[8] = {-1, -1, 1, -1, -1, 1, 1, 1};
    glGenBuffers(1, &buf);
    glBindBuffer(GL_ARRAY_BUFFER, buf);
    glBufferData(GL_ARRAY_BUFFER, sizeof quad, quad, GL_STATIC_DRAW);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, (const void *)0);
    glEnableVertexAttribArray(0);
    glUseProgram(p);
    glUniform1i(glGetUniformLocation(p, "t"), 0);
    double *t = malloc(sizeof(double) * (size_t)frames);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4); /* warm-up: shader JIT */
    glFinish();
    for (int i = 0; i < frames; i++) {
        double t0 = sky_cli_now_ms();
        glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
        glFinish();
        t[i] = sky_cli_now_ms() - t0;
    }
    double m = sky_cli_median(t, frames);
    free(t);
    glDisableVertexAttribArray(0);
    glDeleteBuffers(1, &buf);
    if (core) glDeleteVertexArrays(1, &vao);
    glDeleteTextures(1, &tex);
    glDeleteProgram(p);
    glDeleteShader(v);
    glDeleteShader(f);
    return m;
}

typedef struct row {
    const char *preset;
    const char *profile;
    double frame_ms, ratio;
    double layer_ms[SKY_LAYER_COUNT]; /* medians with profile_layers, -1 if never drawn alone */
    double lut_start_ms, lut_rebuild_ms; /* tables built by creation; a rebuild after the sun moved */
    sky_stats st;
} row;

/* Median frame ms of the scene described by command-line style options. */
static int bench_args(int argc, char **argv, const char *name, sky_gl_profile gl, int w, int h, int frames, row *out)
{
    sky_cli cli;
    char err[512];
    if (sky_cli_parse(&cli, argc, argv, 0, err, sizeof err)) {
        fprintf(stderr, "sky-bench: %s\n", err);
        return -1;
    }
    cli.gl = gl;
    cli.width = w;
    cli.height = h;
    sky_config cfg = sky_cli_config(&cli, sky_osmesa_loader());
    sky *s = sky_create(&cfg, err, sizeof err);
    if (!s) {
        fprintf(stderr, "sky-bench: %s: %s\n", name, err);
        return -1;
    }
    sky_set_params(s, &cli.params);
    sky_set_observer(s, &cli.observer);
    float view[16], proj[16];
    sky_cli_camera(&cli, view, proj);
    /* per-layer GPU time: a second sky with profile_layers (it waits for
     * the GPU around each draw, so it is kept out of the frame timing) */
    sky_config pcfg = cfg;
    pcfg.profile_layers = 1;
    sky *ps = sky_create(&pcfg, err, sizeof err);
    double *lt = malloc(sizeof(double) * (size_t)frames * SKY_LAYER_COUNT);
    for (int l = 0; l < SKY_LAYER_COUNT; l++) out->layer_ms[l] = -1.0;
    if (ps && lt) {
        sky_set_params(ps, &cli.params);
        sky_set_observer(ps, &cli.observer);
        sky_draw(ps, view, proj);
        int n[SKY_LAYER_COUNT] = {0};
        for (int i = 0; i < frames; i++) {
            sky_draw(ps, view, proj);
            sky_stats st;
            sky_get_stats(ps, &st);
            for (int l = 0; l < SKY_LAYER_COUNT; l++)
                if (st.layers[l].ms >= 0.0) lt[l * frames + n[l]++] = st.layers[l].ms;
        }
        for (int l = 0; l < SKY_LAYER_COUNT; l++)
            if (n[l]) out->layer_ms[l] = sky_cli_median(lt + l * frames, n[l]);
    }
    /* a table rebuild, on the profiling sky (its GPU builds are timed to
     * completion): the sun moved 0.36 degree a frame, past every rebuild
     * threshold; CPU builds happen in sky_set_params, GPU builds in sky_draw */
    out->lut_rebuild_ms = 0.0;
    if (ps && lt) {
        sky_params moved = cli.params;
        int n = frames < 10 ? frames : 10;
        for (int i = 0; i < n; i++) {
            moved.time = cli.params.time + 0.001f * (float)(i + 1);
            sky_set_params(ps, &moved);
            sky_draw(ps, view, proj);
            sky_stats st;
            sky_get_stats(ps, &st);
            lt[i] = st.lut_ms;
        }
        out->lut_rebuild_ms = sky_cli_median(lt, n);
    }
    free(lt);
    sky_destroy(ps);
    double *t = malloc(sizeof(double) * (size_t)frames);
    sky_draw(s, view, proj); /* warm-up: shader JIT */
    glFinish();
    /* lookup tables: what creation built (reported by the first draw) */
    sky_stats first;
    sky_get_stats(s, &first);
    out->lut_start_ms = first.lut_ms;
    for (int i = 0; i < frames; i++) {
        sky_update(s, 1.0 / 60.0);
        double t0 = sky_cli_now_ms();
        sky_draw(s, view, proj);
        glFinish();
        t[i] = sky_cli_now_ms() - t0;
    }
    out->frame_ms = sky_cli_median(t, frames);
    free(t);
    sky_get_stats(s, &out->st);
    out->preset = name;
    out->profile = gl == SKY_GL_CORE33 ? "core" : "compat";
    sky_destroy(s);
    return 0;
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

static int bench_preset(const char *preset, sky_gl_profile gl, int w, int h, int frames, row *out)
{
    char *argv[] = {"sky-bench", "--preset", (char *)preset, NULL};
    return bench_args(3, argv, preset, gl, w, h, frames, out);
}

/* Mueller's night layers on their own: the frame with the layer minus the
 * frame without it. Stars and star map on an August night with the Milky
 * Way up; the moon (full, 2024-06-22, looked at) at c_d 3 and 30. */
enum { NIGHT_NONE, NIGHT_STARS, NIGHT_STARMAP, NIGHT_MOON_NONE, NIGHT_MOON3, NIGHT_MOON30, NIGHT_COUNT };
/* the stars and the moon are draws of their own: their GPU time is
 * measured directly; the star map lives in the dome pass: by difference */
static int bench_night(sky_gl_profile gl, int w, int h, int frames, double out_ms[NIGHT_COUNT])
{
    static const char *features[3] = {"none", "stars", "starmap"};
    row r;
    for (int i = 0; i < 3; i++) {
        char *argv[] = {"sky-bench", "--features", (char *)features[i], "--date", "2024-08-10T21:00:00Z",
                        "--lat", "45", "--yaw", "180", "--pitch", "30", NULL};
        if (bench_args(11, argv, features[i], gl, w, h, frames, &r)) return -1;
        out_ms[i] = i == 1 ? r.layer_ms[SKY_LAYER_STARS] : r.frame_ms;
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
    double frame_ms, ratio, lut_start_ms, lut_rebuild_ms;
    sky_atmo_errors err;
} atmo_row;

/* A setting's options after the given leading ones; returns argc. */
static int setting_argv(const atmo_setting *a, char **argv, int argc)
{
    for (int i = 0; i < 6 && a->args[i]; i++) argv[argc++] = (char *)a->args[i];
    return argc;
}

/* One setting in one profile: the frame of the full sky's atmosphere and
 * sun at the bench size (the default camera of sky-render, morning sun). */
static int bench_atmosphere(const atmo_setting *a, sky_gl_profile gl, int w, int h, int frames, double baseline,
                            atmo_row *out)
{
    char *argv[12] = {"sky-bench", "--features", "sun", "--time", "0.35"};
    int argc = setting_argv(a, argv, 5);
    row r;
    if (bench_args(argc, argv, a->path, gl, w, h, frames, &r)) return -1;
    out->setting = a;
    out->profile = gl == SKY_GL_CORE33 ? "core" : "compat";
    out->frame_ms = r.frame_ms;
    out->ratio = r.frame_ms / baseline;
    out->lut_start_ms = r.lut_start_ms;
    out->lut_rebuild_ms = r.lut_rebuild_ms;
    return 0;
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
    printf("| path | setting | profile | frame ms | x baseline | LUT ms at start | sky-view rebuild ms | "
           "mean rel err day | max rel err day | mean rel err twilight | mean dE2000 day |\n"
           "|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (int i = 0; i < n; i++)
        printf("| %s | %s | %s | %.2f | %.2f | %.1f | %.1f | %.1f %% | %.0f %% | %.0f %% | %.1f |\n",
               rows[i].setting->path, rows[i].setting->setting, rows[i].profile, rows[i].frame_ms, rows[i].ratio,
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

static void print_preset_table(const row *rows, int nrows)
{
    printf("| preset | profile | GPU bytes | textures | programs | draws | frame ms | x baseline |\n");
    printf("|---|---|---|---|---|---|---|---|\n");
    for (int i = 0; i < nrows; i++)
        printf("| %s | %s | %zu | %d | %d | %d | %.2f | %.2f |\n", rows[i].preset, rows[i].profile,
               rows[i].st.gpu_bytes, rows[i].st.textures, rows[i].st.programs, rows[i].st.draws_per_frame,
               rows[i].frame_ms, rows[i].ratio);
}

int main(int argc, char **argv)
{
    int json = 0, w = 1280, h = 720, frames = 20, stability = 0, paths = 1024, only_atmosphere = 0, only_presets = 0;
    const char *make_reference = NULL, *reference = "tests/data/atmosphere_reference.txt", *plot = NULL;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--json"))
            json = 1;
        else if (!strcmp(argv[i], "--only-atmosphere"))
            only_atmosphere = 1;
        else if (!strcmp(argv[i], "--only-presets"))
            only_presets = 1;
        else if (!strcmp(argv[i], "--make-reference") && i + 1 < argc)
            make_reference = argv[++i];
        else if (!strcmp(argv[i], "--reference") && i + 1 < argc)
            reference = argv[++i];
        else if (!strcmp(argv[i], "--plot") && i + 1 < argc)
            plot = argv[++i];
        else if (!strcmp(argv[i], "--paths") && i + 1 < argc && (paths = atoi(argv[i + 1])) >= 1 && paths <= 1000000)
            i++;
        else if (!strcmp(argv[i], "--stability"))
            stability = 1;
        else if (!strcmp(argv[i], "--size") && i + 1 < argc && sscanf(argv[i + 1], "%dx%d", &w, &h) == 2 && w > 0 &&
                 h > 0 && w <= 8192 && h <= 8192)
            i++;
        else if (!strcmp(argv[i], "--frames") && i + 1 < argc && (frames = atoi(argv[i + 1])) >= 3 && frames <= 10000)
            i++;
        else {
            fprintf(stderr, "sky-bench: bad argument '%s'\nusage: sky-bench [--json] [--size WxH] [--frames N>=3] "
                    "[--reference FILE] [--only-atmosphere | --only-presets] [--plot FILE.png]\n"
                    "       sky-bench --stability [--json]\n"
                    "       sky-bench --make-reference FILE [--paths N]\n",
                    argv[i]);
            return 2;
        }
    }
    if (stability) return stability_table(json);
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
    char ref_err[512];
    if (sky_atmo_reference_load(reference, &ref, ref_err, sizeof ref_err)) {
        fprintf(stderr, "sky-bench: %s\n", ref_err);
        return 1;
    }
    atmo_row atmo[2 * ATMO_SETTINGS];
    int natmo = 0;
    static const char *presets[] = {"minimal", "noon", "overcast", "sunset", "starry", "moonlit", "eclipse", "solar-eclipse"};
    enum { NP = sizeof presets / sizeof presets[0] };
    row rows[2 * NP];
    double base[2] = {0, 0}, night[2][NIGHT_COUNT];
    int nrows = 0;
    for (int prof = 0; prof < 2; prof++) {
        sky_gl_profile gl = prof == 0 ? SKY_GL_CORE33 : SKY_GL_COMPAT20;
        char err[512];
        sky_osmesa ctx;
        if (sky_osmesa_create(&ctx, w, h, gl, 0, err, sizeof err)) {
            fprintf(stderr, "sky-bench: %s\n", err);
            return 1;
        }
        base[prof] = baseline_ms(prof == 0, frames);
        if (base[prof] <= 0) {
            fprintf(stderr, "sky-bench: baseline shader failed\n");
            return 1;
        }
        for (int p = 0; p < NP && !only_atmosphere; p++) {
            if (bench_preset(presets[p], gl, w, h, frames, &rows[nrows])) return 1;
            rows[nrows].ratio = rows[nrows].frame_ms / base[prof];
            nrows++;
        }
        if (only_presets) {
            sky_osmesa_destroy(&ctx);
            continue;
        }
        if (!only_atmosphere && bench_night(gl, w, h, frames, night[prof])) return 1;
        for (int a = 0; a < ATMO_SETTINGS; a++)
            if (bench_atmosphere(&atmo_settings[a], gl, w, h, frames, base[prof], &atmo[natmo + a])) return 1;
        sky_osmesa_destroy(&ctx);
        for (int a = 0; a < ATMO_SETTINGS; a++)
            if (measure_atmosphere(&atmo[natmo + a], &ref, gl)) return 1;
        natmo += ATMO_SETTINGS;
    }
    if (only_presets) {
        printf("baseline (one-texture full-screen quad, %dx%d): core %.2f ms, compat %.2f ms\n", w, h, base[0], base[1]);
        print_preset_table(rows, nrows);
        return 0;
    }
    if (only_atmosphere) {
        if (plot && plot_atmosphere(plot, atmo, natmo)) return 1;
        printf("baseline (one-texture full-screen quad, %dx%d): core %.2f ms, compat %.2f ms\n", w, h, base[0], base[1]);
        print_atmosphere_table(atmo, natmo, &ref);
        return 0;
    }
    if (plot && plot_atmosphere(plot, atmo, natmo)) return 1;
    double astro = astro_us(2000);
    if (json) {
        printf("{\"size\":\"%dx%d\", \"frames\":%d, \"astro_update_us\":%.2f,\n"
               " \"baseline\": {\"frame_ms\":%.4f, \"compat_frame_ms\":%.4f},\n"
               " \"presets\": [\n",
               w, h, frames, astro, base[0], base[1]);
        for (int i = 0; i < nrows; i++)
            printf("  {\"preset\":\"%s\", \"profile\":\"%s\", \"gpu_bytes\":%zu, \"textures\":%d, \"programs\":%d, "
                   "\"draws\":%d, \"frame_ms\":%.4f, \"ratio\":%.3f}%s\n",
                   rows[i].preset, rows[i].profile, rows[i].st.gpu_bytes, rows[i].st.textures, rows[i].st.programs,
                   rows[i].st.draws_per_frame, rows[i].frame_ms, rows[i].ratio, i + 1 < nrows ? "," : "");
        printf(" ],\n \"night_layers\": [\n");
        for (int prof = 0; prof < 2; prof++)
            printf("  {\"profile\":\"%s\", \"stars_ms\":%.4f, \"starmap_ms\":%.4f, \"moon_cd3_ms\":%.4f, "
                   "\"moon_cd30_ms\":%.4f}%s\n",
                   prof ? "compat" : "core", night[prof][NIGHT_STARS], night[prof][NIGHT_STARMAP] - night[prof][NIGHT_NONE],
                   night[prof][NIGHT_MOON3], night[prof][NIGHT_MOON30], prof ? "" : ",");
        printf(" ],\n \"reference\": {\"method\":\"spectral, 16 wavelengths; single scattering by quadrature, orders >= 2 "
               "by Monte Carlo\", \"paths\":%d, \"std_err\":%.6g},\n \"rows\": [\n",
               ref.paths, reference_rel_std_err(&ref));
        for (int i = 0; i < natmo; i++) {
            const atmo_row *r = &atmo[i];
            printf("  {\"path\":\"%s\", \"setting\":\"%s\", \"profile\":\"%s\", \"frame_ms\":%.4f, \"ratio\":%.3f, "
                   "\"lut_ms\":%.4f, \"lut_rebuild_ms\":%.4f, \"mean_rel_err_day\":%.5f, \"max_rel_err_day\":%.5f, "
                   "\"mean_rel_err_twilight\":%.5f, \"mean_de2000_day\":%.4f, \"mean_rel_err_by_elevation\":[",
                   r->setting->path, r->setting->setting, r->profile, r->frame_ms, r->ratio, r->lut_start_ms,
                   r->lut_rebuild_ms,
                   r->err.mean_rel_day, r->err.max_rel_day, r->err.mean_rel_twilight, r->err.mean_de2000_day);
            for (int s = 0; s < SKY_ATMO_SUNS; s++) printf("%.5f%s", r->err.mean_rel[s], s + 1 < SKY_ATMO_SUNS ? "," : "");
            printf("]}%s\n", i + 1 < natmo ? "," : "");
        }
        printf(" ]}\n");
        return 0;
    }
    printf("sky-bench: %dx%d, median of %d frames, llvmpipe or whatever GL OSMesa provides\n", w, h, frames);
    printf("baseline (one-texture full-screen quad): core %.2f ms, compat %.2f ms\n", base[0], base[1]);
    printf("astronomy: %.1f us of CPU per full update (median of 2000; time slider mode)\n\n", astro);
    print_preset_table(rows, nrows);
    printf("\nMueller's night layers: the stars' and the moon's own draw (GPU time around it), the star map as\n"
           "what it adds to an atmosphere-only night frame:\n\n");
    printf("| layer | profile | ms | x baseline |\n|---|---|---|---|\n");
    static const char *names[NIGHT_COUNT] = {"", "8874 catalogue stars", "star map", "", "moon, c_d 3", "moon, c_d 30"};
    /* -1: measured directly, else the frame it is the difference from */
    static const int from[NIGHT_COUNT] = {0, -1, NIGHT_NONE, 0, -1, -1};
    for (int prof = 0; prof < 2; prof++)
        for (int k = 0; k < NIGHT_COUNT; k++) {
            if (!names[k][0]) continue;
            double ms = from[k] < 0 ? night[prof][k] : night[prof][k] - night[prof][from[k]];
            printf("| %s | %s | %.2f | %.2f |\n", names[k], prof ? "compat" : "core", ms, ms / base[prof]);
        }
    print_atmosphere_table(atmo, natmo, &ref);
    return 0;
}
