/*
 * The rainbow (SKY_RAINBOW, rainbow.c), measured as the light it adds: the
 * same HDR frame with and without the feature, each pixel's difference
 * binned by its angle from the point opposite the sun. Geometry and
 * colour against Descartes and Airy: the primary's red peak at 42 +- 1
 * degrees and outside its blue, the secondary's red at 50-53.5 and inside
 * its blue, the secondary 0.1-0.7 of the primary, the sun 20 degrees up
 * behind the viewer in showers; a fogbow broad and nearly white; nothing
 * where nothing calls for a bow.
 */
#define GL_GLEXT_PROTOTYPES 1
#include "test.h"
#include "cli.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { W = 480, H = 270, BINS = 280 }; /* bins of 0.25 degrees, 0..70 */
#define BIN_DEG 0.25

/* The sun some 20 degrees up (the equinox at 40 N, the time slider's
 * 0.3275 is 20.3 degrees; its azimuth 108.3) */
#define SUN_TIME 0.3275f


/* (test.h) An HDR frame of a weather at the time slider's time and a
 * latitude, looking from yaw and pitch with a 90-degree field, with the
 * optics feature bit given or without any (0); *drawn: whether the layer
 * named was drawn. */
int optics_frame(unsigned optics, const char *layer, const sky_weather *w, float time, double latitude, double yaw,
                 double pitch, sky_gl_profile profile, int width, int height, float *rgb, sky_lighting *light,
                 int *drawn)
{
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.features = SKY_CLOUDS | SKY_SUN | SKY_WEATHER | optics;
    cfg.output = SKY_OUTPUT_HDR;
    fixture f;
    if (fixture_open_sized(&f, width, height, 1, profile, &cfg)) return -1;
    sky_params p = sky_default_params();
    p.time = time;
    sky_set_params(f.s, &p);
    sky_observer o;
    sky_get_observer(f.s, &o);
    o.latitude_deg = latitude;
    sky_set_observer(f.s, &o);
    sky_set_weather(f.s, w, 0.0);
    sky_set_elapsed(f.s, 2.0);
    float view[16], proj[16];
    sky_cli_camera_at(yaw, pitch, 90.0, width, height, view, proj);
    int rc = sky_draw(f.s, view, proj) == SKY_OK ? 0 : -1;
    sky_osmesa_finish(&f.ctx);
    const float *px = f.ctx.pixels;
    for (int i = 0; i < width * height; i++)
        for (int c = 0; c < 3; c++) rgb[3 * i + c] = px[4 * i + c];
    if (light) sky_get_lighting(f.s, light);
    if (drawn) {
        int index = sky_layer_index(layer);
        sky_layer_stats ls;
        *drawn = index >= 0 && sky_get_layer_stats(f.s, index, &ls) == SKY_OK && ls.drawn;
    }
    fixture_close(&f);
    return rc;
}

/* (test.h) Pixel (x, y)'s direction (rows bottom first), unit. */
void optics_pixel_dir(const float view[16], const float proj[16], int width, int height, int x, int y, double d[3])
{
    double e[3] = {((x + 0.5) / width * 2.0 - 1.0) / proj[0], ((y + 0.5) / height * 2.0 - 1.0) / proj[5], -1.0};
    for (int r = 0; r < 3; r++) d[r] = view[r * 4] * e[0] + view[r * 4 + 1] * e[1] + view[r * 4 + 2] * e[2];
    double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int r = 0; r < 3; r++) d[r] /= len;
}

static int frame_at(const sky_weather *w, float time, double latitude, double yaw, double pitch, int rainbow,
                    sky_gl_profile profile, float *rgb, sky_lighting *light, int *drawn)
{
    return optics_frame(rainbow ? SKY_RAINBOW : 0, "rainbow", w, time, latitude, yaw, pitch, profile, W, H, rgb,
                        light, drawn);
}

/* at the default place, 40 N */
static int frame(const sky_weather *w, float time, double yaw, double pitch, int rainbow, sky_gl_profile profile,
                 float *rgb, sky_lighting *light, int *drawn)
{
    return frame_at(w, time, 40.0, yaw, pitch, rainbow, profile, rgb, light, drawn);
}

