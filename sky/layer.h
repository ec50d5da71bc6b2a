/*
 * The layer interface: one table of functions per drawn phenomenon, as
 * GLFW's platform table or osghimmel's geodes. Each layer file exports one
 * sky_layer_class and owns its state (a struct private to the file, which
 * sky.c allocates with state_size bytes and hands back on every call), its
 * programs, buffers, uniforms (its rows read its own state), draw and
 * byte accounting. sky.c walks the back-to-front table of them in
 * layers.c; adding a layer is its own file and one row there
 * (docs/ARCHITECTURE.md, "Adding a layer").
 */
#ifndef SKY_LAYER_H
#define SKY_LAYER_H

#include "core.h"
#include "gl/gl.h"

/* Where a layer's snippet goes in the dome's program, if it has one. */
typedef enum sky_dome_role {
    SKY_DOME_NONE,  /* drawn by itself                                         */
    SKY_DOME_FRONT, /* in front of everything behind it (clouds): compiled into
                       the dome and into every layer drawn over the dome, so
                       those hide behind it                                  */
    SKY_DOME_NIGHT, /* the night backdrop (flicker stars, star map): only in
                       the dome's night variants                              */
    SKY_DOME_OPTICS, /* light in front (a rainbow, a halo: the snippet's
                       front_function): only in the dome's optics variants,
                       drawn while one of them shows over the front layers  */
    SKY_DOME_NIGHT_OCCASIONAL /* a night glow that seldom shows and costs when
                       compiled in (the aurora): only in the night variants
                       built with it, drawn while it shows                 */
} sky_dome_role;

/* The stats index of a layer added after 0.5 (which has no sky_layer
 * constant): it follows SKY_LAYER_COUNT in the table's order, and the
 * host finds it by name (sky_layer_index). */
#define SKY_LAYER_NEXT ((sky_layer)-1)

typedef struct sky_layer_class {
    const char *name;         /* sky_layer_name's, the stats' and the command
                                 line's                                      */
    sky_layer slot;           /* its stats index: a sky_layer of 0.5, or
                                 SKY_LAYER_NEXT                              */
    unsigned feature;         /* the SKY_* bit that includes it; 0: always     */
    size_t state_size;        /* bytes of private state (zeroed)              */
    sky_dome_role dome_role;
    const sky_snippet *dome_snippet; /* with a dome role                      */
    sky_blend blend;          /* for draw                                     */
    /* Resources. 0, or -1 with a message. destroy is called for every
     * state sky.c allocated: after a failed create on whatever it left, and
     * on a state still all zero when an earlier step failed (no GL object
     * to delete then, so it must call no GL function). */
    int (*create)(sky_core *s, void *state, char *err, size_t err_len);
    void (*destroy)(sky_core *s, void *state);
    /* Clocks: dt seconds of running time (finite, >= 0). */
    void (*advance)(sky_core *s, void *state, double dt);
    /* Its clocks back to zero (sky_set_elapsed). */
    void (*reset_clock)(void *state);
    /* Per-frame state from the sliders, observer and atmosphere (after
     * exposure.c): its part of s->frame. */
    void (*frame)(sky_core *s, void *state);
    /* Per draw, once the camera is set: what depends on the view. */
    void (*view)(sky_core *s, void *state);
    /* Whether it shows anything this frame. */
    int (*visible)(const sky_core *s, const void *state);
    /* Draws; returns the number of draw calls made. */
    int (*draw)(sky_core *s, void *state);
    /* GPU bytes it holds besides its textures (which are counted by their
     * owner); NULL: none. */
    size_t (*buffer_bytes)(const sky_core *s, const void *state);
    /* A night glow (NULL: not one): its light above the air in kcd/m^2 per
     * channel, at the zenith from the date and cfg alone (callable before
     * the layer's frame: the atmosphere's summary), and from horizon
     * direction d after its frame (the atmosphere's CPU radiance). The
     * atmosphere dims both by the air and adds them, knowing no layer. */
    void (*glow_zenith)(const sky_core *s, const void *state, double rgb[3]);
    void (*glow_at)(const sky_core *s, const void *state, const double d[3], double rgb[3]);
} sky_layer_class;

/* (The layers' classes are declared where their table is: layers.c.) */

/* The dome snippets of the enabled layers, by role (sky.c fills them from
 * the table before any layer is created, each bound to its layer's
 * state): the dome composes its programs from them, and each layer drawn
 * over the dome includes the front ones. As many as the table has rows. */
typedef struct sky_dome_snippets {
    const sky_snippet **front, **night, **optics, **occasional;
    int front_count, night_count, optics_count, occasional_count;
} sky_dome_snippets;
/* dome.c: the divisor of the dome's image for this context and output
 * (0: the dome is drawn directly), decided before any layer is created. */
int sky_dome_divisor_for(const sky_core *s);
/* dome.c: the divisor of the image for a day frame whose clouds show
 * (smaller than sky_dome_divisor_for's where that frame affords it). */
int sky_dome_day_divisor_for(const sky_core *s);
/* over_dome.c: the dome image's uniforms (the composite pass's), its
 * alpha as the cover of a layer drawn over it, and the define for an
 * image in the corner of a power-of-two texture. */
