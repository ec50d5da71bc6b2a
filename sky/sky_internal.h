/*
 * libsky internals shared by the per-phenomenon files. Not installed.
 */
#ifndef SKY_INTERNAL_H
#define SKY_INTERNAL_H

#include "astro.h"
#include "gl/glapi.h"
#include "sky.h"

#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#define SKY_PI 3.14159265358979323846

/* ---- small numeric guards (named, so a reader sees the intent) ---------- */
static inline double sky_clampd(double x, double lo, double hi) { return x < lo ? lo : (x > hi ? hi : x); }
static inline float sky_clampf(float x, float lo, float hi) { return x < lo ? lo : (x > hi ? hi : x); }
/* Wraps x into [0, period): long-running offsets stay small enough for
 * float uniforms. fmod keeps the full double precision of x. */
double sky_wrap(double x, double period);
/* A clock's phase in [0, 1) advanced by rate cycles per second over dt
 * seconds (any finite dt >= 0, up to the largest double). */
double sky_phase_advance(double phase, double rate, double dt);
/* The stars' scintillation clock (stars.frag): RATE new random values a
 * second, counted modulo PERIOD so the float uniform keeps its fraction
 * after years of running. */
#define SKY_SCINTILLATION_RATE 10.0
#define SKY_SCINTILLATION_PERIOD 997.0
double sky_smoothstep(double e0, double e1, double x);
/* Wall-clock milliseconds (C11 timespec_get), for statistics. */
double sky_now_ms(void);

/* ---- embedded assets (generated at build time by tools/embed) ----------- */
typedef struct sky_blob {
    const char *name;
    const unsigned char *data;
    size_t size;
} sky_blob;
const sky_blob *sky_find_blob(const char *name); /* NULL if not embedded */

/* ---- PNG decoding (gl/image.c) ----------------------------------------- */
int sky_png_info(const unsigned char *data, size_t size, int *w, int *h);
unsigned char *sky_png_decode_rgba(const unsigned char *data, size_t size, int *w, int *h, const char **why);
void sky_png_free(unsigned char *rgba);
/* Decodes a PNG of exactly expect_w x expect_h to RGBA8 (checked from the
 * header before decoding). Returns 0, or -1 with a message naming label. */
int sky_image_decode(const unsigned char *data, size_t size, int expect_w, int expect_h, unsigned char **rgba,
                     const char *label, char *err, size_t err_len);

/* ---- textures ----------------------------------------------------------- */
typedef enum sky_texture_id {
    SKY_TEX_CLOUDS = 0, /* RGBA: photo, noise, detail, sunset gradient (R-P sec. 3) */
    SKY_TEX_FLICKER,    /* RGBA: intensity, rate, variance, phase (R-P sec. 4)      */
    SKY_TEX_STARMAP,    /* equirectangular J2000 faint stars + Milky Way (Mueller 4.4) */
    SKY_TEX_MOON,       /* 256x128 lunar albedo, selenographic (Mueller 2.2.2)       */
    SKY_TEX_ECLIPSE,    /* 128x1 eclipse colour h(t), log10-encoded (Mueller 3.2)    */
    SKY_TEX_SKYVIEW,    /* Hillaire's sky-view table (atmosphere/hillaire.c)       */
    SKY_TEX_TRANSMITTANCE, /* Hillaire's transmittance table (CORE33: GPU builds)  */
    SKY_TEX_MULTISCATTER,  /* Hillaire's multiple-scattering table (CORE33)        */
    SKY_TEX_COUNT
} sky_texture_id;

typedef struct sky_texture {
    GLuint id;
    int width, height;
    size_t bytes;
    sky_layer owner;
} sky_texture;

/* ---- star catalogue (catalog.c) --------------------------------------------- */
typedef struct sky_catalog {
    sky_star *stars; /* sorted by magnitude, brightest first */
    int count;
} sky_catalog;
int sky_catalog_parse(sky_catalog *cat, const unsigned char *data, size_t size, char *err, size_t err_len);
int sky_catalog_load(sky_catalog *cat, char *err, size_t err_len); /* the embedded one */
const sky_star *sky_catalog_find(const sky_catalog *cat, int hip);
void sky_catalog_free(sky_catalog *cat);

/* ---- observer (observer.c) --------------------------------------------------- */
sky_observer sky_default_observer(void);
int sky_observer_check(const sky_observer *o, char *err, size_t err_len);
/* Astronomy for the observer, with the time slider's time of day when the
 * observer asks for it. */