/* The light the bow adds, binned by the angle from the antisolar point:
 * sums per channel and counts, over the rows from 2 to 18 degrees up
 * (in the rain, above the haze's thickest). */
typedef struct profile {
    double sum[BINS][3];
    int count[BINS];
} profile;

static void bin_added(const float *with, const float *without, const sky_lighting *l, double yaw, double pitch,
                      profile *out)
{
    memset(out, 0, sizeof *out);
    float view[16], proj[16];
    sky_cli_camera_at(yaw, pitch, 90.0, W, H, view, proj);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double d[3];
            optics_pixel_dir(view, proj, W, H, x, y, d);
            if (d[1] < sin(2.0 * M_PI / 180.0) || d[1] > sin(18.0 * M_PI / 180.0)) continue;
            double c = -(d[0] * l->sun_direction[0] + d[1] * l->sun_direction[1] + d[2] * l->sun_direction[2]);
            double rho = acos(c < -1.0 ? -1.0 : c > 1.0 ? 1.0 : c) * 180.0 / M_PI;
            int b = (int)(rho / BIN_DEG);
            if (b < 0 || b >= BINS) continue;
            for (int k = 0; k < 3; k++) out->sum[b][k] += with[3 * (y * W + x) + k] - without[3 * (y * W + x) + k];
            out->count[b]++;
        }
}

/* The bin of the largest mean in channel k between lo and hi degrees, its
 * centre in degrees (-1 if no bin there has pixels); the mean at *peak. */
static double peak_of(const profile *p, int k, double lo, double hi, double *peak)
{
    double best = -1e30, at = -1.0;
    for (int b = (int)(lo / BIN_DEG); b < (int)(hi / BIN_DEG) && b < BINS; b++) {
        if (p->count[b] < 4) continue;
        double m = p->sum[b][k] / p->count[b];
        if (m > best) best = m, at = (b + 0.5) * BIN_DEG;
    }
    if (peak) *peak = best;
    return at;
}

static double luma_of(const profile *p, int b)
{
    return p->count[b] ? (0.2126 * p->sum[b][0] + 0.7152 * p->sum[b][1] + 0.0722 * p->sum[b][2]) / p->count[b] : 0.0;
}

static void bow_checks(sky_gl_profile gl, const char *name)
{
    static float with[W * H * 3], without[W * H * 3];
    sky_weather showers = weather_preset(SKY_WEATHER_SHOWERS);
    sky_lighting l;
    /* facing the antisolar point's azimuth, the bow's sides in view */
    double yaw = 108.3 + 180.0, pitch = 10.0;
    int drawn = 0;
    if (frame(&showers, SUN_TIME, yaw, pitch, 1, gl, with, &l, &drawn) ||
        frame(&showers, SUN_TIME, yaw, pitch, 0, gl, without, NULL, NULL)) {
        CHECK(0, "%s: the frames rendered", name);
        return;
    }
    CHECK(drawn, "%s: the rainbow is drawn in showers with the sun out", name);
    static profile p;
    bin_added(with, without, &l, yaw, pitch, &p);
    double red1 = peak_of(&p, 0, 36.0, 46.0, NULL), blue1 = peak_of(&p, 2, 36.0, 46.0, NULL);
    double red2 = peak_of(&p, 0, 48.0, 56.0, NULL), blue2 = peak_of(&p, 2, 48.0, 56.0, NULL);
    /* the bows' strength: their luminance's peak over the dark band's floor */
    double y1 = 0.0, y2 = 0.0, band = 1e30;
    for (int b = (int)(38.0 / BIN_DEG); b < (int)(44.0 / BIN_DEG); b++) y1 = fmax(y1, luma_of(&p, b));
    for (int b = (int)(49.0 / BIN_DEG); b < (int)(55.0 / BIN_DEG); b++) y2 = fmax(y2, luma_of(&p, b));
    for (int b = (int)(44.0 / BIN_DEG); b < (int)(49.0 / BIN_DEG); b++)
        if (p.count[b] >= 4) band = fmin(band, luma_of(&p, b));
    NOTE("%s: primary red at %.2f, blue at %.2f degrees; secondary red at %.2f, blue at %.2f; peaks %.3g and %.3g "
         "kcd/m^2 (ratio %.2f), Alexander's band %.3g", name, red1, blue1, red2, blue2, y1, y2, y2 / y1, band);
    CHECK(fabs(red1 - 42.0) <= 1.0, "%s: the primary's red peak at 42 +- 1 degrees (%.2f)", name, red1);
    CHECK(red1 > blue1, "%s: the primary's red outside its blue (%.2f > %.2f)", name, red1, blue1);
    CHECK(red2 >= 50.0 && red2 <= 53.5, "%s: the secondary's red at 50-53.5 degrees (%.2f)", name, red2);
    CHECK(red2 < blue2, "%s: the secondary's red inside its blue (%.2f < %.2f)", name, red2, blue2);
    CHECK(y2 >= 0.1 * y1 && y2 <= 0.7 * y1, "%s: the secondary 0.1-0.7 of the primary (%.2f)", name, y2 / y1);
    CHECK(band < 0.5 * y2, "%s: Alexander's dark band between them (%.3g against %.3g)", name, band, y2);
}

