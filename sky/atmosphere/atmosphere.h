/*
 * The atmosphere room: after the astronomy, before exposure and the
 * layers. One selected path (gradient, Preetham, analytic Rayleigh,
 * Hillaire's tables, or a blend) writes the sky's part of the frame: the
 * direct sun's transmittance, the day and night sky's scales, the path's
 * shader coefficients, and the host's ambient and fog. The dome layer
 * compiles the path's snippets; nothing else reads the path's state.
 */
#ifndef SKY_ATMOSPHERE_H
#define SKY_ATMOSPHERE_H

#include "../gl/gl.h"
#include "hillaire.h"

/* ---- the stage (atmosphere.c) ---------------------------------------------- */
/* The path's resources (Hillaire's tables on HILLAIRE and BLEND); 0, or
 * -1 with a message. destroy takes whatever create left. */
int sky_atmosphere_create(sky_core *s, char *err, size_t err_len);
void sky_atmosphere_destroy(sky_core *s);
/* The sky's part of the frame (needs the astronomy's). */
void sky_atmosphere_frame(sky_core *s);
/* Before the dome is drawn: a sky-view table rebuilt since the last draw
 * goes to the GPU. */
void sky_atmosphere_upload(sky_core *s);
/* The snippets of the selected path (at most SKY_ATMOSPHERE_SNIPPETS, in
 * order; encoded_tables: COMPAT20's 8-bit sky-view table). */
#define SKY_ATMOSPHERE_SNIPPETS 5
int sky_atmosphere_snippets(sky_atmosphere_path path, sky_atmosphere_path blend_partner, int encoded_tables,
                            const sky_snippet **out);
/* BLEND's analytic path: cfg.blend_partner with 0 resolved (RAYLEIGH) */
sky_atmosphere_path sky_blend_partner(sky_atmosphere_path requested);
/* Vertical optical depth above the observer per channel: the atmosphere
 * description's for the physical paths, the sun model's otherwise; what
 * dims the stars and the moon (Mueller sec. 5). */
void sky_atmosphere_zenith_depth(const sky_core *s, double depth[3]);
/* (airmass.c) What the air leaves of light from above it (the night glows) seen in
 * direction d, per channel: the zenith depths over the shell's path
 * (atmosphere.glsl's sky_night_extinction). */
void sky_night_extinction(const sky_core *s, const double d[3], double t[3]);
/* The zenith brightness of a Bortle class (1..9, fractions between), V
 * mag/arcsec^2. */
double sky_bortle_zenith_mag(double bortle);
/* The CPU twin of what the atmosphere draws in direction d (horizon
 * frame, unit), kcd/m^2: the path's sky with its eclipse dimming and the
 * night floor above the horizon, the ground below it (atmosphere.glsl's
 * sky_or_ground); no sun, moon, stars or clouds. */
void sky_atmosphere_radiance(const sky_core *s, const double d[3], double rgb[3]);
/* The physical paths' moonlit sky in direction d per unit of the moon's
 * illuminance (1/sr per channel; 0 below the horizon, on the other paths
 * and before the first night): the path's model lit from the moon's
 * place rounded (atmosphere.c), what the dome's vertices carry. */
void sky_atmosphere_moonlit_unit(const sky_core *s, const double d[3], double rgb[3]);
/* 1 for the paths that scatter light through a described atmosphere
 * (Rayleigh's, Hillaire's, the blend), 0 for the gradient and Preetham's. */
int sky_atmosphere_is_physical(sky_atmosphere_path path);
/* (airmass.c) The sun model's direct-beam transmittance for a ray at the given
 * altitude (radians): Kasten-Young air mass times a Rayleigh+aerosol
 * optical depth; below the horizon, the horizon's value. Non-decreasing
 * in altitude. */
void sky_sun_transmittance(double altitude, float out[3]);
/* (spectrum.c) The sun above the atmosphere in linear sRGB, klx per channel: the
 * reference's sun (atmosphere/spectrum.c), so the physical paths and their
 * yardstick are lit alike. */
void sky_sun_irradiance_rgb(double rgb[3]);
/* (CIE XYZ to linear sRGB: light_units.h.) */
/* For the tests: Hillaire's tables (NULL on other paths) and the sun and
 * observer the sky-view table was last built for. */
sky_hillaire_tables *sky_atmosphere_tables(const sky_core *s);
void sky_atmosphere_skyview_at(const sky_core *s, double *sun_mu, double *altitude_km);

/* ---- the description (params.c) ---------------------------------------------- */
/* 1 when every field is zero (= the Earth preset). */
int sky_atmosphere_is_zero(const sky_atmosphere_params *atm);
/* The description with its aerosol scaled to a turbidity (sky.h,
 * sky_config.turbidity); turbidity <= 0 copies it unchanged. */
void sky_atmosphere_with_turbidity(const sky_atmosphere_params *in, double turbidity, sky_atmosphere_params *out);
/* A description's turbidity: 1 + its aerosol's optical depth at 550 nm
 * over its molecules'. */
