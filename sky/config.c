/*
 * sky_create's check of a sky_config: one table of rules, a row per
 * field (its name, type, accepted range, whether 0 stands for the
 * default, and the field that must be set for the rule to apply), and
 * the few rules between fields after it. Every refusal names the field.
 */
#include "sky_internal.h"

#include <math.h>
#include <string.h>

enum rule_type { RULE_ENUM, RULE_INT, RULE_FLOAT };

typedef struct config_rule {
    const char *field;   /* as sky.h spells it                                  */
    size_t offset;       /* in sky_config                                       */
    enum rule_type type; /* enums are read as int (asserted below)              */
    double lo, hi;       /* accepted                                            */
    int zero_default;    /* 0 is accepted too: the default                      */
    ptrdiff_t when;      /* the int field that must be non-zero for the rule to
                            apply, or -1 for always                              */
    const char *meaning; /* the message's parenthesis                           */
} config_rule;

_Static_assert(sizeof(sky_atmosphere_path) == sizeof(int) && sizeof(sky_gl_profile) == sizeof(int) &&
                   sizeof(sky_output) == sizeof(int) && sizeof(sky_tone_map) == sizeof(int) &&
                   sizeof(sky_depth) == sizeof(int),
               "sky_config's enums are read as int");

#define AT(f) offsetof(sky_config, f)
#define ENUM(f, hi, meaning) {#f, AT(f), RULE_ENUM, 0, hi, 0, -1, meaning}
#define INT(f, lo, hi, zero, meaning) {#f, AT(f), RULE_INT, lo, hi, zero, -1, meaning}
#define FLOAT(f, lo, hi, zero, meaning) {#f, AT(f), RULE_FLOAT, lo, hi, zero, -1, meaning}
#define FLOAT_WHEN(f, lo, hi, when, meaning) {#f, AT(f), RULE_FLOAT, lo, hi, 0, (ptrdiff_t)AT(when), meaning}
#define LUT_SIZE(f) INT(luts.f, 4, 1024, 1, "0 = default, 4..1024")
#define LUT_STEPS(f) INT(luts.f, 1, 256, 1, "0 = default, 1..256")

static const config_rule rules[] = {
    ENUM(atmosphere, SKY_ATMOSPHERE_BLEND, "a sky_atmosphere_path"),
    ENUM(gl_profile, SKY_GL_ES20, "a sky_gl_profile"),
    ENUM(output, SKY_OUTPUT_HDR, "SKY_OUTPUT_LDR or SKY_OUTPUT_HDR"),
    ENUM(tone_map, SKY_TONE_MAP_NEUTRAL, "hue, filmic or neutral"),
    ENUM(depth, SKY_DEPTH_FAR_ZERO_CLIP01, "a sky_depth"),
    INT(dome_divisor, 1, 8, 1, "0 = default, 1..8"),
    LUT_SIZE(transmittance_width),
    LUT_SIZE(transmittance_height),
    LUT_SIZE(multiscatter_size),
    LUT_SIZE(skyview_width),
    LUT_SIZE(skyview_height),
    LUT_STEPS(transmittance_steps),
    LUT_STEPS(multiscatter_directions),
    LUT_STEPS(multiscatter_steps),
    LUT_STEPS(skyview_steps),
    FLOAT_WHEN(blend_weight, 0.0, 1.0, blend_manual, "0..1"),
    FLOAT(turbidity, 1.0, 64.0, 1, "0 = default, or 1..64"),
    FLOAT(moon_scale, 0.5, 50.0, 1, "0 = default, or 0.5..50"),
    FLOAT(exposure_range, 0.01, 16.0, 1, "0 = default, or 0.01..16 stops"),
    FLOAT(cloud_height_m, 100.0, 20000.0, 1, "0 = 1500, or 100..20000 m"),
    FLOAT(star_control_magnitude, 1.0, 10.0, 1, "0 = default, or 1..10"),
    INT(solar_activity_manual, 0, 1, 0, "0 = from the date, or 1"),
    FLOAT_WHEN(solar_activity, 0.0, 1.0, solar_activity_manual, "0 = minimum .. 1 = maximum"),
    FLOAT(bortle, 1.0, 9.0, 1, "0 = no light pollution, or 1..9"),
    FLOAT(kp, 0.0, 9.0, 0, "the Kp index, 0..9"),
};
/* (the table's helpers end with it: in the amalgamation, one translation
 * unit, names this generic would reach every file after this one) */
#undef LUT_STEPS
#undef LUT_SIZE
#undef FLOAT_WHEN
#undef FLOAT
#undef INT
#undef ENUM
#undef AT

