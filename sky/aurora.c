/*
 * The aurora (SKY_AURORA): curtains of the oxygen green line (557.7 nm)
 * with red tops (630 nm) where the observer lies under or near the
 * auroral oval for the frame's Kp (cfg.kp, sky_set_kp). A night glow of
 * the dome's night variant (aurora.glsl), dimmed by the air below and
 * hidden by the clouds as the airglow is (dome.frag), its CPU twin
 * (aurora_at) seen by the SH irradiance and the lighting queries.
 *
 * Where. The observer's geomagnetic latitude in a centred dipole: the
 * IGRF-13 dipole's north pole for 2020.0, 80.65 N 72.68 W (Alken et al.
 * 2021, "International Geomagnetic Reference Field: the thirteenth
 * generation", Earth Planets Space 73:49, table 2). The oval's
 * equatorward edge for Kp is NOAA SWPC's table ("Tips on viewing the
 * aurora", swpc.noaa.gov: the geomagnetic latitude of the oval's
 * equatorward boundary, 66.5 degrees at Kp 0 to 48.1 at Kp 9),
 * interpolated for fractional Kp. Its poleward edge, which moves less, is
 * a model choice near the nightside boundary of Feldstein's ovals: 74
 * degrees at Kp 0, 0.4 lower a step. The curtains are east-west (along
 * geomagnetic east) lines across that band, one every CURTAIN_SPACING_KM
 * poleward of the edge, each wandering about its place, folded by two
 * sines along its length, with a slow envelope and fine rays: their
 * phases from cfg.seed (SplitMix64) and the running clock (wrapped to
 * whole turns here, in double, so the shader's phases stay small). The
 * oval is taken as its nightside all day long (no magnetic local time):
 * by day the sun hides it anyway.
 *
 * How it looks. A curtain is a vertical sheet; a view ray crosses it
 * once, at a ground distance s where its height is h = R (r0 cos e /
 * (R cos(e + s / R)) - 1) (e the elevation, R the Earth's radius, r0 the
 * observer's radius). The green emits from a sharp lower edge at 95-110
 * km fading upward over 30 km, the red from 170-250 km fading upward
 * over 50 km. The column is longer where the ray crosses the sheet
 * obliquely: by 1 / (|dD/ds| cos e_local), D the ray's distance from the
 * sheet across it, at most 6.7 (seen face-on: 1).
 *
 * How bright. A curtain seen face-on has I(Kp) = 3 kR * 1.45^Kp in the
 * green line (28 kR at Kp 6: an IBC II-III aurora; up to 6.7 times that
 * seen obliquely) and 0.03 + 0.01 Kp of that in the red line (0.09 at Kp
 * 6: a normal aurora's 630 nm is a tenth or less of its 557.7), in
 * rayleighs.
 * One rayleigh is 10^10 / (4 pi) photons s^-1 m^-2 sr^-1; a photon of
 * wavelength l carries h c / l (3.562e-19 J at 557.7 nm, 3.153e-19 at
 * 630), and a watt of it 683 V(l) lumens, the CIE 1931 photopic V (=
 * y-bar, CIE 015:2004's table: 0.9973 at 557.7 nm, interpolated, 0.2650
 * at 630). So 1 kR of the green is 1.93e-4 cd/m^2 and of the red 4.54e-5:
 * a Kp 6 curtain face-on is 5.4 mcd/m^2, some 30 times a dark zenith
 * (0.17 mcd/m^2). Their
 * colours are those lines' CIE 1931 x-bar, y-bar, z-bar through sRGB's
 * matrix, outside its gamut, the negative channels clipped to 0 (linear
 * sRGB per unit luminance: green 0.27, 1.32, 0; red 4.70, 0, 0).
 *
 * When. It shows while the band is within 2000 km (poleward or
 * equatorward) of the observer, which is as far as the red tops stand
 * above the horizon, and while its brightest curtain would add a
 * quarter of an 8-bit step at the exposure (as the other glows): the
 * day's and twilight's exposure, the moon's and the clouds' hide it.
 * Otherwise its light is zero (its uniforms and its twin). It adds
 * nothing to the zenith the exposure adapts to (glow_zenith is 0): the
 * night stays exposed for the night, and the aurora shows on it.
 */
#include "layer.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

#define EARTH_RADIUS_KM 6371.0
#define KM_PER_DEGREE (EARTH_RADIUS_KM * SKY_PI / 180.0)
#define POLE_LAT_DEG 80.65  /* IGRF-13, 2020.0 */
#define POLE_LON_DEG -72.68
#define POLEWARD_EDGE_KP0 74.0
#define POLEWARD_EDGE_PER_KP 0.4
#define CURTAIN_SPACING_KM 240.0
#define FOLD_KM 60.0         /* the folds' amplitude (the two sines' sum) */
#define REACH_KM 2000.0      /* the farthest band that shows */
#define GREEN_KR_KP0 3.0
#define GREEN_GAIN_PER_KP 1.45
#define OBLIQUITY_MAX (1.0 / 0.15)

