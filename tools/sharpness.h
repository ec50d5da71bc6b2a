/*
 * Sharpness: what the 8-bit frame keeps of the every-pixel frame's fine
 * structure (issue "Sharp at the same cost"). The measure: luminance by
 * Rec. 709's weights on the 8-bit sRGB values as written; its fine
 * structure the standard deviation of luminance minus its box blur of
 * side 2k, over the top rows that are sky in these presets (0-459 of 720,
 * the same fraction at other heights); "kept" the default frame's over
 * the every-pixel frame's (--dome-divisor 1); PSNR over the whole frame.
 * sky-bench --only-sharpness prints the table; the tests hold it.
 */
#ifndef SKY_SHARPNESS_H
#define SKY_SHARPNESS_H

#include "sky.h"

#include <stddef.h>

/* The rows measured: the sky above the presets' horizon (0-459 at 720). */
int sky_sharpness_rows(int height);
/* The fine structure of an RGBA8 image (top row first) at box side 2k,
 * over its first rows rows. -1 when out of memory. */
double sky_fine_structure(const unsigned char *rgba, int width, int height, int rows, int k);
/* PSNR of b against a over every pixel's R, G and B, in dB (infinity for
 * identical images). */
double sky_psnr_rgba(const unsigned char *a, const unsigned char *b, int width, int height);

typedef struct sky_sharpness {
    double kept2, kept5; /* kept at k = 2 and 5 px */
    double psnr;         /* dB, the default frame against the every-pixel one */
} sky_sharpness;

/* Renders a preset's frame (the preset's camera; extra: more sky-render
 * options after it, or NULL) at width x height in profile gl, once as the
 * library draws it by default and once at --dome-divisor 1, and measures.
 * Returns 0, or -1 with err. */
int sky_sharpness_measure(const char *preset, const char *extra, sky_gl_profile gl, int width, int height,
                          sky_sharpness *out, char *err, size_t err_len);
/* One frame of a preset as sky-render draws it, RGBA8, top row first
 * (malloc'd into *rgba; free it). divisor 0: the library's default. */
int sky_sharpness_frame(const char *preset, const char *extra, int divisor, sky_gl_profile gl, int width, int height,
                        unsigned char **rgba, char *err, size_t err_len);

#endif
