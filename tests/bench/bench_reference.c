/* The CPU reference of one frame of a module: bench_reference.h. */
#include "bench_reference.h"

#include <stdlib.h>

static void fill_media(sbfx *fx, sbfx_rf_frame *f)
{
    const sbfx_medium_params *m = sbfx_media(fx);
    for (int i = 0; i < SBFX_MEDIUM_COUNT; i++)
        f->media[i] = (sbfx_rf_medium){
            .albedo = m[i].albedo, .tau = m[i].tau, .phase_g = m[i].phase_g,
            .color = {m[i].color[0], m[i].color[1], m[i].color[2]},
            .detail_strength = m[i].detail_strength, .detail_window = m[i].detail_window,
            .t0 = m[i].t0, .t1 = m[i].t1, .cooling = m[i].cooling, .soot = m[i].soot, .emission_scale = m[i].emission_scale,
            .has_detail = m[i].detail_strength > 0};
}

static int fill_lights(sbfx *fx, const float view[16], sbfx_rf_light *out, double ambient[3])
{
    sbfx_view_light lights[SBFX_RF_MAX_LIGHTS];
    int n = sbfx_frame_lights(fx, view, lights, SBFX_RF_MAX_LIGHTS);
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 4; k++) {
            out[i].vector[k] = lights[i].vector[k];
            if (k < 3) out[i].color[k] = lights[i].color[k];
        }
    float a[3];
    sbfx_frame_ambient(fx, a);
    for (int k = 0; k < 3; k++) ambient[k] = a[k];
    return n;
}

static sbfx_rf_particle *fill_particles(sbfx *fx, const float view[16], int *count)
{
    const sbfx_view_particle *v;
    int n = sbfx_frame_particles(fx, view, &v);
    sbfx_rf_particle *p = calloc(n > 0 ? (size_t)n : 1, sizeof(*p));
    for (int i = 0; p && i < n; i++) {
        p[i] = (sbfx_rf_particle){.radius = v[i].radius, .intensity = v[i].intensity, .medium = v[i].medium};
        for (int k = 0; k < 3; k++) p[i].center[k] = v[i].center[k], p[i].detail[k] = v[i].detail[k];
    }
    *count = n;
    return p;
}

int bench_reference_render(const bench_reference *r, sbfx *fx, const sbfx_frame *frame, const double *distance,
                           const uint8_t *scene_rgba, double *out_rgb, uint8_t *footprint)
{
    int w = frame->width, h = frame->height, count = 0;
    const float *p = frame->projection;
    sbfx_rf_light lights[SBFX_RF_MAX_LIGHTS];
    sbfx_rf_frame f = {.width = w, .height = h, .projection = {p[0], p[5], p[8], p[9]},
                       .near = sbfx_window_distance(frame, 0.0f), .opaque_distance = distance,
                       .opacity = SBFX_OPACITY_EXACT, .lights = lights, .detail = r->detail,
                       .detail_size = r->detail_size, .detail_frames = r->detail_frames,
                       .detail_time = sbfx_detail_time(fx), .cmf = r->cmf,
                       .blackbody_norm = sbfx_blackbody_norm(r->cmf, SBFX_DEFAULT_MAX_KELVIN)};
    fill_media(fx, &f);
    f.exposure = sbfx_get_desc(fx)->exposure;
    f.fire_light = sbfx_fire_lit(fx);
    f.light_count = fill_lights(fx, frame->view, lights, f.ambient);
    sbfx_rf_particle *particles = fill_particles(fx, frame->view, &count);
    double *layer = calloc((size_t)w * h * 4, sizeof(double));
    uint8_t *own = footprint ? NULL : calloc((size_t)w * h, 1);
    int result = count;
    if (!particles || !layer || (!footprint && !own) ||
        sbfx_rf_render_layer(&f, particles, count, layer, footprint ? footprint : own) < 0)
        result = -1;
    else
        sbfx_rf_composite(layer, scene_rgba, w, h, sbfx_get_desc(fx)->tone_map, out_rgb);
    free(layer);
    free(own);
    free(particles);
    return result;
}