TEST(rainbow_bows_core) { bow_checks(SKY_GL_CORE33, "core"); }
TEST(rainbow_bows_compat) { bow_checks(SKY_GL_COMPAT20, "compat"); }

/* A fogbow: fog's tiny drops make a broad bow of nearly the sunlight's
 * own colour a little inside the rainbow's 42 degrees. */
TEST(rainbow_fogbow_broad_and_white)
{
    static float with[W * H * 3], without[W * H * 3];
    sky_weather fog = weather_preset(SKY_WEATHER_FOG);
    sky_lighting l;
    double yaw = 108.3 + 180.0, pitch = 10.0;
    if (frame(&fog, SUN_TIME, yaw, pitch, 1, SKY_GL_AUTO, with, &l, NULL) ||
        frame(&fog, SUN_TIME, yaw, pitch, 0, SKY_GL_AUTO, without, NULL, NULL)) {
        CHECK(0, "the frames rendered");
        return;
    }
    static profile p;
    bin_added(with, without, &l, yaw, pitch, &p);
    double peak_y = 0.0, at = 0.0;
    for (int b = (int)(25.0 / BIN_DEG); b < (int)(46.0 / BIN_DEG); b++)
        if (luma_of(&p, b) > peak_y) peak_y = luma_of(&p, b), at = (b + 0.5) * BIN_DEG;
    /* its width at half its peak, and its colour there */
    double lo = at, hi = at;
    while (lo > 20.0 && luma_of(&p, (int)(lo / BIN_DEG)) > 0.5 * peak_y) lo -= BIN_DEG;
    while (hi < 60.0 && luma_of(&p, (int)(hi / BIN_DEG)) > 0.5 * peak_y) hi += BIN_DEG;
    /* its colour at the peak over the sunlight's own (the sun 20 degrees
     * up through fog is yellow: a white bow is the light's colour) */
    int b = (int)(at / BIN_DEG);
    double r = p.sum[b][0] / l.sun_color[0], g = p.sum[b][1] / l.sun_color[1], bl = p.sum[b][2] / l.sun_color[2];
    double spread = (fmax(r, fmax(g, bl)) - fmin(r, fmin(g, bl))) / fmax(r, fmax(g, bl));
    NOTE("fogbow: peak %.3g kcd/m^2 at %.2f degrees, %.1f degrees wide at half its peak, channels within %.0f %% "
         "of the sunlight's colour (%.3g %.3g %.3g)", peak_y, at, hi - lo, 100.0 * spread, r, g, bl);
    CHECK(peak_y > 0.0 && at > 30.0 && at < 42.0, "a fogbow inside 42 degrees (%.2f)", at);
    CHECK(hi - lo > 4.0, "broad: %.1f degrees at half its peak", hi - lo);
    CHECK(spread < 0.25, "nearly white: its channels within %.0f %%", 100.0 * spread);
}

/* Nothing calls for a bow: a clear sky, snow, the sun above the
 * secondary's reach: the optics variant stays undrawn and the frame is
 * the one without the feature. */
