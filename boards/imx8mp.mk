# NXP i.MX 8M Plus: 4x Cortex-A53, Vivante GC7000UL on Mesa's etnaviv. Runtime profile:
# imx8mp.cfg.
include boards/aarch64-debian.mk.inc
CFLAGS += -mcpu=cortex-a53
