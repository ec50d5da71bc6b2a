/*
 * Aerial perspective (sky_get_aerial_perspective and sky_aerial_bind in
 * sky.h): what the air between the observer and a point adds to and
 * takes from the point's light, from the atmosphere the sky is drawn
 * with (aerial.c).
 */
#ifndef SKY_AERIAL_H
#define SKY_AERIAL_H

#include "atmosphere/hillaire.h"
#include "core.h"
#include "irradiance.h"

/* The shader's table (sky_aerial_glsl): per slice of distance an
 * AZIMUTHS x ELEVATIONS block of directions about the sun's vertical
 * (from the horizon up: a view below it is taken as level);
 * slices side by side, the in-scattered light's rows above the
 * transmittance's. Slice 0 is the observer (nothing between), slices
 * 1 .. SLICES - 3 lie at SKY_AP_TABLE_M (k / (SLICES - 3))^2, the next
 * at twice SKY_AP_TABLE_M, the last at the view ray's end (the ground or
 * space). */
enum { SKY_AP_AZIMUTHS = 16, SKY_AP_ELEVATIONS = 32, SKY_AP_SLICES = 16 };
#define SKY_AP_TABLE_M 50000.0
#define SKY_AP_TABLE_W (SKY_AP_AZIMUTHS * SKY_AP_SLICES)
#define SKY_AP_TABLE_H (2 * SKY_AP_ELEVATIONS)

typedef struct sky_aerial_state {
    sky_hillaire_tables own; /* paths without Hillaire's tables: made at first use */
    int own_ready;
    int table_valid;
    double key[SKY_ATMOSPHERE_KEY];
    unsigned char *texels;  /* SKY_AP_TABLE_W x SKY_AP_TABLE_H RGBA8           */
    float *values;          /* the table before its encoding: per elevation,
                               azimuth and slice the light and transmittance */
    sky_hillaire_point *profile; /* one ray's running sums                  */
    double scale;           /* kcd/m^2 of the in-scatter encoding's 1          */
    int uploaded;           /* the texture holds this table                    */
} sky_aerial_state;

void sky_aerial_free(sky_aerial_state *a);
/* The air between the observer and the point km away in the horizon
 * frame's unit direction d (km may be INFINITY: the ray's end): the light
 * it scatters toward the observer (kcd/m^2, linear RGB) and the share of
 * the point's light it lets through. 0, or -1 when the tables it needs
 * could not be made (out of memory). */
int sky_aerial_eval(const sky_core *s, sky_aerial_state *a, const double d[3], double km, double inscatter[3],
                    double transmittance[3]);
/* The radii (km) the table was made for: the observer's and the top of
 * the atmosphere (aerial.glsl finds a view ray's end from them). */
void sky_aerial_shell(const sky_core *s, sky_aerial_state *a, double *observer_radius_km, double *top_km);
/* The shader's table for the frame, remade when what it depends on
 * changed (sky_atmosphere_key): 1 remade, 0 current, -1 out of memory. */
int sky_aerial_table(const sky_core *s, sky_aerial_state *a);

/* The weather over the air's light and transmittance at km (the CPU's
 * share of aerial.glsl's; aerial.c), and the deck's dimming alone. */
void sky_aerial_weather(const sky_core *s, double km, double inscatter[3], double transmittance[3]);
double sky_aerial_deck_dim(const sky_core *s);

#endif /* SKY_AERIAL_H */
