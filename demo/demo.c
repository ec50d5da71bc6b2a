/*
 * sky-demo: the sky in a GLFW window (OpenGL 3.3 core, else 2.0; or ES 2.0 with --gl es20), steered
 * by Roden & Parberry's six sliders drawn over it (drag them, or 1-6 and
 * Up/Down). Space runs the time of day, +/- its speed; C U M K T P E
 * toggle the layers, A the atmosphere path, G the GL profile; right-drag
 * looks around, Left/Right turn, the wheel zooms; L times each layer; S
 * saves sky-demo.png. --help lists it all.
 * Without a display it says so and renders headless through OSMesa.
 * Built with Emscripten (make web) it runs in a browser's WebGL 1 canvas,
 * a frame each time the browser asks (demo_frame), with no files: the
 * page (web/shell.html) passes its options and picks presets.
 */
#include "cli.h"
#ifndef __EMSCRIPTEN__
#include "osmesa_ctx.h"
#endif
#include "ui.h"

#define GLFW_INCLUDE_GLEXT /* the query entry points' types and enums */
#include <GLFW/glfw3.h>
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef __EMSCRIPTEN__
#include <emscripten.h>
#endif

#ifndef __EMSCRIPTEN__
/* out: the PNG to write (relative to the current directory, so an
 * installed sky-demo works anywhere). */
static int headless(const sky_cli *cli, const char *out)
{
    char err[512];
    sky_osmesa ctx;
    if (sky_osmesa_create(&ctx, cli->width, cli->height, cli->gl, 0, err, sizeof err)) {
        fprintf(stderr, "sky-demo: %s\n", err);
        return 1;
    }
    sky_config cfg = sky_cli_config(cli, sky_headless_loader(&ctx));
    sky *s = sky_create(&cfg, err, sizeof err);
    if (!s) {
        fprintf(stderr, "sky-demo: %s\n", err);
        sky_osmesa_destroy(&ctx);
        return 1;
    }
    float view[16], proj[16];
    sky_cli_camera(cli, view, proj);
    sky_cli_apply(s, cli);
    int rc = 0;
    for (int f = 0; f < cli->frames && !rc; f++) {
        if (f) sky_update(s, 1.0 / 30.0);
        if ((cli->fisheye ? sky_draw_fisheye(s) : sky_draw(s, view, proj)) < 0) {
            fprintf(stderr, "sky-demo: %s\n", sky_last_error(s));
            rc = 1;
        }
    }
    sky_osmesa_finish(&ctx);
    if (!rc && sky_osmesa_write_png(&ctx, out, NULL, 0)) {
        fprintf(stderr, "sky-demo: cannot write %s\n", out);
        rc = 1;
    }
    if (!rc) printf("sky-demo: no display; rendered %s headless\n", out);
    sky_destroy(s);
    sky_osmesa_destroy(&ctx);
    return rc;
}
#else
/* A browser always has its canvas. */
static int headless(const sky_cli *cli, const char *out)
{
    (void)cli;
    fprintf(stderr, "sky-demo: no WebGL canvas for %s\n", out);
    return 1;
}
#endif

/* ---- the readout's frame time: the GPU time of the sky's frame ---------------------------------
 *
 * What sky-bench measures: the time from issuing sky_draw to the end of its
 * rendering, as the median of recent frames. Where the context has timer
 * queries (GL 3.3 or ARB_timer_query) a GL_TIME_ELAPSED query wraps
 * sky_draw and is read two frames later, when it is done, so the frame
 * does not wait for it. But a query is only trusted once the first frames
 * have been measured both ways: llvmpipe (Mesa 22) reports about 0.02 ms
 * for a 17 ms frame, the time to bin the draws rather than to rasterise
 * them. Where there are no queries, or they disagree with the clock, each
 * frame waits with glFinish before and after sky_draw and is timed by the
 * clock, exactly as sky-bench does. The first frame of a sky is not
 * counted (sky-bench draws once before it times: shaders are compiled at
 * the first draw). */
enum { TIMER_RING = 4, TIMER_LAG = 2, TIMER_SAMPLES = 30, TIMER_CALIBRATE = 3 };
enum { TIMER_CALIBRATING, TIMER_QUERY, TIMER_FINISH };

typedef struct frame_timer {
    int mode;
    GLuint q[TIMER_RING];
    unsigned frame;          /* sky frames timed since the last reset */
    int warm;                /* the first frame of a sky (shader compilation) is behind us */
    double calib_query[TIMER_CALIBRATE], calib_wall[TIMER_CALIBRATE];
    double samples[TIMER_SAMPLES];
    int count, next;
    double t0;               /* the frame in progress (glFinish mode), ms */
    double ticks[TIMER_SAMPLES]; /* when the last frames were shown, s */
    int nticks, next_tick;
    PFNGLGENQUERIESPROC gen_queries;
    PFNGLDELETEQUERIESPROC delete_queries;
    PFNGLBEGINQUERYPROC begin_query;
    PFNGLENDQUERYPROC end_query;
    PFNGLGETQUERYOBJECTIVPROC query_iv;
    PFNGLGETQUERYOBJECTUI64VPROC query_ui64v;
} frame_timer;

