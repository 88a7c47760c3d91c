# sbfx in a browser (docs/web.md), included by the Makefile: the library (src/, the same embedded
# shaders), libconfig (Debian's source: tools/web-libconfig.sh) and the page's host
# (platform/web/) built with Debian's emscripten for WebGL 2 into build/web/, with the page
# (web/) and the example scenes. Its own tree: BOARD, SANITIZE and CFLAGS do not reach it.
#   make web          build/web/: index.html, app.js, sbfx.js + sbfx.wasm, scenes/
#   make web-serve    serve build/web/ on http://127.0.0.1:$(WEB_PORT)/ (python3 -m http.server)
#   make test-web     the page in headless Chromium over the DevTools protocol, and its frames beside
#                     sbfx-play's on Mesa (tests/web/; frames and differences in build/web-same-picture/)
WEB := $(BUILD)/web
WEB_PORT ?= 8045
EMCC ?= emcc
# emscripten's JavaScript tools require() Debian's node modules, also where the node on PATH is
# not Debian's; emcc is a Python program and runs with the first python3 on PATH: Debian's.
$(WEB)/%: export NODE_PATH := /usr/share/nodejs
$(WEB)/%: export PATH := /usr/bin:$(PATH)
WEB_LIBCONFIG := $(WEB)/libconfig
# -O2 as the native build; the library's own warnings; libconfig's locale calls as its configure
# finds them on a glibc system (emscripten's libc has newlocale, uselocale, freelocale); clang 19
# (Debian 13's emscripten 3.1.69) warns about libconfig's generated parser calling functions
# declared without a prototype: its code, not ours (clang 14, Debian 12's, knows no such warning)
WEB_OPT := -O2
WEB_CFLAGS := -std=c11 -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE $(WEB_OPT) $(WARN) -Iinclude -Isrc \
	-I$(WEB_LIBCONFIG)/src/lib
WEB_LIBCONFIG_CFLAGS := $(WEB_OPT) -Wno-unknown-warning-option -Wno-deprecated-non-prototype -DHAVE_NEWLOCALE -DHAVE_USELOCALE -DHAVE_FREELOCALE -I$(WEB_LIBCONFIG)/src/lib
WEB_HOST := host/test_scene host/host_depth egl/gl_check
WEB_PLATFORM := $(WEB_HOST) web/web_host web/web_pick web/web_stats
WEB_LIB_OBJ := $(SRC:src/%.c=$(WEB)/obj/src/%.o) $(WEB)/obj/gen/shaders_es.o $(WEB)/obj/gen/cie1931_2deg.o \
	$(WEB)/obj/libconfig/libconfig.a
WEB_OBJ := $(WEB_LIB_OBJ) $(WEB_PLATFORM:%=$(WEB)/obj/platform/%.o)
WEB_EXPORTS := sbfx_web_start sbfx_web_resize sbfx_web_load sbfx_web_settings sbfx_web_frame \
	sbfx_web_read_pixels sbfx_web_trigger sbfx_web_effect_name sbfx_web_click_coordinate sbfx_web_pick \
	sbfx_web_project sbfx_web_stats sbfx_web_info sbfx_web_message malloc free
# WebGL 2 (= OpenGL ES 3.0) with the whole ES 3.0 API; a factory createSbfx() rather than a global
# module; memory grows with the particle pool a scene asks for
WEB_LDFLAGS := -sUSE_WEBGL2=1 -sFULL_ES3=1 -sMIN_WEBGL_VERSION=2 -sMAX_WEBGL_VERSION=2 -sMODULARIZE=1 \
	-sEXPORT_NAME=createSbfx -sALLOW_MEMORY_GROWTH=1 -sENVIRONMENT=web \
	-sEXPORTED_FUNCTIONS=$(subst $(eval ) ,$(comma),$(WEB_EXPORTS:%=_%)) \
	-sEXPORTED_RUNTIME_METHODS=ccall,cwrap,UTF8ToString,HEAPU8
