/* detail.source naming a video clip (docs/detail-clips.md): a relative path is resolved against
 * the scene file's folder, an absolute one kept; the one detail volume takes one feed, so two
 * different clips, or a clip beside the camera, are errors naming the line. */
#include <string.h>
#include "check.h"
#include "scene/scene.h"

#define DETAIL(medium, source) \
    medium " = { albedo = 0.2; density = 0.4; detail = { source = \"" source "\"; strength = 0.5; }; };\n"
#define EFFECT "effects = { puff = { steps = ( { type = \"emitter\"; medium = \"smoke\"; count = 10; } ); }; };\n"

static const char *clip_of(const char *text, const char *name, int medium, char *err, size_t n)
{
    static char path[256];
    sbfx_scene *scene = NULL;
    if (sbfx_scene_parse(text, name, &scene, err, n) != SBFX_OK) return NULL;
    snprintf(path, sizeof(path), "%s", scene->media[medium].detail_clip);
    sbfx_scene_free(scene);
    return path;
}

CHECK_TEST(clip_path_is_resolved_against_the_scene_folder)
{
    char err[512] = "";
    const char *text = "media = {\n" DETAIL("smoke", "clips/smoke.mp4") "};\n" EFFECT;
    const char *p = clip_of(text, "scenes/mine.cfg", SBFX_SMOKE, err, sizeof(err));
    CHECK(p && strcmp(p, "scenes/clips/smoke.mp4") == 0, "%s %s", p ? p : "", err);
    p = clip_of(text, "/srv/fx/mine.cfg", SBFX_SMOKE, err, sizeof(err));
    CHECK(p && strcmp(p, "/srv/fx/clips/smoke.mp4") == 0, "%s %s", p ? p : "", err);
    p = clip_of(text, "mine.cfg", SBFX_SMOKE, err, sizeof(err)); /* in the current folder */
    CHECK(p && strcmp(p, "clips/smoke.mp4") == 0, "%s %s", p ? p : "", err);
    const char *absolute = "media = {\n" DETAIL("smoke", "/data/fire.mkv") "};\n" EFFECT;
    p = clip_of(absolute, "scenes/mine.cfg", SBFX_SMOKE, err, sizeof(err));
    CHECK(p && strcmp(p, "/data/fire.mkv") == 0, "%s %s", p ? p : "", err);
}

CHECK_TEST(keywords_are_not_clips)
{
    char err[512] = "";
    const char *p = clip_of("media = {\n" DETAIL("smoke", "procedural") "};\n" EFFECT, "a/b.cfg", SBFX_SMOKE, err,
                            sizeof(err));
    CHECK(p && p[0] == '\0', "%s %s", p ? p : "", err);
    p = clip_of("media = {\n" DETAIL("smoke", "v4l2") "};\n" EFFECT, "a/b.cfg", SBFX_SMOKE, err, sizeof(err));
    CHECK(p && p[0] == '\0', "%s %s", p ? p : "", err);
}

static void expect_error(const char *text, const char *needle)
{
    char err[512] = "";
    sbfx_scene *scene = NULL;
    CHECK(sbfx_scene_parse(text, "bad.cfg", &scene, err, sizeof(err)) == SBFX_ERR_INVALID_ARGUMENT, "accepted");
    CHECK(scene == NULL);
    CHECK(strncmp(err, "bad.cfg:", 8) == 0 && strstr(err, needle), "message \"%s\" lacks \"%s\"", err, needle);
}

CHECK_TEST(one_volume_takes_one_feed)
{
    expect_error("media = {\n" DETAIL("smoke", "a.mp4") DETAIL("dust", "b.mp4") "};\n" EFFECT,
                 "different detail sources");
    expect_error("media = {\n" DETAIL("smoke", "a.mp4") DETAIL("dust", "v4l2") "};\n" EFFECT,
                 "different detail sources");
    expect_error("media = {\n" DETAIL("smoke", "") "};\n" EFFECT, "a video file's path");
    char err[512] = "";
    const char *same = "media = {\n" DETAIL("smoke", "a.mp4") DETAIL("dust", "a.mp4") "};\n" EFFECT;
    CHECK(clip_of(same, "x.cfg", SBFX_DUST, err, sizeof(err)) != NULL, "%s", err);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