/* For the current context. */
static void timer_init(frame_timer *t, GLFWwindow *w)
{
    memset(t, 0, sizeof *t);
    t->mode = TIMER_FINISH;
    int major = glfwGetWindowAttrib(w, GLFW_CONTEXT_VERSION_MAJOR);
    int minor = glfwGetWindowAttrib(w, GLFW_CONTEXT_VERSION_MINOR);
    if (major * 10 + minor < 33 && !glfwExtensionSupported("GL_ARB_timer_query")) return;
    t->gen_queries = (PFNGLGENQUERIESPROC)glfwGetProcAddress("glGenQueries");
    t->delete_queries = (PFNGLDELETEQUERIESPROC)glfwGetProcAddress("glDeleteQueries");
    t->begin_query = (PFNGLBEGINQUERYPROC)glfwGetProcAddress("glBeginQuery");
    t->end_query = (PFNGLENDQUERYPROC)glfwGetProcAddress("glEndQuery");
    t->query_iv = (PFNGLGETQUERYOBJECTIVPROC)glfwGetProcAddress("glGetQueryObjectiv");
    t->query_ui64v = (PFNGLGETQUERYOBJECTUI64VPROC)glfwGetProcAddress("glGetQueryObjectui64v");
    if (!t->gen_queries || !t->delete_queries || !t->begin_query || !t->end_query || !t->query_iv || !t->query_ui64v)
        return;
    t->gen_queries(TIMER_RING, t->q);
    t->mode = TIMER_CALIBRATING;
}

/* Before the context goes. */
static void timer_destroy(frame_timer *t)
{
    if (t->q[0]) t->delete_queries(TIMER_RING, t->q);
    memset(t, 0, sizeof *t);
}

/* A new sky: its own figures from now on (queries in flight are dropped). */
static void timer_reset(frame_timer *t)
{
    t->count = t->next = 0;
    t->frame = 0;
    t->warm = 0;
}

static void timer_sample(frame_timer *t, double ms)
{
    t->samples[t->next] = ms;
    t->next = (t->next + 1) % TIMER_SAMPLES;
    if (t->count < TIMER_SAMPLES) t->count++;
}

static double median3(double *v)
{
    double a = v[0], b = v[1], c = v[2];
    return a < b ? (b < c ? b : a < c ? c : a) : (a < c ? a : b < c ? c : b);
}

static void timer_begin(frame_timer *t)
{
    if (t->mode != TIMER_QUERY) {
        glFinish(); /* nothing earlier is counted */
        t->t0 = glfwGetTime() * 1e3;
    }
    if (t->mode != TIMER_FINISH) t->begin_query(GL_TIME_ELAPSED, t->q[t->frame % TIMER_RING]);
}

static void timer_end(frame_timer *t)
{
    if (t->mode != TIMER_FINISH) t->end_query(GL_TIME_ELAPSED);
    if (t->mode == TIMER_QUERY) {
        /* the query of TIMER_LAG frames ago, if the GPU has got there */
        if (t->frame >= TIMER_LAG) {
            GLuint q = t->q[(t->frame - TIMER_LAG) % TIMER_RING];
            GLint ready = 0;
            t->query_iv(q, GL_QUERY_RESULT_AVAILABLE, &ready);
            GLuint64 ns = 0;
            if (ready) {
                t->query_ui64v(q, GL_QUERY_RESULT, &ns);
                if (t->frame > TIMER_LAG) timer_sample(t, (double)ns * 1e-6); /* not the first frame's */
            }
        }
    } else {
        glFinish();
        double wall = glfwGetTime() * 1e3 - t->t0;
        if (!t->warm) { /* as sky-bench, which draws once before it times */
            t->warm = 1;
            return;
        }
        timer_sample(t, wall);
        if (t->mode == TIMER_CALIBRATING) {
            /* done (we waited): reading the query does not stall */
            GLuint64 ns = 0;
            t->query_ui64v(t->q[t->frame % TIMER_RING], GL_QUERY_RESULT, &ns);
            t->calib_query[t->frame] = (double)ns * 1e-6;
            t->calib_wall[t->frame] = wall;
            if (t->frame + 1 == TIMER_CALIBRATE) {
                /* the query must see at least half of what the clock saw;
                 * where it does not (or a tiny frame is mostly the clock's
                 * overhead), the clock stays: slower, never wrong */
                double q = median3(t->calib_query), c = median3(t->calib_wall);
                t->mode = q >= 0.5 * c ? TIMER_QUERY : TIMER_FINISH;
                t->frame = 0; /* the ring starts over */
                return;
            }
        }
    }
    t->frame++;
}