/* NOAA SWPC: the oval's equatorward edge, geomagnetic latitude, Kp 0..9 */
static const double equatorward_edge_deg[10] = {66.5, 64.5, 62.4, 60.4, 58.3, 56.3, 54.2, 52.2, 50.1, 48.1};

typedef struct aurora_state {
    float axes[4];  /* xy: poleward unit vector's horizon x (east) and z
                       (south); z: observer's radius over the Earth's; w:
                       the rays' clock phase                            */
    float oval[4];  /* km poleward of the observer: equatorward edge,
                       poleward edge; z: the curtains' spacing; w: their
                       wander's clock phase                               */
    float green[4]; /* rgb: kcd/m^2 of a face-on curtain (0: nothing
                       shows); a: the seed's phase of the curtains' hash */
    float red[4];   /* rgb: the red tops, kcd/m^2 face-on; a: the folds'
                       clock phase                                        */
} aurora_state;

static const sky_uniform_desc aurora_uniforms[] = {
    SKY_US("u_aurora_axes", SKY_U_F4, aurora_state, axes),
    SKY_US("u_aurora_oval", SKY_U_F4, aurora_state, oval),
    SKY_USL("u_aurora_green", SKY_U_F4, aurora_state, green, SKY_RGB),
    SKY_USL("u_aurora_red", SKY_U_F4, aurora_state, red, SKY_RGB),
};
static const sky_snippet aurora_snippet = {"SKY_HAS_AURORA", "aurora.glsl", aurora_uniforms,
                                           SKY_UNIFORM_COUNT(aurora_uniforms), NULL, "sky_aurora", NULL};

/* The oval's equatorward edge for a Kp (0..9, clamped), degrees. */
static double equatorward_edge(double kp)
{
    kp = sky_clampd(kp, 0.0, 9.0);
    int i = (int)floor(kp);
    if (i >= 9) return equatorward_edge_deg[9];
    double f = kp - i;
    return equatorward_edge_deg[i] * (1.0 - f) + equatorward_edge_deg[i + 1] * f;
}

/* A number in [0, 1) from the seed and a key (SplitMix64's finaliser, as
 * lightning's). */
static double seed_uniform(unsigned seed, uint64_t key)
{
    uint64_t z = sky_mix64((uint64_t)seed * 0x9e3779b97f4a7c15ull ^ (key + 0x632be59bd9b4e019ull));
    return (double)(z >> 11) * (1.0 / 9007199254740992.0);
}

/* A clock's phase, in radians: t / period turns, wrapped in double. */
static double clock_phase(double t, double period_s, double offset_turns)
{
    double turns = t / period_s + offset_turns;
    return 2.0 * SKY_PI * (turns - floor(turns));
}

/* The observer's geomagnetic latitude (degrees) and the horizon unit
 * vector toward the nearer geomagnetic pole (x east, z south). */
static double geomagnetic(const sky_observer *o, double poleward[2])
{
    const double d = SKY_PI / 180.0;
    double lat = sky_clampd(o->latitude_deg, -90.0, 90.0) * d, dlon = (POLE_LON_DEG - o->longitude_deg) * d;
    double sp = sin(POLE_LAT_DEG * d), cp = cos(POLE_LAT_DEG * d);
    double sin_m = sky_clampd(sin(lat) * sp + cos(lat) * cp * cos(dlon), -1.0, 1.0);
    /* the great circle's bearing to the pole, from north through east */
    double az = atan2(sin(dlon) * cp, cos(lat) * sp - sin(lat) * cp * cos(dlon));
    double sign = sin_m < 0.0 ? -1.0 : 1.0; /* the south's: the antipode's bearing */
    poleward[0] = sign * sin(az);
    poleward[1] = -sign * cos(az);
    return asin(sin_m) / d;
}

/* The lines' colours, linear sRGB of unit luminance (see the top). */
static void line_colour(const double xyz_bar[3], double rgb[3])
{
    sky_xyz_to_linear_srgb(xyz_bar, rgb);
    for (int i = 0; i < 3; i++) rgb[i] = fmax(rgb[i], 0.0);
    double y = 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
    for (int i = 0; i < 3; i++) rgb[i] /= y;
}

/* kcd/m^2 per rayleigh of a line: wavelength nm, photopic V there */
static double kcd_per_rayleigh(double nm, double v)
{
    const double photons = 1e10 / (4.0 * SKY_PI), joules = 6.62607015e-34 * 2.99792458e8 / (nm * 1e-9);
    return photons * joules * 683.0 * v / 1000.0;
}