WEB_PAGE := $(addprefix $(WEB)/,index.html app.js style.css scenes/index.json)
WEB_SCENES := $(wildcard scenes/*.cfg)

.PHONY: web web-serve test-web
web: $(WEB)/sbfx.js $(WEB_PAGE) $(WEB_SCENES:scenes/%=$(WEB)/scenes/%)

$(WEB_LIBCONFIG)/src/lib/libconfig.h: | web-deps
	tools/web-libconfig.sh $(WEB_LIBCONFIG) >/dev/null
.PHONY: web-deps
web-deps:
	@tools/deps.sh web

# every C file of its lib/ (1.5 in Debian 12 has five, 1.7 in Debian 13 more), into one archive
$(WEB)/obj/libconfig/libconfig.a: $(WEB_LIBCONFIG)/src/lib/libconfig.h
	@rm -rf $(@D)
	@mkdir -p $(@D)
	@for f in $(WEB_LIBCONFIG)/src/lib/*.c; do echo "  CC      $(@D)/$$(basename $$f .c).o"; \
		$(EMCC) $(WEB_LIBCONFIG_CFLAGS) -c -o $(@D)/$$(basename $$f .c).o $$f || exit 1; done
	emar rcs $@ $(@D)/*.o
$(WEB)/obj/src/%.o: src/%.c $(WEB_LIBCONFIG)/src/lib/libconfig.h
	@mkdir -p $(@D)
	$(EMCC) $(WEB_CFLAGS) -MMD -MP -c -o $@ $<
$(WEB)/obj/gen/%.o: $(BUILD)/gen/%.c | web-deps
	@mkdir -p $(@D)
	$(EMCC) $(WEB_CFLAGS) -c -o $@ $<
$(WEB)/obj/platform/%.o: platform/%.c | web-deps
	@mkdir -p $(@D)
	$(EMCC) $(WEB_CFLAGS) -Iplatform -MMD -MP -c -o $@ $<
$(WEB)/obj/ref/%.o: ref/%.c | web-deps
	@mkdir -p $(@D)
	$(EMCC) $(WEB_CFLAGS) -Iref -MMD -MP -c -o $@ $<
$(WEB)/sbfx.js: $(WEB_OBJ)
	$(EMCC) $(WEB_OPT) $(WEB_LDFLAGS) -o $@ $^

$(WEB)/%: web/%
	@mkdir -p $(@D)
	cp $< $@
$(WEB)/scenes/%.cfg: scenes/%.cfg
	@mkdir -p $(@D)
	cp $< $@
# the example scenes the page offers (its "open" list)
$(WEB)/scenes/index.json: $(WEB_SCENES)
	@mkdir -p $(@D)
	printf '[%s]\n' "$$(for s in $(notdir $(WEB_SCENES)); do printf '"%s",' "$$s"; done | sed 's/,$$//')" > $@

# The accuracy suites (tests/precision.sh --suites) built for the browser: the same test programs
# over egl_web.c's WebGL 2 contexts, one page each (tests/web/suite.html), run by make
# test-web-suites (tests/web/suites.js; docs/web.md "A second OpenGL ES").
WEB_SUITES := $(shell tests/precision.sh --suites)
WEB_SUITE_OBJ := $(WEB_LIB_OBJ) $(patsubst ref/%.c,$(WEB)/obj/ref/%.o,$(wildcard ref/*.c)) \
	$(WEB_HOST:%=$(WEB)/obj/platform/%.o) $(WEB)/obj/platform/web/egl_web.o
# test_gl_look renders and measures through tests/look/ (as the Makefile's LOOK_OBJ)
$(WEB)/suites/test_gl_look.js: WEB_SUITE_EXTRA := tests/look/look_metrics.c tests/look/look_render.c
# the example scenes some cases load are embedded (emscripten's in-memory file system)
$(WEB)/suites/%.js: tests/gl/%.c $(WEB_SUITE_OBJ) tests/check.h tests/gl/gl_fixture.h tests/web/clearenv.c $(WEB_SCENES)
	@mkdir -p $(@D)
	$(EMCC) $(WEB_CFLAGS) -Iplatform -Iref -Itests -Itests/look -Wno-unused-function -o $@ $< tests/web/clearenv.c \
		$(WEB_SUITE_EXTRA) $(WEB_SUITE_OBJ) -sUSE_WEBGL2=1 \
		-sFULL_ES3=1 -sMIN_WEBGL_VERSION=2 -sMAX_WEBGL_VERSION=2 -sALLOW_MEMORY_GROWTH=1 -sENVIRONMENT=web \
		-sEXIT_RUNTIME=1 --embed-file scenes
$(WEB)/suites/suite.html: tests/web/suite.html
	@mkdir -p $(@D)
	cp $< $@
.PHONY: test-web-suites
test-web-suites: $(WEB_SUITES:%=$(WEB)/suites/%.js) $(WEB)/suites/suite.html
	@tools/deps.sh web
	@node tests/web/suites.js $(WEB)/suites $(WEB_SUITES)

web-serve: web
	@echo "web-serve: http://127.0.0.1:$(WEB_PORT)/ (Ctrl-C stops it)"
	cd $(WEB) && python3 -m http.server --bind 127.0.0.1 $(WEB_PORT)

test-web: web $(BUILD)/sbfx-play
	@tools/deps.sh web
	@tests/web/run.sh $(WEB)

-include $(shell find $(WEB)/obj -name '*.d' 2>/dev/null)