int sky_observer_astro(const sky_observer *o, double time_of_day, sky_astro *a, char *err, size_t err_len);
void sky_astronomy_from_astro(const sky_astro *a, sky_astronomy *out);

/* ---- per-frame state: everything the shaders read ------------------------ */
typedef struct sky_frame {
    /* common */
    float sun_dir[3];        /* horizon frame, unit                              */
    float moon_dir[3];       /* horizon frame, unit, refracted                   */
    float sun_altitude;      /* radians, geometric                               */
    float daylight;          /* R-P "amount of sunlight", 0..1                   */
    float night;             /* visibility of night layers, 0..1                 */
    float sun_transmittance[3]; /* direct sunlight through the atmosphere       */
    float sun_luminance;     /* kcd/m^2 at the disc centre, before extinction    */
    float sun_radius;        /* angular radius of the drawn disc, radians        */
    float sun_true_dir[3];   /* the sun's centre without refraction              */
    float refraction_pressure; /* Saemundsson's scale at the observer (astro.c)  */
    float sky_luminance;     /* kcd/m^2: the day sky's scale (exposure, clouds,
                                moon), dimmed by a solar eclipse               */
    float day_luminance;     /* kcd/m^2: the gradient path's own scale, before
                                the eclipse (its shader applies that per pixel) */
    float eclipse_sky[4];    /* x: the day sky's light left everywhere by a solar
                                eclipse; yzw: the extra at the horizon, rgb     */
    float eclipse_sky_mean;  /* what that leaves of the sky's mean luminance (1
                                without an eclipse; sky_luminance has it)       */
    float eclipse_sun[4];    /* x: the moon's true angular radius, y: the sun's
                                light left (glare), z: corona's scale (kcd/m^2) */
    float eclipse_moon_dir[3]; /* the moon's centre, topocentric, unrefracted   */
    float horizon_tint[3];   /* colour of the horizon under a low sun            */
    float night_luminance;   /* kcd/m^2: scale of the night sky background       */
    float moonlight;         /* 0..25: the moon's brightening of the night sky    */
    float exposure;          /* LDR: 1 / (kcd/m^2) scale before the tone map    */
    float night_shift;       /* 0..0.6: scotopic blue shift in the tone map      */
    float output_hdr;        /* 1 = linear out, 0 = tone mapped                 */
    float fisheye;           /* 1 = equidistant all-sky mapping                 */
    float aspect[2];         /* fisheye: ndc scale so the circle is round        */
    float frame_index;       /* dither seed                                     */
    float view_proj[16];     /* horizon direction (w = 0) -> clip                */
    float pixel_angle;       /* radians per pixel at the view centre             */
    float ambient_rgb[3];    /* sky irradiance on an upward surface, klx         */
    float fog_rgb[3];        /* horizon luminance, kcd/m^2                       */
    /* Preetham (preetham.c): Perez A..E and zenith values for (Y, x, y) */
    float perez[5][3], perez_zenith[3];
    /* analytic Rayleigh + Mie (rayleigh.c) */
    float tau_rayleigh[3], tau_mie_sca[3], tau_mie_ext[3], tau_ozone[3];
    float chapman_x[3], sun_depth[3], sun_irradiance[3], mie_phase[3];
    /* Hillaire's sky-view table (hillaire.c) and the blend */
    float skyview_map[4], skyview_horizon[2], skyview_decode[3], blend_weight;
    /* the GPU build of the sky-view table (skyview_build.frag) */
    float hl_geometry[4], hl_profile[4], hl_rayleigh[3], hl_mie_sca[3], hl_mie_ext[3], hl_ozone[3], hl_albedo[3];
    float hl_sizes[4], hl_misc[4], hl_steps[4];
    /* clouds (R-P sec. 3.1) */
    float cover, density, sunset;
    float cloud_uv_scale;    /* from height                                      */
    float cloud_offset0[2], cloud_offset1[2], cloud_offset_detail[2], cloud_offset_upper[2];
    float cloud_light[3];    /* cloud colour multiplier: sunlight + ambient      */
    float sunset_color[3];
    /* flicker stars (R-P sec. 4) */
    float flicker_phase;     /* flicker time in rate units, wrapped             */
    float star_luminance;    /* kcd/m^2 of a full-intensity star texel          */
    /* catalogue stars (stars.c) */
    float star_rot[16], star_aberration[3], star_size[4], star_viewport[4], star_pressure[3];
    float star_flux_scale, star_extinction[3], star_shell[3], star_seed;
    float star_occulter[4];  /* the moon's true direction and the cosine of its
                                drawn radius (2: no moon): stars behind it go */
    float star_local_gain;   /* LDR: the stars' gain against a sky the eye has
                                not adapted to (a solar eclipse; sky.c)        */
    /* star map (starmap.c) */
    float starmap_rot[16], starmap_scale;
    /* moon (moon.c) */
    float moon_body[16], moon_view[16], moon_light[3], moon_color[3], moon_terms[4], moon_earthshine[3];
    float moon_radius_tan;   /* the drawn disc's radius on its tangent plane     */
    float moon_center_km[3], shadow_axis[3], shadow[4];
} sky_frame;

