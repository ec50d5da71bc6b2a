/*
 * What the 8-bit output does to the sky's colours (issue "Look"): one
 * frame rendered twice, linear (HDR) and tone-mapped (LDR), and compared
 * per pixel. sky-bench prints the table; the tests hold two paths to it.
 */
#ifndef SKY_COLOUR_H
#define SKY_COLOUR_H

#include "sky.h"

#include <stddef.h>

/* The sun heights of the table, degrees. The colour targets hold from -4
 * to 60; -8 is there for the twilight ground. */
#define SKY_COLOUR_SUNS 8
extern const double sky_colour_suns[SKY_COLOUR_SUNS];

typedef struct sky_colour_row {
    sky_atmosphere_path path;
    sky_tone_map tone_map;
    double sun_deg;        /* asked for; the frame's is within 0.01 degree */
    int toward;            /* 1: facing the sun, pitch 8; 0: away, pitch 20  */
    /* over sky pixels more than 3 degrees from the sun whose linear
     * saturation exceeds 0.15 and whose 8-bit value (largest channel) is
     * at least 25; -1 when there are none */
    int counted;
    double saturation_kept_median, saturation_kept_p10; /* LDR / HDR        */
    double hue_shift_median, hue_shift_p90;            /* degrees           */
    double clipped;        /* share of all sky pixels with a channel at 255 */
    /* below the horizon (HDR): the ground within 4 degrees of the sun's
     * azimuth over the ground further than 20 degrees from it (sun 0..8
     * degrees and facing it; else -1), and the ground's mean luminance over
     * the sky's (sun below the horizon; else -1) */
    double pillar, ground_to_sky;
} sky_colour_row;

/* Renders the frame (the sunset preset's place and date, the sun at
 * sun_deg, the atmosphere and the sun only, size w x h) with both outputs
 * and fills row. Returns 0, or -1 with err. */
int sky_colour_measure(sky_atmosphere_path path, sky_tone_map tone_map, sky_gl_profile profile, double sun_deg,
                       int toward, int w, int h, sky_colour_row *row, char *err, size_t err_len);

/* The day's end (issue "Dusk and night"): the sun heights of its table,
 * noon (50 degrees on the default date and place) first. */
#define SKY_DUSK_SUNS 10
extern const double sky_dusk_suns[SKY_DUSK_SUNS];

/* The mean display luminance (the 8-bit sRGB values decoded to linear) of
 * the sky more than 5 degrees up, averaged over a view toward the sun
 * (pitch 10) and one away from it (pitch 20), 60 degrees high, w x h: the
 * library's default features with the clouds off, its default date and
 * place, the sun at sun_deg in the evening (or at noon). */
int sky_dusk_brightness(sky_atmosphere_path path, sky_gl_profile profile, double sun_deg, int w, int h, double *mean,
                        char *err, size_t err_len);
/* The day's end of a path: each of sky_dusk_suns' brightness over noon's
 * (rel[0] = 1), w x h. Returns 0, or -1 with err. */
int sky_dusk_measure(sky_atmosphere_path path, sky_gl_profile profile, int w, int h, double rel[SKY_DUSK_SUNS],
                     char *err, size_t err_len);
/* Whether a day's end meets its targets: at most 0.5 of noon at -6
 * degrees, 0.2 at -12 and 0.1 at -18; from 4 degrees down no step more
 * than 5 % brighter than the one before; sunset (0) no brighter than noon.
 * Why not in why. */
int sky_dusk_ok(const double rel[SKY_DUSK_SUNS], char *why, size_t why_len);

/* The night (issue "Dusk and night"): the sky more than 10 degrees up in
 * a 60-degree view, the library's default features and the moon, clouds
 * off: a full moon 67 degrees up (2024-01-26 00:00 UTC, 45 N 0 E, looking
 * north 30 degrees up) or a moonless sky (2024-01-11 22:00 UTC, 45 N
 * 10 E, looking south 30 degrees up). */
typedef struct sky_night_view {
    int median[3];     /* each channel's median, 8-bit sRGB */
    double hue;        /* HSV hue of that median colour, degrees */
    double b_over_r;   /* its blue over its red */
    double mean;       /* the mean display luminance (decoded to linear) */
} sky_night_view;
int sky_night_measure(sky_atmosphere_path path, sky_gl_profile profile, int full_moon, int w, int h,
                      sky_night_view *out, char *err, size_t err_len);
/* The full moon's disc (the night view's date and place, the camera on
 * the moon, 3 degrees high, w x h, HDR and LDR): the HSV hue of its mean
 * colour in linear light, HDR and the 8-bit frame decoded, over the pixels
 * brighter in HDR than half the disc's brightest. */
int sky_moon_disc_hues(sky_atmosphere_path path, sky_gl_profile profile, int w, int h, double *hdr_hue,
                       double *ldr_hue, char *err, size_t err_len);

/* Whether a night view meets its targets, its mean against noon's (the
 * day's end's noon, sky_dusk_brightness at 50 degrees): the full moon hue
 * 190-250, b/r >= 1.6, the brightest channel's median >= 40, at most 0.35
 * of noon; the moonless sky hue 190-260, b/r >= 1.2, the brightest
 * channel's median 8..40. Why not in why. */
int sky_night_ok(const sky_night_view *v, int full_moon, double noon, char *why, size_t why_len);

/* Whether a row meets the targets that apply at its sun height; why not
 * in why. */
int sky_colour_row_ok(const sky_colour_row *row, char *why, size_t why_len);

#endif /* SKY_COLOUR_H */