/* Once per displayed frame. */
static void timer_tick(frame_timer *t)
{
    t->ticks[t->next_tick] = glfwGetTime();
    t->next_tick = (t->next_tick + 1) % TIMER_SAMPLES;
    if (t->nticks < TIMER_SAMPLES) t->nticks++;
}

/* Frames per second over the last TIMER_SAMPLES frames shown, or 0. */
static double timer_fps(const frame_timer *t)
{
    if (t->nticks < 2) return 0.0;
    double newest = t->ticks[(t->next_tick + TIMER_SAMPLES - 1) % TIMER_SAMPLES];
    double oldest = t->ticks[(t->next_tick + TIMER_SAMPLES - t->nticks) % TIMER_SAMPLES];
    return newest > oldest ? (t->nticks - 1) / (newest - oldest) : 0.0;
}

/* The median of the recent frames, or -1 before the first. */
static double timer_ms(const frame_timer *t)
{
    if (!t->count) return -1.0;
    double v[TIMER_SAMPLES];
    memcpy(v, t->samples, sizeof(double) * (size_t)t->count);
    return sky_cli_median(v, t->count);
}

static const char *timer_method(const frame_timer *t)
{
    /* while calibrating, the figures are the clock's around glFinish */
    return t->mode == TIMER_QUERY ? "timer query" : "glFinish";
}

typedef struct demo {
    sky_cli cli;
    sky *s;
    ui *overlay;
    int slider;       /* 0..5 */
    int running;      /* the time of day advancing */
    double time_rate; /* slider units per second while running */
    int save;
    int profiling;
    int looking;      /* right button held: mouse-look */
    double last_x, last_y;
    unsigned features;
    int recreate;     /* features changed: build a new sky */
    double elapsed;   /* the animation clock, carried into every new sky */
    sky_atmosphere_path atmosphere; /* the path of the sky on screen */
    int switch_profile;
    float values[6];  /* the six sliders, in sky_params order */
    char message[200]; /* the last error, shown in the readout */
    frame_timer timer; /* the sky's GPU frame time and the frame rate */
    GLFWwindow *win;
    int kind;          /* the window's context: UI_GL20, UI_CORE33, UI_ES20 */
    int automated;     /* --screenshot: save after --frames and leave */
    const char *keys;  /* --keys: pressed after the first frame */
    int frame, status;
    double last;       /* the clock at the last frame */
    int weather;       /* the state W picked last (sky_weather_state), -1 none */
    int weather_pending; /* W pressed: set it on the sky (once it has SKY_WEATHER) */
    sky_weather weather_from; /* where W's change started, and when on the */
    double weather_since;     /* sky's running clock: a rebuilt sky replays it */
} demo;

static void values_from_params(float v[6], const sky_params *p)
{
    v[0] = p->cover, v[1] = p->height, v[2] = p->density, v[3] = p->sunset, v[4] = p->speed, v[5] = p->time;
}

static sky_params params_from_values(const float v[6])
{
    sky_params p = {v[0], v[1], v[2], v[3], v[4], v[5]};
    return p;
}

static void on_key(GLFWwindow *w, int key, int scancode, int action, int mods)
{
    (void)scancode;
    (void)mods;
    demo *d = glfwGetWindowUserPointer(w);
    if (action == GLFW_RELEASE) return;
    float *v = d->values;
    if (key >= GLFW_KEY_1 && key <= GLFW_KEY_6) d->slider = key - GLFW_KEY_1;
    if (key == GLFW_KEY_UP) v[d->slider] = v[d->slider] + 0.02f > 1.0f ? 1.0f : v[d->slider] + 0.02f;
    if (key == GLFW_KEY_DOWN) v[d->slider] = v[d->slider] - 0.02f < 0.0f ? 0.0f : v[d->slider] - 0.02f;
    if (key == GLFW_KEY_LEFT) d->cli.yaw -= 5.0;
    if (key == GLFW_KEY_RIGHT) d->cli.yaw += 5.0;
    if (key == GLFW_KEY_SPACE) d->running = !d->running;
    if (key == GLFW_KEY_EQUAL || key == GLFW_KEY_KP_ADD) d->time_rate *= 2.0;
    if (key == GLFW_KEY_MINUS || key == GLFW_KEY_KP_SUBTRACT) d->time_rate /= 2.0;
    if (key == GLFW_KEY_F) d->cli.fisheye = !d->cli.fisheye;
    if (key == GLFW_KEY_S) d->save = 1;
    if (key == GLFW_KEY_L) d->profiling = !d->profiling, d->recreate = 1;
#ifndef __EMSCRIPTEN__
    if (key == GLFW_KEY_G) d->switch_profile = 1; /* (a page has its one WebGL context) */
#endif
    if (key == GLFW_KEY_O) { /* the next tone map */
        d->cli.tone_map = d->cli.tone_map >= SKY_TONE_MAP_NEUTRAL ? SKY_TONE_MAP_HUE : d->cli.tone_map + 1;
        d->recreate = 1;
    }
    if (key == GLFW_KEY_A) { /* the next atmosphere path; DEFAULT is GRADIENT, so it goes on to PREETHAM */
        sky_atmosphere_path p = d->cli.atmosphere == SKY_ATMOSPHERE_DEFAULT ? SKY_ATMOSPHERE_GRADIENT : d->cli.atmosphere;
        d->cli.atmosphere = p >= SKY_ATMOSPHERE_BLEND ? SKY_ATMOSPHERE_GRADIENT : p + 1;
        d->recreate = 1;
    }
    /* feature toggles: the sky is rebuilt with only what is on */
    static const struct { int key; unsigned bit; } toggles[] = {
        {GLFW_KEY_C, SKY_CLOUDS}, {GLFW_KEY_U, SKY_SUN}, {GLFW_KEY_M, SKY_MOON}, {GLFW_KEY_K, SKY_FLICKER_STARS},
        {GLFW_KEY_T, SKY_STARS}, {GLFW_KEY_P, SKY_STARMAP}, {GLFW_KEY_E, SKY_LUNAR_ECLIPSE}};
    for (size_t i = 0; i < sizeof toggles / sizeof toggles[0]; i++)
        if (key == toggles[i].key) {
            d->features ^= toggles[i].bit;
            if ((d->features & SKY_LUNAR_ECLIPSE) && !(d->features & SKY_MOON)) d->features |= SKY_MOON;
            d->recreate = 1;
        }
    if (key == GLFW_KEY_W) { /* the next weather, a 10-second change (a sky without the
                                weather's shading is rebuilt with it first) */
        d->weather = d->weather + 1 >= SKY_WEATHER_COUNT ? 0 : d->weather + 1;
        d->weather_pending = 1;
        if (!(d->features & SKY_WEATHER)) d->features |= SKY_WEATHER, d->recreate = 1;
    }
    if (key == GLFW_KEY_ESCAPE) glfwSetWindowShouldClose(w, 1);
}

