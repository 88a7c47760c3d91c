# sbfx — build, test, demo, bench, install. `make help` prints the "#   make" entries below, whole.
#   make [all]        library (build/libsbfx.a, .so), build/sbfx-play, build/sbfx-probe, build/sbfx-soak
#   make help         this list of targets
#   make demo         render the built-in explosion headless into build/demo/
#   make gallery      one contact sheet per example scene into docs/gallery/ (docs/scene-format.md)
#   make test         every suite once: unit, GL (surfaceless Mesa) and CLI tests under ASan+UBSan,
#                     precision, hosts, shaders, docs... from the normal build; every core
#                     (tests/run.sh; docs/testing.md: one suite, one case)
#   make check        the edit-compile loop's tier: unit tests, a GL smoke test per pass, shaders,
#                     the rooms' one-way dependencies (tests/layers.sh, src/rooms.txt)
#   make test-hosts   the SDL2, desktop OpenGL and Qt Quick hosts and their tests (docs/hosts/;
#                     make test runs them)
#   make test-qt-quick  the Qt Quick item, its example and test where Qt 6 is installed (test-hosts)
#   make gstreamer    the GStreamer element sbfx, build/gstreamer/libgstsbfx.so (docs/hosts/gstreamer.md;
#                     part of make where GStreamer's -dev packages are)
#   make test-gstreamer  the element and its tests (tests/gstreamer/; make test runs them)
#   make test-load    60 s of 5,000 DIS Entity State PDUs and 50 detonations a second while rendering
#                     (tests/load.sh; make test runs 3 s; docs/simulators.md)
#   make test-precision  the accuracy suites at GPU precision: SBFX_MEDIUMP=native SBFX_FILTER_BITS=8
#                     (and 6 bits for NVIDIA's cases; tests/precision.sh; make test runs it)
#   make bench        timings into build/bench/
#   make figures      the seed's figures rendered into docs/figures/ (docs/figures.md)
#   make ladder       src/budget/ladder_default.h from build/bench/accuracy.csv (the frame budget's ladder;
#                     LADDER_RUNS="a.csv b.csv": from several runs, each time the least of theirs)
#   make install      PREFIX=/usr/local DESTDIR= (LIBDIR, INCLUDEDIR, BINDIR, MANDIR, DATADIR); also
#                     scenes, boards, the kiosk's unit and udev rule (dist/), and libgstsbfx.so into
#                     GStreamer's plugin folder under PREFIX (GST_PLUGINDIR)
#   make uninstall    remove what make install put there (same PREFIX, DESTDIR)
#   make BOARD=name   cross build for boards/name.mk into build/name/
#   make cross-check  BOARD=rk3588 cross build (Debian's aarch64 toolchain), checks it links
#   make abi-baseline dist/abi/libsbfx.so.N.abi from the built library (abidw), the ABI that tests/abi.sh
#                     (make test) holds the library to; at a release that adds functions or moves the SONAME
#   make deb          the Debian packages libsbfx1, libsbfx-dev, sbfx-player, gstreamer1.0-sbfx into
#                     build/deb/ARCH/ (dpkg-buildpackage from dist/debian/, then lintian: no errors,
#                     no warnings); make deb ARCH=arm64 cross builds them (docs/packaging.md)
#   make test-vm      real-kernel tests in a qemu VM (vkms, vivid, gpio-sim; tests/vm/)
#   make test-fresh   the README's quick start in a bare Debian root: DIST=bookworm (12) or trixie
#                     (13); debootstrap, a clone of HEAD, make demo and make test (tests/fresh/run.sh), as root
#   make test-debian13  make test-fresh DIST=trixie
#   make web          sbfx for WebGL 2 with emscripten and the authoring page into build/web/ (docs/web.md)
#   make web-serve    serve build/web/ on 127.0.0.1 (python3 -m http.server)
#   make test-web     the page in headless Chromium over the DevTools protocol, its frames beside
#                     sbfx-play's on Mesa (tests/web/; make test runs its first case)
#   make test-web-suites  the accuracy suites in headless Chromium: ANGLE over SwiftShader (docs/web.md)
#   make test-deb     the Debian packages from a bare root (DIST as make test-fresh, as root): built there
#                     with debian/control's build dependencies and lintian, installed with apt into a
#                     second bare root, run (player, a pkg-config host, gst-inspect-1.0, systemd-analyze
#                     verify) and purged; ARCH=arm64 cross builds them (tests/fresh/run.sh)
#   make test-gpus    every scene's shaders through Mesa's Mali, V3D, Adreno, Vivante compilers
#                     (drm-shims; builds Mesa 25 into build/mesa-shim/ once; docs/gpus.md)
#   make gpiod2       sbfx-play again against libgpiod 2.x built from Debian 13's source (docs/gpio.md)
#   make mesa-shim    Mesa 25 with the drm-shims of panfrost, v3d, freedreno, etnaviv (docs/gpus.md)
#   make soak         SOAK_HOURS (10) simulated hours of the kiosk loop: build/soak/soak.csv, .png
#   make fuzz         FUZZ_SECONDS (60) of libFuzzer on the scene parser, FUZZ_DIS_SECONDS (15) on the
#                     DIS parser and receiver, FUZZ_CIGI_SECONDS (15) on the CIGI ones (clang)
#   make clean        remove build/
#   make V=1 ...      print every command line (quiet by default: "  CC      build/obj/src/sim.o")
# Every build first checks the Debian packages it needs (tools/deps.sh $(DEPS): as root it
# installs what is missing, otherwise it names the apt-get line and stops).
PREFIX ?= /usr/local
DESTDIR ?=
LIBDIR ?= $(PREFIX)/lib
INCLUDEDIR ?= $(PREFIX)/include
BINDIR ?= $(PREFIX)/bin
DATADIR ?= $(PREFIX)/share
BUILD ?= build
MANDIR ?= $(PREFIX)/share/man
# Quiet builds, as the kernel's kbuild: recipe lines are not echoed, and tools/quiet-shell.sh,
# make's shell, prints one short line per compile, link or archive. make V=1: the command lines.
V ?= 0
ifneq ($(V),1)
.SILENT:
SHELL := $(CURDIR)/tools/quiet-shell.sh
endif
CC ?= cc
PKG_CONFIG ?= pkg-config
# The library's version: the minor grows when a function is added to include/sbfx.h, the major
# (the soname's number) when a signature or a public struct's layout changes.
VERSION := 1.5.0
SOVERSION := $(firstword $(subst ., ,$(VERSION)))
# tools/deps.sh's package set for this build (a board's .mk names its own)
DEPS := build

ifneq ($(BOARD),)
include boards/$(BOARD).mk
BUILD := build/$(BOARD)
endif

SRC_PKGS := glesv2 libconfig
PLATFORM_PKGS := egl glesv2 libpng libdrm gbm libgpiod
# FFmpeg's libraries: detail from a recorded clip (platform/video/clip_detail.c, docs/detail-clips.md)
CLIP_PKGS := libavformat libavcodec libswscale libavutil

# pkg-config is asked when a recipe first needs the answer, not when make reads this file: on a
# fresh machine the dependency step runs first and pkg-config never complains about packages
# it is about to install. $(call pkg_config,VAR,ARGS) asks once and keeps the answer in VAR.
pkg_config = $(eval $1 := $$(shell $(PKG_CONFIG) $2))$($1)
SRC_PKG_CFLAGS = $(call pkg_config,SRC_PKG_CFLAGS,--cflags $(SRC_PKGS))
SRC_PKG_LIBS = $(call pkg_config,SRC_PKG_LIBS,--libs $(SRC_PKGS))
PLATFORM_PKG_CFLAGS = $(call pkg_config,PLATFORM_PKG_CFLAGS,--cflags $(PLATFORM_PKGS))
PLATFORM_PKG_LIBS = $(call pkg_config,PLATFORM_PKG_LIBS,--libs $(PLATFORM_PKGS))
CLIP_PKG_CFLAGS = $(call pkg_config,CLIP_PKG_CFLAGS,--cflags $(CLIP_PKGS))
CLIP_PKG_LIBS = $(call pkg_config,CLIP_PKG_LIBS,--libs $(CLIP_PKGS))

WARN := -Wall -Wextra -Wshadow -Wstrict-prototypes -Wmissing-prototypes -Wno-unused-parameter
OPT ?= -O2 -g
CFLAGS ?=
SANITIZE ?=
ifeq ($(SANITIZE),1)
OPT := -O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=undefined
endif
BASE_CFLAGS := -std=c11 -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE $(OPT) $(WARN) -fPIC -MMD -MP
SRC_CFLAGS = $(BASE_CFLAGS) $(SRC_PKG_CFLAGS) -Iinclude -Isrc $(CFLAGS)
SRC_LIBS = $(SRC_PKG_LIBS) -lm
PLATFORM_CFLAGS = $(BASE_CFLAGS) $(PLATFORM_PKG_CFLAGS) -Iinclude -Isrc -Iplatform $(CFLAGS)
PLATFORM_LIBS = $(PLATFORM_PKG_LIBS) $(SRC_LIBS)
comma := ,
# The ASan+UBSan tree (tests only, never installed) links with gold where the toolchain has it
# (Debian 12's binutils; 13 has no gold and keeps ld.bfd): about 90 links of the sanitized
# library, each 0.2 s rather than 0.3 s on the development VM.
LDSAN := $(if $(filter 1,$(SANITIZE)),-fsanitize=address$(comma)undefined \
	$(shell env $(CC) -fuse-ld=gold -Wl,--version 2>/dev/null | grep -q '^GNU gold' && echo -fuse-ld=gold))

