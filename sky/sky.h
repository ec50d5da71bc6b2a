/*
 * libsky: a procedural sky for games and simulators on low-end OpenGL.
 *
 * The only header a game includes. One sky object per GL context; no global
 * state, no printing, no abort: every failure is a return value plus text
 * (sky_last_error, or the err buffer of sky_create).
 *
 *   sky_config cfg = {0};                      // zero = sensible defaults
 *   cfg.get_proc_address = glfwGetProcAddress;  // the host owns the context
 *   char err[256];
 *   sky *s = sky_create(&cfg, err, sizeof err);
 *   ...each frame:
 *   sky_update(s, dt);
 *   sky_draw(s, view, proj);                    // first thing after glClear
 *   ...
 *   sky_destroy(s);
 *
 * Conventions
 *   Matrices are column-major, as OpenGL expects (m[col * 4 + row]). The
 *   sky's own frame, the horizon frame, is right-handed: +x east, +y up (the
 *   zenith), +z south, so a camera looking down -z faces north.
 *   sky_config.horizon_to_world (column-major 3x3, its columns the horizon
 *   frame's x, y, z axes in the host's world) says how the host's world
 *   lies; sky_draw takes the host's own view and projection:
 *
 *   engine                    horizon_to_world           projection
 *   right-handed, Y up        all zero (identity)        OpenGL's (clip w = -z)
 *     (OpenGL, three.js, Godot, SDL + your own maths; examples/sdl2.c)
 *   right-handed, Z up        {1,0,0, 0,0,1, 0,-1,0}     OpenGL's
 *     (OpenSceneGraph, Blender-like worlds: north +y, up +z; examples/osg.cpp)
 *   left-handed, Y up         {1,0,0, 0,1,0, 0,0,-1}     the engine's own (clip
 *     (Irrlicht, Unity, DirectX-style maths;               w = +z): pass it as is
 *      examples/irrlicht.cpp)
 *
 *   A reflecting horizon_to_world is how a left-handed world states its
 *   handedness; any orthonormal matrix is accepted (determinant +1 or -1),
 *   anything else is rejected by sky_create. Where the projection and
 *   horizon_to_world disagree (a left-handed projection with a rotation, or
 *   a right-handed one with a reflection), sky_draw draws a mirror image and
 *   returns SKY_WARN_MIRRORED. Only the rotation of the view is used (the sky
 *   is centred on the viewer); any near and far planes, an infinite far plane
 *   and reversed-Z projections work.
 *   Drawing order: by default the sky is drawn first, right after glClear,
 *   and neither tests nor writes depth. An engine that draws its sky after
 *   its opaque scene (so the pixels the scene covers cost little) sets
 *   sky_config.depth to its convention: SKY_DEPTH_FAR_ONE (depth cleared
 *   to 1), SKY_DEPTH_FAR_ZERO (reversed-Z, cleared to 0) or
 *   SKY_DEPTH_FAR_ZERO_CLIP01 (reversed-Z with a 0..1 clip range); the sky
 *   then sits on the far plane with the depth test on and writes none.
 *   (examples/sdl2.c draws after its scene in each of the three; the
 *   OpenSceneGraph and Irrlicht examples draw first, in render bin -1 and
 *   the sky-box pass.) sky_draw_fisheye needs no matrices.
 *
 * Versions: SKY_VERSION_MAJOR, _MINOR, _PATCH below, sky_version() at run
 * time, and the same in sky.pc; CHANGELOG.md lists each version's changes.
 *  - A patch version fixes; it adds and removes nothing.
 *  - A minor version may add functions, enumerators, feature bits and
 *    fields. Before 1.0 it may also change sky_config or a function
 *    (binary incompatible): the shared library's soname is
 *    libsky.so.0.MINOR. From 1.0 on it adds only (fields at the end of a
 *    struct the library sizes, never one a host allocates), and the soname
 *    is libsky.so.MAJOR, changed only with the major version.
 *  - A name or field to be removed is deprecated first: kept working for
 *    one minor version, marked here ("Deprecated since X.Y, removed in
 *    X.Y+1") and in CHANGELOG.md, then removed.
 *
 * Reading this header: each function's comment opens with its name and
 * what it does (units, ranges, what 0 and NULL mean), then gives four fixed
 * parts, in this order, as GLFW's reference does with @errors,
 * @thread_safety and @since:
 *   Errors:         the sky_result codes it returns, and for what;
 *   Thread safety:  "any thread (pure)" or "the sky's thread" (Threads;
 *                   sky_create runs where the sky's context is to be);
 *   GL:             "none" (no GL call, no context needed), or what it needs
 *                   of the context and which of the host's GL state it
 *                   changes and puts back;
 *   Since:          the version that first had it.
 *
 * Since, the rule: sky.h's SKY_VERSION_* has been set six times, 0.1.0
 * by the first commit and then 0.2.0 .. 0.6.0, each number taking in all
 * that had landed since the one before. A function's version is the first
 * number set at or after the commit that added it; one added after 0.6.0
 * was set is 0.6.0's, the version on main. CHANGELOG.md's entries agree
 * from 0.3.0 on (before it, the git history), and "Since: 0.1.0" marks
 * what the first commit already had. A later change to a function's
 * signature is named beside its version.
 *
 * Errors: a sky_result below 0 is an error, and the call changed nothing
 * unless its Errors part says otherwise; above 0 is a warning (SKY_CLAMPED,
 * SKY_WARN_MIRRORED): the call did its work, and the message says what it
 * adjusted or what to fix. So `rc < 0` tests for failure. A call on a sky
 * that returns anything but SKY_OK leaves a message for sky_last_error,
 * except where its Errors part says "no message"; a NULL sky is always
 * SKY_ERR_INVALID_ARGUMENT with no message (there is no sky to keep one).
 * Functions without a sky report through their return value, and write
 * into an err buffer where they take one. Nothing prints, asserts or
 * aborts.
 *
 * Threads: a sky belongs to the GL context that was current when
 * sky_create made it (and to the contexts sharing its objects); a context
 * may hold several skies, which share nothing. The library keeps no global
 * state and takes no lock.
 *  - "any thread (pure)": the function takes no sky and makes no GL call;
 *    it reads only its arguments and constant data, and writes only its
 *    outputs: call it from any thread at any time.
 *  - "the sky's thread": call it from the thread where the sky's context is
 *    current, and never while another call on the same sky runs (a sky has
 *    no lock). Where the GL part says "none", the function makes no GL
 *    call and needs no current context: a host may make it on another
 *    thread (sky_update on a simulation thread, say) if it keeps it from
 *    overlapping every other call on that sky.
 *
 * GL: "needs the sky's context current" means the context sky_create ran
 * in, or one sharing its objects, current on the calling thread. The
 * drawing calls (sky_draw, sky_draw_fisheye, sky_capture_environment), the
 * binders (sky_display_bind, sky_aerial_bind) and sky_aerial_froxels check
 * that it is the sky's, without glGetError; the others check only that
 * some context is current, where their Errors part says so. glGetError returns and clears
 * the host's pending errors too: sky_create reads it always, sky_draw only
 * when sky_config.check_gl_errors asks, and the calls that make a texture
 * outside sky_draw (sky_capture_environment into the library's cube map,
 * sky_aerial_bind and sky_aerial_froxels, the first time) read it after
 * creating one, so an error the host left pending then is taken for
 * theirs.
 */
#ifndef SKY_H
#define SKY_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define SKY_VERSION_MAJOR 0
#define SKY_VERSION_MINOR 6
#define SKY_VERSION_PATCH 0

/* Symbols the shared library exports; everything else stays hidden. On
 * Windows a program that links sky.dll (through its import library)
 * defines SKY_DLL before including this header; one that links the static
 * libsky.a, or builds the sources, does not. */
#if defined(_WIN32) && defined(SKY_SHARED_BUILD)
#define SKY_API __declspec(dllexport)
#elif defined(_WIN32) && defined(SKY_DLL)
#define SKY_API __declspec(dllimport)
#elif defined(__GNUC__)
#define SKY_API __attribute__((visibility("default")))
#else
#define SKY_API
#endif

typedef struct sky sky;

/* Results. Negative values are errors (nothing was changed, unless the
 * function's Errors part says otherwise); SKY_CLAMPED means the call
 * succeeded after clamping an out-of-range input, and sky_last_error names
 * which one. */
typedef enum sky_result {
    SKY_OK = 0,
    SKY_CLAMPED = 1,
    SKY_WARN_MIRRORED = 2,    /* sky_draw drew, but the projection's and
                                 horizon_to_world's handedness disagree: the
                                 sky is a mirror image (see Conventions)     */
    SKY_ERR_INVALID_ARGUMENT = -1,
    SKY_ERR_GL = -2,          /* the context cannot do what was asked     */
    SKY_ERR_ASSET = -3,       /* an embedded or override asset is broken  */
    SKY_ERR_OUT_OF_MEMORY = -4,
    SKY_ERR_UNSUPPORTED = -5  /* asked for a feature that is not built    */
} sky_result;

/* Feature mask: what the scene contains. Nothing outside the mask is ever
 * created (no texture, buffer or shader code). 0 means SKY_FEATURES_DEFAULT;
 * an empty sky (atmosphere only) is SKY_FEATURES_NONE. */
typedef enum sky_feature {
    SKY_CLOUDS        = 1u << 0, /* Roden-Parberry cloud layers             */
    SKY_SUN           = 1u << 1, /* limb-darkened sun disc                  */
    SKY_MOON          = 1u << 2, /* Mueller moon: phase, libration, shading  */
    SKY_STARS         = 1u << 3, /* catalogue stars (Mueller sec. 4)         */
    SKY_FLICKER_STARS = 1u << 4, /* Roden-Parberry flicker stars + galaxy   */
    SKY_STARMAP       = 1u << 5, /* Milky Way star map (Mueller sec. 4.4)    */
    SKY_LUNAR_ECLIPSE = 1u << 6, /* lunar eclipses on the moon (needs MOON)  */
    SKY_ECLIPSE       = SKY_LUNAR_ECLIPSE, /* deprecated: SKY_LUNAR_ECLIPSE   */
    SKY_SOLAR_ECLIPSE = 1u << 7, /* the moon hides the sun, dims the sky and
                                    the host's sunlight; nothing while they
                                    are apart. It creates no resource: left
                                    out, the sun's and the sky's shaders
                                    read "no eclipse"                      */
    SKY_PLANETS       = 1u << 8, /* Mercury, Venus, Mars, Jupiter, Saturn as
                                    points like the catalogue stars        */
    SKY_AIRGLOW       = 1u << 9, /* the upper atmosphere's own faint light:
                                    most of a moonless night's sky       */
    SKY_ZODIACAL      = 1u << 10, /* sunlight scattered by interplanetary
                                    dust (Leinert et al. 1998): the false
                                    dawn, the gegenschein                */
    SKY_WEATHER       = 1u << 11, /* the weather's shading in the clouds'
                                    shaders: the deck, the haze, lightning's
                                    flash (sky_set_weather needs it; it
                                    draws through SKY_CLOUDS). Since 0.6.0 */
    SKY_RAINBOW       = 1u << 12, /* rainbows in a weather's rain in sunlight
                                    (Airy's theory for its drops), a fogbow
                                    in fog, a moon's bow; nothing otherwise.
                                    Needs SKY_CLOUDS and SKY_WEATHER (the
                                    rain is the weather's). Since 0.6.0   */
    SKY_HALO          = 1u << 13, /* the 22 and 46 degree halos and the
                                    parhelia around the sun and the moon in
                                    the thin upper layer's ice (cirrus);
                                    nothing without it. Needs SKY_CLOUDS.
                                    Since 0.6.0                          */
    SKY_AURORA        = 1u << 14 /* the aurora's green curtains with red
                                    tops, where the observer is under or
                                    near the auroral oval for cfg.kp
                                    (sky_set_kp); nothing elsewhere, by
                                    day or behind clouds. Since 0.6.0 */
} sky_feature;
/* The empty sky. Bit 31, outside the enum: ISO C wants every enumerator
 * to fit an int. */
