/*
 * The moon after Mueller et al. 2012, sec. 2-3: a billboard sphere at the
 * topocentric moon, sized from its true distance times an artificial
 * scale c_d (eq. 1), oriented by libration, axis and parallactic angles
 * (eq. 2), shaded Lommel-Seeliger (eq. 3) scaled to the published phase
 * law (Krisciunas & Schaefer 1991), with earthshine (eq. 4), dimmed
 * by extinction, and, with SKY_LUNAR_ECLIPSE, darkened and reddened per fragment
 * by the Earth's shadow (sec. 3). Shaders: moon.vert/.frag.
 */
#include "layer.h"
#include "disc.h"
#include "moonlight.h"
#include "atmosphere/atmosphere.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Earthshine at new moon relative to the full moon's surface brightness:
 * about 1.5e-4 (the ashen light of a young crescent, near magnitude -3
 * spread over the disc, against the full moon's -12.7). */
#define MOON_EARTHSHINE 1.5e-4
#define MOON_QUAD_RADII 4.0 /* the quad reaches 4 disc radii: the halo */
/* The halo's profile over the quad (moon.frag), ((4 - r) / 3)^2 / r^2 for
 * r = 1..4 disc radii, integrated over the plane: 2 pi (16 ln 4 - 16.5) / 9 */
#define MOON_HALO_INTEGRAL (2.0 * SKY_PI * (16.0 * 1.3862943611198906 - 16.5) / 9.0)

/* Extinction over the moon's air mass, per channel, as for the stars
 * (the spherical shell of stars.vert over the atmosphere's zenith optical
 * depth, sky_night_extinction): the disc and the moonlight dim alike. */
static void moon_extinction(const sky_core *s, double ext[3]) { sky_night_extinction(s, s->astro.moon.dir, ext); }

/* Mueller's c_i: how much a total eclipse is brightened in LDR output, as
 * a photographer would lengthen the exposure */
#define ECLIPSE_BOOST 30.0

typedef struct moon_state {
    sky_program program;
    sky_disc_grid grid;       /* the moon's quad, tessellated               */
    float albedo_mean;        /* the albedo map's near-side mean            */
    unsigned char *albedo;    /* the map's red channel, 256x128, for lit_sum */
    double lit_key[12];       /* light and body the sum below was taken for */
    double lit_sum;           /* mean over the disc of albedo x the LS law  */
    double axes[3][3];        /* billboard x (right), y (up), moon direction */
    double radius_tan;        /* drawn disc radius on the tangent plane     */
    /* its uniforms (moon.vert/.frag) */
    float body[16], view[16], light[3], color[3], earthshine[3];
    struct {                  /* u_moon_terms                               */
        float phase_factor;   /* HLS phase factor relative to full (eq. 3)  */
        float unused;         /* (the lit side's own LDR exposure is in color) */
        float halo;           /* the night halo's share of the disc's light */
        float hides;          /* 0..1: the disc hides what is behind it    */
    } terms;
    float drawn_radius_tan;   /* radius_tan as the shader takes it          */
    float brighter;           /* LDR: 1 / the sunlit disc's own exposure scale */
    float shadow_offset[3], shadow_axis[3], shadow[4]; /* a lunar eclipse   */
} moon_state;
/* The uniform table reads the packed vec4 as four floats in a row. */
_Static_assert(sizeof(((moon_state *)0)->terms) == 4 * sizeof(float), "the moon's terms are a vec4");

static const sky_uniform_desc moon_uniforms[] = {
    SKY_UT("u_moon_tex", SKY_TEX_MOON),
    SKY_US("u_moon_body", SKY_U_M4, moon_state, body),
    SKY_US("u_moon_view", SKY_U_M4, moon_state, view),
    SKY_US("u_moon_light", SKY_U_F3, moon_state, light),
    SKY_USL("u_moon_color", SKY_U_F3, moon_state, color, SKY_RGB),
    SKY_US("u_moon_terms", SKY_U_F4, moon_state, terms),
    SKY_US("u_moon_earthshine", SKY_U_F3, moon_state, earthshine),
    SKY_US("u_moon_radius_tan", SKY_U_F1, moon_state, drawn_radius_tan),
    SKY_US("u_moon_brighter", SKY_U_F1, moon_state, brighter),
};
static const sky_snippet moon_snippet = {NULL, NULL, moon_uniforms, SKY_UNIFORM_COUNT(moon_uniforms), NULL, NULL, NULL};

static const sky_uniform_desc eclipse_uniforms[] = {
    SKY_UT("u_eclipse_tex", SKY_TEX_ECLIPSE),
    SKY_US("u_shadow_offset", SKY_U_F3, moon_state, shadow_offset),
    SKY_US("u_shadow_axis", SKY_U_F3, moon_state, shadow_axis),
    SKY_US("u_shadow", SKY_U_F4, moon_state, shadow),
};
static const sky_snippet eclipse_snippet = {"SKY_HAS_ECLIPSE", NULL, eclipse_uniforms,
                                         SKY_UNIFORM_COUNT(eclipse_uniforms), NULL, NULL, NULL};

/* Mueller's h(t) (sec. 3.2, fig. 5), our own fit of its four phenomena:
 * t in [0, 1/2] is the umbra (centre to edge), [1/2, 1] the penumbra.
 * Returned as log10 per channel. */
static void eclipse_h(double t, double out[3])
{
    /* penumbra: barely noticeable, darkening softly toward the umbra */
    double pen = t >= 0.5 ? (t - 0.5) / 0.5 : 0.0;
    double pen_h = log10(0.3 + 0.7 * pow(pen, 0.7));
    /* umbra: dark, red-orange, darker toward the centre; a bluish rim at
     * its edge (light that skimmed the upper atmosphere) */
    double u = t < 0.5 ? t / 0.5 : 1.0;
    double red = -3.7 + 1.6 * u * u, green = -4.4 + 1.8 * u * u, blue = -4.9 + 2.1 * u * u;
    double rim = exp(-(u - 0.97) * (u - 0.97) / (2 * 0.04 * 0.04));
    double umb[3] = {red, green + 0.6 * rim, blue + 1.4 * rim};
    /* a soft umbra edge: blend over t = 0.47..0.53 */
    double w = sky_smoothstep(0.47, 0.53, t);
    double penumbra_side = t >= 0.5 ? pen_h : log10(0.3);
    for (int c = 0; c < 3; c++) out[c] = (1.0 - w) * umb[c] + w * penumbra_side;
}

static int moon_create(sky_core *s, void *state, char *err, size_t err_len)
{
    moon_state *st = state;
    if (sky_texture_load(s, SKY_TEX_MOON, SKY_LAYER_MOON, "moon.png", 256, 128, 1, err, err_len)) return -1;
    /* the albedo map's mean over the full moon as seen, so the full disc's
     * mean luminance is moon_full_luminance: near-side texels weighted by
     * their area on the sphere (cos lat) times their foreshortening toward
     * the observer (cos lat cos lon, the sub-earth point at the map's
     * centre; libration moves it by a few degrees only) */
    unsigned char *albedo = NULL;
    if (sky_asset_load_rgba(s, "moon.png", 256, 128, &albedo, err, err_len)) return -1;
    double sum = 0.0, wsum = 0.0;
    for (int y = 0; y < 128; y++) {
        double cl = cos(((y + 0.5) / 128.0 - 0.5) * SKY_PI);
        for (int x = 64; x < 192; x++) {
            double w = cl * cl * cos(((x + 0.5) / 256.0 - 0.5) * 2.0 * SKY_PI);
            sum += w * albedo[4 * (y * 256 + x)] / 255.0, wsum += w;
        }
    }
    st->albedo = malloc(256 * 128);
    if (!st->albedo) {
        sky_png_free(albedo);
        sky_format(err, err_len, "out of memory for the moon's albedo");
        return -1;
    }
    for (int i = 0; i < 256 * 128; i++) st->albedo[i] = albedo[4 * i];
    sky_png_free(albedo);
    st->albedo_mean = (float)(sum / wsum);
    if (sky_disc_grid_create(s, &st->grid, "moon", err, err_len)) return -1;
    if (s->features & SKY_LUNAR_ECLIPSE) {
        unsigned char lut[128 * 4];
        for (int i = 0; i < 128; i++) {
            double h[3];
            eclipse_h((i + 0.5) / 128.0, h);
            for (int c = 0; c < 3; c++) lut[4 * i + c] = (unsigned char)lround(sky_clampd(-h[c] / 5.0, 0.0, 1.0) * 255.0);
            lut[4 * i + 3] = 255;
        }
        if (sky_texture_create(s, SKY_TEX_ECLIPSE, SKY_LAYER_MOON, lut, 4, 128, 1, 0, err, err_len)) return -1;
    }
    if (sky_snippet_bind(s, &moon_snippet, state) || sky_snippet_bind(s, &eclipse_snippet, state)) {
        sky_format(err, err_len, "out of memory");
        return -1;
    }
    const sky_snippet *own[2];
    int n = 0;
    if (s->features & SKY_LUNAR_ECLIPSE) own[n++] = &eclipse_snippet;
    own[n++] = &moon_snippet;
    return sky_program_build_over_dome(s, s->dome_snippets, &st->program, "moon.vert", "moon.frag", own, n, err,
                                       err_len);
}

static void moon_destroy(sky_core *s, void *state)
{
    moon_state *st = state;
    sky_program_destroy(s, &st->program);
    sky_disc_grid_destroy(s, &st->grid);
    free(st->albedo);
    st->albedo = NULL;
}

/* What moon.frag draws, summed over the disc on the CPU: the mean over the
 * disc (its projected area, a 48 x 48 grid) of albedo x cos i / (cos i +
 * cos r) for the sun direction l and the orientation body (both in the
 * billboard frame, as in the shader; the albedo texel nearest to the
 * shader's lookup). Dividing the phase law by it makes the drawn disc sum
 * to the moonlight whatever part of the map is lit: a crescent lights the
 * bright highlands at the limb, and a uniform-albedo law would leave it
 * 18 % too bright. Retaken only when the geometry has moved by 1e-3 (a
 * twentieth of a degree; the sum changes by under 0.1 % over that, a
 * thin crescent's by about 1 %): with the clock running it is 2304 texel
 * lookups that every frame would otherwise pay (their cost:
 * docs/validation.md). */
static double lit_sum(moon_state *st, const double l[3], const double body[9])
{
    double key[12] = {l[0], l[1], l[2]};
    for (int i = 0; i < 9; i++) key[3 + i] = body[i];
    int same = st->lit_sum > 0.0;
    for (int i = 0; i < 12 && same; i++) same = fabs(key[i] - st->lit_key[i]) < 1e-3;
    if (same) return st->lit_sum;
    const int n = 48;
    double sum = 0.0;
    int count = 0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            double u = (i + 0.5) / n * 2.0 - 1.0, v = (j + 0.5) / n * 2.0 - 1.0, r2 = u * u + v * v;
            if (r2 >= 1.0) continue;
            count++;
            double nz = sqrt(1.0 - r2);
            double cos_i = fmax(u * l[0] + v * l[1] + nz * l[2], 0.0);
            if (cos_i <= 0.0) continue;
            double bx = body[0] * u + body[1] * v + body[2] * nz;
            double by = body[3] * u + body[4] * v + body[5] * nz;
            double bz = body[6] * u + body[7] * v + body[8] * nz;
            double sx = 0.5 + atan2(bx, bz) / (2.0 * SKY_PI), sy = 0.5 - asin(sky_clampd(by, -1.0, 1.0)) / SKY_PI;
            int tx = (int)(sx * 256.0), ty = (int)(sy * 128.0);
            tx = tx < 0 ? 0 : tx > 255 ? 255 : tx;
            ty = ty < 0 ? 0 : ty > 127 ? 127 : ty;
            double albedo = st->albedo ? st->albedo[ty * 256 + tx] / 255.0 : 1.0;
            sum += albedo * cos_i / (cos_i + fmax(nz, 1e-4));
        }
    memcpy(st->lit_key, key, sizeof key);
    st->lit_sum = count ? sum / count : 0.0;
    return st->lit_sum;
}

