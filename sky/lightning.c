/*
 * Lightning (sky.h, "Weather"): strikes at the weather's rate, drawn from
 * cfg.seed and the running clock alone, so that the strikes of a time are
 * the same however the sky was stepped there and whatever it showed before.
 *
 * The clock is cut into one-second slots. A slot's strikes are a Poisson
 * draw at the rate of the weather in its middle (lightning_per_minute /
 * 60 a second), each with its time in the slot, azimuth, distance and the
 * number of its return strokes, all from a hash of (seed, slot, strike):
 * no state, no sequence to replay.
 *
 * A strike's light: three or four return strokes 40-90 ms apart (Rakov &
 * Uman 2003: 3-5 strokes, some 60 ms apart, each light pulse decaying in
 * tens of milliseconds), the first the brightest, over a fainter glow of
 * the channel that dies within half a second. Its peak illuminance on a
 * surface facing it falls with the square of the distance: 2 klx at a
 * kilometre (a flash lights a night landscape far beyond the full moon's
 * 0.3 lx, and shows through a storm's day).
 */
#include "core.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

/* (core.h) SplitMix64's finaliser (Steele, Lea & Flood 2014): a
 * well-mixed 64-bit hash. */
uint64_t sky_mix64(uint64_t z)
{
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/* A uniform number in [0, 1) from the four keys. */
static double uniform(unsigned seed, int64_t slot, int strike, int draw)
{
    uint64_t h = sky_mix64((uint64_t)seed * 0x9e3779b97f4a7c15ull ^ sky_mix64((uint64_t)slot + 0x632be59bd9b4e019ull));
    h = sky_mix64(h ^ ((uint64_t)(unsigned)strike << 32 | (uint64_t)(unsigned)draw));
    return (double)(h >> 11) * (1.0 / 9007199254740992.0);
}

#define SKY_STRIKES_PER_SLOT 4 /* the most a slot holds (60 a minute: P(> 4) < 0.4 %) */

/* The strikes of slot n (its second [n, n + 1)): up to SKY_STRIKES_PER_SLOT,
 * in time order; returns how many. */
static int slot_strikes(const sky_weather_clock *clock, unsigned seed, int64_t n, sky_lightning_strike *out)
{
    sky_weather w;
    sky_weather_at(clock, (double)n + 0.5, &w);
    double rate = w.lightning_per_minute / 60.0; /* the slot's expected count */
    if (!(rate > 0.0)) return 0;
    /* Poisson by inversion of its distribution */
    double u = uniform(seed, n, 0, 0), p = exp(-rate), cdf = p;
    int k = 0;
    while (u > cdf && k < SKY_STRIKES_PER_SLOT) {
        k++;
        p *= rate / k;
        cdf += p;
    }
    for (int j = 0; j < k; j++) {
        sky_lightning_strike *s = &out[j];
        /* distances 0.5 .. 15 km, even over the area around the observer */
        double r_km = 0.5 + 14.5 * sqrt(uniform(seed, n, j + 1, 1));
        s->time = (double)n + uniform(seed, n, j + 1, 0);
        s->azimuth_deg = (float)(360.0 * uniform(seed, n, j + 1, 2));
        s->distance_m = (float)(1000.0 * r_km);
        /* the flash's centre in the cloud, some 2 km up */
        s->altitude_deg = (float)(atan2(2.0, r_km) * 180.0 / SKY_PI);
        s->strokes = 3 + (int)(2.0 * uniform(seed, n, j + 1, 3));
    }
    /* in time order (insertion: four at most) */
    for (int i = 1; i < k; i++)
        for (int j = i; j > 0 && out[j].time < out[j - 1].time; j--) {
            sky_lightning_strike t = out[j];
            out[j] = out[j - 1];
            out[j - 1] = t;
        }
    return k;
}

int sky_lightning_strikes(const sky_weather_clock *clock, unsigned seed, double t0, double t1,
                          sky_lightning_strike *out, int max)
{
    int count = 0;
    if (!clock->set || !(t1 > t0)) return 0;
    for (int64_t n = (int64_t)floor(t0); (double)n < t1; n++) {
        sky_lightning_strike slot[SKY_STRIKES_PER_SLOT];
        int k = slot_strikes(clock, seed, n, slot);
        for (int j = 0; j < k; j++) {
            if (slot[j].time < t0 || slot[j].time >= t1) continue;
            if (count < max) out[count] = slot[j];
            count++;
        }
    }
    return count;
}

/* One strike's light at t, relative to its first stroke's peak. */
static double strike_light(const sky_lightning_strike *s, double t)
{
    double dt = t - s->time;
    if (dt < 0.0 || dt > 0.6) return 0.0;
    double light = 0.15 * exp(-dt / 0.15); /* the channel's glow */
    for (int k = 0; k < s->strokes; k++) {
        double at = 0.065 * k, amplitude = k ? 0.6 / k : 1.0;
        if (dt >= at) light += amplitude * exp(-(dt - at) / 0.025);
    }
    return light;
}

/* A strike's direction in the horizon frame (x east, y up, z south). */
static void strike_direction(const sky_lightning_strike *s, double d[3])
{
    double az = s->azimuth_deg * SKY_PI / 180.0, alt = s->altitude_deg * SKY_PI / 180.0;
    d[0] = cos(alt) * sin(az);
    d[1] = sin(alt);
    d[2] = -cos(alt) * cos(az);
}

/* The flashes at running time t: their summed illuminance on a surface
 * facing the brightest, klx, and its direction; and the deck as that one
 * lights it from inside: the luminance where it is lit (a cloud's albedo
 * over pi times some 25 klx, the channel's light a few hundred metres into
 * the cloud, whatever the distance: a lit patch keeps its luminance and
 * shrinks with distance) and how sharply it falls off around the flash. */
void sky_lightning_flash(const sky_weather_clock *clock, unsigned seed, double t, sky_flash *out)
{
    memset(out, 0, sizeof *out);
    out->dir[1] = 1.0f;
    sky_lightning_strike s[2 * SKY_STRIKES_PER_SLOT];
    int n = sky_lightning_strikes(clock, seed, t - 0.6, t, s, 2 * SKY_STRIKES_PER_SLOT);
    double total = 0.0, best = 0.0;
    for (int i = 0; i < n && i < 2 * SKY_STRIKES_PER_SLOT; i++) {
        double km = s[i].distance_m / 1000.0, pulse = strike_light(&s[i], t), e = 2.0 * pulse / (km * km);
        total += e;
        if (e > best) {
            double d[3];
            strike_direction(&s[i], d);
            for (int k = 0; k < 3; k++) out->dir[k] = (float)d[k];
            out->deck_kcd = (float)(25.0 * 0.8 / SKY_PI * pulse);
            /* the lit patch some 3 km across: exp(k (cos - 1)) halves at
             * about the angle it subtends */
            double half = atan2(1.5, km);
            out->sharpness = (float)(0.693 / (1.0 - cos(half)));
            best = e;
        }
    }
    out->klx = (float)total;
}