#define SKY_FEATURES_NONE 0x80000000u

#define SKY_FEATURES_DEFAULT \
    (SKY_CLOUDS | SKY_SUN | SKY_FLICKER_STARS | SKY_SOLAR_ECLIPSE | SKY_AIRGLOW | SKY_WEATHER)
/* The features this build can render; asking for others is
 * SKY_ERR_UNSUPPORTED from sky_create. */
#define SKY_FEATURES_AVAILABLE \
    (SKY_CLOUDS | SKY_SUN | SKY_MOON | SKY_FLICKER_STARS | SKY_STARS | SKY_STARMAP | SKY_LUNAR_ECLIPSE | \
     SKY_SOLAR_ECLIPSE | SKY_PLANETS | SKY_AIRGLOW | SKY_ZODIACAL | SKY_WEATHER | SKY_RAINBOW | \
     SKY_HALO | SKY_AURORA)

typedef enum sky_atmosphere_path {
    SKY_ATMOSPHERE_DEFAULT = 0, /* = GRADIENT in this build                 */
    SKY_ATMOSPHERE_GRADIENT,    /* Roden-Parberry day gradient texture      */
    SKY_ATMOSPHERE_PREETHAM,    /* Preetham's analytic daylight (turbidity) */
    SKY_ATMOSPHERE_RAYLEIGH,    /* closed-form Rayleigh + Mie single scattering
                                   of sky_config.atmosphere_params         */
    SKY_ATMOSPHERE_HILLAIRE,    /* Hillaire 2020's tables (transmittance,
                                   multiple scattering, sky-view) of
                                   sky_config.atmosphere_params             */
    SKY_ATMOSPHERE_BLEND        /* an analytic path (RAYLEIGH, or PREETHAM:
                                   sky_config.blend_partner) and HILLAIRE
                                   mixed by a weight (sky_config.blend_manual,
                                   blend_weight)                            */
} sky_atmosphere_path;

typedef enum sky_gl_profile {
    SKY_GL_AUTO = 0,   /* CORE33 when the context offers it, else COMPAT20;
                          ES20 on an OpenGL ES context                      */
    SKY_GL_CORE33,     /* OpenGL 3.3 core, GLSL 330                         */
    SKY_GL_COMPAT20,   /* OpenGL 2.0, GLSL 110, RGBA8 power-of-two only     */
    SKY_GL_ES20        /* OpenGL ES 2.0 / WebGL 1, GLSL ES 1.00: COMPAT20's
                          resources on an ES 2.0 (or later) context. Needs 4
                          texture units and nothing else; takes extensions
                          and highp when offered. Without highp in the
                          fragment stage HDR output loses the night, and HDR
                          stops at 65504 kcd/m^2: docs/guide.md, ES 2.0    */
} sky_gl_profile;

/* How LDR output turns the sky's light into 8-bit colour (HDR output is
 * linear and untouched by it). */
typedef enum sky_tone_map {
    SKY_TONE_MAP_HUE = 0, /* the default: a filmic curve on each colour's
                             luminance, the colour scaled with it (a soft
                             shoulder keeps its largest channel below
                             white), so hue and saturation survive (a
                             sunset stays orange, noon stays blue); only
                             the sun and its glare, far above white, turn
                             white                                        */
    SKY_TONE_MAP_FILMIC,  /* Hejl and Burgess-Dawson's curve on each channel
                             apart: contrasty, and bright colours drift
                             toward white and yellow (libsky before 2026-11) */
    SKY_TONE_MAP_NEUTRAL  /* Khronos PBR Neutral: linear to 0.76, then a soft
                             shoulder with slight desaturation; flatter   */
} sky_tone_map;

/* Where the sky is drawn in the host's frame (Conventions). */
typedef enum sky_depth {
    SKY_DEPTH_NONE = 0,    /* first, right after glClear: it neither tests
                              nor writes depth and covers every pixel     */
    SKY_DEPTH_FAR_ONE,     /* after the opaque scene, on the far plane at
                              depth 1 (glClearDepth(1), LESS or LEQUAL): the
                              depth test keeps it behind the scene, whose
                              pixels then cost it little; no depth write   */
    SKY_DEPTH_FAR_ZERO,    /* the same for reversed-Z, far at depth 0
                              (glClearDepth(0), GREATER) with OpenGL's
                              -1..1 clip range                             */
    SKY_DEPTH_FAR_ZERO_CLIP01 /* reversed-Z with glClipControl(GL_LOWER_LEFT,
                              GL_ZERO_TO_ONE), far at depth 0              */
} sky_depth;

typedef enum sky_output {
    SKY_OUTPUT_LDR = 0, /* exposure, tone map, sRGB encode and dither built in */
    SKY_OUTPUT_HDR      /* linear RGB, luminance in kcd/m^2 (sRGB primaries), for
                           a float render target and the host's own tone map  */
} sky_output;

/* A planet's atmosphere (Elek 2009; Hillaire 2020 sec. 4): what the
 * physical paths (RAYLEIGH, HILLAIRE, BLEND) and the CPU reference read.
 * Lengths in km, coefficients in 1/km at sea level, given at the three
 * wavelengths the real-time paths use for R, G, B: 680, 550 and 440 nm
 * (the reference interpolates a smooth spectrum through them). Densities
 * fall off exponentially with their scale heights; ozone follows a tent
 * that peaks at ozone_peak_km and reaches zero ozone_half_width_km above
 * and below. All zero = SKY_ATMOSPHERE_PRESET_EARTH. */
typedef struct sky_atmosphere_params {
    float planet_radius_km;         /* ground                                  */
    float top_radius_km;            /* top of the shell; > planet radius       */
    float rayleigh_scattering[3];   /* molecules: they scatter, never absorb   */
    float rayleigh_scale_height_km;
    float mie_scattering[3];        /* aerosols (haze, dust)                   */
    float mie_extinction[3];        /* >= mie_scattering; the rest is absorbed */
    float mie_scale_height_km;
    float mie_g;                    /* Cornette-Shanks asymmetry, -0.999..0.999 */
    float ozone_absorption[3];
    float ozone_peak_km, ozone_half_width_km;
    float ground_albedo[3];         /* Lambertian, 0..1                        */
} sky_atmosphere_params;

/* The Earth presets differ in their aerosol: its optical depth at 550 nm
 * (AOD; real clear skies 0.05-0.2), falling with wavelength as lambda^-1.3
 * (Angstrom), and its turbidity, the ratio of the whole vertical optical
 * depth at 550 nm to the molecules' alone (sky_config.turbidity). */
typedef enum sky_atmosphere_preset {
    SKY_ATMOSPHERE_PRESET_EARTH = 0, /* clear (the default): AOD 0.085, turbidity
                                        1.9; matched to the CIE clear sky, gensky's
                                        clear zenith and the IES illuminances    */
    SKY_ATMOSPHERE_PRESET_HAZY,      /* AOD 0.3 in a 2 km layer (turbidity 4.1)  */
    SKY_ATMOSPHERE_PRESET_MARS,      /* thin CO2 and a tall layer of red dust    */
    SKY_ATMOSPHERE_PRESET_VERY_CLEAN, /* mountains, open ocean: AOD 0.04 (1.4)   */
    SKY_ATMOSPHERE_PRESET_POLLUTED,  /* summer smog: AOD 0.6 of absorbing
                                        particles (turbidity 7.2)               */
    SKY_ATMOSPHERE_PRESET_HILLAIRE_2020  /* Hillaire 2020's published constants
                                        (AOD 0.0053, turbidity 1.05): for comparison
                                        with other implementations of his paper */
} sky_atmosphere_preset;

/* sky_atmosphere_get_preset: fills *out with a preset's description, to
 * pass as sky_config.atmosphere_params as it is or with a field changed.
 * Errors: SKY_ERR_INVALID_ARGUMENT for out NULL or a value that names no
 * preset.
 * Thread safety: any thread (pure).
 * GL: none.
 * Since: 0.2.0 */
SKY_API sky_result sky_atmosphere_get_preset(sky_atmosphere_preset preset, sky_atmosphere_params *out);
/* sky_atmosphere_check: checks a description as sky_create does: every
 * value finite; planet_radius_km 1..1e6; top_radius_km from
 * planet_radius_km + 1 to twice planet_radius_km; each scattering,
 * extinction and absorption coefficient 0..10 per km (more makes the air
 * at sea level opaque within 100 m); mie_extinction >= mie_scattering;
 * |mie_g| <= 0.999; both scale heights and ozone_half_width_km at least
 * 0.01 km; ground_albedo 0..1. An all-zero description fails here
 * (sky_config reads all zero as SKY_ATMOSPHERE_PRESET_EARTH before its
 * check). err (may be NULL; err_len bytes, the NUL included) gets "" on
 * success, else the first bad field and its range.
 * Errors: SKY_ERR_INVALID_ARGUMENT for atm NULL or a value out of range.
 * Thread safety: any thread (pure).
 * GL: none.
 * Since: 0.2.0 */
SKY_API sky_result sky_atmosphere_check(const sky_atmosphere_params *atm, char *err, size_t err_len);

