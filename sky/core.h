/*
 * libsky's bottom module: what every file of the library shares and
 * nothing more. Named numeric guards, the clocks' arithmetic, error text,
 * the embedded assets, and the two structures every room reads: the
 * frame (sky_frame, what the shaders read) and the shared context
 * (sky_core). It knows no layer. See docs/ARCHITECTURE.md for the rooms
 * above it and the one-way flow between them.
 */
#ifndef SKY_CORE_H
#define SKY_CORE_H

#include "astro.h"
#include "light_units.h"
#include "gl/glapi.h"
#include "sky.h"

#include <math.h>

#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#define SKY_PI 3.14159265358979323846

/* ---- small numeric guards (named, so a reader sees the intent) ---------- */
static inline double sky_clampd(double x, double lo, double hi) { return x < lo ? lo : (x > hi ? hi : x); }
static inline float sky_clampf(float x, float lo, float hi) { return x < lo ? lo : (x > hi ? hi : x); }
double sky_smoothstep(double e0, double e1, double x);
/* Row-major 3x3 product out = a b (out may not alias a or b). */
void sky_mat3_mul(const double a[9], const double b[9], double out[9]);
/* The sky's rotation from J2000 to the horizon frame, horizon *
 * precession-nutation (Mueller eq. 7), as a column-major mat4 for a
 * uniform; inverse: its transpose, horizon back to J2000. */
void sky_j2000_to_horizon_mat4(const sky_astro *a, int inverse, float out[16]);

/* ---- clocks ------------------------------------------------------------- */
/* Wraps x into [0, period): long-running offsets stay small enough for
 * float uniforms. fmod keeps the full double precision of x. */
double sky_wrap(double x, double period);
/* A clock's phase in [0, 1) advanced by rate cycles per second over dt
 * seconds (any finite dt >= 0, up to the largest double). */
double sky_phase_advance(double phase, double rate, double dt);
/* Wall-clock milliseconds (C11 timespec_get), for statistics. */
double sky_now_ms(void);

