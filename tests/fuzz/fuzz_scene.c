/* libFuzzer target: scene parsing must never crash, leak or accept half a scene.
 * Built by `make fuzz` with clang -fsanitize=fuzzer,address,undefined; the example scenes in
 * scenes/ are the seed corpus. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include "sbfx.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1);
    if (!text) return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    char err[512];
    sbfx_scene *scene = NULL;
    sbfx_result r = sbfx_scene_parse(text, "fuzz.cfg", &scene, err, sizeof(err));
    if (r == SBFX_OK) {
        const sbfx_gpio_trigger *gpio;
        int n = sbfx_scene_gpio_triggers(scene, &gpio);
        for (int i = 0; i < n; i++)
            if (gpio[i].line < 0 || !gpio[i].effect[0]) abort(); /* validated, or not accepted */
        sbfx_scene_free(scene);
    } else if (scene != NULL || err[0] == '\0') {
        abort(); /* a failure leaves no scene and always says why */
    }
    free(text);
    return 0;
}
