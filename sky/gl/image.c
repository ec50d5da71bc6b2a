/*
 * PNG decoding for textures (embedded or override), through stb_image kept
 * private to this file: STB_IMAGE_STATIC so a host that links its own copy
 * of stb_image sees no clash, and only the PNG decoder compiled in.
 */
#include "../core.h"

#include <stdlib.h>
#include <string.h>

#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_NO_STDIO
#define STBI_NO_LINEAR
#define STBI_NO_HDR
#define STBI_MAX_DIMENSIONS 4096 /* refuse absurd headers before allocating */
/* Every byte stb hands back is one it wrote or a zero: a truncated or
 * corrupt stream can leave part of a buffer unwritten, which must not
 * reach a texture as whatever the heap held (fuzz_png decodes twice and
 * compares). */
static void *sky_stbi_realloc_sized(void *p, size_t old_size, size_t new_size)
{
    unsigned char *q = realloc(p, new_size);
    if (q && new_size > old_size) memset(q + old_size, 0, new_size - old_size);
    return q;
}
#define STBI_MALLOC(size) calloc(1, (size))
#define STBI_REALLOC(p, size) realloc((p), (size))
#define STBI_REALLOC_SIZED(p, old_size, new_size) sky_stbi_realloc_sized((p), (old_size), (new_size))
#define STBI_FREE(p) free(p)
/* stb defines static functions this file does not call: the warning is
 * silenced for stb's lines alone (push and pop), so that in the
 * amalgamation, one translation unit, it reaches no other file. GCC judges
 * a static function declared and never defined at the end of the
 * translation unit, past the pop, so none may be left: STBI_NO_GIF drops
 * the GIF loader's declaration (STBI_ONLY_PNG leaves out its body), and
 * stb_image 2.27 (Debian 12) declares stbi_set_unpremultiply_on_load_thread
 * but defines it as stbi__unpremultiply_on_load_thread, which the macro
 * renames to match (later versions fixed the name; the macro then names
 * nothing). */
#define STBI_NO_GIF
#define stbi__unpremultiply_on_load_thread stbi_set_unpremultiply_on_load_thread
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#endif
#include <stb/stb_image.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif
#undef stbi__unpremultiply_on_load_thread

int sky_png_info(const unsigned char *data, size_t size, int *w, int *h)
{
    int comp = 0;
    if (size == 0 || size > (size_t)0x7fffffff) return 0;
    return stbi_info_from_memory(data, (int)size, w, h, &comp);
}

/* Every chunk's declared length fits in the bytes that follow it (up to
 * IEND). stb_image sizes its buffer for the compressed data from the
 * lengths before it reads them, so a 26-byte file declaring a 1 GiB IDAT
 * made it allocate 2 GiB (found by the PNG fuzzer): allocations now stay
 * bounded by the input's size. */
static int png_chunks_fit(const unsigned char *data, size_t size)
{
    size_t at = 8; /* the signature */
    while (at + 12 <= size) {
        size_t len = (size_t)data[at] << 24 | (size_t)data[at + 1] << 16 | (size_t)data[at + 2] << 8 | data[at + 3];
        if (len > size - at - 12) return 0;
        if (!memcmp(data + at + 4, "IEND", 4)) return 1;
        at += 12 + len;
    }
    return 0;
}

static size_t be32(const unsigned char *p)
{
    return (size_t)p[0] << 24 | (size_t)p[1] << 16 | (size_t)p[2] << 8 | p[3];
}

unsigned long sky_png_crc32(const unsigned char *p, size_t n)
{
    unsigned long c = 0xffffffffUL;
    for (size_t i = 0; i < n; i++) {
        c ^= p[i];
        for (int k = 0; k < 8; k++) c = (c >> 1) ^ (0xedb88320UL & (0UL - (c & 1UL)));
    }
    return c ^ 0xffffffffUL;
}

/* A paletted image may hold indices past the end of its PLTE (an error in
 * the PNG spec that decoders must survive). stb_image decodes those from
 * the unwritten rest of its palette array on the stack, so such a file
 * gave uninitialised bytes (valgrind, at stbi__parse_png_file). A short
 * palette is legal and common (optimisers trim unused entries), so it is
 * not refused: the file is copied with its PLTE padded to 2^bit-depth
 * entries of black, as libpng does for out-of-range indices. Returns the
 * copy (free it), NULL when the file needs none, and NULL with *bad set
 * when it has more than one PLTE (1: the spec forbids it, and stb would
 * take the last) or the copy cannot be allocated (2). Call after
 * png_chunks_fit. */