/* ---- error text --------------------------------------------------------- */
/* snprintf into an error buffer that may be NULL or empty. */
void sky_format(char *buf, size_t len, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* ---- embedded assets (generated at build time by tools/embed) ----------- */
typedef struct sky_blob {
    const char *name;
    const unsigned char *data;
    size_t size;
} sky_blob;
const sky_blob *sky_find_blob(const char *name); /* NULL if not embedded */

/* PNG decoding (gl/image.c) */
int sky_png_info(const unsigned char *data, size_t size, int *w, int *h);
unsigned char *sky_png_decode_rgba(const unsigned char *data, size_t size, int *w, int *h, const char **why);
void sky_png_free(unsigned char *rgba);
/* The CRC-32 of a PNG chunk's type and data (ISO 3309, as the PNG
 * specification gives it). */
unsigned long sky_png_crc32(const unsigned char *p, size_t n);
/* Decodes a PNG of exactly expect_w x expect_h to RGBA8 (checked from the
 * header before decoding). Returns 0, or -1 with a message naming label. */
int sky_image_decode(const unsigned char *data, size_t size, int expect_w, int expect_h, unsigned char **rgba,
                     const char *label, char *err, size_t err_len);

/* ---- textures ----------------------------------------------------------- */
typedef enum sky_texture_id {
    SKY_TEX_CLOUDS = 0, /* RGBA: photo, noise, detail, sunset gradient (R-P sec. 3) */
    SKY_TEX_STARMAP,    /* equirectangular J2000 faint stars + Milky Way (Mueller 4.4) */
    SKY_TEX_MOON,       /* 256x128 lunar albedo, selenographic (Mueller 2.2.2)       */
    SKY_TEX_ECLIPSE,    /* 128x1 eclipse colour h(t), log10-encoded (Mueller 3.2)    */
    SKY_TEX_SKYVIEW,    /* Hillaire's sky-view table (atmosphere/hillaire.c)       */
    SKY_TEX_TRANSMITTANCE, /* Hillaire's transmittance table (CORE33: GPU builds)  */
    SKY_TEX_MULTISCATTER,  /* Hillaire's multiple-scattering table and its moments,
                              6 layers (CORE33)                                  */
    SKY_TEX_MS_ORDER,      /* while it is built: the order a pass traces, and   */
    SKY_TEX_MS_ORDER_PREV, /* the one before, which it scatters (7 layers each) */
    SKY_TEX_ENVIRONMENT,   /* sky_capture_environment's own cube map             */
    SKY_TEX_AERIAL,        /* sky_aerial_bind's table (aerial.c), RGBA8          */
    SKY_TEX_CLOUD_SHADOW,  /* sky_get_cloud_shadow's map (cloud_shadow.c), RGBA8 */
    SKY_TEX_FROXELS,       /* sky_aerial_froxels' volume (CORE33, Hillaire)      */
    SKY_TEX_DOME,       /* the LDR dome at reduced size: tone-mapped sky and clouds,
                           the clouds' alpha in A (dome.c)                      */
    SKY_TEX_COUNT
} sky_texture_id;

typedef struct sky_texture {
    GLuint id;
    GLenum target;   /* GL_TEXTURE_2D or GL_TEXTURE_CUBE_MAP */
    int width, height;
    size_t bytes;
    sky_layer owner; /* whose stats row counts its bytes */
} sky_texture;

/* Samples of the clouds' sunset gradient across 0..1 of its coordinate
 * (clouds.glsl's u_sunset_gradient has as many). */
#define SKY_SUNSET_SAMPLES 33

/* ---- the frame: what more than one room reads -----------------------------
 * One writer per field: the room named in its group. The uniform tables
 * (each room's sky_uniform_desc rows) point into it by offset; a layer's
 * own uniforms live in its state instead (SKY_US rows, gl/gl.h). */
/* What stars.vert draws a set of points with (the catalogue stars, the
 * planets), as its uniforms have it. */
typedef struct sky_point_frame {
    float rot[16];           /* the points' frame -> horizon (J2000 for stars) */
    float aberration[3];     /* annual aberration, horizon frame (0: applied)  */
    float pressure[3];       /* refraction's pressure factor, the faintest V
                                drawn (sky_point_limit), -                   */
    struct {                 /* Mueller eq. 9, pixels                          */
        float q, glare_ck, max_radius, control_magnitude;
    } size;
    float flux_scale;        /* kcd/m^2 at the PSF's peak of a V = 0 point     */
    float extinction[3], shell[3]; /* zenith optical depths; eq. 11's shell     */
    float seed;              /* the scintillation clock, in random values       */
    float occulter[4];       /* the moon's true direction and the cosine of its
                                drawn radius (2: no moon): points behind it go */
} sky_point_frame;

typedef struct sky_frame {
    /* astronomy and the shared frame state (sky.c) */
    float sun_dir[3];        /* horizon frame, unit                              */
    float moon_dir[3];       /* horizon frame, unit, refracted                   */
    float sun_altitude;      /* radians, apparent                                */
    float daylight;          /* R-P "amount of sunlight", 0..1                   */
    float naked_eye_limit;   /* V of the faintest point the eye sees against the
                                zenith's sky (sky_point_limit; sky.c, after
                                the layers' frames)                          */
    float night;             /* visibility of night layers, 0..1                 */
    float refraction_pressure; /* Saemundsson's scale at the observer (astro.c)  */
    float output_hdr;        /* 1 = linear out, 0 = tone mapped                 */
    float frame_index;       /* dither seed                                     */
    /* the atmosphere (atmosphere/) */
    float sun_transmittance[3]; /* direct sunlight through the atmosphere       */
    float sky_luminance;     /* kcd/m^2: the day sky's scale (exposure, clouds,
                                moon), dimmed by a solar eclipse               */
    float day_luminance;     /* kcd/m^2: the gradient path's own scale, before
                                the eclipse (its shader applies that per pixel) */
    float horizon_tint[3];   /* colour of the horizon under a low sun            */
    float moon_sky[3];       /* kcd/m^2 of a gradient texel of value 1 lit by the
                                moon (the gradient path's moonlit sky; 0 on
                                the others and without a moon)               */
    float moon_beam[3];      /* the moon's light through the air, its aureole's
                                tint (the sun's beam model at its altitude)  */
    float moonlit_light[3];  /* the physical paths' moonlit sky: the moon's light
                                above the air, klx per channel (0 by day)   */
    unsigned moonlit_generation; /* bumped when their moonlit sky per unit of
                                it changes (the dome's vertices follow)      */
    float glows_key;         /* what of the night glows' light their zenith does
                                not show (the aurora's Kp and clocks:
                                aurora.c): a key of the irradiance's cache */
    float night_luminance;   /* kcd/m^2: the moonless or moonlit night sky's zenith
                                (airglow, zodiacal light, the floor, light
                                pollution): what the exposure adapts to     */
    float night_floor[3];    /* zenith kcd/m^2 of what no layer draws: the stars
                                fainter than the star map, and the moonlit air
                                where the path does not draw it              */
    float artificial_glow[3];/* zenith kcd/m^2 of light pollution (cfg.bortle)  */
    float night_depth[3], night_shell[3]; /* the air's zenith optical depths and
                                the shell of Mueller eq. 11 (observer radius,
                                top, thickness, km): the night glows' extinction */
    float night_air[3];      /* that shell for the dome's pixels, in mediump's
                                range (atmosphere.glsl): (b/a)^2 - 1, the
                                zenith path's 2 + t/a, a/t                    */
    float moon_sky_luminance; /* kcd/m^2: the moonlit sky's zenith, the moon's share
                                of night_luminance (0 without a moon)        */
    float ambient_rgb[3];    /* sky irradiance on an upward surface, klx         */
    float fog_rgb[3];        /* horizon luminance, kcd/m^2                       */
    float ground_rgb[3];     /* the ground below the horizon, kcd/m^2            */
    /* Preetham (preetham.c): Perez A..E and zenith values for (Y, x, y) */
    float perez[5][3], perez_zenith[3];
    float perez_moon_zenith[3], moon_tint[3]; /* Preetham's moonlit sky: its zenith
                                values for the moon's place, and the moon's colour
                                (unit luminance); 0 without (preetham.c)      */
    double perez_horizon_klx, perez_horizon_t; /* the fit's horizon-sun illuminance
                                                  for turbidity t (0: none yet) */
    /* analytic Rayleigh + Mie (rayleigh.c) */
    float tau_rayleigh[3], tau_mie_sca[3], tau_mie_ext[3], tau_ozone[3];
    float chapman_x[3], sun_depth[3], sun_irradiance[3], mie_phase[3];
    float sun_irradiance_sent[3]; /* u_sun_irradiance: sun_irradiance times light_scale
                                over 2^sun_gain_log2 (exposure.c)              */
    float sun_gain_log2;     /* what the shaders put back                        */
    float rl_geometry[4];    /* r_obs, R_planet, H_rayleigh, H_mie (km)        */
    float rl_multiple[3];    /* isotropic phase of multiple scattering, per sr */
    float rl_skylight[3];    /* the skylight's floor on multiple scattering's
                                exponent in the Earth's shadow (rayleigh.c)   */
    float rl_ozone[3];       /* the ozone tent: peak, half width (km), 1 / its
                                column above the observer                     */
    /* Hillaire's sky-view table (hillaire.c) and the blend */
    float skyview_map[4], skyview_horizon[2], skyview_decode[3], blend_weight;
    /* the GPU build of the sky-view table (skyview_build.frag) */
    float hl_geometry[4], hl_profile[4], hl_rayleigh[3], hl_mie_sca[3], hl_mie_ext[3], hl_ozone[3], hl_albedo[3];
    float hl_sizes[4], hl_steps[4];
    float hl_chi[3];         /* u_hl_chi: Mie's chi_1, chi_2, Rayleigh's chi_2  */
    float hl_chi_zonal[2];   /* u_hl_chi_zonal: Mie's chi_3, chi_4             */
    float ms_pass[4];        /* u_ms_pass: the order a pass traces, its
                                directions (half), steps, and how many of the
                                directions follow the aerosol's peak          */
    struct {                 /* u_hl_misc                                      */
        float multiscatter_size, sun_mu, skyview_steps, mie_g;
    } hl_misc;
    /* a solar eclipse (solar_eclipse.c) */
    float eclipse_sky[4];    /* x: the day sky's light left everywhere by a solar
                                eclipse; yzw: the extra at the horizon, rgb     */
    float eclipse_sky_mean;  /* what that leaves of the sky's mean luminance (1
                                without an eclipse; sky_luminance has it)       */
    struct {                 /* u_eclipse_sun                                  */
        float moon_radius;   /* the moon's true angular radius, radians        */
        float light_left;    /* the sun's light the moon leaves (glare)        */
        float corona_scale;  /* Baumbach's corona, kcd/m^2 (0: none)          */
        float unused;
    } eclipse_sun;
    float eclipse_moon_dir[3]; /* the moon's centre, topocentric, unrefracted   */
    /* exposure (exposure.c) */
    float exposure;          /* LDR: 1 / (kcd/m^2) scale before the tone map    */
    float light_scale;       /* what the light rows (sky_uniform_desc.light) are
                                multiplied by on their way to the shaders: the
                                exposure on a fragment stage without highp
                                (LDR), else 1                                  */
    float shader_exposure;   /* sky_display_exposure: exposure / light_scale    */
    float night_shift;       /* sky_display_rods: 0..1, the rods' share at the
                                eye's adaptation, the blue shift at most        */
    float display_exposure;  /* the 8-bit output's exposure (= exposure in LDR;
                                for an HDR host's sky_display: sky_display_bind) */
    float display_cd;        /* sky_display_cd: cd/m^2 of a unit of the tone
                                map's input (1000 / display_exposure)           */
    float star_local_gain;   /* LDR: the stars' gain against a sky the eye has
                                not adapted to (a solar eclipse)               */
    /* the camera (camera.c) */
    float fisheye;           /* 1 = equidistant all-sky mapping                 */
    float aspect[2];         /* fisheye: ndc scale so the circle is round        */
    float view_proj[16];     /* horizon direction (w = 0) -> clip                */
    float pixel_angle;       /* radians per pixel at the view centre             */
    float viewport[4];       /* window x, y, width, height of the host's viewport */
    float far_z;             /* clip z / w of the far plane (sky.c, cfg.depth)    */
    /* the dome's image (dome.c) */
    float dome_texel[2];     /* 1 / its texture's width, height                  */
    float dome_scale[2];     /* the share of the texture it uses, per axis       */
    /* clouds (clouds.c, R-P sec. 3.1) */
    float cover, density, sunset;
    float cloud_uv_scale;    /* from height                                      */
    float cloud_texels_per_step; /* texels per unit of coordinate over the pixels
                                    of the viewport one fragment step spans  */
    float dome_step_pixels;  /* the viewport pixels a step in the dome's image spans */
    float cloud_offset0[2], cloud_offset1[2], cloud_offset_upper[2];
    float cloud_light[3];    /* cloud colour multiplier: sunlight + ambient      */
    float upper_cover;       /* the cover the thin upper layer's amount, 0.35 x
                                cover, reads: the cover itself, or with a
                                weather its upper / 0.35 (weather.c)         */
    float light_through;     /* the weather's deck: the share of the light above
                                it that passes where it covers (weather.c)   */
    float deck;              /* 0..1: a weather's uniform deck under the layers
                                (weather.c): no gaps, less contrast          */
    float haze[2];           /* a weather's haze beyond the clear sky's: its
                                optical depth straight up, and its layer's
                                height over the path to the horizon (weather.c) */
    float visibility_km;     /* the weather's (60 without one; weather.c)         */
    float haze_beta;         /* its haze's extinction beyond the clear sky's, /m */
    float flash_klx;         /* lightning now: illuminance facing it (weather.c) */
    float flash_dir[4];      /* toward the brightest flash, horizon frame; w the
                                sharpness of the patch it lights              */
    float flash_deck_kcd;    /* the deck's luminance where the flash lights it  */
    float flash_light[3];    /* that, held for a night-adapted eye and tinted    */
    float deck_opacity;      /* the clouds' mean opacity, what lighting.c dims
                                the beam by (clouds.c; the cover without them) */
    /* the aerial-perspective froxels (hillaire.c, sky_aerial_froxels) */
    float froxel_clip_to_dir[16]; /* clip to a horizon-frame point on the view ray */
    float froxel[4];         /* the pass's first slice, km per slice, steps per slice */
    float froxel_weather[2]; /* a weather's: the deck's dimming of the air's light, the haze's 1/m */
    float cloud_mean[2];     /* the clouds' opacity and grey times opacity,
                                averaged over the texture (the host's ambient)  */
    float sunset_color[3];
    float sunset_gradient[SKY_SUNSET_SAMPLES]; /* R-P's sunset gradient by the
                                angle from the sun, from the texture's alpha */
} sky_frame;
/* The uniform table reads each packed vec4 above as four floats in a row. */
_Static_assert(sizeof(((sky_point_frame *)0)->size) == 4 * sizeof(float), "a point's size is a vec4");
_Static_assert(sizeof(((sky_frame *)0)->hl_misc) == 4 * sizeof(float), "hl_misc is a vec4");
_Static_assert(sizeof(((sky_frame *)0)->eclipse_sun) == 4 * sizeof(float), "eclipse_sun is a vec4");

/* ---- the weather (weather.c) -----------------------------------------------
 * sky_set_weather's transition, on the sky's running clock (sky_core's
 * running): from, to, when it starts and how long it takes. */
typedef struct sky_weather_clock {
    int set; /* sky_set_weather was called: the weather owns cover and density */
    sky_weather from, to;
    double start, seconds;
} sky_weather_clock;
/* The target as the sky keeps it: NaN and unknown kinds refused, the rest
 * clamped (the first clamp named in err), the wind's direction wrapped
 * into 0..360. Returns SKY_OK, SKY_CLAMPED or SKY_ERR_INVALID_ARGUMENT. */
sky_result sky_weather_checked(const sky_weather *in, sky_weather *out, char *err, size_t err_len);
/* The transition's progress at t: 0 before it starts, 1 after it ends. */
double sky_weather_progress(const sky_weather_clock *c, double t);
/* The weather at running time t. */
void sky_weather_at(const sky_weather_clock *c, double t, sky_weather *out);
/* The wind (as the clouds' texture offsets move: x east, y south, m/s)
 * integrated from running time t0 to t1, exact for any step. */
void sky_weather_wind_integral(const sky_weather_clock *c, double t0, double t1, double out[2]);
/* Where a wind comes from, degrees clockwise from north, whose texture
 * offsets move along (vx, vy) (the inverse of the direction above). */
float sky_weather_wind_from(double vx, double vy);
/* lightning.c: SplitMix64's finaliser, for the hashes of cfg.seed's
 * random events (lightning, the aurora's curtains). */
uint64_t sky_mix64(uint64_t z);
/* Lightning's blue-white (weather.c): the deck's tint; the host's flash
 * light is it scaled to a luminance of one (lighting.c). */
extern const float sky_flash_tint[3];

/* lightning.c: the strikes from t0 to t1 at the clock's weather, drawn
 * from seed (the first max into out; returns how many there are), and
 * the flashes' light at t (klx on a surface facing the brightest; its
 * direction, horizon frame). */
int sky_lightning_strikes(const sky_weather_clock *clock, unsigned seed, double t0, double t1,
                          sky_lightning_strike *out, int max);
typedef struct sky_flash {
    float klx;       /* illuminance on a surface facing the brightest        */
    float dir[3];    /* toward it, horizon frame                            */
    float deck_kcd;  /* the deck's luminance where it lights it             */
    float sharpness; /* of its patch: exp(sharpness (cos angle - 1))        */
} sky_flash;
void sky_lightning_flash(const sky_weather_clock *clock, unsigned seed, double t, sky_flash *out);

/* ---- the shared context ---------------------------------------------------
 * What every room may read: the configuration, the GL functions and
 * profile, the sliders and observer, the astronomy, the atmosphere's
 * description, the texture registry and the frame. Each room writes only
 * its own part (see docs/ARCHITECTURE.md); its private state is its own
 * struct, which sky.c allocates and hands back to it. */
struct sky_atmosphere_state; /* atmosphere/atmosphere.c */
struct sky_dome_snippets;    /* layer.h */
struct sky_snippet;          /* gl/gl.h */
struct sky_layer_class;      /* layer.h */
/* A snippet whose in_state uniform rows read from a layer's state
 * (sky_snippet_bind, gl/program.c). */
typedef struct sky_snippet_binding {
    const struct sky_snippet *snippet;
    const void *state;
} sky_snippet_binding;
/* A night glow (a layer whose class has glow functions) and its state:
 * the atmosphere adds their light to its summary and its CPU radiance
 * without knowing which layers they are (sky.c fills the list). */
typedef struct sky_glow_source {
    const struct sky_layer_class *layer;
    const void *state;
} sky_glow_source;
typedef struct sky_core {
    sky_config cfg;               /* texture_dir: during sky_create only        */
    unsigned features;            /* resolved: never 0                          */
    sky_gl gl;
    sky_gl_profile profile;
    char gl_version[128];         /* copy of GL_VERSION                        */
    sky_gl_caps caps;             /* what beyond GL 2.0 it may use (gl/load.c)     */

    sky_params params;            /* cover and density: the weather's once set   */
    sky_weather_clock weather;    /* sky_set_weather's transition (weather.c)   */
    double running, running_before; /* the running clock, seconds, after and
                                     before the last sky_update (sky.c)      */
    sky_observer observer;
    sky_astro astro;              /* for observer + time slider; see observer.c */
    sky_astro_cache astro_cache;  /* the series' nodes last used (astro.h)      */
    float exposure_bias;          /* stops, sky_set_exposure_bias               */
    float horizon_to_world[9];    /* column-major; identity when cfg's is zero   */
    int horizon_handedness;       /* its determinant's sign: -1 a reflection     */

    sky_atmosphere_path atmosphere;  /* resolved: never DEFAULT                  */
    sky_atmosphere_params atm;       /* checked; the Earth preset when zero      */
    sky_atmosphere_params atm_rgb;   /* atm averaged over the sRGB channels     */
    double sun_irradiance_klx[3];    /* sky_sun_irradiance_rgb, once            */
    struct sky_atmosphere_state *atmosphere_state; /* atmosphere.c's own      */
    unsigned char gradient_texels[256 * 4]; /* the day gradient (gradient.png),
                                     for the gradient path's CPU twin (dome.c) */

    sky_texture *textures;        /* by sky_texture_id, then those registered at
                                     run time (sky_texture_register)         */
    int texture_count, texture_capacity;
    sky_snippet_binding *snippet_bindings; /* sky_snippet_bind's             */
    int snippet_binding_count, snippet_binding_capacity;
    sky_glow_source *glows;       /* the enabled night glows (sky.c)          */
    int glow_count;
    sky_layer creating_layer;     /* the stats index of the layer whose create
                                     runs: the owner of the textures it makes
                                     (a layer after 0.5 has no constant)     */
    int program_count, buffer_count; /* live GL objects, for the stats          */
    size_t buffer_bytes;
    double lut_ms;                /* table builds since the last draw          */
    int viewport[4];              /* the host's viewport at this sky_draw       */
    const struct sky_dome_snippets *dome_snippets; /* of the enabled layers (sky.c) */
    int dome_front_shows, dome_night_shows, /* this draw: a layer of that dome */
        dome_optics_shows, dome_occasional_shows; /* role is visible (sky.c) */

    GLuint identity_program;      /* the first program built: a context where it
                                     is no program is not the sky's (sky.c)   */
    int drawing;                  /* inside sky_draw (sky.c)                   */
    int capture_without_sun;      /* a capture that leaves the sun's disc out  */
    int capturing;                /* inside sky_capture_environment: the dome
                                     at every pixel (dome.c)                  */
    int dome_divisor;             /* the dome's image is 1/divisor of the viewport
                                     on each axis; 0: drawn directly (dome.c) */
    int dome_day_divisor;         /* that of a day frame whose clouds show     */

    sky_frame frame;
} sky_core;

/* weather.c: the frame's part, before the layers': the weather's cover
 * and density into the sliders, its thin layer and deck light into the
 * frame. */
void sky_weather_frame(sky_core *c);
/* after the layers': a weather's deck greys and dims the ambient, the
 * horizon and the ground by its light_through where it covers the sky. */
void sky_weather_light(sky_core *c);
/* the share of the light that a weather's deck takes away where it
 * covers the sky: its opacity times what it does not let through (0
 * without one) */
double sky_weather_deck_share(const sky_frame *f);
/* lighting.c: the sun's beam at the observer, klx per channel (what
 * sky_get_lighting reports as sun_color): through the air, the part of
 * the disc above the horizon, a solar eclipse's share, a weather's deck. */
void sky_sun_beam(const sky_core *c, float rgb[3]);

#endif /* SKY_CORE_H */
