/* libFuzzer harness: the texture loader (PNG header check, then decode)
 * on arbitrary bytes, for two of the sizes the library asks for. */
#include "sky_internal.h"

#include <stdlib.h>

int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size);
int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size)
{
    static const int sizes[2][2] = {{256, 1}, {128, 128}};
    for (int k = 0; k < 2; k++) {
        unsigned char *rgba = NULL;
        char err[256];
        if (sky_image_decode(data, size, sizes[k][0], sizes[k][1], &rgba, "fuzz", err, sizeof err) == 0) {
            volatile unsigned sum = 0;
            for (int i = 0; i < sizes[k][0] * sizes[k][1] * 4; i++) sum += rgba[i];
            sky_png_free(rgba);
        }
    }
    return 0;
}