static void on_button(GLFWwindow *w, int button, int action, int mods)
{
    (void)mods;
    demo *d = glfwGetWindowUserPointer(w);
    double x, y;
    glfwGetCursorPos(w, &x, &y);
    if (button == GLFW_MOUSE_BUTTON_LEFT)
        ui_mouse_button(d->overlay, action == GLFW_PRESS, x, y, d->values, &d->slider);
    if (button == GLFW_MOUSE_BUTTON_RIGHT) d->looking = action == GLFW_PRESS, d->last_x = x, d->last_y = y;
}

static void on_cursor(GLFWwindow *w, double x, double y)
{
    demo *d = glfwGetWindowUserPointer(w);
    if (ui_mouse_move(d->overlay, x, y, d->values)) return;
    if (d->looking) {
        d->cli.yaw += (x - d->last_x) * 0.1 * d->cli.fov / 60.0;
        d->cli.pitch -= (y - d->last_y) * 0.1 * d->cli.fov / 60.0;
        d->cli.pitch = d->cli.pitch > 90 ? 90 : d->cli.pitch < -90 ? -90 : d->cli.pitch;
        d->last_x = x, d->last_y = y;
    }
}

static void on_scroll(GLFWwindow *w, double dx, double dy)
{
    (void)dx;
    demo *d = glfwGetWindowUserPointer(w);
    /* zooming in reveals fainter stars (Mueller eq. 9-10) */
    d->cli.fov *= dy > 0 ? 0.9 : 1.0 / 0.9;
    d->cli.fov = d->cli.fov < 1.0 ? 1.0 : d->cli.fov > 120.0 ? 120.0 : d->cli.fov;
}

/* Returns 0, or -1 after saying why. */
#ifdef __EMSCRIPTEN__
static int save_screenshot(int width, int height, const char *path)
{
    (void)width, (void)height;
    printf("sky-demo: a page has no files for %s; the browser saves the canvas\n", path);
    return -1;
}
#else
static int save_screenshot(int width, int height, const char *path)
{
    sky_osmesa shot = {0};
    shot.width = width;
    shot.height = height;
    shot.pixels = malloc((size_t)width * (size_t)height * 4u);
    int rc = -1;
    if (shot.pixels) {
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, shot.pixels);
        rc = sky_osmesa_write_png(&shot, path, NULL, 0);
    }
    if (rc)
        fprintf(stderr, "sky-demo: cannot write %s\n", path);
    else
        printf("sky-demo: saved %s\n", path);
    free(shot.pixels);
    return rc;
}
#endif

static sky_gl_profile profile_of(int kind)
{
    return kind == UI_CORE33 ? SKY_GL_CORE33 : kind == UI_ES20 ? SKY_GL_ES20 : SKY_GL_COMPAT20;
}

/* kind: UI_GL20 an OpenGL 2.0 context, UI_CORE33 a 3.3 core one,
 * UI_ES20 an OpenGL ES 2.0 one */
