# sbfx — build, test, demo, bench, install.
#   make [all]        library (build/libsbfx.a, .so), build/sbfx-play, build/sbfx-probe
#   make demo         render the built-in explosion headless into build/demo/
#   make gallery      one contact sheet per example scene into docs/gallery/ (README "Gallery")
#   make test         unit + GL (surfaceless Mesa) tests, shader validation, then ASan+UBSan
#   make bench        timings into build/bench/
#   make install      PREFIX=/usr/local DESTDIR=
#   make BOARD=name   cross build for boards/name.mk into build/name/
#   make cross-check  BOARD=rk3588 cross build (Debian's aarch64 toolchain), checks it links
#   make test-vm      real-kernel tests in a qemu VM (vkms, vivid, gpio-sim; tests/vm/)
PREFIX ?= /usr/local
DESTDIR ?=
BUILD ?= build
CC ?= cc
PKG_CONFIG ?= pkg-config
VERSION := 0.1.0

ifneq ($(BOARD),)
include boards/$(BOARD).mk
BUILD := build/$(BOARD)
endif

SRC_PKGS := glesv2 lcms2 libconfig
PLATFORM_PKGS := egl glesv2 libpng libdrm gbm libgpiod

WARN := -Wall -Wextra -Wshadow -Wstrict-prototypes -Wmissing-prototypes -Wno-unused-parameter
OPT ?= -O2 -g
CFLAGS ?=
SANITIZE ?=
ifeq ($(SANITIZE),1)
OPT := -O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=undefined
endif
BASE_CFLAGS := -std=c11 -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE $(OPT) $(WARN) -fPIC -MMD -MP
SRC_CFLAGS := $(BASE_CFLAGS) $(shell $(PKG_CONFIG) --cflags $(SRC_PKGS)) -Isrc $(CFLAGS)
SRC_LIBS := $(shell $(PKG_CONFIG) --libs $(SRC_PKGS)) -lm
PLATFORM_CFLAGS := $(BASE_CFLAGS) $(shell $(PKG_CONFIG) --cflags $(PLATFORM_PKGS)) -Isrc -Iplatform $(CFLAGS)
PLATFORM_LIBS := $(shell $(PKG_CONFIG) --libs $(PLATFORM_PKGS)) $(SRC_LIBS)
comma := ,
LDSAN := $(if $(filter 1,$(SANITIZE)),-fsanitize=address$(comma)undefined)

