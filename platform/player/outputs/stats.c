/* sbfx-play --stats: the keys, their JSON and their --help text from one table. */
#include "player/outputs/stats.h"

#include <errno.h>
#include <stddef.h>

enum stats_group { GROUP_EVERY_RUN, GROUP_KIOSK, GROUP_PRESENTATION, GROUP_GPIO, GROUP_VIDEO, GROUP_DIS, GROUP_MQTT,
                   GROUP_CIGI, GROUP_WORLD, GROUP_COUNT };
enum stats_kind { KIND_INT, KIND_G, KIND_MS3, KIND_STRING, KIND_TRIGGER_LOG };

struct stats_key {
    const char *name;
    enum stats_kind kind;
    enum stats_group group;
    size_t offset; /* of the field in struct player_stats_record */
    const char *meaning;
};

#define KEY(field, kind, group, meaning) \
    {#field, kind, group, offsetof(struct player_stats_record, field), meaning}

/* In the order the JSON object has them. */
static const struct stats_key stats_keys[] = {
    KEY(programs, KIND_INT, GROUP_EVERY_RUN, "GL programs sbfx holds"),
    KEY(textures, KIND_INT, GROUP_EVERY_RUN, "GL textures sbfx holds"),
    KEY(framebuffers, KIND_INT, GROUP_EVERY_RUN, "GL framebuffers sbfx holds"),
    KEY(gpu_bytes, KIND_INT, GROUP_EVERY_RUN, "bytes of GPU memory sbfx holds"),
    KEY(passes, KIND_INT, GROUP_EVERY_RUN, "render passes of the last frame"),
    KEY(draw_calls, KIND_INT, GROUP_EVERY_RUN, "draw calls of the last frame"),
    KEY(composite_tiles, KIND_INT, GROUP_EVERY_RUN, "screen tiles the last frame composited"),
    KEY(composite_pixels, KIND_INT, GROUP_EVERY_RUN, "pixels those tiles cover"),
    KEY(particles_simulated, KIND_INT, GROUP_EVERY_RUN, "particles the last frame's updates advanced"),
    KEY(heap_allocs_after_load, KIND_INT, GROUP_EVERY_RUN, "heap allocations after sbfx_create (0)"),
    KEY(budget_ms, KIND_G, GROUP_EVERY_RUN, "the frame budget (0: none)"),
    KEY(gpu_ms, KIND_MS3, GROUP_EVERY_RUN, "the budget governor's GPU time of the current level"),
    KEY(frames_over_budget, KIND_INT, GROUP_EVERY_RUN, "measured frames over the budget"),
    KEY(quality_changes, KIND_INT, GROUP_EVERY_RUN, "quality level changes"),
    KEY(quality, KIND_STRING, GROUP_EVERY_RUN, "the current quality level's name (a string)"),
    KEY(gpu_resets, KIND_INT, GROUP_EVERY_RUN, "GPU resets the player recovered from"),
    KEY(gpu_reset_notification, KIND_INT, GROUP_EVERY_RUN, "1 when the context reports GPU resets"),
    KEY(frames, KIND_INT, GROUP_KIOSK, "frames rendered"),
    KEY(flips, KIND_INT, GROUP_KIOSK, "page flips (wayland: frame callbacks)"),
    KEY(missed_vblanks, KIND_INT, GROUP_KIOSK, "vblanks a flip missed (wayland: refreshes)"),
    KEY(triggers_fired, KIND_INT, GROUP_KIOSK, "effects started"),
    KEY(triggers_refused, KIND_INT, GROUP_KIOSK, "triggers refused (particle pool or frame's queue full, rate limit)"),
    KEY(trigger_log, KIND_TRIGGER_LOG, GROUP_KIOSK, "the last 16 started, oldest first: {source, effect, at, time}"),
    KEY(display_unplugs, KIND_INT, GROUP_KIOSK, "times the display went away"),
    KEY(display_replugs, KIND_INT, GROUP_KIOSK, "times it came back"),
    KEY(display_paused_frames, KIND_INT, GROUP_KIOSK, "frames rendered but not shown meanwhile"),
    KEY(presented_frames, KIND_INT, GROUP_PRESENTATION, "frames the compositor put on screen"),
    KEY(discarded_frames, KIND_INT, GROUP_PRESENTATION, "frames it replaced before showing them"),
    KEY(latency_ms_mean, KIND_MS3, GROUP_PRESENTATION, "commit to on screen, mean (ms)"),
    KEY(latency_ms_max, KIND_MS3, GROUP_PRESENTATION, "commit to on screen, max (ms)"),
    KEY(gpio_edges, KIND_INT, GROUP_GPIO, "edges read from the GPIO lines"),
    KEY(gpio_fired, KIND_INT, GROUP_GPIO, "edges that fired their effect"),
    KEY(gpio_filtered, KIND_INT, GROUP_GPIO, "edges the debounce or rate limit dropped"),
    KEY(gpio_refused, KIND_INT, GROUP_GPIO, "edges whose trigger sbfx refused"),
    KEY(gpio_overflows, KIND_INT, GROUP_GPIO, "reads that found the kernel's event FIFO full"),
    KEY(gpio_losses, KIND_INT, GROUP_GPIO, "lines lost (their chip went away)"),
    KEY(gpio_returns, KIND_INT, GROUP_GPIO, "lost lines requested again"),
    KEY(gpio_retries, KIND_INT, GROUP_GPIO, "attempts to request a lost line"),
    KEY(gpio_absent, KIND_INT, GROUP_GPIO, "lines whose chip or line was absent at start"),
    KEY(gpio_appeared, KIND_INT, GROUP_GPIO, "lines absent at start that appeared later"),
    KEY(video_frames, KIND_INT, GROUP_VIDEO, "camera slices pushed to the detail volume"),
    KEY(video_distinct, KIND_INT, GROUP_VIDEO, "slices that differed from the slice before"),
    KEY(video_losses, KIND_INT, GROUP_VIDEO, "outages: the camera went away, failed or fell silent"),
    KEY(video_reopens, KIND_INT, GROUP_VIDEO, "outages that ended with frames again"),
    KEY(video_takeovers, KIND_INT, GROUP_VIDEO, "procedural volumes pushed back meanwhile"),
    KEY(dis_pdus, KIND_INT, GROUP_DIS, "DIS PDUs read (= detonations + ignored + malformed)"),
    KEY(dis_detonations, KIND_INT, GROUP_DIS, "Detonation PDUs that set off an effect"),
    KEY(dis_ignored, KIND_INT, GROUP_DIS, "other PDU types, exercises, repeats, out of range, unmapped"),
    KEY(dis_malformed, KIND_INT, GROUP_DIS, "truncated, oversized, wrong version or length: dropped"),
    KEY(mqtt_messages, KIND_INT, GROUP_MQTT, "messages on the trigger topic"),
    KEY(mqtt_malformed, KIND_INT, GROUP_MQTT, "payloads not EFFECT[@X,Y,Z] of an effect there is"),
    KEY(mqtt_reconnects, KIND_INT, GROUP_MQTT, "connections made again after the broker went away"),
    KEY(cigi_messages, KIND_INT, GROUP_CIGI, "CIGI messages (datagrams) read from the host"),
    KEY(cigi_malformed, KIND_INT, GROUP_CIGI, "packets dropped: truncated, wrong size, version or magic, not a number"),
    KEY(cigi_ignored, KIND_INT, GROUP_CIGI, "packets not used: other types, entities that are no effect, other views"),
    KEY(cigi_entities, KIND_INT, GROUP_CIGI, "effect entities started (Entity Control went Active)"),
    KEY(cigi_stopped, KIND_INT, GROUP_CIGI, "effect instances ended (Destroyed, Inactive, animation stopped)"),
    KEY(cigi_start_of_frame, KIND_INT, GROUP_CIGI, "Start of Frame messages sent to the host"),
    KEY(world_time, KIND_MS3, GROUP_WORLD, "the last frame's world time (s)"),
    KEY(triggers_expired, KIND_INT, GROUP_WORLD, "identified triggers heard after their effect had ended"),
};

static const char *const group_titles[GROUP_COUNT] = {
    [GROUP_EVERY_RUN] = "every run (sbfx_stats() after the last frame, and GPU resets)",
    [GROUP_KIOSK] = "with a DRM or Wayland display, GPIO lines, a camera, --dis or --mqtt",
    [GROUP_PRESENTATION] = "with a Wayland compositor's presentation-time feedback",
    [GROUP_GPIO] = "with GPIO lines",
    [GROUP_VIDEO] = "with a camera",
    [GROUP_DIS] = "with --dis (or a board's dis.listen)",
    [GROUP_MQTT] = "with --mqtt (or a board's mqtt.host)",
    [GROUP_CIGI] = "with --cigi",
    [GROUP_WORLD] = "in world mode (--world-time, --world-clock)",
};

static bool group_written(const struct player_stats_record *r, enum stats_group group)
{
    switch (group) {
    case GROUP_KIOSK: return r->kiosk_on;
    case GROUP_PRESENTATION: return r->presentation_on;
    case GROUP_GPIO: return r->kiosk_on && r->gpio_on;
    case GROUP_VIDEO: return r->kiosk_on && r->video_on;
    case GROUP_DIS: return r->dis_on;
    case GROUP_MQTT: return r->mqtt_on;
    case GROUP_CIGI: return r->cigi_on;
    case GROUP_WORLD: return r->world_on;
    default: return true;
    }
}

/* [{"source": "dis", "effect": "explosion", "at": [x, y, z], "time": s}, ...] (names of the
 * module's effects: letters, digits, _ - . only; escaped all the same) */
static void write_trigger_log(const struct player_stats_record *r, FILE *f)
{
    fputc('[', f);
    for (int i = 0; i < r->trigger_log_count; i++) {
        const struct stats_trigger *e = &r->trigger_log[i];
        fprintf(f, "%s{\"source\": \"%s\", \"effect\": \"", i ? ", " : "", e->source);
        for (const char *c = e->effect; *c; c++) {
            if (*c == '"' || *c == '\\') fputc('\\', f);
            if ((unsigned char)*c >= 0x20) fputc(*c, f);
        }
        fprintf(f, "\", \"at\": [%.7g, %.7g, %.7g], \"time\": %.6f}", (double)e->at[0], (double)e->at[1],
                (double)e->at[2], e->time);
    }
    fputc(']', f);
}

static void write_value(const struct player_stats_record *r, const struct stats_key *k, FILE *f)
{
    const char *field = (const char *)r + k->offset;
    switch (k->kind) {
    case KIND_INT: fprintf(f, "%lld", *(const long long *)(const void *)field); break;
    case KIND_G: fprintf(f, "%g", *(const double *)(const void *)field); break;
    case KIND_MS3: fprintf(f, "%.3f", *(const double *)(const void *)field); break;
    /* the level's name comes from sbfx_quality_name: letters, digits and '/' only */
    case KIND_STRING: fprintf(f, "\"%s\"", field); break;
    case KIND_TRIGGER_LOG: write_trigger_log(r, f); break;
    }
}

int player_stats_write(const struct player_stats_record *r, FILE *f)
{
    const char *sep = "{";
    for (size_t i = 0; i < sizeof(stats_keys) / sizeof(stats_keys[0]); i++) {
        const struct stats_key *k = &stats_keys[i];
        if (!group_written(r, k->group)) continue;
        fprintf(f, "%s\"%s\": ", sep, k->name);
        write_value(r, k, f);
        sep = ", ";
    }
    fprintf(f, "}\n");
    return ferror(f) ? -EIO : 0;
}

void player_stats_usage(FILE *f)
{
    fprintf(f, "--stats keys (one JSON object; numbers unless said):\n");
    for (int g = 0; g < GROUP_COUNT; g++) {
        fprintf(f, "  %s:\n", group_titles[g]);
        for (size_t i = 0; i < sizeof(stats_keys) / sizeof(stats_keys[0]); i++)
            if (stats_keys[i].group == (enum stats_group)g)
                fprintf(f, "    %-24s %s\n", stats_keys[i].name, stats_keys[i].meaning);
    }
}