extern const sky_snippet sky_dome_image_snippet, sky_dome_cover_snippet, sky_dome_corner_snippet;
/* over_dome.c: builds a program of a layer drawn over the dome: what it needs to hide
 * behind the front layers (their snippets, or where the dome has an image,
 * the image's alpha: dome_cover.glsl), then its own snippets. */
int sky_program_build_over_dome(sky_core *s, const sky_dome_snippets *dome, sky_program *p, const char *vert_main,
                                const char *frag_main, const sky_snippet *const *own, int own_count, char *err,
                                size_t err_len);

/* ---- what layers offer each other and the tests ------------------------- */
/* clouds.c: drift of each cloud layer (0 with its detail, 1, the thin
 * upper one) in texture periods per second at speed 1; the wrapped
 * offsets (SKY_CLOUD_LAYERS x 2). */
#define SKY_CLOUD_LAYERS 3
extern const double sky_cloud_velocity[SKY_CLOUD_LAYERS][2];
const double *sky_clouds_offsets(const void *clouds_state);
/* The clouds' shadow on the ground (sky.h, "Cloud shadows"): w x h bytes,
 * rows north to south, over extent_m along the longer side around the
 * observer, the layer at height_m; 255 = full sun. Only the rows
 * first_row, first_row + row_step, ... are written (1 and 0: all). */
void sky_clouds_shadow(const sky_core *s, const void *clouds_state, double extent_m, int w, int h, double height_m,
                       int first_row, int row_step, unsigned char *out);
/* clouds.c: the clouds as the host's ambient sees them in direction d
 * (horizon frame, unit): their mean opacity over the drifting texture
 * (frame.cloud_mean, faded into the horizon as the dome fades them) and
 * their colour there (kcd/m^2, lit and sunset-tinted as clouds.glsl
 * tints them); 0 below the horizon, without clouds or at cover 0. */
void sky_clouds_mean_at(const sky_core *s, const double d[3], double *alpha, double rgb[3]);
/* clouds.c: the viewport pixels one step of the fragments drawing the
 * clouds spans (the dome's image's divisor, or 1), for the fade of the
 * detail a pixel cannot hold; the dome sets it for each draw. */
void sky_clouds_image_step(sky_core *s, int step_pixels);
/* flicker.c: galaxy brightness 0..1 for a direction, from the 128x128
 * galaxy image stretched over the dome (R-P sec. 4); the flicker clock. */
float sky_flicker_galaxy_vertex(const unsigned char *galaxy_rgba, const float dir[3]);
double sky_flicker_clock(const void *flicker_state);
/* flicker.c: kcd/m^2 of a full-intensity star texel this frame (0: the
 * layer is off, not just dim). */
float sky_flicker_star_luminance(const void *flicker_state);
/* stars.c: the scintillation clock; the catalogue it draws, and a
 * request to upload it again (after a test changed it). (A B - V's colour:
 * light_units.h.) */
double sky_stars_clock(const void *stars_state);
struct sky_catalog *sky_stars_catalog(void *stars_state);
void sky_stars_reload(void *stars_state);
/* stars.c, for the tests: every star through stars.vert (1), or only the
 * cells' selection (0, the default) */
void sky_stars_draw_whole(void *stars_state, int whole);
/* (What the sets of points share, stars.c's and planets.c's: points.h.) */
/* planets.c: the planets' places of the last frame (SKY_ASTRO_PLANETS). */
const sky_astro_planet *sky_planets_places(const void *planets_state);
/* zodiacal.c, for the tests: the frame's horizon -> ecliptic rotation
 * (column-major mat4, +x at the sun) of a zodiacal state. */
const float *sky_zodiacal_rotation(const void *zodiacal_state);

/* sun.c: the sunlight above the atmosphere that the drawn disc sums to,
 * klx (1 / r^2 with the sun's distance). */
double sky_sun_illuminance_klx(const sky_core *s);

/* moon.c: the factor the moon is drawn larger than its true size
 * (cfg.moon_scale, back to 1 near the sun, where it eclipses); the
 * moonlight a host's scene receives (sky_get_lighting). */
double sky_moon_drawn_scale(const sky_core *s);
void sky_moon_lighting(const sky_core *s, float moon_color[3]);
/* clouds.c: the clouds' base height, metres (cfg.cloud_height_m, 1500 by
 * default, at the height slider's middle, scaled as the slider scales the
 * drawn clouds): where their shadows fall, where the rain hangs from. */
double sky_cloud_height_m(const sky_core *c);
/* lighting.c: the light an optical phenomenon (a bow, a halo) is seen by:
 * the sun's beam or the moon's light (with SKY_MOON), whichever is the
 * brighter of those allowed, klx per channel in rgb (the moon's grey: to
 * the eye colourless at its level) and toward it in dir; *by_moon 1 for
 * the moon. Returns its luminance (0: neither). */
double sky_optics_light(const sky_core *c, int sun_allowed, int moon_allowed, float rgb[3], float dir[3],
                        int *by_moon);
/* (The moon's light above the air, which the atmosphere and the clouds
 * scatter: moonlight.h.) */

#endif /* SKY_LAYER_H */