static unsigned char *png_pad_palette(const unsigned char *data, size_t size, size_t *padded_size, int *bad)
{
    *bad = 0;
    /* IHDR first, 13 bytes: width, height, bit depth, colour type 3 */
    if (size < 33 || be32(data + 8) != 13 || memcmp(data + 12, "IHDR", 4) || data[25] != 3) return NULL;
    int depth = data[24];
    if (depth != 1 && depth != 2 && depth != 4 && depth != 8) return NULL; /* stb refuses it */
    size_t full = (size_t)1 << depth, plte_at = 0, plte_count = 0;
    for (size_t at = 8; at + 12 <= size; at += 12 + be32(data + at)) {
        if (!memcmp(data + at + 4, "PLTE", 4)) {
            plte_at = at;
            plte_count++;
        }
        if (!memcmp(data + at + 4, "IEND", 4)) break;
    }
    if (plte_count > 1) {
        *bad = 1;
        return NULL;
    }
    size_t len = plte_count ? be32(data + plte_at) : 0;
    if (!plte_count || len % 3 || len / 3 >= full) return NULL; /* none (stb refuses), malformed (stb refuses), full */
    size_t grow = full * 3 - len, body = plte_at + 8 + len; /* the old palette's end */
    unsigned char *out = malloc(size + grow);
    if (!out) {
        *bad = 2; /* decoding the unpadded file is what this is here to avoid */
        return NULL;
    }
    memcpy(out, data, body);
    memset(out + body, 0, grow);
    size_t new_len = full * 3;
    for (int i = 0; i < 4; i++) out[plte_at + (size_t)i] = (unsigned char)(new_len >> (24 - 8 * i));
    unsigned long crc = sky_png_crc32(out + plte_at + 4, 4 + new_len);
    for (int i = 0; i < 4; i++) out[body + grow + (size_t)i] = (unsigned char)(crc >> (24 - 8 * i));
    memcpy(out + body + grow + 4, data + body + 4, size - body - 4); /* after the old CRC */
    *padded_size = size + grow;
    return out;
}

unsigned char *sky_png_decode_rgba(const unsigned char *data, size_t size, int *w, int *h, const char **why)
{
    int comp = 0;
    if (size == 0 || size > (size_t)0x7fffffff - 768) { /* room for a padded palette */
        *why = "bad size";
        return NULL;
    }
    if (!png_chunks_fit(data, size)) {
        *why = "a chunk runs past the end of the data";
        return NULL;
    }
    int bad = 0;
    size_t padded_size = 0;
    unsigned char *padded = png_pad_palette(data, size, &padded_size, &bad);
    if (bad) {
        *why = bad == 1 ? "more than one PLTE chunk" : "out of memory";
        return NULL;
    }
    unsigned char *rgba = padded ? stbi_load_from_memory(padded, (int)padded_size, w, h, &comp, 4)
                                 : stbi_load_from_memory(data, (int)size, w, h, &comp, 4);
    if (!rgba) *why = stbi_failure_reason();
    free(padded);
    return rgba;
}

void sky_png_free(unsigned char *rgba) { stbi_image_free(rgba); }

int sky_image_decode(const unsigned char *data, size_t size, int expect_w, int expect_h, unsigned char **rgba,
                     const char *label, char *err, size_t err_len)
{
    int w = 0, h = 0;
    *rgba = NULL;
    /* the header first: a wrong or absurd size is refused before any
     * pixel is decoded or allocated */
    if (!sky_png_info(data, size, &w, &h)) {
        sky_format(err, err_len, "%s is not a readable PNG", label);
        return -1;
    }
    if (w != expect_w || h != expect_h) {
        sky_format(err, err_len, "%s is %dx%d; expected %dx%d", label, w, h, expect_w, expect_h);
        return -1;
    }
    const char *why = "";
    *rgba = sky_png_decode_rgba(data, size, &w, &h, &why);
    if (!*rgba || w != expect_w || h != expect_h) {
        sky_png_free(*rgba);
        *rgba = NULL;
        sky_format(err, err_len, "%s: the PNG data is corrupt or truncated (%s)", label, why);
        return -1;
    }
    return 0;
}