/* HILLAIRE and BLEND: the lookup tables' sizes and sample counts (Hillaire
 * 2020 sec. 5). Zero fields take Hillaire's values; sizes 4..1024, sample
 * counts 1..256. Larger tables and more samples: closer to the reference,
 * slower to build (sky-bench shows both).
 * The transmittance and multiple-scattering tables are built by sky_create.
 * The sky-view table follows the sun's elevation (past 0.05 degree) and the
 * observer's altitude (past 10 m). CORE33 rebuilds it on the GPU in the
 * next sky_draw. COMPAT20 builds it on the CPU, in the calls that recompute
 * the frame (sky_set_params, sky_set_observer, sky_set_exposure_bias,
 * sky_update, sky_set_elapsed):
 *  - at once, in the call that made the change, when it is a jump: the
 *    sun's elevation moved more than 1 degree since the last sky_draw (since
 *    sky_create before the first), or the observer's altitude moved past
 *    10 m. The next frame shows the exact sky for the new sun;
 *  - otherwise (an animated time of day) a slice of at most about 0.4 ms
 *    per call, while the previous table stays on screen; the finished table
 *    replaces it in the call that completes it (about 20 slices with the
 *    default sizes). The sky then lags a moving sun by one to two builds,
 *    and sky_get_lighting's ambient and fog colours follow the table shown.
 *    Once the sun stops, the builds catch up with it (to the 0.05 degree). */
typedef struct sky_lut_settings {
    int transmittance_width, transmittance_height; /* 256 x 64                */
    int transmittance_steps;                       /* 40                      */
    int multiscatter_size;                         /* 32 (square)             */
    int multiscatter_directions;                   /* 64                      */
    int multiscatter_steps;                        /* 20                      */
    int skyview_width, skyview_height;             /* 192 x 108               */
    int skyview_steps;                             /* 30 at most per ray      */
} sky_lut_settings;

/* The host's GL loader: glfwGetProcAddress, OSMesaGetProcAddress, or a
 * wrapper around SDL_GL_GetProcAddress. */
typedef void (*sky_gl_proc)(void);
typedef sky_gl_proc (*sky_get_proc_address_fn)(const char *name);

typedef struct sky_config {
    unsigned features;                 /* sky_feature mask; 0 = default       */
    sky_atmosphere_path atmosphere;
    sky_gl_profile gl_profile;
    sky_get_proc_address_fn get_proc_address; /* required                     */
    sky_output output;
    /* LDR: the dome (atmosphere, galaxy glow, star map and clouds) is
     * evaluated on 1/dome_divisor of the viewport's pixels along each axis,
     * into an image filtered up to the viewport; the sun, the moon and the
     * stars stay at full resolution, hidden by the clouds' alpha from that
     * image. 0 = the default: 3 for a day frame whose clouds show over the
     * gradient sky, 4 for the rest (the per-pixel atmospheres, the night),
     * which keeps a frame within about 2 textured full-screen quads on a
     * software rasteriser (clouds a little softer than at every pixel);
     * 1 = every pixel (the sharpest clouds, about 4 times the quad); 2..8
     * for every frame. Needs framebuffer objects (GL 3.0, or
     * ARB/EXT_framebuffer_object on 2.0); without them, and for HDR output,
     * the dome is drawn at every pixel. The image is one RGBA8 texture,
     * counted in sky_stats (at 1280x720 about 410 KB at 3, 230 KB at 4;
     * the viewport's size while sky_draw_fisheye draws). */
    int dome_divisor;
    /* LDR: the tone map (above); 0 = SKY_TONE_MAP_HUE. */
    sky_tone_map tone_map;
    /* Drawn first (0) or after the opaque scene against its depth buffer
     * in the host's depth convention (above). */
    sky_depth depth;
    /* Non-zero: sky_draw asks GL for errors (glGetError, a pipeline stall on
     * some drivers): one the host left pending before the call is reported
     * as the host's, one of the sky's own as SKY_ERR_GL. Zero (the default):
     * sky_draw calls no glGetError and leaves pending errors to the host;
     * it still detects, without glGetError, that no context is current or
     * that the current one is not the sky's (a context holding no program
     * of the sky's first program's name; one that happens to hold a
     * program of that name, another sky's say, is not noticed). sky_create
     * always drains the errors pending before it starts and checks its
     * own. */
    int check_gl_errors;
    /* Optional directory whose PNG files replace the embedded textures of the
     * same name (clouds.png, flicker.png, galaxy.png, gradient.png,
     * moon.png, starmap.png). A name not there keeps the embedded copy; one
     * that is there but is not a regular file (a directory, a FIFO, a
     * device), a symbolic link to nothing, or a broken PNG makes sky_create
     * fail, naming it. NULL = embedded only. */
    const char *texture_dir;
    /* Non-zero: sky_draw waits for the GPU around each layer so sky_get_stats
     * can report per-layer milliseconds. Costs a pipeline stall; for tools. */
    int profile_layers;
    /* From the horizon frame to the host's world (column-major 3x3, see
     * Conventions at the top): orthonormal, a rotation or, for a left-handed
     * world, a reflection; all zero = identity (right-handed, y up). */
    float horizon_to_world[9];
    /* Mueller's control magnitude m_a for catalogue stars: stars are drawn
     * 2.512^(m_a - 4) times their physical brightness, and those brighter
     * than m_a get a glare. 0 = 4 (physical); else 1..10 (sky_create rejects
     * anything else, NaN included). */
    float star_control_magnitude;
    /* Mueller's artificial moon scale c_d (eq. 1): the disc is drawn c_d
     * times its true size. 0 = 2.5; else 0.5..50 (sky_create rejects
     * anything else). The enlarged disc keeps the moon's surface brightness
     * (as a telephoto view shows it), so in HDR it carries c_d^2 times the
     * moonlight; sky_lighting.moon_color stays the true moon's, which the
     * disc at c_d = 1 sums to. */
    float moon_scale;
    /* Haze, on every path in one unit: turbidity, the ratio of the
     * atmosphere's vertical optical depth at 550 nm to its molecules' alone
     * (Linke; Preetham et al. 1999). 0 = each path's own: PREETHAM 2.5, the
     * physical paths (RAYLEIGH, HILLAIRE, BLEND) their description's
     * aerosol (SKY_ATMOSPHERE_PRESET_EARTH: 1.9). Else 1..64: PREETHAM clamps it
     * into its fitted range, 2..10; the physical paths scale their
     * description's aerosol to an optical depth of (T - 1) times the
     * molecules' (at most 10/km of extinction), keeping its colour,
     * albedo, asymmetry and height. */
    float turbidity;
    /* The atmosphere's composition; all zero = Earth (see above). */
    sky_atmosphere_params atmosphere_params;
    /* HILLAIRE and BLEND: table sizes and samples; all zero = Hillaire's. */
    sky_lut_settings luts;
    /* BLEND: 0 = the weight follows the sun (Hillaire's tables alone with
     * the sun below 15 degrees, half tables and half the analytic RAYLEIGH
     * path above 60); 1 = use blend_weight, 0 (analytic) .. 1 (Hillaire). */
    int blend_manual;
    float blend_weight;
    /* BLEND: the analytic path mixed with Hillaire's tables (weight 0):
     * SKY_ATMOSPHERE_DEFAULT (0) = SKY_ATMOSPHERE_RAYLEIGH, or
     * SKY_ATMOSPHERE_PREETHAM (its turbidity is cfg.turbidity). sky_create
     * rejects any other path. Ignored by the other paths. */
    sky_atmosphere_path blend_partner;
    /* SKY_AIRGLOW: the airglow follows the sun's 11-year cycle, brighter
     * by 1.6 at its maximum. 0 = the date's place in the cycle (minima
     * at 2008.9 and 2019.9, 11 years apart); 1 = solar_activity, 0
     * (minimum) .. 1 (maximum; sky_create rejects anything else). */
    int solar_activity_manual;
    float solar_activity;
    /* Light pollution: the artificial sky glow of a Bortle class, 1 (an
     * excellent dark site) .. 9 (an inner city), fractions allowed; its
     * zenith brightness is the class's published one (docs/guide.md, "The night
     * sky") less the natural sky's, rising toward the horizon. 0 = none;
     * sky_create rejects anything else. */
    float bortle;
    /* LDR: how far the display follows daylight down at the day's end, in
     * stops. The eye adapts fully to daylight as bright as the day's sky
     * with the sun some 20 degrees up (5 kcd/m^2); below that the
     * automatic exposure makes up only part of each further stop the
     * sunlit sky loses (0.7 at first) and falls at most this many stops
     * short of full adaptation, so the evening darkens as a player expects
     * (at -6 degrees the sky shows about a quarter of noon's brightness).
     * The night's own light (the moon, the glows) is adapted to fully: a
     * night is as legible as ever (docs/DUSK.md). 0 = 3; else 0.01..16
     * (sky_create rejects anything else, NaN included); a small value is
     * the old full adaptation, where dusk shows nearly as bright as noon.
     * sky_set_exposure_bias adds on top. */
    float exposure_range;
    /* The seed of every random event (lightning): the same seed, inputs
     * and running time give the same strikes. Any value. Since 0.6.0 */
    unsigned seed;
    /* The clouds' base height in metres at the height slider's middle
     * (0.5): the slider scales it by 4^(height - 0.5), so 0..1 spans a
     * quarter to twice it, as it scales the drawn clouds' size. Where the
     * cloud shadows fall (sky_get_cloud_shadow). 0 = 1500; else 100..20000.
     * Since 0.6.0 */
    float cloud_height_m;
    /* SKY_AURORA: the planetary K index, 0 (quiet) .. 9 (an extreme
     * storm), fractions allowed: the auroral oval's equatorward edge
     * follows NOAA SWPC's table, from 66.5 degrees geomagnetic latitude
     * at 0 to 48.1 at 9 (docs/guide.md, "Aurora"), and the curtains
     * brighten with it. 0 is Kp 0; sky_create rejects anything outside
     * 0..9, NaN included. sky_set_kp changes it later. Since 0.6.0 */
    float kp;
} sky_config;

/* Roden & Parberry's six sliders, each in 0..1 (values outside are clamped,
 * NaN is rejected).
 *   cover   amount of cloud cover (0 = clear)
 *   height  how high the clouds are: scales their texture coordinates, low
 *           clouds look bigger and closer
 *   density dense clouds are smoother and darker
 *   sunset  strength of the red sunset tint on the clouds
 *   speed   wind speed: rate at which the cloud layers drift
 *   time    local solar time of day: 0 = midnight, 0.25 = 6h, 0.5 = noon */
typedef struct sky_params {
    float cover, height, density, sunset, speed, time;
} sky_params;

/* sky_default_params: the sliders sky_create starts with: cover 0.45,
 * height 0.5, density 0.3, sunset 0.1, speed 0.2, time 0.45 (10:48 local
 * solar time).
 * Errors: none.
 * Thread safety: any thread (pure).
 * GL: none.
 * Since: 0.1.0 */
SKY_API sky_params sky_default_params(void);

