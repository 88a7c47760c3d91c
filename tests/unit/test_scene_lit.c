/* Scene keys of the lit-smoke work: a medium's lighting model and its parameters, and orbiting
 * point lights. Good values land in the scene; each bad one gets one message with the file
 * name, the line and what is wrong. */
#include <string.h>
#include "check.h"
#include "scene/scene.h"

#define EFFECT "effects = { puff = { steps = ( { type = \"emitter\"; medium = \"smoke\"; count = 10; } ); }; };\n"
#define SMOKE(keys) "media = { smoke = { albedo = 0.3; density = 0.5;\n" keys " }; };\n" EFFECT

static sbfx_scene *parse(const char *text)
{
    char err[512] = "";
    sbfx_scene *scene = NULL;
    CHECK(sbfx_scene_parse(text, "lit.cfg", &scene, err, sizeof(err)) == SBFX_OK, "%s", err);
    if (!scene) exit(1);
    return scene;
}

static void expect_error(const char *text, int line, const char *needle)
{
    char err[512] = "", where[64];
    sbfx_scene *scene = (sbfx_scene *)1;
    sbfx_result r = sbfx_scene_parse(text, "bad.cfg", &scene, err, sizeof(err));
    CHECK(r == SBFX_ERR_INVALID_ARGUMENT, "accepted: %s", text);
    CHECK(scene == NULL, "a failed parse left a scene behind");
    snprintf(where, sizeof(where), "bad.cfg:%d:", line);
    CHECK(strncmp(err, where, strlen(where)) == 0, "message \"%s\" does not start with %s", err, where);
    CHECK(strstr(err, needle) != NULL, "message \"%s\" lacks \"%s\"", err, needle);
}

CHECK_TEST(phase_is_the_default_with_the_seeds_lit_parameters)
{
    sbfx_scene *s = parse(SMOKE(""));
    const sbfx_medium_params *m = &s->media[SBFX_SMOKE];
    CHECK(!m->lit);
    CHECK(m->wrap == 0.6f && m->translucency == 1.0f && m->dampening == 0.0f);
    CHECK(m->steps_min == 4 && m->steps_max == 16 && m->texture_size == 128 && m->texture_variants == 4);
    sbfx_scene_free(s);
}

CHECK_TEST(lit_keys_are_read)
{
    sbfx_scene *s = parse(SMOKE("lighting = \"lit\"; wrap = 0.3; translucency = 2.5; dampening = 0.25;\n"
                                "steps = [2, 24]; texture = { size = 64; variants = 6; };"));
    const sbfx_medium_params *m = &s->media[SBFX_SMOKE];
    CHECK(m->lit && m->wrap == 0.3f && m->translucency == 2.5f && m->dampening == 0.25f);
    CHECK(m->steps_min == 2 && m->steps_max == 24 && m->texture_size == 64 && m->texture_variants == 6);
    sbfx_scene_free(s);
    s = parse(SMOKE("lighting = \"phase\"; steps = [0, 0];"));
    CHECK(!s->media[SBFX_SMOKE].lit && s->media[SBFX_SMOKE].steps_max == 0);
    sbfx_scene_free(s);
}

CHECK_TEST(bad_lit_values_are_named)
{
    expect_error(SMOKE("lighting = \"shaded\";"), 2, "'lighting' = \"shaded\" is not one of: phase, lit");
    expect_error(SMOKE("lighting = 1;"), 2, "'lighting' must be a string");
    expect_error(SMOKE("wrap = 1.5;"), 2, "'wrap' = 1.5 is out of range [0, 1]");
    expect_error(SMOKE("wrap = \"soft\";"), 2, "'wrap' must be a number");
    expect_error(SMOKE("translucency = -0.5;"), 2, "'translucency' = -0.5 is out of range");
    expect_error(SMOKE("dampening = 2.0;"), 2, "'dampening' = 2 is out of range [0, 1]");
    expect_error(SMOKE("steps = [8, 4];"), 2, "'steps' = [8, 4]: the first must not exceed the second");
    expect_error(SMOKE("steps = [4, 65];"), 2, "'steps'[1] = 65 is out of range [0, 64]");
    expect_error(SMOKE("steps = [4.0, 8.0];"), 2, "'steps' must be an array of 2 integers");
    expect_error(SMOKE("steps = 8;"), 2, "'steps' must be an array of 2 integers");
    expect_error(SMOKE("texture = { size = 8; };"), 2, "'size' = 8 is out of range [16, 512]");
    expect_error(SMOKE("texture = { size = 64; variants = 0; };"), 2, "'variants' = 0 is out of range [1, 16]");
    expect_error(SMOKE("texture = 64;"), 2, "texture must be a group");
    expect_error("media = { smoke = { albedo = 0.0;\n lighting = \"lit\"; }; };\n" EFFECT, 2, "its albedo is 0");
}