/* ---- programs and the uniform table ------------------------------------- */
typedef enum sky_uniform_type { SKY_U_F1, SKY_U_F2, SKY_U_F3, SKY_U_F4, SKY_U_M4, SKY_U_TEX } sky_uniform_type;

/* One row per uniform: the GLSL name, its type, and where its value lives
 * (an offset into sky_frame, or a texture id). Each phenomenon file owns its
 * rows; a program built from several snippets sets the rows of each. */
typedef struct sky_uniform_desc {
    const char *name;
    sky_uniform_type type;
    size_t offset;           /* into sky_frame; texture id for SKY_U_TEX      */
} sky_uniform_desc;
#define SKY_UF(name, type, field) { name, type, offsetof(sky_frame, field) }
#define SKY_UT(name, tex) { name, SKY_U_TEX, (size_t)(tex) }

/* A snippet: the GLSL functions of one phenomenon plus its uniform rows. */
typedef struct sky_snippet {
    const char *define;      /* e.g. "SKY_HAS_CLOUDS"                          */
    const char *source;      /* embedded GLSL file name; NULL = uniform rows only */
    const sky_uniform_desc *uniforms;
    int uniform_count;
} sky_snippet;

#define SKY_MAX_SNIPPETS 8
#define SKY_MAX_UNIFORMS 64
typedef struct sky_program {
    GLuint id;
    int uniform_count;
    const sky_uniform_desc *uniforms[SKY_MAX_UNIFORMS];
    GLint locations[SKY_MAX_UNIFORMS];
} sky_program;

/* The sun's and the moon's quads are drawn as a grid of
 * SKY_DISC_GRID^2 cells: their vertex shaders undo the refraction at each
 * vertex (common.glsl's sky_unrefract), which is smooth enough over a
 * cell (0.53 degree for the sun, 0.33 for the moon at its default scale)
 * for linear interpolation to keep the disc's shape: w^2/8 times the
 * refraction's curvature is at most 13 arcseconds at the horizon (1.3 %
 * of the sun's radius), 5 for the moon. The fragment shaders only
 * normalise. The vertices (grid position, direction) are rewritten each
 * frame; the indices are fixed. */
#define SKY_DISC_GRID 16
#define SKY_DISC_GRID_VERTICES ((SKY_DISC_GRID + 1) * (SKY_DISC_GRID + 1))
#define SKY_DISC_GRID_INDICES (SKY_DISC_GRID * SKY_DISC_GRID * 6)
#define SKY_DISC_GRID_BYTES \
    (SKY_DISC_GRID_VERTICES * 5 * sizeof(float) + SKY_DISC_GRID_INDICES * sizeof(unsigned short))
typedef struct sky_disc_grid {
    GLuint vertices, indices;
} sky_disc_grid;

/* A physical path's sky in a few numbers (atmosphere.c): the mean
 * luminance over the upper hemisphere, the irradiance on an upward surface
 * and the horizon's luminance, without the night sky's own light. */
typedef struct sky_summary {
    double mean, irradiance[3], fog[3];
} sky_summary;

/* ---- the sky ------------------------------------------------------------ */
struct sky {
    sky_config cfg;
    sky_gl gl;
    sky_gl_profile profile;
    unsigned features;
    char gl_version[128];         /* copy of GL_VERSION                        */
    char error[256];

