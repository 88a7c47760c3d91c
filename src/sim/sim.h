/* The sim room (src/rooms.txt; docs/hacking.md): the particles on the CPU, no GL. Above the
 * scene (what to spawn) and the tables' math.
 *
 * Exports to the rooms above:
 *   - the pool and the view-space particle (particles.h); the fixed-step simulation and effect
 *     instances spawned into the pool (sim.c), the clock and the timeline of triggers
 *     (timeline.c: sbfx_fire, which tells the host's trigger listener, sbfx_timeline_add/advance,
 *     sbfx_clock_phase);
 *   - the frame's particles in view space (view.c), their back-to-front order (sort.c), the
 *     level of detail that merges them (lod.h);
 *   - orbiting lights on the clock (lights.c);
 *   - fire as light (fire_light.h: the model in double; fire_lights.c: the live fire gathered
 *     into point lights, for the host and for the frame's dust and smoke).
 * Its state: sbfx_sim (fx->sim). */
#ifndef SBFX_SIM_H
#define SBFX_SIM_H

#include "base/base.h"
#include "scene/scene_tables.h"
#include "sim/fire_light.h"
#include "sim/lod.h"
#include "sim/particles.h"

#define SBFX_MAX_SCHEDULE 128
#define SBFX_MAX_LIVE_FLASHES 8
#define SBFX_DETAIL_LOOP_SECONDS 4.0 /* the detail animation's loop */

typedef struct sbfx_scheduled {
    int effect;
    double time;
    float position[3];
    sbfx_trigger_origin origin; /* sbfx_schedule, or the scene's timeline */
} sbfx_scheduled;

typedef struct sbfx_live_flash {
    uint64_t identity;           /* its instance's (sbfx_trigger_identified), 0: none */
    double start;
    float duration;
    float color[3], position[3];
} sbfx_live_flash;

/* The sim room's state (fx->sim). */
typedef struct sbfx_sim {
    sbfx_pool pool;
    double time, accumulator;    /* time: seconds since create (whole steps); the clock
                                    is desc.start_time + time (sbfx_time) */
    uint64_t step_index;
    uint32_t trigger_count;
    sbfx_trigger_fn trigger_listener; /* sbfx_set_trigger_listener: told of each instance started */
    void *trigger_listener_user;
    int particles_simulated;
    sbfx_scheduled schedule[SBFX_MAX_SCHEDULE]; /* sorted by time; [next_scheduled, count) pending */
    int schedule_count, next_scheduled;
    sbfx_live_flash flashes[SBFX_MAX_LIVE_FLASHES];
    int flash_count;
    /* the frame's scratch, sized max_particles at load */
    sbfx_view_particle *view;
    float *sort_keys;
    bool view_identified;        /* the frame's particles include identified ones (sort.c's ties) */
    uint32_t *order, *order_tmp;
    float *instances;            /* the plan's instance_floats per particle (render/particles.c) */
    float previous_view[16];     /* the last render's view and time (particle velocities) */
    double previous_render_time;
    bool have_previous_view;
    particle_lod lod;            /* level of detail (lodN levels): work memory made with the */
    void *lod_work;              /* first level that needs it (at load for declared ones) */
    /* fire as light (fire_lights.c): work memory made at load when the scene has fire */
    sbfx_fire_particle *fire_particles;
    sbfx_fire_work *fire_work;
    double fire_detail[SBFX_FIRE_DETAIL_LEVELS]; /* the detail volume's quantiles (fire_light.h), */
    bool fire_detail_made;       /* made with the volume only where the scene has fire (gl/luts.c) */
    uint16_t *fire_slice_histograms; /* detail_frames x SBFX_FIRE_DETAIL_BINS: each slice's values, so
                                        the quantiles follow pushed slices; only where the scene's
                                        detail is live or a clip and fire emits (gl/luts.c) */
    sbfx_fire_gathered emitted[SBFX_MAX_POINT_LIGHTS]; /* world space, after the last update */
    int emitted_count;
    bool emitted_current;        /* emitted[] gathered since the last sbfx_update */
    sbfx_fire_gathered frame_fire[SBFX_MAX_POINT_LIGHTS]; /* view space, the frame rendered */
    int frame_fire_count;
} sbfx_sim;

