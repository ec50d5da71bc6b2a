/*
 * The zodiacal light (SKY_ZODIACAL): sunlight scattered by the
 * interplanetary dust of the ecliptic plane, from the brightness table of
 * Leinert et al. 1998 ("The 1997 reference of diffuse night sky
 * brightness", A&AS 127, 1), table 17: at 500 nm, in 10^-8 W m^-2 sr^-1
 * um^-1, by the ecliptic longitude from the sun (0..180 degrees, rows) and
 * the ecliptic latitude (0..90, columns), both folded. Its cone along the
 * ecliptic after dusk and before dawn is the "false dawn"; the bump at 180
 * degrees the gegenschein. The table has no values within about 15
 * degrees of the sun (its 1e6 entries), where it is day or twilight for
 * any observer: they take the table's brightest value, 11 500. The
 * numbers were checked against the copy the EXOSIMS project distributes
 * (Leinert98_table17.txt).
 *
 * One S10 (a tenth-magnitude solar-type star per square degree) is 1.28
 * table units at 500 nm (Leinert et al. sec. 2), and the table's 77 at
 * the ecliptic pole is its 60 S10. The light is the sun's colour (B - V
 * 0.65), dimmed by the air below as the airglow is (dome.frag). Dome role
 * NIGHT (zodiacal.glsl), with a 64 x 32 RGBA8 texture of the table.
 */
#include "layer.h"

#include <math.h>
#include <string.h>

#define ZODI_ROWS 19 /* longitude from the sun: 0..45 by 5, then 60..180 by 15 */
#define ZODI_COLS 11 /* latitude: 0..30 by 5, then 45, 60, 75, 90 */
/* The texture resamples the table by what a pixel has with no more than
 * a square root: cos(lambda / 2) = sqrt((1 + cos lambda) / 2) of the angle
 * lambda from the sun along the ecliptic, 0..1 across (even steps in
 * lambda at the gegenschein, where the cosine itself would crowd them),
 * and the sine of the latitude, 0..1, down. */
#define ZODI_TEX_W 64
#define ZODI_TEX_H 32
#define ZODI_UNITS_PER_S10 1.28
#define ZODI_FLOOR 60.0   /* the encoding's 0 */
#define ZODI_RANGE 200.0  /* and its 255: 12 000 */
#define ZODI_SUN_BV 0.65

static const double leinert_table17[ZODI_ROWS][ZODI_COLS] = {
    {11500, 11500, 11500, 3140, 1610, 985, 640, 275, 150, 100, 77},
    {11500, 11500, 11500, 2940, 1540, 945, 625, 271, 150, 100, 77},
    {11500, 11500, 4740, 2470, 1370, 865, 590, 264, 148, 100, 77},
    {11500, 6780, 3440, 1860, 1110, 755, 525, 251, 146, 100, 77},
    {6400, 4480, 2410, 1410, 910, 635, 454, 237, 141, 99, 77},
    {3840, 2830, 1730, 1100, 749, 545, 410, 223, 136, 97, 77},
    {2480, 1870, 1220, 845, 615, 467, 365, 207, 131, 95, 77},
    {1650, 1270, 910, 680, 510, 397, 320, 193, 125, 93, 77},
    {1180, 940, 700, 530, 416, 338, 282, 179, 120, 92, 77},
    {910, 730, 555, 442, 356, 292, 250, 166, 116, 90, 77},
    {505, 442, 352, 292, 243, 209, 183, 134, 104, 86, 77},
    {338, 317, 269, 227, 196, 172, 151, 116, 93, 82, 77},
    {259, 251, 225, 193, 166, 147, 132, 104, 86, 79, 77},
    {212, 210, 197, 170, 150, 133, 119, 96, 82, 77, 77},
    {188, 186, 177, 154, 138, 125, 113, 90, 77, 74, 77},
    {179, 178, 166, 147, 134, 122, 110, 90, 77, 73, 77},
    {179, 178, 165, 148, 137, 127, 116, 96, 79, 72, 77},
    {196, 192, 179, 165, 151, 141, 131, 104, 82, 72, 77},
    {230, 212, 195, 178, 163, 148, 134, 105, 83, 72, 77},
};

typedef struct zodiacal_state {
    int texture;       /* its texture (registered at create)               */
    float rot[16];     /* horizon -> ecliptic of date, +x at the sun        */
    float light[4];    /* rgb: kcd/m^2 at the encoding's 0; a: ln range     */
    unsigned char texels[ZODI_TEX_W * ZODI_TEX_H]; /* as the texture holds
                          them, for the CPU twin                           */
} zodiacal_state;

static const sky_uniform_desc zodiacal_uniforms[] = {
    SKY_UTS("u_zodiacal_tex", zodiacal_state, texture),
    SKY_US("u_zodiacal_rot", SKY_U_M4, zodiacal_state, rot),
    SKY_USL("u_zodiacal", SKY_U_F4, zodiacal_state, light, SKY_RGB),
};
static const sky_snippet zodiacal_snippet = {"SKY_HAS_ZODIACAL", "zodiacal.glsl", zodiacal_uniforms,
                                             SKY_UNIFORM_COUNT(zodiacal_uniforms), NULL, "sky_zodiacal", NULL};