static GLFWwindow *open_window(demo *d, int kind)
{
    glfwDefaultWindowHints();
    if (kind == UI_CORE33) {
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
        glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    } else if (kind == UI_ES20) {
        glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_ES_API);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 2);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 0);
    } else {
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 2);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 0);
    }
    GLFWwindow *w = glfwCreateWindow(d->cli.width, d->cli.height, "libsky", NULL, NULL);
    if (!w) return NULL;
    glfwMakeContextCurrent(w);
    glfwSwapInterval(1);
    glfwSetWindowUserPointer(w, d);
    glfwSetKeyCallback(w, on_key);
    glfwSetMouseButtonCallback(w, on_button);
    glfwSetCursorPosCallback(w, on_cursor);
    glfwSetScrollCallback(w, on_scroll);
    return w;
}

/* A new sky for the demo's options, its clock where the last one's was
 * (a rebuilt sky must not make the clouds jump back to their start). */
static sky *make_sky(demo *d, char *err, size_t len)
{
    sky_config cfg = sky_cli_config(&d->cli, glfwGetProcAddress);
    cfg.features = d->features;
    cfg.profile_layers = d->profiling;
    sky *s = sky_create(&cfg, err, len);
    if (s) {
        /* the options' sliders, observer and weather (--weather ...: on the
         * running clock from 0), then the running clock the last sky had
         * reached. W's change is replayed where it started, so a rebuilt
         * sky draws the frame the last one would have, mid-change too. */
        sky_cli_apply(s, &d->cli);
        sky_weather target;
        if (d->s && d->weather >= 0 && !d->weather_pending &&
            sky_weather_preset((sky_weather_state)d->weather, &target) == SKY_OK) {
            sky_set_elapsed(s, d->weather_since);
            sky_set_weather(s, &d->weather_from, 0.0);
            sky_set_weather(s, &target, 10.0);
        }
        sky_set_elapsed(s, d->elapsed);
        d->atmosphere = cfg.atmosphere == SKY_ATMOSPHERE_DEFAULT ? SKY_ATMOSPHERE_GRADIENT : cfg.atmosphere;
    }
    return s;
}

static const char *atmosphere_name(sky_atmosphere_path p)
{
    static const char *const names[] = {"gradient", "gradient", "preetham", "rayleigh", "hillaire", "blend"};
    return (unsigned)p < sizeof names / sizeof names[0] ? names[p] : "?";
}

/* The --drag SLIDER:FROM:TO test hook: a left-button drag on a slider,
 * fed through the same handlers as the mouse. */
static int simulate_drag(demo *d, const char *spec)
{
    char name[16];
    float from, to;
    if (!spec || sscanf(spec, "%15[a-z]:%f:%f", name, &from, &to) != 3) return -1;
    static const char *const names[6] = {"cover", "height", "density", "sunset", "speed", "time"};
    for (int i = 0; i < 6; i++)
        if (!strcmp(name, names[i])) {
            double y = UI_SLIDER_Y0 + i * UI_SLIDER_DY + UI_SLIDER_H / 2;
            float *v = d->values;
            ui_mouse_button(d->overlay, 1, UI_SLIDER_X + from * UI_SLIDER_W, y, v, &d->slider);
            for (int k = 1; k <= 8; k++) ui_mouse_move(d->overlay, UI_SLIDER_X + (from + (to - from) * k / 8.0) * UI_SLIDER_W, y, v);
            ui_mouse_button(d->overlay, 0, 0, 0, v, &d->slider);
            return 0;
        }
    return -1;
}

/* The readout's lines (each ended by a NUL, the last by two): where,
 * when, the profile and path, the cost, the layers, the last error. */
