/*
 * Aerial perspective: the light the air between the observer and a point
 * scatters toward the observer, and what it lets through of the point's
 * own (Hillaire 2020 sec. 5.4; Bruneton's GetSkyRadianceToPoint). The
 * physics is Hillaire's ray march stopped at the point
 * (sky_hillaire_segment): single scattering with the sun's transmittance
 * and the multiple-scattering table, on the description the sky is drawn
 * with (its tables on the Hillaire and blend paths, tables of our own on
 * the others, made at the first call).
 *
 * Every path draws its own sky, and at the view ray's end the air's light
 * must be the sky drawn there (a far mountain fades into the horizon on
 * screen, not into a physical horizon the path does not draw). So the
 * march's light is scaled per channel by drawn / marched at the ray's end
 * (1 on the Hillaire path by day), at most 4 times; what the sky draws
 * beyond that (the night floor, which no sunlight explains) is laid along
 * the ray in proportion to its optical depth.
 *
 * A view below the horizon is taken as level at its azimuth. The host's
 * points lie on or above its ground, but its eye is rarely at the
 * observer's altitude: from the ground (altitude 0) every downward ray
 * meets the description's sphere at once, while the host's ground 2 km
 * away is seen 0.05 degrees down through 2 km of air at the ground's
 * density, which is what the level view has. A view down from high
 * altitude gets the level view's thinner air.
 */
#include "aerial.h"
#include "atmosphere/atmosphere.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void sky_aerial_free(sky_aerial_state *a)
{
    if (!a) return;
    sky_hillaire_free(&a->own);
    free(a->texels);
    free(a->values);
    free(a->profile);
    memset(a, 0, sizeof *a);
}

/* Hillaire's tables: the sky's own, or ours (the description the sky is
 * drawn with, averaged over the sRGB channels as the physical paths have
 * it), made once. */
static const sky_hillaire_tables *tables_for(const sky_core *s, sky_aerial_state *a)
{
    const sky_hillaire_tables *t = sky_atmosphere_tables(s);
    if (t && t->transmittance && t->multiscatter) return t;
    if (!a->own_ready) {
        char why[160];
        sky_hillaire_free(&a->own);
        if (sky_hillaire_init(&a->own, &s->atm_rgb, NULL, why, sizeof why)) return NULL;
        sky_hillaire_build_transmittance(&a->own);
        if (sky_hillaire_build_multiscatter(&a->own)) return NULL;
        a->own_ready = 1;
    }
    return &a->own;
}

/* The observer's altitude in the description's shell (km). */
static double observer_km(const sky_core *s, const sky_hillaire_tables *t)
{
    double top = t->atm.top_radius_km - t->atm.planet_radius_km;
    return sky_clampd(s->observer.altitude_m / 1000.0, 0.0, top);
}

/* The scale from the march's light (per unit sun) at the end of a view
 * ray to the sky drawn there: scale[c] (0..4) and the rest drawn beyond. */
static void scale_from(const sky_core *s, const double drawn[3], const double marched[3], double scale[3],
                       double rest[3])
{
    for (int c = 0; c < 3; c++) {
        double m = marched[c] * s->sun_irradiance_klx[c];
        scale[c] = m > 0.0 ? sky_clampd(drawn[c] / m, 0.0, 4.0) : 0.0;
        rest[c] = fmax(drawn[c] - scale[c] * m, 0.0);
    }
}

/* The marched light (per unit sun) and transmittance to km and to the
 * ray's end into the frame's units: the drawn sky's scale, the rest along
 * the optical depth. */
static void finish(const sky_core *s, const double scale[3], const double rest[3], const double marched[3],
                   const double tr[3], const double end_tr[3], double inscatter[3], double transmittance[3])
{
    for (int c = 0; c < 3; c++) {
        double share = end_tr[c] < 1.0 ? sky_clampd((1.0 - tr[c]) / (1.0 - end_tr[c]), 0.0, 1.0) : 0.0;
        inscatter[c] = scale[c] * marched[c] * s->sun_irradiance_klx[c] + rest[c] * share;
        transmittance[c] = sky_clampd(tr[c], 0.0, 1.0);
    }
}

/* A weather over the air's own light (weather.c), as aerial.glsl applies
 * it after the table (so that a change of weather remakes no table): under
 * its deck the air's light dims as the sky's does, and its haze
 * (Koschmieder's extinction beyond the clear sky's) hides what lies beyond
 * in the horizon's light. Nothing changes without one. */
