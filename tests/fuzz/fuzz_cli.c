/* libFuzzer harness: the command-line parser of sky-render and sky-demo on
 * arbitrary arguments (the input split at NUL bytes into argv). */
#include "cli.h"

#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size);
int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size)
{
    if (size > 4096) return 0;
    char *buf = malloc(size + 1);
    if (!buf) return 0;
    memcpy(buf, data, size);
    buf[size] = '\0';
    char *argv[65];
    int argc = 0;
    argv[argc++] = "sky-render";
    for (size_t i = 0; i < size && argc < 64;) {
        argv[argc++] = buf + i;
        i += strlen(buf + i) + 1;
    }
    argv[argc] = NULL;
    sky_cli cli;
    char err[512];
    for (int demo = 0; demo < 2; demo++) {
        if (sky_cli_parse(&cli, argc, argv, demo, err, sizeof err) == SKY_CLI_OK) {
            float view[16], proj[16];
            sky_cli_camera(&cli, view, proj);
        }
    }
    free(buf);
    return 0;
}