    sky_params params;
    sky_observer observer;
    float exposure_bias;          /* stops, sky_set_exposure_bias               */
    sky_atmosphere_params atm;    /* checked; the Earth preset when zero        */
    sky_atmosphere_params atm_rgb; /* atm at the channels' effective wavelengths */
    sky_atmosphere_path atmosphere; /* resolved: never DEFAULT                  */
    double sun_irradiance_klx[3];   /* sky_sun_irradiance_rgb, once            */
    struct sky_hillaire_tables *hillaire; /* HILLAIRE, BLEND (hillaire.c)       */
    unsigned char *skyview_encoded;       /* COMPAT20's 8-bit sky-view table   */
    int skyview_valid, skyview_uploaded; /* CPU table (COMPAT20) or GPU build done */
    double skyview_sun_mu, skyview_altitude_km, skyview_log2_floor;
    double lut_ms;                        /* table builds since the last draw  */
    sky_summary summary;                  /* of the last table rebuild (atmosphere.c) */
    int summary_valid;                    /* 0: the tables changed since         */
    sky_astro astro;              /* for observer + time slider; see observer.c */
    double scintillation_phase;   /* wrapped: the stars' clock (stars.c)       */
    double cloud_offsets[4][2];   /* wrapped into [0,1): layers 0, 1, detail, upper */
    double flicker_phase;         /* wrapped (see flicker.c)                   */
    float horizon_to_world[9];
    int world_is_identity;

    sky_texture textures[SKY_TEX_COUNT];
    sky_program dome;             /* the dome pass: atmosphere + clouds          */
    sky_program dome_night;       /* the same with the night layers (flicker)    */
    sky_program dome_night_clear; /* night layers without clouds (cover 0)       */
    sky_program ground;           /* below the horizon: atmosphere only          */
    sky_program sun;              /* sun quad                                  */
    sky_program transmittance_build, multiscatter_build, skyview_build; /* CORE33: Hillaire's tables on the GPU */
    GLuint skyview_fbo;           /* renders into each of the tables in turn    */
    sky_program stars;            /* catalogue stars (points)                  */
    sky_program moon;             /* moon billboard                            */
    sky_disc_grid moon_grid;      /* the moon's quad, tessellated               */
    float moon_albedo_mean;       /* the albedo map's near-side mean            */
    double moon_axes[3][3];       /* billboard x (right), y (up), moon direction */
    double moon_radius_tan;       /* drawn disc radius on the tangent plane     */
    sky_catalog catalog;
    GLuint star_buffer;
    double star_epoch;            /* years since J2000 of the uploaded positions */
    float star_point_max;         /* largest point size the context draws      */
    GLuint dome_vertices;         /* dome.c: direction, gradient colour, galaxy */
    GLuint dome_indices;
    int dome_index_count, dome_upper_first; /* indices: all, and where the upper hemisphere starts */
    sky_disc_grid sun_grid;       /* the sun's quad, tessellated                */
    GLuint vao;                   /* CORE33 only                               */
    int program_count, buffer_count;
    size_t buffer_bytes;

    sky_frame frame;
    sky_stats stats;
};