/* The frame's uniforms; the light stays zero when nothing can show. */
static void aurora_frame(sky_core *s, void *state)
{
    aurora_state *st = state;
    memset(st, 0, sizeof *st);
    s->frame.glows_key = 0.0f;
    double poleward[2];
    double lat_m = fabs(geomagnetic(&s->observer, poleward));
    double kp = sky_clampd(s->cfg.kp, 0.0, 9.0);
    double edge = equatorward_edge(kp), pole_edge = POLEWARD_EDGE_KP0 - POLEWARD_EDGE_PER_KP * kp;
    double nb = (edge - lat_m) * KM_PER_DEGREE, np = (pole_edge - lat_m) * KM_PER_DEGREE;
    double t = s->running;
    unsigned seed = s->cfg.seed;
    st->axes[0] = (float)poleward[0];
    st->axes[1] = (float)poleward[1];
    st->axes[2] = (float)((EARTH_RADIUS_KM + sky_clampd(s->observer.altitude_m / 1000.0, -0.5, 20.0)) /
                          EARTH_RADIUS_KM);
    st->axes[3] = (float)clock_phase(t, 97.0, seed_uniform(seed, 1));
    st->oval[0] = (float)nb;
    st->oval[1] = (float)np;
    st->oval[2] = (float)CURTAIN_SPACING_KM;
    st->oval[3] = (float)clock_phase(t, 601.0, seed_uniform(seed, 2));
    st->green[3] = (float)(64.0 * seed_uniform(seed, 3));
    st->red[3] = (float)clock_phase(t, 263.0, seed_uniform(seed, 4));
    /* out of reach: the band wholly farther than REACH_KM either way */
    if (!(s->features & SKY_AURORA) || nb > REACH_KM || np < -REACH_KM) return;
    static const double green_bar[3] = {0.5566, 0.9973, 0.00473}, red_bar[3] = {0.6424, 0.2650, 0.00005};
    double g[3], r[3];
    line_colour(green_bar, g);
    line_colour(red_bar, r);
    double kr = GREEN_KR_KP0 * pow(GREEN_GAIN_PER_KP, kp), red_share = 0.03 + 0.01 * kp;
    double green_l = kr * 1000.0 * kcd_per_rayleigh(557.7, 0.9973);
    double red_l = red_share * kr * 1000.0 * kcd_per_rayleigh(630.0, 0.2650);
    /* a quarter of an 8-bit step at the exposure, seen as obliquely as it
     * may be */
    if (green_l * OBLIQUITY_MAX * s->frame.exposure < 1.0 / 1024.0) return;
    for (int i = 0; i < 3; i++) {
        st->green[i] = (float)(green_l * g[i]);
        st->red[i] = (float)(red_l * r[i]);
    }
    /* the irradiance's cache follows the curtains (their zenith is 0) */
    s->frame.glows_key = st->green[1] * 1e6f + st->oval[0] + st->axes[3] + st->oval[3] + st->red[3];
}

/* ---- aurora.glsl's sky_aurora, in C (float where the shader's hash
 * wants the same rounding) ---------------------------------------------- */
static double aurora_hash(float k, float seed)
{
    float x = sinf(k * 12.9898f + seed) * 43758.5453f;
    return (double)(x - floorf(x));
}

/* the second hash of a curtain from its first (one sine a curtain) */
static double aurora_hash2(double h1)
{
    float x = (float)h1 * 61.7f + 0.37f;
    return (double)(x - floorf(x));
}

/* the fold of curtain (hashes h1, h2) at east coordinate e, and its
 * slope (its long wave's: what turns the curtain toward the eye) */
static double aurora_fold(double e, double h1, double h2, double phase, double *slope)
{
    double a1 = e / 330.0 + 6.2832 * h1 + phase, a2 = e / 130.0 + 6.2832 * h2 - 2.0 * phase;
    *slope = FOLD_KM * 0.65 / 330.0 * cos(a1);
    return FOLD_KM * (0.65 * sin(a1) + 0.35 * sin(a2));
}

/* the ground distance (km) where a ray of elevation e (sine y, cosine c)
 * reaches height h km from radius ratio r0 */
static double aurora_ground_at(double y, double c, double r0, double h)
{
    double e = asin(sky_clampd(y, -1.0, 1.0));
    return EARTH_RADIUS_KM * (acos(sky_clampd(c * r0 * EARTH_RADIUS_KM / (EARTH_RADIUS_KM + h), -1.0, 1.0)) - e);
}