# The runtime library: src/ and the embedded shaders. Only what include/sbfx.h declares (SBFX_API)
# is exported from the .so; the rest is hidden, and what no public function reaches is dropped.
# src/ is in rooms, one folder per floor (src/rooms.txt): src/ROOM/NAME.c -> $(BUILD)/obj/src/ROOM/NAME.o
SRC := $(sort $(wildcard src/*.c src/*/*.c))
SHADERS := $(sort $(wildcard shaders_es/*.vert shaders_es/*.frag))
# A shader written in parts, shaders_es/NAME.STAGE.parts/N-WHAT.glsl (particle.frag.parts/): joined at
# build time into $(BUILD)/gen/shaders_es/NAME.STAGE, with #line directives that name each part
# and its line (tools/embed_shaders.c; docs/hacking.md), then embedded like the others.
SHADER_PARTS := $(sort $(wildcard shaders_es/*.parts/*.glsl))
SHADERS_JOINED := $(patsubst shaders_es/%.parts,$(BUILD)/gen/shaders_es/%,$(wildcard shaders_es/*.parts))
LIB_OBJ := $(SRC:src/%.c=$(BUILD)/obj/src/%.o) $(BUILD)/obj/gen/shaders_es.o $(BUILD)/obj/gen/cie1931_2deg.o
LIB_CFLAGS := -fvisibility=hidden -ffunction-sections -fdata-sections
SONAME := libsbfx.so.$(SOVERSION)
SO_LINKS := $(BUILD)/$(SONAME) $(BUILD)/libsbfx.so
# The CPU reference in double precision (ref/, libsbfx_ref.a): tests, the probe and the bench
# link it before the runtime library, whose table math it calls.
REF_OBJ := $(patsubst ref/%.c,$(BUILD)/obj/ref/%.o,$(wildcard ref/*.c))
REF_LIBS := $(BUILD)/libsbfx_ref.a $(BUILD)/libsbfx.a
# platform/ is in rooms, one folder per concern (platform/ROOM/NAME.c -> $(BUILD)/obj/platform/ROOM/NAME.o)
PLATFORM_COMMON := egl/egl_headless egl/gl_reset egl/gl_check image/png_io host/test_scene host/host_depth
PLATFORM_COMMON_OBJ := $(PLATFORM_COMMON:%=$(BUILD)/obj/platform/%.o)

UNIT_TESTS := $(patsubst tests/unit/%.c,$(BUILD)/tests/unit/%,$(wildcard tests/unit/*.c))
GL_TESTS := $(patsubst tests/gl/%.c,$(BUILD)/tests/gl/%,$(wildcard tests/gl/*.c))

.PHONY: all deps lib test test-unit test-gl test-asan demo gallery bench ladder install uninstall clean help
all: lib $(BUILD)/sbfx-play $(BUILD)/sbfx-probe $(BUILD)/sbfx-soak $(BUILD)/sbfx.pc
lib: $(BUILD)/libsbfx.a $(SO_LINKS) $(BUILD)/libsbfx_ref.a

# each "#   make" line and the comment lines that go on with it (indented under its text), whole
help:
	@awk '/^#   make / { on = 1; print substr($$0, 5); next } on && /^#     / { print substr($$0, 5); next } \
		{ on = 0 }' $(firstword $(MAKEFILE_LIST))

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

$(BUILD)/gen/shaders_es/%: $(SHADER_PARTS) $(BUILD)/tools/embed_shaders
	@mkdir -p $(@D)
	$(BUILD)/tools/embed_shaders --join shaders_es/$*.parts $@

$(BUILD)/gen/shaders_es.c: $(SHADERS) $(SHADERS_JOINED) $(BUILD)/tools/embed_shaders
	@mkdir -p $(@D)
	$(BUILD)/tools/embed_shaders $@ $(SHADERS) $(SHADERS_JOINED)

$(BUILD)/obj/gen/shaders_es.o: $(BUILD)/gen/shaders_es.c | deps
	@mkdir -p $(@D)
	$(CC) $(SRC_CFLAGS) $(LIB_CFLAGS) -c -o $@ $<

# The CIE 1931 2° colour-matching functions compiled in (src/tables/tables.h): generated from
# colord-data's file through lcms2 by a build-time program, so the library reads no file and
# does not link lcms2 (docs/distributions.md). The host's lcms2, also in a cross build.
CIE_CMF ?= /usr/share/colord/cmf/CIE1931-2deg-XYZ.cmf
HOST_PKG_CONFIG ?= pkg-config
$(BUILD)/tools/gen_cmf: tools/gen_cmf.c | deps
	@mkdir -p $(@D)
	$(HOSTCC) -std=c11 -O1 $(WARN) $(shell $(HOST_PKG_CONFIG) --cflags lcms2) -o $@ $< \
		$(shell $(HOST_PKG_CONFIG) --libs lcms2) -lm

$(BUILD)/gen/cie1931_2deg.c: $(wildcard $(CIE_CMF)) $(BUILD)/tools/gen_cmf
	@mkdir -p $(@D)
	$(BUILD)/tools/gen_cmf $(CIE_CMF) $@

$(BUILD)/obj/gen/cie1931_2deg.o: $(BUILD)/gen/cie1931_2deg.c | deps
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
	$(CC) -shared -Wl,-soname,$(SONAME) -Wl,--gc-sections $(if $(LDSAN),,-Wl,-z,defs) $(LDSAN) $(LDFLAGS) \
		-o $@ $^ $(SRC_LIBS)

$(BUILD)/$(SONAME): $(BUILD)/libsbfx.so.$(VERSION)
	ln -sf $(<F) $@
$(BUILD)/libsbfx.so: $(BUILD)/$(SONAME)
	ln -sf $(<F) $@

# The Wayland display (display_wayland.c, docs/kiosk-deploy.md "Wayland"): libwayland-client and
# wayland-egl, the player only. The xdg-shell and presentation-time protocols' code is generated
# by wayland-scanner (libwayland-bin, run on the build machine) from the XML of wayland-protocols
# (architecture-independent: the build machine's, also in a cross build) into $(BUILD)/gen/wayland/.
WAYLAND_PKGS := wayland-client wayland-egl
WAYLAND_PKG_CFLAGS = $(call pkg_config,WAYLAND_PKG_CFLAGS,--cflags $(WAYLAND_PKGS))
WAYLAND_PKG_LIBS = $(call pkg_config,WAYLAND_PKG_LIBS,--libs $(WAYLAND_PKGS))
WAYLAND_SCANNER ?= wayland-scanner
WAYLAND_PROTOCOLS_DIR = $(call pkg_config_host,WAYLAND_PROTOCOLS_DIR,--variable=pkgdatadir wayland-protocols)
pkg_config_host = $(eval $1 := $$(shell $(HOST_PKG_CONFIG) $2))$($1)
WAYLAND_GEN := $(BUILD)/gen/wayland
WAYLAND_PROTOCOLS := xdg-shell presentation-time
WAYLAND_HEADERS := $(WAYLAND_PROTOCOLS:%=$(WAYLAND_GEN)/%-client-protocol.h)
WAYLAND_PROTOCOL_OBJ := $(WAYLAND_PROTOCOLS:%=$(BUILD)/obj/gen/wayland/%-protocol.o)
$(WAYLAND_GEN)/%-client-protocol.h: | deps
	@mkdir -p $(@D)
	$(WAYLAND_SCANNER) client-header $(WAYLAND_PROTOCOLS_DIR)/stable/$*/$*.xml $@
$(WAYLAND_GEN)/%-protocol.c: | deps
	@mkdir -p $(@D)
	$(WAYLAND_SCANNER) private-code $(WAYLAND_PROTOCOLS_DIR)/stable/$*/$*.xml $@
$(BUILD)/obj/gen/wayland/%.o: $(WAYLAND_GEN)/%.c | deps
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) $(WAYLAND_PKG_CFLAGS) -c -o $@ $<
$(BUILD)/obj/platform/display/display_wayland.o: $(WAYLAND_HEADERS)
$(BUILD)/obj/platform/display/display_wayland.o $(BUILD)/obj/platform/wayland/wayland_egl.o: \
	PLATFORM_CFLAGS += $(WAYLAND_PKG_CFLAGS) -I$(WAYLAND_GEN)

# Network triggers (platform/net/, docs/triggers.md, docs/cigi.md): DIS and CIGI over UDP (libc), MQTT
# through libmosquitto
# platform/net/ is in rooms (platform/net/rooms.txt): what the protocols share, then one folder each
NET_SRC := $(addprefix common/,geodesy net_address udp_socket scene_group) \
	$(addprefix dis/,dis_pdu dis_effects dis_events dis_receiver dis_config) \
	$(addprefix cigi/,cigi_packet cigi_entities cigi_receiver cigi_config) $(addprefix mqtt/,mqtt_client)
# sbfx-play: the player, its displays (headless, DRM/KMS, Wayland), camera, GPIO and network inputs (platform/)
PLAYER_SRC := $(addprefix player/,player module loop host reset authoring clock world) \
	$(addprefix player/options/,args usage board channel) $(addprefix player/outputs/,stats notify) \
	$(addprefix player/inputs/,triggers trigger_queue gpio_source dis_source cigi_source mqtt_source detail watch \
	signals) \
	$(addprefix video/,luma live_detail v4l2_source clip_detail) \
	$(addprefix gpio/,gpio_backend effect_names effect_at gpio_triggers trigger_filter) \
	$(addprefix net/,$(NET_SRC)) \
	$(addprefix display/,display_headless display_drm display_link display_wayland) \
	$(addprefix drm/,drm_mode_spec drm_device drm_fb drm_atomic drm_legacy drm_writeback gbm_egl) \
	$(addprefix wayland/,wayland_egl present_feedback)
PLAYER_OBJ := $(PLAYER_SRC:%=$(BUILD)/obj/platform/%.o) $(WAYLAND_PROTOCOL_OBJ)
# --version prints the Makefile's VERSION (the library's)
$(BUILD)/obj/platform/player/options/usage.o: PLATFORM_CFLAGS += -DSBFX_VERSION='"$(VERSION)"'
# The GPIO backend (docs/gpio.md): platform/gpio/gpio_gpiod2.c when pkg-config's libgpiod is 2.x
# or later, else gpio_gpiod1.c (1.6). gpiod-version holds the version the object was built for, so
# a different libgpiod (PKG_CONFIG_PATH) rebuilds it.
GPIOD_VERSION = $(call pkg_config,GPIOD_VERSION_,--modversion libgpiod)
GPIOD_BACKEND = gpio_gpiod$(if $(filter 0 1,$(firstword $(subst ., ,$(GPIOD_VERSION)))),1,2)
$(BUILD)/gen/gpiod-version: FORCE | deps
	@mkdir -p $(@D)
	@[ "$$(cat $@ 2>/dev/null)" = "$(GPIOD_VERSION)" ] || echo "$(GPIOD_VERSION)" > $@
$(BUILD)/obj/platform/gpio/gpio_backend.o: platform/gpio/gpio_gpiod1.c platform/gpio/gpio_gpiod2.c \
		$(BUILD)/gen/gpiod-version | deps
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -c -o $@ platform/gpio/$(GPIOD_BACKEND).c
$(BUILD)/sbfx-play: $(PLAYER_OBJ) $(PLATFORM_COMMON_OBJ) $(BUILD)/libsbfx.a
	$(CC) $(LDSAN) $(LDFLAGS) $(PLAYER_TEST_WRAP) -o $@ $^ $(PLATFORM_LIBS) $(NOTIFY_PKG_LIBS) $(CLIP_PKG_LIBS) $(WAYLAND_PKG_LIBS) $(MQTT_PKG_LIBS)
# libmosquitto runs the MQTT client on a thread of its own (net/mqtt/mqtt_client.h); the player only
MQTT_PKG_CFLAGS = $(call pkg_config,MQTT_PKG_CFLAGS,--cflags libmosquitto)
MQTT_PKG_LIBS = $(call pkg_config,MQTT_PKG_LIBS,--libs libmosquitto) -pthread
$(BUILD)/obj/platform/net/mqtt/mqtt_client.o: PLATFORM_CFLAGS += $(MQTT_PKG_CFLAGS) -pthread
# READY=1 and the watchdog's pings for systemd (player/outputs/notify.c): libsystemd, the player only
NOTIFY_PKG_CFLAGS = $(call pkg_config,NOTIFY_PKG_CFLAGS,--cflags libsystemd)
NOTIFY_PKG_LIBS = $(call pkg_config,NOTIFY_PKG_LIBS,--libs libsystemd)
$(BUILD)/obj/platform/player/outputs/notify.o: PLATFORM_CFLAGS += $(NOTIFY_PKG_CFLAGS)
$(BUILD)/obj/platform/video/clip_detail.o: PLATFORM_CFLAGS += $(CLIP_PKG_CFLAGS)

# sbfx-probe and sbfx-soak (tools/probe/, tools/soak/): tools that look inside the module through
# src/'s private headers, so they live outside platform/, which only uses include/sbfx.h.
$(BUILD)/obj/tools/%.o: tools/%.c | deps
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -Iref -c -o $@ $<

$(BUILD)/sbfx-probe: $(BUILD)/obj/tools/probe/probe.o $(PLATFORM_COMMON_OBJ) $(REF_LIBS)
	$(CC) $(LDSAN) $(LDFLAGS) -o $@ $^ $(PLATFORM_LIBS)

# sbfx-soak: the kiosk loop for simulated hours, flatness checked (docs/kiosk-and-devices.md,
# "Kiosk months"); a test tool, not installed. `make soak` runs it for SOAK_HOURS and plots the record
# with gnuplot (tests/soak/soak.gp); tests/soak.sh runs a short one inside `make test`.
$(BUILD)/sbfx-soak: $(BUILD)/obj/tools/soak/soak.o $(BUILD)/obj/tools/soak/soak_check.o $(PLATFORM_COMMON_OBJ) \
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
# $(call pc_write,OUT,PREFIX,LIBDIR,INCLUDEDIR)
pc_write = sed -e 's|@PREFIX@|$2|' \
	-e 's|@LIBDIR@|$(patsubst $2/%,$${prefix}/%,$3)|' \
	-e 's|@INCLUDEDIR@|$(patsubst $2/%,$${prefix}/%,$4)|' \
	-e 's|@VERSION@|$(VERSION)|' -e 's|@REQUIRES_PRIVATE@|$(SRC_PKGS)|' sbfx.pc.in > $1
pc_from_template = $(call pc_write,$1,$(PREFIX),$(LIBDIR),$(INCLUDEDIR))
$(BUILD)/sbfx.pc: sbfx.pc.in FORCE
	@mkdir -p $(@D)
	@$(call pc_from_template,$@)
# The same for the tree itself: sbfx-uninstalled.pc names include/ and $(BUILD)/ (pkg-config prefers
# NAME-uninstalled.pc on its path), so the in-tree hosts take their flags as installed ones do.
SBFX_PC_UNINSTALLED := $(BUILD)/pkgconfig/sbfx-uninstalled.pc
SBFX_PC_PATH := $(CURDIR)/$(BUILD)/pkgconfig$(if $(PKG_CONFIG_PATH),:$(PKG_CONFIG_PATH))
SBFX_PC_CFLAGS = $(eval SBFX_PC_CFLAGS := $$(shell PKG_CONFIG_PATH=$(SBFX_PC_PATH) $(PKG_CONFIG) --cflags sbfx))$(SBFX_PC_CFLAGS)
$(SBFX_PC_UNINSTALLED): sbfx.pc.in Makefile
	@mkdir -p $(@D)
	@$(call pc_write,$@,$(CURDIR),$(CURDIR)/$(BUILD),$(CURDIR)/include)

# ---- tests -------------------------------------------------------------------------------
$(BUILD)/tests/unit/%: tests/unit/%.c $(REF_LIBS) tests/check.h
	@mkdir -p $(@D)
	$(CC) $(SRC_CFLAGS) -Iref -Itests $(LDSAN) -o $@ $< $(REF_LIBS) $(SRC_LIBS)

# The GL tests take the module's procedural detail volume from a cache of this test run
# (tests/gl/support/detail_cache.c says why it still tests what it did): every GL test links it.
GL_TEST_SUPPORT := $(BUILD)/obj/tests/gl/support/detail_cache.o
GL_TEST_WRAP := -Wl,--wrap=sbfx_detail_generate,--wrap=sbfx_smoke_texture_generate $(GL_TEST_SUPPORT)
# The ASan+UBSan tier's player (build/asan/sbfx-play, which only tests/cli.sh runs) too: its
# runs in make test each spent some seconds generating the volume under ASan. The player that
# ships (build/) is linked as it is, and tests/cli.sh runs it with the real generator every time.
PLAYER_TEST_WRAP = $(if $(filter 1,$(SANITIZE)),-Wl$(comma)--wrap=sbfx_detail_generate$(comma)--wrap=sbfx_smoke_texture_generate)
ifeq ($(SANITIZE),1)
$(BUILD)/sbfx-play: $(GL_TEST_SUPPORT)
endif
$(BUILD)/obj/tests/gl/support/%.o: tests/gl/support/%.c | deps
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -c -o $@ $<

$(BUILD)/tests/gl/%: tests/gl/%.c $(PLATFORM_COMMON_OBJ) $(REF_LIBS) tests/check.h tests/gl/gl_fixture.h $(GL_TEST_SUPPORT)
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -Iref -Itests $(LDSAN) -o $@ $< $(GL_TEST_WRAP) $(PLATFORM_COMMON_OBJ) $(REF_LIBS) $(PLATFORM_LIBS)

# The GL state test also runs on desktop OpenGL (tests/run.sh), where sbfx reaches glPolygonMode
# through the process (src/gl/gl_state.c): libOpenGL is in it, as in a desktop host.
OPENGL_LIBS = $(call pkg_config,OPENGL_LIBS,--libs opengl)
$(BUILD)/tests/gl/test_gl_state: PLATFORM_LIBS += -Wl,--no-as-needed $(OPENGL_LIBS) -Wl,--as-needed

test-unit: $(UNIT_TESTS)
test-gl: $(GL_TESTS) $(BUILD)/sbfx-play $(BUILD)/sbfx-probe

.PHONY: test-precision
test-precision: test-gl
	@tests/precision.sh $(BUILD)

# A real exercise's load (tests/load.sh, docs/simulators.md): 5,000 DIS Entity State PDUs and 50
# detonations a second for LOAD_SECONDS (60) while sbfx-play renders; make test runs 3 s of it
LOAD_SECONDS ?= 60
.PHONY: test-load
test-load: $(BUILD)/sbfx-play $(BUILD)/tests/net/dis_send $(BUILD)/tests/net/cigi_send $(BUILD)/tests/vm/alloc_count.so
	@LOAD_SECONDS=$(LOAD_SECONDS) tests/load.sh $(BUILD)

# make test and make check use every core without -j: their builds run with -j(cores) unless
# make was given a job server already (make -jN test), and tests/run.sh runs suites in parallel.
NPROC := $(shell nproc 2>/dev/null || echo 1)
JOBS_FLAG = $(if $(findstring jobserver,$(MAKEFLAGS)),,-j$(NPROC))

# TEST_ASAN=cpu: the ASan+UBSan tier runs the unit and platform suites only, not the suites that
# render on Mesa: a lighter run for a slow machine (docs/testing.md says what it leaves out).
TEST_ASAN ?= full
# (its player, which test_sd_notify runs, and GL tests; not its probe and soak, which nothing runs)
ASAN_TEST_TARGETS := lib build/asan/sbfx-play test-unit test-platform \
	$(if $(filter cpu,$(TEST_ASAN)),,$(patsubst $(BUILD)/%,build/asan/%,$(GL_TESTS)))

# What make test runs from the normal build (tests/run.sh runs each suite once: the unit, platform
# and GL suites and the CLI tests from the ASan+UBSan build): the GL tests of the precision suites
# (tests/precision.sh --suites), the network suites' sender and allocation counter, the hosts and
# GStreamer. TEST_ASAN=cpu: every GL test (the GL suites run from the normal build then).
PRECISION_GL_TESTS = $(addprefix $(BUILD)/tests/gl/,$(shell tests/precision.sh --suites))
NORMAL_TEST_TARGETS = $(if $(filter cpu,$(TEST_ASAN)),test-gl,$(PRECISION_GL_TESTS)) \
	$(BUILD)/tests/net/dis_send $(BUILD)/tests/net/cigi_send $(BUILD)/tests/net/cigi_ig $(BUILD)/tests/vm/alloc_count.so \
	$(BUILD)/tests/seam/seam_check test-hosts test-gstreamer web

# the normal and the ASan+UBSan build side by side, sharing the job server
.PHONY: test-build test-build-normal test-build-asan check
test-build: test-build-normal test-build-asan
test-build-normal:
	@$(MAKE) --no-print-directory all $(NORMAL_TEST_TARGETS)
test-build-asan:
	@$(MAKE) --no-print-directory BUILD=build/asan SANITIZE=1 $(ASAN_TEST_TARGETS)

test:
	@tools/deps.sh test
	@$(MAKE) --no-print-directory $(JOBS_FLAG) test-build
	@tests/run.sh --asan=$(TEST_ASAN)

# The edit-compile tier (docs/testing.md): unit tests, one GL smoke test per pass, the shaders, the
# rooms' one-way dependencies (src/'s and the player's: the objects of libsbfx.a, which test-unit
# builds, and the player's own, made here).
check:
	@tools/deps.sh test
	@$(MAKE) --no-print-directory $(JOBS_FLAG) test-unit $(BUILD)/tests/gl/test_gl_smoke \
		$(filter $(BUILD)/obj/platform/player/% $(BUILD)/obj/platform/net/%,$(PLAYER_OBJ))
	@tests/run.sh --check

# The build's lines are left out (QUIET_LINES=0: tools/quiet-shell.sh); warnings still show.
demo:
	@tools/deps.sh build
	@echo "demo: building $(BUILD)/sbfx-play and the library (make V=1 demo shows the commands)"
	@QUIET_LINES=0 $(MAKE) --no-print-directory all
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
		for tm in none hue-preserving per-channel filmic; do \
			$(BUILD)/sbfx-play --headless --quiet --scene scenes/$$s.cfg --size 640x360 --frames 2 --fps $$fps \
				--tone-map $$tm --out $(BUILD)/gallery/tone-$$s-$$tm || exit 1; \
			cp $(BUILD)/gallery/tone-$$s-$$tm/frame-0001.png docs/gallery/tonemap-$$s-$$tm.png; \
		done; echo "gallery: docs/gallery/tonemap-$$s-*.png"; \
	done

bench: all
	@tests/bench/run.sh $(BUILD)

# The seed's figures 1, 2, 4, 5, 7, 8 and 10 as pictures, rendered by sbfx-play and composed with
# ImageMagick (tools/figures.sh): docs/figures/*.png, described in docs/figures.md.
.PHONY: figures
figures:
	@tools/deps.sh test
	@$(MAKE) --no-print-directory $(BUILD)/sbfx-play
	@tools/figures.sh $(BUILD)

# The header, both libraries (the .so as libsbfx.so.VERSION with its soname and development
# links), sbfx.pc, the two programs and their man pages; ldconfig when it is the live
# system. Not the CPU reference (libsbfx_ref.a): tests only.
install: all
	install -d $(DESTDIR)$(LIBDIR)/pkgconfig $(DESTDIR)$(INCLUDEDIR) $(DESTDIR)$(BINDIR)
	install -m 644 include/sbfx.h $(DESTDIR)$(INCLUDEDIR)/
	install -m 644 $(BUILD)/libsbfx.a $(DESTDIR)$(LIBDIR)/
	install -m 755 $(BUILD)/libsbfx.so.$(VERSION) $(DESTDIR)$(LIBDIR)/
	ln -sf libsbfx.so.$(VERSION) $(DESTDIR)$(LIBDIR)/$(SONAME)
	ln -sf $(SONAME) $(DESTDIR)$(LIBDIR)/libsbfx.so
	$(call pc_from_template,$(DESTDIR)$(LIBDIR)/pkgconfig/sbfx.pc)
	install -m 755 $(BUILD)/sbfx-play $(BUILD)/sbfx-probe $(DESTDIR)$(BINDIR)/
	install -d $(DESTDIR)$(MANDIR)/man1
	install -m 644 platform/player/sbfx-play.1 tools/probe/sbfx-probe.1 $(DESTDIR)$(MANDIR)/man1/
	@if [ -z "$(DESTDIR)" ] && [ "$$(id -u)" -eq 0 ]; then ldconfig; fi

uninstall:
	rm -f $(DESTDIR)$(INCLUDEDIR)/sbfx.h $(DESTDIR)$(LIBDIR)/libsbfx.a \
		$(DESTDIR)$(LIBDIR)/libsbfx.so.$(VERSION) $(DESTDIR)$(LIBDIR)/$(SONAME) \
		$(DESTDIR)$(LIBDIR)/libsbfx.so $(DESTDIR)$(LIBDIR)/pkgconfig/sbfx.pc \
		$(DESTDIR)$(BINDIR)/sbfx-play $(DESTDIR)$(BINDIR)/sbfx-probe $(DESTDIR)$(MANDIR)/man1/sbfx-play.1 \
		$(DESTDIR)$(MANDIR)/man1/sbfx-probe.1

clean:
	rm -rf --one-file-system build

-include $(shell find $(BUILD)/obj -name '*.d' 2>/dev/null)
# make web, web-serve, test-web (docs/web.md)
include web/web.mk

# ---- fuzzing (clang, libFuzzer): FUZZ_SECONDS bounded, the example scenes as corpus ----
# and FUZZ_DIS_SECONDS of the DIS parser and receiver, valid v6 and v7 PDUs as corpus, and
# FUZZ_CIGI_SECONDS of the CIGI parser and receiver, messages in both byte orders as corpus
FUZZ_SECONDS ?= 60
FUZZ_DIS_SECONDS ?= 15
FUZZ_CIGI_SECONDS ?= 15
FUZZ_SRC := src/scene/scene.c src/scene/effects.c src/scene/quality_name.c
$(BUILD)/fuzz/fuzz_scene: tests/fuzz/fuzz_scene.c $(FUZZ_SRC) include/sbfx.h src/scene/scene.h
	@mkdir -p $(@D)
	clang -std=c11 -D_DEFAULT_SOURCE -g -O1 -fsanitize=fuzzer,address,undefined -Iinclude -Isrc \
		$(shell $(PKG_CONFIG) --cflags glesv2 libconfig) -o $@ tests/fuzz/fuzz_scene.c $(FUZZ_SRC) \
		$(shell $(PKG_CONFIG) --libs libconfig)

FUZZ_DIS_SRC := $(addprefix platform/net/,dis/dis_pdu.c dis/dis_receiver.c dis/dis_events.c dis/dis_effects.c \
	common/geodesy.c common/udp_socket.c common/net_address.c)
$(BUILD)/fuzz/fuzz_dis: tests/fuzz/fuzz_dis.c $(FUZZ_DIS_SRC) $(wildcard platform/net/*/*.h)
	@mkdir -p $(@D)
	clang -std=c11 -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE -g -O1 -fsanitize=fuzzer,address,undefined \
		-Iplatform -o $@ tests/fuzz/fuzz_dis.c $(FUZZ_DIS_SRC) -lm

FUZZ_CIGI_SRC := $(addprefix platform/net/,cigi/cigi_packet.c cigi/cigi_entities.c cigi/cigi_receiver.c \
	common/geodesy.c common/udp_socket.c common/net_address.c)
$(BUILD)/fuzz/fuzz_cigi: tests/fuzz/fuzz_cigi.c $(FUZZ_CIGI_SRC) $(wildcard platform/net/*/*.h)
	@mkdir -p $(@D)
	clang -std=c11 -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE -g -O1 -fsanitize=fuzzer,address,undefined \
		-Iplatform -o $@ tests/fuzz/fuzz_cigi.c $(FUZZ_CIGI_SRC) -lm

.PHONY: fuzz
fuzz: $(BUILD)/fuzz/fuzz_scene $(BUILD)/fuzz/fuzz_dis $(BUILD)/tests/net/dis_send $(BUILD)/fuzz/fuzz_cigi \
		$(BUILD)/tests/net/cigi_send
	@rm -rf $(BUILD)/fuzz/corpus && mkdir -p $(BUILD)/fuzz/corpus && cp scenes/*.cfg $(BUILD)/fuzz/corpus/
	LSAN_OPTIONS=suppressions=$(CURDIR)/tests/fuzz/lsan.supp:print_suppressions=0 \
		$(BUILD)/fuzz/fuzz_scene -max_total_time=$(FUZZ_SECONDS) -max_len=8192 -timeout=10 \
		-artifact_prefix=$(BUILD)/fuzz/ -print_final_stats=1 $(BUILD)/fuzz/corpus > $(BUILD)/fuzz/log 2>&1 \
		|| { tail -n 40 $(BUILD)/fuzz/log; exit 1; }
	@grep -E "stat::number_of_executed_units|Done" $(BUILD)/fuzz/log | tail -n 2
	@rm -rf $(BUILD)/fuzz/dis-corpus && mkdir -p $(BUILD)/fuzz/dis-corpus
	@d=$(BUILD)/fuzz/dis-corpus; s=$(BUILD)/tests/net/dis_send; o=48.137154,11.576124,519; \
		$$s --file $$d/v6 --version 6 --origin $$o --enu 100,0,0 detonation && \
		$$s --file $$d/v7-records --version 7 --vp 2 --origin $$o --enu 0,100,50 --result 7 detonation && \
		$$s --file $$d/v7-bundle --count 2 --origin $$o detonation && \
		$$s --file $$d/entity-state entity-state
	$(BUILD)/fuzz/fuzz_dis -max_total_time=$(FUZZ_DIS_SECONDS) -max_len=9000 -timeout=10 \
		-artifact_prefix=$(BUILD)/fuzz/dis- -print_final_stats=1 $(BUILD)/fuzz/dis-corpus > $(BUILD)/fuzz/dis.log 2>&1 \
		|| { tail -n 40 $(BUILD)/fuzz/dis.log; exit 1; }
	@grep -E "stat::number_of_executed_units|Done" $(BUILD)/fuzz/dis.log | tail -n 2
	@rm -rf $(BUILD)/fuzz/cigi-corpus && mkdir -p $(BUILD)/fuzz/cigi-corpus
	@d=$(BUILD)/fuzz/cigi-corpus; s=$(BUILD)/tests/net/cigi_send; o=48.137154,11.576124,519; \
		$$s --file $$d/be --origin $$o entity=5,1001,1,2@100,0,0/10,2,1 entity=0,7,1,0@0,0,300 \
			view-def=1,2,-30,30,-20,20,0.5,20000 view-ctrl=1,0,0,1,2,3,45,-5,0 other=50,16 && \
		$$s --file $$d/le --little-endian --origin $$o entity=5,1001,2,0@100,0,0 entity=6,1001,1,0@0,100,50 && \
		$$s --file $$d/animation --origin $$o entity=5,1001,1,0@0,0,0 entity=5,1001,1,2@0,0,0 && \
		$$s --file $$d/ig-control-only
	$(BUILD)/fuzz/fuzz_cigi -max_total_time=$(FUZZ_CIGI_SECONDS) -max_len=9000 -timeout=10 \
		-artifact_prefix=$(BUILD)/fuzz/cigi- -print_final_stats=1 $(BUILD)/fuzz/cigi-corpus > $(BUILD)/fuzz/cigi.log 2>&1 \
		|| { tail -n 40 $(BUILD)/fuzz/cigi.log; exit 1; }
	@grep -E "stat::number_of_executed_units|Done" $(BUILD)/fuzz/cigi.log | tail -n 2

# ---- bench (issue #4: what accuracy costs) ------------------------------------------------
# tests/bench/*.c link into one program. --wrap lets the bench time the module's particle pass
# on its own and count every pass's fragments (tests/bench/bench_gl.h, bench_fragments.h say
# how); nothing else is wrapped.
BENCH_SRC := $(wildcard tests/bench/*.c)
BENCH_OBJ := $(BENCH_SRC:tests/bench/%.c=$(BUILD)/obj/bench/%.o)
BENCH_WRAP := -Wl,--wrap=glBindFramebuffer -Wl,--wrap=glDrawArraysInstanced -Wl,--wrap=glDrawArrays

$(BUILD)/obj/bench/%.o: tests/bench/%.c | deps
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -Iref -Itests/bench -Itests/look -c -o $@ $<

$(BUILD)/bench/bench_accuracy: $(BENCH_OBJ) $(BUILD)/obj/look/look_metrics.o $(PLATFORM_COMMON_OBJ) $(REF_LIBS)
	@mkdir -p $(@D)
	$(CC) $(LDSAN) $(BENCH_WRAP) -o $@ $^ $(PLATFORM_LIBS)

bench: $(BUILD)/bench/bench_accuracy

# ---- the default quality ladder (issue 11): src/budget/ladder_default.h from the accuracy bench's CSV ----
# make bench writes $(BUILD)/bench/ladder_default.h (the ladder its run proposes); make ladder
# regenerates the committed src/budget/ladder_default.h from $(BUILD)/bench/accuracy.csv (tools/ladder.sh),
# or from several runs' CSVs: make ladder LADDER_RUNS="run1.csv run2.csv run3.csv" (each time the least
# of the runs'), keeping the CSV it was made from in docs/ladder-accuracy.csv.
LADDER_RUNS ?= $(BUILD)/bench/accuracy.csv
ladder:
	LADDER_CSV=docs/ladder-accuracy.csv tools/ladder.sh $(LADDER_RUNS) src/budget/ladder_default.h

# ---- frame budget bench (issue 11): the barrage at several budgets and at every fixed level ----
# A program of its own (tests/bench/budget/), with the accuracy bench's read-backs, metrics and
# CPU reference; writes $(BUILD)/bench/budget.csv and budget.txt when run (tests/bench/run.sh).
BUDGET_BENCH_OBJ := $(addprefix $(BUILD)/obj/bench/,bench_gl.o bench_fragments.o bench_metrics.o bench_reference.o)
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

# ---- fire as light (issue 17 item 2; docs/look-fire.md) -------------------------------------
# tests/look/: the fire luminance metric (fire_metric.c, plain C, for any bench to call) and the
# renderer that feeds it; the bench writes $(BUILD)/bench/look-fire.csv, test_gl_fire_look
# asserts the ratios.
FIRE_LOOK_OBJ := $(BUILD)/obj/look/fire_metric.o $(BUILD)/obj/look/fire_look.o
# The look metric (tests/look/) is the tests' measuring instrument, not sbfx: the ASan+UBSan build
# compiles it as the normal build does (its blur was 61 % of asan:test_gl_look's CPU), while
# sbfx's own code that the look suites drive stays sanitised.
LOOK_CFLAGS = $(if $(filter 1,$(SANITIZE)),$(subst $(OPT),-O2 -g,$(PLATFORM_CFLAGS)),$(PLATFORM_CFLAGS))
$(BUILD)/obj/look/%.o: tests/look/%.c | deps
	@mkdir -p $(@D)
	$(CC) $(LOOK_CFLAGS) -Iref -Itests/look -c -o $@ $<
$(BUILD)/bench/bench_look_fire: tests/look/bench_look_fire.c $(FIRE_LOOK_OBJ) $(PLATFORM_COMMON_OBJ) $(BUILD)/libsbfx.a
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -Itests/look $(LDSAN) -o $@ $< $(FIRE_LOOK_OBJ) $(PLATFORM_COMMON_OBJ) $(BUILD)/libsbfx.a $(PLATFORM_LIBS)
$(BUILD)/tests/gl/test_gl_fire_look: tests/gl/test_gl_fire_look.c $(FIRE_LOOK_OBJ) $(PLATFORM_COMMON_OBJ) $(REF_LIBS) tests/check.h \
		$(GL_TEST_SUPPORT)
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -Iref -Itests -Itests/look $(LDSAN) -o $@ $< $(GL_TEST_WRAP) $(FIRE_LOOK_OBJ) $(PLATFORM_COMMON_OBJ) $(REF_LIBS) $(PLATFORM_LIBS)

bench: $(BUILD)/bench/bench_look_fire

# ---- the boards' frame (issue 33): every example scene over its life, fragments per program ----
# A program of its own (tests/bench/boards/) with the accuracy bench's fragment counting; writes
# $(BUILD)/bench/boards.csv when run, which tools/boards-table.sh prices (tests/bench/run.sh).
BOARDS_BENCH_OBJ := $(addprefix $(BUILD)/obj/bench/,bench_gl.o bench_fragments.o bench_programs.o)
$(BUILD)/bench/bench_boards: tests/bench/boards/bench_boards.c $(BOARDS_BENCH_OBJ) $(PLATFORM_COMMON_OBJ) $(BUILD)/libsbfx.a
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -Itests/bench $(LDSAN) $(BENCH_WRAP) -o $@ $< $(BOARDS_BENCH_OBJ) \
		$(PLATFORM_COMMON_OBJ) $(BUILD)/libsbfx.a $(PLATFORM_LIBS)

bench: $(BUILD)/bench/bench_boards

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

# ---- the host's shadow map (issue 27): its size and cost ------------------------------------
$(BUILD)/bench/bench_shadow: tests/bench/shadow/bench_shadow.c $(PLATFORM_COMMON_OBJ) $(BUILD)/libsbfx.a
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -o $@ $< $(PLATFORM_COMMON_OBJ) $(BUILD)/libsbfx.a $(PLATFORM_LIBS)

bench: $(BUILD)/bench/bench_shadow

# ---- platform (issue #5: DRM/KMS kiosk, V4L2 detail, GPIO triggers, boards) ---------------
# tests/platform/: the player's logic without devices (luma slices, debounce, board profiles,
# the --gpio/--mode syntax), run by tests/run.sh like the unit tests.
PLATFORM_TEST_OBJ := $(addprefix $(BUILD)/obj/platform/,video/luma.o gpio/trigger_filter.o player/options/board.o drm/drm_mode_spec.o \
	player/options/args.o player/options/channel.o display/display_link.o gpio/effect_at.o net/common/net_address.o) $(BUILD)/obj/tools/soak/soak_check.o
PLATFORM_TESTS := $(patsubst tests/platform/%.c,$(BUILD)/tests/platform/%,$(wildcard tests/platform/*.c))
$(BUILD)/tests/platform/%: tests/platform/%.c $(PLATFORM_TEST_OBJ) tests/check.h
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -Itests -Itools $(LDSAN) -o $@ $< $(PLATFORM_TEST_OBJ) $(PLATFORM_LIBS)
# GPIO lines lost and requested again: gpio_triggers.c against a fake gpio.h backend (in the test)
$(BUILD)/tests/platform/test_gpio_recovery: tests/platform/test_gpio_recovery.c \
		$(BUILD)/obj/platform/gpio/gpio_triggers.o $(BUILD)/obj/platform/gpio/trigger_filter.o \
		$(BUILD)/obj/platform/gpio/effect_names.o tests/check.h
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -Itests $(LDSAN) -o $@ $< $(BUILD)/obj/platform/gpio/gpio_triggers.o \
		$(BUILD)/obj/platform/gpio/trigger_filter.o $(BUILD)/obj/platform/gpio/effect_names.o $(PLATFORM_LIBS)
# DIS without a network and the one trigger queue (test_dis), the network's flags, board keys and
# scene keys (test_net_config), CIGI's parser, receiver and scene group (test_cigi): platform/net/
# but its MQTT client, which the player's runs test
NET_TEST_OBJ := $(addprefix $(BUILD)/obj/platform/,$(patsubst %,net/%.o,$(filter-out mqtt/mqtt_client common/net_address,$(NET_SRC))) \
	player/inputs/trigger_queue.o)
$(BUILD)/tests/platform/test_dis $(BUILD)/tests/platform/test_net_config $(BUILD)/tests/platform/test_cigi: \
		$(BUILD)/tests/platform/%: \
		tests/platform/%.c $(NET_TEST_OBJ) $(PLATFORM_TEST_OBJ) $(BUILD)/libsbfx.a tests/check.h
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -Itests $(LDSAN) -o $@ $< $(NET_TEST_OBJ) $(PLATFORM_TEST_OBJ) $(BUILD)/libsbfx.a $(PLATFORM_LIBS)
# tests/seam.sh's judge: channels side by side against the wide frame (docs/simulators.md)
$(BUILD)/tests/seam/seam_check: tests/seam/seam_check.c $(BUILD)/obj/platform/image/png_io.o
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -o $@ $^ $(PLATFORM_LIBS)
# tests/dis.sh's sender: DIS PDUs encoded from the standard's layout, on its own
$(BUILD)/tests/net/dis_send: tests/net/dis_send.c | deps
	@mkdir -p $(@D)
	$(CC) -std=c11 -O1 -g $(WARN) -o $@ $< -lm
# tests/cigi.sh's host: CIGI 3.3 messages encoded from the standard's layout, on its own; and its
# image generator, the player's CIGI receiver alone (events printed, Start of Frame sent back)
$(BUILD)/tests/net/cigi_send: tests/net/cigi_send.c | deps
	@mkdir -p $(@D)
	$(CC) -std=c11 -O1 -g $(WARN) -o $@ $< -lm
CIGI_IG_OBJ := $(addprefix $(BUILD)/obj/platform/net/,$(addsuffix .o,$(filter cigi/% common/%,$(NET_SRC))))
$(BUILD)/tests/net/cigi_ig: tests/net/cigi_ig.c $(CIGI_IG_OBJ) | deps
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) $(LDSAN) -o $@ $< $(CIGI_IG_OBJ) $(PLATFORM_LIBS)
test-platform: $(BUILD)/tests/net/dis_send $(BUILD)/tests/net/cigi_send $(BUILD)/tests/net/cigi_ig $(BUILD)/tests/vm/alloc_count.so
# the GPIO backend this build chose, where no chip is needed (errors, calls on no line)
$(BUILD)/tests/platform/test_gpio_backend: tests/platform/test_gpio_backend.c \
		$(BUILD)/obj/platform/gpio/gpio_backend.o tests/check.h
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -Itests $(LDSAN) -o $@ $< $(BUILD)/obj/platform/gpio/gpio_backend.o $(PLATFORM_LIBS)
# presentation-time feedback into the Wayland display's counters (pure logic)
$(BUILD)/tests/platform/test_present_feedback: tests/platform/test_present_feedback.c \
		$(BUILD)/obj/platform/wayland/present_feedback.o tests/check.h
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -Itests $(LDSAN) -o $@ $< $(BUILD)/obj/platform/wayland/present_feedback.o $(PLATFORM_LIBS)
GL_RESET_OBJ := $(BUILD)/obj/platform/egl/gl_reset.o $(BUILD)/obj/platform/egl/egl_headless.o
$(BUILD)/tests/platform/test_gl_reset: tests/platform/test_gl_reset.c $(GL_RESET_OBJ) tests/check.h
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -Itests $(LDSAN) -o $@ $< $(GL_RESET_OBJ) $(PLATFORM_LIBS)
# Clip detail: decoding, loop and seam (tests/platform), into a module's volume (tests/gl)
$(BUILD)/tests/platform/test_clip_detail: tests/platform/test_clip_detail.c $(BUILD)/obj/platform/video/clip_detail.o \
		$(BUILD)/obj/platform/video/luma.o $(BUILD)/libsbfx.a tests/check.h
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -Itests $(LDSAN) -o $@ $< $(BUILD)/obj/platform/video/clip_detail.o \
		$(BUILD)/obj/platform/video/luma.o $(BUILD)/libsbfx.a $(PLATFORM_LIBS) $(CLIP_PKG_LIBS)
$(BUILD)/tests/gl/test_gl_clip: tests/gl/test_gl_clip.c $(BUILD)/obj/platform/video/clip_detail.o \
		$(BUILD)/obj/platform/video/luma.o $(PLATFORM_COMMON_OBJ) $(REF_LIBS) tests/check.h $(GL_TEST_SUPPORT)
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -Iref -Itests $(LDSAN) -o $@ $< $(GL_TEST_WRAP) $(BUILD)/obj/platform/video/clip_detail.o \
		$(BUILD)/obj/platform/video/luma.o $(PLATFORM_COMMON_OBJ) $(REF_LIBS) $(PLATFORM_LIBS) $(CLIP_PKG_LIBS)
.PHONY: test-platform test-vm cross-check
test-platform: $(PLATFORM_TESTS)

# The real-kernel tier: boots Debian's kernel under qemu with vkms, vivid and gpio-sim and runs
# sbfx-play against them (tests/vm/run.sh, docs/testing.md "Real-kernel tests"). Downloads from
# Debian's archive, cached in build/vm/.
VM_TOOLS := $(BUILD)/tests/vm/pngdiff $(BUILD)/tests/vm/drm_state $(BUILD)/tests/vm/v4l2_ctrl \
	$(BUILD)/tests/vm/alloc_count.so $(BUILD)/tests/vm/vblank_stress $(BUILD)/tests/vm/gpio_backend \
	$(BUILD)/tests/platform/test_gpio_backend
# the GPIO backend this build chose, against gpio-sim (built again against libgpiod 2 below)
$(BUILD)/tests/vm/gpio_backend: tests/vm/gpio_backend.c $(BUILD)/obj/platform/gpio/gpio_backend.o
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -o $@ $^ $(PLATFORM_LIBS)
$(BUILD)/tests/vm/pngdiff: tests/vm/pngdiff.c $(BUILD)/obj/platform/image/png_io.o
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
	@$(MAKE) --no-print-directory gpiod2
	@$(MAKE) --no-print-directory test-qt-quick
	@BUILD=$(BUILD) tests/vm/run.sh

# sbfx-play and the backend check a second time, against libgpiod 2.x built from Debian 13's
# source package (tools/libgpiod2.sh, cached in build/libgpiod2), into $(BUILD)/gpiod2/: the VM
# tier runs its GPIO groups with both builds (docs/gpio.md).
.PHONY: gpiod2
gpiod2:
	@pc=$$(tools/libgpiod2.sh build/libgpiod2) && PKG_CONFIG_PATH=$$pc $(MAKE) --no-print-directory \
		BUILD=$(BUILD)/gpiod2 $(BUILD)/gpiod2/sbfx-play $(BUILD)/gpiod2/tests/vm/gpio_backend \
		$(BUILD)/gpiod2/tests/platform/test_gpio_backend

# ---- hosts (issue 18): the SDL2 example (docs/hosts/) ----------
# Built by make test (tools/deps.sh test installs their -dev packages); make and make demo
# never need them. Their tests run headless: SDL's offscreen driver (tests/hosts/).
SDL2_CFLAGS = $(call pkg_config,SDL2_CFLAGS,--cflags sdl2)
SDL2_LIBS = $(call pkg_config,SDL2_LIBS,--libs sdl2)
# The examples and integrations are hosts: they see only include/sbfx.h, through pkg-config as a
# user's build does (SBFX_PC_CFLAGS: $(BUILD)/pkgconfig/sbfx-uninstalled.pc, which pkg-config takes
# for sbfx when its folder is on PKG_CONFIG_PATH; tests/install.sh builds them again against an
# installed copy). Only the tests that look inside the module add -Isrc.
EXAMPLE_CFLAGS = $(BASE_CFLAGS) $(SBFX_PC_CFLAGS) $(CFLAGS)
$(BUILD)/obj/examples/sdl2/%.o: examples/sdl2/%.c examples/sdl2/sdl2_host.h $(SBFX_PC_UNINSTALLED) | deps
	@mkdir -p $(@D)
	$(CC) $(EXAMPLE_CFLAGS) $(SDL2_CFLAGS) -c -o $@ $<
$(BUILD)/examples/sbfx-sdl2: $(BUILD)/obj/examples/sdl2/main.o $(BUILD)/obj/examples/sdl2/sdl2_host.o $(BUILD)/libsbfx.a
	@mkdir -p $(@D)
	$(CC) $(LDSAN) -o $@ $^ $(SDL2_LIBS) $(SRC_LIBS)
$(BUILD)/tests/hosts/test_sdl2: tests/hosts/test_sdl2.c $(BUILD)/obj/examples/sdl2/sdl2_host.o $(BUILD)/libsbfx.a tests/check.h
	@mkdir -p $(@D)
	$(CC) $(EXAMPLE_CFLAGS) $(SDL2_CFLAGS) -Isrc -Iexamples/sdl2 -Itests $(LDSAN) -o $@ $< \
		$(BUILD)/obj/examples/sdl2/sdl2_host.o $(BUILD)/libsbfx.a $(SDL2_LIBS) $(SRC_LIBS)
.PHONY: test-hosts
test-hosts: $(BUILD)/examples/sbfx-sdl2 $(BUILD)/tests/hosts/test_sdl2

# The desktop OpenGL host (examples/desktop-gl/, docs/hosts/desktop-gl.md): a 3.3 core profile
# context through EGL, its own GLSL 330 shaders and libOpenGL, sbfx on the same context.
$(BUILD)/examples/sbfx-desktop-gl: examples/desktop-gl/host.c $(BUILD)/libsbfx.a $(SBFX_PC_UNINSTALLED) | deps
	@mkdir -p $(@D)
	$(CC) $(EXAMPLE_CFLAGS) $(LDSAN) -o $@ $< $(BUILD)/libsbfx.a $(OPENGL_LIBS) \
		$(call pkg_config,EGL_LIBS,--libs egl) $(SRC_LIBS)
test-hosts: $(BUILD)/examples/sbfx-desktop-gl

# ---- hosts (issue 18): Qt Quick (integrations/qt/, examples/qt-quick/, docs/hosts/qt-quick.md) ----
# Built by make test-hosts where pkg-config finds Qt 6 Quick (tools/deps.sh test installs it):
# C++17, moc and rcc from Qt6Core's libexecdir (qt6-base-dev-tools). Its test runs under Xvfb
# (tests/hosts/qt_quick.sh), so it lives in tests/qt/, not in tests/hosts/.
QT_PKGS := Qt6Quick Qt6Qml Qt6Gui
QT_PKG_CFLAGS = $(call pkg_config,QT_PKG_CFLAGS,--cflags $(QT_PKGS))
QT_PKG_LIBS = $(call pkg_config,QT_PKG_LIBS,--libs $(QT_PKGS))
QT_LIBEXEC = $(call pkg_config,QT_LIBEXEC,--variable=libexecdir Qt6Core)
QT_CXXFLAGS = -std=c++17 $(OPT) -Wall -Wextra -Wno-unused-parameter -fPIC -MMD -MP $(SBFX_PC_CFLAGS) \
	-Iintegrations/qt $(QT_PKG_CFLAGS) $(CXXFLAGS)
QT_LIBS = $(QT_PKG_LIBS) $(SRC_LIBS)
QT_OBJ := $(addprefix $(BUILD)/obj/integrations/qt/,sbfx_item.o sbfx_render_node.o moc_sbfx_item.o)
$(BUILD)/gen/qt/moc_%.cpp: integrations/qt/%.h $(SBFX_PC_UNINSTALLED) | deps
	@mkdir -p $(@D)
	$(QT_LIBEXEC)/moc -o $@ $<
$(BUILD)/gen/qt/qrc_qt_quick.cpp: examples/qt-quick/qt-quick.qrc examples/qt-quick/main.qml | deps
	@mkdir -p $(@D)
	$(QT_LIBEXEC)/rcc --name qt_quick -o $@ $<
$(BUILD)/obj/integrations/qt/%.o: integrations/qt/%.cpp integrations/qt/sbfx_item.h integrations/qt/sbfx_render_node.h $(SBFX_PC_UNINSTALLED) | deps
	@mkdir -p $(@D)
	$(CXX) $(QT_CXXFLAGS) -c -o $@ $<
$(BUILD)/obj/integrations/qt/moc_%.o: $(BUILD)/gen/qt/moc_%.cpp
	@mkdir -p $(@D)
	$(CXX) $(QT_CXXFLAGS) -c -o $@ $<
$(BUILD)/obj/examples/qt-quick/%.o: examples/qt-quick/%.cpp integrations/qt/sbfx_item.h integrations/qt/sbfx_render_node.h $(SBFX_PC_UNINSTALLED) | deps
	@mkdir -p $(@D)
	$(CXX) $(QT_CXXFLAGS) -c -o $@ $<
$(BUILD)/obj/examples/qt-quick/qrc_qt_quick.o: $(BUILD)/gen/qt/qrc_qt_quick.cpp
	@mkdir -p $(@D)
	$(CXX) $(QT_CXXFLAGS) -c -o $@ $<
$(BUILD)/examples/sbfx-qt-quick: $(BUILD)/obj/examples/qt-quick/main.o $(BUILD)/obj/examples/qt-quick/qrc_qt_quick.o \
		$(QT_OBJ) $(BUILD)/libsbfx.a
	@mkdir -p $(@D)
	$(CXX) $(LDSAN) -o $@ $^ $(QT_LIBS)
$(BUILD)/tests/qt/test_qt_quick: tests/hosts/test_qt_quick.cpp $(QT_OBJ) $(BUILD)/libsbfx.a tests/check.h \
		tests/gl/gl_snapshot.h integrations/qt/sbfx_item.h integrations/qt/sbfx_render_node.h
	@mkdir -p $(@D)
	$(CXX) $(QT_CXXFLAGS) -Itests -Itests/gl $(LDSAN) -o $@ $< $(QT_OBJ) $(BUILD)/libsbfx.a $(QT_LIBS)
.PHONY: test-qt-quick
# the library first, here: the sub-make then finds it made (no second make builds it at the same time)
test-qt-quick: $(BUILD)/libsbfx.a | deps
	@if $(PKG_CONFIG) --exists $(QT_PKGS); then \
		$(MAKE) --no-print-directory BUILD=$(BUILD) $(BUILD)/examples/sbfx-qt-quick $(BUILD)/tests/qt/test_qt_quick; \
	else echo "test-qt-quick: no Qt 6 Quick -dev packages (tools/deps.sh test installs them): not built"; fi
test-hosts: test-qt-quick

# Cross build for a board (boards/rk3588.mk: Debian's aarch64 toolchain and arm64 multiarch
# -dev packages, which its deps step installs or names) into build/rk3588/, and a check that
# what it linked is AArch64 code.
CROSS_BOARD ?= rk3588
cross-check:
	@$(MAKE) --no-print-directory BOARD=$(CROSS_BOARD) all
	@for f in build/$(CROSS_BOARD)/sbfx-play build/$(CROSS_BOARD)/sbfx-probe build/$(CROSS_BOARD)/libsbfx.so; do \
		readelf -h $$f | grep -q 'Machine:.*AArch64' || { echo "cross-check: $$f is not AArch64" >&2; exit 1; }; \
	done; echo "cross-check: build/$(CROSS_BOARD)/sbfx-play, sbfx-probe, libsbfx.so link for AArch64"

# The target GPUs' compilers without the GPUs: Mesa 25's drm-shims (tools/mesa-shim.sh, built
# once into build/mesa-shim/), every example scene compiled by each (tests/gpus/run.sh).
.PHONY: mesa-shim test-gpus
mesa-shim:
	@tools/deps.sh mesa-shim
	@nice -n 10 tools/mesa-shim.sh build >/dev/null
test-gpus: mesa-shim all
	@tests/gpus/run.sh $(BUILD)

.PHONY: FORCE
FORCE:
# Nothing made is an intermediate file: make would delete the generated sources that only a pattern
# rule reaches (the Wayland protocols' code, Qt's moc output) after a build, and the next make
# (make install, or a test suite's) would make them again and relink sbfx-play while tests run it.
.SECONDARY:

# ---- the kiosk's deployment (issue 20; docs/kiosk-deploy.md) --------------------------------
# make install also installs the example scenes and board profiles under $(DATADIR)/sbfx, the
# hardened unit dist/systemd/sbfx-kiosk.service.in with its paths filled in (and the drop-in that
# opens the network to DIS and MQTT triggers, dist/systemd/network.conf, to copy), the udev rule that
# gives /dev/gpiochip* to the group gpio and the sysusers.d file that makes that group. udev
# reads rules only from /usr/lib/udev/rules.d and /etc/udev/rules.d, so a PREFIX other than
# /usr puts the rule under /etc. On the live system (no DESTDIR, as root) the group is made
# and systemd and udev reload.
SYSTEMDUNITDIR ?= $(PREFIX)/lib/systemd/system
SYSTEMDUSERUNITDIR ?= $(PREFIX)/lib/systemd/user
SYSUSERSDIR ?= $(PREFIX)/lib/sysusers.d
UDEVRULESDIR ?= $(if $(filter /usr,$(PREFIX)),/usr/lib/udev/rules.d,/etc/udev/rules.d)
KIOSK_UNIT := sbfx-kiosk.service
# the Wayland kiosk (docs/kiosk-deploy.md "Wayland"): cage on tty1 (system), or a client of the
# session's compositor (user unit)
KIOSK_CAGE_UNIT := sbfx-kiosk-cage.service
KIOSK_USER_UNIT := sbfx-kiosk-wayland.service
kiosk_unit_from = sed -e 's|@BINDIR@|$(BINDIR)|g' -e 's|@DATADIR@|$(DATADIR)|g' $1 > $2 && chmod 644 $2
KIOSK_UDEV_RULE := 60-sbfx-gpio.rules
.PHONY: install-kiosk uninstall-kiosk
install: install-kiosk
uninstall: uninstall-kiosk
install-kiosk:
	install -d $(DESTDIR)$(DATADIR)/sbfx/scenes $(DESTDIR)$(DATADIR)/sbfx/boards \
		$(DESTDIR)$(SYSTEMDUNITDIR) $(DESTDIR)$(UDEVRULESDIR) $(DESTDIR)$(SYSUSERSDIR) \
		$(DESTDIR)$(SYSTEMDUSERUNITDIR)
	install -m 644 scenes/*.cfg $(DESTDIR)$(DATADIR)/sbfx/scenes/
	install -m 644 boards/*.cfg $(DESTDIR)$(DATADIR)/sbfx/boards/
	sed -e 's|@BINDIR@|$(BINDIR)|g' -e 's|@DATADIR@|$(DATADIR)|g' dist/systemd/$(KIOSK_UNIT).in \
		> $(DESTDIR)$(SYSTEMDUNITDIR)/$(KIOSK_UNIT)
	chmod 644 $(DESTDIR)$(SYSTEMDUNITDIR)/$(KIOSK_UNIT)
	$(call kiosk_unit_from,dist/systemd/$(KIOSK_CAGE_UNIT).in,$(DESTDIR)$(SYSTEMDUNITDIR)/$(KIOSK_CAGE_UNIT))
	$(call kiosk_unit_from,dist/systemd/user/$(KIOSK_USER_UNIT).in,$(DESTDIR)$(SYSTEMDUSERUNITDIR)/$(KIOSK_USER_UNIT))
	install -m 644 dist/udev/$(KIOSK_UDEV_RULE) $(DESTDIR)$(UDEVRULESDIR)/
	install -d $(DESTDIR)$(DATADIR)/sbfx/systemd
	$(call kiosk_unit_from,dist/systemd/network.conf,$(DESTDIR)$(DATADIR)/sbfx/systemd/network.conf)
	install -m 644 dist/sysusers/sbfx.conf $(DESTDIR)$(SYSUSERSDIR)/
	@if [ -z "$(DESTDIR)" ] && [ "$$(id -u)" -eq 0 ]; then \
		if command -v systemd-sysusers >/dev/null; then systemd-sysusers $(SYSUSERSDIR)/sbfx.conf; fi; \
		if [ -d /run/systemd/system ]; then systemctl daemon-reload; fi; \
		if command -v udevadm >/dev/null && [ -d /run/udev ]; then udevadm control --reload && \
			udevadm trigger --subsystem-match=gpio; fi; \
	fi
uninstall-kiosk:
	rm -rf $(DESTDIR)$(DATADIR)/sbfx
	rm -f $(DESTDIR)$(SYSTEMDUNITDIR)/$(KIOSK_CAGE_UNIT) $(DESTDIR)$(SYSTEMDUSERUNITDIR)/$(KIOSK_USER_UNIT)
	rm -f $(DESTDIR)$(SYSTEMDUNITDIR)/$(KIOSK_UNIT) $(DESTDIR)$(UDEVRULESDIR)/$(KIOSK_UDEV_RULE) \
		$(DESTDIR)$(SYSUSERSDIR)/sbfx.conf

# ---- Debian packages (issue 46; docs/packaging.md) ------------------------------------------
# make deb: libsbfx1, libsbfx-dev, sbfx-player, gstreamer1.0-sbfx with dpkg-buildpackage from
# dist/debian/ (tools/deb.sh: a copy of the tree in build/deb/ARCH/, the version the Makefile's
# VERSION), then lintian. ARCH=arm64: the same cross built with Debian's aarch64 toolchain and
# the arm64 build dependencies (multiarch). The packages land in build/deb/ARCH/.
SBFX_DEB_ARCH = $(or $(ARCH),$(shell dpkg --print-architecture 2>/dev/null))
DEB_DEPS = $(if $(filter $(SBFX_DEB_ARCH),$(shell dpkg --print-architecture 2>/dev/null)),deb,deb-$(SBFX_DEB_ARCH))
.PHONY: deb
deb:
	@tools/deps.sh $(DEB_DEPS)
	@tools/deb.sh $(SBFX_DEB_ARCH) build/deb

# The ABI's baseline (tests/abi.sh, in make test, compares the built library with it): abidw's
# XML of the release's libsbfx.so, the types limited to include/sbfx.h's, no build paths.
# Written once per release that changes the ABI (a new function, or a new SONAME).
ABI_BASELINE := dist/abi/libsbfx.so.$(SOVERSION).abi
.PHONY: abi-baseline
abi-baseline: lib
	@mkdir -p $(dir $(ABI_BASELINE))
	abidw --headers-dir include --drop-private-types --no-comp-dir-path --no-corpus-path --no-elf-needed \
		--out-file $(ABI_BASELINE) $(BUILD)/libsbfx.so.$(VERSION)
	@echo "abi-baseline: $(ABI_BASELINE) from $(BUILD)/libsbfx.so.$(VERSION) (sbfx $(VERSION))"

# ---- a fresh machine (issue 36; docs/testing.md "A fresh machine") ---------------------------
# The README's quick start, verbatim, in a bare Debian root (debootstrap minbase plus git and
# make): the commit under test cloned, then make demo and make test as root, and make demo as a
# plain user (the one apt-get line, run as root, then the demo). DIST=bookworm (Debian 12) or
# trixie (Debian 13: GCC 14, Mesa 25, libgpiod 2). As root; tests/fresh/run.sh says how.
# make test-debian13 is make test-fresh DIST=trixie.
.PHONY: test-fresh test-debian13
test-fresh:
	@tools/deps.sh fresh
	@DIST=$(or $(DIST),bookworm) tests/fresh/run.sh
test-debian13:
	@$(MAKE) --no-print-directory test-fresh DIST=trixie

# The Debian packages proven from the same bare root (issue 46; tests/fresh/run.sh's scenario deb,
# docs/packaging.md): built there from debian/control's build dependencies, installed with apt into
# a second bare root, run, verified and purged. ARCH=arm64: cross built and checked as aarch64 code.
.PHONY: test-deb
test-deb:
	@tools/deps.sh fresh
	@DIST=$(or $(DIST),bookworm) FRESH_AS=deb DEB_ARCH=$(SBFX_DEB_ARCH) tests/fresh/run.sh

# ---- the look (issue 17): the β metric (tests/look/look_metrics.c, docs/look.md) ----------
$(BUILD)/tests/unit/test_look_metrics: tests/unit/test_look_metrics.c $(BUILD)/obj/look/look_metrics.o $(REF_LIBS) \
		tests/check.h
	@mkdir -p $(@D)
	$(CC) $(SRC_CFLAGS) -Iref -Itests -Itests/look $(LDSAN) -o $@ $< $(BUILD)/obj/look/look_metrics.o $(REF_LIBS) \
		$(SRC_LIBS)
LOOK_OBJ := $(BUILD)/obj/look/look_metrics.o $(BUILD)/obj/look/look_render.o
$(BUILD)/bench/bench_look: $(BUILD)/obj/look/bench_look.o $(LOOK_OBJ) $(BUILD)/obj/look/fire_metric.o $(PLATFORM_COMMON_OBJ) $(REF_LIBS)
	@mkdir -p $(@D)
	$(CC) $(LDSAN) -o $@ $^ $(PLATFORM_LIBS)
bench: $(BUILD)/bench/bench_look
$(BUILD)/tests/gl/test_gl_look: tests/gl/test_gl_look.c $(LOOK_OBJ) $(PLATFORM_COMMON_OBJ) $(REF_LIBS) tests/check.h \
		$(GL_TEST_SUPPORT)
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -Iref -Itests -Itests/look $(LDSAN) -o $@ $< $(GL_TEST_WRAP) $(LOOK_OBJ) $(PLATFORM_COMMON_OBJ) \
		$(REF_LIBS) $(PLATFORM_LIBS)

# ---- GStreamer (issue 34): the element sbfx in the plugin libgstsbfx.so ---------------------
# integrations/gstreamer/ (docs/hosts/gstreamer.md): a GstGLFilter linked against libsbfx.so
# (NEEDED libsbfx.so.1), with the player's luma normalisation and clip decoding
# (platform/video/luma.c, clip_detail.c: FFmpeg's libraries). Part of `make` where pkg-config
# finds GStreamer's GL library (tools/deps.sh build installs its -dev packages), else skipped
# with a note; not under SANITIZE=1 (gst-launch-1.0 and GStreamer's plugin scanner load it, and
# they are not ASan programs). It exports GStreamer's entry point only (plugin.map).
GST_PKGS := gstreamer-1.0 gstreamer-base-1.0 gstreamer-video-1.0 gstreamer-gl-1.0
GST_PKG_CFLAGS = $(call pkg_config,GST_PKG_CFLAGS,--cflags $(GST_PKGS))
GST_PKG_LIBS = $(call pkg_config,GST_PKG_LIBS,--libs $(GST_PKGS))
GST_PLUGIN := $(BUILD)/gstreamer/libgstsbfx.so
GST_OBJ := $(patsubst %.c,$(BUILD)/obj/%.o,$(wildcard integrations/gstreamer/*.c))
GST_PLATFORM_OBJ := $(BUILD)/obj/platform/video/luma.o $(BUILD)/obj/platform/video/clip_detail.o
# The element is a host: include/sbfx.h through pkg-config (as the examples), and platform/'s luma
# and clip decoding (-Iplatform), never src/'s private headers.
GST_CFLAGS = $(BASE_CFLAGS) $(SBFX_PC_CFLAGS) $(PLATFORM_PKG_CFLAGS) -Iplatform $(CFLAGS)
$(BUILD)/obj/integrations/gstreamer/%.o: integrations/gstreamer/%.c $(SBFX_PC_UNINSTALLED) | deps
	@mkdir -p $(@D)
	$(CC) $(GST_CFLAGS) $(GST_PKG_CFLAGS) -fvisibility=hidden -DSBFX_VERSION='"$(VERSION)"' -c -o $@ $<
$(GST_PLUGIN): $(GST_OBJ) $(GST_PLATFORM_OBJ) $(SO_LINKS) integrations/gstreamer/plugin.map
	@mkdir -p $(@D)
	$(CC) -shared -Wl,-z,defs -Wl,--version-script=integrations/gstreamer/plugin.map $(LDFLAGS) -o $@ $(GST_OBJ) \
		$(GST_PLATFORM_OBJ) -L$(BUILD) -lsbfx $(GST_PKG_LIBS) $(CLIP_PKG_LIBS) $(call pkg_config,GLES_LIBS,--libs glesv2) -lm
.PHONY: gstreamer
all: gstreamer
gstreamer: lib
ifeq ($(SANITIZE),1)
	@echo "gstreamer: libgstsbfx.so is not built under SANITIZE=1 (it is loaded by programs that are not ASan's)"
else
	@if $(PKG_CONFIG) --exists $(GST_PKGS); then \
		$(MAKE) --no-print-directory BUILD=$(BUILD) $(GST_PLUGIN); \
	else echo "gstreamer: no GStreamer -dev packages (tools/deps.sh build installs them): $(GST_PLUGIN) not built"; fi
endif
# Its tests (tests/gstreamer/, run by tests/run.sh with tests/gstreamer/env.sh): C programs on
# GStreamer's libraries and appsink, built by make test where the plugin is.
GST_TEST_PKGS := $(GST_PKGS) gstreamer-app-1.0 glesv2
GST_TEST_PKG_CFLAGS = $(call pkg_config,GST_TEST_PKG_CFLAGS,--cflags $(GST_TEST_PKGS))
GST_TEST_PKG_LIBS = $(call pkg_config,GST_TEST_PKG_LIBS,--libs $(GST_TEST_PKGS))
GST_TESTS := $(patsubst tests/gstreamer/%.c,$(BUILD)/tests/gstreamer/%,$(wildcard tests/gstreamer/*.c))
$(BUILD)/tests/gstreamer/%: tests/gstreamer/%.c tests/gstreamer/gst_harness.h tests/check.h tests/gl/gl_snapshot.h | deps
	@mkdir -p $(@D)
	$(CC) $(BASE_CFLAGS) $(GST_TEST_PKG_CFLAGS) -Itests -Itests/gl $(CFLAGS) -o $@ $< $(GST_TEST_PKG_LIBS) -lm
# the element's arithmetic alone (stream_clock.c, ground_tap.c), with sbfx's matrix helpers
GST_UNIT_OBJ := $(BUILD)/obj/integrations/gstreamer/stream_clock.o $(BUILD)/obj/integrations/gstreamer/ground_tap.o
$(BUILD)/tests/gstreamer/test_gst_units: tests/gstreamer/test_gst_units.c $(GST_UNIT_OBJ) $(BUILD)/libsbfx.a tests/check.h
	@mkdir -p $(@D)
	$(CC) $(SRC_CFLAGS) -Itests -Iintegrations/gstreamer -o $@ $< $(GST_UNIT_OBJ) $(BUILD)/libsbfx.a $(SRC_LIBS)
.PHONY: test-gstreamer
test-gstreamer: gstreamer
ifneq ($(SANITIZE),1)
	@if $(PKG_CONFIG) --exists $(GST_PKGS) gstreamer-app-1.0; then \
		$(MAKE) --no-print-directory BUILD=$(BUILD) $(GST_TESTS); fi
endif
# GStreamer's plugin folder under PREFIX: pkg-config's pluginsdir with GStreamer's own prefix
# replaced by PREFIX (/usr/lib/x86_64-linux-gnu/gstreamer-1.0 -> $(PREFIX)/lib/x86_64-linux-gnu/
# gstreamer-1.0). GStreamer scans only its own folder, the user's and GST_PLUGIN_PATH: PREFIX=/usr
# installs where every GStreamer program finds it; another PREFIX needs GST_PLUGIN_PATH set to that
# folder (docs/hosts/gstreamer.md). GST_PLUGINDIR= overrides it.
GST_PKG_PREFIX = $(call pkg_config,GST_PKG_PREFIX,--variable=prefix gstreamer-1.0)
GST_PKG_PLUGINSDIR = $(call pkg_config,GST_PKG_PLUGINSDIR,--variable=pluginsdir gstreamer-1.0)
GST_PLUGINDIR ?= $(patsubst $(GST_PKG_PREFIX)/%,$(PREFIX)/%,$(GST_PKG_PLUGINSDIR))
.PHONY: install-gstreamer uninstall-gstreamer
install: install-gstreamer
uninstall: uninstall-gstreamer
install-gstreamer: all
	@if [ -f $(GST_PLUGIN) ]; then \
		install -d $(DESTDIR)$(GST_PLUGINDIR) && install -m 755 $(GST_PLUGIN) $(DESTDIR)$(GST_PLUGINDIR)/; \
	else echo "install: $(GST_PLUGIN) was not built (no GStreamer -dev packages): not installed"; fi
uninstall-gstreamer:
	@if $(PKG_CONFIG) --exists gstreamer-1.0; then rm -f $(DESTDIR)$(GST_PLUGINDIR)/libgstsbfx.so; fi