/* sim.c */
sbfx_result sbfx_pool_create(sbfx *fx, int capacity);
void sbfx_pool_destroy(sbfx *fx);
sbfx_result sbfx_spawn_effect(sbfx *fx, const sbfx_effect *effect, const float position[3]);
/* An identified instance (sbfx_trigger_identified): seeded from identity alone, its particles
 * on the grid start + j * step (sbfx_sync_identified brings them to the clock). */
sbfx_result sbfx_spawn_identified(sbfx *fx, const sbfx_effect *effect, const float position[3],
                                  uint64_t identity, double start);
/* Steps every identified particle to the host's time `now` (clock seconds): as many steps of its
 * own grid as lie in (start, now]; catching up is at most its delay + life. */
void sbfx_sync_identified(sbfx *fx, double now);
/* Removes every particle of the identified instance; returns how many. */
int sbfx_retire_identified(sbfx *fx, uint64_t identity);
/* One module step: the particles that step with the module (identified ones are synced). */
void sbfx_simulate_step(sbfx *fx, float step);
/* The level of detail's work memory (first lodN level). */
sbfx_result sbfx_lod_create(sbfx *fx);
/* Hash of the live particles' simulation state (determinism tests). */
uint64_t sbfx_state_hash(const sbfx *fx);

/* timeline.c */
/* Starts one instance of effect `index`: its particles, and its light flashes as live lights;
 * the trigger listener is told, with the origin. */
sbfx_result sbfx_fire(sbfx *fx, int index, const float position[3], sbfx_trigger_origin origin);
/* The same for an identified instance (sbfx_trigger_identified): start on the clock (sbfx_time). */
sbfx_result sbfx_fire_identified(sbfx *fx, int index, const float position[3], uint64_t identity, double start);
/* Ends an identified instance: its particles and flashes; returns the particles removed. */
int sbfx_stop_instance(sbfx *fx, uint64_t identity);
/* The host's time: the clock (sbfx_time) plus the update's remainder not yet stepped. */
double sbfx_host_time(const sbfx *fx);
/* Adds a trigger of effect `index` at `seconds` (simulation time) to the timeline; it fires with
 * its origin (sbfx_schedule's, or the scene's timeline). */
sbfx_result sbfx_timeline_add(sbfx *fx, int index, double seconds, const float position[3],
                              sbfx_trigger_origin origin);
/* Advances the clock by dt in whole steps: the triggers due fired, the particles simulated. */
void sbfx_timeline_advance(sbfx *fx, double dt);
/* The clock's phase in a cycle of |period| seconds, in [0, 1), reduced in double precision
 * (docs/design.md §7): what every periodic value starts from. */
double sbfx_clock_phase(const sbfx *fx, double period);
/* The detail time coordinate the shader samples at (in detail-volume loops). */
double sbfx_detail_time(const sbfx *fx);

/* view.c */
/* Live particles whose delay has passed, in view space, into fx->sim->view; returns the count. */
int sbfx_collect_view_particles(sbfx *fx, const float view[16]);
/* The view and clock of the frame just rendered (the next one's particle velocities). */
void sbfx_view_rendered(sbfx *fx, const float view[16]);
/* What the renderer would draw for this view: live particles in view space (unsorted,
 * invalid ones skipped), as the last sbfx_render saw them. Returns the count; *out is owned
 * by the module and valid until the next render or update. */
int sbfx_frame_particles(sbfx *fx, const float view[16], const sbfx_view_particle **out);

/* sort.c: back-to-front order of fx->sim->view[0..count) by view distance into fx->sim->order */
void sbfx_sort_back_to_front(sbfx *fx, int count);

/* lights.c: moves orbiting point lights to their place on the clock */
void sbfx_orbit_lights(sbfx *fx);

/* fire_lights.c: fire gathered into point lights (sim/fire_light.h) */
sbfx_result sbfx_fire_lights_create(sbfx *fx);
void sbfx_fire_lights_destroy(sbfx *fx);
/* The fire model of the loaded scene (its black body: the scene's table). */
sbfx_fire_model sbfx_fire_model_of(const sbfx *fx);
/* The frame's fire (fx->sim->view[0..count), view space) gathered into fx->sim->frame_fire. */
void sbfx_fire_lights_of_frame(sbfx *fx, int count);

#endif
