# The web page (make web, included by the Makefile): every technique of
# build/shadows compiled with Debian's Emscripten for WebGL 2, in
# out/web/index.html and out/web/shadows.js (the wasm, the shaders, the
# page's scenes and their models embedded, so that the page works from
# file:// as from any static server).
#
# The same sources as the native programs, except the platform's:
# the browser's context (common/web/context_browser.c) instead of GLFW's
# window, EGL and OSMesa; model files as mesh packs and glTF scenes as
# scene packs, written natively by build/bake (common/web/mesh_file_web.c,
# common/web/scene_gltf_web.c), instead of assimp; no ray
# tracer (Embree is native only: common/web/raytrace_web.c), so compare
# mode shows truths baked natively (common/measure/truth_bake.h); cJSON's
# API over the browser's JSON (common/web/cjson_browser.c).

WEB_BUILD := build-web
WEB_OUT := out/web
# emcc runs under Debian's own python3 (the first python3 on PATH may be
# another, under which it fails) and finds Debian's node-acorn.
EMCC := env PATH=/usr/bin:$$PATH NODE_PATH=/usr/share/nodejs emcc
WEB_HAVE_EMCC := $(shell command -v emcc >/dev/null 2>&1 && echo yes)

# What the page shows: the tours, the scenes they step through, the
# standard and soft scenes, build/scenegen's glTF scenes, and the models
# these use; the models and glTF scenes as packs (WEB_PACKS).
WEB_TOURS := $(wildcard assets/tours/*.json)
WEB_TOUR_SCENES := $(patsubst ../scenes/%,assets/scenes/%,$(shell sed -n 's/.*"scene": *"\([^"]*\)".*/\1/p' $(WEB_TOURS)))
WEB_MODELS := assets/bunny.obj assets/teapot.obj
WEB_GLTF_SCENES := assets/scenes/fence.gltf assets/scenes/stained_glass.gltf
# The scene files embedded as they are: a glTF scene a tour steps through
# goes as its pack alone, at the same path.
WEB_SCENES := $(filter-out $(WEB_GLTF_SCENES),$(sort $(STANDARD_SCENES) $(SOFT_SCENES) $(WEB_TOUR_SCENES)))
WEB_PACKS := $(WEB_MODELS) $(WEB_GLTF_SCENES)
# The truths compare mode shows in the page: every tour, and each
# standard, soft and glTF scene in compare mode, run natively (EGL) at
# build/shadows' default size, the page's canvas in compare mode, baking
# the truths of its compare steps into WEB_BAKING/RUN/truths/ beside its
# pictures and compare figures (figures.txt), which test_web holds the
# page's to; then all of them in WEB_TRUTHS.
WEB_TRUTHS := $(WEB_BUILD)/truths
WEB_BAKING := $(WEB_BUILD)/baking
WEB_BAKED := $(patsubst assets/tours/%.json,$(WEB_BAKING)/tours/%/done,$(WEB_TOURS)) \
	$(patsubst assets/scenes/%.json,$(WEB_BAKING)/scenes/%/done,$(STANDARD_SCENES) $(SOFT_SCENES)) \
	$(patsubst assets/scenes/%.gltf,$(WEB_BAKING)/scenes/%/done,$(WEB_GLTF_SCENES))

# Native sources the page has no use for or cannot link; common/web/ has
# the browser's versions of what it needs of them.
WEB_NATIVE_ONLY := common/gl/context_glfw.c common/gl/context_egl.c common/gl/context_osmesa.c \
	common/data/mesh_file.c common/data/scene_gltf.c common/data/gltf_write.c common/measure/raytrace.c
WEB_SRC := $(filter-out $(WEB_NATIVE_ONLY),$(COMMON_SRC)) $(DEMO_SRC) $(wildcard demos/lib/*.c) demos/registry.c \
	$(wildcard common/web/*.c) common/programs/main_registry.c
WEB_OBJ := $(patsubst %.c,$(WEB_BUILD)/%.o,$(WEB_SRC)) $(WEB_BUILD)/glad/gl.o
WEB_GLAD_C := $(WEB_BUILD)/glad/src/gl.c
WEB_GLAD_H := $(WEB_BUILD)/glad/include/glad/gl.h
# The header-only and header libraries' headers, without the rest of
# /usr/include (which would shadow Emscripten's own C library).
WEB_INCLUDE := $(WEB_BUILD)/include
WEB_HEADERS := $(WEB_INCLUDE)/cglm $(WEB_INCLUDE)/cjson $(WEB_INCLUDE)/stb
# -Wno-align-mismatch: scene_object's model matrices are _Alignas(16), as
# cglm's mat4 parameters want, but a decayed array's type cannot say so
# (clang warns, gcc does not).
WEB_CFLAGS := -std=c11 -O2 -Wall -Wextra -Werror -Wno-align-mismatch -D_XOPEN_SOURCE=700 -DGLFW_INCLUDE_NONE \
	-I$(WEB_INCLUDE) \
	-I$(WEB_INCLUDE)/cjson -I$(WEB_INCLUDE)/stb \
	-I$(WEB_BUILD)/glad/include -Icommon/data -Icommon/measure -Icommon/gl -Icommon/programs -Idemos -Idemos/lib
# What the page's menu asks the program (common/programs/app.c).
WEB_MENU_FUNCTIONS := _app_technique_name,_app_technique_shown,_app_compare_shown,_app_scene_shown
WEB_LDFLAGS := -O2 -sUSE_GLFW=3 -sMIN_WEBGL_VERSION=2 -sMAX_WEBGL_VERSION=2 -sALLOW_MEMORY_GROWTH=1 \
	-sSINGLE_FILE=1 -sINVOKE_RUN=0 -sEXPORTED_RUNTIME_METHODS=callMain,FS,UTF8ToString \
	-sEXPORTED_FUNCTIONS=_main,_emscripten_set_main_loop_timing,$(WEB_MENU_FUNCTIONS)
# Embedded at the paths the programs look for (path_in_project: /shaders,
# /assets/scenes; a tour's scenes relative to it); the models and glTF
# scenes as packs at their files' own paths.
WEB_EMBED := --embed-file shaders@/shaders $(foreach f,$(WEB_TOURS) $(WEB_SCENES),--embed-file $(f)@/$(f)) \
	$(foreach p,$(WEB_PACKS),--embed-file $(WEB_BUILD)/$(p)@/$(p)) --embed-file $(WEB_TRUTHS)@/truths

.PHONY: web web-bench
ifeq ($(WEB_HAVE_EMCC),yes)
web: $(WEB_OUT)/index.html $(WEB_OUT)/shadows.js
else
web:
	@echo "make web: emcc not found: make deps installs Debian's emscripten"; exit 1
endif

# The page's frame time in headless Chromium: out/web/bench.md.
web-bench: web $(BUILD)/shadows
	common/web/page_bench.sh

$(WEB_OUT)/index.html: common/web/index.html
	@mkdir -p $(dir $@)
	cp $< $@

$(WEB_OUT)/shadows.js: $(WEB_OBJ) $(addprefix $(WEB_BUILD)/,$(WEB_PACKS)) $(wildcard shaders/*) $(WEB_TOURS) common/web/web.mk \
		$(WEB_SCENES) $(WEB_BAKING)/done
	@mkdir -p $(dir $@)
	@echo "emcc -o $@" && $(EMCC) $(WEB_LDFLAGS) $(WEB_OBJ) $(WEB_EMBED) -o $@

# One run's truths, pictures and figures (the folder's name says which).
WEB_BAKE = rm -rf $(dir $@) && mkdir -p $(dir $@)truths && \
	$(BUILD)/shadows --backend egl $(1) --bake-truths $(dir $@)truths --screenshot $(dir $@)$(2) > $(dir $@)figures.txt && \
	touch $@

$(WEB_BAKING)/tours/%/done: assets/tours/%.json $(BUILD)/shadows $(WEB_SCENES) $(WEB_GLTF_SCENES) $(WEB_MODELS)
	$(call WEB_BAKE,--tour $<,step.png)

$(WEB_BAKING)/scenes/%/done: assets/scenes/%.json $(BUILD)/shadows $(WEB_MODELS)
	$(call WEB_BAKE,--scene $< --compare,compare.png)

$(WEB_BAKING)/scenes/%/done: assets/scenes/%.gltf $(BUILD)/shadows
	$(call WEB_BAKE,--scene $< --compare,compare.png)

$(WEB_BAKING)/done: $(WEB_BAKED)
	rm -rf $(WEB_TRUTHS) && mkdir -p $(WEB_TRUTHS)
	for run in $(WEB_BAKED:/done=/truths); do cp -R $$run/. $(WEB_TRUTHS); done
	touch $@

$(addprefix $(WEB_BUILD)/,$(WEB_PACKS)): $(WEB_BUILD)/%: % $(BUILD)/bake
	@mkdir -p $(dir $@)
	$(BUILD)/bake $< $@

$(WEB_HEADERS):
	@mkdir -p $(WEB_INCLUDE)
	ln -sfn /usr/include/$(notdir $@) $@

$(WEB_GLAD_C) $(WEB_GLAD_H) &: $(GLAD_EXTENSIONS_FILE)
	@mkdir -p $(WEB_BUILD)/glad
	glad --quiet --reproducible --api gl:core=3.3 --extensions $(GL_EXTENSIONS) --out-path $(WEB_BUILD)/glad c

$(WEB_BUILD)/glad/gl.o: $(WEB_GLAD_C)
	@echo "emcc $<" && $(EMCC) $(WEB_CFLAGS) -c $< -o $@

$(WEB_BUILD)/%.o: %.c $(WEB_GLAD_H) | $(WEB_HEADERS)
	@mkdir -p $(dir $@)
	@echo "emcc $<" && $(EMCC) $(WEB_CFLAGS) -MMD -MP -c $< -o $@

-include $(shell find $(WEB_BUILD) -name '*.d' 2>/dev/null)
