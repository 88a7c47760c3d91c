/* Scene files: the examples load; every kind of bad input gets one message with the file name
 * and line number, an error code, and no scene. */
#include <math.h>
#include <string.h>
#include "check.h"
#include "sbfx.h"
#include "scene/scene.h"

#define MEDIA "media = { smoke = { albedo = 0.2; density = 0.4; }; };\n"
#define EFFECT(body) "effects = { puff = { steps = ( " body " ); }; };\n"
#define EMITTER "{ type = \"emitter\"; medium = \"smoke\"; count = 10; }"

static const char *const examples[] = {"explosion", "smoke", "campfire", "dust-storm", "barrage"};

CHECK_TEST(example_scenes_load)
{
    for (size_t i = 0; i < sizeof(examples) / sizeof(examples[0]); i++) {
        char path[256], err[512] = "";
        snprintf(path, sizeof(path), "scenes/%s.cfg", examples[i]);
        sbfx_scene *scene = NULL;
        sbfx_result r = sbfx_scene_load(path, &scene, err, sizeof(err));
        CHECK(r == SBFX_OK && scene, "%s: %s", path, err);
        sbfx_scene_free(scene);
    }
}

/* Parses `text` and expects failure with a message containing each of `needles`. */
static void expect_error(const char *text, int line, const char *needle)
{
    char err[512] = "", where[64];
    sbfx_scene *scene = (sbfx_scene *)1;
    sbfx_result r = sbfx_scene_parse(text, "bad.cfg", &scene, err, sizeof(err));
    CHECK(r == SBFX_ERR_INVALID_ARGUMENT, "accepted: %s", text);
    CHECK(scene == NULL, "a failed parse left a scene behind");
    if (line > 0) snprintf(where, sizeof(where), "bad.cfg:%d:", line);
    else snprintf(where, sizeof(where), "bad.cfg: "); /* about the file as a whole */
    CHECK(strncmp(err, where, strlen(where)) == 0, "message \"%s\" does not start with %s", err, where);
    CHECK(strstr(err, needle) != NULL, "message \"%s\" lacks \"%s\"", err, needle);
}

CHECK_TEST(minimal_scene_parses)
{
    char err[256];
    sbfx_scene *scene = NULL;
    CHECK(sbfx_scene_parse(MEDIA EFFECT(EMITTER), "ok.cfg", &scene, err, sizeof(err)) == SBFX_OK, "%s", err);
    sbfx_scene_free(scene);
}

CHECK_TEST(syntax_error_names_line)
{
    expect_error(MEDIA "\neffects = { puff = { steps = ( { type = \"emitter\"; count = ; } ); }; };\n", 3,
                 "syntax error");
}

CHECK_TEST(unknown_key_suggests_nearest)
{
    expect_error("media = { smoke = { albedo = 0.2;\n densty = 0.4; }; };\n" EFFECT(EMITTER), 2,
                 "did you mean 'density'");
    expect_error(MEDIA "\n\nrender = { target_scal = 4; };\n" EFFECT(EMITTER), 4, "did you mean 'target_scale'");
    expect_error(MEDIA "effekts = {};\n", 2, "did you mean 'effects'");
}

CHECK_TEST(wrong_type_is_named)
{
    expect_error("media = { smoke = { albedo = \"high\"; }; };\n" EFFECT(EMITTER), 1, "'albedo' must be a number");
    expect_error(MEDIA EFFECT("{ type = \"emitter\"; medium = \"smoke\"; count = 2.5; }"), 2,
                 "'count' must be an integer");
    expect_error(MEDIA EFFECT("{ type = \"emitter\"; medium = \"smoke\"; speed = 3.0; }"), 2,
                 "'speed' must be an array of 2 numbers");
}

