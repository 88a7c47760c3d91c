# sbfx — build, test, demo, bench, install.
#   make [all]        library (build/libsbfx.a, .so), build/sbfx-play, build/sbfx-probe, build/sbfx-soak
#   make demo         render the built-in explosion headless into build/demo/
#   make gallery      one contact sheet per example scene into docs/gallery/ (README "Gallery")
#   make test         unit + GL (surfaceless Mesa) tests, shader validation, then ASan+UBSan
#   make test-hosts   the SDL2 example and the Qt Quick integration with their tests (docs/hosts/)
#   make bench        timings into build/bench/
#   make ladder       src/ladder_default.h from build/bench/accuracy.csv (the frame budget's ladder)
#   make install      PREFIX=/usr/local DESTDIR= (LIBDIR, INCLUDEDIR, BINDIR); make uninstall
#   make BOARD=name   cross build for boards/name.mk into build/name/
#   make cross-check  BOARD=rk3588 cross build (Debian's aarch64 toolchain), checks it links
#   make test-vm      real-kernel tests in a qemu VM (vkms, vivid, gpio-sim; tests/vm/)
#   make soak         SOAK_HOURS (10) simulated hours of the kiosk loop: build/soak/soak.csv, .png
# Every build first checks the Debian packages it needs (tools/deps.sh $(DEPS): as root it
# installs what is missing, otherwise it names the apt-get line and stops).
PREFIX ?= /usr/local
DESTDIR ?=
LIBDIR ?= $(PREFIX)/lib
INCLUDEDIR ?= $(PREFIX)/include
BINDIR ?= $(PREFIX)/bin
BUILD ?= build
CC ?= cc
PKG_CONFIG ?= pkg-config
# The library's version: the minor grows when a function is added to src/sbfx.h, the major
# (the soname's number) when a signature or a public struct's layout changes.
VERSION := 1.0.0
SOVERSION := $(firstword $(subst ., ,$(VERSION)))
# tools/deps.sh's package set for this build (a board's .mk names its own)
DEPS := build

ifneq ($(BOARD),)
include boards/$(BOARD).mk
BUILD := build/$(BOARD)
endif

SRC_PKGS := glesv2 lcms2 libconfig
PLATFORM_PKGS := egl glesv2 libpng libdrm gbm libgpiod

# pkg-config is asked when a recipe first needs the answer, not when make reads this file: on a
# fresh machine the dependency step runs first and pkg-config never complains about packages
# it is about to install. $(call pkg_config,VAR,ARGS) asks once and keeps the answer in VAR.
pkg_config = $(eval $1 := $$(shell $(PKG_CONFIG) $2))$($1)
SRC_PKG_CFLAGS = $(call pkg_config,SRC_PKG_CFLAGS,--cflags $(SRC_PKGS))
SRC_PKG_LIBS = $(call pkg_config,SRC_PKG_LIBS,--libs $(SRC_PKGS))
PLATFORM_PKG_CFLAGS = $(call pkg_config,PLATFORM_PKG_CFLAGS,--cflags $(PLATFORM_PKGS))
PLATFORM_PKG_LIBS = $(call pkg_config,PLATFORM_PKG_LIBS,--libs $(PLATFORM_PKGS))

WARN := -Wall -Wextra -Wshadow -Wstrict-prototypes -Wmissing-prototypes -Wno-unused-parameter
OPT ?= -O2 -g
CFLAGS ?=
SANITIZE ?=
ifeq ($(SANITIZE),1)
OPT := -O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=undefined
endif
BASE_CFLAGS := -std=c11 -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE $(OPT) $(WARN) -fPIC -MMD -MP
SRC_CFLAGS = $(BASE_CFLAGS) $(SRC_PKG_CFLAGS) -Isrc $(CFLAGS)
SRC_LIBS = $(SRC_PKG_LIBS) -lm
PLATFORM_CFLAGS = $(BASE_CFLAGS) $(PLATFORM_PKG_CFLAGS) -Isrc -Iplatform $(CFLAGS)
PLATFORM_LIBS = $(PLATFORM_PKG_LIBS) $(SRC_LIBS)
comma := ,
LDSAN := $(if $(filter 1,$(SANITIZE)),-fsanitize=address$(comma)undefined)