SRC := $(wildcard src/*.c)
SHADERS := $(sort $(wildcard shaders_es/*.vert shaders_es/*.frag))
LIB_OBJ := $(SRC:src/%.c=$(BUILD)/obj/src/%.o) $(BUILD)/obj/gen/shaders_es.o
PLATFORM_COMMON := egl_headless png_io test_scene gl_check
PLATFORM_COMMON_OBJ := $(PLATFORM_COMMON:%=$(BUILD)/obj/platform/%.o)

UNIT_TESTS := $(patsubst tests/unit/%.c,$(BUILD)/tests/unit/%,$(wildcard tests/unit/*.c))
GL_TESTS := $(patsubst tests/gl/%.c,$(BUILD)/tests/gl/%,$(wildcard tests/gl/*.c))

.PHONY: all deps lib test test-unit test-gl test-asan demo gallery bench install clean
all: lib $(BUILD)/sbfx-play $(BUILD)/sbfx-probe $(BUILD)/sbfx.pc
lib: $(BUILD)/libsbfx.a $(BUILD)/libsbfx.so

deps:
	@tools/deps.sh build

$(BUILD)/tools/embed_shaders: tools/embed_shaders.c
	@mkdir -p $(@D)
	$(HOSTCC) -O1 -o $@ $<
HOSTCC ?= cc

$(BUILD)/gen/shaders_es.c: $(SHADERS) $(BUILD)/tools/embed_shaders
	@mkdir -p $(@D)
	$(BUILD)/tools/embed_shaders $@ $(SHADERS)

$(BUILD)/obj/gen/shaders_es.o: $(BUILD)/gen/shaders_es.c
	@mkdir -p $(@D)
	$(CC) $(SRC_CFLAGS) -c -o $@ $<

$(BUILD)/obj/src/%.o: src/%.c
	@mkdir -p $(@D)
	$(CC) $(SRC_CFLAGS) -c -o $@ $<

$(BUILD)/obj/platform/%.o: platform/%.c
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -c -o $@ $<

$(BUILD)/libsbfx.a: $(LIB_OBJ)
	@rm -f $@
	$(AR) rcs $@ $^

$(BUILD)/libsbfx.so: $(LIB_OBJ)
	$(CC) -shared -Wl,-soname,libsbfx.so.0 $(LDSAN) -o $@ $^ $(SRC_LIBS)

# sbfx-play: the player, its displays (headless, DRM/KMS), camera and GPIO inputs (platform/)
PLAYER_SRC := player player_args player_usage player_inputs player_loop board luma live_detail \
	v4l2_source gpio_gpiod1 gpio_triggers trigger_filter display_headless display_drm drm_device \
	drm_fb drm_atomic drm_legacy drm_writeback gbm_egl
PLAYER_OBJ := $(PLAYER_SRC:%=$(BUILD)/obj/platform/%.o)
$(BUILD)/sbfx-play: $(PLAYER_OBJ) $(PLATFORM_COMMON_OBJ) $(BUILD)/libsbfx.a
	$(CC) $(LDSAN) -o $@ $^ $(PLATFORM_LIBS)

$(BUILD)/sbfx-probe: $(BUILD)/obj/platform/probe.o $(PLATFORM_COMMON_OBJ) $(BUILD)/libsbfx.a
	$(CC) $(LDSAN) -o $@ $^ $(PLATFORM_LIBS)

# rewritten on every run: it carries PREFIX, which may differ between "make" and "make install"
$(BUILD)/sbfx.pc: Makefile FORCE
	@mkdir -p $(@D)
	@printf 'prefix=%s\nlibdir=$${prefix}/lib\nincludedir=$${prefix}/include\n\nName: sbfx\nDescription: volumetric particle effects (spherical billboards) on OpenGL ES 3.0\nVersion: %s\nRequires.private: %s\nLibs: -L$${libdir} -lsbfx\nLibs.private: -lm\nCflags: -I$${includedir}\n' \
		'$(PREFIX)' '$(VERSION)' '$(SRC_PKGS)' > $@

# ---- tests -------------------------------------------------------------------------------
$(BUILD)/tests/unit/%: tests/unit/%.c $(BUILD)/libsbfx.a tests/check.h
	@mkdir -p $(@D)
	$(CC) $(SRC_CFLAGS) -Itests $(LDSAN) -o $@ $< $(BUILD)/libsbfx.a $(SRC_LIBS)

$(BUILD)/tests/gl/%: tests/gl/%.c $(PLATFORM_COMMON_OBJ) $(BUILD)/libsbfx.a tests/check.h
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -Itests $(LDSAN) -o $@ $< $(PLATFORM_COMMON_OBJ) $(BUILD)/libsbfx.a $(PLATFORM_LIBS)

test-unit: $(UNIT_TESTS)
test-gl: $(GL_TESTS) $(BUILD)/sbfx-play $(BUILD)/sbfx-probe

test:
	@tools/deps.sh test
	@$(MAKE) --no-print-directory all test-unit test-gl test-platform
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

install: all
	install -d $(DESTDIR)$(PREFIX)/lib $(DESTDIR)$(PREFIX)/include $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(PREFIX)/lib/pkgconfig
	install -m 644 $(BUILD)/libsbfx.a $(DESTDIR)$(PREFIX)/lib/
	install -m 755 $(BUILD)/libsbfx.so $(DESTDIR)$(PREFIX)/lib/libsbfx.so.0
	ln -sf libsbfx.so.0 $(DESTDIR)$(PREFIX)/lib/libsbfx.so
	install -m 644 src/sbfx.h $(DESTDIR)$(PREFIX)/include/
	install -m 644 $(BUILD)/sbfx.pc $(DESTDIR)$(PREFIX)/lib/pkgconfig/
	install -m 755 $(BUILD)/sbfx-play $(BUILD)/sbfx-probe $(DESTDIR)$(PREFIX)/bin/

clean:
	rm -rf build

-include $(shell find $(BUILD)/obj -name '*.d' 2>/dev/null)

# ---- fuzzing (clang, libFuzzer): FUZZ_SECONDS bounded, the example scenes as corpus ----
FUZZ_SECONDS ?= 60
FUZZ_SRC := src/scene.c src/effects.c
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

$(BUILD)/obj/bench/%.o: tests/bench/%.c
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -Itests/bench -c -o $@ $<

$(BUILD)/bench/bench_accuracy: $(BENCH_OBJ) $(PLATFORM_COMMON_OBJ) $(BUILD)/libsbfx.a
	@mkdir -p $(@D)
	$(CC) $(LDSAN) $(BENCH_WRAP) -o $@ $^ $(PLATFORM_LIBS)

bench: $(BUILD)/bench/bench_accuracy

# ---- lighting bench (issue #7: lit smoke) -------------------------------------------------
# A program of its own (tests/bench/lighting/, outside the accuracy bench's tests/bench/*.c):
# step count vs time and error of the lit-smoke ray march, lit vs phase cost. Writes
# $(BUILD)/bench/lighting.csv when run (tests/bench/run.sh).
$(BUILD)/bench/bench_lighting: tests/bench/lighting/bench_lighting.c $(PLATFORM_COMMON_OBJ) $(BUILD)/libsbfx.a
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) $(LDSAN) -o $@ $< $(PLATFORM_COMMON_OBJ) $(BUILD)/libsbfx.a $(PLATFORM_LIBS)

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

# ---- platform (issue #5: DRM/KMS kiosk, V4L2 detail, GPIO triggers, boards) ---------------
# tests/platform/: the player's logic without devices (luma slices, debounce, board profiles,
# the --gpio/--mode syntax), run by tests/run.sh like the unit tests.
PLATFORM_TEST_OBJ := $(addprefix $(BUILD)/obj/platform/,luma.o trigger_filter.o board.o player_args.o)
PLATFORM_TESTS := $(patsubst tests/platform/%.c,$(BUILD)/tests/platform/%,$(wildcard tests/platform/*.c))
$(BUILD)/tests/platform/%: tests/platform/%.c $(PLATFORM_TEST_OBJ) tests/check.h
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -Itests $(LDSAN) -o $@ $< $(PLATFORM_TEST_OBJ) $(PLATFORM_LIBS)
.PHONY: test-platform test-vm cross-check
test-platform: $(PLATFORM_TESTS)

# The real-kernel tier: boots Debian's kernel under qemu with vkms, vivid and gpio-sim and runs
# sbfx-play against them (tests/vm/run.sh, README "Real-kernel tests"). Downloads from Debian's
# archive, cached in build/vm/.
VM_TOOLS := $(BUILD)/tests/vm/pngdiff $(BUILD)/tests/vm/drm_state $(BUILD)/tests/vm/v4l2_ctrl \
	$(BUILD)/tests/vm/alloc_count.so
$(BUILD)/tests/vm/pngdiff: tests/vm/pngdiff.c $(BUILD)/obj/platform/png_io.o
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -o $@ $^ $(PLATFORM_LIBS)
$(BUILD)/tests/vm/alloc_count.so: tests/vm/alloc_count.c
	@mkdir -p $(@D)
	$(CC) -std=c11 -O1 -g $(WARN) -shared -fPIC -o $@ $<
$(BUILD)/tests/vm/v4l2_ctrl: tests/vm/v4l2_ctrl.c
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -o $@ $<
$(BUILD)/tests/vm/drm_state: tests/vm/drm_state.c
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -o $@ $< $(PLATFORM_LIBS)
test-vm:
	@tools/deps.sh vm
	@$(MAKE) --no-print-directory all $(VM_TOOLS)
	@BUILD=$(BUILD) tests/vm/run.sh

# Cross build for a board (boards/rk3588.mk: Debian's aarch64 toolchain and arm64 multiarch
# -dev packages) into build/rk3588/, and a check that what it linked is AArch64 code.
CROSS_BOARD ?= rk3588
cross-check:
	@tools/deps.sh cross-arm64
	@$(MAKE) --no-print-directory BOARD=$(CROSS_BOARD) all
	@for f in build/$(CROSS_BOARD)/sbfx-play build/$(CROSS_BOARD)/sbfx-probe build/$(CROSS_BOARD)/libsbfx.so; do \
		readelf -h $$f | grep -q 'Machine:.*AArch64' || { echo "cross-check: $$f is not AArch64" >&2; exit 1; }; \
	done; echo "cross-check: build/$(CROSS_BOARD)/sbfx-play, sbfx-probe, libsbfx.so link for AArch64"

.PHONY: FORCE
FORCE:
