/*
 * Hillaire's LUT atmosphere (Hillaire 2020, "A Scalable and Production
 * Ready Sky and Atmosphere Rendering Technique", EGSR): the CPU builder.
 * COMPAT20 builds every table here and uploads it in 8 bits; CORE33
 * builds the same tables on the GPU (hillaire_*.glsl) and the CPU tables
 * serve as its check.
 *
 * Tables (all RGB at the 680/550/440 nm coefficients of
 * sky_atmosphere_params, sun illuminance 1: transfer factors):
 *   transmittance  T(r, mu) to the top of the atmosphere or 0 where the
 *                  ray meets the ground; Bruneton's (r, mu) mapping.
 *   multiscatter   Psi_ms(r, mu_s): the mean over the sphere of the
 *                  light that reaches a point after one or more
 *                  scatterings, which the observer scatters once more
 *                  (Hillaire sec. 5.5's Psi_ms, eq. 10; here carried
 *                  order by order, see sky_hillaire_add_order).
 *   ms_moments     that light beyond its mean: its dipole and quadrupole,
 *                  and the first bounce's zonal harmonics of degrees 3
 *                  and 4 about the sun, from which the observer scatters
 *                  it with the real phase functions instead of
 *                  isotropically (see skyview_row).
 *   skyview        L(view) for one observer altitude and sun zenith:
 *                  u = azimuth from the sun's vertical plane (0..pi,
 *                  symmetric), v = elevation with the horizon-concentrated
 *                  mapping of Hillaire sec. 5.3 (sqrt toward the horizon).
 * Radiance in the sky-view table is per unit of solar illuminance above
 * the atmosphere (1/sr); the caller multiplies by the sun's irradiance.
 *
 * Choices of this implementation (hillaire_cpu.c):
 *   - every table coordinate x in 0..1 maps to 0.5/N + x (1 - 1/N), so
 *     texel i holds x = i / (N - 1); lookups are GL_LINEAR +
 *     CLAMP_TO_EDGE.
 *   - transmittance: rays that meet the ground have no texel (Bruneton);
 *     sky_hillaire_transmittance returns 0 for them, decided from the
 *     caller's (r, mu) in double, and the entry-point value (or 1) from
 *     above the top. T along a ray to the ground point is the caller's:
 *     T(r, mu) / T(r_ground, mu_ground) with both rays mirrored upward.
 *   - multiscatter: u = 0.5 + 0.5 sign(mu_s) sqrt|mu_s| (columns crowd
 *     toward the horizon), v = (r - R) / (Rt - R); SKY_HL_ORDERS orders
 *     of scattering, each traced from the one before with the real phase
 *     functions, the rest a geometric series; per column, directions
 *     about the sun (half of them spread evenly, half
 *     Henyey-Greenstein-distributed like the aerosol's forward peak,
 *     weighted by the balance heuristic), mirrored across the sun's plane
 *     (multiscatter_directions rounded up to even; for the smoother
 *     orders after the first, half as many, all spread evenly, and half
 *     the steps).
 *   - ms_moments: per texel D_x, D_y (the dipole: 3 x the mean of L w, x
 *     toward the sun's azimuth, y up), Q_xx, Q_yy, Q_xy (the traceless
 *     quadrupole 3 x mean of L w w^T - mean of L) and Z_3, Z_4 (the first
 *     bounce's (2l + 1) x mean of L P_l(s . w), s the sun), each RGB.
 *   - both as the lookups interpolate them: multiscatter holds Psi^(1/16)
 *     and ms_moments each moment over Psi (0 where Psi is 0), since Psi
 *     falls steeply in the Earth's shadow (hillaire_cpu.c's ms_root);
 *     sky_hillaire_multiscatter gives Psi back. An order's table (below)
 *     is kept the same way, its irradiance as a sixteenth root too.
 *   - skyview: u = sqrt((1 - cos az) / 2) = sin(az / 2), the sun's vertical
 *     at u = 0; v = 0.5 (1 - sqrt(1 - theta / theta_h)) above the
 *     geometric horizon theta_h = pi - asin(R / r) and 0.5 + 0.5 sqrt((theta
 *     - theta_h) / (pi - theta_h)) below it. The horizon is v = 0.5: the
 *     boundary between the two middle rows for an even height (the
 *     default 108), whose centres lie within 0.01 deg (above) and 0.03 deg
 *     (below) of it, so a lookup never blends sky far from the horizon
 *     with ground.
 * sky_hillaire_init takes settings NULL as all defaults; a NULL table or
 * atmosphere is an error; an all-zero atmosphere is Earth.
 */