/* sky_create: makes a sky in the GL context current on the calling thread:
 * checks cfg, loads the GL entry points through cfg->get_proc_address,
 * settles the profile (cfg->gl_profile) and creates the programs, textures
 * and buffers of the features asked for, nothing outside the mask (HILLAIRE
 * and BLEND also build their first two tables: sky_lut_settings). cfg is
 * copied: neither it nor the texture_dir string need outlive the call. The
 * sky starts with sky_default_params, exposure bias 0, running time 0 and
 * the default observer (sky_observer), its frame computed: sky_draw may
 * follow at once.
 * Errors: returns NULL and says why in err (may be NULL; err_len bytes,
 * the NUL included; "" on success), naming the field it refuses: cfg or
 * get_proc_address NULL; a field outside the range its comment gives (NaN
 * included); a blend_partner other than 0, RAYLEIGH or PREETHAM;
 * SKY_FEATURES_NONE with other bits; features outside
 * SKY_FEATURES_AVAILABLE; SKY_LUNAR_ECLIPSE without SKY_MOON; an
 * atmosphere_params that sky_atmosphere_check refuses; a horizon_to_world
 * that is not orthonormal. Then the context: none current, OpenGL below
 * 2.0, an entry point missing, fewer than 4 texture units, a profile it
 * cannot run (CORE33 without 3.3 and GLSL 3.30, COMPAT20 in a core context,
 * ES20 on desktop GL, CORE33 or COMPAT20 on ES), errors that glGetError
 * never clears (a lost context). Then the resources: a file in texture_dir
 * that is not a regular file, or a PNG that does not decode or has the
 * wrong size (the file is named); a shader that does not compile or link
 * (the driver's log); a GL error while creating; out of memory. What was
 * made before the failure is released.
 * Thread safety: the thread where the host's context is current; the sky
 * is the context's from then on.
 * GL: needs a current context. It reads glGetError until it returns
 * GL_NO_ERROR before it starts, so errors the host left pending are
 * cleared. What it binds and sets while creating (buffers, textures and
 * the active unit, the pixel store, the vertex array) is the host's again
 * when it returns, on success or failure.
 * Since: 0.1.0 */
SKY_API sky *sky_create(const sky_config *cfg, char *err, size_t err_len);
/* sky_destroy: deletes the sky's GL objects and frees it. NULL does
 * nothing.
 * Errors: none.
 * Thread safety: the sky's thread.
 * GL: needs the sky's context current (not checked). A texture of the
 * sky's that the host left bound in that context (sky_aerial_bind's
 * table, sky_aerial_froxels's volume, the environment cube map) reverts
 * to 0 as GL does for any deleted texture.
 * Since: 0.1.0 */
SKY_API void sky_destroy(sky *s);

/* sky_last_error: the message of this sky's most recent call that returned
 * anything but SKY_OK and wrote one; "" before any, "sky is NULL" for s
 * NULL. A later SKY_OK leaves it as it was, so read it straight after the
 * result it explains. The string is the sky's: valid until sky_destroy,
 * its text replaced by the next message.
 * Errors: none.
 * Thread safety: the sky's thread.
 * GL: none.
 * Since: 0.1.0 */
SKY_API const char *sky_last_error(const sky *s);
/* sky_version: the library's version as built, (MAJOR << 16) | (MINOR <<
 * 8) | PATCH: compare with the SKY_VERSION_* macros a host was compiled
 * against (a shared library found at run time may be another; its soname
 * keeps incompatible ones apart, Versions above).
 * Errors: none.
 * Thread safety: any thread (pure).
 * GL: none.
 * Since: 0.2.0 */
SKY_API unsigned sky_version(void);

/* sky_set_params: sets the six sliders and recomputes the frame: the sun
 * and moon (when the observer follows the time slider), the atmosphere,
 * the exposure and each layer's state. sky_get_lighting and the queries
 * below read the new state at once; the next sky_draw shows it. HILLAIRE
 * and BLEND in COMPAT20 may build part of the sky-view table on the CPU
 * here (sky_lut_settings).
 * Errors: SKY_ERR_INVALID_ARGUMENT for s NULL (no message), p NULL or a
 * NaN field: nothing changes. SKY_CLAMPED when a field is outside 0..1
 * (infinities included): it is set to the nearest end, and the message
 * names it (the last one, if several).
 * Thread safety: the sky's thread.
 * GL: none.
 * Since: 0.1.0 */
SKY_API sky_result sky_set_params(sky *s, const sky_params *p);
/* sky_get_params: the sliders as set (clamped).
 * Errors: SKY_ERR_INVALID_ARGUMENT for s or p NULL (no message).
 * Thread safety: the sky's thread.
 * GL: none.
 * Since: 0.1.0 */
SKY_API sky_result sky_get_params(const sky *s, sky_params *p);

/* sky_set_exposure_bias: the LDR output's exposure relative to the
 * automatic one, in stops: +1 doubles the light shown, -1 halves it (0 at
 * sky_create). It recomputes the frame as sky_set_params does. HDR output
 * stays the sky's light, but the bias still scales sky_lighting.exposure
 * and sky_display_bind's exposure, and with them the level below which the
 * faint layers are skipped: at -10 a night's stars, planets, star map,
 * airglow and zodiacal light are not drawn in HDR either.
 * Errors: SKY_ERR_INVALID_ARGUMENT for s NULL (no message) or ev NaN:
 * nothing changes. SKY_CLAMPED outside -10..10 (infinities included): set
 * to the nearest end.
 * Thread safety: the sky's thread.
 * GL: none.
 * Since: 0.2.0 */
SKY_API sky_result sky_set_exposure_bias(sky *s, float ev);

/* sky_set_kp: the aurora's Kp index (sky_config.kp) from now on: the
 * oval's place and the curtains' brightness. It recomputes the frame as
 * sky_set_params does. Without SKY_AURORA it is kept and shows nothing.
 * Errors: SKY_ERR_INVALID_ARGUMENT for s NULL (no message) or kp NaN:
 * nothing changes. SKY_CLAMPED outside 0..9 (infinities included): set to
 * the nearest end.
 * Thread safety: the sky's thread.
 * GL: none.
 * Since: 0.6.0 */
SKY_API sky_result sky_set_kp(sky *s, float kp);

/* sky_update: advances the sky's running clocks by dt_seconds (the clouds'
 * drift at the speed slider's rate, the flicker stars' flicker, the stars'
 * and planets' twinkle), then recomputes the frame as sky_set_params does.
 * It does not move the sun or the moon: the time of day is the time
 * slider's, or the observer's instant. The clocks are doubles wrapped to
 * their periods, so a game may run for years without the clouds
 * stuttering. dt_seconds 0 recomputes without advancing.
 * Errors: SKY_ERR_INVALID_ARGUMENT for s NULL (no message), or dt_seconds
 * NaN, infinite or negative: nothing changes.
 * Thread safety: the sky's thread.
 * GL: none.
 * Since: 0.1.0 */
SKY_API sky_result sky_update(sky *s, double dt_seconds);
/* sky_set_elapsed: sets those clocks to an absolute running time: back to
 * zero, then sky_update(s, seconds). Two skies with the same sliders and
 * seconds show the same clouds and stars, whatever ran before; the clouds
 * drift over the whole span at the speed slider's present rate.
 * Errors: SKY_ERR_INVALID_ARGUMENT for s NULL (no message), or seconds NaN,
 * infinite or negative: nothing changes.
 * Thread safety: the sky's thread.
 * GL: none.
 * Since: 0.1.0 */
SKY_API sky_result sky_set_elapsed(sky *s, double seconds);

/* sky_draw: draws the sky's current frame into the current framebuffer
 * and viewport, seen through the host's view and proj (column-major; only
 * the rotation part of view is used: the sky is centred on the viewer;
 * Conventions). Depth is never written, and tested only when
 * sky_config.depth says where the far plane is; polygons are filled
 * whatever glPolygonMode says, and GL_FRAMEBUFFER_SRGB is off for its draws
 * (LDR output is sRGB-encoded by the sky itself: into an sRGB target it
 * lands as the encoded bytes). With LDR output, framebuffer objects and a
 * dome_divisor above 1 it first renders the dome into an image of its own
 * at 1/dome_divisor of the viewport (sky_config.dome_divisor) through a
 * framebuffer object of its own, then draws into the host's.
 * sky_get_stats describes the draw afterwards.
 * Errors: SKY_ERR_INVALID_ARGUMENT for s NULL (no message), view or proj
 * NULL, an element not finite, a view whose rotation part is degenerate,
 * or a singular projection: nothing drawn. SKY_ERR_GL when no context is current
 * or the current one is not the sky's (one holding a program of the name
 * of the sky's first program, another sky's say, passes for it): nothing
 * drawn. With sky_config.check_gl_errors also SKY_ERR_GL for an error the
 * host left pending (read, so cleared, and named as the host's; nothing
 * drawn), or for one the sky's own calls raised (the frame was drawn).
 * SKY_WARN_MIRRORED (a warning): drawn, but the projection's and
 * horizon_to_world's handedness disagree, so the sky is a mirror image.
 * Thread safety: the sky's thread.
 * GL: needs the sky's context current. Every state it changes is put back
 * before it returns: the current program; the active unit and the 2D,
 * cube-map (and CORE33's 2D-array) bindings of units 0..3; the buffer and
 * vertex-array bindings, or without a vertex array of its own the
 * attribute arrays 0..2; the draw and read framebuffers, the viewport,
 * the scissor box and the clear colour; the blend, depth, cull, scissor,
 * stencil, rasterizer-discard, program-point-size and framebuffer-sRGB
 * switches; the blend functions and equations, colour and depth masks,
 * depth function and polygon mode.
 * Since: 0.1.0 */
SKY_API sky_result sky_draw(sky *s, const float view[16], const float proj[16]);
/* sky_draw_fisheye: draws an equidistant all-sky image of the current
 * frame into the viewport: zenith at the centre, horizon on the inscribed
 * circle, north at the top, east on the left (as seen looking up). The
 * viewport is cleared to black first, so outside the circle is black. An
 * image to look at rather than a frame rate: with LDR output its dome is
 * drawn at every pixel (its image the viewport's size) whatever
 * dome_divisor says.
 * Errors: SKY_ERR_INVALID_ARGUMENT for s NULL (no message); SKY_ERR_GL as
 * for sky_draw. It never warns of a mirror image.
 * Thread safety: the sky's thread.
 * GL: as sky_draw.
 * Since: 0.1.0 */
SKY_API sky_result sky_draw_fisheye(sky *s);