void sky_aerial_weather(const sky_core *s, double km, double inscatter[3], double transmittance[3])
{
    const sky_frame *f = &s->frame;
    double dim = sky_aerial_deck_dim(s), haze = exp(-f->haze_beta * km * 1000.0);
    if (dim >= 1.0 && haze >= 1.0) return;
    for (int c = 0; c < 3; c++) {
        inscatter[c] = inscatter[c] * dim * haze + f->fog_rgb[c] * (1.0 - haze);
        transmittance[c] *= haze;
    }
}

double sky_aerial_deck_dim(const sky_core *s) { return 1.0 - sky_weather_deck_share(&s->frame); }

/* A view below the horizon taken as level at its azimuth (straight
 * down: the sun's). */
static void level_below(const sky_core *s, const double d[3], double v[3])
{
    v[0] = d[0], v[1] = d[1], v[2] = d[2];
    if (d[1] >= 0.0) return;
    double h = hypot(d[0], d[2]);
    const float *sun = s->frame.sun_dir;
    double hs = hypot(sun[0], sun[2]);
    v[0] = h > 1e-9 ? d[0] / h : hs > 1e-9 ? sun[0] / hs : 1.0;
    v[1] = 0.0;
    v[2] = h > 1e-9 ? d[2] / h : hs > 1e-9 ? sun[2] / hs : 0.0;
}

int sky_aerial_eval(const sky_core *s, sky_aerial_state *a, const double d[3], double km, double inscatter[3],
                    double transmittance[3])
{
    for (int c = 0; c < 3; c++) inscatter[c] = 0.0, transmittance[c] = 1.0;
    const sky_hillaire_tables *t = tables_for(s, a);
    if (!t) return -1;
    if (!(km > 0.0)) return 0;
    double sun[3] = {s->frame.sun_dir[0], s->frame.sun_dir[1], s->frame.sun_dir[2]}, alt = observer_km(s, t);
    double v[3], marched[3], tr[3], end[3], end_tr[3], drawn[3], scale[3], rest[3];
    level_below(s, d, v);
    /* (HUGE_VAL: the whole ray to the top) */
    sky_hillaire_segment(t, alt, v, sun, isfinite(km) ? km : HUGE_VAL, marched, tr);
    sky_hillaire_segment(t, alt, v, sun, HUGE_VAL, end, end_tr);
    sky_atmosphere_radiance(s, v, drawn);
    scale_from(s, drawn, end, scale, rest);
    finish(s, scale, rest, marched, tr, end_tr, inscatter, transmittance);
    sky_aerial_weather(s, isfinite(km) ? km : 1e4, inscatter, transmittance);
    return 0;
}

/* ---- the shader's table ------------------------------------------------------ */

void sky_aerial_shell(const sky_core *s, sky_aerial_state *a, double *observer_radius_km, double *top_km)
{
    const sky_hillaire_tables *t = tables_for(s, a);
    const sky_atmosphere_params *atm = t ? &t->atm : &s->atm_rgb;
    *observer_radius_km = atm->planet_radius_km + (t ? observer_km(s, t) : 0.0);
    *top_km = atm->top_radius_km;
}

/* a texel's coordinate in 0..1 (texel i holds i / (n - 1), as the
 * shader maps it) */
static double texel_x(int i, int n) { return (double)i / (n - 1); }

/* The slice's distance (km): 13 slices at D (k / 13)^2 after the
 * observer's, slice 14 at 2 D, the last at the ray's end (aerial.glsl
 * maps a distance between them). */
static double slice_km(int k)
{
    double D = SKY_AP_TABLE_M / 1000.0;
    if (k >= SKY_AP_SLICES - 1) return HUGE_VAL;
    if (k == SKY_AP_SLICES - 2) return 2.0 * D;
    double x = (double)k / (SKY_AP_SLICES - 3);
    return D * x * x;
}

/* The running sums at km: the light linear between two points, the
 * transmittance exponential. */
static void profile_at(const sky_hillaire_point *p, int n, double km, double light[3], double tr[3])
{
    int i = 1;
    while (i < n && p[i].km < km) i++;
    if (i >= n) {
        for (int c = 0; c < 3; c++) light[c] = p[n - 1].inscatter[c], tr[c] = p[n - 1].transmittance[c];
        return;
    }
    const sky_hillaire_point *a = &p[i - 1], *b = &p[i];
    double f = b->km > a->km ? sky_clampd((km - a->km) / (b->km - a->km), 0.0, 1.0) : 1.0;
    for (int c = 0; c < 3; c++) {
        light[c] = a->inscatter[c] + (b->inscatter[c] - a->inscatter[c]) * f;
        double ta = a->transmittance[c], tb = b->transmittance[c];
        tr[c] = ta > 0.0 && tb > 0.0 ? ta * pow(tb / ta, f) : ta + (tb - ta) * f;
    }
}

