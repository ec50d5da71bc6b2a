/*
 * The command line shared by sky-render, sky-demo and sky-game (the
 * contract is docs/guide.md's sky-render section: exit 0 on success, 2 for a bad
 * argument, named with its range, 1 for a runtime failure): parsing,
 * presets and the camera it describes.
 */
#ifndef SKY_CLI_H
#define SKY_CLI_H

#include "sky.h"

#include <stdio.h>

enum { SKY_CLI_OK = 0, SKY_CLI_RUNTIME = 1, SKY_CLI_USAGE = 2, SKY_CLI_HELP = 3 };

typedef struct sky_cli {
    int width, height;
    sky_params params;
    double seconds;
    double yaw, pitch, fov; /* degrees */
    int fisheye;
    unsigned features;      /* sky_config.features (0 = default)  */
    sky_gl_profile gl;
    sky_atmosphere_path atmosphere;
    float moon_scale;       /* --moon-scale (0 = the library's default)  */
    float bortle;           /* --bortle (0 = no light pollution)         */
    float kp;               /* --kp: the aurora's Kp index (0..9)        */
    int solar_activity_manual; /* --solar-activity given                 */
    float solar_activity;
    float exposure;         /* --exposure: stops on the automatic exposure */
    float exposure_range;   /* --exposure-range (0 = the library's default) */
    float turbidity;        /* --turbidity (0 = the library's default)   */
    int dome_divisor;       /* --dome-divisor (0 = the library's default) */
    sky_tone_map tone_map;  /* --tone-map hue|filmic|neutral              */
    sky_atmosphere_preset planet; /* --planet earth|hazy|mars          */
    sky_lut_settings luts;  /* --luts small|default|large              */
    int blend_manual;       /* --blend W                               */
    float blend_weight;
    sky_atmosphere_path blend_partner; /* --blend-partner rayleigh|preetham  */
    const char *preset;
    int weather, weather_to;  /* --weather, --weather-to: a sky_weather_state,
                                 or -1 for none                             */
    double weather_seconds;   /* --weather-seconds: the transition's length */
    unsigned seed;            /* --seed: sky_config.seed                  */
    const char *out_png, *out_pfm;
    const char *out_shadow;   /* --out-shadow: the cloud shadow map's PNG   */
    double shadow_extent_km;  /* --shadow-extent: its side (default 10)    */
    int frames;
    int stats;
    /* where and when */
    sky_observer observer;   /* default observer unless --date/--lat/... */
    int query;               /* --query: astronomy JSON, no GL           */
    int capture;             /* --capture N: the cube map's face size, 0 off */
    int hip[64];
    int hip_count;
    /* sky-demo only */
    const char *screenshot;
} sky_cli;

/* Parses argv into cli. Returns SKY_CLI_OK, SKY_CLI_HELP (usage printed to
 * out), or SKY_CLI_USAGE with a message naming the argument in err. */
int sky_cli_parse(sky_cli *cli, int argc, char **argv, int is_demo, char *err, size_t err_len);
void sky_cli_usage(FILE *out, const char *prog, int is_demo);

/* Sets what the options say on a new sky: the sliders, the observer, the
 * weather (--weather from time 0, --weather-to over --weather-seconds from
 * time 0), the running time (--seconds) and the exposure bias. Returns the
 * first failure (sky_last_error says why) or SKY_OK. */
sky_result sky_cli_apply(sky *s, const sky_cli *cli);

/* The sky_config the options describe, for the given GL loader. */
sky_config sky_cli_config(const sky_cli *cli, sky_get_proc_address_fn loader);

/* Wall-clock milliseconds, and the median of n samples (sorts v). */
double sky_cli_now_ms(void);
double sky_cli_median(double *v, int n);

/* Column-major view and projection matrices for --yaw/--pitch/--fov. */
void sky_cli_camera(const sky_cli *cli, float view[16], float proj[16]);
/* The same camera from its parts: yaw and pitch in degrees (yaw from
 * north through east), fov vertical in degrees, for a width x height view. */
/* sky-demo's and sky-game's --out FILE.png (the headless image) at
 * argv[*i]: 1 taken (*out set, *i past its value), 0 not --out, -1 a name
 * that does not end in .png (message on stderr, prog named). */
int sky_cli_take_out(int *i, int argc, char **argv, const char *prog, const char **out);
void sky_cli_camera_at(double yaw, double pitch, double fov, int width, int height, float view[16], float proj[16]);

/* Prints the --query JSON object (its fields: docs/guide.md, "Where and when";
 * their meaning: sky_astronomy in sky.h). */
void sky_cli_print_query(FILE *out, const sky_astronomy *a, const sky_star_place *stars, int count);

/* Prints sky_get_stats as a JSON object (sky_stats in sky.h), with every
 * layer of this build by name (sky_layer_count, sky_get_layer_stats),
 * sky_get_lighting's fields, the weather and the lightning strikes from
 * time 0 (or a day before) to seconds, the frame's running time.
 * frame_ms overrides the sky's own figure (sky-render passes a median). */
void sky_cli_print_stats(FILE *out, sky *s, double frame_ms, double seconds);

#endif