/* ---- where and when ----------------------------------------------------------

 * The observer: a UTC instant (as a Julian day; sky_julian_day converts a
 * calendar date) and a place on the WGS84 ellipsoid. Supported: years
 * -1999..3000, latitude -90..90, longitude -180..180 (east positive),
 * altitude -500..100000 m. With time_from_params set, the time slider sets
 * the local apparent solar time on the observer's local date (0 midnight,
 * 0.5 noon, when the sun crosses the meridian); otherwise the instant is
 * used as given and the time slider is ignored.
 *
 * Until sky_set_observer is called, a sky shows the vernal equinox of
 * 2026 (2026-03-20) from latitude 40 N, longitude 0, sea level, with the
 * time slider setting the time of day. */
typedef struct sky_observer {
    double julian_day_utc;
    double latitude_deg, longitude_deg, altitude_m;
    int time_from_params;
} sky_observer;

/* sky_julian_day: the Julian day of a proleptic Gregorian UTC date and
 * time: years within a million of year 0, month 1..12, day 1..31, hour
 * 0..24, minute 0..60, second 0..61 with a fraction. A day, hour or minute
 * past its unit's end runs on into the next (2026-02-31 is 2026-03-03).
 * Errors: NaN for anything outside those ranges (which sky_set_observer
 * refuses); no sky_result.
 * Thread safety: any thread (pure).
 * GL: none.
 * Since: 0.2.0 */
SKY_API double sky_julian_day(int year, int month, int day, int hour, int minute, double second);
/* sky_calendar: the proleptic Gregorian date of a Julian day, with the
 * fraction of the day since 0h UTC. Any output may be NULL.
 * Errors: SKY_ERR_INVALID_ARGUMENT, the outputs set to zero, for a day
 * that is not finite or lies more than a million years from year 0.
 * Thread safety: any thread (pure).
 * GL: none.
 * Since: 0.2.0 (returning void; sky_result since 0.3.0) */
SKY_API sky_result sky_calendar(double julian_day, int *year, int *month, int *day, double *day_fraction);
/* sky_set_observer: sets the instant and place (sky_observer, above) and
 * recomputes the frame as sky_set_params does.
 * Errors: SKY_ERR_INVALID_ARGUMENT for s NULL (no message), obs NULL, or
 * a field outside its range or not finite (the message names it): nothing
 * changes.
 * Thread safety: the sky's thread.
 * GL: none.
 * Since: 0.2.0 */
SKY_API sky_result sky_set_observer(sky *s, const sky_observer *obs);
/* sky_get_observer: the observer as set (the default one before any
 * sky_set_observer).
 * Errors: SKY_ERR_INVALID_ARGUMENT for s or obs NULL (no message).
 * Thread safety: the sky's thread.
 * GL: none.
 * Since: 0.2.0 */
SKY_API sky_result sky_get_observer(const sky *s, sky_observer *obs);

typedef struct sky_body_place {
    double alt_deg;           /* topocentric, refracted (standard atmosphere) */
    double alt_geometric_deg; /* topocentric, without refraction              */
    double az_deg;            /* from north through east                      */
    double ra_deg, dec_deg;   /* geocentric apparent, of date                 */
    double distance_km;
} sky_body_place;

/* The planets, in the order of sky_astronomy's planets[]. */
typedef enum sky_planet {
    SKY_PLANET_MERCURY = 0,
    SKY_PLANET_VENUS,
    SKY_PLANET_MARS,
    SKY_PLANET_JUPITER,
    SKY_PLANET_SATURN,
    SKY_PLANET_COUNT
} sky_planet;
/* sky_planet_name: a planet's name in lower case ("mercury", ...;
 * "unknown" for a value that names none); a static string.
 * Errors: none.
 * Thread safety: any thread (pure).
 * GL: none.
 * Since: 0.4.0 */
SKY_API const char *sky_planet_name(sky_planet planet);

typedef struct sky_planet_place {
    sky_body_place place;          /* distance_km geocentric                    */
    double distance_au;            /* geocentric, where the light left it       */
    double vmag;                   /* V magnitude, Mallama & Hilton 2018, above
                                      the atmosphere                           */
    double illuminated_fraction;   /* of the disc, 0..1                         */
    double phase_angle_deg;        /* sun-planet-observer                       */
    double diameter_arcsec;        /* apparent equatorial diameter              */
} sky_planet_place;

/* The astronomical state of an instant and place (Meeus-class theories;
 * docs/validation.md, "Astronomy", gives the measured accuracy against
 * ERFA and PyEphem). */
typedef struct sky_astronomy {
    double julian_day_ut, delta_t_s, lmst_deg;
    sky_body_place sun, moon;
    double moon_illuminated_fraction;  /* 0..1                                */
    double moon_phase_angle_deg;       /* 0 full .. 180 new                   */
    double moon_bright_limb_deg;       /* position angle from north via east  */
    double moon_libration_lat_deg, moon_libration_lon_deg;
    double moon_axis_angle_deg;        /* position angle of the moon's axis   */
    double moon_parallactic_deg;       /* parallactic angle at the moon       */
    double umbral_magnitude, penumbral_magnitude; /* lunar eclipse, Danjon   */
    /* solar eclipse as the observer sees it: fraction of the sun's disc
     * area covered; magnitude, the fraction of its diameter covered in
     * Meeus's local form (r_sun + r_moon - d) / (2 r_sun), above 1 when
     * total (at mid-totality (1 + k) / 2, k the moon/sun diameter ratio
     * that catalogues quote), 0 without contact; fraction of its
     * limb-darkened light left */
    double solar_obscuration, solar_magnitude, solar_flux_fraction;
    double star_visibility;  /* Mueller sec. 5 star fade: 0 day .. 1 night      */
    double moon_visibility;  /* Mueller sec. 5 moon factor: 0.5 day .. 1.207
                                (0.5 + 1/sqrt 2) with the sun well down       */
    sky_planet_place planets[SKY_PLANET_COUNT]; /* VSOP87D truncated to 2" of
                                the full series, apparent topocentric        */
} sky_astronomy;

/* A catalogue star's place (Hipparcos number; found = 0 if it is not in
 * the built-in catalogue, every star to V 6.5). */
typedef struct sky_star_place {
    int hip, found;
    double alt_deg, alt_geometric_deg, az_deg;
    double vmag, bv;
} sky_star_place;

/* sky_compute_astronomy: the astronomy of an observer, without a sky:
 * *out as sky_get_astronomy gives it (the planets included), and for each
 * of the count Hipparcos numbers in hip its place in stars[i] (found 0 for
 * a number not in the catalogue; not an error). time_of_day is the time
 * slider, used when obs->time_from_params is set (clamped to 0..1
 * silently). hip and stars may be NULL when count is 0. err (may be NULL;
 * err_len bytes, the NUL included) gets "" on success, else why.
 * Errors: SKY_ERR_INVALID_ARGUMENT for obs or out NULL, count negative, hip
 * or stars NULL with count above 0, time_of_day NaN, an observer that
 * sky_set_observer would refuse (the same messages); SKY_ERR_ASSET when
 * the embedded star catalogue does not decode (stars asked for only).
 * Thread safety: any thread (pure).
 * GL: none.
 * Since: 0.2.0 */
SKY_API sky_result sky_compute_astronomy(const sky_observer *obs, float time_of_day, const int *hip, int count,
                                         sky_star_place *stars, sky_astronomy *out, char *err, size_t err_len);
/* sky_get_astronomy: the astronomy of the sky's current frame: its
 * observer at the time slider's instant (time_from_params) or its own, as
 * the last call that recomputed the frame left it. The planets are the
 * frame's with SKY_PLANETS, else computed in this call.
 * Errors: SKY_ERR_INVALID_ARGUMENT for s or out NULL (no message).
 * Thread safety: the sky's thread.
 * GL: none.
 * Since: 0.2.0 */
SKY_API sky_result sky_get_astronomy(const sky *s, sky_astronomy *out);

/* Layers, for per-layer statistics. */
typedef enum sky_layer {
    SKY_LAYER_STARMAP = 0,
    SKY_LAYER_STARS,
    SKY_LAYER_FLICKER,
    SKY_LAYER_MOON,
    SKY_LAYER_ATMOSPHERE,
    SKY_LAYER_SUN,
    SKY_LAYER_CLOUDS,
    SKY_LAYER_PLANETS,
    SKY_LAYER_AIRGLOW,
    SKY_LAYER_ZODIACAL,
    SKY_LAYER_COUNT
} sky_layer;
/* sky_layer_name: a layer's name by its index ("unknown" outside 0 ..
 * sky_layer_count() - 1); a static string.
 * Errors: none.
 * Thread safety: any thread (pure).
 * GL: none.
 * Since: 0.1.0 */
SKY_API const char *sky_layer_name(sky_layer layer); /* "starmap", "stars", ... */

typedef struct sky_layer_stats {
    int enabled;      /* created (in the feature mask)                       */
    int drawn;        /* contributed to the last frame                       */
    int draws;        /* draw calls of its own in the last frame            */
    double ms;        /* GPU time in the last frame (profile_layers only, else
                         -1). Layers evaluated inside another layer's pass
                         report that pass's time in the pass owner only.   */
    size_t bytes;     /* GPU memory of its textures and buffers             */
} sky_layer_stats;

typedef struct sky_stats {
    const char *gl_version;   /* GL_VERSION of the context; valid while the sky lives */
    sky_gl_profile profile;   /* the profile in use (never AUTO)              */
    unsigned features;        /* the feature mask in use                      */
    double frame_ms;          /* CPU wall time of the last sky_draw (with
                                 profile_layers: including GPU completion)   */
    double lut_ms;            /* time spent building lookup tables, last frame */
    size_t gpu_bytes;         /* all textures and buffers                     */
    int textures, programs, buffers;
    int draws_per_frame;
} sky_stats;

/* sky_get_stats: what the sky holds now (profile, features, textures,
 * programs, buffers and their bytes) and what its last draw did (the last
 * sky_draw or sky_draw_fisheye, or the last face sky_capture_environment
 * drew: draws, times); each layer's, sky_get_layer_stats.
 * Errors: SKY_ERR_INVALID_ARGUMENT for s or out NULL (no message).
 * Thread safety: the sky's thread.
 * GL: none (gl_version was read by sky_create).
 * Since: 0.1.0 */
SKY_API sky_result sky_get_stats(const sky *s, sky_stats *out);
/* sky_layer_count, sky_get_layer_stats: the layers by index, so that
 * adding one changes no public struct: how many this build has
 * (SKY_LAYER_COUNT or more: a layer added after 0.5 has an index but no
 * sky_layer constant; sky_layer_name names each), and one's statistics
 * for the last frame (the draw sky_get_stats describes).
 * Errors: sky_layer_count none; sky_get_layer_stats
 * SKY_ERR_INVALID_ARGUMENT (no message) for a NULL sky or output or an
 * index outside 0 .. sky_layer_count() - 1.
 * Thread safety: sky_layer_count any thread (pure); sky_get_layer_stats
 * the sky's thread.
 * GL: none.
 * Since: 0.5.0 (both) */
