#ifndef SKY_ASTRO_TABLES_H
#define SKY_ASTRO_TABLES_H
typedef struct sky_moon_term { signed char d, m, mp, f; double a, b; } sky_moon_term;
typedef struct sky_vsop_term { double a, b, c; } sky_vsop_term;
typedef struct sky_vsop_series { const sky_vsop_term *terms; int count; } sky_vsop_series;
extern const sky_moon_term sky_moon_lr[60], sky_moon_b[60];
extern const sky_vsop_series sky_earth_L[6], sky_earth_B[2], sky_earth_R[5];
#endif
