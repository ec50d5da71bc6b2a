/*
 * The inside of the sky handle, for sky.c and the white-box tests. No file
 * of the library below sky.c includes it: the rooms see the shared
 * context (core.h) and their own state only (docs/ARCHITECTURE.md).
 */
#ifndef SKY_INTERNAL_H
#define SKY_INTERNAL_H

#include "atmosphere/atmosphere.h"
#include "camera.h"
#include "catalog.h"
#include "core.h"
#include "aerial.h"
#include "irradiance.h"
#include "disc.h"
#include "exposure.h"
#include "layer.h"
#include "observer.h"
#include "solar_eclipse.h"

struct sky {
    sky_core core;                        /* what every room reads          */
    void **layer_state;                   /* each layer's own, by its stats
                                             index (sky_layer_count())       */
    sky_layer_stats *layer_stats;         /* this draw's, by stats index     */
    sky_dome_snippets dome_snippets;      /* of the enabled layers          */
    GLuint vao;                           /* CORE33 only                    */
    char error[256];
    sky_stats stats;
    sky_irradiance_cache irradiance;      /* sky_get_irradiance_sh's          */
    GLuint capture_fbo;                   /* sky_capture_environment's        */
    int capture_overwrote[4];             /* x, y, w, h of the host's draw
                                             buffer its last call drew into
                                             (no FBO), else zero              */
    sky_aerial_state aerial;              /* sky_get_aerial_perspective's and
                                             sky_aerial_bind's                */
    sky_cloud_shadow shadow_last;         /* the last sky_get_cloud_shadow's
                                             (cloud_shadow.c); texture 0: none */
    unsigned char shadow_map[64 * 64];    /* its texture's texels, rows refreshed
                                             a quarter at a time             */
    float shadow_key[8];                  /* what a full refresh follows      */
    int shadow_phase;                     /* the quarter refreshed next       */
};

/* layers.c: the layer table, back to front, and a row's stats index (its
 * class's slot, or for SKY_LAYER_NEXT the next after SKY_LAYER_COUNT in
 * the table's order). */
extern const sky_layer_class *const sky_layer_table[];
extern const int sky_layer_table_size;
int sky_layer_table_index(int row);

/* Runs its body for each layer this sky has (those its features left out
 * have no state), in the table's order, with L its class, index its stats
 * index and state its state; `continue` goes on to the next layer. */
#define FOR_EACH_LAYER(s, L, index, state)                                                           \
    for (int layer_row_ = 0; layer_row_ < sky_layer_table_size; layer_row_++)                      \
        for (const sky_layer_class *L = sky_layer_table[layer_row_]; L; L = NULL)                    \
            for (int index = sky_layer_table_index(layer_row_), layer_once_ = 1; layer_once_;       \
                 layer_once_ = 0)                                                                    \
                for (void *state = (s)->layer_state[index]; state; state = NULL)

/* sky.c: writes the message sky_last_error returns, and returns code. */
sky_result sky_fail(sky *s, sky_result code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
/* sky.c: SKY_OK when a GL context is current and it is the sky's (or
 * shares its objects), found without glGetError; else SKY_ERR_GL with a
 * message that starts with what. */
sky_result sky_own_context_check(sky *s, const char *what);
/* sky.c: draws through the view and projection (NULL: the all-sky
 * fisheye) with the host's state saved and restored around it. */
sky_result sky_draw_view(sky *s, const float *view, const float *proj);
/* config.c: checks cfg against sky.h's ranges, naming the field it
 * refuses, and derives what sky_create keeps: the features (0 meaning the
 * defaults resolved), the atmosphere at cfg's turbidity, and
 * horizon_to_world (the identity for all zero). 0, or -1 with a message. */
int sky_config_check(const sky_config *cfg, unsigned *features, sky_atmosphere_params *atm,
                     float horizon_to_world[9], char *err, size_t err_len);

#endif /* SKY_INTERNAL_H */