double sky_atmosphere_turbidity(const sky_atmosphere_params *atm);
/* The description's coefficients as the sRGB channels see them: each
 * component's spectrum averaged over the channel's share of sunlight
 * (params.c). What the real-time physical paths render with. */
void sky_atmosphere_effective(const sky_atmosphere_params *in, sky_atmosphere_params *out);

/* ---- the paths ----------------------------------------------------------------- */
/* Each path's snippet(s) and per-frame coefficients; the CPU twins of
 * their shaders give radiance in kcd/m^2 for an upper-hemisphere
 * direction, without the night floor. */
extern const sky_snippet sky_atmosphere_snippet; /* shared by every path */
extern const sky_snippet sky_gradient_snippet;
extern const sky_snippet sky_preetham_snippet;
extern const sky_snippet sky_rayleigh_snippet;
extern const sky_snippet sky_extinction_snippet; /* the physical paths' optical depth */
extern const sky_snippet sky_hillaire_snippet;
extern const sky_snippet sky_hillaire_encoded_snippet; /* COMPAT20's 8-bit table */
extern const sky_snippet sky_blend_snippet;
void sky_gradient_frame(sky_core *s);
/* The gradient path's moonlit sky into the frame (moon_sky, moon_beam);
 * returns its zenith luminance, kcd/m^2. */
double sky_gradient_moon(sky_core *s);
/* Day-gradient colour (linear RGB) for a direction, from the 256x1
 * gradient image, as R-P's gradient texture maps it onto the dome (the
 * dome bakes it into its vertices). */
void sky_gradient_vertex(const unsigned char *gradient_rgba, const float dir[3], float rgb[3]);
double sky_preetham_turbidity(float requested); /* the turbidity the model uses */
void sky_preetham_frame(sky_core *s);
void sky_preetham_eval(const sky_frame *f, const double d[3], double rgb[3]);
/* Preetham's moonlit sky into the frame (perez_moon_zenith, moon_tint);
 * returns its zenith luminance, kcd/m^2; and its CPU twin (0 without). */
double sky_preetham_moon(sky_core *s);
void sky_preetham_moon_eval(const sky_frame *f, const double d[3], double rgb[3]);
void sky_rayleigh_frame(sky_core *s);
/* The same for the light along f->sun_dir into f (the moonlit sky's frame:
 * atmosphere.c), the sun's irradiance in f->sun_irradiance. */
void sky_rayleigh_light_frame(const sky_core *s, sky_frame *f);
void sky_rayleigh_eval(const sky_frame *f, const double d[3], double rgb[3]);
/* Chapman's grazing-incidence function: slant over vertical column of an
 * exponential atmosphere, X = radius / scale height, mu = cos(zenith angle),
 * any mu in -1..1 (rayleigh.c). */
double sky_chapman(double X, double mu);

/* Hillaire's tables in the sky (hillaire.c): the tables at creation, the
 * sky-view rebuild per frame (COMPAT20: on the CPU, at once after a jump,
 * else a slice per frame), its upload or GPU build before the dome is
 * drawn, the CPU twin of the shader (for the sun at the elevation of the
 * table in use). */
typedef struct sky_hillaire_state sky_hillaire_state;
int sky_hillaire_create(sky_core *s, sky_hillaire_state **out, char *err, size_t err_len);
void sky_hillaire_destroy(sky_core *s, sky_hillaire_state *h);
/* Returns 1 when a new sky-view table came into use (the summary follows
 * it). */
int sky_hillaire_frame(sky_core *s, sky_hillaire_state *h);
void sky_hillaire_upload(sky_core *s, sky_hillaire_state *h);
void sky_hillaire_eval(const sky_core *s, const sky_hillaire_state *h, const double d[3], double rgb[3]);
sky_hillaire_tables *sky_hillaire_state_tables(const sky_hillaire_state *h);
/* Hillaire's aerial-perspective volume (sec. 5.4) for a camera, into
 * SKY_TEX_FROXELS (CORE33): SKY_FROXEL_SIZE^3 froxels, x and y across the
 * viewport, slice k the air between the observer and
 * (k + 1) SKY_FROXEL_KM_PER_SLICE km along the view: RGB in-scattered
 * kcd/m^2, A the mean transmittance. clip_to_dir: sky_camera_clip_to_horizon.
 * 0, or -1 with a message. */
#define SKY_FROXEL_SIZE 32
#define SKY_FROXEL_KM_PER_SLICE 1.0
int sky_hillaire_froxels(sky_core *s, sky_hillaire_state *h, const float clip_to_dir[16], char *err, size_t err_len);
/* The same from the stage (sky_hillaire_froxels' -1 and message where
 * there are no tables on the GPU: off the Hillaire and blend paths or
 * outside CORE33; sky.c refuses those first). */
int sky_atmosphere_froxels(sky_core *s, const float clip_to_dir[16], char *err, size_t err_len);
void sky_hillaire_skyview_at(const sky_hillaire_state *h, double *sun_mu, double *altitude_km);

#endif /* SKY_ATMOSPHERE_H */