static void aurora_at(const sky_core *s, const void *state, const double d[3], double rgb[3])
{
    (void)s;
    const aurora_state *st = state;
    rgb[0] = rgb[1] = rgb[2] = 0.0;
    if (d[1] <= 0.0 || (st->green[1] <= 0.0f && st->red[0] <= 0.0f)) return;
    double y = sky_clampd(d[1], 0.0, 1.0), c = sqrt(fmax(1.0 - y * y, 0.0)), r0 = st->axes[2];
    double hx = c > 1e-6 ? d[0] / c : 0.0, hz = c > 1e-6 ? d[2] / c : 0.0;
    /* poleward and geomagnetic east (poleward turned clockwise seen from
     * above: north's east) components of the ray's horizontal direction */
    double cn = hx * st->axes[0] + hz * st->axes[1], ce = -hx * st->axes[1] + hz * st->axes[0];
    double s_lo = aurora_ground_at(y, c, r0, 95.0), s_hi = aurora_ground_at(y, c, r0, 320.0);
    double n_lo = fmin(s_lo * cn, s_hi * cn) - FOLD_KM, nb = st->oval[0], np = st->oval[1], sp = st->oval[2];
    double k0 = fmax(floor((n_lo - nb) / sp - 0.8), 0.0);
    double cn_safe = cn < 0.0 ? fmin(cn, -0.03) : fmax(cn, 0.03);
    double e = asin(y);
    /* (the sheets the ray crosses and the fold's steps: aurora.glsl's, whose
     * cost they set: two sheets and one step keep a night with the aurora
     * near the night presets' cost) */
    for (int i = 0; i < 2; i++) {
        double k = k0 + i;
        double h1 = aurora_hash((float)k, st->green[3]), h2 = aurora_hash2(h1);
        double nk = nb + (k + 0.5 + 0.3 * sin(6.2832 * h1 + st->oval[3])) * sp;
        double oval = sky_smoothstep(nb - 100.0, nb + 100.0, nk) * (1.0 - sky_smoothstep(np - 200.0, np + 50.0, nk));
        double slope, g = nk / cn_safe;
        g = (nk + aurora_fold(g * ce, h1, h2, st->red[3], &slope)) / cn_safe;
        double east = g * ce;
        aurora_fold(east, h1, h2, st->red[3], &slope);
        double local = cos(e + g / EARTH_RADIUS_KM);
        if (g <= 0.0 || local <= 0.02) continue;
        double h = EARTH_RADIUS_KM * (r0 * c / local - 1.0);
        double green = sky_smoothstep(95.0, 110.0, h) * exp(-fmax(h - 110.0, 0.0) / 30.0);
        double red = sky_smoothstep(170.0, 250.0, h) * exp(-fmax(h - 250.0, 0.0) / 50.0);
        double oblique = 1.0 / fmax(fabs(cn - slope * ce) * local, 1.0 / OBLIQUITY_MAX);
        double envelope = 0.25 + 0.75 * sky_smoothstep(-0.3, 0.8, sin(east / 700.0 + 6.2832 * h2 + st->red[3]));
        double rays = 0.55 + 0.45 * sin(east / 15.0 + 40.0 * h1 + st->axes[3]) * sin(east / 6.5 + 2.0 * st->axes[3]);
        double w = oval * oblique * envelope * rays * (0.4 + 0.6 * h2);
        for (int j = 0; j < 3; j++) rgb[j] += (st->green[j] * green + st->red[j] * red) * w;
    }
}

/* Nothing at the zenith the exposure adapts to (see the top). */
static void aurora_zenith(const sky_core *s, const void *state, double rgb[3])
{
    (void)s;
    (void)state;
    rgb[0] = rgb[1] = rgb[2] = 0.0;
}

static int aurora_create(sky_core *s, void *state, char *err, size_t err_len)
{
    if (sky_snippet_bind(s, &aurora_snippet, state) == 0) return 0;
    sky_format(err, err_len, "out of memory");
    return -1;
}

static int aurora_visible(const sky_core *s, const void *state)
{
    (void)s;
    const aurora_state *st = state;
    return st->green[1] > 0.0f;
}

const sky_layer_class sky_aurora_layer = {
    .name = "aurora",
    .slot = SKY_LAYER_NEXT,
    .feature = SKY_AURORA,
    .state_size = sizeof(aurora_state),
    .dome_role = SKY_DOME_NIGHT_OCCASIONAL,
    .dome_snippet = &aurora_snippet,
    .create = aurora_create,
    .frame = aurora_frame,
    .visible = aurora_visible,
    .glow_zenith = aurora_zenith,
    .glow_at = aurora_at,
};

/* (in the amalgamation, one translation unit, its names end here) */
#undef EARTH_RADIUS_KM
#undef KM_PER_DEGREE
#undef POLE_LAT_DEG
#undef POLE_LON_DEG
#undef POLEWARD_EDGE_KP0
#undef POLEWARD_EDGE_PER_KP
#undef CURTAIN_SPACING_KM
#undef FOLD_KM
#undef REACH_KM
#undef GREEN_KR_KP0
#undef GREEN_GAIN_PER_KP
#undef OBLIQUITY_MAX
