/* libFuzzer harness: the texture loader (PNG header check, then decode)
 * on arbitrary bytes, for two of the sizes the library asks for. Each
 * input is decoded twice with the stack below filled differently in
 * between: pixels that differ were read from memory the decoder never
 * wrote (as a paletted image indexing past its PLTE once did), which
 * ASan alone does not see. */
#include "sky_internal.h"

#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size);

static void fill_stack(unsigned char value)
{
    volatile unsigned char junk[64 * 1024];
    for (size_t i = 0; i < sizeof junk; i++) junk[i] = value;
}

int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size)
{
    static const int sizes[2][2] = {{256, 1}, {128, 128}};
    for (int k = 0; k < 2; k++) {
        unsigned char *rgba[2] = {NULL, NULL};
        int rc[2];
        char err[256];
        for (int pass = 0; pass < 2; pass++) {
            fill_stack(pass ? 0x5a : 0xa5);
            rc[pass] = sky_image_decode(data, size, sizes[k][0], sizes[k][1], &rgba[pass], "fuzz", err, sizeof err);
        }
        if (rc[0] != rc[1]) abort();
        if (rc[0] == 0 && memcmp(rgba[0], rgba[1], (size_t)sizes[k][0] * (size_t)sizes[k][1] * 4u)) abort();
        sky_png_free(rgba[0]);
        sky_png_free(rgba[1]);
    }
    return 0;
}
