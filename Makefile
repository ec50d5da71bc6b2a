# libsky: make | make run | make check | make test | make install PREFIX=... | make textures
#
# Outputs go to build/ only. `make run` and `make test` first install the Debian
# packages they need when missing (tools/deps.sh); `make check`, the fast tier, does not.

CC      ?= cc
PREFIX  ?= /usr/local
BUILD   := build
WARN    := -Wall -Wextra -Werror -Wshadow -Wstrict-prototypes -Wmissing-prototypes
CFLAGS  ?= -O2 -g
ALL_CFLAGS := -std=c11 $(WARN) $(CFLAGS) -fPIC -fvisibility=hidden -Isky -I$(BUILD)/gen
LDLIBS_M := -lm
# the headless contexts (demo/osmesa_ctx.c): OSMesa, and EGL for ES 2.0
HEADLESS_LIBS := -lOSMesa -lEGL

# The library's sources and the assets it embeds are found, not listed: a
# new layer's .c, shader and texture join the build by being there. The
# patterns are sky/sources.txt's, which CMakeLists.txt reads too, so the two
# builds cannot drift apart. (The double-precision reference,
# sky/atmosphere/reference.c, is excluded there: see REF_SRC.)
SKY_LIST := sky/sources.txt
sky_list = $(shell sed -n 's/^$(1)[[:space:]][[:space:]]*//p' $(SKY_LIST))
SKY_SRC := $(filter-out $(call sky_list,exclude),$(sort $(wildcard $(call sky_list,source))))
SHADERS := $(wildcard $(call sky_list,shader))
TEXTURES := $(sort $(wildcard $(call sky_list,texture)))
SKY_OBJ := $(SKY_SRC:%.c=$(BUILD)/obj/%.o) $(BUILD)/obj/gen/sky_blobs.o
# The double-precision spectral reference is a yardstick, not part of the
# library: only the programs that measure against it (sky-bench, the test
# runners) compile it in.
REF_SRC := sky/atmosphere/reference.c
REF_HDR := sky/atmosphere/reference.h sky/atmosphere/spectrum.h sky/sky.h
SKY_HDR := $(sort $(wildcard sky/*.h sky/atmosphere/*.h sky/gl/*.h))

BIN := $(BUILD)/bin
LIB := $(BUILD)/lib
TOOL_CFLAGS := -std=c11 $(WARN) $(CFLAGS) -D_DEFAULT_SOURCE

.PHONY: all deps run check test install textures planet-tables screenshots bench fuzz clean examples test-examples windows test-windows \
	web test-web bench-web amalgamation
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

# (-MMD -MP: each object's headers beside it, as the sanitizer trees
# below do; SKY_HDR names the public and core ones for the first build)
$(BUILD)/obj/%.o: %.c $(SKY_HDR)
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) -MMD -MP -c -o $@ $<
-include $(SKY_OBJ:.o=.d)

$(LIB)/libsky.a: $(SKY_OBJ)
	@mkdir -p $(@D)
	rm -f $@ && ar rcs $@ $^

# The version is sky.h's; the soname follows its rule (sky.h, Versions):
# libsky.so.0.MINOR before 1.0, libsky.so.MAJOR after.
SKY_VERSION := $(shell sed -n 's/^\#define SKY_VERSION_\(MAJOR\|MINOR\|PATCH\) \([0-9]*\)$$/\2/p' sky/sky.h | paste -sd.)
SKY_SONAME := libsky.so.$(if $(filter 0.%,$(SKY_VERSION)),0.$(word 2,$(subst ., ,$(SKY_VERSION))),$(word 1,$(subst ., ,$(SKY_VERSION))))

$(LIB)/libsky.so: $(SKY_OBJ)
	@mkdir -p $(@D)
	$(CC) -shared -Wl,-soname,$(SKY_SONAME) -o $@ $^ $(LDLIBS_M)

$(BUILD)/include/sky.h: sky/sky.h
	@mkdir -p $(@D)
	cp $< $@

# ---- the amalgamation: the library as two files ---------------------------
# build/amalgamation/sky.c and sky.h, for projects that drop sources in: one
# translation unit of SKY_SRC (the same list as the library's), the
# internal headers inlined, the shaders and textures as tools/embed gives
# them, and stb_image's decoder from Debian's libstb-dev (docs/guide.md,
# "Drop in two files").
AMALG := $(BUILD)/amalgamation
STB_IMAGE_H := /usr/include/stb/stb_image.h
amalgamation: $(AMALG)/sky.c $(AMALG)/sky.h

$(AMALG)/sky.c $(AMALG)/sky.h &: tools/amalgamate.sh $(SKY_SRC) $(SKY_HDR) $(BUILD)/gen/sky_blobs.c
	sh tools/amalgamate.sh $(AMALG) $(BUILD)/gen/sky_blobs.c $(STB_IMAGE_H) $(SKY_SRC)

# ---- programs -------------------------------------------------------------
DEMO_CFLAGS := -std=c11 $(WARN) $(CFLAGS) -D_DEFAULT_SOURCE -Isky -Idemo
CLI_SRC := demo/cli.c demo/osmesa_ctx.c demo/image_out.c
CLI_HDR := demo/cli.h demo/osmesa_ctx.h sky/sky.h
# the stability suite and the atmosphere's error against the reference:
# test and benchmark infrastructure (sky-bench prints them, the tests
# assert them), so they live in tools/ and not among the demos
STAB_SRC := tools/stability.c tools/atmo_error.c tools/colour.c tools/photometry.c tools/sharpness.c
STAB_HDR := tools/stability.h tools/atmo_error.h tools/colour.h tools/photometry.h tools/sharpness.h

$(BIN)/sky-render: demo/render.c $(CLI_SRC) $(CLI_HDR) $(LIB)/libsky.a
	@mkdir -p $(@D)
	$(CC) $(DEMO_CFLAGS) -o $@ demo/render.c $(CLI_SRC) $(LIB)/libsky.a $(HEADLESS_LIBS) $(LDLIBS_M)

$(BIN)/sky-demo: demo/demo.c demo/ui.c demo/ui.h $(CLI_SRC) $(CLI_HDR) $(LIB)/libsky.a
	@mkdir -p $(@D)
	$(CC) $(DEMO_CFLAGS) -o $@ demo/demo.c demo/ui.c $(CLI_SRC) $(LIB)/libsky.a -lglfw -lGL $(HEADLESS_LIBS) $(LDLIBS_M)

$(BIN)/sky-game: demo/game.c $(CLI_SRC) $(CLI_HDR) $(LIB)/libsky.a
	@mkdir -p $(@D)
	$(CC) $(DEMO_CFLAGS) -o $@ demo/game.c $(CLI_SRC) $(LIB)/libsky.a -lglfw -lGL $(HEADLESS_LIBS) $(LDLIBS_M)

$(BIN)/sky-bench: tools/bench.c tools/plot.c tools/plot.h $(CLI_SRC) $(CLI_HDR) $(STAB_SRC) $(STAB_HDR) $(REF_SRC) $(REF_HDR) $(LIB)/libsky.a
	@mkdir -p $(@D)
	$(CC) $(DEMO_CFLAGS) -o $@ tools/bench.c tools/plot.c $(CLI_SRC) $(STAB_SRC) $(REF_SRC) $(LIB)/libsky.a $(HEADLESS_LIBS) -lpthread $(LDLIBS_M)

# The full benchmark: its charts into docs/img and its report into
# docs/benchmarks.md (written beside and moved, so a failed run leaves
# the page as it was).
bench: all
	$(BIN)/sky-bench --markdown --plot docs/img/atmosphere-pareto.png --plot-photometry docs/img/photometry.png \
		> $(BUILD)/benchmarks.md
	mv $(BUILD)/benchmarks.md docs/benchmarks.md
	@cat docs/benchmarks.md

$(BIN)/catgen: tools/catgen.c
	@mkdir -p $(@D)
	$(CC) $(TOOL_CFLAGS) -o $@ $< $(LDLIBS_M)

$(BIN)/vsopgen: tools/vsopgen.c
	@mkdir -p $(@D)
	$(CC) $(TOOL_CFLAGS) -o $@ $< $(LDLIBS_M)

$(BIN)/texgen: tools/texgen.c
	@mkdir -p $(@D)
	$(CC) $(TOOL_CFLAGS) -o $@ $< $(LDLIBS_M)

$(BIN)/pngcrop: tools/pngcrop.c
	@mkdir -p $(@D)
	$(CC) $(TOOL_CFLAGS) -o $@ $< $(LDLIBS_M)

# ---- run, test ----------------------------------------------------------------
run: deps all
	@sh tools/run.sh

# The test runner: one object per file, in a tree of its own (the tools'
# flags), and its list of tests written from the files' TEST lines
# (tests/list.sh), so a new test is its function and nothing else.
TEST_SRC := $(sort $(wildcard tests/*.c))
TEST_DIR := $(BUILD)/tests/obj
TEST_OBJ := $(patsubst %.c,$(TEST_DIR)/%.o,$(TEST_SRC) $(CLI_SRC) $(STAB_SRC) $(REF_SRC))
TEST_CFLAGS := $(DEMO_CFLAGS) -Itests -Itools -I$(BUILD)/gen/tests

$(BUILD)/gen/tests/test_list.h: tests/list.sh $(TEST_SRC)
	@mkdir -p $(@D)
	sh tests/list.sh $@ $(TEST_SRC)

$(TEST_DIR)/%.o: %.c
	@mkdir -p $(@D)
	$(CC) $(TEST_CFLAGS) -MMD -MP -c -o $@ $<
$(TEST_DIR)/tests/test_main.o: $(BUILD)/gen/tests/test_list.h
-include $(TEST_OBJ:.o=.d)

# (the amalgamation's tests read build/amalgamation: made with the runner,
# order-only, as a new amalgamation needs no relink)
$(BIN)/sky-tests: $(TEST_OBJ) $(LIB)/libsky.a | $(AMALG)/sky.c $(AMALG)/sky.h
	@mkdir -p $(@D)
	$(CC) -o $@ $(TEST_OBJ) $(LIB)/libsky.a $(HEADLESS_LIBS) -lerfa -lpthread $(LDLIBS_M)

# The sanitized programs are linked from objects compiled once per
# sanitizer, each in a tree of its own. -MMD -MP write each object's
# header dependencies beside it, so a header change rebuilds exactly the
# objects that include it (these trees mix library, test and tool sources,
# whose headers differ).
DEPFLAGS := -MMD -MP

# AddressSanitizer + UndefinedBehaviorSanitizer: one set of objects for the
# test runner and the leak check (ASan includes LeakSanitizer; the leak
# test runs sky-leaks with detect_leaks=1).
SAN_FLAGS := -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer
SAN_CFLAGS := -std=c11 $(WARN) -O1 -g $(SAN_FLAGS) -D_DEFAULT_SOURCE -Isky -I$(BUILD)/gen -Idemo -Itools -Itests -I$(BUILD)/gen/tests -Wno-missing-prototypes
SAN_DIR := $(BUILD)/asan/obj
SAN_SKY_OBJ := $(SKY_SRC:%.c=$(SAN_DIR)/%.o) $(SAN_DIR)/gen/sky_blobs.o
SAN_TEST_OBJ := $(patsubst %.c,$(SAN_DIR)/%.o,$(TEST_SRC) $(CLI_SRC) $(STAB_SRC) $(REF_SRC))
SAN_LEAKS_OBJ := $(SAN_DIR)/tests/leaks/leaks.o $(SAN_DIR)/demo/osmesa_ctx.o

$(SAN_DIR)/gen/sky_blobs.o: $(BUILD)/gen/sky_blobs.c
	@mkdir -p $(@D)
	$(CC) $(SAN_CFLAGS) $(DEPFLAGS) -c -o $@ $<

$(SAN_DIR)/%.o: %.c
	@mkdir -p $(@D)
	$(CC) $(SAN_CFLAGS) $(DEPFLAGS) -c -o $@ $<
$(SAN_DIR)/tests/test_main.o: $(BUILD)/gen/tests/test_list.h

$(BUILD)/asan/sky-tests: $(SAN_TEST_OBJ) $(SAN_SKY_OBJ)
	@mkdir -p $(@D)
	$(CC) $(SAN_FLAGS) -o $@ $^ $(HEADLESS_LIBS) -lerfa -lpthread $(LDLIBS_M)

$(BIN)/sky-leaks: $(SAN_LEAKS_OBJ) $(SAN_SKY_OBJ)
	@mkdir -p $(@D)
	$(CC) $(SAN_FLAGS) -o $@ $^ $(HEADLESS_LIBS) $(LDLIBS_M)

# libFuzzer harnesses (clang with compiler-rt); built only where that links.
# The library is compiled once with fuzzer-no-link (coverage without
# libFuzzer's main) and each harness linked with -fsanitize=fuzzer.
FUZZ_CC ?= clang
HAVE_FUZZ := $(shell printf 'int LLVMFuzzerTestOneInput(const unsigned char *d, unsigned long n) { (void)d; (void)n; return 0; }' \
    | $(FUZZ_CC) -fsanitize=fuzzer -x c - -o /dev/null 2>/dev/null && echo yes)
FUZZ_CFLAGS := -std=c11 -g -O1 -fsanitize=fuzzer-no-link,address,undefined -D_DEFAULT_SOURCE -Isky -I$(BUILD)/gen -Idemo
FUZZ_DIR := $(BUILD)/fuzz/obj
FUZZ_SKY_OBJ := $(SKY_SRC:%.c=$(FUZZ_DIR)/%.o) $(FUZZ_DIR)/gen/sky_blobs.o
FUZZ_BIN := $(BUILD)/fuzz/fuzz_catalog $(BUILD)/fuzz/fuzz_png $(BUILD)/fuzz/fuzz_cli
FUZZERS := $(if $(HAVE_FUZZ),$(FUZZ_BIN))

$(FUZZ_DIR)/gen/sky_blobs.o: $(BUILD)/gen/sky_blobs.c
	@mkdir -p $(@D)
	$(FUZZ_CC) $(FUZZ_CFLAGS) $(DEPFLAGS) -c -o $@ $<

$(FUZZ_DIR)/%.o: %.c
	@mkdir -p $(@D)
	$(FUZZ_CC) $(FUZZ_CFLAGS) $(DEPFLAGS) -c -o $@ $<

$(FUZZ_BIN): $(BUILD)/fuzz/fuzz_%: $(FUZZ_DIR)/tests/fuzz/fuzz_%.o $(FUZZ_SKY_OBJ)
	$(FUZZ_CC) -fsanitize=fuzzer,address,undefined -o $@ $^ $(LDLIBS_M)
$(BUILD)/fuzz/fuzz_cli: $(FUZZ_DIR)/demo/cli.o

-include $(patsubst %.o,%.d,$(SAN_SKY_OBJ) $(SAN_TEST_OBJ) $(SAN_LEAKS_OBJ) $(FUZZ_SKY_OBJ) \
    $(FUZZ_BIN:$(BUILD)/fuzz/%=$(FUZZ_DIR)/tests/fuzz/%.o) $(FUZZ_DIR)/demo/cli.o)

# make fuzz: five minutes a harness (make test runs each for SKY_FUZZ_SECONDS, 20 by default)
fuzz: $(FUZZERS)
	@SKY_FUZZ_SECONDS=300 SKY_FUZZ=$(BUILD)/fuzz sh tests/fuzz/run.sh

# make check: the fast tier, for iterating: the plain runner without the
# tests marked SLOW_TEST, no sanitizer builds, no fuzzers, and no package
# manager (make run or make test install the packages); SKY_LEAKS empty
# makes the leak test, whose program is one of make test's sanitizer
# builds, skip rather than run a stale one.
check: all $(BIN)/sky-tests
	@SKY_BIN=$(BIN) SKY_LEAKS= $(BIN)/sky-tests --fast

# make test: everything: the plain runner, the ASan/UBSan runner, the leak
# check and the fuzzers.
test: deps all $(BIN)/sky-tests $(BIN)/sky-leaks $(BUILD)/asan/sky-tests $(FUZZERS)
	@SKY_BIN=$(BIN) SKY_LEAKS=$(BIN)/sky-leaks SKY_ASAN=$(BUILD)/asan SKY_FUZZ=$(if $(HAVE_FUZZ),$(BUILD)/fuzz) sh tests/run.sh

# ---- the engine examples ------------------------------------------------------------
# Not part of all, run or test: OpenSceneGraph alone brings about fifty
# packages. make examples installs the engines' Debian packages and builds
# the three programs; make test-examples runs their tests under Xvfb.
EXAMPLE_PACKAGES := g++ libsdl2-dev libopenscenegraph-dev libirrlicht-dev
EX := $(BUILD)/examples
EXAMPLES := $(EX)/sky-sdl2 $(EX)/sky-osg $(EX)/sky-irrlicht
EX_CFLAGS := -std=c11 $(WARN) $(CFLAGS) -Isky
EX_CXXFLAGS := -std=c++11 -Wall -Wextra -Werror $(CFLAGS) -Isky
CXX ?= c++

examples: all
	@sh tools/deps.sh $(EXAMPLE_PACKAGES)
	@$(MAKE) --no-print-directory $(EXAMPLES)

$(EX)/sky-sdl2: examples/sdl2.c sky/sky.h $(LIB)/libsky.a
	@mkdir -p $(@D)
	$(CC) $(EX_CFLAGS) $$(pkg-config --cflags sdl2) -o $@ $< $(LIB)/libsky.a $$(pkg-config --libs sdl2) -lGL -lstb $(LDLIBS_M)

$(EX)/sky-osg: examples/osg.cpp sky/sky.h $(LIB)/libsky.a
	@mkdir -p $(@D)
	$(CXX) $(EX_CXXFLAGS) -o $@ $< $(LIB)/libsky.a -losgViewer -losgGA -losgDB -losgUtil -losg -lOpenThreads -lGL $(LDLIBS_M)

$(EX)/sky-irrlicht: examples/irrlicht.cpp sky/sky.h $(LIB)/libsky.a
	@mkdir -p $(@D)
	$(CXX) $(EX_CXXFLAGS) -isystem /usr/include/irrlicht -o $@ $< $(LIB)/libsky.a -lIrrlicht -lGL $(LDLIBS_M)

# the test runner's harness (test_main.c) with the examples' tests in place
# of the library's
$(EX)/gen/test_list.h: tests/list.sh tests/examples/test_examples.c
	@mkdir -p $(@D)
	sh tests/list.sh $@ tests/examples/test_examples.c

$(EX)/example-tests: tests/examples/test_examples.c tests/test_main.c tests/test.h $(EX)/gen/test_list.h $(CLI_SRC) $(CLI_HDR) $(LIB)/libsky.a
	@mkdir -p $(@D)
	$(CC) $(DEMO_CFLAGS) -Itests -I$(EX)/gen -o $@ tests/examples/test_examples.c tests/test_main.c $(CLI_SRC) $(LIB)/libsky.a $(HEADLESS_LIBS) $(LDLIBS_M)

test-examples: examples $(EX)/example-tests
	@SKY_EXAMPLES=$(EX) xvfb-run -a -s '-screen 0 1280x720x24' $(EX)/example-tests

# ---- the browser: make web, make test-web ---------------------------------------------
# The library and sky-demo through Debian's Emscripten (GLFW is its own
# port, in JavaScript; WebGL 1), the shaders and textures embedded as in
# every build, into build/web/index.html with its .js and .wasm beside it.
# Debian's Emscripten keeps a frozen cache (EM_CACHE stays unset) and finds
# acorn through NODE_PATH. stb comes from libstb-dev through a directory of
# its own, so that the system's other headers stay out of the build.
WEB := $(BUILD)/web
WEB_PACKAGES := emscripten chromium-headless-shell python3
WEB_SRC := $(SKY_SRC) $(BUILD)/gen/sky_blobs.c demo/demo.c demo/ui.c demo/cli.c
WEB_FLAGS := -std=c11 $(WARN) -O2 -D_DEFAULT_SOURCE -Isky -Idemo -I$(BUILD)/gen -I$(WEB)/include \
	-sUSE_GLFW=3 -sMIN_WEBGL_VERSION=1 -sMAX_WEBGL_VERSION=1 -sALLOW_MEMORY_GROWTH=1 \
	-sEXPORTED_RUNTIME_METHODS=ccall -sMINIFY_HTML=0

web: $(BUILD)/gen/sky_blobs.c
	@sh tools/deps.sh $(WEB_PACKAGES)
	@$(MAKE) --no-print-directory $(WEB)/index.html

$(WEB)/index.html: $(WEB_SRC) $(SKY_HDR) demo/cli.h demo/ui.h web/shell.html
	@mkdir -p $(WEB)/include && ln -sfn /usr/include/stb $(WEB)/include/stb
	NODE_PATH=/usr/share/nodejs emcc $(WEB_FLAGS) -sEXPORTED_FUNCTIONS=_main,_sky_demo_preset \
		--shell-file web/shell.html -o $@ $(WEB_SRC)

# The browser's timing page (web/bench.c, web/bench.html) and its run in
# headless Chromium with three.js's Sky beside libsky (tools/bench-web.sh).
WEB_BENCH_SRC := $(SKY_SRC) $(BUILD)/gen/sky_blobs.c web/bench.c demo/cli.c
$(WEB)/bench.html: $(WEB_BENCH_SRC) $(SKY_HDR) demo/cli.h web/bench.html
	@mkdir -p $(WEB)/include && ln -sfn /usr/include/stb $(WEB)/include/stb
	NODE_PATH=/usr/share/nodejs emcc $(WEB_FLAGS) -sEXPORTED_FUNCTIONS=_main,_web_bench_open,_web_bench_quad,_web_bench_preset \
		--shell-file web/bench.html -o $@ $(WEB_BENCH_SRC)

bench-web: web
	@command -v npm >/dev/null 2>&1 || sh tools/deps.sh npm
	@$(MAKE) --no-print-directory $(WEB)/bench.html
	@sh tools/bench-web.sh

# The page in headless Chromium (WebGL 1 through SwiftShader): the runner
# is the test harness built natively with tests/web/.
$(WEB)/gen/test_list.h: tests/list.sh tests/web/test_web.c
	@mkdir -p $(@D)
	sh tests/list.sh $@ tests/web/test_web.c

$(WEB)/web-tests: tests/web/test_web.c tests/test_main.c tests/test.h $(WEB)/gen/test_list.h $(CLI_SRC) $(CLI_HDR) $(LIB)/libsky.a
	@mkdir -p $(@D)
	$(CC) $(DEMO_CFLAGS) -Itests -I$(WEB)/gen -o $@ tests/web/test_web.c tests/test_main.c $(CLI_SRC) $(LIB)/libsky.a $(HEADLESS_LIBS) $(LDLIBS_M)

test-web: web $(WEB)/web-tests
	@SKY_WEB=$(WEB) $(WEB)/web-tests

# ---- Windows: make windows ---------------------------------------------------------
# The library cross-built with MinGW-w64 (x86_64) into build/windows/: libsky.a (static,
# no SKY_DLL), sky.dll with its import library libsky.dll.a (hosts define SKY_DLL), sky.h,
# and bin/sky-render.exe (sky-render's command line; a hidden window's WGL context).
# The embedder runs natively (build/gen/sky_blobs.c is the one every build embeds); stb
# comes from libstb-dev through a directory of its own, as in the browser build.
WIN := $(BUILD)/windows
WIN_CC := x86_64-w64-mingw32-gcc
WIN_AR := x86_64-w64-mingw32-ar
WIN_CFLAGS := -std=c11 $(WARN) -O2 -Isky -I$(BUILD)/gen -I$(WIN)/include
WIN_STATIC_OBJ := $(SKY_SRC:%.c=$(WIN)/obj/static/%.o) $(WIN)/obj/static/gen/sky_blobs.o
WIN_DLL_OBJ := $(SKY_SRC:%.c=$(WIN)/obj/dll/%.o) $(WIN)/obj/dll/gen/sky_blobs.o

windows: $(BUILD)/gen/sky_blobs.c
	@sh tools/deps.sh mingw-w64
	@$(MAKE) --no-print-directory $(WIN)/libsky.a $(WIN)/sky.dll $(WIN)/include/sky.h $(WIN)/bin/sky-render.exe

$(WIN)/include/sky.h: sky/sky.h
	@mkdir -p $(@D) && ln -sfn /usr/include/stb $(@D)/stb
	cp $< $@

$(WIN)/obj/static/gen/sky_blobs.o $(WIN)/obj/dll/gen/sky_blobs.o: $(BUILD)/gen/sky_blobs.c $(WIN)/include/sky.h
	@mkdir -p $(@D)
	$(WIN_CC) $(WIN_CFLAGS) $(if $(findstring /dll/,$@),-DSKY_SHARED_BUILD) -Wno-missing-prototypes -c -o $@ $<

$(WIN)/obj/static/%.o: %.c $(WIN)/include/sky.h
	@mkdir -p $(@D)
	$(WIN_CC) $(WIN_CFLAGS) -MMD -MP -c -o $@ $<

$(WIN)/obj/dll/%.o: %.c $(WIN)/include/sky.h
	@mkdir -p $(@D)
	$(WIN_CC) $(WIN_CFLAGS) -DSKY_SHARED_BUILD -MMD -MP -c -o $@ $<

$(WIN)/libsky.a: $(WIN_STATIC_OBJ)
	rm -f $@ && $(WIN_AR) rcs $@ $^

$(WIN)/sky.dll: $(WIN_DLL_OBJ)
	$(WIN_CC) -shared -static-libgcc -o $@ $^ -Wl,--out-implib,$(WIN)/libsky.dll.a

-include $(WIN_STATIC_OBJ:.o=.d) $(WIN_DLL_OBJ:.o=.d)

# make test-windows: under Wine and Xvfb, the Windows build of the tests that need neither
# OSMesa nor ERFA (the API, validation, stability and the planets against committed tables),
# with tests/windows/'s own: every preset's frame from sky-render.exe (a hidden WGL window)
# against Linux's, the opengl32.dll fallback behind a bare wglGetProcAddress, the DLL and the
# amalgamation.
# tests/windows/run.sh renders the Linux frames and runs the runner; it ends "N passed, N failed".
WIN_BIN := $(WIN)/bin
WIN_TEST_SRC := tests/test_main.c tests/test_api.c tests/test_validation.c tests/test_stability.c \
	tests/test_planets.c tests/windows/test_windows.c
WIN_FRONT_SRC := demo/cli.c demo/wgl_ctx.c demo/image_out.c
WIN_PROG_CFLAGS := -std=c11 $(WARN) -O2 -Isky -Idemo -isystem $(WIN)/include
WIN_GL_LIBS := -lopengl32 -lgdi32
WIN_PACKAGES := mingw-w64 wine wine64 xvfb xauth

$(WIN)/gen/test_list.h: tests/list.sh $(WIN_TEST_SRC)
	@mkdir -p $(@D)
	sh tests/list.sh $@ $(WIN_TEST_SRC)

$(WIN_BIN)/sky-tests.exe: $(WIN_TEST_SRC) tests/windows/gl_entry.c tests/test.h $(WIN_FRONT_SRC) $(CLI_HDR) $(STAB_SRC) $(REF_SRC) $(WIN)/gen/test_list.h $(WIN)/libsky.a
	@mkdir -p $(@D)
	$(WIN_CC) $(WIN_PROG_CFLAGS) -Itests -Itools -I$(WIN)/gen -o $@ $(WIN_TEST_SRC) tests/windows/gl_entry.c \
		$(WIN_FRONT_SRC) tools/stability.c $(REF_SRC) $(WIN)/libsky.a $(WIN_GL_LIBS)

$(WIN_BIN)/sky-render.exe: demo/render.c $(WIN_FRONT_SRC) $(CLI_HDR) $(WIN)/libsky.a
	@mkdir -p $(@D)
	$(WIN_CC) $(WIN_PROG_CFLAGS) -o $@ demo/render.c $(WIN_FRONT_SRC) $(WIN)/libsky.a $(WIN_GL_LIBS)

# the same front end linked against the DLL (SKY_DLL: sky.h's functions are dllimport), the
# DLL beside it
$(WIN_BIN)/sky-render-dll.exe: demo/render.c $(WIN_FRONT_SRC) $(CLI_HDR) $(WIN)/sky.dll
	@mkdir -p $(@D)
	cp $(WIN)/sky.dll $(WIN_BIN)/sky.dll
	$(WIN_CC) $(WIN_PROG_CFLAGS) -DSKY_DLL -o $@ demo/render.c $(WIN_FRONT_SRC) $(WIN)/libsky.dll.a $(WIN_GL_LIBS)

# and linked against the amalgamation alone, compiled by MinGW-w64 at the flags it promises
$(WIN_BIN)/sky-render-amalgamation.exe: demo/render.c $(WIN_FRONT_SRC) $(CLI_HDR) $(AMALG)/sky.c $(AMALG)/sky.h
	@mkdir -p $(WIN)/obj/amalgamation
	$(WIN_CC) -std=c11 -Wall -Wextra -Wshadow -pedantic -Wvla -Werror -O2 -c -o $(WIN)/obj/amalgamation/sky.o $(AMALG)/sky.c
	$(WIN_CC) $(WIN_PROG_CFLAGS) -o $@ demo/render.c $(WIN_FRONT_SRC) $(WIN)/obj/amalgamation/sky.o $(WIN_GL_LIBS)

test-windows: all $(BUILD)/gen/sky_blobs.c
	@sh tools/deps.sh $(WIN_PACKAGES)
	@$(MAKE) --no-print-directory $(WIN)/libsky.a $(WIN)/sky.dll $(WIN)/include/sky.h $(WIN_BIN)/sky-tests.exe \
		$(WIN_BIN)/sky-render.exe $(WIN_BIN)/sky-render-dll.exe $(WIN_BIN)/sky-render-amalgamation.exe
	@sh tests/windows/run.sh $(BIN) $(WIN_BIN) $(WIN)

# ---- install ----------------------------------------------------------------------
install: all
	install -d $(DESTDIR)$(PREFIX)/include $(DESTDIR)$(PREFIX)/lib/pkgconfig $(DESTDIR)$(PREFIX)/bin
	install -m 644 sky/sky.h $(DESTDIR)$(PREFIX)/include/sky.h
	install -m 644 $(LIB)/libsky.a $(DESTDIR)$(PREFIX)/lib/libsky.a
	install -m 755 $(LIB)/libsky.so $(DESTDIR)$(PREFIX)/lib/$(SKY_SONAME)
	ln -sf $(SKY_SONAME) $(DESTDIR)$(PREFIX)/lib/libsky.so
	install -m 755 $(BIN)/sky-render $(BIN)/sky-demo $(DESTDIR)$(PREFIX)/bin/
	sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@LIBDIR@|$${prefix}/lib|' -e 's|@INCLUDEDIR@|$${prefix}/include|' \
		-e 's|@VERSION@|$(SKY_VERSION)|' sky/sky.pc.in > $(DESTDIR)$(PREFIX)/lib/pkgconfig/sky.pc

# ---- CMake: make cmake ----------------------------------------------------------
# The library through CMakeLists.txt (for projects that consume it natively)
# into build/cmake, warnings as errors, static unless CMAKE_ARGS says
# otherwise (make cmake CMAKE_ARGS=-DBUILD_SHARED_LIBS=ON). Both builds take
# their sources from sky/sources.txt.
.PHONY: cmake
CMAKE_ARGS ?=
cmake:
	@sh tools/deps.sh cmake
	cmake -S . -B $(BUILD)/cmake -DSKY_WERROR=ON $(CMAKE_ARGS)
	cmake --build $(BUILD)/cmake

# ---- assets ---------------------------------------------------------------------------
# Rebuilds textures/ from their origins (see textures/README.md). Needs
# Debian's stellarium-data, which it downloads and unpacks into build/.
textures: $(BIN)/texgen $(BIN)/catgen
	@sh tools/fetch-stellarium.sh $(BUILD)/stellarium
	@sh tools/fetch-npm.sh d3-celestial 0.7.35 $(BUILD)/d3-celestial package/data/stars.8.json
	$(BIN)/texgen --out textures --photo $(BUILD)/stellarium/usr/share/stellarium/textures/earth-clouds.png --crop 0,20,176 \
	    --moon $(BUILD)/stellarium/usr/share/stellarium/textures/moon.png
	$(BIN)/catgen --stars $(BUILD)/d3-celestial/package/data/stars.8.json \
	    --pm $(BUILD)/stellarium/usr/share/stellarium/stars/default/hip_pm.dat --max-mag 6.5 --out textures/stars.dat \
	    --map textures/starmap.png --mw $(BUILD)/d3-celestial/package/data/mw.json

# Rebuilds sky/planet_tables.c (the VSOP87D series, truncated) from the
# npm package astronomia, and tests/data/planets_reference.txt (the planets
# as PyEphem sees them: Debian's python3-ephem, hence /usr/bin/python3).
planet-tables: $(BIN)/vsopgen
	@sh tools/fetch-npm.sh astronomia 4.2.0 $(BUILD)/astronomia package/data/vsop87Dmars.js
	$(BIN)/vsopgen --data $(BUILD)/astronomia/package/data --out sky/planet_tables.c
	/usr/bin/python3 tools/planet-reference.py > tests/data/planets_reference.txt.tmp
	mv tests/data/planets_reference.txt.tmp tests/data/planets_reference.txt

# The pictures of README.md and docs/ (docs/img), rendered by sky-render and
# the programs.
screenshots: all $(BIN)/pngcrop
	@sh tools/screenshots.sh

clean:
	rm -rf $(BUILD)
