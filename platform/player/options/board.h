/* Board profiles: what the player needs to know about a board at run time, read from a
 * libconfig file (boards/NAME.cfg, `sbfx-play --board FILE`). The toolchain side of a board is
 * boards/NAME.mk, included by the Makefile for `make BOARD=NAME`.
 *
 *   board = "rk3588"; description = "...";
 *   display = { device = "/dev/dri/card0"; connector = "HDMI-A-1"; mode = "1920x1080@60";
 *               modeset = "auto";                       # auto | atomic | legacy
 *               backend = "wayland"; };                 # drm | wayland | auto: the display
 *                                                       # without --display (or --headless)
 *   video   = { device = "/dev/video0"; size = [640, 480]; };
 *   gpio    = { debounce_ms = 30; min_interval_ms = 250;
 *               lines = ( { chip = "gpiochip0"; line = 17; edge = "rising";
 *                           effect = "explosion"; position = [0.0, 0.0, 0.0]; } ); };
 *   render  = { target_scale = 4; max_particles = 1024; };
 *   mqtt    = { host = "broker.local"; port = 1883; topic = "sbfx/trigger";     # triggers from a
 *               status_topic = "sbfx/status"; username = "kiosk";             # broker (docs/
 *               password_file = "/etc/sbfx/mqtt-password";                     # triggers.md)
 *               ca_file = "/etc/sbfx/broker-ca.pem"; min_interval_ms = 250; };
 *   dis     = { listen = "239.1.2.3:3000"; interface = "eth1"; };              # DIS detonations
 *   channel = { frustum = [-30.0, -10.0, -15.0, 15.0];      # this display's slice of the view:
 *               view_offset = [0.0, 0.0, 0.0]; };           # degrees (--frustum, --view-offset)
 *
 * Every key is optional; "" means "not set". An unknown key, a value of the wrong type or out of
 * range is an error naming the file, the line and the key. */
#ifndef SBFX_BOARD_H
#define SBFX_BOARD_H

#include <stddef.h>

#include "drm/drm_mode_spec.h" /* enum modeset_kind, mode_spec_parse: the display keys */
#include "gpio/gpio_triggers.h"
#include "net/common/net_address.h"
#include "net/mqtt/mqtt_client.h"
#include "player/options/options.h" /* struct player_channel */

struct board_profile {
    char name[64];
    char description[160];
    char drm_device[128];
    char connector[32];
    char mode[32];
    enum modeset_kind modeset;
    char backend[16];                /* "drm", "wayland", "auto" or "" (not set) */
    char video_device[128];
    int video_width, video_height;   /* 0: the driver's size */
    int gpio_debounce_ms;            /* defaults of lines that do not say (-1: not set) */
    int gpio_min_interval_ms;
    struct gpio_trigger_spec gpio[GPIO_TRIGGERS_MAX];
    int gpio_count;
    int target_scale;                /* 0: not set */
    int max_particles;               /* 0: not set */
    struct mqtt_settings mqtt;       /* host "": no broker; port 0, topics "": the defaults */
    int mqtt_min_interval_ms;        /* MQTT's rate limit per effect (GPIO's default when not set) */
    char dis_listen[64];             /* "[ADDR:]PORT" (--dis's syntax), "": not set */
    char dis_interface[16];          /* the multicast group's interface, "": the kernel's choice */
    struct player_channel channel;   /* channel.frustum, channel.view_offset */
};

void board_profile_defaults(struct board_profile *b);
/* 0, or -ENOENT / -EINVAL with "FILE:LINE: what" in err. */
int board_load(const char *path, struct board_profile *b, char *err, size_t n);


#endif
