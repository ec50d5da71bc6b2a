/*
 * The sky's light on a scene (issue: the sky lights the scene): its
 * radiance around the observer projected on real spherical harmonics of
 * degree 0..2 (Ramamoorthi & Hanrahan 2001, "An Efficient Representation
 * for Irradiance Environment Maps"), from the atmosphere's CPU twin, in
 * the world frame.
 */
#include "irradiance.h"
#include "camera.h"
#include "layer.h"
#include "atmosphere/atmosphere.h"

#include <math.h>
#include <string.h>

void sky_sh_basis(const double w[3], double y[SKY_SH_COUNT])
{
    double x = w[0], yy = w[1], z = w[2];
    y[0] = 0.282095;
    y[1] = 0.488603 * yy;
    y[2] = 0.488603 * z;
    y[3] = 0.488603 * x;
    y[4] = 1.092548 * x * yy;
    y[5] = 1.092548 * yy * z;
    y[6] = 0.315392 * (3.0 * z * z - 1.0);
    y[7] = 1.092548 * x * z;
    y[8] = 0.546274 * (x * x - yy * yy);
    double x2 = x * x, y2 = yy * yy, z2 = z * z;
    y[9] = 2.503343 * x * yy * (x2 - y2);
    y[10] = 1.770131 * yy * z * (3.0 * x2 - y2);
    y[11] = 0.946175 * x * yy * (7.0 * z2 - 1.0);
    y[12] = 0.669047 * yy * z * (7.0 * z2 - 3.0);
    y[13] = 0.105786 * (35.0 * z2 * z2 - 30.0 * z2 + 3.0);
    y[14] = 0.669047 * x * z * (7.0 * z2 - 3.0);
    y[15] = 0.473087 * (x2 - y2) * (7.0 * z2 - 1.0);
    y[16] = 1.770131 * x * z * (x2 - 3.0 * y2);
    y[17] = 0.625836 * (x2 * (x2 - 3.0 * y2) - y2 * (3.0 * x2 - y2));
}

/* degrees 6 and 8 about the horizon's up, t = up . direction */
void sky_sh_zonal(double t, double y[SKY_SH_COUNT])
{
    double t2 = t * t, t4 = t2 * t2, t6 = t4 * t2, t8 = t4 * t4;
    y[18] = 1.017107 * (231.0 * t6 - 315.0 * t4 + 105.0 * t2 - 5.0) / 16.0;
    y[19] = 1.163106 * (6435.0 * t8 - 12012.0 * t6 + 6930.0 * t4 - 1260.0 * t2 + 35.0) / 128.0;
}

/* Gauss-Legendre on -1..1: 8 nodes for the sky's elevation sine, 4 for
 * each of the ground's two bands */
static const double gl8_x[4] = {0.1834346425, 0.5255324099, 0.7966664774, 0.9602898565};
static const double gl8_w[4] = {0.3626837834, 0.3137066459, 0.2223810345, 0.1012285363};
static const double gl4_x[2] = {0.3399810436, 0.8611363116};
static const double gl4_w[2] = {0.6521451549, 0.3478548451};
enum { AZIMUTHS = 16 };

/* One ring of directions at elevation sine mu, weight w per unit of mu:
 * its radiance projected onto the basis in the world frame. */
static void ring(const sky_core *s, double mu, double w, double sh[SKY_SH_COUNT][3])
{
    double c = sqrt(fmax(1.0 - mu * mu, 0.0)), dphi = 2.0 * SKY_PI / AZIMUTHS;
    for (int a = 0; a < AZIMUTHS; a++) {
        double phi = (a + 0.5) * dphi, d[3] = {c * sin(phi), mu, -c * cos(phi)}, rgb[3], y[SKY_SH_COUNT];
        double cloud_alpha, cloud[3];
        sky_atmosphere_radiance(s, d, rgb);
        /* the clouds over it, as their mean over the drifting texture */
        sky_clouds_mean_at(s, d, &cloud_alpha, cloud);
        for (int i = 0; i < 3; i++) rgb[i] += (cloud[i] - rgb[i]) * cloud_alpha;
        float h[3] = {(float)d[0], (float)d[1], (float)d[2]}, wf[3];
        sky_camera_to_world(s, h, wf);
        double wd[3] = {wf[0], wf[1], wf[2]};
        sky_sh_basis(wd, y);
        sky_sh_zonal(d[1], y);
        for (int k = 0; k < SKY_SH_COUNT; k++)
            for (int i = 0; i < 3; i++) sh[k][i] += w * dphi * y[k] * rgb[i];
    }
}