SKY_API int sky_layer_count(void);
SKY_API sky_result sky_get_layer_stats(const sky *s, int layer, sky_layer_stats *out);
/* sky_layer_index: the index of the layer named name (sky_layer_name's
 * names; a layer added after 0.5 has no sky_layer constant and is found
 * this way).
 * Errors: -1 for name NULL or a name no layer of this build has.
 * Thread safety: any thread (pure).
 * GL: none.
 * Since: 0.5.0 */
SKY_API int sky_layer_index(const char *name);

/* What a game needs to light its scene, for the current state. Directions
 * are unit vectors in the world frame (horizon_to_world applied);
 * colours are linear RGB, sRGB primaries. */
typedef struct sky_lighting {
    float sun_direction[3];
    float sun_color[3];        /* illuminance on a surface facing the sun, klx
                                  per channel, after atmospheric extinction   */
    float sun_altitude_deg;    /* apparent (refracted) altitude of its centre  */
    float moon_direction[3];
    float moon_color[3];       /* moonlight on a surface facing the moon, klx
                                  (0 when the scene has no moon or it is down):
                                  the full moon's -12.73 mag at its mean
                                  distance, 1 / r^2, the published phase law,
                                  the same extinction as the drawn disc, which
                                  sums to it in HDR at moon_scale 1 */
    float ambient_color[3];    /* sky irradiance on an upward surface, klx     */
    float fog_color[3];        /* horizon sky luminance, kcd/m^2               */
    float daylight;            /* 0 (night) .. 1 (full day): Roden-Parberry's
                                  amount of sunlight                          */
    float exposure;            /* the sky's LDR exposure, 1/(kcd/m^2): a host
                                  that lights its scene with the values above
                                  (luminance = albedo * illuminance / pi) and
                                  multiplies by this lands in the sky's range */
    float flash_color[3];      /* lightning's light on a surface facing the
                                  brightest flash now, klx (0 between flashes;
                                  sky_get_lightning lists the strikes); for an
                                  eye adapted to the night held to what shows
                                  a white surface facing it as one display
                                  white (the lit cloud shows at most two)    */
    float flash_direction[3];  /* toward it, unit (world frame)               */
    float fog_density;         /* per metre, for the host's own fog toward
                                  fog_color: Koschmieder's 3.912 / the
                                  weather's visibility (the clear state's
                                  60 km without a weather). Since 0.6.0      */
} sky_lighting;

/* sky_get_lighting: what a game needs to light its scene (sky_lighting,
 * above) for the sky's current frame, as sky_create or the last call that
 * recomputed it left it (sky_set_params, sky_set_observer,
 * sky_set_exposure_bias, sky_update, sky_set_elapsed). The moon's fields
 * are zero without SKY_MOON.
 * Errors: SKY_ERR_INVALID_ARGUMENT for s or out NULL (no message).
 * Thread safety: the sky's thread.
 * GL: none.
 * Since: 0.1.0 */
SKY_API sky_result sky_get_lighting(const sky *s, sky_lighting *out);

/* ---- Weather ------------------------------------------------------------------------
 * The state of the whole sky, which the sky moves toward smoothly on its
 * own clock (the running time sky_update accumulates and sky_set_elapsed
 * sets: a frame at time T is the same however the sky was stepped to T).
 * Once sky_set_weather has been called the weather owns the clouds' cover
 * and density (a host that wants its own cover sets it in the weather it
 * passes); sky_set_params keeps the time, height, sunset and speed
 * sliders. Before the first call the sky has no weather: the sliders
 * alone, as in 0.5. docs/guide.md, "Weather", gives each state's numbers. */
typedef enum sky_weather_state {
    SKY_WEATHER_CLEAR = 0,
    SKY_WEATHER_FAIR,     /* fair-weather cumulus, the sun out             */
    SKY_WEATHER_CIRRUS,   /* thin high ice cloud, little else              */
    SKY_WEATHER_CLOUDY,
    SKY_WEATHER_OVERCAST, /* a deck without gaps                           */
    SKY_WEATHER_RAIN,
    SKY_WEATHER_SHOWERS,  /* rain with the sun out between the clouds     */
    SKY_WEATHER_STORM,
    SKY_WEATHER_FOG,
    SKY_WEATHER_SNOW,
    SKY_WEATHER_COUNT
} sky_weather_state;

typedef enum sky_precipitation {
    SKY_PRECIPITATION_NONE = 0,
    SKY_PRECIPITATION_RAIN,
    SKY_PRECIPITATION_SNOW
} sky_precipitation;

/* One weather: every number a state is made of, each with its range
 * (sky_set_weather clamps what lies outside and refuses NaN). */
typedef struct sky_weather {
    float cover;                /* 0..1: the cloud layers' cover (the slider's
                                   meaning)                                   */
    float density;              /* 0..1: their density (the slider's meaning) */
    float upper;                /* 0..1: the thin high ice layer; 0.35 x cover
                                   is what the sliders alone draw            */
    float visibility_km;        /* 0.05..300: the meteorological range        */
    float precipitation;        /* 0..1: none .. the heaviest                 */
    sky_precipitation precipitation_kind;
    float drop_size_mm;         /* 0..10: rain's drops, snow's flakes         */
    float lightning_per_minute; /* 0..60                                      */
    float wind_from_deg;        /* where the wind comes from, clockwise from
                                   north (any value; reported in 0..360)      */
    float wind_speed_ms;        /* 0..60 m/s at the clouds' height: the drift
                                   (at 5 m/s the sliders' own drift; the speed
                                   slider scales it as before)               */
    float light_through;        /* 0..1: the fraction of the light above it
                                   that the cloud deck lets through where it
                                   covers the sky (1: the sliders' clouds)    */
} sky_weather;

/* sky_weather_preset: a named state's numbers into out, the wind from the
 * west (270 degrees), for a host to pass as they are or change.
 * Errors: SKY_ERR_INVALID_ARGUMENT for out NULL or state out of range.
 * Thread safety: any thread (pure).
 * GL: none.
 * Since: 0.6.0 */
SKY_API sky_result sky_weather_preset(sky_weather_state state, sky_weather *out);
/* sky_weather_name: "clear", "fair", "cirrus", "cloudy", "overcast", "rain",
 * "showers", "storm", "fog", "snow"; NULL out of range.
 * Since: 0.6.0 */
SKY_API const char *sky_weather_name(sky_weather_state state);
/* sky_weather_from_name: the state of a name above, or -1.
 * Since: 0.6.0 */
SKY_API int sky_weather_from_name(const char *name);

/* sky_set_weather: moves the sky from its present weather (the sliders'
 * clouds the first time) to target over seconds of its running clock,
 * starting now; every number eases in and out (a smoothstep), the wind
 * turning through the shorter way. 0 seconds: at once. A call during a
 * transition starts the next from where it stands. Then recomputes the
 * frame as sky_set_params does. What the sky does with it: cover and
 * density as the sliders' (the layers thicken), the drift along the wind,
 * the thin upper layer, and where the deck covers the sky the clouds' light
 * and sky_get_lighting's beam fall with light_through while its ambient and
 * fog colours grey. The exposure stays the clear sky's, so a storm shows
 * darker than the day around it.
 * Errors: SKY_ERR_INVALID_ARGUMENT for s NULL (no message), target NULL, a
 * field NaN, precipitation_kind unknown, or seconds NaN, infinite or
 * negative: nothing changes. SKY_ERR_UNSUPPORTED for a sky created
 * without SKY_WEATHER (its shaders lack the weather's shading): nothing
 * changes. SKY_CLAMPED: a field outside its range (the message names it)
 * was set to the nearest end.
 * Thread safety: the sky's thread.
 * GL: none.
 * Since: 0.6.0 */
SKY_API sky_result sky_set_weather(sky *s, const sky_weather *target, double seconds);
/* sky_get_weather: the weather at the sky's running time (a transition's
 * numbers part way); before any sky_set_weather, the sliders' cover and
 * density in the clear state. *moving (may be NULL): 1 during a
 * transition.
 * Errors: SKY_ERR_INVALID_ARGUMENT for s or out NULL (no message).
 * Thread safety: the sky's thread.
 * GL: none.
 * Since: 0.6.0 */
SKY_API sky_result sky_get_weather(const sky *s, sky_weather *out, int *moving);

/* One lightning strike (sky_get_lightning). The thunder reaches the
 * observer distance_m / 343 seconds after time. */
typedef struct sky_lightning_strike {
    double time;        /* on the running clock, seconds                      */
    float azimuth_deg;  /* from north through east, the horizon frame          */
    float altitude_deg; /* of the flash's centre in the cloud                  */
    float distance_m;   /* 500 .. 15 000                                       */
    int strokes;        /* return strokes: the flash flickers that many times  */
} sky_lightning_strike;

/* sky_get_lightning: the strikes from running time t0 (inclusive) to t1
 * (exclusive), in time order, at the weather's lightning_per_minute (a
 * Poisson process drawn from cfg.seed and the clock alone: the same for
 * one seed however the sky was stepped, different for another). The first
 * max go into out (out may be NULL when max is 0); *count (may be NULL)
 * gets them all. A game schedules its thunder from them, ahead if it asks
 * for a window in the future: the strikes follow the weather as it stands,
 * transitions included. None before any sky_set_weather.
 * Errors: SKY_ERR_INVALID_ARGUMENT for s NULL (no message), t0 or t1 not
 * finite, t0 negative, t1 < t0, a window over a day (86 400 s), max
 * negative or out NULL with max above 0.
 * Thread safety: the sky's thread.
 * GL: none.
 * Since: 0.6.0 */
SKY_API sky_result sky_get_lightning(sky *s, double t0, double t1, sky_lightning_strike *out, int max, int *count);

/* ---- Cloud shadows for the host's ground ---------------------------------------------
 * Where the drawn clouds (the first layer, the second's noise, the thin
 * upper layer, as the dome draws them, as a flat layer at the clouds'
 * height) stand between the sun and a point on the ground, that point gets
 * less of the sun's beam: the map gives the fraction of sky_lighting's
 * sun_color that reaches it, 1 in full sun. sun_color is the beam where
 * no cloud of the layers stands in its way (a weather's deck, which covers
 * everything alike, is in sun_color itself); the map follows the layers'
 * cover (nothing shadowed at cover 0) and drifts with the drawn clouds.
 * The sky is at infinity: the camera's own movement does not move the
 * drawn clouds, and the map is centred on the observer's place. */
