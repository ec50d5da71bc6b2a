/*
 * The test runner's small harness. A test is a function; CHECK records a
 * failure with its reason and the test goes on, so one run shows every
 * broken property. A test whose prerequisite was not built (the fast
 * tier, make check, builds no sanitizer programs) SKIPs instead of failing.
 * The runner prints "N passed, N failed" last, then ", N skipped" when any
 * were.
 */
#ifndef SKY_TEST_H
#define SKY_TEST_H

#include "sky.h"
#include "osmesa_ctx.h"

#include <stdio.h>

typedef struct test_case {
    const char *name;
    void (*fn)(void);
    int slow; /* SLOW_TEST: make test runs it, make check (--fast) not */
} test_case;

/* A test: TEST(name) { ... } defines test_name, which tests/list.sh finds
 * (at the start of a line) and the runner runs. SLOW_TEST: one that takes
 * a second or more, left out of make check's fast tier. */
#define TEST(name)               \
    void test_##name(void);      \
    void test_##name(void)
#define SLOW_TEST(name) TEST(name)

extern int test_failures; /* failures within the running test */
extern int test_skipped;  /* the running test could not run here */

#define CHECK(cond, ...)                                                   \
    do {                                                                   \
        if (!(cond)) {                                                     \
            test_failures++;                                               \
            printf("    %s:%d: check failed: %s\n      ", __FILE__, __LINE__, #cond); \
            printf(__VA_ARGS__);                                           \
            printf("\n");                                                  \
        }                                                                  \
    } while (0)

/* Marks the running test as skipped, with the reason; the test returns
 * right after. A skip is counted neither as passed nor as failed. */
#define SKIP(...)             \
    do {                      \
        test_skipped = 1;     \
        printf("    skip: "); \
        printf(__VA_ARGS__);  \
        printf("\n");         \
    } while (0)

/* Prints a measurement that belongs in the test log. */
#define NOTE(...)            \
    do {                     \
        printf("    note: "); \
        printf(__VA_ARGS__); \
        printf("\n");        \
    } while (0)

/* ---- shared fixtures (test_main.c) ---------------------------------------- */

/* An image read back from a render: linear floats (HDR) or 8-bit sRGB
 * values scaled to 0..1; rows top first; 3 channels. */
typedef struct image {
    int w, h;
    float *px;
} image;

typedef struct scene {
    sky_config cfg;     /* get_proc_address and output are filled in   */
    sky_params params;
    double seconds;
    int fisheye;
    double yaw, pitch, fov;
    int w, h;
    float exposure_bias; /* stops (sky_set_exposure_bias) */
    int has_observer;   /* 0: the sky's default observer */
    sky_observer observer;
} scene;

scene scene_default(void);
/* Renders a scene in a fresh OSMesa context. hdr: float buffer + linear
 * output. want: the context kind. Returns 0, or -1 (message printed). */
int render_scene(const scene *sc, int hdr, sky_gl_profile want, image *out);
void image_free(image *im);
float image_luminance(const image *im, int x, int y);
/* The camera of a scene as sky-render builds it. */
void scene_camera(const scene *sc, float view[16], float proj[16]);
/* Where a horizon direction (degrees) lands in the scene's image, in
 * pixels from the top left; -1 behind the camera. */
int scene_project(const scene *sc, double alt_deg, double az_deg, double *px, double *py);
/* Luminance-weighted centroid of the brightest blob within r px of
 * (cx, cy); returns its peak. */
double image_blob(const image *im, double cx, double cy, int r, double *bx, double *by);
/* The luminance within radius px of the centre of an n x n RGBA float
 * image (rows bottom first or top first alike), less the median of the
 * ring 2-6 px outside it: a point's light in pixel units. */
double image_centre_sum(const float *rgba, int n, int radius);

/* A small OSMesa context and a sky in it (base: config or NULL for the
 * defaults; the loader and profile are filled in). */
typedef struct fixture {
    sky_osmesa ctx;
    sky *s;
} fixture;
int fixture_open(fixture *f, sky_gl_profile profile, const sky_config *base);
/* The same at w x h, with a float framebuffer (HDR output) or not. */
int fixture_open_sized(fixture *f, int w, int h, int float_buffer, sky_gl_profile profile, const sky_config *base);
/* The equator at the 2026 March equinox: the time slider sweeps the sun
 * from the nadir (0) through the zenith (0.5) with declination ~0. */
sky_observer equator_equinox(void);
void fixture_close(fixture *f);

/* Every atmosphere path and its name, in sky.h's order (test_lighting.c). */
#define TEST_PATHS 5
extern const sky_atmosphere_path test_paths[TEST_PATHS];
extern const char *const test_path_names[TEST_PATHS];
/* tools/atmo_error.h's HDR cube around the observer, for a path (the
 * photometry's config: defaults, core profile) with features (0: none,
 * or SKY_CLOUDS); NULL after a failed CHECK naming the path. */
typedef struct sky_atmo_hemisphere sky_atmo_hemisphere;
sky_atmo_hemisphere *hemisphere_open(sky_atmosphere_path path, unsigned features);

/* A host's own program (test_api.c): white, its attribute 0 "p" the clip
 * position (a vec4: give it x, y, z and GL supplies w = 1). */
unsigned test_host_program(int core);
/* A host's program with a snippet of the library's (NULL for none)
 * between its #version line and body, which writes FRAG; attribute 0
 * "p" as above. A fragment stage that does not compile is a failed CHECK
 * with its log. */
unsigned test_snippet_program(int core, const char *snippet, const char *body);
/* A triangle over the whole viewport on attribute 0 (with a VAO in the
 * core profile); test_fullscreen_free deletes them. */
void test_fullscreen_triangle(int core, unsigned *vao, unsigned *buf);
void test_fullscreen_free(unsigned vao, unsigned buf);

/* A named weather state's numbers (test_weather.c). */
sky_weather weather_preset(sky_weather_state state);
/* The optics' tests (test_rainbow.c, test_halo.c): an HDR frame (width x
 * height x 3 floats, rows bottom first) of weather w at the time slider's
 * time and latitude, from yaw and pitch with a 90-degree field, with the
 * optics feature bit given (or 0) over clouds, sun and weather; *drawn
 * (if asked): whether the layer named was drawn. 0, or -1 when no frame.
 * optics_pixel_dir: a pixel's unit direction for such a camera. */
int optics_frame(unsigned optics, const char *layer, const sky_weather *w, float time, double latitude, double yaw,
                 double pitch, sky_gl_profile profile, int width, int height, float *rgb, sky_lighting *light,
                 int *drawn);
void optics_pixel_dir(const float view[16], const float proj[16], int width, int height, int x, int y, double d[3]);

/* Path of a built program (SKY_BIN or build/bin). */
/* A file's whole text (NUL-terminated; free it), or NULL; *len its size
 * when len is given. */
char *read_text_file(const char *path, size_t *len);
const char *bin_path(const char *name, char *buf, size_t len);
/* A file name of this run's own in TMPDIR (or /tmp): sky-test-PID-name. */
const char *tmp_path(const char *name, char *buf, size_t len);
/* Runs a shell command, returns its exit status; output into buf. */
int run_command(const char *cmd, char *buf, size_t len);
/* Reads a PNG/PFM written by sky-render. */
int image_load_png(const char *path, image *out);
/* PSNR in dB of two images of the same size (values 0..1; 99 when equal). */
double image_psnr(const image *a, const image *b);

#endif