# The runtime library: src/ and the embedded shaders. Only what src/sbfx.h declares (SBFX_API)
# is exported from the .so; the rest is hidden, and what no public function reaches is dropped.
SRC := $(wildcard src/*.c)
SHADERS := $(sort $(wildcard shaders_es/*.vert shaders_es/*.frag))
LIB_OBJ := $(SRC:src/%.c=$(BUILD)/obj/src/%.o) $(BUILD)/obj/gen/shaders_es.o
LIB_CFLAGS := -fvisibility=hidden -ffunction-sections -fdata-sections
SONAME := libsbfx.so.$(SOVERSION)
SO_LINKS := $(BUILD)/$(SONAME) $(BUILD)/libsbfx.so
# The CPU reference in double precision (ref/, libsbfx_ref.a): tests, the probe and the bench
# link it before the runtime library, whose table math it calls.
REF_OBJ := $(patsubst ref/%.c,$(BUILD)/obj/ref/%.o,$(wildcard ref/*.c))
REF_LIBS := $(BUILD)/libsbfx_ref.a $(BUILD)/libsbfx.a
PLATFORM_COMMON := egl_headless gl_reset png_io test_scene gl_check host_depth
PLATFORM_COMMON_OBJ := $(PLATFORM_COMMON:%=$(BUILD)/obj/platform/%.o)

UNIT_TESTS := $(patsubst tests/unit/%.c,$(BUILD)/tests/unit/%,$(wildcard tests/unit/*.c))
GL_TESTS := $(patsubst tests/gl/%.c,$(BUILD)/tests/gl/%,$(wildcard tests/gl/*.c))

.PHONY: all deps lib test test-unit test-gl test-asan demo gallery bench ladder install uninstall clean
all: lib $(BUILD)/sbfx-play $(BUILD)/sbfx-probe $(BUILD)/sbfx-soak $(BUILD)/sbfx.pc
lib: $(BUILD)/libsbfx.a $(SO_LINKS) $(BUILD)/libsbfx_ref.a

# Every compile waits for this step (order-only: it never makes anything out of date).
# DEPS=none skips it (a toolchain and sysroot that do not come from Debian packages).
deps:
ifneq ($(DEPS),none)
	@tools/deps.sh $(DEPS)
endif

$(BUILD)/tools/embed_shaders: tools/embed_shaders.c | deps
	@mkdir -p $(@D)
	$(HOSTCC) -O1 -o $@ $<
HOSTCC ?= cc

$(BUILD)/gen/shaders_es.c: $(SHADERS) $(BUILD)/tools/embed_shaders
	@mkdir -p $(@D)
	$(BUILD)/tools/embed_shaders $@ $(SHADERS)

$(BUILD)/obj/gen/shaders_es.o: $(BUILD)/gen/shaders_es.c | deps
	@mkdir -p $(@D)
	$(CC) $(SRC_CFLAGS) $(LIB_CFLAGS) -c -o $@ $<

$(BUILD)/obj/src/%.o: src/%.c | deps
	@mkdir -p $(@D)
	$(CC) $(SRC_CFLAGS) $(LIB_CFLAGS) -c -o $@ $<

$(BUILD)/obj/ref/%.o: ref/%.c | deps
	@mkdir -p $(@D)
	$(CC) $(SRC_CFLAGS) -Iref -c -o $@ $<

$(BUILD)/obj/platform/%.o: platform/%.c | deps
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -c -o $@ $<

$(BUILD)/libsbfx.a: $(LIB_OBJ)
	@rm -f $@
	$(AR) rcs $@ $^

$(BUILD)/libsbfx_ref.a: $(REF_OBJ)
	@rm -f $@
	$(AR) rcs $@ $^

# -z defs: every symbol the library needs comes from a library it names (not under ASan, whose
# runtime the executable brings).
$(BUILD)/libsbfx.so.$(VERSION): $(LIB_OBJ)
	$(CC) -shared -Wl,-soname,$(SONAME) -Wl,--gc-sections $(if $(LDSAN),,-Wl,-z,defs) $(LDSAN) \
		-o $@ $^ $(SRC_LIBS)

$(BUILD)/$(SONAME): $(BUILD)/libsbfx.so.$(VERSION)
	ln -sf $(<F) $@
$(BUILD)/libsbfx.so: $(BUILD)/$(SONAME)
	ln -sf $(<F) $@

# sbfx-play: the player, its displays (headless, DRM/KMS), camera and GPIO inputs (platform/)
PLAYER_SRC := player player_args player_usage player_inputs player_loop board luma live_detail \
	v4l2_source gpio_gpiod1 gpio_triggers trigger_filter display_headless display_drm drm_device \
	drm_fb drm_atomic drm_legacy drm_writeback gbm_egl player_reset display_link
PLAYER_OBJ := $(PLAYER_SRC:%=$(BUILD)/obj/platform/%.o)
$(BUILD)/sbfx-play: $(PLAYER_OBJ) $(PLATFORM_COMMON_OBJ) $(BUILD)/libsbfx.a
	$(CC) $(LDSAN) -o $@ $^ $(PLATFORM_LIBS)

$(BUILD)/obj/platform/probe.o: PLATFORM_CFLAGS += -Iref
$(BUILD)/sbfx-probe: $(BUILD)/obj/platform/probe.o $(PLATFORM_COMMON_OBJ) $(REF_LIBS)
	$(CC) $(LDSAN) -o $@ $^ $(PLATFORM_LIBS)

# sbfx-soak: the kiosk loop for simulated hours, flatness checked (README "Kiosk months");
# a test tool, not installed. `make soak` runs it for SOAK_HOURS and plots the record
# with gnuplot (tests/soak/soak.gp); tests/soak.sh runs a short one inside `make test`.
$(BUILD)/sbfx-soak: $(BUILD)/obj/platform/soak.o $(BUILD)/obj/platform/soak_check.o $(PLATFORM_COMMON_OBJ) \
		$(BUILD)/libsbfx.a
	$(CC) $(LDSAN) -o $@ $^ $(PLATFORM_LIBS)

SOAK_HOURS ?= 10
.PHONY: soak
soak:
	@tools/deps.sh build
	@$(MAKE) --no-print-directory $(BUILD)/sbfx-soak
	@rc=0; $(BUILD)/sbfx-soak --hours $(SOAK_HOURS) --out $(BUILD)/soak || rc=$$?; \
	if command -v gnuplot >/dev/null 2>&1; then \
		gnuplot -e "dir='$(BUILD)/soak'" tests/soak/soak.gp && echo "soak: $(BUILD)/soak/soak.png"; \
	else echo "soak: gnuplot is not installed (apt-get install gnuplot-nox): no $(BUILD)/soak/soak.png" >&2; fi; \
	exit $$rc

# sbfx.pc: sbfx.pc.in with the install directories. build/sbfx.pc is rewritten on every run, as
# they may differ between "make" and "make install", which writes its own.
pc_from_template = sed -e 's|@PREFIX@|$(PREFIX)|' \
	-e 's|@LIBDIR@|$(patsubst $(PREFIX)/%,$${prefix}/%,$(LIBDIR))|' \
	-e 's|@INCLUDEDIR@|$(patsubst $(PREFIX)/%,$${prefix}/%,$(INCLUDEDIR))|' \
	-e 's|@VERSION@|$(VERSION)|' -e 's|@REQUIRES_PRIVATE@|$(SRC_PKGS)|' sbfx.pc.in > $1
$(BUILD)/sbfx.pc: sbfx.pc.in FORCE
	@mkdir -p $(@D)
	@$(call pc_from_template,$@)

# ---- tests -------------------------------------------------------------------------------
$(BUILD)/tests/unit/%: tests/unit/%.c $(REF_LIBS) tests/check.h
	@mkdir -p $(@D)
	$(CC) $(SRC_CFLAGS) -Iref -Itests $(LDSAN) -o $@ $< $(REF_LIBS) $(SRC_LIBS)

$(BUILD)/tests/gl/%: tests/gl/%.c $(PLATFORM_COMMON_OBJ) $(REF_LIBS) tests/check.h
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -Iref -Itests $(LDSAN) -o $@ $< $(PLATFORM_COMMON_OBJ) $(REF_LIBS) $(PLATFORM_LIBS)

# The GL state test also runs on desktop OpenGL (tests/run.sh), where sbfx reaches glPolygonMode
# through the process (src/gl_state.c): libOpenGL is in it, as in a desktop host.
OPENGL_LIBS = $(call pkg_config,OPENGL_LIBS,--libs opengl)
$(BUILD)/tests/gl/test_gl_state: PLATFORM_LIBS += -Wl,--no-as-needed $(OPENGL_LIBS) -Wl,--as-needed

test-unit: $(UNIT_TESTS)
test-gl: $(GL_TESTS) $(BUILD)/sbfx-play $(BUILD)/sbfx-probe

test:
	@tools/deps.sh test
	@$(MAKE) --no-print-directory all test-unit test-gl test-platform test-hosts
	@$(MAKE) --no-print-directory BUILD=build/asan SANITIZE=1 all test-unit test-gl test-platform
	@tests/run.sh

demo:
	@tools/deps.sh build
	@$(MAKE) --no-print-directory all
	@$(BUILD)/sbfx-play --headless --scene scenes/explosion.cfg --size 960x540 --frames 36 --out $(BUILD)/demo --contact-sheet

# Each example scene through sbfx-play from its own camera (its `camera` group, else the default
# orbit): 12 frames, 0.4 s apart, as one contact sheet docs/gallery/<scene>.png. Then one frame
# of the explosion (0.3 s) and of the barrage (1.2 s) per tone map: docs/gallery/tonemap-*.png.
GALLERY_SCENES := $(basename $(notdir $(wildcard scenes/*.cfg)))
GALLERY_TONE_SHOTS := explosion:3.3333 barrage:0.8333
gallery:
	@tools/deps.sh build
	@$(MAKE) --no-print-directory all
	@mkdir -p docs/gallery
	@for s in $(GALLERY_SCENES); do \
		$(BUILD)/sbfx-play --headless --quiet --scene scenes/$$s.cfg --size 960x540 --frames 12 --fps 2.5 \
			--out $(BUILD)/gallery/$$s --contact-sheet || exit 1; \
		cp $(BUILD)/gallery/$$s/contact-sheet.png docs/gallery/$$s.png && echo "gallery: docs/gallery/$$s.png"; \
	done
	@for shot in $(GALLERY_TONE_SHOTS); do s=$${shot%%:*}; fps=$${shot#*:}; \
		for tm in none hue-preserving per-channel; do \
			$(BUILD)/sbfx-play --headless --quiet --scene scenes/$$s.cfg --size 640x360 --frames 2 --fps $$fps \
				--tone-map $$tm --out $(BUILD)/gallery/tone-$$s-$$tm || exit 1; \
			cp $(BUILD)/gallery/tone-$$s-$$tm/frame-0001.png docs/gallery/tonemap-$$s-$$tm.png; \
		done; echo "gallery: docs/gallery/tonemap-$$s-*.png"; \
	done

bench: all
	@tests/bench/run.sh $(BUILD)

# The header, both libraries (the .so as libsbfx.so.VERSION with its soname and development
# links), sbfx.pc and the two programs; ldconfig when it is the live system. Not the CPU
# reference (libsbfx_ref.a): tests only.
install: all
	install -d $(DESTDIR)$(LIBDIR)/pkgconfig $(DESTDIR)$(INCLUDEDIR) $(DESTDIR)$(BINDIR)
	install -m 644 src/sbfx.h $(DESTDIR)$(INCLUDEDIR)/
	install -m 644 $(BUILD)/libsbfx.a $(DESTDIR)$(LIBDIR)/
	install -m 755 $(BUILD)/libsbfx.so.$(VERSION) $(DESTDIR)$(LIBDIR)/
	ln -sf libsbfx.so.$(VERSION) $(DESTDIR)$(LIBDIR)/$(SONAME)
	ln -sf $(SONAME) $(DESTDIR)$(LIBDIR)/libsbfx.so
	$(call pc_from_template,$(DESTDIR)$(LIBDIR)/pkgconfig/sbfx.pc)
	install -m 755 $(BUILD)/sbfx-play $(BUILD)/sbfx-probe $(DESTDIR)$(BINDIR)/
	@if [ -z "$(DESTDIR)" ] && [ "$$(id -u)" -eq 0 ]; then ldconfig; fi

uninstall:
	rm -f $(DESTDIR)$(INCLUDEDIR)/sbfx.h $(DESTDIR)$(LIBDIR)/libsbfx.a \
		$(DESTDIR)$(LIBDIR)/libsbfx.so.$(VERSION) $(DESTDIR)$(LIBDIR)/$(SONAME) \
		$(DESTDIR)$(LIBDIR)/libsbfx.so $(DESTDIR)$(LIBDIR)/pkgconfig/sbfx.pc \
		$(DESTDIR)$(BINDIR)/sbfx-play $(DESTDIR)$(BINDIR)/sbfx-probe

clean:
	rm -rf build

-include $(shell find $(BUILD)/obj -name '*.d' 2>/dev/null)

# ---- fuzzing (clang, libFuzzer): FUZZ_SECONDS bounded, the example scenes as corpus ----
FUZZ_SECONDS ?= 60
FUZZ_SRC := src/scene.c src/effects.c src/quality_name.c
$(BUILD)/fuzz/fuzz_scene: tests/fuzz/fuzz_scene.c $(FUZZ_SRC) src/sbfx.h src/scene.h
	@mkdir -p $(@D)
	clang -std=c11 -D_DEFAULT_SOURCE -g -O1 -fsanitize=fuzzer,address,undefined -Isrc \
		$(shell $(PKG_CONFIG) --cflags glesv2 libconfig) -o $@ tests/fuzz/fuzz_scene.c $(FUZZ_SRC) \
		$(shell $(PKG_CONFIG) --libs libconfig)

.PHONY: fuzz
fuzz: $(BUILD)/fuzz/fuzz_scene
	@rm -rf $(BUILD)/fuzz/corpus && mkdir -p $(BUILD)/fuzz/corpus && cp scenes/*.cfg $(BUILD)/fuzz/corpus/
	LSAN_OPTIONS=suppressions=$(CURDIR)/tests/fuzz/lsan.supp:print_suppressions=0 \
		$(BUILD)/fuzz/fuzz_scene -max_total_time=$(FUZZ_SECONDS) -max_len=8192 -timeout=10 \
		-artifact_prefix=$(BUILD)/fuzz/ -print_final_stats=1 $(BUILD)/fuzz/corpus > $(BUILD)/fuzz/log 2>&1 \
		|| { tail -n 40 $(BUILD)/fuzz/log; exit 1; }
	@grep -E "stat::number_of_executed_units|Done" $(BUILD)/fuzz/log | tail -n 2

# ---- bench (issue #4: what accuracy costs) ------------------------------------------------
# tests/bench/*.c link into one program. --wrap lets the bench time the module's particle pass
# on its own (tests/bench/bench_gl.h says how); nothing else is wrapped.
BENCH_SRC := $(wildcard tests/bench/*.c)
BENCH_OBJ := $(BENCH_SRC:tests/bench/%.c=$(BUILD)/obj/bench/%.o)
BENCH_WRAP := -Wl,--wrap=glBindFramebuffer -Wl,--wrap=glDrawArraysInstanced

$(BUILD)/obj/bench/%.o: tests/bench/%.c | deps
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -Iref -Itests/bench -c -o $@ $<

$(BUILD)/bench/bench_accuracy: $(BENCH_OBJ) $(PLATFORM_COMMON_OBJ) $(REF_LIBS)
	@mkdir -p $(@D)
	$(CC) $(LDSAN) $(BENCH_WRAP) -o $@ $^ $(PLATFORM_LIBS)

bench: $(BUILD)/bench/bench_accuracy

# ---- the default quality ladder (issue 11): src/ladder_default.h from the accuracy bench's CSV ----
# make bench writes $(BUILD)/bench/ladder_default.h (the ladder its run proposes); make ladder
# regenerates the committed src/ladder_default.h from $(BUILD)/bench/accuracy.csv (tools/ladder.sh).
ladder:
	tools/ladder.sh $(BUILD)/bench/accuracy.csv src/ladder_default.h

# ---- frame budget bench (issue 11): the barrage at several budgets and at every fixed level ----
# A program of its own (tests/bench/budget/), with the accuracy bench's read-backs, metrics and
# CPU reference; writes $(BUILD)/bench/budget.csv and budget.txt when run (tests/bench/run.sh).
BUDGET_BENCH_OBJ := $(addprefix $(BUILD)/obj/bench/,bench_gl.o bench_metrics.o bench_reference.o)
$(BUILD)/bench/bench_budget: tests/bench/budget/bench_budget.c $(BUDGET_BENCH_OBJ) $(PLATFORM_COMMON_OBJ) $(REF_LIBS)
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -Iref -Itests/bench $(LDSAN) $(BENCH_WRAP) -o $@ $< $(BUDGET_BENCH_OBJ) \
		$(PLATFORM_COMMON_OBJ) $(REF_LIBS) $(PLATFORM_LIBS)

bench: $(BUILD)/bench/bench_budget

# ---- lighting bench (issue #7: lit smoke) -------------------------------------------------
# A program of its own (tests/bench/lighting/, outside the accuracy bench's tests/bench/*.c):
# step count vs time and error of the lit-smoke ray march, lit vs phase cost. Writes
# $(BUILD)/bench/lighting.csv when run (tests/bench/run.sh).
$(BUILD)/bench/bench_lighting: tests/bench/lighting/bench_lighting.c $(PLATFORM_COMMON_OBJ) $(REF_LIBS)
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -Iref $(LDSAN) -o $@ $< $(PLATFORM_COMMON_OBJ) $(REF_LIBS) $(PLATFORM_LIBS)

bench: $(BUILD)/bench/bench_lighting

# ---- display bench (issue 12: tone mapping) -------------------------------------------------
# A program of its own: clipped particle pixels and the fire's chromaticity on the display per
# tone map, explosion and barrage; writes $(BUILD)/bench/tonemap.csv when run (tests/bench/run.sh).
$(BUILD)/bench/bench_tonemap: tests/bench/tonemap/bench_tonemap.c $(PLATFORM_COMMON_OBJ) $(BUILD)/libsbfx.a
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) $(LDSAN) -o $@ $< $(PLATFORM_COMMON_OBJ) $(BUILD)/libsbfx.a $(PLATFORM_LIBS)

bench: $(BUILD)/bench/bench_tonemap

# ---- scenes and post-effects bench (issues #3, #6) ------------------------------------------
$(BUILD)/bench/bench_scenes: tests/bench/scenes/bench_scenes.c $(PLATFORM_COMMON_OBJ) $(BUILD)/libsbfx.a
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -o $@ $< $(PLATFORM_COMMON_OBJ) $(BUILD)/libsbfx.a $(PLATFORM_LIBS)

bench: $(BUILD)/bench/bench_scenes

# ---- host contract bench (issue #10): GL state save/restore cost, far-field depth precision ----
$(BUILD)/bench/bench_state: tests/bench/state/bench_state.c $(PLATFORM_COMMON_OBJ) $(REF_LIBS)
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -Iref -o $@ $< $(PLATFORM_COMMON_OBJ) $(REF_LIBS) $(PLATFORM_LIBS)

bench: $(BUILD)/bench/bench_state

# ---- platform (issue #5: DRM/KMS kiosk, V4L2 detail, GPIO triggers, boards) ---------------
# tests/platform/: the player's logic without devices (luma slices, debounce, board profiles,
# the --gpio/--mode syntax), run by tests/run.sh like the unit tests.
PLATFORM_TEST_OBJ := $(addprefix $(BUILD)/obj/platform/,luma.o trigger_filter.o board.o player_args.o \
	soak_check.o display_link.o)
PLATFORM_TESTS := $(patsubst tests/platform/%.c,$(BUILD)/tests/platform/%,$(wildcard tests/platform/*.c))
$(BUILD)/tests/platform/%: tests/platform/%.c $(PLATFORM_TEST_OBJ) tests/check.h
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -Itests $(LDSAN) -o $@ $< $(PLATFORM_TEST_OBJ) $(PLATFORM_LIBS)
# GPIO lines lost and requested again: gpio_triggers.c against a fake gpio.h backend (in the test)
$(BUILD)/tests/platform/test_gpio_recovery: tests/platform/test_gpio_recovery.c \
		$(BUILD)/obj/platform/gpio_triggers.o $(BUILD)/obj/platform/trigger_filter.o tests/check.h
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -Itests $(LDSAN) -o $@ $< $(BUILD)/obj/platform/gpio_triggers.o \
		$(BUILD)/obj/platform/trigger_filter.o $(PLATFORM_LIBS)
$(BUILD)/tests/platform/test_gl_reset: tests/platform/test_gl_reset.c $(BUILD)/obj/platform/gl_reset.o tests/check.h
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -Itests $(LDSAN) -o $@ $< $(BUILD)/obj/platform/gl_reset.o $(PLATFORM_LIBS)
.PHONY: test-platform test-vm cross-check
test-platform: $(PLATFORM_TESTS)

# The real-kernel tier: boots Debian's kernel under qemu with vkms, vivid and gpio-sim and runs
# sbfx-play against them (tests/vm/run.sh, README "Real-kernel tests"). Downloads from Debian's
# archive, cached in build/vm/.
VM_TOOLS := $(BUILD)/tests/vm/pngdiff $(BUILD)/tests/vm/drm_state $(BUILD)/tests/vm/v4l2_ctrl \
	$(BUILD)/tests/vm/alloc_count.so $(BUILD)/tests/vm/vblank_stress
$(BUILD)/tests/vm/pngdiff: tests/vm/pngdiff.c $(BUILD)/obj/platform/png_io.o
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -o $@ $^ $(PLATFORM_LIBS)
$(BUILD)/tests/vm/alloc_count.so: tests/vm/alloc_count.c
	@mkdir -p $(@D)
	$(CC) -std=c11 -O1 -g $(WARN) -shared -fPIC -o $@ $<
$(BUILD)/tests/vm/v4l2_ctrl: tests/vm/v4l2_ctrl.c
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -o $@ $<
$(BUILD)/tests/vm/vblank_stress: tests/vm/vblank_stress.c
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -o $@ $< $(PLATFORM_LIBS)
$(BUILD)/tests/vm/drm_state: tests/vm/drm_state.c
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -o $@ $< $(PLATFORM_LIBS)
test-vm:
	@tools/deps.sh vm
	@$(MAKE) --no-print-directory all $(VM_TOOLS)
	@BUILD=$(BUILD) tests/vm/run.sh

# ---- hosts (issue 18): the SDL2 example and the Qt Quick integration (docs/hosts/) ----------
# Built by make test (tools/deps.sh test installs their -dev packages); make and make demo
# never need them. Their tests run headless: SDL's offscreen driver, Qt on Xvfb (tests/hosts/).
SDL2_CFLAGS = $(call pkg_config,SDL2_CFLAGS,--cflags sdl2)
SDL2_LIBS = $(call pkg_config,SDL2_LIBS,--libs sdl2)
EXAMPLE_CFLAGS = $(BASE_CFLAGS) $(SRC_PKG_CFLAGS) -Isrc $(CFLAGS)
$(BUILD)/obj/examples/sdl2/%.o: examples/sdl2/%.c examples/sdl2/sdl2_host.h | deps
	@mkdir -p $(@D)
	$(CC) $(EXAMPLE_CFLAGS) $(SDL2_CFLAGS) -c -o $@ $<
$(BUILD)/examples/sbfx-sdl2: $(BUILD)/obj/examples/sdl2/main.o $(BUILD)/obj/examples/sdl2/sdl2_host.o $(BUILD)/libsbfx.a
	@mkdir -p $(@D)
	$(CC) $(LDSAN) -o $@ $^ $(SDL2_LIBS) $(SRC_LIBS)
$(BUILD)/tests/hosts/test_sdl2: tests/hosts/test_sdl2.c $(BUILD)/obj/examples/sdl2/sdl2_host.o $(BUILD)/libsbfx.a tests/check.h
	@mkdir -p $(@D)
	$(CC) $(EXAMPLE_CFLAGS) $(SDL2_CFLAGS) -Iexamples/sdl2 -Itests $(LDSAN) -o $@ $< \
		$(BUILD)/obj/examples/sdl2/sdl2_host.o $(BUILD)/libsbfx.a $(SDL2_LIBS) $(SRC_LIBS)
.PHONY: test-hosts
test-hosts: $(BUILD)/examples/sbfx-sdl2 $(BUILD)/tests/hosts/test_sdl2

# Cross build for a board (boards/rk3588.mk: Debian's aarch64 toolchain and arm64 multiarch
# -dev packages, which its deps step installs or names) into build/rk3588/, and a check that
# what it linked is AArch64 code.
CROSS_BOARD ?= rk3588
cross-check:
	@$(MAKE) --no-print-directory BOARD=$(CROSS_BOARD) all
	@for f in build/$(CROSS_BOARD)/sbfx-play build/$(CROSS_BOARD)/sbfx-probe build/$(CROSS_BOARD)/libsbfx.so; do \
		readelf -h $$f | grep -q 'Machine:.*AArch64' || { echo "cross-check: $$f is not AArch64" >&2; exit 1; }; \
	done; echo "cross-check: build/$(CROSS_BOARD)/sbfx-play, sbfx-probe, libsbfx.so link for AArch64"

.PHONY: FORCE
FORCE:
