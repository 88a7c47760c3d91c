# Rockchip RK3588 / RK3588S (Radxa Rock 5B, Orange Pi 5...): 4x Cortex-A76 + 4x Cortex-A55,
# Mali-G610 MP4 on Mesa's Panfrost (panthor on newer kernels). Runtime profile: rk3588.cfg.
include boards/aarch64-debian.mk.inc
CFLAGS += -mcpu=cortex-a76.cortex-a55
