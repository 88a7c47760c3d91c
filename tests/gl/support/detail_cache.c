/* The procedural detail volume, generated once per test run and shared by every GL test
 * (issue 26: reference data computed once per run).
 *
 * sbfx_create generates the 128 x 128 x 32 turbulence volume on the CPU (src/tables/detail_gen.c:
 * ~1 s, ~5 s under ASan), and the GL suites create a module in almost every one of their
 * hundreds of forked tests: that generation was most of their time. The GL tests are linked with
 * -Wl,--wrap=sbfx_detail_generate (Makefile, GL_TEST_WRAP), so the module's call lands here:
 *   - without SBFX_TEST_CACHE (a test binary run by hand), the real generator runs, as before;
 *   - with it (tests/run.sh sets a fresh folder per run and build, removed at the end), the
 *     first test to ask for a (size, frames, seed) runs the real generator and stores its
 *     output there (under a lock, so tests running in parallel wait instead of generating it
 *     again); every later one reads those exact floats back.
 * What the tests see is bit for bit what the generator makes, and it ran, sanitised in the
 * ASan tier, in this run; the folder lives for one run only, so no earlier build's generator
 * can ever answer. test_detail (unit) tests the generator itself, unwrapped. */
#include <fcntl.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/file.h>
#include <unistd.h>

void __real_sbfx_detail_generate(int size, int frames, uint32_t seed, float *out);
void __wrap_sbfx_detail_generate(int size, int frames, uint32_t seed, float *out);

static bool read_all(const char *path, float *out, size_t n)
{
    FILE *f = fopen(path, "rb");
    if (!f) return false;
    size_t got = fread(out, sizeof(float), n, f);
    bool whole = got == n && fgetc(f) == EOF;
    fclose(f);
    return whole;
}

static void write_all(const char *path, const float *v, size_t n)
{
    char tmp[4200];
    snprintf(tmp, sizeof(tmp), "%s.%d", path, (int)getpid());
    FILE *f = fopen(tmp, "wb");
    if (!f) return;
    bool ok = fwrite(v, sizeof(float), n, f) == n;
    ok = fclose(f) == 0 && ok;
    if (!ok || rename(tmp, path) != 0) remove(tmp); /* the next test generates it again */
}

void __wrap_sbfx_detail_generate(int size, int frames, uint32_t seed, float *out)
{
    const char *dir = getenv("SBFX_TEST_CACHE");
    if (!dir || !*dir || !out || size < 1 || frames < 1) {
        __real_sbfx_detail_generate(size, frames, seed, out);
        return;
    }
    char path[4096];
    snprintf(path, sizeof(path), "%s/detail-%dx%dx%d-seed%u.f32", dir, size, size, frames, (unsigned)seed);
    size_t n = (size_t)size * size * frames;
    if (read_all(path, out, n)) return;
    char lock_path[4200];
    snprintf(lock_path, sizeof(lock_path), "%s.lock", path);
    int lock = open(lock_path, O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (lock >= 0) flock(lock, LOCK_EX);
    if (!read_all(path, out, n)) { /* not made while this test waited for the lock */
        __real_sbfx_detail_generate(size, frames, seed, out);
        write_all(path, out, n);
    }
    if (lock >= 0) close(lock); /* releases the lock */
}