/* 0 when the field passes its rule, else -1 with the message. */
static int check_rule(const sky_config *cfg, const config_rule *r, char *err, size_t err_len)
{
    const char *base = (const char *)cfg;
    if (r->when >= 0) {
        int when;
        memcpy(&when, base + r->when, sizeof when);
        if (!when) return 0;
    }
    double v, lo = r->lo, hi = r->hi;
    if (r->type == RULE_FLOAT) {
        float f;
        memcpy(&f, base + r->offset, sizeof f);
        v = f;
        /* the bounds as the field's own type holds them (0.01f < 0.01) */
        lo = (float)lo;
        hi = (float)hi;
    } else {
        int i;
        memcpy(&i, base + r->offset, sizeof i);
        v = i;
    }
    /* NaN fails both comparisons: refused */
    if ((r->zero_default && v == 0.0) || (v >= lo && v <= hi)) return 0;
    if (r->type == RULE_FLOAT)
        sky_format(err, err_len, "sky_create: %s %g is out of range (%s)", r->field, v, r->meaning);
    else
        sky_format(err, err_len, "sky_create: %s %d is out of range (%s)", r->field, (int)v, r->meaning);
    return -1;
}

int sky_config_check(const sky_config *cfg, unsigned *features, sky_atmosphere_params *atm,
                     float horizon_to_world[9], char *err, size_t err_len)
{
    if (!cfg) {
        sky_format(err, err_len, "sky_create: config is NULL (a zeroed sky_config with get_proc_address set is enough)");
        return -1;
    }
    if (!cfg->get_proc_address) {
        sky_format(err, err_len, "sky_create: get_proc_address is NULL; pass the host's GL loader");
        return -1;
    }
    for (size_t i = 0; i < sizeof rules / sizeof rules[0]; i++)
        if (check_rule(cfg, &rules[i], err, err_len)) return -1;
    if (cfg->blend_partner != SKY_ATMOSPHERE_DEFAULT && cfg->blend_partner != SKY_ATMOSPHERE_RAYLEIGH &&
        cfg->blend_partner != SKY_ATMOSPHERE_PREETHAM) {
        sky_format(err, err_len,
                   "sky_create: blend_partner %d is not an analytic path the blend can mix (0 = RAYLEIGH, "
                   "SKY_ATMOSPHERE_RAYLEIGH or SKY_ATMOSPHERE_PREETHAM)",
                   (int)cfg->blend_partner);
        return -1;
    }
    if ((cfg->features & SKY_FEATURES_NONE) && cfg->features != SKY_FEATURES_NONE) {
        sky_format(err, err_len, "sky_create: features 0x%x: SKY_FEATURES_NONE (an empty sky) cannot be combined "
                   "with other features", cfg->features);
        return -1;
    }
    *features = cfg->features == 0 ? SKY_FEATURES_DEFAULT : cfg->features == SKY_FEATURES_NONE ? 0u : cfg->features;
    if (*features & ~(unsigned)SKY_FEATURES_AVAILABLE) {
        sky_format(err, err_len, "sky_create: features 0x%x are not built yet (available: 0x%x)",
                   *features & ~(unsigned)SKY_FEATURES_AVAILABLE, (unsigned)SKY_FEATURES_AVAILABLE);
        return -1;
    }
    if ((*features & SKY_LUNAR_ECLIPSE) && !(*features & SKY_MOON)) {
        sky_format(err, err_len, "sky_create: SKY_LUNAR_ECLIPSE needs SKY_MOON (the eclipse is drawn on the moon)");
        return -1;
    }
    if ((*features & SKY_RAINBOW) && (*features & (SKY_CLOUDS | SKY_WEATHER)) != (SKY_CLOUDS | SKY_WEATHER)) {
        sky_format(err, err_len, "sky_create: SKY_RAINBOW needs SKY_CLOUDS and SKY_WEATHER (the bow is drawn over "
                   "the clouds, in the weather's rain)");
        return -1;
    }
    if ((*features & SKY_HALO) && !(*features & SKY_CLOUDS)) {
        sky_format(err, err_len, "sky_create: SKY_HALO needs SKY_CLOUDS (the halos are drawn over the clouds, in "
                   "their thin upper layer's ice)");
        return -1;
    }
    sky_atmosphere_params described = cfg->atmosphere_params;
    if (sky_atmosphere_is_zero(&described)) sky_atmosphere_get_preset(SKY_ATMOSPHERE_PRESET_EARTH, &described);
    char atm_err[160];
    if (sky_atmosphere_check(&described, atm_err, sizeof atm_err) != SKY_OK) {
        sky_format(err, err_len, "sky_create: %s", atm_err);
        return -1;
    }
    /* the haze knob: the description's aerosol at cfg->turbidity (checked
     * above: 0 or 1..64) */
    sky_atmosphere_with_turbidity(&described, cfg->turbidity, atm);
    if (sky_camera_horizon_to_world(cfg->horizon_to_world, horizon_to_world)) {
        sky_format(err, err_len,
                   "sky_create: horizon_to_world is not orthonormal (its columns must be unit vectors at right "
                   "angles: a rotation, or a reflection for a left-handed world; all zero = identity)");
        return -1;
    }
    return 0;
}
