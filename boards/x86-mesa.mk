# A generic x86-64 PC with Mesa (i915/iris, amdgpu/radeonsi, or llvmpipe): the host toolchain,
# built into build/x86-mesa/. Runtime profile: x86-mesa.cfg.
CC := gcc
DEPS := build
CFLAGS += -march=x86-64-v2
