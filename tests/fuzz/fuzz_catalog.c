/* libFuzzer harness: the star catalogue reader on arbitrary bytes. */
#include "sky_internal.h"

int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size);
int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size)
{
    sky_catalog cat;
    char err[256];
    if (sky_catalog_parse(&cat, data, size, err, sizeof err) == 0) {
        /* what it accepted must be usable */
        volatile double sum = 0;
        for (int i = 0; i < cat.count; i++) sum += cat.stars[i].ra + cat.stars[i].dec;
        (void)sky_catalog_find(&cat, 32349);
        sky_catalog_free(&cat);
    }
    return 0;
}