/* One 8-bit value of the table, rounded. */
static unsigned char byte_of(double x) { return (unsigned char)lrint(255.0 * sky_clampd(x, 0.0, 1.0)); }

int sky_aerial_table(const sky_core *s, sky_aerial_state *a)
{
    double key[SKY_ATMOSPHERE_KEY];
    sky_atmosphere_key(s, key);
    if (a->table_valid && memcmp(key, a->key, sizeof key) == 0) return 0;
    const sky_hillaire_tables *t = tables_for(s, a);
    if (!t) return -1;
    enum { AZ = SKY_AP_AZIMUTHS, EL = SKY_AP_ELEVATIONS, SL = SKY_AP_SLICES, W = SKY_AP_TABLE_W };
    size_t values = (size_t)EL * AZ * SL * 6;
    if (!a->texels && !(a->texels = malloc((size_t)W * SKY_AP_TABLE_H * 4))) return -1;
    if (!a->values && !(a->values = malloc(values * sizeof *a->values))) return -1;
    if (!a->profile && !(a->profile = malloc(SKY_HL_PROFILE_MAX * sizeof *a->profile))) return -1;
    const sky_frame *f = &s->frame;
    double sun[3] = {f->sun_dir[0], f->sun_dir[1], f->sun_dir[2]}, alt = observer_km(s, t);
    /* the sun's azimuth: the table's az = 0 (a zenith sun: any) */
    double sh = hypot(sun[0], sun[2]), sx = sh > 1e-9 ? sun[0] / sh : 1.0, sz = sh > 1e-9 ? sun[2] / sh : 0.0;
    double brightest = 0.0;
    for (int i = 0; i < AZ; i++) {
        double u = texel_x(i, AZ), caz = 1.0 - 2.0 * u * u, saz = sqrt(fmax(1.0 - caz * caz, 0.0));
        double hx = caz * sx - saz * sz, hz = caz * sz + saz * sx;
        for (int j = 0; j < EL; j++) {
            double y = texel_x(j, EL), el = y * y * SKY_PI / 2.0;
            double d[3] = {cos(el) * hx, sin(el), cos(el) * hz}, drawn[3], scale[3], rest[3];
            int n = sky_hillaire_profile(t, alt, d, sun, a->profile, SKY_HL_PROFILE_MAX);
            const sky_hillaire_point *end = &a->profile[n - 1];
            sky_atmosphere_radiance(s, d, drawn);
            scale_from(s, drawn, end->inscatter, scale, rest);
            for (int k = 0; k < SL; k++) {
                double light[3], tr[3];
                float *v = a->values + (((size_t)j * AZ + i) * SL + k) * 6;
                profile_at(a->profile, n, slice_km(k), light, tr);
                double in[3], out_tr[3];
                finish(s, scale, rest, light, tr, end->transmittance, in, out_tr);
                for (int c = 0; c < 3; c++) {
                    v[c] = (float)in[c];
                    v[3 + c] = (float)out_tr[c];
                    brightest = fmax(brightest, in[c]);
                }
            }
        }
    }
    /* 8 bits: the light's square root over the table's brightest (the
     * dim end keeps its steps small against itself), the transmittance
     * as it is */
    a->scale = brightest > 0.0 ? brightest : 1.0;
    for (int j = 0; j < EL; j++)
        for (int i = 0; i < AZ; i++)
            for (int k = 0; k < SL; k++) {
                const float *v = a->values + (((size_t)j * AZ + i) * SL + k) * 6;
                unsigned char *light = a->texels + ((size_t)j * W + (size_t)k * AZ + i) * 4;
                unsigned char *tr = a->texels + ((size_t)(j + EL) * W + (size_t)k * AZ + i) * 4;
                for (int c = 0; c < 3; c++) {
                    light[c] = byte_of(sqrt(v[c] / a->scale));
                    tr[c] = byte_of(v[3 + c]);
                }
                light[3] = tr[3] = 255;
            }
    memcpy(a->key, key, sizeof key);
    a->table_valid = 1;
    a->uploaded = 0;
    return 1;
}
