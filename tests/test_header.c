/*
 * The public header as a host's compiler sees it: strict ISO C and C++.
 */
#include "test.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* sky/sky.h alone, under -pedantic -Werror, in C99, C11 and (where a C++
 * compiler is installed) C++98 and C++20: ISO C wants every enumerator to
 * fit an int, which SKY_FEATURES_NONE (bit 31) once did not. */
TEST(header_compiles_pedantic)
{
    char src[256], cmd[1024], out[4096];
    const char *dir = getenv("TMPDIR");
    snprintf(src, sizeof src, "%s/sky-header-%d.c", dir ? dir : "/tmp", (int)getpid());
    FILE *f = fopen(src, "w");
    if (!f) {
        CHECK(0, "cannot write %s", src);
        return;
    }
    /* the presets keep their values (0.6 removed the old names, not the
     * numbers a host built against 0.5 passes) */
    fputs("#include \"sky.h\"\n"
          "typedef char preset_values[(SKY_ATMOSPHERE_PRESET_EARTH == 0 && SKY_ATMOSPHERE_PRESET_HAZY == 1 && "
          "SKY_ATMOSPHERE_PRESET_MARS == 2 && SKY_ATMOSPHERE_PRESET_VERY_CLEAN == 3 && "
          "SKY_ATMOSPHERE_PRESET_POLLUTED == 4 && SKY_ATMOSPHERE_PRESET_HILLAIRE_2020 == 5) ? 1 : -1];\n"
          "int main(void) { preset_values ok; (void)ok; return SKY_FEATURES_NONE == 0; }\n",
          f);
    fclose(f);
    static const char *const compilers[4] = {"cc -std=c99", "cc -std=c11", "c++ -x c++ -std=c++98", "c++ -x c++ -std=c++20"};
    for (int i = 0; i < 4; i++) {
        if (i >= 2 && run_command("command -v c++ >/dev/null 2>&1", out, sizeof out) != 0) {
            NOTE("no C++ compiler here: %s skipped", compilers[i]);
            continue;
        }
        snprintf(cmd, sizeof cmd, "%s -pedantic -Wall -Wextra -Werror -fsyntax-only -Isky %s 2>&1", compilers[i], src);
        int rc = run_command(cmd, out, sizeof out);
        CHECK(rc == 0, "%s: the header compiles pedantically: %s", compilers[i], out);
    }
    remove(src);
}