#ifndef SKY_ATMOSPHERE_HILLAIRE_H
#define SKY_ATMOSPHERE_HILLAIRE_H

#include "../sky.h"

/* floats per texel of the moments table, and of both tables */
#define SKY_HL_MOMENTS 21
#define SKY_HL_MS_ALL (3 + SKY_HL_MOMENTS)
/* The orders of scattering the multiple-scattering table traces one by
 * one, and the floats per texel of one order's table: the mean, the
 * moments (as ms_moments) and the irradiance of a level surface facing
 * up (the next order's light off the ground), each RGB. */
#define SKY_HL_ORDERS 3
#define SKY_HL_ORDER (SKY_HL_MS_ALL + 3)

/* The public sky_lut_settings of sky.h (zero fields = Hillaire's). */
typedef sky_lut_settings sky_hillaire_settings;

typedef struct sky_hillaire_tables {
    sky_hillaire_settings settings;  /* with the defaults filled in         */
    sky_atmosphere_params atm;
    float *transmittance;  /* width * height * 3, row-major, v rows        */
    float *multiscatter;   /* size * size * 3                               */
    float *ms_moments;     /* size * size * SKY_HL_MOMENTS: D_x, D_y, Q_xx,
                              Q_yy, Q_xy, Z_3, Z_4, each RGB                */
    double chi[5];         /* Legendre moments the observer scatters them
                              with: Mie's l = 1 and 2, Rayleigh's l = 2,
                              Mie's l = 3 and 4                             */
    double *scratch;       /* the sky-view builder's: both tables at one
                              altitude and 8 numbers per column; a table
                              set is built and read by one thread at a time */
    float *skyview;        /* width * height * 3                            */
    double skyview_altitude_km, skyview_sun_mu; /* inputs of the last build */
} sky_hillaire_tables;

/* Validates settings (each size 4..1024, steps 1..256) and the atmosphere,
 * fills defaults, allocates. Returns 0, or -1 with err. */
int sky_hillaire_init(sky_hillaire_tables *t, const sky_atmosphere_params *atm, const sky_hillaire_settings *s,
                      char *err, size_t err_len);
void sky_hillaire_free(sky_hillaire_tables *t);
void sky_hillaire_build_transmittance(sky_hillaire_tables *t);
/* needs transmittance; 0, or -1 when out of memory (the table is then
 * left as it was) */
int sky_hillaire_build_multiscatter(sky_hillaire_tables *t);
/* Adds order k (1 .. SKY_HL_ORDERS) of the light that reaches each texel
 * to the multiple-scattering table and its moments: order 1 starts them,
 * the last adds itself as the first term of a geometric series whose
 * ratio per texel and channel is its mean over the previous order's.
 * order and prev (order k - 1, unused for k = 1) are size * size *
 * SKY_HL_ORDER tables: what sky_hillaire_build_multiscatter traces, or
 * what the GPU traced (CORE33). */
void sky_hillaire_add_order(sky_hillaire_tables *t, int k, const float *order, const float *prev);
/* The directions (mirrored pairs: half of them), how many of those
 * follow the aerosol's forward peak about the sun, and the steps that
 * order k traces per texel: the settings' (half the directions about the
 * peak) for the first; for the smoother orders after it, half the
 * directions, all spread evenly, and half the steps (against the
 * settings' for every order: the same light within 2 % at 1 km under a
 * sun 5-60 deg up). */