static void readout(demo *d, char *lines, size_t len)
{
    char layer_ms[32];
    size_t room = len > 124 ? len - 124 : 0; /* what the last lines may need */
    sky_stats st;
    sky_astronomy a;
    sky_get_stats(d->s, &st);
    sky_get_astronomy(d->s, &a);
    int y, m, dd;
    double frac;
    sky_calendar(a.julian_day_ut, &y, &m, &dd, &frac);
    int used = snprintf(lines, len, "%04d-%02d-%02d %02d:%02d UTC  lat %.1f lon %.1f%c", y, m, dd,
                        (int)(frac * 24), (int)(frac * 1440) % 60, d->cli.observer.latitude_deg,
                        d->cli.observer.longitude_deg, 0);
    used += snprintf(lines + used, len - (size_t)used, "sun %.1f deg  moon %.1f deg, %.0f %% lit%c",
                     a.sun.alt_deg, a.moon.alt_deg, 100 * a.moon_illuminated_fraction, 0);
    if (a.solar_obscuration > 0.0)
        used += snprintf(lines + used, len - (size_t)used, "solar eclipse: %.1f %% covered, magnitude %.3f%c",
                         100 * a.solar_obscuration, a.solar_magnitude, 0);
    static const char *const tone_maps[3] = {"hue", "filmic", "neutral"};
    used += snprintf(lines + used, len - (size_t)used, "%s  atmosphere %s  tone map %s%c",
                     st.profile == SKY_GL_CORE33 ? "GL 3.3 core" : st.profile == SKY_GL_ES20 ? "GL ES 2.0" : "GL 2.0",
                     atmosphere_name(d->atmosphere), tone_maps[d->cli.tone_map], 0);
    used += snprintf(lines + used, len - (size_t)used, "fov %.0f  time %s x%.0f%c", d->cli.fov,
                     d->running ? "running" : "paused", d->time_rate * 86400.0, 0);
    int state = d->weather >= 0 ? d->weather : d->cli.weather_to >= 0 ? d->cli.weather_to : d->cli.weather, moving = 0;
    sky_weather w;
    if (state >= 0 && sky_get_weather(d->s, &w, &moving) == SKY_OK)
        used += snprintf(lines + used, len - (size_t)used, "weather %s%s  cover %.2f  visibility %.1f km%c",
                         moving ? "-> " : "", sky_weather_name((sky_weather_state)state), w.cover, w.visibility_km, 0);
    /* the cost: the sky's GPU frame time as sky-bench measures it, and
     * the frame rate of the window */
    double gpu_ms = timer_ms(&d->timer), fps = timer_fps(&d->timer);
    char ms_text[32] = "--", fps_text[32] = "--"; /* nothing measured yet */
    if (gpu_ms >= 0.0) snprintf(ms_text, sizeof ms_text, "%.2f", gpu_ms);
    if (fps > 0.0) snprintf(fps_text, sizeof fps_text, "%.0f", fps);
    used += snprintf(lines + used, len - (size_t)used, "sky %s ms GPU (%s)  %s fps%c", ms_text,
                     timer_method(&d->timer), fps_text, 0);
    used += snprintf(lines + used, len - (size_t)used, "%zu KiB GPU memory  %d draws%c",
                     st.gpu_bytes / 1024, st.draws_per_frame, 0);
    for (int l = 0; l < sky_layer_count() && (size_t)used < room; l++) {
        sky_layer_stats ls;
        if (sky_get_layer_stats(d->s, l, &ls) != SKY_OK || !ls.enabled) continue;
        used += snprintf(lines + used, len - (size_t)used, "%s %s%c", sky_layer_name((sky_layer)l),
                         ls.ms >= 0 ? (snprintf(layer_ms, sizeof layer_ms, "%.2f ms", ls.ms), layer_ms)
                                    : (ls.drawn ? "on" : "idle"), 0);
    }
    if (d->message[0] && (size_t)used < room)
        used += snprintf(lines + used, len - (size_t)used, "%.100s%c", d->message, 0);
    lines[used] = '\0';
}

/* One frame of the window: input hooks, a rebuilt sky or context when
 * asked, the sky, the overlay and its readout. Returns 1 to go on, 0 when
 * the demo is done (d->status says how). */