typedef struct sky_cloud_shadow {
    unsigned texture;     /* GL_TEXTURE_2D, size x size RGBA8, the fraction
                             in every channel (255 = full sun), linear,
                             clamped at its edges; the sky's: valid until
                             the next call that recomputes the frame    */
    int size;             /* its side in texels                            */
    float height_m;       /* the clouds' base height (cfg.cloud_height_m and
                             the height slider)                          */
    float extent_m;       /* the square's side, metres, centred on the
                             observer                                    */
    float matrix[16];     /* column-major: a position relative to the
                             observer in the host's units and world frame
                             (horizon_to_world) -> (s, t, 0, 1) on the map */
    float mean;           /* the map's mean fraction: what the shadows
                             average to far away, where sky_cloud_shadow_glsl
                             fades to it (the last sixth of the way to the
                             map's edge, and beyond) rather than stretch the
                             edge's texels to the horizon              */
} sky_cloud_shadow;

/* sky_cloud_shadow_image: the map as 8-bit pixels on the CPU, without
 * GL: w x h bytes, rows from north to south, columns from west to east,
 * over extent_m along the longer side, centred on the observer; 255 = full
 * sun. For a host that lights its ground on the CPU, or a picture
 * (sky-render --out-shadow).
 * Errors: SKY_ERR_INVALID_ARGUMENT for s NULL (no message), out NULL, w or
 * h outside 1..4096, extent_m not in 10..1e6.
 * Thread safety: the sky's thread.
 * GL: none.
 * Since: 0.6.0 */
SKY_API sky_result sky_cloud_shadow_image(sky *s, float extent_m, int w, int h, unsigned char *out);
/* sky_get_cloud_shadow: the map as a texture of the sky's (64 x 64) over
 * extent_m around the observer, made or updated now, and the matrix from
 * the host's positions, given metres_per_unit (the host's unit in
 * metres). Call it once a frame, after sky_update: the cost is spread, a
 * quarter of the rows refreshed each call (the clouds drift a few metres a
 * frame against a texel's 150 m at the default extent), all of them when
 * the sun, the sliders, the weather's deck or the extent changed.
 * Errors: SKY_ERR_INVALID_ARGUMENT for s NULL (no message), out NULL,
 * metres_per_unit not in 1e-6..1e6, extent_m not in 10..1e6. SKY_ERR_GL
 * for a context that is not the sky's, or a texture that cannot be made.
 * Thread safety: the sky's thread.
 * GL: the sky's context current. The active texture unit, the unit's 2D
 * texture and the unpack state are the host's again afterwards.
 * Since: 0.6.0 */
SKY_API sky_result sky_get_cloud_shadow(sky *s, float metres_per_unit, float extent_m, sky_cloud_shadow *out);
/* sky_cloud_shadow_glsl: the host's GLSL for the map (GLSL 1.10 .. 3.30,
 * ES 1.00), after the #version line:
 *   float sun = sky_cloud_shadow(position_relative_to_observer);
 * sky_cloud_shadow_bind sets what it reads. "" if this build lacks it.
 * Near the map's edge and beyond it, the map's mean.
 * Since: 0.6.0 */
SKY_API const char *sky_cloud_shadow_glsl(void);
/* sky_cloud_shadow_bind: binds the map of the last sky_get_cloud_shadow
 * (made now with 1 metre per unit over 10 km if there was none; it
 * refreshes nothing, so call sky_get_cloud_shadow each frame) on
 * texture_unit and sets the snippet's uniforms in program (not made
 * current: the host's program comes back).
 * Errors: as sky_aerial_bind's: SKY_ERR_INVALID_ARGUMENT for s NULL (no
 * message), program 0 or not a program, a texture unit out of range;
 * SKY_ERR_GL for a context that is not the sky's.
 * Thread safety: the sky's thread.
 * GL: the sky's context current; the map stays bound on texture_unit.
 * Since: 0.6.0 */
SKY_API sky_result sky_cloud_shadow_bind(sky *s, unsigned program, int texture_unit);

/* sky_capture_environment: the sky as sky_draw draws it (every layer,
 * clouds included), seen from the observer in the six directions of a
 * cube map in the world frame (horizon_to_world applied; GL's face order
 * +X, -X, +Y, -Y, +Z, -Z and its face orientation, so that a samplerCube
 * looked up with a world direction finds the sky there), for reflections
 * and image-based lighting.
 *   cube_texture  0: the library's own (sky_environment_texture; made or
 *                 remade at face_size), else the host's GL_TEXTURE_CUBE_MAP
 *                 whose level 0 is face_size square on every face captured,
 *                 in a format the output fits: RGBA8 for LDR, a float
 *                 format for HDR (the library's own is RGBA32F: the sun's
 *                 disc is far beyond a half float's range)
 *   face_size     a power of two, 4..2048, at most the context's limit
 *   face          0..5, one face (to spread the cost over frames), or
 *                 SKY_CAPTURE_ALL_FACES
 *   flags         SKY_CAPTURE_SUN_DISC to keep the sun's disc (its light is
 *                 sky_get_lighting's beam; left out by default)
 * Each face is the picture sky_draw draws with that face's camera
 * (sky_capture_face_matrices) at dome_divisor 1: the faces are small, and
 * a reduced image's steps would show at their edges. sky_get_stats then
 * describes the last face drawn.
 * It renders through a framebuffer object of its own. A COMPAT20 context
 * without framebuffer objects has no such object: there each face is drawn
 * into the host's current draw buffer, face_size square at the lower-left
 * corner of its viewport, and copied from the read buffer into the cube map
 * (glCopyTexSubImage2D; the read buffer must be the draw buffer, as
 * GL_BACK is for both by default). Call it there where those pixels are
 * the host's to lose: before it draws its frame (sky_draw and the scene
 * then cover them) or on a frame it clears; sky_capture_overwrote says
 * which they were. HDR output in COMPAT20 (and ES20) is captured into the
 * host's float cube map only (the library's textures there are 8-bit, and
 * the layers blend in linear light, which no 8-bit encoding can be blended
 * in): through a framebuffer object where the context renders into float
 * textures, else copied from a float draw buffer.
 * Errors: SKY_ERR_INVALID_ARGUMENT for s NULL (no message), a face_size
 * that is not a power of two in 4..2048 or is over the context's cube-map
 * limit (or, without framebuffer objects, does not fit the viewport), a
 * face other than 0..5 or SKY_CAPTURE_ALL_FACES, an unknown flag, or a
 * host texture that is not a cube map of that size (not checked on ES 2.0,
 * which cannot ask: there it must be face_size). SKY_ERR_UNSUPPORTED for
 * HDR output outside CORE33 into the library's own cube map. SKY_ERR_GL
 * when no context is current, the current one is not the sky's, the
 * library's cube map cannot be made (a GL error the host left pending is
 * taken for this) or its framebuffer object cannot, or a face cannot be
 * rendered into (its format?): the faces before that one were drawn.
 * Thread safety: the sky's thread.
 * GL: needs the sky's context current. The host's framebuffer bindings,
 * viewport and every state sky_draw puts back come back; without
 * framebuffer objects the pixels of the host's draw buffer it drew into
 * are left as drawn (sky_capture_overwrote).
 * Since: 0.4.0 */
#define SKY_CAPTURE_ALL_FACES (-1)
#define SKY_CAPTURE_SUN_DISC 1u
SKY_API sky_result sky_capture_environment(sky *s, unsigned cube_texture, int face_size, int face, unsigned flags);
/* sky_capture_face_matrices: the view and projection
 * sky_capture_environment draws face 0..5 with (world frame,
 * right-handed, 90 degrees square): sky_draw with them at a square
 * viewport draws that face's pixels.
 * Errors: SKY_ERR_INVALID_ARGUMENT for face outside 0..5, or view or proj
 * NULL.
 * Thread safety: any thread (pure).
 * GL: none.
 * Since: 0.4.0 */
SKY_API sky_result sky_capture_face_matrices(int face, float view[16], float proj[16]);
/* sky_capture_overwrote: the pixels of the host's draw buffer that the
 * last sky_capture_environment drew into (a context without framebuffer
 * objects): x, y, width, height in rect (may be NULL), returns 1; 0 (and
 * zeros) when it drew into a framebuffer object of its own, has not run,
 * or s is NULL.
 * Errors: none.
 * Thread safety: the sky's thread.
 * GL: none.
 * Since: 0.4.0 */
SKY_API int sky_capture_overwrote(const sky *s, int rect[4]);
/* sky_environment_texture: the library's own cube map: 0 before the first
 * capture into it (and for s NULL). A capture at another face_size makes
 * a new one, whose name may differ; it lives until sky_destroy.
 * Errors: none.
 * Thread safety: the sky's thread.
 * GL: none.
 * Since: 0.4.0 */
SKY_API unsigned sky_environment_texture(const sky *s);

/* The sky as a light for a scene's ambient: the radiance that reaches the
 * observer from every direction, as real spherical harmonics of degree
 * 0..2 (9 coefficients per channel; Ramamoorthi & Hanrahan 2001), linear
 * RGB in kcd/m^2, in the world frame (horizon_to_world applied). It is
 * what the atmosphere draws around the observer: the sky with its night
 * floor (moonlit when the moon is up) above the horizon, the ground lit
 * by sun, moon and sky below it, under the clouds (with SKY_CLOUDS and
 * cover above 0): their mean opacity and colour over the drifting texture
 * (the pattern overhead at one moment is not followed: the ambient would
 * flicker as it drifts), lit and tinted as they are drawn. The sun's and
 * the moon's discs are left out and given apart as beams (as
 * sky_get_lighting gives them, not dimmed by the clouds); the catalogue
 * stars and the star map are not in it.
 * A shader that lights with the 9 of degree <= 2 (the common form) is
 * within about 3 % of the true irradiance on surfaces facing the sky and
 * up to 15 % off on surfaces facing a dark ground under a bright sunset
 * sky (the truncation); sky_irradiance_sh_eval adds degree 4 and the
 * horizon's zonal degrees 6 and 8 and is within 2 % (make test measures
 * both against renders).
 * The basis, for a unit world direction (x, y, z):
 *   [0] 0.282095            [1] 0.488603 y     [2] 0.488603 z
 *   [3] 0.488603 x          [4] 1.092548 x y   [5] 1.092548 y z
 *   [6] 0.315392 (3 z^2 - 1) [7] 1.092548 x z  [8] 0.546274 (x^2 - y^2) */