void sky_hillaire_order_samples(const sky_hillaire_tables *t, int k, int *half_directions, int *peaked, int *steps);
/* needs both; altitude_km of the observer, sun_mu = cos(sun zenith) */
void sky_hillaire_build_skyview(sky_hillaire_tables *t, double altitude_km, double sun_mu);
/* The same table a few rows at a time: rows row0 .. row1 - 1 (clamped to
 * the table) of the sky-view table for altitude_km and sun_mu, into table
 * (skyview_width * skyview_height * 3 floats, laid out as t->skyview).
 * Each row is one zenith angle, marched on its own, so rows built in any
 * order and over any number of calls make exactly the table
 * sky_hillaire_build_skyview makes (which calls this for all rows). Reads
 * t's transmittance and multiple-scattering tables, writes nothing of t. */
void sky_hillaire_build_skyview_rows(const sky_hillaire_tables *t, double altitude_km, double sun_mu, int row0,
                                     int row1, float *table);
/* Puts a table finished by sky_hillaire_build_skyview_rows in place:
 * exchanges t->skyview and *table (which then holds the old table, for the
 * next build) and records altitude_km and sun_mu as
 * sky_hillaire_build_skyview does. */
void sky_hillaire_install_skyview(sky_hillaire_tables *t, float **table, double altitude_km, double sun_mu);

/* Table coordinates in 0..1 (texel centres mapped as Bruneton does: a
 * value at the table's edge samples the edge texel's centre). */
/* sky_hillaire_transmittance_uv is for the default 256 x 64 table (it is
 * not told the size); _sized takes the table's size. mu below the
 * horizon (the ray meets the ground) clamps to the grazing column: the
 * table holds rays to the top only. A zero atmosphere is Earth. */
void sky_hillaire_transmittance_uv(const sky_atmosphere_params *atm, double r, double mu, double *u, double *v);
void sky_hillaire_transmittance_uv_sized(const sky_atmosphere_params *atm, double r, double mu, int width,
                                         int height, double *u, double *v);
void sky_hillaire_skyview_uv(const sky_hillaire_tables *t, double view_mu, double cos_azimuth_from_sun,
                             double altitude_km, double *u, double *v);

/* Bilinear lookups, as the shaders do them. */
void sky_hillaire_transmittance(const sky_hillaire_tables *t, double r, double mu, double rgb[3]);
void sky_hillaire_multiscatter(const sky_hillaire_tables *t, double r, double mu_s, double rgb[3]);
/* Sky radiance per unit solar illuminance (1/sr) for a view direction in
 * the horizon frame (+y up) with the sun at sun_dir, from the sky-view
 * table (built for the same altitude and sun). */
void sky_hillaire_sky(const sky_hillaire_tables *t, const double view[3], const double sun_dir[3], double rgb[3]);

/* The same radiance marched along one view ray (no sky-view table; the
 * transmittance and multiple-scattering tables must be built): what the
 * sky-view table holds at that direction, before its interpolation. */
void sky_hillaire_ray(const sky_hillaire_tables *t, double altitude_km, const double view[3], const double sun_dir[3],
                      double rgb[3]);
/* Aerial perspective: the same march stopped max_km from the observer
 * (short of the ground or the top it would meet): the light scattered
 * into the view on the way (per unit solar illuminance, 1/sr; a finite
 * max_km leaves the ground's own light out: the host's object is there)
 * and the view's transmittance there (NULL: not wanted). max_km 0:
 * nothing scattered, transmittance 1; INFINITY: sky_hillaire_ray. */
void sky_hillaire_segment(const sky_hillaire_tables *t, double altitude_km, const double view[3],
                          const double sun_dir[3], double max_km, double rgb[3], double transmittance[3]);
/* The march's running sums: the light scattered into the view between
 * the observer and each sample's far end, and the view's transmittance
 * there, from the observer (0 km: nothing, 1) to the ray's end at the
 * ground or the top (the ground's own light left out). Distances rise;
 * between two points the light grows about linearly and the
 * transmittance about exponentially with distance. Up to max_points
 * (SKY_HL_PROFILE_MAX holds any ray); returns how many, at least 1. */
#define SKY_HL_MAX_STEPS 256
#define SKY_HL_PROFILE_MAX (SKY_HL_MAX_STEPS + 2)
typedef struct sky_hillaire_point {
    double km, inscatter[3], transmittance[3];
} sky_hillaire_point;
int sky_hillaire_profile(const sky_hillaire_tables *t, double altitude_km, const double view[3],
                         const double sun_dir[3], sky_hillaire_point *points, int max_points);

#endif