CHECK_TEST(unknown_lit_keys_suggest_the_nearest)
{
    expect_error(SMOKE("lightning = \"lit\";"), 2, "did you mean 'lighting'");
    expect_error(SMOKE("translucence = 1.0;"), 2, "did you mean 'translucency'");
    expect_error(SMOKE("texture = { sise = 64; };"), 2, "unknown key 'sise' in texture (did you mean 'size'?)");
    expect_error(SMOKE("stepz = [1, 2];"), 2, "did you mean 'steps'");
}

#define LIGHT(body) "lights = ( {\n" body " } );\n"
#define MEDIA "media = { smoke = { albedo = 0.3; }; };\n"

CHECK_TEST(orbiting_point_light_is_read)
{
    sbfx_scene *s = parse(LIGHT("type = \"point\"; color = [2.0, 2.0, 2.0];\n"
                                "orbit = { center = [0.0, 1.5, 0.0]; radius = 3.0; period = -6.0; phase = 90.0; };")
                              MEDIA EFFECT);
    const sbfx_light *l = &s->lights[0];
    CHECK(s->light_count == 1 && l->type == SBFX_LIGHT_POINT && l->orbit.on);
    CHECK(l->orbit.center[1] == 1.5f && l->orbit.radius == 3.0f && l->orbit.period == -6.0f);
    CHECK_NEAR(l->orbit.phase, M_PI / 2, 1e-6);
    sbfx_scene_free(s);
    s = parse(LIGHT("type = \"point\"; position = [1.0, 2.0, 3.0];") MEDIA EFFECT);
    CHECK(!s->lights[0].orbit.on);
    sbfx_scene_free(s);
}

CHECK_TEST(bad_orbits_are_named)
{
    expect_error(LIGHT("type = \"directional\"; direction = [0.0, -1.0, 0.0];\n orbit = { radius = 2.0; };")
                     MEDIA EFFECT, 3, "'orbit' needs a point light");
    expect_error(LIGHT("type = \"point\";\n orbit = { radius = -2.0; };") MEDIA EFFECT, 3,
                 "'radius' = -2 is out of range");
    expect_error(LIGHT("type = \"point\";\n orbit = { period = 0.0; };") MEDIA EFFECT, 3,
                 "'period' = 0: use at least 0.01 s");
    expect_error(LIGHT("type = \"point\";\n orbit = { centre = [0.0, 0.0, 0.0]; };") MEDIA EFFECT, 3,
                 "did you mean 'center'");
    expect_error(LIGHT("type = \"point\";\n orbit = { phase = 720.0; };") MEDIA EFFECT, 3,
                 "'phase' = 720 is out of range");
    expect_error(LIGHT("type = \"point\"; color = [1.0, 1.0, 1.0];") MEDIA EFFECT, 1, "a point light needs 'position'");
}

CHECK_TEST(lit_smoke_example_loads)
{
    char err[512] = "";
    sbfx_scene *scene = NULL;
    CHECK(sbfx_scene_load("scenes/lit-smoke.cfg", &scene, err, sizeof(err)) == SBFX_OK, "%s", err);
    if (!scene) return;
    CHECK(scene->media[SBFX_SMOKE].lit, "the example's smoke is not lit");
    bool orbit = false;
    for (int i = 0; i < scene->light_count; i++) orbit |= scene->lights[i].orbit.on;
    CHECK(orbit, "no light orbits in the example");
    sbfx_scene_free(scene);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