static int demo_frame(demo *d)
{
    char err[512];
    double now = glfwGetTime();
    double dt = d->automated ? 1.0 / 30.0 : now - d->last;
    d->last = now;
    int frame = d->frame++;
    if (d->keys && frame == 1) /* the --keys test hook, through the same handler as the keyboard */
        for (const char *k = d->keys; *k; k++) on_key(d->win, toupper((unsigned char)*k), 0, GLFW_PRESS, 0);
    if (d->switch_profile) { /* a new context: the sky and overlay go with the old one */
        d->switch_profile = 0;
        sky_destroy(d->s);
        ui_destroy(d->overlay);
        timer_destroy(&d->timer);
        glfwDestroyWindow(d->win);
        d->win = NULL;
        /* the next kind of context that opens: core, ES 2.0, 2.0 */
        for (int tries = 0; tries < 3 && !d->win; tries++) d->win = open_window(d, d->kind = (d->kind + 1) % 3);
        if (!d->win) {
            fprintf(stderr, "sky-demo: no GL window for any profile\n");
            d->s = NULL;
            d->overlay = NULL;
            d->status = 1;
            return 0;
        }
        d->cli.gl = profile_of(d->kind);
        d->overlay = ui_create(d->kind);
        timer_init(&d->timer, d->win);
        d->recreate = 1;
        d->s = NULL;
    }
    if (d->recreate) {
        d->recreate = 0;
        sky *s = make_sky(d, err, sizeof err);
        if (s) {
            sky_destroy(d->s);
            d->s = s;
            d->message[0] = '\0';
            timer_reset(&d->timer);
        } else {
            /* keep the sky that works and say why */
            fprintf(stderr, "sky-demo: %s\n", err);
            snprintf(d->message, sizeof d->message, "%.180s", err);
            if (!d->s) {
                d->status = 1;
                return 0;
            }
        }
    }
    if (d->running) {
        double t = d->values[5] + dt * d->time_rate;
        d->values[5] = (float)(t - (long)t);
    }
    d->cli.params = params_from_values(d->values);
    sky_set_params(d->s, &d->cli.params);
    sky_update(d->s, dt);
    if (d->weather_pending && d->weather >= 0) {
        sky_weather target;
        sky_weather_preset((sky_weather_state)d->weather, &target);
        sky_get_weather(d->s, &d->weather_from, NULL);
        d->weather_since = d->elapsed + dt; /* the clock sky_update has just reached */
        if (sky_set_weather(d->s, &target, 10.0) != SKY_OK)
            snprintf(d->message, sizeof d->message, "%.180s", sky_last_error(d->s));
        d->weather_pending = 0;
    }
    if (d->weather >= 0 || d->cli.weather >= 0 || d->cli.weather_to >= 0) {
        /* a weather owns cover and density: the sliders show its */
        sky_params driven;
        sky_get_params(d->s, &driven);
        d->values[0] = driven.cover;
        d->values[2] = driven.density;
    }
    d->elapsed += dt;
    int fw, fh;
    glfwGetFramebufferSize(d->win, &fw, &fh);
    glViewport(0, 0, fw, fh);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    d->cli.width = fw > 0 ? fw : 1;
    d->cli.height = fh > 0 ? fh : 1;
    float view[16], proj[16];
    sky_cli_camera(&d->cli, view, proj);
    timer_begin(&d->timer);
    int drawn = d->cli.fisheye ? sky_draw_fisheye(d->s) : sky_draw(d->s, view, proj);
    timer_end(&d->timer);
    if (drawn < 0) fprintf(stderr, "sky-demo: %s\n", sky_last_error(d->s));
    char lines[1024];
    readout(d, lines, sizeof lines);
    double gpu_ms = timer_ms(&d->timer), fps = timer_fps(&d->timer);
    ui_draw(d->overlay, fw, fh, d->values, d->slider, lines);
    if (d->save || (d->automated && frame + 1 >= d->cli.frames)) {
        const char *path = d->automated ? d->cli.screenshot : "sky-demo.png";
        int saved = save_screenshot(fw, fh, path) == 0;
        d->save = 0;
        if (d->automated) {
            printf("sky-demo: sky %.2f ms GPU (%s, median of %d frames), %.1f fps\n", gpu_ms,
                   timer_method(&d->timer), d->timer.count, fps);
            printf("sky-demo: atmosphere %s\n", atmosphere_name(d->atmosphere)); /* as the readout says */
            d->status = saved ? 0 : 1; /* a script must see that its image is missing */
            return 0;
        }
        if (!saved) snprintf(d->message, sizeof d->message, "cannot write %.160s", path);
    }
    glfwSwapBuffers(d->win);
    timer_tick(&d->timer);
    glfwPollEvents();
    return !glfwWindowShouldClose(d->win);
}

/* What the window leaves behind. */
static void demo_stop(demo *d)
{
    sky_destroy(d->s);
    ui_destroy(d->overlay);
    timer_destroy(&d->timer);
    if (d->win) glfwDestroyWindow(d->win);
    glfwTerminate();
}

/* Options, window, overlay and first sky. Returns -1 when the window is
 * open and the frames can run, else the exit status. */