/* ---- error text --------------------------------------------------------- */
/* snprintf into an error buffer that may be NULL or empty. */
void sky_format(char *buf, size_t len, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
sky_result sky_fail(sky *s, sky_result code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* ---- gl/gl.c ------------------------------------------------------------ */
/* Loads the function table and picks the profile. Returns 0 or writes err. */
int sky_gl_init(sky *s, char *err, size_t err_len);
/* Compiles and links a program from the common prologue, the given snippets
 * and a vertex and fragment main file. Attributes: 0 a_pos, 1 a_dir,
 * 2 a_color. */
int sky_program_build(sky *s, sky_program *p, const char *vert_main, const char *frag_main,
                      const sky_snippet *const *snippets, int snippet_count, char *err, size_t err_len);
void sky_program_destroy(sky *s, sky_program *p);
/* Sets every uniform of the program from s->frame and binds its textures. */
void sky_program_apply(sky *s, const sky_program *p);
/* Uploads an RGBA8 image. repeat: wrap mode. Power-of-two sizes only. */
/* A power-of-two lookup texture without contents: RGBA32F with linear
 * filtering (is_float) or RGBA8 for an encoding, unfiltered;
 * sky_texture_update_lut fills its w x h corner (one of the two data
 * pointers). */
int sky_texture_create_lut(sky *s, sky_texture_id id, sky_layer owner, int w, int h, int is_float, char *err,
                           size_t err_len);
void sky_texture_update_lut(sky *s, sky_texture_id id, int w, int h, const unsigned char *rgba8, const float *rgb32f);
int sky_texture_create(sky *s, sky_texture_id id, sky_layer owner, const unsigned char *rgba, int w, int h,
                       int repeat, char *err, size_t err_len);
/* Loads a texture by file name: the override directory first, then the
 * embedded copy. Checks size and channel count against what is expected. */
int sky_texture_load(sky *s, sky_texture_id id, sky_layer owner, const char *name, int expect_w, int expect_h,
                     int repeat, char *err, size_t err_len);
void sky_texture_destroy(sky *s, sky_texture_id id);
/* Reads an asset (override directory first, then the embedded copy) and
 * decodes it to RGBA8, checking its size. Free with sky_png_free. */
int sky_asset_load_rgba(sky *s, const char *name, int expect_w, int expect_h, unsigned char **rgba, char *err,
                        size_t err_len);
GLuint sky_buffer_create(sky *s, GLenum target, const void *data, size_t bytes, GLenum usage);

/* Host GL state that sky_draw changes, saved and restored around it. */
#define SKY_ATTRIBS 3 /* a_pos, a_dir, a_color */
typedef struct sky_gl_state {
    GLint program, active_texture, array_buffer, element_buffer, vao, viewport[4], scissor_box[4];
    GLfloat clear_color[4];
    GLint textures[4];
    GLboolean blend, depth_test, cull_face, scissor_test, stencil_test, depth_mask, color_mask[4];
    GLint blend_src_rgb, blend_dst_rgb, blend_src_alpha, blend_dst_alpha, blend_eq_rgb, blend_eq_alpha;
    GLboolean program_point_size;
    GLint attrib_enabled[SKY_ATTRIBS], attrib_size[SKY_ATTRIBS], attrib_type[SKY_ATTRIBS], attrib_norm[SKY_ATTRIBS],
        attrib_stride[SKY_ATTRIBS], attrib_buffer[SKY_ATTRIBS];
    void *attrib_pointer[SKY_ATTRIBS];
} sky_gl_state;
void sky_gl_state_save(sky *s, sky_gl_state *st);
void sky_gl_state_restore(sky *s, const sky_gl_state *st);

/* ---- phenomena ---------------------------------------------------------- */
extern const sky_snippet sky_common_snippet;
extern const sky_snippet sky_gradient_snippet;
extern const sky_snippet sky_preetham_snippet;
extern const sky_snippet sky_rayleigh_snippet;
extern const sky_snippet sky_atmosphere_snippet; /* shared by every path */
extern const sky_snippet sky_extinction_snippet; /* the physical paths' optical depth */
extern const sky_snippet sky_hillaire_snippet;
extern const sky_snippet sky_hillaire_encoded_snippet; /* COMPAT20's 8-bit table */
extern const sky_snippet sky_blend_snippet;
/* atmosphere/params.c: 1 when every field is zero (= the Earth preset). */
int sky_atmosphere_is_zero(const sky_atmosphere_params *atm);
/* The description's coefficients re-sampled at the wavelengths the sRGB
 * channels of scattered sunlight come from (sky_ref_effective_wavelengths):
 * what the real-time physical paths render with. */
void sky_atmosphere_effective(const sky_atmosphere_params *in, sky_atmosphere_params *out);
/* atmosphere/atmosphere.c: the snippets of the selected path (up to 5, in
 * order; encoded_tables: COMPAT20's 8-bit sky-view table), and its
 * per-frame state (night sky, path coefficients, the host's ambient and
 * fog). */
int sky_atmosphere_snippets(sky_atmosphere_path path, int encoded_tables, const sky_snippet **out);
void sky_atmosphere_frame(sky *s);
/* Vertical optical depth above the observer per channel: the atmosphere
 * description's for the physical paths, the sun model's otherwise; what
 * dims the stars and the moon (Mueller sec. 5). */
void sky_atmosphere_zenith_depth(const sky *s, double depth[3]);
/* atmosphere/hillaire.c: tables at creation, the sky-view rebuild per
 * frame (CPU), its upload in sky_draw, the CPU twin of the shader. */
int sky_hillaire_create(sky *s, char *err, size_t err_len);
void sky_hillaire_destroy(sky *s);
void sky_hillaire_frame(sky *s);
void sky_hillaire_upload(sky *s);
void sky_hillaire_eval(const sky *s, const double d[3], double rgb[3]);
/* The sun above the atmosphere in linear sRGB, klx per channel: the
 * reference's (atmosphere/reference.c), so the physical paths and their
 * yardstick are lit alike. */
void sky_sun_irradiance_rgb(double rgb[3]);
/* CIE 1931 XYZ to linear sRGB (IEC 61966-2-1). */
void sky_xyz_to_linear_srgb(const double xyz[3], double rgb[3]);
/* atmosphere/preetham.c, rayleigh.c: per-frame coefficients, and CPU twins
 * of the shaders (radiance in kcd/m^2 for an upper-hemisphere direction,
 * without the night floor). */
double sky_preetham_turbidity(float requested); /* the turbidity the model uses */
void sky_preetham_frame(sky *s);
void sky_preetham_eval(const sky_frame *f, const double d[3], double rgb[3]);
void sky_rayleigh_frame(sky *s);
void sky_rayleigh_eval(const sky_frame *f, const double d[3], double rgb[3]);
/* Chapman's grazing-incidence function: slant over vertical column of an
 * exponential atmosphere, X = radius / scale height, mu = cos(zenith angle),
 * any mu in -1..1 (rayleigh.c). */
double sky_chapman(double X, double mu);
extern const sky_snippet sky_clouds_snippet;
extern const sky_snippet sky_flicker_snippet;
extern const sky_snippet sky_sun_snippet;
extern const sky_snippet sky_stars_snippet;
extern const sky_snippet sky_starmap_snippet;
extern const sky_snippet sky_moon_snippet;
extern const sky_snippet sky_eclipse_snippet;

/* The dome mesh with per-vertex gradient colour and galaxy (dome.c). */
int sky_dome_create(sky *s, char *err, size_t err_len);
/* Binds the dome's buffers and draws its upper (1) or lower (0) hemisphere. */
void sky_dome_draw(sky *s, int upper);
void sky_gradient_frame(sky *s);
/* Day-gradient colour (linear RGB) for a direction, from the 256x1
 * gradient image, as R-P's gradient texture maps it onto the dome. */
void sky_gradient_vertex(const unsigned char *gradient_rgba, const float dir[3], float rgb[3]);
/* Galaxy brightness 0..1 for a direction, from the 128x128 galaxy image
 * stretched over the dome (R-P sec. 4). */
float sky_flicker_galaxy_vertex(const unsigned char *galaxy_rgba, const float dir[3]);
/* Drift of each cloud layer (0, 1, detail, upper) in texture periods per
 * second at speed 1. */
extern const double sky_cloud_velocity[4][2];
int sky_clouds_create(sky *s, char *err, size_t err_len);
void sky_clouds_advance(sky *s, double dt);
void sky_clouds_frame(sky *s);
int sky_clouds_visible(const sky *s);
int sky_flicker_create(sky *s, char *err, size_t err_len);
void sky_flicker_advance(sky *s, double dt);
void sky_flicker_frame(sky *s);
int sky_stars_create(sky *s, char *err, size_t err_len);
void sky_stars_destroy(sky *s);
void sky_stars_frame(sky *s); /* after the camera is set up */
int sky_stars_visible(const sky *s);
void sky_stars_draw(sky *s);
/* B-V to linear sRGB of unit luminance (stars.c). */
void sky_star_color(double bv, float rgb[3]);
int sky_starmap_create(sky *s, char *err, size_t err_len);
void sky_starmap_frame(sky *s); /* after the camera is set up */
int sky_moon_create(sky *s, char *err, size_t err_len);
void sky_moon_frame(sky *s);
/* The factor the moon is drawn larger than its true size (cfg.moon_scale,
 * back to 1 near the sun, where it eclipses) */
double sky_moon_drawn_scale(const sky *s);
int sky_moon_visible(const sky *s);
void sky_moon_update_quad(sky *s);
int sky_sun_create(sky *s, char *err, size_t err_len);
void sky_sun_frame(sky *s);
int sky_sun_visible(const sky *s);
/* Fills the sun quad's corner directions for the current frame. */
void sky_sun_update_quad(sky *s);

/* Direct-beam transmittance for a ray at the given altitude (radians),
 * Kasten-Young air mass times a Rayleigh+aerosol optical depth; below the
 * horizon, the horizon's value. Non-decreasing in altitude. */
void sky_sun_transmittance(double altitude, float out[3]);
/* The fraction of a disc of the given angular radius (radians) whose
 * centre is at altitude that stands above the horizon: 0..1, continuous. */
double sky_disc_above_horizon(double altitude, double radius);
/* The grid's buffers (sun.c); 0, or -1 with a message naming `what`. */
int sky_disc_grid_create(sky *s, sky_disc_grid *g, const char *what, char *err, size_t err_len);
/* Rewrites the grid over the square centre +- half (tangent-plane units)
 * along the unit axes x and y; a_pos runs over +-pos_half. */
void sky_disc_grid_update(sky *s, const sky_disc_grid *g, const double centre[3], const double x[3],
                          const double y[3], double half, double pos_half);

#endif /* SKY_INTERNAL_H */