typedef struct sky_irradiance_sh {
    float radiance[9][3];      /* coefficient k, channel: kcd/m^2             */
    float radiance_l4[9][3];   /* degree 4, which sky_irradiance_sh_eval adds
                                  (A_4 = -pi/24; degree 3 lights nothing):
                                  [0] 2.503343 x y (x^2 - y^2)
                                  [1] 1.770131 y z (3 x^2 - y^2)
                                  [2] 0.946175 x y (7 z^2 - 1)
                                  [3] 0.669047 y z (7 z^2 - 3)
                                  [4] 0.105786 (35 z^4 - 30 z^2 + 3)
                                  [5] 0.669047 x z (7 z^2 - 3)
                                  [6] 0.473087 (x^2 - y^2) (7 z^2 - 1)
                                  [7] 1.770131 x z (x^2 - 3 y^2)
                                  [8] 0.625836 (x^4 - 6 x^2 y^2 + y^4)     */
    float radiance_zonal[2][3];/* degrees 6 and 8 about up alone (the sharp
                                  horizon between sky and ground), which
                                  sky_irradiance_sh_eval also adds:
                                  [0] 1.017107 P6(t), [1] 1.163106 P8(t),
                                  t = up . direction, P Legendre's          */
    float up[3];               /* the horizon's up in the world frame       */
    float sun_direction[3];    /* world frame, unit (sky_get_lighting's)      */
    float sun_color[3];        /* illuminance facing the sun, klx             */
    float moon_direction[3];
    float moon_color[3];       /* 0 when the scene has no moon or it is down  */
} sky_irradiance_sh;

/* sky_get_irradiance_sh: fills *out (above) for the sky's current frame.
 * The coefficients are projected from the atmosphere's CPU twin over 256
 * directions, once per change of the sun, sliders, observer, world frame
 * or tables, and cached in the sky (sky-bench gives the cost); the beams
 * are sky_get_lighting's.
 * Errors: SKY_ERR_INVALID_ARGUMENT for s or out NULL (no message).
 * Thread safety: the sky's thread (it fills the sky's cache).
 * GL: none.
 * Since: 0.4.0 */
SKY_API sky_result sky_get_irradiance_sh(sky *s, sky_irradiance_sh *out);
/* sky_irradiance_sh_eval: the irradiance from the sky alone (beams
 * excluded) on a surface whose unit normal (world frame; any length is
 * normalised) is normal, klx per channel: the sum over the coefficients
 * of A_l radiance Y(normal), A = pi, 2 pi/3, pi/4, -pi/24, pi/64, -pi/128
 * for degrees 0, 1, 2, 4, 6, 8 (Ramamoorthi & Hanrahan 2001 eq. 8); never
 * below 0 (a truncated sum can dip below it facing a dark hemisphere).
 * Errors: SKY_ERR_INVALID_ARGUMENT for sh, normal or irradiance NULL, or
 * a normal not finite or zero (irradiance then set to 0).
 * Thread safety: any thread (pure).
 * GL: none.
 * Since: 0.4.0 */
SKY_API sky_result sky_irradiance_sh_eval(const sky_irradiance_sh *sh, const float normal[3], float irradiance[3]);

/* Aerial perspective: what the air between the observer and a point of
 * the scene does to the point's light (Hillaire 2020 sec. 5.4). A host
 * that sees a surface of radiance L (kcd/m^2, as it lights it with the
 * values above) at distance d in direction v draws
 *     L * transmittance + inscatter
 * instead, then applies the sky's exposure: far hills take the colour of
 * the sky behind them, near ones are untouched.
 * One atmosphere for every path: Hillaire's ray march stopped at the point
 * on the description the sky is drawn with (sky_config.atmosphere_params
 * and turbidity), its light scaled so that at the ray's end it is the sky
 * the path draws (so it meets the gradient's or Preetham's horizon too;
 * the night floor is spread along the ray by optical depth). The light
 * of the ground itself is not in it: the host's ground is the point. */
typedef struct sky_aerial {
    float transmittance[3];
    float inscatter[3];
} sky_aerial;
/* sky_get_aerial_perspective: the air's effect (above) on the light of the
 * point at distance_m along direction, for the sky's current frame:
 *   direction   world frame (horizon_to_world applied), any length
 *   distance_m  metres from the observer, 0 or more (INFINITY: the end of
 *               the view ray, where the air's light is the sky drawn
 *               there, the horizon's colour for a level view)
 *   out         transmittance (0..1 per channel) and inscatter (kcd/m^2,
 *               linear RGB); 0 m: 1 and 0
 * The Hillaire and blend paths use their own tables; the others build a
 * transmittance and multiple-scattering table on the CPU at the first
 * call, once. A call marches three rays. (Their costs: sky-bench's
 * aerial perspective table, docs/benchmarks.md.)
 * Errors: SKY_ERR_INVALID_ARGUMENT for s NULL (no message), direction or
 * out NULL, a direction not finite or zero, a distance negative or NaN;
 * SKY_ERR_OUT_OF_MEMORY for the tables. After any error out (where not
 * NULL) is transmittance 1, inscatter 0.
 * Thread safety: the sky's thread (it keeps the tables in the sky).
 * GL: none.
 * Since: 0.4.0 */
SKY_API sky_result sky_get_aerial_perspective(sky *s, const float direction[3], float distance_m, sky_aerial *out);
/* sky_aerial_glsl: the same for the host's own shaders: GLSL source to
 * include after its #version line (GLSL 1.10 to 3.30 and ES 1.00; a
 * NUL-terminated static string, "" in a build without it) that defines
 *     vec3 sky_aerial_apply(vec3 radiance, vec3 direction, float distance_m);
 *     void sky_aerial(vec3 direction, float distance_m,
 *                     out vec3 transmittance, out vec3 inscatter);
 * with the arguments and units of sky_get_aerial_perspective, from a
 * 256 x 64 RGBA8 table (directions about the sun by 16 slices of distance
 * to 50 km and the ray's end; aerial.glsl describes it), and outside GLSL
 * ES sky_aerial_froxel_apply (sky_aerial_froxels). It declares the
 * uniforms sky_aerial_table (sampler2D), sky_aerial_up, sky_aerial_sun
 * and sky_aerial_params, which sky_aerial_bind sets.
 * Errors: none.
 * Thread safety: any thread (pure).
 * GL: none.
 * Since: 0.4.0 */
SKY_API const char *sky_aerial_glsl(void);
/* sky_aerial_bind: makes the table current for the frame (remade on the
 * CPU when the sun, sliders, observer or world frame moved: sky-bench's
 * aerial perspective table gives the cost), binds it to texture_unit and
 * sets the uniforms of program (a linked program that includes
 * sky_aerial_glsl; uniforms it optimised away are skipped). Call it after
 * sky_update, before drawing with the program.
 * Errors: SKY_ERR_INVALID_ARGUMENT for s NULL (no message), program 0 or
 * a name that is no program of the current context (glIsProgram; whether
 * it linked is not checked), or a texture_unit below 0 or not below the
 * context's GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS. SKY_ERR_GL when no
 * context is current or the current one is not the sky's, or the table's
 * texture cannot be made (the first call; a GL error the host left pending
 * is taken for this). SKY_ERR_OUT_OF_MEMORY for the table.
 * Thread safety: the sky's thread.
 * GL: needs the sky's context current. The
 * host's current program and active texture unit come back, and what the
 * table's upload binds on unit 0; the table stays bound to GL_TEXTURE_2D
 * of texture_unit, which is the point: the host keeps that unit for it
 * while it draws.
 * Since: 0.4.0 */
SKY_API sky_result sky_aerial_bind(sky *s, unsigned program, int texture_unit);
/* sky_display_glsl: the 8-bit output's display stages for a host that
 * takes the sky's HDR output (or lights its own scene in kcd/m^2) and
 * wants it shown as the sky shows itself: GLSL source to include after the
 * #version line (GLSL 1.10 to 3.30 and ES 1.00 with highp; a
 * NUL-terminated static string, "" in a build without it) that defines
 *     vec3 sky_display(vec3 radiance_kcd);
 * returning display values 0..1: the automatic exposure with its partial
 * adaptation at the day's end and at night (sky_config.exposure_range),
 * the rods' blue shift of night vision (Jensen et al. 2000), and the tone
 * map (the hue map; a #define SKY_TONE_MAP_FILMIC or SKY_TONE_MAP_NEUTRAL
 * before it picks the others). The library's own 8-bit frames are these
 * values plus a dither of one step. It declares the uniforms
 * sky_display_exposure, sky_display_rods and sky_display_cd, which
 * sky_display_bind sets. (docs/DUSK.md)
 * Errors: none.
 * Thread safety: any thread (pure).
 * GL: none.
 * Since: 0.5.0 */
SKY_API const char *sky_display_glsl(void);
/* sky_display_bind: sets those uniforms in program (a linked program that
 * includes sky_display_glsl; uniforms it optimised away are skipped) for
 * the sky's current frame: call it after sky_update, before drawing with
 * the program.
 * Errors: SKY_ERR_INVALID_ARGUMENT for s NULL (no message), program 0 or
 * a name that is no program of the current context (glIsProgram; whether
 * it linked is not checked); SKY_ERR_GL when no context is current or the
 * current one is not the sky's.
 * Thread safety: the sky's thread.
 * GL: needs the sky's context current. The host's current program and
 * active texture unit come back.
 * Since: 0.5.0 */
SKY_API sky_result sky_display_bind(sky *s, unsigned program);
/* sky_aerial_froxels: Hillaire's froxel volume (Hillaire 2020 sec. 5.4;
 * Unreal's aerial perspective table), CORE33 on the hillaire and blend
 * paths: the same air for one camera (view and proj as sky_draw takes
 * them), marched on the GPU into a 32 x 32 x 32 RGBA16F GL_TEXTURE_3D that
 * *texture names (the library's; valid until the next call or
 * sky_destroy): x and y across the viewport, slice k the air between the
 * observer and (k + 1) km along the view (32 km in all): RGB the
 * in-scattered light (kcd/m^2), A the mean transmittance of the three
 * channels. The physical march alone (no path's drawn-sky scale, night
 * floor or eclipse) under a weather's deck and haze, as sky_aerial's. sky_aerial_glsl's sky_aerial_froxel_apply(volume,
 * radiance, screen_uv, distance_m) reads it (the first km from the
 * identity, beyond 32 km the last slice). Rebuild it when the camera turns
 * or the sun moves; sky-bench gives its cost.
 * Errors: SKY_ERR_INVALID_ARGUMENT for s NULL (no message), view, proj or
 * texture NULL, or a camera that is not finite or is degenerate.
 * SKY_ERR_UNSUPPORTED outside CORE33's HILLAIRE and BLEND paths
 * (sky_aerial_bind serves every path and profile). SKY_ERR_GL when no
 * context is current, the current one is not the sky's, or the build fails (the message says why; the
 * volume's texture is made at the first call, and a GL error the host
 * left pending then is taken for the build's). *texture is 0 after any
 * error (where texture is not NULL).
 * Thread safety: the sky's thread.
 * GL: needs the sky's context current. The
 * host's framebuffers, program, viewport, vertex array and texture bindings
 * (unit 0's 3D one included) come back.
 * Since: 0.4.0 */
SKY_API sky_result sky_aerial_froxels(sky *s, const float view[16], const float proj[16], unsigned *texture);

#ifdef __cplusplus
}
#endif
#endif /* SKY_H */
