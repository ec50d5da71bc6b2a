/*
 * PNG decoding for textures (embedded or override), through stb_image kept
 * private to this file: STB_IMAGE_STATIC so a host that links its own copy
 * of stb_image sees no clash, and only the PNG decoder compiled in.
 */
#include "../core.h"

#include <string.h>

#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_NO_STDIO
#define STBI_NO_LINEAR
#define STBI_NO_HDR
#define STBI_MAX_DIMENSIONS 4096 /* refuse absurd headers before allocating */
/* stb declares static helpers this file does not call; the warning about
 * them is reported at the end of the file, so it is silenced file-wide in
 * this file, which holds nothing but the wrappers below. */
#if defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wunused-function"
#endif
#include <stb/stb_image.h>

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

unsigned char *sky_png_decode_rgba(const unsigned char *data, size_t size, int *w, int *h, const char **why)
{
    int comp = 0;
    if (size == 0 || size > (size_t)0x7fffffff) {
        *why = "bad size";
        return NULL;
    }
    if (!png_chunks_fit(data, size)) {
        *why = "a chunk runs past the end of the data";
        return NULL;
    }
    unsigned char *rgba = stbi_load_from_memory(data, (int)size, w, h, &comp, 4);
    if (!rgba) *why = stbi_failure_reason();
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
