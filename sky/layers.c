/*
 * The layer table: every layer the sky draws, back to front, one row
 * each, and what is asked of the layers by index (their names, their
 * statistics). Adding a layer is its file and its row here.
 */
#include "sky_internal.h"

#include <string.h>

/* The layers, back to front: the dome (the atmosphere with the night
 * backdrop behind and the clouds in front), the catalogue stars added over
 * it, the moon, the sun. Layers with a dome role live in the dome's
 * program and draw nothing themselves. A layer is its file and its row
 * here; its stats index is its class's slot (the layers of 0.5) or, for
 * SKY_LAYER_NEXT, the next after SKY_LAYER_COUNT in this order. */
extern const sky_layer_class sky_dome_layer, sky_clouds_layer, sky_flicker_layer, sky_starmap_layer,
    sky_airglow_layer, sky_zodiacal_layer, sky_stars_layer, sky_planets_layer, sky_moon_layer, sky_sun_layer,
    sky_rainbow_layer, sky_halo_layer, sky_aurora_layer;
const sky_layer_class *const sky_layer_table[] = {
    &sky_dome_layer, &sky_clouds_layer, &sky_flicker_layer, &sky_starmap_layer,
    &sky_airglow_layer, &sky_zodiacal_layer, &sky_stars_layer, &sky_planets_layer,
    &sky_moon_layer, &sky_sun_layer, &sky_rainbow_layer, &sky_halo_layer, &sky_aurora_layer,
};
const int sky_layer_table_size = (int)(sizeof sky_layer_table / sizeof sky_layer_table[0]);

int sky_layer_table_index(int row)
{
    if (sky_layer_table[row]->slot != SKY_LAYER_NEXT) return (int)sky_layer_table[row]->slot;
    int index = SKY_LAYER_COUNT;
    for (int r = 0; r < row; r++) index += sky_layer_table[r]->slot == SKY_LAYER_NEXT;
    return index;
}

const char *sky_layer_name(sky_layer layer)
{
    for (int row = 0; row < sky_layer_table_size; row++)
        if (sky_layer_table_index(row) == (int)layer) return sky_layer_table[row]->name;
    return "unknown";
}

int sky_layer_index(const char *name)
{
    for (int row = 0; name && row < sky_layer_table_size; row++)
        if (!strcmp(sky_layer_table[row]->name, name)) return sky_layer_table_index(row);
    return -1;
}

int sky_layer_count(void) { return sky_layer_table_size; }

sky_result sky_get_layer_stats(const sky *s, int layer, sky_layer_stats *out)
{
    if (!s || !out || layer < 0 || layer >= sky_layer_table_size) return SKY_ERR_INVALID_ARGUMENT;
    const sky_core *c = &s->core;
    *out = s->layer_stats[layer];
    out->bytes = 0;
    out->enabled = 0;
    for (int i = 0; i < c->texture_count; i++)
        if (c->textures[i].id && (int)c->textures[i].owner == layer) out->bytes += c->textures[i].bytes;
    FOR_EACH_LAYER(s, L, index, state) {
        if (index != layer) continue;
        out->enabled = 1;
        if (L->buffer_bytes) out->bytes += L->buffer_bytes(c, state);
    }
    return SKY_OK;
}

sky_result sky_get_stats(const sky *s, sky_stats *out)
{
    if (!s || !out) return SKY_ERR_INVALID_ARGUMENT;
    const sky_core *c = &s->core;
    *out = s->stats;
    out->gl_version = c->gl_version;
    out->profile = c->profile;
    out->features = c->features;
    out->lut_ms = s->stats.lut_ms;
    out->textures = 0;
    out->gpu_bytes = c->buffer_bytes;
    for (int i = 0; i < c->texture_count; i++)
        if (c->textures[i].id) {
            out->textures++;
            out->gpu_bytes += c->textures[i].bytes;
        }
    out->programs = c->program_count;
    out->buffers = c->buffer_count;
    return SKY_OK;
}
