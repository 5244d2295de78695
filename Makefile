# Shadow-rendering demo suite. `make help` lists the targets.
#
# Build outputs go to build/ (or build-san/ with SANITIZE=1: AddressSanitizer
# and UBSan). The GL loader is generated here by Debian's glad, from its
# bundled Khronos XML (--reproducible), never fetched or committed.

SANITIZE ?= 0
# Parallel by default; sub-makes share the top one's job slots.
ifeq ($(MAKELEVEL),0)
MAKEFLAGS += -j$(shell nproc)
endif
ifeq ($(SANITIZE),1)
BUILD ?= build-san
SAN_FLAGS := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
else
BUILD ?= build
SAN_FLAGS :=
endif

CC ?= cc
PKGS := glfw3 egl cglm libcjson assimp stb
PKG_CFLAGS = $(shell pkg-config --cflags $(PKGS))
PKG_LIBS = $(shell pkg-config --libs $(PKGS))
CFLAGS ?= -O2 -g
ALL_CFLAGS = -std=c11 -fopenmp -Wall -Wextra -Werror -D_XOPEN_SOURCE=700 -DGLFW_INCLUDE_NONE \
	$(SAN_FLAGS) $(LAYER_INCLUDES) $(PKG_CFLAGS) $(CFLAGS)
LDLIBS = $(PKG_LIBS) -lembree3 -ldl -lm
LDFLAGS += $(SAN_FLAGS) -fopenmp

# GL 3.3 core plus the extensions used behind a check.
GL_EXTENSIONS := GL_KHR_debug,GL_EXT_depth_bounds_test,GL_ARB_clip_control
GLAD_C := $(BUILD)/glad/src/gl.c
GLAD_H := $(BUILD)/glad/include/glad/gl.h

# Layers, each compiled with only the include paths it may use, so that a
# wrong include fails to build (README, "Layout"):
#   common/data      scenes, meshes, camera, dumps, images, files, flags: no GL
#   common/measure   the reference and the metrics: data only, no GL
#   common/gl        contexts, target, shaders, HUD, the lit scene, capture,
#                    the technique interface: data and the GL loader
#   demos/           the techniques (demos/lib: what several share): gl, data
#   common/programs  the frame loop, the frame's host (technique_host) and
#                    every main: all of common; only the
#                    main files see demos/ (for the registry)
GLAD_INCLUDE = -I$(BUILD)/glad/include
INCLUDES_data = -Icommon/data
INCLUDES_measure = -Icommon/measure $(INCLUDES_data)
INCLUDES_gl = -Icommon/gl $(INCLUDES_data) $(GLAD_INCLUDE)
INCLUDES_demos = -Idemos -Idemos/lib $(INCLUDES_gl)
INCLUDES_programs = -Icommon/programs -Icommon/measure $(INCLUDES_gl)
$(BUILD)/common/data/%.o: LAYER_INCLUDES = $(INCLUDES_data)
$(BUILD)/common/measure/%.o: LAYER_INCLUDES = $(INCLUDES_measure)
$(BUILD)/common/gl/%.o: LAYER_INCLUDES = $(INCLUDES_gl)
$(BUILD)/glad/gl.o: LAYER_INCLUDES = $(GLAD_INCLUDE)
$(BUILD)/demos/%.o: LAYER_INCLUDES = $(INCLUDES_demos)
$(BUILD)/common/programs/%.o: LAYER_INCLUDES = $(INCLUDES_programs)
$(BUILD)/common/programs/main_%.o: LAYER_INCLUDES = $(INCLUDES_programs) -Idemos
$(BUILD)/main_%.o: LAYER_INCLUDES = $(INCLUDES_programs) -Idemos
$(BUILD)/tests/%.o: LAYER_INCLUDES = -Itests -Idemos -Idemos/lib $(INCLUDES_programs)