/* The table at (longitude from the sun, latitude) in degrees, bilinear
 * over its rows and columns. */
static double table_at(double lon, double lat)
{
    double row = lon < 45.0 ? lon / 5.0 : 9.0 + (lon - 45.0) / 15.0;
    double col = lat < 30.0 ? lat / 5.0 : 6.0 + (lat - 30.0) / 15.0;
    int r0 = (int)sky_clampd(floor(row), 0.0, ZODI_ROWS - 2), c0 = (int)sky_clampd(floor(col), 0.0, ZODI_COLS - 2);
    double fr = sky_clampd(row - r0, 0.0, 1.0), fc = sky_clampd(col - c0, 0.0, 1.0);
    return (leinert_table17[r0][c0] * (1 - fc) + leinert_table17[r0][c0 + 1] * fc) * (1 - fr) +
           (leinert_table17[r0 + 1][c0] * (1 - fc) + leinert_table17[r0 + 1][c0 + 1] * fc) * fr;
}

/* Texel (i, j) of the texture: the table where the pixel's u = (i + 1/2)
 * / W and sine of the latitude (j + 1/2) / H, as an 8-bit logarithm over
 * the encoding's range. The pixel's x (= cos latitude cos lambda) comes
 * back as 2 u^2 - 1. Made once at create into the state, whose copy the
 * CPU twin reads: it sees what the GPU interpolates. */
static unsigned char make_texel(int i, int j)
{
    double u = (i + 0.5) / ZODI_TEX_W, sb = (j + 0.5) / ZODI_TEX_H, cx = 2.0 * u * u - 1.0;
    double cb = sqrt(fmax(1.0 - sb * sb, 0.0));
    double lon = acos(sky_clampd(cb > 1e-9 ? cx / cb : 1.0, -1.0, 1.0)) * 180.0 / SKY_PI;
    double lat = asin(sb) * 180.0 / SKY_PI;
    double units = sky_clampd(table_at(lon, lat), ZODI_FLOOR, ZODI_FLOOR * ZODI_RANGE);
    return (unsigned char)lround(log(units / ZODI_FLOOR) / log(ZODI_RANGE) * 255.0);
}

/* Horizon -> ecliptic of date turned so that +x points at the sun, +z at
 * the ecliptic's north pole (row-major). */
static void ecliptic_frame(const sky_astro *a, double m[9])
{
    double ce = cos(a->obliquity), se = sin(a->obliquity);
    /* the horizon matrix's rows are east, up, south in equatorial
     * coordinates: its transpose takes horizon vectors back */
    double h_to_eq[9];
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) h_to_eq[r * 3 + c] = a->horizon[c * 3 + r];
    double eq_to_ecl[9] = {1, 0, 0, 0, ce, se, 0, -se, ce};
    double sun_eq[3] = {cos(a->sun.dec) * cos(a->sun.ra), cos(a->sun.dec) * sin(a->sun.ra), sin(a->sun.dec)};
    double sun_lon = atan2(eq_to_ecl[3] * sun_eq[0] + eq_to_ecl[4] * sun_eq[1] + eq_to_ecl[5] * sun_eq[2],
                           sun_eq[0]);
    double cl = cos(sun_lon), sl = sin(sun_lon);
    double turn[9] = {cl, sl, 0, -sl, cl, 0, 0, 0, 1};
    double t[9];
    sky_mat3_mul(eq_to_ecl, h_to_eq, t);
    sky_mat3_mul(turn, t, m);
}

/* kcd/m^2 at the encoding's 0 (ZODI_FLOOR table units), the sun's colour:
 * the frame's u_zodiacal */
static void floor_colour(double rgb[3])
{
    float colour[3];
    sky_star_color(ZODI_SUN_BV, colour);
    double per_unit = sky_mag_arcsec2_to_kcd(27.78) / ZODI_UNITS_PER_S10; /* one S10 is 27.78 mag/arcsec^2 */
    for (int i = 0; i < 3; i++) rgb[i] = per_unit * colour[i] * ZODI_FLOOR;
}

/* The state's copy of texel (i, j), clamped to the edges as GL does. */
static double texel(const zodiacal_state *st, int i, int j)
{
    i = i < 0 ? 0 : (i >= ZODI_TEX_W ? ZODI_TEX_W - 1 : i);
    j = j < 0 ? 0 : (j >= ZODI_TEX_H ? ZODI_TEX_H - 1 : j);
    return st->texels[j * ZODI_TEX_W + i];
}

/* The texture for a pixel's x and |z| in the frame, as GL's bilinear
 * filter with clamped edges reads it, decoded: the light over the
 * encoding's 0. */
