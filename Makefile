# libsky: make | make run | make test | make install PREFIX=... | make textures
#
# Outputs go to build/ only. `make run` and `make test` first install the
# Debian packages they need when missing (tools/deps.sh).

CC      ?= cc
PREFIX  ?= /usr/local
BUILD   := build
WARN    := -Wall -Wextra -Werror -Wshadow -Wstrict-prototypes -Wmissing-prototypes
CFLAGS  ?= -O2 -g
ALL_CFLAGS := -std=c11 $(WARN) $(CFLAGS) -fPIC -fvisibility=hidden -Isky -I$(BUILD)/gen
LDLIBS_M := -lm

SKY_SRC := sky/sky.c sky/core.c sky/camera.c sky/disc.c sky/exposure.c sky/solar_eclipse.c sky/astro.c sky/astro_tables.c sky/observer.c sky/catalog.c sky/dome.c sky/sun.c sky/stars.c sky/starmap.c sky/moon.c sky/clouds.c sky/flicker.c sky/atmosphere/gradient.c sky/atmosphere/params.c sky/atmosphere/atmosphere.c sky/atmosphere/preetham.c sky/atmosphere/rayleigh.c sky/atmosphere/spectrum.c sky/atmosphere/hillaire_cpu.c sky/atmosphere/hillaire.c sky/gl/gl.c sky/gl/image.c
SHADERS := $(wildcard sky/shaders/*.glsl sky/shaders/*.vert sky/shaders/*.frag)
TEXTURES := textures/clouds.png textures/flicker.png textures/galaxy.png textures/gradient.png textures/stars.dat textures/starmap.png textures/moon.png
SKY_OBJ := $(SKY_SRC:%.c=$(BUILD)/obj/%.o) $(BUILD)/obj/gen/sky_blobs.o
# The double-precision spectral reference is a yardstick, not part of the
# library: only the programs that measure against it (sky-bench, the test
# runners) compile it in.
REF_SRC := sky/atmosphere/reference.c
REF_HDR := sky/atmosphere/reference.h sky/atmosphere/spectrum.h sky/sky.h
SKY_HDR := sky/sky.h sky/sky_internal.h sky/core.h sky/layer.h sky/camera.h sky/disc.h sky/exposure.h sky/solar_eclipse.h sky/observer.h sky/catalog.h sky/gl/gl.h sky/atmosphere/atmosphere.h sky/atmosphere/spectrum.h sky/atmosphere/hillaire.h sky/gl/glapi.h sky/astro.h sky/astro_tables.h

BIN := $(BUILD)/bin
LIB := $(BUILD)/lib
TOOL_CFLAGS := -std=c11 $(WARN) $(CFLAGS) -D_DEFAULT_SOURCE

.PHONY: all deps run test install textures screenshots bench fuzz clean
all: $(LIB)/libsky.a $(LIB)/libsky.so $(BUILD)/include/sky.h $(BIN)/sky-render $(BIN)/sky-demo $(BIN)/sky-bench $(BIN)/sky-game

deps:
	@sh tools/deps.sh

# ---- library ------------------------------------------------------------
$(BIN)/embed: tools/embed.c
	@mkdir -p $(@D)
	$(CC) $(TOOL_CFLAGS) -o $@ $<

$(BUILD)/gen/sky_blobs.c: $(BIN)/embed $(SHADERS) $(TEXTURES)
	@mkdir -p $(@D)
	$(BIN)/embed $@ $(SHADERS) $(TEXTURES)

$(BUILD)/obj/gen/sky_blobs.o: $(BUILD)/gen/sky_blobs.c $(SKY_HDR)
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) -Wno-missing-prototypes -c -o $@ $<

$(BUILD)/obj/%.o: %.c $(SKY_HDR)
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) -c -o $@ $<

$(LIB)/libsky.a: $(SKY_OBJ)
	@mkdir -p $(@D)
	rm -f $@ && ar rcs $@ $^

$(LIB)/libsky.so: $(SKY_OBJ)
	@mkdir -p $(@D)
	$(CC) -shared -Wl,-soname,libsky.so.0 -o $@ $^ $(LDLIBS_M)

$(BUILD)/include/sky.h: sky/sky.h
	@mkdir -p $(@D)
	cp $< $@

# ---- programs -------------------------------------------------------------
DEMO_CFLAGS := -std=c11 $(WARN) $(CFLAGS) -D_DEFAULT_SOURCE -Isky -Idemo
CLI_SRC := demo/cli.c demo/osmesa_ctx.c
CLI_HDR := demo/cli.h demo/osmesa_ctx.h sky/sky.h
# the stability suite and the atmosphere's error against the reference:
# test and benchmark infrastructure (sky-bench prints them, the tests
# assert them), so they live in tools/ and not among the demos
STAB_SRC := tools/stability.c tools/atmo_error.c
STAB_HDR := tools/stability.h tools/atmo_error.h

$(BIN)/sky-render: demo/render.c $(CLI_SRC) $(CLI_HDR) $(LIB)/libsky.a
	@mkdir -p $(@D)
	$(CC) $(DEMO_CFLAGS) -o $@ demo/render.c $(CLI_SRC) $(LIB)/libsky.a -lOSMesa $(LDLIBS_M)

$(BIN)/sky-demo: demo/demo.c demo/ui.c demo/ui.h $(CLI_SRC) $(CLI_HDR) $(LIB)/libsky.a
	@mkdir -p $(@D)
	$(CC) $(DEMO_CFLAGS) -o $@ demo/demo.c demo/ui.c $(CLI_SRC) $(LIB)/libsky.a -lglfw -lGL -lOSMesa $(LDLIBS_M)

$(BIN)/sky-game: demo/game.c $(CLI_SRC) $(CLI_HDR) $(LIB)/libsky.a
	@mkdir -p $(@D)
	$(CC) $(DEMO_CFLAGS) -o $@ demo/game.c $(CLI_SRC) $(LIB)/libsky.a -lglfw -lGL -lOSMesa $(LDLIBS_M)

$(BIN)/sky-bench: tools/bench.c tools/plot.c tools/plot.h $(CLI_SRC) $(CLI_HDR) $(STAB_SRC) $(STAB_HDR) $(REF_SRC) $(REF_HDR) $(LIB)/libsky.a
	@mkdir -p $(@D)
	$(CC) $(DEMO_CFLAGS) -o $@ tools/bench.c tools/plot.c $(CLI_SRC) $(STAB_SRC) $(REF_SRC) $(LIB)/libsky.a -lOSMesa -lpthread $(LDLIBS_M)

bench: all
	$(BIN)/sky-bench --plot docs/img/atmosphere-pareto.png

$(BIN)/catgen: tools/catgen.c
	@mkdir -p $(@D)
	$(CC) $(TOOL_CFLAGS) -o $@ $< $(LDLIBS_M)

$(BIN)/texgen: tools/texgen.c
	@mkdir -p $(@D)
	$(CC) $(TOOL_CFLAGS) -o $@ $< $(LDLIBS_M)

# ---- run, test ----------------------------------------------------------------
run: deps all
	@sh tools/run.sh

TEST_SRC := $(wildcard tests/*.c)
$(BIN)/sky-tests: $(TEST_SRC) tests/test.h $(CLI_SRC) $(CLI_HDR) $(STAB_SRC) $(STAB_HDR) $(REF_SRC) $(REF_HDR) $(SKY_HDR) $(LIB)/libsky.a
	@mkdir -p $(@D)
	$(CC) $(DEMO_CFLAGS) -Itests -Itools -o $@ $(TEST_SRC) $(CLI_SRC) $(STAB_SRC) $(REF_SRC) $(LIB)/libsky.a -lOSMesa -lerfa -lpthread $(LDLIBS_M)

# The leak check links the library with LeakSanitizer in its own build dir.
$(BIN)/sky-leaks: tests/leaks/leaks.c demo/osmesa_ctx.c demo/osmesa_ctx.h $(SKY_SRC) $(BUILD)/gen/sky_blobs.c $(SKY_HDR)
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) -Wno-missing-prototypes -D_DEFAULT_SOURCE -fsanitize=leak -Idemo -o $@ \
	    tests/leaks/leaks.c demo/osmesa_ctx.c $(SKY_SRC) $(BUILD)/gen/sky_blobs.c -lOSMesa $(LDLIBS_M)

# The same runner built with AddressSanitizer and UndefinedBehaviorSanitizer
# over the library's sources, in a directory of its own.
SAN_FLAGS := -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer
$(BUILD)/asan/sky-tests: $(TEST_SRC) tests/test.h $(CLI_SRC) $(CLI_HDR) $(STAB_SRC) $(STAB_HDR) $(REF_SRC) $(REF_HDR) $(SKY_SRC) $(SKY_HDR) $(BUILD)/gen/sky_blobs.c
	@mkdir -p $(@D)
	$(CC) -std=c11 $(WARN) -O1 -g $(SAN_FLAGS) -D_DEFAULT_SOURCE -Isky -I$(BUILD)/gen -Idemo -Itools -Itests -Wno-missing-prototypes \
	    -o $@ $(TEST_SRC) $(CLI_SRC) $(STAB_SRC) $(REF_SRC) $(SKY_SRC) $(BUILD)/gen/sky_blobs.c -lOSMesa -lerfa -lpthread $(LDLIBS_M)

# libFuzzer harnesses (clang with compiler-rt); built only where that links
FUZZ_CC ?= clang
HAVE_FUZZ := $(shell printf 'int LLVMFuzzerTestOneInput(const unsigned char *d, unsigned long n) { (void)d; (void)n; return 0; }' \
    | $(FUZZ_CC) -fsanitize=fuzzer -x c - -o /dev/null 2>/dev/null && echo yes)
FUZZ_FLAGS := -std=c11 -g -O1 -fsanitize=fuzzer,address,undefined -D_DEFAULT_SOURCE -Isky -I$(BUILD)/gen -Idemo
FUZZERS := $(if $(HAVE_FUZZ),$(BUILD)/fuzz/fuzz_catalog $(BUILD)/fuzz/fuzz_png $(BUILD)/fuzz/fuzz_cli)
$(BUILD)/fuzz/fuzz_catalog: tests/fuzz/fuzz_catalog.c $(SKY_SRC) $(SKY_HDR) $(BUILD)/gen/sky_blobs.c
	@mkdir -p $(@D)
	$(FUZZ_CC) $(FUZZ_FLAGS) -o $@ tests/fuzz/fuzz_catalog.c $(SKY_SRC) $(BUILD)/gen/sky_blobs.c $(LDLIBS_M)
$(BUILD)/fuzz/fuzz_png: tests/fuzz/fuzz_png.c $(SKY_SRC) $(SKY_HDR) $(BUILD)/gen/sky_blobs.c
	@mkdir -p $(@D)
	$(FUZZ_CC) $(FUZZ_FLAGS) -o $@ tests/fuzz/fuzz_png.c $(SKY_SRC) $(BUILD)/gen/sky_blobs.c $(LDLIBS_M)
$(BUILD)/fuzz/fuzz_cli: tests/fuzz/fuzz_cli.c demo/cli.c demo/cli.h $(SKY_SRC) $(SKY_HDR) $(BUILD)/gen/sky_blobs.c
	@mkdir -p $(@D)
	$(FUZZ_CC) $(FUZZ_FLAGS) -o $@ tests/fuzz/fuzz_cli.c demo/cli.c $(SKY_SRC) $(BUILD)/gen/sky_blobs.c $(LDLIBS_M)

# make fuzz: five minutes a harness (make test runs each for SKY_FUZZ_SECONDS, 20 by default)
fuzz: $(FUZZERS)
	@SKY_FUZZ_SECONDS=300 SKY_FUZZ=$(BUILD)/fuzz sh tests/fuzz/run.sh

test: deps all $(BIN)/sky-tests $(BIN)/sky-leaks $(BUILD)/asan/sky-tests $(FUZZERS)
	@SKY_BIN=$(BIN) SKY_ASAN=$(BUILD)/asan SKY_FUZZ=$(if $(HAVE_FUZZ),$(BUILD)/fuzz) sh tests/run.sh

# ---- install ----------------------------------------------------------------------
install: all
	install -d $(DESTDIR)$(PREFIX)/include $(DESTDIR)$(PREFIX)/lib/pkgconfig $(DESTDIR)$(PREFIX)/bin
	install -m 644 sky/sky.h $(DESTDIR)$(PREFIX)/include/sky.h
	install -m 644 $(LIB)/libsky.a $(DESTDIR)$(PREFIX)/lib/libsky.a
	install -m 755 $(LIB)/libsky.so $(DESTDIR)$(PREFIX)/lib/libsky.so.0
	ln -sf libsky.so.0 $(DESTDIR)$(PREFIX)/lib/libsky.so
	install -m 755 $(BIN)/sky-render $(BIN)/sky-demo $(DESTDIR)$(PREFIX)/bin/
	sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@VERSION@|0.1.0|' sky/sky.pc.in > $(DESTDIR)$(PREFIX)/lib/pkgconfig/sky.pc

# ---- assets ---------------------------------------------------------------------------
# Rebuilds textures/ from their origins (see textures/README.md). Needs
# Debian's stellarium-data, which it downloads and unpacks into build/.
textures: $(BIN)/texgen $(BIN)/catgen
	@sh tools/fetch-stellarium.sh $(BUILD)/stellarium
	@sh tools/fetch-d3celestial.sh $(BUILD)/d3-celestial
	$(BIN)/texgen --out textures --photo $(BUILD)/stellarium/usr/share/stellarium/textures/earth-clouds.png --crop 0,20,176 \
	    --moon $(BUILD)/stellarium/usr/share/stellarium/textures/moon.png
	$(BIN)/catgen --stars $(BUILD)/d3-celestial/package/data/stars.8.json \
	    --pm $(BUILD)/stellarium/usr/share/stellarium/stars/default/hip_pm.dat --max-mag 6.5 --out textures/stars.dat \
	    --map textures/starmap.png --mw $(BUILD)/d3-celestial/package/data/mw.json

# The README's pictures, rendered by sky-render.
screenshots: all
	@sh tools/screenshots.sh

clean:
	rm -rf $(BUILD)