COMMON_SRC := $(wildcard common/data/*.c common/measure/*.c common/gl/*.c) common/programs/app.c common/programs/compare.c \
	common/programs/technique_host.c
DEMO_SRC := $(filter-out demos/registry.c,$(wildcard demos/*.c))
DEMOS := $(patsubst demos/%.c,%,$(DEMO_SRC))
TEST_SRC := $(wildcard tests/test_*.c)
# Every C file of the suite, for the format's check.
C_FILES := $(wildcard demos/*.[ch] demos/lib/*.[ch] common/*/*.[ch] tests/*.[ch])
TEST_SUPPORT := $(BUILD)/tests/support.o
TESTS := $(patsubst tests/%.c,$(BUILD)/tests/%,$(TEST_SRC))

LIB := $(BUILD)/libshadows.a
LIB_OBJ := $(patsubst %.c,$(BUILD)/%.o,$(COMMON_SRC) $(DEMO_SRC) $(wildcard demos/lib/*.c) demos/registry.c) \
	$(BUILD)/glad/gl.o
# Programs whose main is common/programs/main_NAME.c (the reference, the
# metrics, the benchmark, the scene generator, the stress suite, the
# web build's model baker); the
# demos' main is common/programs/main_single.c.
TOOLS := raytrace shadowdiff bench scenegen stress report bake
PROGRAMS := $(BUILD)/shadows $(addprefix $(BUILD)/,$(DEMOS) $(TOOLS))
STANDARD_SCENES := assets/scenes/simple.json assets/scenes/bunny.json assets/scenes/teapot.json
# Scenes with area lights: their truth has penumbrae.
SOFT_SCENES := assets/scenes/soft_table.json assets/scenes/soft_sun.json

.PHONY: all deps demo gallery test test-all sanitizer-quick web web-bench device-bundle bench stress ruler report readme-report scenes update-golden test-technique readme-flags format clean help
all: $(PROGRAMS) $(TESTS)

help:
	@echo "make deps           install the Debian packages (apt-get; sudo when not root)"
	@echo "make demo           build, then the interactive window (with a display) or the gallery"
	@echo "make gallery        render every technique on each standard and soft scene and two real models to out/gallery/"
	@echo "make test           build and run the quick tier of the tests, plain and under ASan+UBSan"
	@echo "make test-all       the whole matrix of the tests (make report runs it)"
	@echo "make bench          time and measure every technique: out/bench/ (QUICK=1: a short run)"
	@echo "make stress         adversarial scenes through every technique against the reference: out/stress/"
	@echo "make ruler          out/ruler/: the reference's own noise under area lights"
	@echo "make report         make test-all, make bench, make stress, make ruler, then make readme-report (QUICK=1: short runs)"
	@echo "make readme-report  out/report/ and README.md's current figures from the runs already in out/"
	@echo "make scenes         regenerate the generated scenes in assets/scenes/ (city_*.json, dense.json, stacked_*)"
	@echo "make update-golden  re-record tests/golden/*.png on purpose (ONLY=NAME: that case, or a technique's; say why in the commit)"
	@echo "make test-technique one technique's checks, ONLY=NAME: its golden cases and tests/test_NAME.c"
	@echo "make readme-flags   rewrite README.md's table of keys and flags from the programs' flag tables"
	@echo "make format         rewrite the C files in .clang-format's style (make test checks it)"
	@echo "make web            out/web/: every technique in a web page (Emscripten, WebGL 2)"
	@echo "make web-bench      the page's frame time in headless Chromium: out/web/bench.md"
	@echo "make device-bundle  out/device/: build/bench and its libraries, for tests/device_bench.sh on a GPU machine"
	@echo "make clean          remove build/, build-san/ and out/"

DEB_PACKAGES := build-essential pkg-config python3-glad libglfw3-dev libegl-dev \
	libegl-mesa0 libgl1-mesa-dri libosmesa6 libcglm-dev libstb-dev libassimp-dev \
	assimp-testmodels libcjson-dev libembree-dev libcmocka-dev gnuplot-nox xvfb xauth xdotool ffmpeg chromium \
	clang-format emscripten node-acorn
deps:
	@if [ "$$(id -u)" = 0 ]; then SUDO=; elif command -v sudo >/dev/null; then SUDO=sudo; \
	else echo "make deps: not root and no sudo; run as root:"; \
	echo "  apt-get update && apt-get install -y --no-install-recommends $(DEB_PACKAGES)"; exit 1; fi; \
	$$SUDO env DEBIAN_FRONTEND=noninteractive apt-get update -qq && \
	$$SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $(DEB_PACKAGES)

demo: $(PROGRAMS)
	@if [ -n "$$DISPLAY$$WAYLAND_DISPLAY" ]; then $(BUILD)/shadows; else $(MAKE) --no-print-directory gallery; fi

# Real glTF models from assimp-testmodels (make deps): a textured one a
# scene file includes over a ground, one seen by its own camera.
GALLERY_MODELS := $(if $(wildcard /usr/share/assimp/models/glTF/CesiumMilkTruck),assets/scenes/truck.json) \
	$(wildcard /usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb)
gallery: $(PROGRAMS)
	$(BUILD)/shadows --gallery out/gallery $(STANDARD_SCENES) assets/scenes/long_view.json $(SOFT_SCENES) \
		$(GALLERY_MODELS)

# First the C files' format (.clang-format), the comments' check
# (tests/check_comments.sh: no measured figure or tracker number in a
# comment) and the README's links' (tests/check_links.sh), each itself
# checked first; the web page where emcc is installed
# (test_web runs it in headless Chromium) and its JSON reader against
# Debian's cJSON (tests/web/check_json.sh); then the suite,
# twice, plain and built with ASan+UBSan (build-san/), both at once
# (tests/run.sh).
# `make test SANITIZE=1` runs only the sanitizer pass. make test is the
# quick tier (within CI's 15 minutes: sweeps strided, the sanitizer pass a
# subset), make test-all the whole matrix (tests/run.sh's TEST_TIER).
test-all: export TEST_TIER = all
test-all: test
test: $(PROGRAMS) $(TESTS)
	@clang-format --dry-run --Werror $(C_FILES) || { echo "make test: C files not in .clang-format's style: run make format"; exit 1; }
	@tests/check_comments.sh --self-test && tests/check_comments.sh
	@tests/check_links.sh --self-test && tests/check_links.sh
	@$(if $(WEB_HAVE_EMCC),$(MAKE) --no-print-directory web,echo "make test: no emcc, so no web page: test_web \
		skips (make deps installs Debian's emscripten)")
	@tests/web/check_json.sh
ifeq ($(SANITIZE),1)
	@tests/run.sh $(BUILD)
else
	@$(MAKE) --no-print-directory SANITIZE=1 $(if $(filter all,$(TEST_TIER)),all,sanitizer-quick)
	@tests/run.sh $(BUILD) build-san
endif

# The programs, and the tests the quick tier runs under the sanitizers
# (tests/sanitizer_quick.list): the sanitizer build's share of make test.
SANITIZER_QUICK := $(shell grep -v '^\#' tests/sanitizer_quick.list)
sanitizer-quick: $(PROGRAMS) $(addprefix $(BUILD)/tests/,$(SANITIZER_QUICK))

# The standard scenes' whole sweeps, nothing moving, the lights moving, and
# the camera moving (its yaw, and dolly's walk: where each row's shimmer is
# measured); then each technique's defaults on the cities and the dense scene, skips on
# against --no-skip, with time per frame against object count
# (out/bench/scaling.png, and cities-light/scaling.png with the lights moving).
# The cities see the same street, so their plot is cost against object
# count; dense (one view, many triangles) is timed on its own. Last, the
# shadow maps' whole sweeps (PCSS, the moment filters, the hard kernels) on
# the area lights' scenes and the flat boxes, still and with the lights
# moving, with planar's and volumes' sweeps of --light-samples: the soft
# ruler's figures (make report's "Soft shadows").
# Then the scenes where what is hidden, not what is outside, is to skip:
# the city across from its edge with unranged lamps, and the engines.
# Then volumes' sweep with the eye in a shadow (z-fail's caps against ZP+'s
# near-plane count): a slab's shadow with the light behind the eye and
# ahead of it, a closed model's, an open one's under a sun.
# Last, perspective shadow maps' sweep on its hard cases: the light in
# front of the viewer and behind it, a caster behind the camera, a point
# light far above the view and one among the receivers.
BENCH_HIDDEN := assets/scenes/street.json assets/scenes/engine.json
# The street of 64 shadowed lamps, measured at lamp 27 (it lights half the
# view): still, that lamp moving, every lamp moving. Of the maps' sweep the
# defaults (hw: many lights), poisson (the default of fewer lights) and the
# budget: the moment filters' maps of 64 lamps do not fit a software
# rasterizer's memory.
BENCH_LAMPS := --light 27 --technique shadowmap --technique volumes --configs-with budget \
	--configs-with 'filter poisson' \
	assets/scenes/lamps_64.json
BENCH_CITIES := $(patsubst %,assets/scenes/city_%.json,100 300 1000 3000)
BENCH_SOFT := $(patsubst %,assets/scenes/%.json,soft_table soft_sun flat_boxes flat_boxes_point)
BENCH_MAPS := --technique shadowmap --technique psm --technique cascades --technique hybrid
BENCH_SAMPLED := --technique planar --technique volumes
BENCH_PSM_CASES := $(patsubst %,assets/scenes/%.json,long_view long_view_behind psm_caster_behind psm_point_high \
	psm_point_low)
BENCH_EYE_IN_SHADOW := assets/scenes/eye_in_shadow.json $(patsubst %,tests/data/vol_eye_in_%.json,shadow_light_ahead \
	bunny_shadow wuson_shadow)
QUICK_FLAG := $(if $(filter 1,$(QUICK)),--quick)
bench: $(PROGRAMS)
	$(BUILD)/bench $(QUICK_FLAG) --motion static --out out/bench/static
	$(BUILD)/bench $(QUICK_FLAG) --motion light --out out/bench/light
	$(BUILD)/bench $(QUICK_FLAG) --motion camera --out out/bench/camera
	$(BUILD)/bench $(QUICK_FLAG) --motion dolly --out out/bench/dolly
	$(BUILD)/bench $(QUICK_FLAG) --configs defaults --skips-compare --scaling --motion static --out out/bench \
		$(BENCH_CITIES)
	$(BUILD)/bench $(QUICK_FLAG) --configs defaults --skips-compare --scaling --motion light \
		--out out/bench/cities-light $(BENCH_CITIES)
	$(BUILD)/bench $(QUICK_FLAG) --configs defaults --skips-compare --motion static --out out/bench/dense \
		assets/scenes/dense.json
	$(BUILD)/bench $(QUICK_FLAG) --configs defaults --skips-compare --motion light --out out/bench/dense-light \
		assets/scenes/dense.json
	$(BUILD)/bench $(QUICK_FLAG) $(BENCH_MAPS) $(BENCH_SAMPLED) --motion static --out out/bench/soft $(BENCH_SOFT)
	$(BUILD)/bench $(QUICK_FLAG) $(BENCH_MAPS) $(BENCH_SAMPLED) --motion light --out out/bench/soft-light $(BENCH_SOFT)
	$(BUILD)/bench $(QUICK_FLAG) --configs defaults --skips-compare --motion static --out out/bench/hidden \
		$(BENCH_HIDDEN)
	$(BUILD)/bench $(QUICK_FLAG) --configs defaults --skips-compare --motion light --out out/bench/hidden-light \
		$(BENCH_HIDDEN)
	$(BUILD)/bench $(QUICK_FLAG) --technique volumes --motion static --out out/bench/eye-in-shadow \
		$(BENCH_EYE_IN_SHADOW)
	$(BUILD)/bench $(QUICK_FLAG) --technique psm --motion static --out out/bench/psm-cases $(BENCH_PSM_CASES)
	$(BUILD)/bench $(QUICK_FLAG) $(BENCH_LAMPS) --motion static --out out/bench/lamps
	$(BUILD)/bench $(QUICK_FLAG) $(BENCH_LAMPS) --motion lamp --out out/bench/lamps-lamp
	$(BUILD)/bench $(QUICK_FLAG) $(BENCH_LAMPS) --motion lamps --out out/bench/lamps-moving

# Every case of build/stress's table, every technique configuration
# against the reference: out/stress/table.md; fails unless every row
# passes, is refused or unmeasured (`make test` runs cases that pass today;
# QUICK=1 runs those alone).
stress: $(PROGRAMS)
	$(BUILD)/stress $(QUICK_FLAG) --out out/stress

# The reference's own noise under an area light: each soft scene traced
# with raytrace's default rays and with RULER_RAYS, compared by shadowdiff
# (the many-ray trace as the truth): out/ruler/SCENE.json, and RULER_RAYS
# in out/ruler/rays.
RULER_SCENES := soft_table soft_sun
RULER_RAYS := $(if $(filter 1,$(QUICK)),1024,4096)
ruler: $(BUILD)/raytrace $(BUILD)/shadowdiff
	@rm -rf out/ruler && mkdir -p out/ruler && echo $(RULER_RAYS) > out/ruler/rays
	@for s in $(RULER_SCENES); do \
		$(BUILD)/raytrace --scene assets/scenes/$$s.json --dump out/ruler/$$s-default && \
		$(BUILD)/raytrace --scene assets/scenes/$$s.json --light-samples $(RULER_RAYS) --dump out/ruler/$$s-many && \
		$(BUILD)/shadowdiff out/ruler/$$s-many out/ruler/$$s-default --json > out/ruler/$$s.json || exit 1; \
		echo "out/ruler/$$s.json"; \
	done

# The whole matrix of the tests, then the runs, one after the other so
# that none is timed under another's load, then the pages and the README's
# figures from them.
# build/bench and the shared libraries it links, but the C runtime's
# (glibc's, libstdc++ and libgcc_s: a GPU driver loaded beside them needs
# the machine's own), in one archive: tests/device_bench.sh runs it on a
# machine without the build's packages.
DEVICE_BUNDLE_KEEP_HOST := /(libc|libm|libpthread|libdl|librt|libstdc\+\+|libgcc_s)\.so
device-bundle: $(BUILD)/bench
	rm -rf out/device && mkdir -p out/device/lib
	cp $(BUILD)/bench out/device/
	ldd $(BUILD)/bench | awk '$$3 ~ /^\// {print $$3}' | grep -v -E '$(DEVICE_BUNDLE_KEEP_HOST)' | \
		xargs -I{} cp -L {} out/device/lib/
	tar -C out/device -cJf out/device/bench.tar.xz bench lib
	rm -rf out/device/bench out/device/lib
	@ls -l out/device/bench.tar.xz

report: $(PROGRAMS)
	@$(MAKE) --no-print-directory test-all
	@$(MAKE) --no-print-directory bench
	@$(MAKE) --no-print-directory stress
	@$(MAKE) --no-print-directory ruler
	@$(MAKE) --no-print-directory readme-report

# out/report/ (index.md, index.html, compact.md, each run's report.md and
# plots) from the runs already in out/, and README.md's current figures:
# out/report/compact.md between the lines <!-- report:begin --> and
# <!-- report:end -->, a blank line either side.
readme-report: $(BUILD)/report
	$(BUILD)/report --readme README.md

# The generated scenes are committed; test_scenegen checks they are what
# the generator writes.
scenes: $(BUILD)/scenegen
	$(BUILD)/scenegen --out assets/scenes

# The screenshot test's table of cases records its own goldens (EGL, the
# flags it checks with); ONLY="NAME..." re-records just those cases.
update-golden: $(PROGRAMS) $(BUILD)/tests/test_render
	BUILD=$(BUILD) $(BUILD)/tests/test_render --record $(ONLY)

# A technique's own checks while it is written (README, "Adding a
# technique"), ONLY=NAME: its golden cases (test_render --check) and its
# tests/test_NAME.c; make test then checks the rest (its flags in the
# README's table among them).
test-technique: $(PROGRAMS) $(BUILD)/tests/test_render \
		$(patsubst tests/%.c,$(BUILD)/tests/%,$(wildcard tests/test_$(ONLY).c))
	@test -n "$(ONLY)" || { echo "make test-technique: which technique? ONLY=NAME"; exit 2; }
	BUILD=$(BUILD) $(BUILD)/tests/test_render --check $(ONLY)
	ONLY="test_$(ONLY)" tests/run.sh $(BUILD)

# README.md's "Keys and flags": what build/shadows --flags-markdown prints,
# between the lines <!-- flags:begin --> and <!-- flags:end -->, a blank
# line either side (test_cli fails while the copy there differs).
README_FLAGS := $(BUILD)/readme-flags.md
format:
	clang-format -i $(C_FILES)

readme-flags: $(BUILD)/shadows
	$(BUILD)/shadows --flags-markdown > $(README_FLAGS)
	awk -v table=$(README_FLAGS) ' \
		/^<!-- flags:end -->$$/ { inside = 0; ends++ } \
		!inside { print } \
		/^<!-- flags:begin -->$$/ { \
			inside = 1; begins++; print ""; \
			while ((got = (getline line < table)) > 0) print line; \
			if (got < 0) { print table ": cannot read" > "/dev/stderr"; unread = 1; exit 1 } \
			print "" } \
		END { if (unread) exit 1; if (begins != 1 || ends != 1 || inside) { \
			print "README.md: expected one <!-- flags:begin --> line, then one <!-- flags:end -->" > "/dev/stderr"; \
			exit 1 } }' README.md > $(BUILD)/README.md.new
	mv $(BUILD)/README.md.new README.md

clean:
	rm -rf build build-san build-web out

include common/web/web.mk

# The extension list, rewritten only when it changes, so that a build
# made before an extension was added regenerates the loader.
GLAD_EXTENSIONS_FILE := $(BUILD)/glad/extensions
$(shell mkdir -p $(BUILD)/glad && (echo '$(GL_EXTENSIONS)' | cmp -s - $(GLAD_EXTENSIONS_FILE) || \
	echo '$(GL_EXTENSIONS)' > $(GLAD_EXTENSIONS_FILE)))

# One run of glad makes both (a grouped target: with -j, two rules racing
# to create the same directories made glad fail now and then).
$(GLAD_C) $(GLAD_H) &: $(GLAD_EXTENSIONS_FILE)
	@mkdir -p $(BUILD)/glad
	glad --quiet --reproducible --api gl:core=3.3 --extensions $(GL_EXTENSIONS) \
		--out-path $(BUILD)/glad c

$(BUILD)/glad/gl.o: $(GLAD_C)
	$(CC) $(ALL_CFLAGS) -c $< -o $@

$(BUILD)/%.o: %.c $(GLAD_H)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -MMD -MP -c $< -o $@

$(LIB): $(LIB_OBJ)
	rm -f $@ && ar rcs $@ $^

$(BUILD)/shadows: $(BUILD)/common/programs/main_registry.o $(LIB)
	$(CC) $(LDFLAGS) $^ $(LDLIBS) -o $@

$(addprefix $(BUILD)/,$(TOOLS)): $(BUILD)/%: $(BUILD)/common/programs/main_%.o $(LIB)
	$(CC) $(LDFLAGS) $^ $(LDLIBS) -o $@

# Each demo binary hosts one technique: the same main, told which one.
$(BUILD)/main_%.o: common/programs/main_single.c $(GLAD_H)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -MMD -MP -DDEMO_TECHNIQUE=$*_technique -c $< -o $@

$(addprefix $(BUILD)/,$(DEMOS)): $(BUILD)/%: $(BUILD)/main_%.o $(LIB)
	$(CC) $(LDFLAGS) $^ $(LDLIBS) -o $@

$(BUILD)/tests/%: $(BUILD)/tests/%.o $(TEST_SUPPORT) $(LIB)
	$(CC) $(LDFLAGS) $^ $(LDLIBS) -lcmocka -o $@

# Objects of tests and programs are kept: they are not throw-away.
.SECONDARY:

-include $(shell find $(BUILD) -name '*.d' 2>/dev/null)
# The .d files are the compiler's (-MMD), never remade: without this empty
# rule make would try its built-in "%: %.o" on each included one and
# compile build/main_psm.d.o from main_single.c, printing errors.
$(BUILD)/%.d: ;