static double texture_at(const zodiacal_state *st, double cx, double sb)
{
    double x = sqrt(fmax(0.5 + 0.5 * cx, 0.0)) * ZODI_TEX_W - 0.5, y = sb * ZODI_TEX_H - 0.5;
    int i0 = (int)floor(x), j0 = (int)floor(y);
    double fx = x - i0, fy = y - j0;
    double v = (texel(st, i0, j0) * (1 - fx) + texel(st, i0 + 1, j0) * fx) * (1 - fy) +
               (texel(st, i0, j0 + 1) * (1 - fx) + texel(st, i0 + 1, j0 + 1) * fx) * fy;
    return exp(v / 255.0 * log(ZODI_RANGE));
}

/* zodiacal.glsl's sky_zodiacal: the light from direction d for a
 * rotation m (row-major) and the light at the encoding's 0. */
static void zodiacal_in(const zodiacal_state *st, const double m[9], const double floor_rgb[3], const double d[3],
                        double rgb[3])
{
    rgb[0] = rgb[1] = rgb[2] = 0.0;
    if (d[1] <= 0.0) return;
    double e[3];
    for (int r = 0; r < 3; r++) e[r] = m[r * 3] * d[0] + m[r * 3 + 1] * d[1] + m[r * 3 + 2] * d[2];
    double over = texture_at(st, sky_clampd(e[0], -1.0, 1.0), sky_clampd(fabs(e[2]), 0.0, 1.0));
    for (int i = 0; i < 3; i++) rgb[i] = over * floor_rgb[i];
}

/* For the atmosphere stage, before this layer's frame: from the astronomy. */
static void zodiacal_zenith(const sky_core *s, const void *state, double rgb[3])
{
    double m[9], floor_rgb[3];
    ecliptic_frame(&s->astro, m);
    floor_colour(floor_rgb);
    const double up[3] = {0.0, 1.0, 0.0};
    zodiacal_in(state, m, floor_rgb, up, rgb);
}

/* After it: the frame's rotation and scale, as the shader has them. */
static void zodiacal_at(const sky_core *s, const void *state, const double d[3], double rgb[3])
{
    (void)s;
    const zodiacal_state *st = state;
    double m[9], floor_rgb[3] = {st->light[0], st->light[1], st->light[2]};
    for (int row = 0; row < 3; row++)
        for (int c = 0; c < 3; c++) m[row * 3 + c] = st->rot[c * 4 + row]; /* column-major mat4 */
    zodiacal_in(st, m, floor_rgb, d, rgb);
}

const float *sky_zodiacal_rotation(const void *zodiacal_state_) { return ((const zodiacal_state *)zodiacal_state_)->rot; }

static int zodiacal_create(sky_core *s, void *state, char *err, size_t err_len)
{
    zodiacal_state *st = state;
    unsigned char texels[ZODI_TEX_W * ZODI_TEX_H * 4];
    for (int row = 0; row < ZODI_TEX_H; row++)
        for (int col = 0; col < ZODI_TEX_W; col++) {
            unsigned char v = make_texel(col, row);
            st->texels[row * ZODI_TEX_W + col] = v;
            unsigned char *p = texels + 4 * (row * ZODI_TEX_W + col);
            p[0] = p[1] = p[2] = v;
            p[3] = 255;
        }
    st->texture = sky_texture_register(s);
    if (st->texture < 0 || sky_snippet_bind(s, &zodiacal_snippet, state)) {
        sky_format(err, err_len, "out of memory");
        return -1;
    }
    return sky_texture_create(s, (sky_texture_id)st->texture, s->creating_layer, texels, 4, ZODI_TEX_W,
                              ZODI_TEX_H, 0, err, err_len);
}

static void zodiacal_frame(sky_core *s, void *state)
{
    zodiacal_state *st = state;
    double m[9], floor_rgb[3];
    ecliptic_frame(&s->astro, m);
    memset(st->rot, 0, sizeof st->rot);
    for (int row = 0; row < 3; row++)
        for (int c = 0; c < 3; c++) st->rot[c * 4 + row] = (float)m[row * 3 + c];
    st->rot[15] = 1.0f;
    floor_colour(floor_rgb);
    for (int i = 0; i < 3; i++) st->light[i] = (float)floor_rgb[i];
    st->light[3] = (float)log(ZODI_RANGE);
}

/* In the night variant while its faintest, the ecliptic pole's 60 S10,
 * would add a quarter of an 8-bit step */
static int zodiacal_visible(const sky_core *s, const void *state)
{
    const zodiacal_state *st = state;
    double pole = 77.0 / ZODI_FLOOR * (0.2126 * st->light[0] + 0.7152 * st->light[1] + 0.0722 * st->light[2]);
    return pole * s->frame.exposure >= 1.0 / 1024.0;
}

const sky_layer_class sky_zodiacal_layer = {
    .name = "zodiacal",
    .slot = SKY_LAYER_ZODIACAL,
    .feature = SKY_ZODIACAL,
    .state_size = sizeof(zodiacal_state),
    .dome_role = SKY_DOME_NIGHT,
    .dome_snippet = &zodiacal_snippet,
    .create = zodiacal_create,
    .frame = zodiacal_frame,
    .visible = zodiacal_visible,
    .glow_zenith = zodiacal_zenith,
    .glow_at = zodiacal_at,
};