TEST(rainbow_none_where_none)
{
    static float with[W * H * 3], without[W * H * 3];
    static const struct {
        sky_weather_state state;
        float time;
        double latitude;
        const char *what;
    } cases[3] = {{SKY_WEATHER_CLEAR, SUN_TIME, 40.0, "clear"}, {SKY_WEATHER_SNOW, SUN_TIME, 40.0, "snow"},
                  {SKY_WEATHER_SHOWERS, 0.5f, 10.0, "showers at noon at 10 N (the sun 80 degrees up)"}};
    for (int k = 0; k < 3; k++) {
        sky_weather w = weather_preset(cases[k].state);
        int drawn = 1;
        if (frame_at(&w, cases[k].time, cases[k].latitude, 180.0, 10.0, 1, SKY_GL_AUTO, with, NULL, &drawn) ||
            frame_at(&w, cases[k].time, cases[k].latitude, 180.0, 10.0, 0, SKY_GL_AUTO, without, NULL, NULL)) {
            CHECK(0, "%s: the frames rendered", cases[k].what);
            continue;
        }
        double most = 0.0;
        for (int i = 0; i < W * H * 3; i++) most = fmax(most, fabs(with[i] - without[i]));
        CHECK(!drawn && most == 0.0, "%s: no bow drawn (drawn %d, largest difference %.3g)", cases[k].what, drawn,
              most);
    }
    /* and a rainbow without the clouds or the weather is refused */
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.features = SKY_SUN | SKY_RAINBOW;
    cfg.get_proc_address = sky_osmesa_loader();
    char err[256] = "";
    sky *s = sky_create(&cfg, err, sizeof err);
    CHECK(!s && strstr(err, "SKY_RAINBOW"), "SKY_RAINBOW alone refused: %s", err);
    sky_destroy(s);
}

/* A moon's bow: a full moon 37 degrees up in the west (2024-01-26 04:30
 * UTC at 40 N, the sun 31 degrees down) over showers makes a faint bow in
 * the east, grey: to the eye colourless at its level. */
TEST(rainbow_moon_bow_grey)
{
    static float with[W * H * 3], without[W * H * 3];
    for (int k = 0; k < 2; k++) {
        sky_config cfg;
        memset(&cfg, 0, sizeof cfg);
        cfg.features = SKY_CLOUDS | SKY_SUN | SKY_MOON | SKY_WEATHER | (k ? 0 : SKY_RAINBOW);
        cfg.output = SKY_OUTPUT_HDR;
        fixture f;
        if (fixture_open_sized(&f, W, H, 1, SKY_GL_AUTO, &cfg)) {
            CHECK(0, "no sky");
            return;
        }
        sky_observer o;
        sky_get_observer(f.s, &o);
        o.julian_day_utc = sky_julian_day(2024, 1, 26, 4, 30, 0.0);
        o.latitude_deg = 40.0;
        o.longitude_deg = 0.0;
        o.time_from_params = 0;
        sky_set_observer(f.s, &o);
        sky_weather showers = weather_preset(SKY_WEATHER_SHOWERS);
        sky_set_weather(f.s, &showers, 0.0);
        sky_set_elapsed(f.s, 2.0);
        float view[16], proj[16];
        sky_cli_camera_at(88.0, 10.0, 90.0, W, H, view, proj);
        sky_draw(f.s, view, proj);
        sky_osmesa_finish(&f.ctx);
        const float *px = f.ctx.pixels;
        float *out = k ? without : with;
        for (int i = 0; i < W * H; i++)
            for (int c = 0; c < 3; c++) out[3 * i + c] = px[4 * i + c];
        fixture_close(&f);
    }
    double sum[3] = {0.0, 0.0, 0.0}, most = 0.0;
    for (int i = 0; i < W * H; i++)
        for (int c = 0; c < 3; c++) {
            double d = with[3 * i + c] - without[3 * i + c];
            sum[c] += d;
            most = fmax(most, d);
        }
    double spread = (fmax(sum[0], fmax(sum[1], sum[2])) - fmin(sum[0], fmin(sum[1], sum[2]))) /
                    fmax(fmax(sum[0], fmax(sum[1], sum[2])), 1e-30);
    NOTE("the moon's bow: its brightest added pixel %.3g kcd/m^2, its channels' sums within %.2f %%", most,
         100.0 * spread);
    CHECK(most > 0.0 && spread < 0.02, "a grey moon's bow (%.3g kcd/m^2, channels within %.2f %%)", most,
          100.0 * spread);
}