CHECK_TEST(out_of_range_values_are_named)
{
    expect_error("media = { smoke = { density = -1.0; }; };\n" EFFECT(EMITTER), 1, "'density' = -1 is out of range");
    expect_error(MEDIA EFFECT("{ type = \"emitter\"; medium = \"smoke\"; radius = [-1.0, 2.0]; }"), 2,
                 "'radius'[0] = -1 is out of range");
    expect_error(MEDIA EFFECT("{ type = \"emitter\"; medium = \"smoke\"; count = 5000000; }"), 2,
                 "'count' = 5000000 is out of range");
    expect_error(MEDIA "render = { target_scale = 3; };\n" EFFECT(EMITTER), 2, "use 1, 2, 4 or 8");
    expect_error(MEDIA EFFECT("{ type = \"emitter\"; medium = \"smoke\"; lifetime = [3.0, 1.0]; }"), 2,
                 "must not exceed");
}

CHECK_TEST(missing_or_undefined_medium)
{
    expect_error(MEDIA EFFECT("{ type = \"emitter\"; count = 3; }"), 2, "needs 'medium'");
    expect_error(MEDIA EFFECT("{ type = \"emitter\"; medium = \"fire\"; }"), 2, "'fire', which is not defined in media");
    expect_error(MEDIA EFFECT("{ type = \"emitter\"; medium = \"lava\"; }"), 2, "\"lava\" is not one of: dust, smoke, fire");
    expect_error(EFFECT(EMITTER), 0, "no 'media'");
}

CHECK_TEST(triggers_must_name_defined_effects)
{
    expect_error(MEDIA EFFECT(EMITTER) "triggers = { timeline = ( { effect = \"boom\"; time = 1.0; } ); };\n", 3,
                 "effect 'boom', which is not defined");
    expect_error(MEDIA EFFECT(EMITTER) "triggers = { gpio = ( { chip = \"gpiochip0\"; effect = \"puff\"; } ); };\n", 3,
                 "needs 'line'");
}

CHECK_TEST(missing_file_is_named)
{
    char err[512];
    sbfx_scene *scene = (sbfx_scene *)1;
    CHECK(sbfx_scene_load("/nonexistent/scene.cfg", &scene, err, sizeof(err)) == SBFX_ERR_INVALID_ARGUMENT);
    CHECK(scene == NULL);
    CHECK(strstr(err, "/nonexistent/scene.cfg") != NULL, "%s", err);
}

CHECK_TEST(gpio_triggers_are_exposed)
{
    char err[256];
    sbfx_scene *scene = NULL;
    const char *text = MEDIA EFFECT(EMITTER)
        "triggers = { gpio = ( { chip = \"gpiochip1\"; line = 17; edge = \"falling\"; debounce_ms = 25;"
        " effect = \"puff\"; position = [1.0, 0.0, -2.0]; } ); };\n";
    CHECK(sbfx_scene_parse(text, "gpio.cfg", &scene, err, sizeof(err)) == SBFX_OK, "%s", err);
    const sbfx_gpio_trigger *g = NULL;
    CHECK(sbfx_scene_gpio_triggers(scene, &g) == 1);
    CHECK(g && strcmp(g->chip, "gpiochip1") == 0 && g->line == 17 && g->edge == SBFX_EDGE_FALLING &&
          g->debounce_ms == 25 && strcmp(g->effect, "puff") == 0 && g->position[2] == -2.0f);
    sbfx_scene_free(scene);
}

/* The camera group is read by viewers (sbfx-play): validated like every other key, left-out keys
 * at the default orbit's values; no group, the default orbit. */