static int demo_start(demo *d, int argc, char **argv)
{
    d->time_rate = 1.0 / 120.0; /* a day in two minutes */
    /* --drag, --keys and --out are sky-demo's own options: take them out
     * before the shared parse */
    const char *drag = NULL, *out = NULL;
    char *args[64];
    int n = 0;
    for (int i = 0; i < argc && n < 64; i++) {
        if (!strcmp(argv[i], "--drag") && i + 1 < argc) {
            drag = argv[++i];
            continue;
        }
        if (!strcmp(argv[i], "--keys") && i + 1 < argc) {
            d->keys = argv[++i];
            if (strspn(d->keys, "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789") != strlen(d->keys)) {
                fprintf(stderr, "sky-demo: --keys: expected letters and digits, e.g. CC, got '%s'\n", d->keys);
                return 2;
            }
            continue;
        }
        int took = sky_cli_take_out(&i, argc, argv, "sky-demo", &out);
        if (took < 0) return 2;
        if (took) continue;
        args[n++] = argv[i];
    }
    char err[512];
    int rc = sky_cli_parse(&d->cli, n, args, 1, err, sizeof err);
    if (rc == SKY_CLI_HELP) {
        sky_cli_usage(stdout, "sky-demo", 1);
        printf("  --out FILE.png           without a display: the image rendered headless (default\n"
               "                           sky.png; else --screenshot's file)\n"
               "  --drag SLIDER:FROM:TO    with --screenshot: drag a slider with the mouse first (tests)\n"
               "  --keys KEYS              with --screenshot and --frames 2 or more: press these keys\n"
               "                           after the first frame (tests)\n"
               "keys: 1-6 pick a slider, Up/Down move it, Space runs time, +/- its speed, F fisheye,\n"
               "      C U M K T P E toggle clouds sun moon flicker stars starmap eclipse, A atmosphere\n"
               "      path, G GL profile, W the next weather (a 10-second change),\n"
               "      L per-layer timing, S screenshot, Esc quit; mouse: drag sliders, right-drag to look,\n"
               "      wheel to zoom\n");
        return 0;
    }
    if (rc) {
        fprintf(stderr, "sky-demo: %s\n", err);
        return 2;
    }
    d->automated = d->cli.screenshot != NULL;
    values_from_params(d->values, &d->cli.params);
    if (!out) out = d->cli.screenshot ? d->cli.screenshot : "sky.png";
#ifndef __EMSCRIPTEN__
    if (!getenv("DISPLAY") && !getenv("WAYLAND_DISPLAY")) {
        fprintf(stderr, "sky-demo: no display found (DISPLAY is unset)\n");
        return headless(&d->cli, out);
    }
#else
    d->cli.gl = SKY_GL_ES20; /* WebGL 1 is OpenGL ES 2.0 */
#endif
    if (!glfwInit()) {
        fprintf(stderr, "sky-demo: GLFW cannot open the display\n");
        return headless(&d->cli, out);
    }
    d->features = d->cli.features ? d->cli.features : (SKY_CLOUDS | SKY_SUN | SKY_MOON | SKY_STARS | SKY_STARMAP);
    if (d->features & SKY_FEATURES_NONE) d->features = SKY_FEATURES_NONE;
    else if (d->cli.weather >= 0 || d->cli.weather_to >= 0) d->features |= SKY_WEATHER; /* its shading */
    d->kind = d->cli.gl == SKY_GL_ES20 ? UI_ES20 : d->cli.gl == SKY_GL_COMPAT20 ? UI_GL20 : UI_CORE33;
    d->win = open_window(d, d->kind);
    if (!d->win && d->kind != UI_GL20) {
        fprintf(stderr, "sky-demo: no %s window; trying OpenGL 2.0\n", d->kind == UI_ES20 ? "OpenGL ES 2.0" : "3.3 core");
        d->win = open_window(d, d->kind = UI_GL20);
    }
    if (!d->win) {
        fprintf(stderr, "sky-demo: no GL window could be created\n");
        glfwTerminate();
        return headless(&d->cli, out);
    }
    d->cli.gl = profile_of(d->kind);
    d->overlay = ui_create(d->kind);
    timer_init(&d->timer, d->win);
    d->elapsed = d->cli.seconds;
    d->weather = -1;
    d->s = make_sky(d, err, sizeof err);
    if (!d->s) {
        fprintf(stderr, "sky-demo: %s\n", err);
        glfwTerminate();
        return 1;
    }
    if (drag && simulate_drag(d, drag)) {
        fprintf(stderr, "sky-demo: --drag: expected SLIDER:FROM:TO, e.g. cover:0.1:0.9\n");
        return 2;
    }
    d->last = glfwGetTime();
    return -1;
}

#ifdef __EMSCRIPTEN__
/* The page's demo: the browser calls back with no user pointer of its
 * own for the preset menu, so the one demo of the page lives here. */
static demo web_demo;

int sky_demo_preset(const char *name); /* the page's, by ccall */

/* The preset menu (web/shell.html): that preset's sliders, features,
 * atmosphere and date, in a new sky. Returns 0, or -1 for an unknown
 * name. */
EMSCRIPTEN_KEEPALIVE int sky_demo_preset(const char *name)
{
    demo *d = &web_demo;
    sky_cli parsed;
    char err[256];
    char *args[4] = {"sky-demo", "--preset", (char *)name, NULL};
    if (sky_cli_parse(&parsed, 3, args, 1, err, sizeof err)) {
        fprintf(stderr, "sky-demo: %s\n", err);
        return -1;
    }
    parsed.gl = d->cli.gl;
    parsed.width = d->cli.width;
    parsed.height = d->cli.height;
    d->cli = parsed;
    d->features = parsed.features ? parsed.features : d->features;
    values_from_params(d->values, &parsed.params);
    d->recreate = 1;
    printf("sky-demo: preset %s\n", name);
    return 0;
}

/* A frame for the browser; the page logs the cost once it is measured. */
static void web_frame(void *arg)
{
    demo *d = arg;
    if (!demo_frame(d)) {
        emscripten_cancel_main_loop();
        demo_stop(d);
        return;
    }
    if (d->frame == 30)
        printf("sky-demo: sky %.2f ms GPU (%s), %.1f fps\n", timer_ms(&d->timer), timer_method(&d->timer),
               timer_fps(&d->timer));
}

int main(int argc, char **argv)
{
    int rc = demo_start(&web_demo, argc, argv);
    if (rc >= 0) return rc;
    printf("sky-demo: running in %s\n", (const char *)glGetString(GL_VERSION));
    emscripten_set_main_loop_arg(web_frame, &web_demo, 0, 1);
    return 0;
}
#else
int main(int argc, char **argv)
{
    demo d;
    memset(&d, 0, sizeof d);
    int rc = demo_start(&d, argc, argv);
    if (rc >= 0) return rc;
    while (demo_frame(&d)) {
    }
    demo_stop(&d);
    return d.status;
}
#endif
