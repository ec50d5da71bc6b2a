/*
 * Command-line parsing shared by sky-render and sky-demo. Every bad value
 * is an error naming the option and its accepted range (exit status 2).
 */
#include "cli.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#ifdef _WIN32
#define WIN32_LEAN_AND_MEAN
#define NOMINMAX
#include <windows.h>
#endif

#define PI 3.14159265358979323846

static int fail(char *err, size_t len, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
static int fail(char *err, size_t len, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, len, fmt, ap);
    va_end(ap);
    return SKY_CLI_USAGE;
}

/* A finite number in [lo, hi], the whole string consumed. */
static int parse_number(const char *s, double lo, double hi, double *out)
{
    if (!s || !*s) return 0;
    char *end = NULL;
    errno = 0;
    double v = strtod(s, &end);
    if (errno || *end != '\0' || !isfinite(v) || v < lo || v > hi) return 0;
    *out = v;
    return 1;
}

/* ISO 8601 UTC: [+-]YYYY-MM-DDTHH:MM:SS[.fff]Z (the Z may be left out). */
static int parse_date(const char *s, double *jd)
{
    int sign = 1, year, month, day, hour, minute, used = 0;
    double second;
    if (!s) return 0;
    if (*s == '-' || *s == '+') sign = *s++ == '-' ? -1 : 1;
    if (sscanf(s, "%d-%d-%dT%d:%d:%lf%n", &year, &month, &day, &hour, &minute, &second, &used) != 6) return 0;
    const char *rest = s + used;
    if (*rest == 'Z') rest++;
    if (*rest != '\0' || year < 0 || month < 1 || month > 12 || hour < 0 || hour > 23 || minute < 0 ||
        minute > 59 || !(second >= 0.0 && second < 61.0))
        return 0;
    year *= sign;
    static const int days[12] = {31, 29, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    int leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
    if (day < 1 || day > days[month - 1] || (month == 2 && day == 29 && !leap)) return 0;
    *jd = sky_julian_day(year, month, day, hour, minute, second);
    return 1;
}

#ifdef _WIN32
/* A file's identity on Windows, whose stat gives every file the inode 0:
 * its volume and its index on the volume. */
static int file_identity(const char *path, BY_HANDLE_FILE_INFORMATION *id)
{
    HANDLE h = CreateFileA(path, 0, FILE_SHARE_READ | FILE_SHARE_WRITE | FILE_SHARE_DELETE, NULL, OPEN_EXISTING,
                           FILE_FLAG_BACKUP_SEMANTICS, NULL);
    if (h == INVALID_HANDLE_VALUE) return 0;
    int ok = GetFileInformationByHandle(h, id) != 0;
    CloseHandle(h);
    return ok;
}

/* Identical names, or two names of one existing file. */
static int same_file(const char *a, const char *b)
{
    if (!strcmp(a, b)) return 1;
    BY_HANDLE_FILE_INFORMATION ia, ib;
    return file_identity(a, &ia) && file_identity(b, &ib) && ia.dwVolumeSerialNumber == ib.dwVolumeSerialNumber &&
           ia.nFileIndexHigh == ib.nFileIndexHigh && ia.nFileIndexLow == ib.nFileIndexLow;
}
#else
/* Identical names, or two names of one existing file. */
static int same_file(const char *a, const char *b)
{
    if (!strcmp(a, b)) return 1;
    struct stat sa, sb;
    return stat(a, &sa) == 0 && stat(b, &sb) == 0 && sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}
#endif

/* Whether name ends in ext (".png"), in any case. The writers take the
 * format from the option, not the name, so a name promising another format
 * (a.jpg holding PNG data) is refused rather than written. */
static int has_extension(const char *name, const char *ext)
{
    size_t n = strlen(name), e = strlen(ext);
    if (n < e) return 0;
    for (size_t i = 0; i < e; i++)
        if (tolower((unsigned char)name[n - e + i]) != tolower((unsigned char)ext[i])) return 0;
    return 1;
}

static int parse_hips(const char *s, sky_cli *cli)
{
    if (!s || !*s) return 0;
    while (*s) {
        char *end = NULL;
        long v = strtol(s, &end, 10);
        if (end == s || v <= 0 || v > 1000000 || cli->hip_count == 64) return 0;
        cli->hip[cli->hip_count++] = (int)v;
        s = end;
        if (*s == ',') s++;
        else if (*s) return 0;
    }
    return 1;
}

/* The command line's names of the feature bits (--features, --stats). */
static const struct {
    const char *name;
    unsigned bit;
} feature_names[] = {{"clouds", SKY_CLOUDS},        {"sun", SKY_SUN},         {"moon", SKY_MOON},
                     {"stars", SKY_STARS},          {"flicker", SKY_FLICKER_STARS}, {"starmap", SKY_STARMAP},
                     {"eclipse", SKY_LUNAR_ECLIPSE}, {"solar-eclipse", SKY_SOLAR_ECLIPSE}, {"planets", SKY_PLANETS},
                     {"airglow", SKY_AIRGLOW},      {"zodiacal", SKY_ZODIACAL}, {"weather", SKY_WEATHER},
                     {"rainbow", SKY_RAINBOW}, {"halo", SKY_HALO}, {"aurora", SKY_AURORA}};
#define FEATURE_NAMES \
    "clouds,sun,moon,flicker,stars,starmap,eclipse,solar-eclipse,planets,airglow,zodiacal,weather,rainbow,halo," \
    "aurora"

static int parse_features(const char *s, unsigned *out, char *err, size_t len)
{
    if (!strcmp(s, "none")) {
        *out = SKY_FEATURES_NONE;
        return SKY_CLI_OK;
    }
    unsigned mask = 0;
    const char *p = s;
    while (*p) {
        size_t n = strcspn(p, ",");
        int found = 0;
        for (size_t i = 0; i < sizeof feature_names / sizeof feature_names[0]; i++)
            if (strlen(feature_names[i].name) == n && !strncmp(p, feature_names[i].name, n)) {
                if (!(feature_names[i].bit & SKY_FEATURES_AVAILABLE))
                    return fail(err, len, "--features: '%s' is not available yet in this build",
                                feature_names[i].name);
                mask |= feature_names[i].bit;
                found = 1;
            }
        if (!found)
            return fail(err, len, "--features: unknown feature '%.*s' (accepted: " FEATURE_NAMES " or none)", (int)n,
                        p);
        p += n;
        if (*p == ',') {
            p++;
            if (!*p) return fail(err, len, "--features: trailing comma in '%s'", s);
        }
    }
    if (!mask) return fail(err, len, "--features: empty list (use 'none' for an empty sky)");
    *out = mask;
    return SKY_CLI_OK;
}

void sky_cli_usage(FILE *out, const char *prog, int is_demo)
{
    fprintf(out,
            "usage: %s [options]\n"
            "  --size WxH               image size (default 1280x720)\n"
            "  --cover F --height F --density F --sunset F --speed F --time F\n"
            "                           the six sliders, each 0..1\n"
            "  --seconds S              elapsed animation time, S >= 0\n"
            "  --weather NAME           the weather from time 0: clear, fair, cirrus, cloudy, overcast,\n"
            "                           rain, showers, storm, fog, snow (it owns cover and density)\n"
            "  --weather-to NAME        a change of weather that starts at time 0 ...\n"
            "  --weather-seconds S      ... and lasts S seconds (default 10); --seconds picks the frame\n"
            "  --seed N                 the seed of the random events (lightning), 0..4294967295\n"
            "  --out-shadow FILE.png    (sky-render) the clouds' shadow on the ground, white = full sun,\n"
            "                           north up, --size pixels over --shadow-extent KM (default 10)\n"
            "  --yaw DEG --pitch DEG --fov DEG | --fisheye\n"
            "                           view azimuth (from north through east), altitude\n"
            "                           (-90..90), vertical field of view (1..179)\n"
            "  --atmosphere gradient|preetham|rayleigh|hillaire|blend   atmosphere path\n"
            "  --luts small|default|large   hillaire/blend: table sizes and samples (x0.5, Hillaire's, x2)\n"
            "  --blend W                blend: fixed weight 0 (analytic) .. 1 (Hillaire); default follows the sun\n"
            "  --blend-partner rayleigh|preetham   blend: the analytic path mixed with Hillaire's (default rayleigh)\n"
            "  --turbidity T            haze on every path: the optical depth's ratio to the molecules' alone,\n"
            "                           1..64 (preetham clamps to 2..10, default 2.5; the others scale the\n"
            "                           description's aerosol, default its own: earth 1.9)\n"
            "  --dome-divisor N         8-bit output: the sky and clouds at 1/N of the pixels per axis,\n"
            "                           filtered up (1..8; default 4; 1 = every pixel, the sharpest)\n"
            "  --tone-map hue|filmic|neutral   8-bit output's curve: hue keeps each colour's hue and\n"
            "                           saturation (default), filmic is libsky's old per-channel curve,\n"
            "                           neutral is Khronos PBR Neutral\n"
            "  --planet NAME            the atmosphere's composition (rayleigh, hillaire, blend): earth (clear,\n"
            "                           the default), very-clean, hazy, polluted, hillaire-2020 (his paper's\n"
            "                           constants), mars\n"
            "  --features LIST          comma list of clouds,sun,moon,flicker,stars,starmap,eclipse,\n"
            "                           solar-eclipse,planets,airglow,zodiacal,weather,rainbow,halo,aurora\n"
            "                           (or none); eclipse = the lunar one\n"
            "  --gl auto|core|compat|es20\n"
            "                           GL profile (es20: OpenGL ES 2.0, headless through EGL)\n"
            "  --preset noon|overcast|sunset|starry|moonlit|eclipse|solar-eclipse|minimal\n"
            "  --frames N               render N frames, 1/30 s apart\n"
            "  --moon-scale C           draw the moon C times its true size (0.5..50; default 2.5)\n"
            "  --bortle N               light pollution of Bortle class N (1 excellent dark site .. 9 inner city)\n"
            "  --kp K                   the aurora's Kp index: 0 quiet .. 9 extreme storm (default 0)\n"
            "  --solar-activity A       the airglow's solar cycle: 0 minimum .. 1 maximum (default: the date's)\n"
            "  --exposure STOPS         on top of the automatic exposure (-10..10; the sun as through a filter: -8)\n"
            "  --exposure-range STOPS   how far dusk and night show darker than full adaptation (0.01..16; 3)\n"
            "  --date YYYY-MM-DDTHH:MM:SSZ   UTC instant (years -1999..3000); with --time,\n"
            "                           --time sets the local solar time on that date\n"
            "  --lat DEG --lon DEG --alt M    observer (east longitude positive)\n",
            prog);
    if (is_demo) {
        fprintf(out, "  --screenshot FILE.png    with --frames: save the last frame and quit\n");
        /* sky-game shares these options but has no keys; sky-demo prints
         * its other keys after its own options (demo.c), these were left
         * out of that list */
        if (!strcmp(prog, "sky-demo"))
            fprintf(out, "keys, besides those below: Left/Right turn the view (5 degrees a press),\n"
                         "      O the next tone map (hue, filmic, neutral; the sky is rebuilt)\n");
    } else
        fprintf(out, "  --out FILE.png           8-bit sRGB image (with --frames: FILE_0001.png ...)\n"
                     "  --out-pfm FILE.pfm       linear float RGB, luminance in kcd/m^2\n"
                     "  --stats                  print JSON statistics after rendering\n"
                     "  --capture N              with --out: the environment cube map, N x N a face (a power of\n"
                     "                           two, 4..2048, sun disc included), written as a cube cross 4N x 3N:\n"
                     "                           +Y above; -X, +Z, +X, -Z across; -Y below (GL's faces, as\n"
                     "                           sky_capture_environment makes them)\n"
                     "  --query                  print the astronomical state as JSON (no GL)\n"
                     "  --hip N,N,...            with --query: also these Hipparcos stars\n");
}

/* Presets: the features and sliders a game would use for a scene; the
 * moonlit and both eclipse ones also bring a date, place and view that show
 * their moon (used unless --date, --lat, --lon, --yaw, --pitch are given).
 * Options given explicitly win over the preset, whatever their order. */
typedef struct preset {
    const char *name;
    unsigned features;
    sky_gl_profile gl;
    float cover, height, density, sunset, speed, time;
    const char *date; /* NULL: no date of its own */
    double lat, lon, yaw, pitch;
    int dome_divisor; /* 0: the library's default */
} preset;

/* Every preset takes the solar eclipse: it costs nothing while the sun
 * and the moon are apart. */
static const preset presets[] = {
    {"noon", SKY_CLOUDS | SKY_SUN | SKY_SOLAR_ECLIPSE, SKY_GL_AUTO, 0.35f, 0.6f, 0.2f, 0.0f, 0.2f, 0.5f, NULL, 0, 0, 0, 0, 0},
    {"overcast", SKY_CLOUDS | SKY_SOLAR_ECLIPSE, SKY_GL_AUTO, 0.95f, 0.3f, 0.85f, 0.0f, 0.3f, 0.45f, NULL, 0, 0, 0, 0, 0},
    {"sunset", SKY_CLOUDS | SKY_SUN | SKY_SOLAR_ECLIPSE, SKY_GL_AUTO, 0.5f, 0.7f, 0.25f, 0.9f, 0.15f, 0.735f, NULL, 0, 0,
     0, 0, 0},
    {"starry", SKY_STARS | SKY_PLANETS | SKY_STARMAP | SKY_AIRGLOW | SKY_ZODIACAL | SKY_CLOUDS | SKY_SOLAR_ECLIPSE,
     SKY_GL_AUTO, 0.15f, 0.6f, 0.2f, 0.0f, 0.1f,
     0.0f, NULL, 0, 0, 0, 0, 0},
    /* the full moon of 2026-04-02 from 40 N, looking at it */
    {"moonlit", SKY_MOON | SKY_STARS | SKY_PLANETS | SKY_STARMAP | SKY_AIRGLOW | SKY_ZODIACAL | SKY_CLOUDS |
                    SKY_SOLAR_ECLIPSE, SKY_GL_AUTO, 0.3f, 0.6f, 0.2f,
     0.0f, 0.1f, 0.0f, "2026-04-02T00:00:00Z", 40.0, 0.0, 181.6, 30.0, 0},
    /* the total lunar eclipse of 2026-03-03, greatest at about 11:33 UTC,
     * from Hawaii where the moon stands at 69 degrees */
    {"eclipse", SKY_MOON | SKY_LUNAR_ECLIPSE | SKY_STARS | SKY_PLANETS | SKY_STARMAP | SKY_AIRGLOW | SKY_ZODIACAL |
                    SKY_SOLAR_ECLIPSE, SKY_GL_AUTO, 0.0f, 0.6f,
     0.2f, 0.0f, 0.1f, 0.0f, "2026-03-03T11:33:00Z", 20.0, -155.0, 229.9, 55.0, 0},
    /* the total solar eclipse of 2024-04-08 near Nazas, Durango, at its
     * greatest (18:17:20 UT), looking up toward the sun at 70 degrees */
    {"solar-eclipse", SKY_SUN | SKY_MOON | SKY_STARS | SKY_PLANETS | SKY_STARMAP | SKY_AIRGLOW | SKY_ZODIACAL |
                          SKY_CLOUDS | SKY_SOLAR_ECLIPSE,
     SKY_GL_AUTO, 0.1f,
     0.6f, 0.2f, 0.0f, 0.1f, 0.0f, "2024-04-08T18:17:20Z", 25.29, -104.14, 149.4, 42.0, 0},
    /* the weakest GPUs' preset: the dome at a fifth of the resolution
     * (softer clouds), which keeps it within one and a half textured
     * full-screen quads on a software rasteriser */
    {"minimal", SKY_CLOUDS | SKY_SUN | SKY_FLICKER_STARS | SKY_SOLAR_ECLIPSE | SKY_AIRGLOW, SKY_GL_COMPAT20, 0.45f, 0.5f, 0.3f, 0.5f,
     0.2f, 0.45f, NULL, 0, 0, 0, 0, 5},
};

static const preset *find_preset(const char *name)
{
    for (size_t i = 0; i < sizeof presets / sizeof presets[0]; i++)
        if (!strcmp(presets[i].name, name)) return &presets[i];
    return NULL;
}

static int apply_preset(sky_cli *cli, const preset *p, const int *given)
{
    if (!given[0]) cli->features = p->features;
    if (!given[1]) cli->gl = p->gl;
    if (!given[8]) cli->dome_divisor = p->dome_divisor;
    float *dst[6] = {&cli->params.cover, &cli->params.height, &cli->params.density,
                     &cli->params.sunset, &cli->params.speed, &cli->params.time};
    const float src[6] = {p->cover, p->height, p->density, p->sunset, p->speed, p->time};
    for (int k = 0; k < 6; k++)
        if (!given[2 + k]) *dst[k] = src[k];
    return SKY_CLI_OK;
}

int sky_cli_parse(sky_cli *cli, int argc, char **argv, int is_demo, char *err, size_t len)
{
    memset(cli, 0, sizeof *cli);
    cli->width = 1280;
    cli->height = 720;
    cli->params = sky_default_params();
    cli->yaw = 180.0;  /* facing south, where the sun culminates */
    cli->pitch = 20.0;
    cli->fov = 60.0;
    cli->frames = 1;
    cli->weather = cli->weather_to = -1;
    cli->shadow_extent_km = 10.0;
    cli->weather_seconds = 10.0;
    memset(&cli->observer, 0, sizeof cli->observer);
    int have_date = 0;
    double date_jd = 0.0;
    sky_observer where = {0.0, 40.0, 0.0, 0.0, 1}; /* sky.h's documented default place */
    static const char *const sliders[6] = {"--cover", "--height", "--density", "--sunset", "--speed", "--time"};
    /* given[]: features, gl, six sliders; seen[] catches duplicates */
    int given[9] = {0}; /* and the dome's divisor */
    const char *seen[64];
    int seen_count = 0;
    for (int i = 1; i < argc; i++) {
        const char *opt = argv[i];
        if (!strcmp(opt, "--help") || !strcmp(opt, "-h")) return SKY_CLI_HELP;
        if (strncmp(opt, "--", 2))
            return fail(err, len, "unexpected argument '%s' (options start with --; see --help)", opt);
        for (int k = 0; k < seen_count; k++)
            if (!strcmp(seen[k], opt)) return fail(err, len, "%s: given more than once", opt);
        if (seen_count < 64) seen[seen_count++] = opt;
        /* flags without a value */
        if (!strcmp(opt, "--fisheye")) {
            cli->fisheye = 1;
            continue;
        }
        if (!is_demo && !strcmp(opt, "--stats")) {
            cli->stats = 1;
            continue;
        }
        if (!is_demo && !strcmp(opt, "--query")) {
            cli->query = 1;
            continue;
        }
        /* options with a value */
        const char *val = i + 1 < argc ? argv[i + 1] : NULL;
        int known = 1;
        double v = 0.0;
        int slider = -1;
        for (int k = 0; k < 6; k++)
            if (!strcmp(opt, sliders[k])) slider = k;
        if (slider >= 0) {
            if (!parse_number(val, 0.0, 1.0, &v))
                return fail(err, len, "%s: expected a number in 0..1, got '%s'", opt, val ? val : "(nothing)");
            float *dst[6] = {&cli->params.cover, &cli->params.height, &cli->params.density,
                             &cli->params.sunset, &cli->params.speed, &cli->params.time};
            *dst[slider] = (float)v;
            given[2 + slider] = 1;
        } else if (!strcmp(opt, "--size")) {
            int w = 0, h = 0;
            char tail = 0;
            if (!val || sscanf(val, "%dx%d%c", &w, &h, &tail) != 2 || w < 1 || h < 1 || w > 16384 || h > 16384)
                return fail(err, len, "--size: expected WxH with 1..16384 each, got '%s'", val ? val : "(nothing)");
            cli->width = w;
            cli->height = h;
        } else if (!strcmp(opt, "--weather") || !strcmp(opt, "--weather-to")) {
            int state = sky_weather_from_name(val);
            if (state < 0)
                return fail(err, len,
                            "%s: expected clear, fair, cirrus, cloudy, overcast, rain, showers, storm, fog or snow, "
                            "got '%s'",
                            opt, val ? val : "(nothing)");
            *(!strcmp(opt, "--weather") ? &cli->weather : &cli->weather_to) = state;
        } else if (!strcmp(opt, "--seed")) {
            if (!parse_number(val, 0.0, 4294967295.0, &v) || v != floor(v))
                return fail(err, len, "--seed: expected a whole number in 0..4294967295, got '%s'",
                            val ? val : "(nothing)");
            cli->seed = (unsigned)v;
        } else if (!strcmp(opt, "--weather-seconds")) {
            if (!parse_number(val, 0.0, 1e9, &v))
                return fail(err, len, "--weather-seconds: expected seconds in 0..1e9, got '%s'",
                            val ? val : "(nothing)");
            cli->weather_seconds = v;
        } else if (!strcmp(opt, "--seconds")) {
            if (!parse_number(val, 0.0, 1e12, &v))
                return fail(err, len, "--seconds: expected a number in 0..1e12, got '%s'", val ? val : "(nothing)");
            cli->seconds = v;
        } else if (!strcmp(opt, "--yaw")) {
            if (!parse_number(val, -360.0, 360.0, &v))
                return fail(err, len, "--yaw: expected degrees in -360..360, got '%s'", val ? val : "(nothing)");
            cli->yaw = v;
        } else if (!strcmp(opt, "--pitch")) {
            if (!parse_number(val, -90.0, 90.0, &v))
                return fail(err, len, "--pitch: expected degrees in -90..90, got '%s'", val ? val : "(nothing)");
            cli->pitch = v;
        } else if (!strcmp(opt, "--fov")) {
            if (!parse_number(val, 1.0, 179.0, &v))
                return fail(err, len, "--fov: expected degrees in 1..179, got '%s'", val ? val : "(nothing)");
            cli->fov = v;
        } else if (!strcmp(opt, "--bortle")) {
            if (!parse_number(val, 1.0, 9.0, &v))
                return fail(err, len, "--bortle: expected a Bortle class in 1..9, got '%s'", val ? val : "(nothing)");
            cli->bortle = (float)v;
        } else if (!strcmp(opt, "--kp")) {
            if (!parse_number(val, 0.0, 9.0, &v))
                return fail(err, len, "--kp: expected a Kp index in 0..9, got '%s'", val ? val : "(nothing)");
            cli->kp = (float)v;
        } else if (!strcmp(opt, "--solar-activity")) {
            if (!parse_number(val, 0.0, 1.0, &v))
                return fail(err, len, "--solar-activity: expected 0 (minimum) .. 1 (maximum), got '%s'",
                            val ? val : "(nothing)");
            cli->solar_activity = (float)v;
            cli->solar_activity_manual = 1;
        } else if (!strcmp(opt, "--moon-scale")) {
            if (!parse_number(val, 0.5, 50.0, &v))
                return fail(err, len, "--moon-scale: expected a factor in 0.5..50, got '%s'", val ? val : "(nothing)");
            cli->moon_scale = (float)v;
        } else if (!strcmp(opt, "--tone-map")) {
            if (val && !strcmp(val, "hue")) cli->tone_map = SKY_TONE_MAP_HUE;
            else if (val && !strcmp(val, "filmic")) cli->tone_map = SKY_TONE_MAP_FILMIC;
            else if (val && !strcmp(val, "neutral")) cli->tone_map = SKY_TONE_MAP_NEUTRAL;
            else return fail(err, len, "--tone-map: expected hue, filmic or neutral, got '%s'", val ? val : "(nothing)");
        } else if (!strcmp(opt, "--dome-divisor")) {
            if (!parse_number(val, 1.0, 8.0, &v) || v != floor(v))
                return fail(err, len, "--dome-divisor: expected a whole number in 1..8, got '%s'", val ? val : "(nothing)");
            cli->dome_divisor = (int)v;
            given[8] = 1;
        } else if (!strcmp(opt, "--exposure")) {
            if (!parse_number(val, -10.0, 10.0, &v))
                return fail(err, len, "--exposure: expected stops in -10..10, got '%s'", val ? val : "(nothing)");
            cli->exposure = (float)v;
        } else if (!strcmp(opt, "--exposure-range")) {
            if (!parse_number(val, 0.01, 16.0, &v))
                return fail(err, len, "--exposure-range: expected stops in 0.01..16, got '%s'", val ? val : "(nothing)");
            cli->exposure_range = (float)v;
        } else if (!strcmp(opt, "--luts")) {
            /* Hillaire's tables: his sizes and samples scaled */
            double k = 0.0;
            if (val && !strcmp(val, "small")) k = 0.5;
            else if (val && !strcmp(val, "default")) k = 1.0;
            else if (val && !strcmp(val, "large")) k = 2.0;
            else return fail(err, len, "--luts: expected small, default or large, got '%s'", val ? val : "(nothing)");
            sky_lut_settings *l = &cli->luts;
            l->transmittance_width = (int)(256 * k), l->transmittance_height = (int)(64 * k);
            l->transmittance_steps = (int)(40 * k), l->multiscatter_size = (int)(32 * k);
            l->multiscatter_directions = (int)(64 * k), l->multiscatter_steps = (int)(20 * k);
            l->skyview_width = (int)(192 * k), l->skyview_height = (int)(108 * k), l->skyview_steps = (int)(30 * k);
        } else if (!strcmp(opt, "--blend")) {
            if (!parse_number(val, 0.0, 1.0, &v))
                return fail(err, len, "--blend: expected a weight in 0..1 (0 analytic, 1 Hillaire), got '%s'",
                            val ? val : "(nothing)");
            cli->blend_manual = 1;
            cli->blend_weight = (float)v;
        } else if (!strcmp(opt, "--blend-partner")) {
            if (val && !strcmp(val, "rayleigh"))
                cli->blend_partner = SKY_ATMOSPHERE_RAYLEIGH;
            else if (val && !strcmp(val, "preetham"))
                cli->blend_partner = SKY_ATMOSPHERE_PREETHAM;
            else
                return fail(err, len, "--blend-partner: expected rayleigh|preetham, got '%s'", val ? val : "(nothing)");
        } else if (!strcmp(opt, "--turbidity")) {
            if (!parse_number(val, 1.0, 64.0, &v))
                return fail(err, len, "--turbidity: expected a turbidity in 1..64, got '%s'", val ? val : "(nothing)");
            cli->turbidity = (float)v;
        } else if (!strcmp(opt, "--planet")) {
            static const char *const names[] = {"earth", "hazy", "mars", "very-clean", "polluted", "hillaire-2020"};
            static const sky_atmosphere_preset planets[] = {SKY_ATMOSPHERE_PRESET_EARTH,      SKY_ATMOSPHERE_PRESET_HAZY,
                                                            SKY_ATMOSPHERE_PRESET_MARS,       SKY_ATMOSPHERE_PRESET_VERY_CLEAN,
                                                            SKY_ATMOSPHERE_PRESET_POLLUTED,   SKY_ATMOSPHERE_PRESET_HILLAIRE_2020};
            int found = -1;
            for (int k = 0; val && k < (int)(sizeof names / sizeof names[0]); k++)
                if (!strcmp(val, names[k])) found = k;
            if (found < 0)
                return fail(err, len,
                            "--planet: expected earth, very-clean, hazy, polluted, hillaire-2020 or mars, got '%s'",
                            val ? val : "(nothing)");
            cli->planet = planets[found];
        } else if (!is_demo && !strcmp(opt, "--capture")) {
            if (!parse_number(val, 4.0, 2048.0, &v) || v != floor(v) || ((int)v & ((int)v - 1)))
                return fail(err, len, "--capture: expected a power of two in 4..2048, got '%s'",
                            val ? val : "(nothing)");
            cli->capture = (int)v;
        } else if (!strcmp(opt, "--frames")) {
            if (!parse_number(val, 1.0, 1e6, &v) || v != floor(v))
                return fail(err, len, "--frames: expected a whole number in 1..1000000, got '%s'",
                            val ? val : "(nothing)");
            cli->frames = (int)v;
        } else if (!strcmp(opt, "--date")) {
            if (!parse_date(val, &date_jd))
                return fail(err, len, "--date: expected YYYY-MM-DDTHH:MM:SSZ (UTC), got '%s'", val ? val : "(nothing)");
            /* The library's own bounds (sky_set_observer): the calendar's
             * first and after-last instants, not a Julian-year estimate,
             * which drifts by a month at the ends and let 3001-01-01 reach
             * the library, which failed it at run time (exit 1). */
            if (date_jd < sky_julian_day(-1999, 1, 1, 0, 0, 0.0) || date_jd >= sky_julian_day(3001, 1, 1, 0, 0, 0.0))
                return fail(err, len, "--date: '%s' is outside the supported years -1999..3000", val);
            have_date = 1;
        } else if (!strcmp(opt, "--lat")) {
            if (!parse_number(val, -90.0, 90.0, &where.latitude_deg))
                return fail(err, len, "--lat: expected degrees in -90..90, got '%s'", val ? val : "(nothing)");
        } else if (!strcmp(opt, "--lon")) {
            if (!parse_number(val, -180.0, 180.0, &where.longitude_deg))
                return fail(err, len, "--lon: expected degrees in -180..180 (east positive), got '%s'",
                            val ? val : "(nothing)");
        } else if (!strcmp(opt, "--alt")) {
            if (!parse_number(val, -500.0, 100000.0, &where.altitude_m))
                return fail(err, len, "--alt: expected metres in -500..100000, got '%s'", val ? val : "(nothing)");
        } else if (!is_demo && !strcmp(opt, "--hip")) {
            if (!parse_hips(val, cli))
                return fail(err, len, "--hip: expected up to 64 Hipparcos numbers N,N,..., got '%s'",
                            val ? val : "(nothing)");
        } else if (!strcmp(opt, "--features")) {
            if (!val) return fail(err, len, "--features: expected a list such as clouds,sun");
            int rc = parse_features(val, &cli->features, err, len);
            if (rc) return rc;
            given[0] = 1;
        } else if (!strcmp(opt, "--gl")) {
            if (val && !strcmp(val, "auto"))
                cli->gl = SKY_GL_AUTO;
            else if (val && !strcmp(val, "core"))
                cli->gl = SKY_GL_CORE33;
            else if (val && !strcmp(val, "compat"))
                cli->gl = SKY_GL_COMPAT20;
            else if (val && !strcmp(val, "es20"))
                cli->gl = SKY_GL_ES20;
            else
                return fail(err, len, "--gl: expected auto, core, compat or es20, got '%s'", val ? val : "(nothing)");
            given[1] = 1;
        } else if (!strcmp(opt, "--atmosphere")) {
            if (val && !strcmp(val, "gradient"))
                cli->atmosphere = SKY_ATMOSPHERE_GRADIENT;
            else if (val && !strcmp(val, "preetham"))
                cli->atmosphere = SKY_ATMOSPHERE_PREETHAM;
            else if (val && !strcmp(val, "rayleigh"))
                cli->atmosphere = SKY_ATMOSPHERE_RAYLEIGH;
            else if (val && !strcmp(val, "hillaire"))
                cli->atmosphere = SKY_ATMOSPHERE_HILLAIRE;
            else if (val && !strcmp(val, "blend"))
                cli->atmosphere = SKY_ATMOSPHERE_BLEND;
            else
                return fail(err, len, "--atmosphere: expected gradient|preetham|rayleigh|hillaire|blend, got '%s'",
                            val ? val : "(nothing)");
        } else if (!strcmp(opt, "--preset")) {
            if (!val) return fail(err, len, "--preset: expected a preset name");
            if (!find_preset(val))
                return fail(err, len,
                            "--preset: unknown preset '%s' (accepted: noon, overcast, sunset, starry, moonlit, eclipse, "
                            "solar-eclipse, minimal)",
                            val);
            cli->preset = val;
        } else if (!is_demo && !strcmp(opt, "--out")) {
            if (!val || !*val) return fail(err, len, "--out: expected a file name");
            if (!has_extension(val, ".png"))
                return fail(err, len, "--out: expected a file name ending in .png (an 8-bit PNG; --out-pfm FILE.pfm "
                            "for linear float), got '%s'", val);
            cli->out_png = val;
        } else if (!is_demo && !strcmp(opt, "--out-pfm")) {
            if (!val || !*val) return fail(err, len, "--out-pfm: expected a file name");
            if (!has_extension(val, ".pfm"))
                return fail(err, len, "--out-pfm: expected a file name ending in .pfm (linear float RGB), got '%s'", val);
            cli->out_pfm = val;
        } else if (!is_demo && !strcmp(opt, "--out-shadow")) {
            if (!val || !*val || !has_extension(val, ".png"))
                return fail(err, len, "--out-shadow: expected a file name ending in .png, got '%s'",
                            val ? val : "(nothing)");
            cli->out_shadow = val;
        } else if (!is_demo && !strcmp(opt, "--shadow-extent")) {
            if (!parse_number(val, 0.01, 1000.0, &v))
                return fail(err, len, "--shadow-extent: expected kilometres in 0.01..1000, got '%s'",
                            val ? val : "(nothing)");
            cli->shadow_extent_km = v;
        } else if (is_demo && !strcmp(opt, "--screenshot")) {
            if (!val || !*val) return fail(err, len, "--screenshot: expected a file name");
            if (!has_extension(val, ".png"))
                return fail(err, len, "--screenshot: expected a file name ending in .png, got '%s'", val);
            cli->screenshot = val;
        } else {
            known = 0;
        }
        if (!known) return fail(err, len, "unknown option '%s' (see --help)", opt);
        i++; /* consumed the value */
    }
    if (cli->preset) {
        const preset *p = find_preset(cli->preset);
        apply_preset(cli, p, given);
        if (p->date) {
            int has_place = 0, has_view = 0;
            for (int k = 0; k < seen_count; k++) {
                has_place |= !strcmp(seen[k], "--lat") || !strcmp(seen[k], "--lon");
                has_view |= !strcmp(seen[k], "--yaw") || !strcmp(seen[k], "--pitch");
            }
            if (!have_date) {
                parse_date(p->date, &date_jd);
                have_date = 1;
            }
            if (!has_place) where.latitude_deg = p->lat, where.longitude_deg = p->lon;
            if (!has_view) cli->yaw = p->yaw, cli->pitch = p->pitch;
        }
    }
    if (cli->hip_count && !cli->query) return fail(err, len, "--hip: only meaningful with --query");
    /* Both outputs naming one file (a hard link, or a symbolic link, from
     * x.pfm to x.png) would keep only the image written last, silently.
     * The names themselves cannot be equal (.png against .pfm), but the
     * comparison stays should that rule ever loosen. With --frames the
     * names written are FILE_0001.png ..., not these, so the check is for
     * a single frame. */
    if (cli->out_png && cli->out_pfm && cli->frames == 1 && same_file(cli->out_png, cli->out_pfm))
        return fail(err, len, "--out '%s' and --out-pfm '%s' are the same file: one would overwrite the other",
                    cli->out_png, cli->out_pfm);
    /* --date alone: the instant as given; with --time: the time slider
     * sets the local solar time on that date; neither: sky.h's default
     * date, the time slider setting the time of day */
    cli->observer = where;
    cli->observer.julian_day_utc = have_date ? date_jd : sky_julian_day(2026, 3, 20, 12, 0, 0.0);
    cli->observer.time_from_params = !have_date || given[2 + 5];
    return SKY_CLI_OK;
}

sky_config sky_cli_config(const sky_cli *cli, sky_get_proc_address_fn loader)
{
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.features = cli->features;
    /* a weather on the command line asks for its shading */
    if ((cli->weather >= 0 || cli->weather_to >= 0) && cfg.features && cfg.features != SKY_FEATURES_NONE)
        cfg.features |= SKY_WEATHER;
    cfg.gl_profile = cli->gl;
    cfg.atmosphere = cli->atmosphere;
    cfg.moon_scale = cli->moon_scale;
    cfg.bortle = cli->bortle;
    cfg.kp = cli->kp;
    cfg.exposure_range = cli->exposure_range;
    cfg.seed = cli->seed;
    cfg.solar_activity_manual = cli->solar_activity_manual;
    cfg.solar_activity = cli->solar_activity;
    cfg.turbidity = cli->turbidity;
    cfg.dome_divisor = cli->dome_divisor;
    cfg.tone_map = cli->tone_map;
    cfg.luts = cli->luts;
    cfg.blend_manual = cli->blend_manual;
    cfg.blend_weight = cli->blend_weight;
    cfg.blend_partner = cli->blend_partner;
    sky_atmosphere_get_preset(cli->planet, &cfg.atmosphere_params);
    cfg.get_proc_address = loader;
    return cfg;
}

double sky_cli_now_ms(void)
{
#ifdef _WIN32
    /* MinGW's C runtime has no timespec_get */
    LARGE_INTEGER count, frequency;
    QueryPerformanceCounter(&count);
    QueryPerformanceFrequency(&frequency);
    return (double)count.QuadPart * 1e3 / (double)frequency.QuadPart;
#else
    struct timespec ts;
    timespec_get(&ts, TIME_UTC);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
#endif
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double sky_cli_median(double *v, int n)
{
    if (n <= 0) return 0.0;
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void sky_cli_camera(const sky_cli *cli, float view[16], float proj[16])
{
    sky_cli_camera_at(cli->yaw, cli->pitch, cli->fov, cli->width, cli->height, view, proj);
}

void sky_cli_camera_at(double yaw, double pitch, double fov, int width, int height, float view[16], float proj[16])
{
    double az = yaw * PI / 180.0, alt = pitch * PI / 180.0;
    /* horizon frame: +x east, +y up, +z south; azimuth from north (-z)
     * through east (+x) */
    double f[3] = {sin(az) * cos(alt), sin(alt), -cos(az) * cos(alt)};
    double r[3] = {cos(az), 0.0, sin(az)}; /* right: east when facing north */
    double u[3] = {r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2], r[0] * f[1] - r[1] * f[0]};
    memset(view, 0, 16 * sizeof(float));
    for (int c = 0; c < 3; c++) {
        view[c * 4 + 0] = (float)r[c];
        view[c * 4 + 1] = (float)u[c];
        view[c * 4 + 2] = (float)-f[c];
    }
    view[15] = 1.0f;
    double aspect = (double)width / height, z_near = 0.1, z_far = 1000.0;
    double t = 1.0 / tan(fov * PI / 360.0);
    memset(proj, 0, 16 * sizeof(float));
    proj[0] = (float)(t / aspect);
    proj[5] = (float)t;
    proj[10] = (float)((z_far + z_near) / (z_near - z_far));
    proj[11] = -1.0f;
    proj[14] = (float)(2.0 * z_far * z_near / (z_near - z_far));
}

static void print_place(FILE *out, const char *name, const sky_body_place *b)
{
    fprintf(out, "\"%s\": {\"alt\":%.6f, \"alt_geometric\":%.6f, \"az\":%.6f, \"ra\":%.6f, \"dec\":%.6f", name,
            b->alt_deg, b->alt_geometric_deg, b->az_deg, b->ra_deg, b->dec_deg);
}

void sky_cli_print_query(FILE *out, const sky_astronomy *a, const sky_star_place *stars, int count)
{
    fprintf(out, "{\"jd_ut\":%.8f, \"delta_t_s\":%.3f, \"lmst_deg\":%.6f,\n ", a->julian_day_ut, a->delta_t_s,
            a->lmst_deg);
    print_place(out, "sun", &a->sun);
    fprintf(out, ", \"distance_au\":%.8f},\n ", a->sun.distance_km / 149597870.7);
    print_place(out, "moon", &a->moon);
    fprintf(out,
            ", \"distance_km\":%.3f, \"illuminated_fraction\":%.6f, \"phase_angle\":%.6f, "
            "\"bright_limb_angle\":%.6f, \"libration_lat\":%.6f, \"libration_lon\":%.6f, "
            "\"axis_angle\":%.6f, \"parallactic_angle\":%.6f},\n",
            a->moon.distance_km, a->moon_illuminated_fraction, a->moon_phase_angle_deg, a->moon_bright_limb_deg,
            a->moon_libration_lat_deg, a->moon_libration_lon_deg, a->moon_axis_angle_deg, a->moon_parallactic_deg);
    fprintf(out, " \"eclipse\": {\"umbral_magnitude\":%.6f, \"penumbral_magnitude\":%.6f},\n", a->umbral_magnitude,
            a->penumbral_magnitude);
    fprintf(out, " \"solar_eclipse\": {\"obscuration\":%.6f, \"magnitude\":%.6f, \"flux_fraction\":%.6f},\n \"stars\": [",
            a->solar_obscuration, a->solar_magnitude, a->solar_flux_fraction);
    for (int i = 0; i < count; i++) {
        const sky_star_place *p = &stars[i];
        if (p->found)
            fprintf(out, "%s{\"hip\":%d, \"alt\":%.6f, \"alt_geometric\":%.6f, \"az\":%.6f, \"vmag\":%.2f, \"bv\":%.3f}",
                    i ? ", " : "", p->hip, p->alt_deg, p->alt_geometric_deg, p->az_deg, p->vmag, p->bv);
        else
            fprintf(out, "%s{\"hip\":%d, \"found\":false}", i ? ", " : "", p->hip);
    }
    fprintf(out, "],\n \"planets\": [");
    for (int i = 0; i < SKY_PLANET_COUNT; i++) {
        const sky_planet_place *p = &a->planets[i];
        fprintf(out,
                "%s{\"name\":\"%s\", \"alt\":%.6f, \"alt_geometric\":%.6f, \"az\":%.6f, \"ra\":%.6f, \"dec\":%.6f, "
                "\"distance_au\":%.8f, \"vmag\":%.3f, \"illuminated_fraction\":%.6f, \"phase_angle\":%.4f, "
                "\"diameter_arcsec\":%.3f}",
                i ? ",\n   " : "", sky_planet_name((sky_planet)i), p->place.alt_deg, p->place.alt_geometric_deg,
                p->place.az_deg, p->place.ra_deg, p->place.dec_deg, p->distance_au, p->vmag, p->illuminated_fraction,
                p->phase_angle_deg, p->diameter_arcsec);
    }
    fprintf(out, "],\n \"star_visibility\":%.6g, \"moon_visibility\":%.6g}\n", a->star_visibility,
            a->moon_visibility);
}

static const char *profile_name(sky_gl_profile p)
{
    return p == SKY_GL_CORE33 ? "core" : p == SKY_GL_ES20 ? "es20" : "compat";
}

static void print_vec3(FILE *out, const char *name, const float v[3], int comma)
{
    fprintf(out, "%s\"%s\":[%.6g, %.6g, %.6g]", comma ? ", " : "", name, v[0], v[1], v[2]);
}

void sky_cli_print_stats(FILE *out, sky *s, double frame_ms, double seconds)
{
    sky_stats stats;
    sky_get_stats(s, &stats);
    const sky_stats *st = &stats;
    fprintf(out, "{\"gl_version\":\"");
    for (const char *p = st->gl_version ? st->gl_version : ""; *p; p++)
        if (*p == '"' || *p == '\\')
            fprintf(out, "\\%c", *p);
        else if ((unsigned char)*p >= 0x20)
            fputc(*p, out);
    fprintf(out, "\", \"profile\":\"%s\", \"features\":[", profile_name(st->profile));
    int first = 1;
    for (size_t i = 0; i < sizeof feature_names / sizeof feature_names[0]; i++)
        if (st->features & feature_names[i].bit) {
            fprintf(out, "%s\"%s\"", first ? "" : ",", feature_names[i].name);
            first = 0;
        }
    fprintf(out, "], \"frame_ms\":%.4f, \"lut_ms\":%.4f, \"gpu_bytes\":%zu, \"textures\":%d, \"programs\":%d, "
                 "\"draws_per_frame\":%d, \"layers\":{",
            frame_ms, st->lut_ms, st->gpu_bytes, st->textures, st->programs, st->draws_per_frame);
    first = 1;
    for (int l = 0; l < sky_layer_count(); l++) {
        sky_layer_stats layer;
        const sky_layer_stats *ls = &layer;
        if (sky_get_layer_stats(s, l, &layer) != SKY_OK || !ls->enabled) continue;
        fprintf(out, "%s\"%s\":{\"ms\":", first ? "" : ", ", sky_layer_name((sky_layer)l));
        if (ls->ms >= 0.0)
            fprintf(out, "%.4f", ls->ms);
        else
            fprintf(out, "null");
        fprintf(out, ", \"draws\":%d, \"drawn\":%s, \"bytes\":%zu}", ls->draws, ls->drawn ? "true" : "false",
                ls->bytes);
        first = 0;
    }
    fprintf(out, "}");
    /* the light the host's scene gets, by sky.h's names */
    sky_lighting l;
    sky_get_lighting(s, &l);
    fprintf(out, ", \"lighting\":{");
    print_vec3(out, "sun_direction", l.sun_direction, 0);
    print_vec3(out, "sun_color", l.sun_color, 1);
    fprintf(out, ", \"sun_altitude_deg\":%.4f", l.sun_altitude_deg);
    print_vec3(out, "moon_direction", l.moon_direction, 1);
    print_vec3(out, "moon_color", l.moon_color, 1);
    print_vec3(out, "ambient_color", l.ambient_color, 1);
    print_vec3(out, "fog_color", l.fog_color, 1);
    print_vec3(out, "flash_color", l.flash_color, 1);
    print_vec3(out, "flash_direction", l.flash_direction, 1);
    fprintf(out, ", \"daylight\":%.6g, \"exposure\":%.6g, \"fog_density\":%.6g}", l.daylight, l.exposure,
            l.fog_density);
    sky_weather w;
    int moving = 0;
    sky_get_weather(s, &w, &moving);
    static const char *const kinds[3] = {"none", "rain", "snow"};
    /* its name: a named state's when the numbers are one's, "changing"
     * during a change, "custom" otherwise */
    const char *name = moving ? "changing" : "custom";
    for (int i = 0; i < SKY_WEATHER_COUNT && !moving; i++) {
        sky_weather p;
        sky_weather_preset((sky_weather_state)i, &p);
        if (p.cover == w.cover && p.density == w.density && p.visibility_km == w.visibility_km &&
            p.light_through == w.light_through && p.precipitation == w.precipitation)
            name = sky_weather_name((sky_weather_state)i);
    }
    fprintf(out,
            ", \"weather\":{\"name\":\"%s\", \"cover\":%.4f, \"density\":%.4f, \"upper\":%.4f, \"visibility_km\":%.4g, "
            "\"precipitation\":%.4f, \"precipitation_kind\":\"%s\", \"drop_size_mm\":%.3g, "
            "\"lightning_per_minute\":%.3g, \"wind_from_deg\":%.2f, \"wind_speed_ms\":%.3f, "
            "\"light_through\":%.4f, \"moving\":%s}",
            name, w.cover, w.density, w.upper, w.visibility_km, w.precipitation, kinds[w.precipitation_kind], w.drop_size_mm,
            w.lightning_per_minute, w.wind_from_deg, w.wind_speed_ms, w.light_through, moving ? "true" : "false");
    /* the strikes from time 0 (or a day before) to the frame's */
    enum { LISTED = 64 };
    sky_lightning_strike strikes[LISTED];
    int count = 0;
    double from = seconds > 86400.0 ? seconds - 86400.0 : 0.0;
    sky_get_lightning(s, from, seconds, strikes, LISTED, &count);
    fprintf(out, ", \"lightning_count\":%d, \"lightning\":[", count);
    for (int i = 0; i < count && i < LISTED; i++)
        fprintf(out, "%s{\"t\":%.4f, \"az\":%.2f, \"alt\":%.2f, \"distance_m\":%.0f, \"strokes\":%d}", i ? ", " : "",
                strikes[i].time, strikes[i].azimuth_deg, strikes[i].altitude_deg, strikes[i].distance_m,
                strikes[i].strokes);
    fprintf(out, "]}\n");
}

sky_result sky_cli_apply(sky *s, const sky_cli *cli)
{
    sky_result rc;
    if ((rc = sky_set_params(s, &cli->params)) < 0 || (rc = sky_set_observer(s, &cli->observer)) < 0) return rc;
    /* a new sky's running clock is at 0: the weather's changes start there */
    sky_weather w;
    if (cli->weather >= 0 && (sky_weather_preset((sky_weather_state)cli->weather, &w) < 0 ||
                              (rc = sky_set_weather(s, &w, 0.0)) < 0))
        return rc < 0 ? rc : SKY_ERR_INVALID_ARGUMENT;
    if (cli->weather_to >= 0 && (sky_weather_preset((sky_weather_state)cli->weather_to, &w) < 0 ||
                                 (rc = sky_set_weather(s, &w, cli->weather_seconds)) < 0))
        return rc < 0 ? rc : SKY_ERR_INVALID_ARGUMENT;
    if ((rc = sky_set_elapsed(s, cli->seconds)) < 0 || (rc = sky_set_exposure_bias(s, cli->exposure)) < 0) return rc;
    return SKY_OK;
}

int sky_cli_take_out(int *i, int argc, char **argv, const char *prog, const char **out)
{
    if (strcmp(argv[*i], "--out")) return 0;
    const char *val = *i + 1 < argc ? argv[*i + 1] : NULL;
    if (!val || !has_extension(val, ".png")) {
        fprintf(stderr, "%s: --out: expected a file name ending in .png, got '%s'\n", prog, val ? val : "(nothing)");
        return -1;
    }
    *out = val;
    (*i)++;
    return 1;
}