static void cross3(const double a[3], const double b[3], double o[3])
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}
static void normalize3(double v[3])
{
    double n = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (n > 0) v[0] /= n, v[1] /= n, v[2] /= n;
}

double sky_moon_drawn_scale(const sky_core *s)
{
    const sky_astro *a = &s->astro;
    double cd = s->cfg.moon_scale > 0.0f ? sky_clampd(s->cfg.moon_scale, 0.5, 50.0) : 2.5;
    /* Mueller's c_d enlarges the moon; a solar eclipse needs both discs at
     * one scale for its contacts to fall at the right times. Near the sun
     * the moon returns to its true size: there it is a new moon, dark
     * against the day sky, so the change goes unseen (the sun growing
     * instead would be seen). The scale moves linearly with the
     * separation between `far`, where the enlarged disc is still clear of
     * the sun, and `near`, outside true contact; both the separation and
     * the radius sum rs + k rm are linear there, so no drawn disc touches
     * the sun before the true discs do. */
    double rs = a->sun_topo_semidiameter, rm = a->moon_topo_semidiameter;
    double near = 1.2 * (rs + rm), far = rs + fmax(cd, 1.0) * rm + 0.5 * (rs + rm);
    double w = sky_clampd((far - a->sun_moon_separation) / (far - near), 0.0, 1.0);
    return cd + (1.0 - cd) * w;
}

