/* What the page's panels show (web.h): sbfx_stats() under sbfx-play's --stats key names
 * (platform/player/outputs/stats.c; the counters a browser run has), and what the WebGL 2
 * context offers that the library looks for, with the fallback it took where it is missing. */
#include <GLES3/gl3.h>
#include <stdio.h>
#include <string.h>

#include "web/web.h"

static const char *const format_names[SBFX_FORMAT_COUNT] = {"default", "rgba8", "rgba16f", "rgba32f"};

const char *web_stats_json(struct web_host *h, char *buf, size_t size)
{
    sbfx_counters c;
    sbfx_stats(h->fx, &c);
    const char *format = (unsigned)c.target_format < SBFX_FORMAT_COUNT ? format_names[c.target_format] : "?";
    snprintf(buf, size,
             "{\"time\":%.4f,\"programs\":%d,\"textures\":%d,\"framebuffers\":%d,\"gpu_bytes\":%zu,"
             "\"passes\":%d,\"draw_calls\":%d,\"composite_tiles\":%d,\"composite_pixels\":%d,"
             "\"particles_simulated\":%d,\"particles_alive\":%d,\"heap_allocs_after_load\":%llu,"
             "\"quality\":\"%s\",\"target_format\":\"%s\",\"triggers_fired\":%d,\"triggers_refused\":%d,"
             "\"gl_state_queries\":%d,\"emitted_lights\":%d,\"fire_lit_particles\":%d,\"shadow_passes\":%d,"
             "\"programs_compiled\":%d,\"targets_created\":%d,\"scene_reloads\":%d,\"budget_ms\":%g,"
             "\"gpu_ms\":%.3f,\"frames_over_budget\":%d,\"quality_changes\":%d,\"width\":%d,\"height\":%d}",
             h->sim_time, c.programs, c.textures, c.framebuffers, c.gpu_bytes, c.passes, c.draw_calls,
             c.composite_tiles, c.composite_pixels, c.particles_simulated, c.particles_alive,
             (unsigned long long)c.heap_allocs_after_load, c.quality, format, c.triggers_fired, c.triggers_refused,
             c.gl_state_queries, c.emitted_lights, c.fire_lit_particles, c.shadow_passes, c.programs_compiled,
             c.targets_created, c.scene_reloads, c.budget_ms, c.gpu_ms, c.frames_over_budget, c.quality_changes,
             h->width, h->height);
    return buf;
}

static bool has_extension(const char *name)
{
    GLint count = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &count);
    for (GLint i = 0; i < count; i++) {
        const char *e = (const char *)glGetStringi(GL_EXTENSIONS, (GLuint)i);
        if (e && strcmp(e, name) == 0) return true;
    }
    return false;
}

static const char *gl_string(GLenum name)
{
    const char *s = (const char *)glGetString(name);
    return s ? s : "?";
}

/* A string with no character JSON would need escaped (the GL strings have none, but a driver's
 * name is not ours to trust): quotes and backslashes become spaces. */
static const char *plain(const char *s, char *out, size_t size)
{
    snprintf(out, size, "%s", s);
    for (char *p = out; *p; p++)
        if (*p == '"' || *p == '\\' || (unsigned char)*p < 0x20) *p = ' ';
    return out;
}

const char *web_info_json(struct web_host *h, char *buf, size_t size)
{
    sbfx_counters c;
    sbfx_stats(h->fx, &c);
    char version[256], renderer[256], glsl[256];
    snprintf(buf, size,
             "{\"version\":\"%s\",\"renderer\":\"%s\",\"glsl\":\"%s\",\"timer_query\":%s,"
             "\"color_buffer_float\":%s,\"color_buffer_half_float\":%s,\"float_blend\":%s,"
             "\"texture_float_linear\":%s,\"target_format\":\"%s\"}",
             plain(gl_string(GL_VERSION), version, sizeof(version)),
             plain(gl_string(GL_RENDERER), renderer, sizeof(renderer)),
             plain(gl_string(GL_SHADING_LANGUAGE_VERSION), glsl, sizeof(glsl)),
             has_extension("GL_EXT_disjoint_timer_query") ? "true" : "false",
             has_extension("GL_EXT_color_buffer_float") ? "true" : "false",
             has_extension("GL_EXT_color_buffer_half_float") ? "true" : "false",
             has_extension("GL_EXT_float_blend") ? "true" : "false",
             has_extension("GL_OES_texture_float_linear") ? "true" : "false",
             (unsigned)c.target_format < SBFX_FORMAT_COUNT ? format_names[c.target_format] : "?");
    return buf;
}
