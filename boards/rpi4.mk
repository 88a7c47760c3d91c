# Raspberry Pi 4 (BCM2711): 4x Cortex-A72, VideoCore VI on Mesa's V3D, 64-bit OS.
# Runtime profile: rpi4.cfg.
include boards/aarch64-debian.mk.inc
CFLAGS += -mcpu=cortex-a72
