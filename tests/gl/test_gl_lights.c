/* The phase shaders' light loop is sized at load (src/scene/plan.c, docs/gpus.md): the scene's
 * lights plus one effect's flashes; more lights set later make the programs again. */
#include "gl_fixture.h"
#include "module.h" /* fx->scene->light_slots */

static char shader_log[8192];

static void keep_shader_builds(sbfx_log_level level, const char *message, void *user)
{
    (void)level, (void)user;
    if (strstr(message, "shader build begin:") && strlen(shader_log) + strlen(message) + 2 < sizeof(shader_log)) {
        strcat(shader_log, message);
        strcat(shader_log, "\n");
    }
}

static sbfx *module_of(const char *scene_name)
{
    sbfx_scene *scene = fixture_load_scene(scene_name);
    sbfx *fx = NULL;
    sbfx_desc d = {.scene = scene, .log = keep_shader_builds};
    CHECK(sbfx_create(&d, &fx) == SBFX_OK, "%s: %s", scene_name, fx ? sbfx_last_error(fx) : "no module");
    sbfx_scene_free(scene);
    if (!fx) exit(1);
    return fx;
}

CHECK_TEST(light_slots_are_the_scenes_lights_and_one_effects_flashes)
{
    gl_fixture f;
    fixture_open(&f, 32, 32);
    setenv("SBFX_SHADER_LOG", "1", 1);
    static const struct { const char *scene; int slots; } cases[] = {
        {"explosion", 2}, /* one directional light, one light flash */
        {"smoke", 1},     /* one light, no flash */
    };
    for (size_t i = 0; i < ARRAY_SIZE(cases); i++) {
        shader_log[0] = '\0';
        sbfx *fx = module_of(cases[i].scene);
        char want[32];
        snprintf(want, sizeof(want), "LIGHT_SLOTS=%d ", cases[i].slots);
        CHECK(fx->scene->light_slots == cases[i].slots, "%s: %d slots", cases[i].scene, fx->scene->light_slots);
        CHECK(strstr(shader_log, want) != NULL, "%s: no %s in\n%s", cases[i].scene, want, shader_log);
        CHECK(strstr(shader_log, "LIGHT_SLOTS=8") == NULL, "%s: a loop over 8 lights", cases[i].scene);
        sbfx_destroy(fx);
    }
    fixture_close(&f);
}

CHECK_TEST(more_lights_than_slots_make_the_programs_again)
{
    gl_fixture f;
    fixture_open(&f, 32, 32);
    setenv("SBFX_SHADER_LOG", "1", 1);
    shader_log[0] = '\0';
    sbfx *fx = module_of("smoke");
    sbfx_counters before, after;
    sbfx_stats(fx, &before);
    sbfx_view_light lights[5];
    for (int i = 0; i < 5; i++)
        lights[i] = (sbfx_view_light){{0.0f, -1.0f, 0.0f, 0.0f}, {0.2f * (float)i, 0.5f, 0.5f}};
    shader_log[0] = '\0';
    sbfx_set_lights(fx, lights, 5, (const float[3]){0.1f, 0.1f, 0.1f});
    sbfx_stats(fx, &after);
    CHECK(fx->scene->light_slots == 5, "%d slots", fx->scene->light_slots);
    CHECK(strstr(shader_log, "LIGHT_SLOTS=5 ") != NULL, "no LIGHT_SLOTS=5 build in\n%s", shader_log);
    CHECK(after.programs == before.programs, "programs %d -> %d", before.programs, after.programs);
    float view[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    sbfx_view_light got[8];
    CHECK(sbfx_frame_lights(fx, view, got, 8) == 5, "the frame's lights");
    fixture_projection(&f, 0.9f, 0.1f, 100.0f);
    CHECK(sbfx_render(fx, &f.frame) == SBFX_OK, "%s", sbfx_last_error(fx));
    shader_log[0] = '\0';
    sbfx_set_lights(fx, lights, 3, (const float[3]){0.1f, 0.1f, 0.1f});
    CHECK(fx->scene->light_slots == 5 && shader_log[0] == '\0', "fewer lights rebuilt: %d slots", fx->scene->light_slots);
    sbfx_destroy(fx);
    fixture_close(&f);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