static void moon_frame(sky_core *s, void *state)
{
    moon_state *st = state;
    sky_frame *f = &s->frame;
    const sky_astro *a = &s->astro;
    double m[3] = {a->moon.dir[0], a->moon.dir[1], a->moon.dir[2]}; /* refracted, topocentric */
    /* The disc is shaped around the moon's true centre (moon.frag takes
     * each fragment back through refraction, so a low moon is flattened
     * like the sun); the quad that holds it is centred where refraction
     * shows the centre. Billboard frame: z toward the viewer, y toward
     * the zenith, x right; x is horizontal, so it is the same for both. */
    const double *mt = a->moon.dir_geometric;
    double z[3] = {-mt[0], -mt[1], -mt[2]}, up[3] = {0.0, 1.0, 0.0}, x[3], y[3];
    if (fabs(mt[1]) > 0.999) up[1] = 0.0, up[2] = -1.0; /* at the zenith: north up */
    double dz = up[0] * mt[0] + up[1] * mt[1] + up[2] * mt[2];
    for (int i = 0; i < 3; i++) y[i] = up[i] - dz * mt[i];
    normalize3(y);
    cross3(y, z, x);
    for (int i = 0; i < 3; i++) {
        st->axes[0][i] = x[i];
        st->axes[1][i] = y[i];
        st->axes[2][i] = m[i];
    }
    memset(st->view, 0, sizeof st->view);
    for (int i = 0; i < 3; i++) st->view[0 * 4 + i] = (float)x[i], st->view[1 * 4 + i] = (float)y[i],
                                st->view[2 * 4 + i] = (float)z[i];
    st->view[15] = 1.0f;
    /* sun seen from the moon: the exact phase geometry */
    double l[3];
    double phase = sky_moon_sun_from_moon(a, l);
    double l_view[3] = {l[0] * x[0] + l[1] * x[1] + l[2] * x[2], l[0] * y[0] + l[1] * y[1] + l[2] * y[2],
                        l[0] * z[0] + l[1] * z[1] + l[2] * z[2]};
    for (int i = 0; i < 3; i++) st->light[i] = (float)l_view[i];
    /* orientation (eq. 2): body = Ry(l) Rx(-b) Rz(-(P - q)) view */
    double alpha = a->moon_axis_angle - a->moon_parallactic, lb = a->moon_libration_lat, ll = a->moon_libration_lon;
    double ca = cos(-alpha), sa = sin(-alpha), cb = cos(-lb), sb = sin(-lb), cl = cos(ll), sl = sin(ll);
    double rz[9] = {ca, -sa, 0, sa, ca, 0, 0, 0, 1};
    double rx[9] = {1, 0, 0, 0, cb, -sb, 0, sb, cb};
    double ry[9] = {cl, 0, sl, 0, 1, 0, -sl, 0, cl};
    double t1[9], body[9];
    sky_mat3_mul(rx, rz, t1);
    sky_mat3_mul(ry, t1, body);
    memset(st->body, 0, sizeof st->body);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) st->body[j * 4 + i] = (float)body[i * 3 + j];
    st->body[15] = 1.0f;
    /* brightness: moon.frag shapes the lit part with Lommel-Seeliger
     * (Mueller eq. 3); the factor scales it so the disc sums to the
     * published phase law, the one sky_moon_lighting uses (Mueller's
     * Hapke B(phi) S(phi) on top of the per-point law counts the phase
     * twice: a quarter moon came out 34 % too faint, a 30 degree crescent
     * 13 times). moon_color carries full / albedo_mean, so the factor is
     * law x albedo_mean / lit_sum; at full, where cos i = cos r makes the
     * law 1/2, it is 2. Capped there: no lit point outshines the full
     * moon's. For a uniform disc the cap binds past about 170 degrees
     * (the Lommel-Seeliger disc integral, 1 - sin(a/2) tan(a/2) ln cot(a/4)
     * (Hapke, Theory of Reflectance and Emittance Spectroscopy), falls
     * faster than the published law there), where the earthshine takes
     * over. */
    double lsum = lit_sum(st, l_view, body);
    double law = sky_moon_phase_law(phase) * st->albedo_mean;
    double phase_factor = fmin(law / fmax(lsum, 1e-9), 2.0);
    /* halo (moon.frag): at night, light the air scatters just off the
     * disc, 2e-3 of the full moon's moon_color at the limb falling off as
     * 1 / r^2 (windowed to the quad's edge), following the phase law like
     * the disc. Its flux, moon_color x halo x HALO_INTEGRAL, is taken out
     * of the disc (moon_color x pi x law x albedo_mean): the layer's total
     * stays the moonlight. */
    double halo = 2e-3 * sky_moon_phase_law(phase) * a->star_visibility;
    double halo_share = halo * MOON_HALO_INTEGRAL / (SKY_PI * fmax(law, 1e-12));
    phase_factor *= 1.0 - sky_clampd(halo_share, 0.0, 0.5);
    /* earthshine (eq. 4), normalised to its new-moon value */
    double es = (-0.0061 * pow(SKY_PI, 3) + 0.0289 * SKY_PI * SKY_PI);
    double e = (-0.0061 * pow(phase, 3) + 0.0289 * phase * phase - 0.0105 * sin(phase)) / es;
    e = sky_clampd(e, 0.0, 1.0) * MOON_EARTHSHINE;
    static const double beta_e[3] = {0.88, 0.96, 1.00}; /* earthshine colour */
    double ext[3];
    moon_extinction(s, ext);
    /* Mueller's day-night factor (sec. 5) is the eye's, not the moon's:
     * LDR only, so HDR output is the moon's own luminance and sums to the
     * moonlight sky_get_lighting reports */
    double fade = f->output_hdr > 0.5f ? 1.0 : a->moon_visibility;
    double full = sky_moon_full_luminance();
    double scale = full / (st->albedo_mean > 0.01f ? st->albedo_mean : 0.01f);
    for (int i = 0; i < 3; i++) st->color[i] = (float)(scale * sky_moon_k_lambda[i] * ext[i] * fade);
    st->terms.phase_factor = (float)phase_factor;
    for (int i = 0; i < 3; i++) st->earthshine[i] = (float)(e * beta_e[i]); /* bluish */
    st->terms.halo = (float)halo;
    /* In a dark sky the disc hides what is behind it (stars). While the
     * sky is brighter than about 1e-6 kcd/m^2 (the sun above -15 degrees)
     * the air in front of the moon shines too: the disc only adds, so its
     * dark side is never darker than the sky around it. */
    st->terms.hides = (float)sky_smoothstep(1e-5, 1e-6, f->sky_luminance);
    /* LDR: expose the sunlit moon on its own, as the eye adapts to it
     * locally: its lit mean lands at the tone curve's shoulder instead of
     * pure white. The earthshine keeps the scene's exposure, so the ashen
     * light still stands out from the twilight. HDR output stays physical. */
    double k = 1.0;
    if (f->output_hdr < 0.5f) {
        double lit = full * fmax(phase_factor * 0.5, 1e-6) * fade;
        k = fmin(1.0, 2.5 / (f->exposure * lit));
        /* the eye compresses the ashen light too: it adds at most about
         * a quarter of the sky's brightness around the moon, so the dark side reads
         * as a glow slightly above the sky, not as a second moon */
        double es_mean = full * fade * e;
        double cap = 0.25 * (0.5 * f->sky_luminance + f->night_luminance);
        if (es_mean > cap)
            for (int i = 0; i < 3; i++) st->earthshine[i] *= (float)(cap / es_mean);
    }
    /* moon.frag takes k in the colour and the earthshine over it: the
     * colour times the exposure alone is past a mediump fragment stage's
     * 2^14 under a full moon at night (sky_frame.light_scale) */
    for (int i = 0; i < 3; i++) {
        st->color[i] *= (float)k;
        st->earthshine[i] /= (float)k;
    }
    /* the disc is as bright as it is for the eye's cones, whatever its
     * own exposure: the blue shift of night vision leaves its colour
     * (display.glsl) */
    st->brighter = (float)(1.0 / k);
    /* quad size (eq. 1): the disc's tangent-plane radius tan(c_d delta / 2),
     * delta the topocentric diameter (up to 2 % larger than the
     * geocentric one with the moon high: an eclipse's totality needs it) */
    st->radius_tan = tan(sky_moon_drawn_scale(s) * a->moon_topo_semidiameter);
    st->drawn_radius_tan = (float)st->radius_tan;
    /* eclipse: geocentric geometry in the horizon frame */
    if (s->features & SKY_LUNAR_ECLIPSE) {
        double mg[3], sg[3], v[3];
        v[0] = cos(a->moon.dec) * cos(a->moon.ra), v[1] = cos(a->moon.dec) * sin(a->moon.ra), v[2] = sin(a->moon.dec);
        for (int i = 0; i < 3; i++) mg[i] = a->horizon[i * 3] * v[0] + a->horizon[i * 3 + 1] * v[1] + a->horizon[i * 3 + 2] * v[2];
        v[0] = cos(a->sun.dec) * cos(a->sun.ra), v[1] = cos(a->sun.dec) * sin(a->sun.ra), v[2] = sin(a->sun.dec);
        for (int i = 0; i < 3; i++) sg[i] = a->horizon[i * 3] * v[0] + a->horizon[i * 3 + 1] * v[1] + a->horizon[i * 3 + 2] * v[2];
        /* in the moon's true radii (the disc as drawn is c_d times too big;
         * the shadow keeps the true geometry), and across the shadow's
         * axis: km at the moon's distance are past a mediump fragment
         * stage's 2^14. The centre's offset from the axis; a moon on the
         * sun's side of the earth is far from the shadow. */
        double km = a->moon.distance_km, along = km * (mg[0] * sg[0] + mg[1] * sg[1] + mg[2] * sg[2]);
        for (int i = 0; i < 3; i++) {
            st->shadow_axis[i] = (float)sg[i];
            st->shadow_offset[i] = along < 0.0 ? (float)((km * mg[i] - along * sg[i]) / SKY_MOON_RADIUS_KM) : 0.0f;
        }
        if (along >= 0.0) st->shadow_offset[0] = 1e3f;
        st->shadow[0] = (float)(km * tan(a->umbra_radius) / SKY_MOON_RADIUS_KM);
        st->shadow[1] = (float)(km * tan(a->penumbra_radius) / SKY_MOON_RADIUS_KM);
        st->shadow[2] = st->shadow[1] - st->shadow[0];
        /* i(t_m): brighten a deep eclipse in LDR (Mueller sec. 3.2.1) */
        double tm = a->umbral_magnitude;
        double boost = 1.0 + (ECLIPSE_BOOST - 1.0) * sky_smoothstep(0.0, 1.0, tm);
        st->shadow[3] = f->output_hdr > 0.5f ? 1.0f : (float)boost;
    }
}