CHECK_TEST(camera_group)
{
    char err[256];
    sbfx_scene *scene = NULL;
    sbfx_scene_camera cam, orbit;
    CHECK(!sbfx_scene_camera_get(NULL, &orbit));
    CHECK(orbit.distance == 8.5f && orbit.height == 2.6f && orbit.fov == 50.0f && orbit.target[1] == 1.5f);
    CHECK(fabs(orbit.azimuth - 20.0535) < 1e-3 && fabs(orbit.orbit - 3.43775) < 1e-4, "%g %g", orbit.azimuth,
          orbit.orbit);
    CHECK(sbfx_scene_parse(MEDIA EFFECT(EMITTER), "ok.cfg", &scene, err, sizeof(err)) == SBFX_OK, "%s", err);
    CHECK(!sbfx_scene_camera_get(scene, &cam) && memcmp(&cam, &orbit, sizeof(cam)) == 0);
    sbfx_scene_free(scene);
    const char *text = MEDIA EFFECT(EMITTER) "camera = { target = [0.0, 0.8, 0.5]; distance = 3.0; orbit = 0.0; };\n";
    CHECK(sbfx_scene_parse(text, "cam.cfg", &scene, err, sizeof(err)) == SBFX_OK, "%s", err);
    CHECK(sbfx_scene_camera_get(scene, &cam));
    CHECK(cam.target[1] == 0.8f && cam.target[2] == 0.5f && cam.distance == 3.0f && cam.orbit == 0.0f);
    CHECK(cam.height == orbit.height && cam.fov == orbit.fov && cam.azimuth == orbit.azimuth, "defaults kept");
    sbfx_scene_free(scene);
    expect_error(MEDIA EFFECT(EMITTER) "camera = {\n distance = 0.0; };\n", 4, "'distance' = 0 is out of range");
    expect_error(MEDIA EFFECT(EMITTER) "camera = { fov = 180.0; };\n", 3, "'fov' = 180 is out of range");
    expect_error(MEDIA EFFECT(EMITTER) "camera = { taget = [0.0, 1.0, 0.0]; };\n", 3, "did you mean 'target'");
    expect_error(MEDIA EFFECT(EMITTER) "camera = { target = [0.0, 1.0]; };\n", 3, "'target' must be an array of 3");
    expect_error(MEDIA EFFECT(EMITTER) "camera = 5;\n", 3, "camera must be a group");
}

CHECK_TEST(tone_map_and_exposure_keys)
{
    char err[256];
    sbfx_scene *scene = NULL;
    const char *text = "render = { tone_map = \"per-channel\"; exposure = 0.5; };\n" MEDIA EFFECT(EMITTER);
    CHECK(sbfx_scene_parse(text, "tone.cfg", &scene, err, sizeof(err)) == SBFX_OK, "%s", err);
    sbfx_scene_free(scene);
    expect_error("render = {\n tone_map = \"aces\"; };\n" MEDIA EFFECT(EMITTER), 2,
                 "is not one of: none, hue-preserving, per-channel, filmic");
    expect_error("render = { exposure = 0.0; };\n" MEDIA EFFECT(EMITTER), 1, "'exposure' = 0 is out of range");
    expect_error("render = { tonemap = \"none\"; };\n" MEDIA EFFECT(EMITTER), 1, "did you mean 'tone_map'");
}

/* Fire's photometric units (docs/look-fire.md): media.fire.emissivity (0..1) and
 * render.white_luminance (cd/m^2 of a linear 1.0); the older bare `emission` scale still parses,
 * but not beside an emissivity. */
#define FIRE_EFFECT "effects = { f = { steps = ( { type = \"emitter\"; medium = \"fire\"; count = 10; } ); }; };\n"
CHECK_TEST(fire_units_keys)
{
    char err[256];
    sbfx_scene *scene = NULL;
    const char *text = "render = { white_luminance = 5000.0; };\nmedia = { fire = { emissivity = 0.5; }; };\n" FIRE_EFFECT;
    CHECK(sbfx_scene_parse(text, "fire.cfg", &scene, err, sizeof(err)) == SBFX_OK, "%s", err);
    if (scene) {
        CHECK(scene->render.white_luminance == 5000.0f && scene->media[SBFX_FIRE].emissivity == 0.5f);
        sbfx_scene_free(scene);
    }
    CHECK(sbfx_scene_parse("media = { fire = { emission = 150.0; }; };\n" FIRE_EFFECT, "old.cfg", &scene, err,
                           sizeof(err)) == SBFX_OK, "%s", err);
    if (scene) {
        CHECK(scene->media[SBFX_FIRE].emissivity == 0.0f && scene->media[SBFX_FIRE].emission_scale == 150.0f);
        sbfx_scene_free(scene);
    }
    expect_error("media = { fire = { emissivity = 0.5;\n emission = 150.0; }; };\n" FIRE_EFFECT, 2,
                 "give 'emissivity' (photometric, 0..1) or 'emission' (a bare scale), not both");
    expect_error("media = { fire = { emissivity = 1.5; }; };\n" FIRE_EFFECT, 1, "'emissivity' = 1.5 is out of range");
    expect_error("render = { white_luminance = 0.0; };\n" FIRE_EFFECT, 1, "'white_luminance' = 0 is out of range");
}