void sky_irradiance_project(const sky_core *s, double sh[SKY_SH_COUNT][3])
{
    for (int k = 0; k < SKY_SH_COUNT; k++) sh[k][0] = sh[k][1] = sh[k][2] = 0.0;
    /* the sky: elevation sine 0..1 */
    for (int n = 0; n < 8; n++) {
        double x = n < 4 ? -gl8_x[3 - n] : gl8_x[n - 4], w = n < 4 ? gl8_w[3 - n] : gl8_w[n - 4];
        ring(s, 0.5 + 0.5 * x, 0.5 * w, sh);
    }
    /* the ground: the horizon's haze over its first 0.035 of sine, then
     * the ground itself down to the nadir (atmosphere.glsl's sky_ground) */
    static const double band[3] = {0.0, -0.035, -1.0};
    for (int b = 0; b < 2; b++) {
        double mid = 0.5 * (band[b] + band[b + 1]), half = 0.5 * (band[b] - band[b + 1]);
        for (int n = 0; n < 4; n++) {
            double x = n < 2 ? -gl4_x[1 - n] : gl4_x[n - 2], w = n < 2 ? gl4_w[1 - n] : gl4_w[n - 2];
            ring(s, mid + half * x, half * w, sh);
        }
    }
}

void sky_atmosphere_key(const sky_core *s, double key[SKY_ATMOSPHERE_KEY])
{
    const sky_frame *f = &s->frame;
    double mu = 0.0, alt = 0.0;
    int n = 0;
    for (int i = 0; i < 3; i++) {
        key[n++] = f->sun_dir[i];
        key[n++] = f->ground_rgb[i];
        key[n++] = f->fog_rgb[i];
        key[n++] = f->horizon_tint[i];
        key[n++] = f->sun_transmittance[i];
        key[n++] = f->moon_dir[i]; /* the moonlit gradient's aureole */
        key[n++] = f->moon_sky[i];
        key[n++] = f->perez_moon_zenith[i];
    }
    for (int i = 0; i < 4; i++) key[n++] = f->eclipse_sky[i];
    for (int i = 0; i < 9; i++) key[n++] = s->horizon_to_world[i];
    if (s->atmosphere == SKY_ATMOSPHERE_HILLAIRE || s->atmosphere == SKY_ATMOSPHERE_BLEND)
        sky_atmosphere_skyview_at(s, &mu, &alt);
    key[n++] = mu;
    key[n++] = alt;
    key[n++] = f->night_luminance;
    key[n++] = f->day_luminance;
    key[n++] = f->blend_weight;
    key[n++] = f->rl_geometry[0]; /* the observer's radius (physical paths) */
    key[n++] = s->observer.altitude_m;
    _Static_assert(8 * 3 + 4 + 9 + 7 == SKY_ATMOSPHERE_KEY, "the key's length");
}

const double (*sky_irradiance_cached(const sky_core *s, sky_irradiance_cache *cache))[3]
{
    const sky_frame *f = &s->frame;
    double key[SKY_IRRADIANCE_KEY];
    sky_atmosphere_key(s, key);
    int n = SKY_ATMOSPHERE_KEY;
    key[n++] = f->cloud_mean[0];
    key[n++] = f->cloud_mean[1];
    for (int i = 0; i < 3; i++) key[n++] = f->cloud_light[i];
    key[n++] = f->sunset;
    key[n++] = f->haze[0]; /* a weather's haze (its colour is fog_rgb's) */
    key[n++] = f->deck;
    key[n++] = f->glows_key; /* the aurora's curtains (aurora.c) */
    _Static_assert(SKY_ATMOSPHERE_KEY + 9 == SKY_IRRADIANCE_KEY, "the key's length");
    if (!cache->valid || memcmp(key, cache->key, sizeof key) != 0) {
        sky_irradiance_project(s, cache->sh);
        memcpy(cache->key, key, sizeof key);
        cache->valid = 1;
    }
    return (const double(*)[3])cache->sh;
}

void sky_irradiance_eval(const double sh[SKY_SH_COUNT][3], const double n[3], const double up[3], double out[3])
{
    /* the clamped cosine's convolution (Ramamoorthi & Hanrahan eq. 8):
     * A_0 = pi, A_1 = 2 pi / 3, A_2 = pi / 4, A_4 = -pi / 24 */
    double y[SKY_SH_COUNT];
    sky_sh_basis(n, y);
    sky_sh_zonal(n[0] * up[0] + n[1] * up[1] + n[2] * up[2], y);
    for (int i = 0; i < 3; i++) {
        double e = 0.0;
        for (int k = 0; k < SKY_SH_COUNT; k++) {
            double a = k == 0  ? SKY_PI
                       : k < 4  ? 2.0 * SKY_PI / 3.0
                       : k < 9  ? SKY_PI / 4.0
                       : k < 18 ? -SKY_PI / 24.0
                       : k < 19 ? SKY_PI / 64.0
                                : -SKY_PI / 128.0;
            e += a * sh[k][i] * y[k];
        }
        out[i] = e;
    }
}