static int moon_visible(const sky_core *s, const void *state)
{
    const moon_state *st = state;
    if (!st->grid.vertices) return 0;
    /* the whole quad, halo included, below the horizon */
    return s->astro.moon.alt > -atan(MOON_QUAD_RADII * st->radius_tan) - 0.01;
}

static int moon_draw(sky_core *s, void *state)
{
    moon_state *st = state;
    sky_disc_grid_update(s, &st->grid, st->axes[2], st->axes[0], st->axes[1], MOON_QUAD_RADII * st->radius_tan,
                         MOON_QUAD_RADII);
    sky_program_apply(s, &st->program);
    sky_disc_grid_draw(s, &st->grid, s->astro.moon.alt, atan(MOON_QUAD_RADII * st->radius_tan));
    return 1;
}

static size_t moon_buffer_bytes(const sky_core *s, const void *state)
{
    (void)s;
    return sky_disc_grid_bytes(&((const moon_state *)state)->grid);
}

void sky_moon_lighting(const sky_core *s, float moon_color[3])
{
    /* above the air, through the same extinction as the disc, times the
     * part of the disc not yet set */
    const sky_astro *a = &s->astro;
    double top[3], ext[3];
    sky_moon_light_above_air(s, top);
    moon_extinction(s, ext);
    double up = sky_disc_above_horizon(a->moon.alt, a->moon_topo_semidiameter);
    for (int i = 0; i < 3; i++) moon_color[i] = (float)(top[i] * ext[i] * up);
}

/* The moon: added by day; at night it also hides the stars behind it
 * (premultiplied: its coverage times the night factor is its alpha). */
const sky_layer_class sky_moon_layer = {
    .name = "moon",
    .slot = SKY_LAYER_MOON,
    .feature = SKY_MOON,
    .state_size = sizeof(moon_state),
    .blend = SKY_BLEND_PREMULTIPLIED,
    .create = moon_create,
    .destroy = moon_destroy,
    .frame = moon_frame,
    .visible = moon_visible,
    .draw = moon_draw,
    .buffer_bytes = moon_buffer_bytes,
};