/* media.fire.soot (docs/look-fire.md "Pink edges"): the cool share's soot, 0..64; a scene file
 * that leaves it out gets the default (2), the built-in explosion none (its soot is smoke). */
CHECK_TEST(fire_soot_key)
{
    char err[256];
    sbfx_scene *scene = NULL;
    CHECK(sbfx_scene_parse("media = { fire = { soot = 0.5; }; };\n" FIRE_EFFECT, "soot.cfg", &scene, err,
                           sizeof(err)) == SBFX_OK, "%s", err);
    if (scene) {
        CHECK(scene->media[SBFX_FIRE].soot == 0.5f);
        sbfx_scene_free(scene);
    }
    CHECK(sbfx_scene_parse("media = { fire = { emissivity = 1.0; }; };\n" FIRE_EFFECT, "default.cfg", &scene, err,
                           sizeof(err)) == SBFX_OK, "%s", err);
    if (scene) {
        CHECK(scene->media[SBFX_FIRE].soot == (float)SBFX_FIRE_SOOT_DEFAULT);
        sbfx_scene_free(scene);
    }
    sbfx_scene builtin;
    sbfx_scene_builtin(&builtin);
    CHECK(builtin.media[SBFX_FIRE].soot == 0.0f);
    expect_error("media = { fire = { soot = -1.0; }; };\n" FIRE_EFFECT, 1, "'soot' = -1 is out of range");
    expect_error("media = { fire = { soot = 65.0; }; };\n" FIRE_EFFECT, 1, "'soot' = 65 is out of range");
    expect_error("media = { fire = { soot = \"black\"; }; };\n" FIRE_EFFECT, 1, "'soot' must be a number");
}

/* render.budget_ms and render.ladder (issue 11): a positive time, known level names. */
CHECK_TEST(budget_and_ladder_errors_name_line_and_token)
{
    expect_error(MEDIA EFFECT(EMITTER) "\nrender = { budget_ms = 0; };\n", 4, "'budget_ms' = 0");
    expect_error(MEDIA EFFECT(EMITTER) "\nrender = { budget_ms = -4.0; };\n", 4, "'budget_ms' = -4");
    expect_error(MEDIA EFFECT(EMITTER) "\nrender = {\n budget_ms = \"fast\"; };\n", 5, "'budget_ms' must be a number");
    expect_error(MEDIA EFFECT(EMITTER) "\nrender = {\n\n ladder = [ \"exact/4/nd\", \"exact/4/zz\" ]; };\n", 6,
                 "'ladder'[1]: quality \"exact/4/zz\": unknown upsample 'zz'");
    expect_error(MEDIA EFFECT(EMITTER) "\nrender = { ladder = [ \"exact/4/nd/turbo\" ]; };\n", 4, "'turbo'");
    expect_error(MEDIA EFFECT(EMITTER) "\nrender = { ladder = [ 4 ]; };\n", 4, "'ladder'[0] must be a string");
    expect_error(MEDIA EFFECT(EMITTER) "\nrender = { ladder = 4; };\n", 4, "'ladder' must be an array");
}

CHECK_TEST(budget_and_ladder_parse)
{
    char err[256];
    sbfx_scene *scene = NULL;
    const char *text = MEDIA EFFECT(EMITTER) "render = { budget_ms = 12.5; ladder = [ \"exact/4/nd\", \"spherical/8/bl/lod64\" ]; };\n";
    CHECK(sbfx_scene_parse(text, "ok.cfg", &scene, err, sizeof(err)) == SBFX_OK, "%s", err);
    sbfx_scene_free(scene);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
