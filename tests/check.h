/* Tiny self-checking test harness (kernel-selftest style, TAP-like output).
 *
 *   CHECK_TEST(name) { ... CHECK(cond, "fmt", ...); CHECK_NEAR(a, b, tol); ... }
 *   int main(void) { return check_main(); }   // or check_main_args(argc, argv)
 *
 * Each test runs in a forked child (a crash fails that test only); output lines are
 *   ok - suite/name
 *   not ok - suite/name: reason
 *   skip - suite/name: reason
 * tests/run.sh counts them and prints "N passed, M failed, K skipped".
 *
 * A suite that sets check_batch (the GL suites: tests/gl/gl_fixture.h) runs its tests one after
 * another in one forked child, a batch, as long as they return: a test that crashes, exits or
 * skips ends the batch, is reported by the parent, and the next test starts a new batch. Each test
 * finds the environment as the batch began. A test that needs a process of its own (Mesa reads
 * some variables once per process) calls check_own_process(): it then runs first in a new batch,
 * and the batch ends after it. (On the development VM a fork and a context's fresh memory cost
 * more than many tests: docs/testing.md "Where the time goes".)
 * CHECK_FORK_EACH=1: a child per test, also for those suites. CHECK_NOFORK=1: every test in the
 * process (for gdb/ASan reports). */
#ifndef SBFX_CHECK_H
#define SBFX_CHECK_H

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

typedef void (*check_fn)(void);
struct check_entry { const char *name; check_fn fn; };

#define CHECK_MAX_TESTS 256
static struct check_entry check_tests[CHECK_MAX_TESTS];
static int check_test_count;
static int check_failed_here; /* failures inside the running test */

#define CHECK_TEST(name)                                                                     \
    static void check_test_##name(void);                                                     \
    __attribute__((constructor)) static void check_register_##name(void)                     \
    {                                                                                        \
        if (check_test_count < CHECK_MAX_TESTS)                                              \
            check_tests[check_test_count++] = (struct check_entry){#name, check_test_##name}; \
    }                                                                                        \
    static void check_test_##name(void)

/* Prints the reason of a failure; the test goes on so that several failures show at once. */
static inline void check_fail(const char *file, int line, const char *fmt, ...)
{
    va_list ap;
    fprintf(stdout, "#   %s:%d: ", file, line);
    va_start(ap, fmt);
    vfprintf(stdout, fmt, ap);
    va_end(ap);
    fputc('\n', stdout);
    fflush(stdout);
    check_failed_here++;
}

#define CHECK(cond, ...)                                                                     \
    do {                                                                                     \
        if (!(cond)) check_fail(__FILE__, __LINE__, "CHECK(" #cond ") " __VA_ARGS__);        \
    } while (0)

#define CHECK_NEAR(a, b, tol)                                                                \
    do {                                                                                     \
        double check_a_ = (a), check_b_ = (b), check_t_ = (tol);                             \
        if (!(fabs(check_a_ - check_b_) <= check_t_))                                        \
            check_fail(__FILE__, __LINE__, "%s = %.9g, %s = %.9g, |diff| %.3g > %.3g", #a,   \
                       check_a_, #b, check_b_, fabs(check_a_ - check_b_), check_t_);         \
    } while (0)

#define CHECK_FINITE(x)                                                                      \
    do {                                                                                     \
        double check_x_ = (x);                                                               \
        if (!isfinite(check_x_)) check_fail(__FILE__, __LINE__, "%s = %g is not finite", #x, check_x_); \
    } while (0)

/* Skips the running test with a reason (exit code 77 from the child). */
#define CHECK_SKIP(...)                                                                      \
    do {                                                                                     \
        fprintf(stdout, "#SKIP ");                                                           \
        fprintf(stdout, __VA_ARGS__);                                                        \
        fputc('\n', stdout);                                                                 \
        fflush(stdout);                                                                      \
        exit(77);                                                                            \
    } while (0)

/* Called once in the parent before it forks the first test, where a suite sets it (the GL
 * fixture loads the EGL driver there: tests/gl/gl_fixture.h); NULL for the others. */
static void (*check_before_forks)(void);

/* Set by a suite (a constructor) whose tests run in batches (above). */
static int check_batch;

/* What a batch child tells its parent, in memory they share: the test it is in (the index of
 * check_tests), or the one to go on from where it ended between tests (`between`; at the end
 * check_test_count), whether the test asked to start again in a new batch (check_own_process),
 * and the failures it reported itself. */
struct check_shared { volatile int current, between, again, failures; };
static struct check_shared *check_shared_state;
static int check_tests_in_process; /* tests begun in this (batch) process */
static int check_end_batch;        /* the running test ends the batch when it returns */

/* The running test needs a process of its own: in a batch where tests ran before it, the batch
 * ends here and the test starts again first in a new one; none runs after it in its batch. */
static inline void check_own_process(void)
{
    if (!check_shared_state) return;
    if (check_tests_in_process > 1) {
        check_shared_state->again = 1;
        fflush(stdout);
        _exit(0);
    }
    check_end_batch = 1;
}

static inline const char *check_suite_name(const char *argv0)
{
    const char *slash = argv0 ? strrchr(argv0, '/') : NULL;
    return slash ? slash + 1 : (argv0 ? argv0 : "test");
}

static inline int check_run_one(const struct check_entry *t)
{
    check_failed_here = 0;
    t->fn();
    return check_failed_here ? 1 : 0;
}

/* Prints a test's result from its status (0 passed, 77 skipped, >= 128 killed by a signal);
 * returns 1 for a failure. */
static inline int check_report(const char *suite, const char *name, int status)
{
    int failed = 0;
    if (status == 0) printf("ok - %s/%s\n", suite, name);
    else if (status == 77) printf("skip - %s/%s\n", suite, name);
    else if (status >= 128) printf("not ok - %s/%s: killed by signal %d\n", suite, name, status - 128), failed = 1;
    else printf("not ok - %s/%s\n", suite, name), failed = 1;
    fflush(stdout);
    return failed;
}

static inline int check_wait(pid_t pid)
{
    int ws = 0;
    if (pid < 0 || waitpid(pid, &ws, 0) < 0) return 2;
    if (WIFEXITED(ws)) return WEXITSTATUS(ws);
    return 128 + (WIFSIGNALED(ws) ? WTERMSIG(ws) : 0);
}

/* The environment as a copy of its own, and putting it back (a batch's tests each find it so). */
extern char **environ;
static inline char **check_environment_copy(void)
{
    size_t n = 0;
    while (environ && environ[n]) n++;
    char **copy = (char **)calloc(n + 1, sizeof(*copy));
    for (size_t i = 0; copy && i < n; i++) copy[i] = strdup(environ[i]);
    return copy;
}
static inline void check_environment_restore(char **copy)
{
    if (!copy) return;
    clearenv();
    for (size_t i = 0; copy[i]; i++) putenv(copy[i]); /* the copy's strings stay for the batch */
}

static inline int check_selected(const char *only, int i)
{
    return !only || strcmp(only, check_tests[i].name) == 0;
}

/* A batch child: the selected tests from `first` on, until one does not return or asks to end the
 * batch; reports those that return itself, then tells the parent where to go on. */
static inline void check_batch_child(const char *suite, const char *only, int first)
{
    char **environment = check_environment_copy();
    int i = first;
    while (i < check_test_count && !check_end_batch) {
        if (check_selected(only, i)) {
            check_shared_state->current = i;
            check_tests_in_process++;
            int rc = check_run_one(&check_tests[i]);
            fflush(stdout);
            check_shared_state->failures += check_report(suite, check_tests[i].name, rc);
            check_environment_restore(environment);
        }
        i++;
    }
    check_shared_state->current = i;
    check_shared_state->between = 1;
    _exit(0);
}

/* The parent of batches: starts one at the first test not yet reported, and reports the test a
 * batch ended in (its status the child's exit) or starts that test again where it asked to. */
static inline int check_run_batches(const char *suite, const char *only)
{
    struct check_shared *shared = (struct check_shared *)mmap(NULL, sizeof(*shared), PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (shared == MAP_FAILED) return -1;
    int failures = 0, next = 0;
    while (next < check_test_count) { /* again only comes from a test that was not the first */
        shared->current = next, shared->between = 0, shared->again = 0, shared->failures = 0;
        fflush(stdout);
        pid_t pid = fork();
        if (pid < 0) {
            failures++;
            break;
        }
        if (pid == 0) {
            check_shared_state = shared;
            check_batch_child(suite, only, next);
        }
        int status = check_wait(pid);
        failures += shared->failures;
        int at = shared->current;
        if (at >= check_test_count) break;
        if (shared->again || (shared->between && status == 0)) {
            next = at; /* that test first in a new batch, or the one after a test that ended it */
        } else {
            failures += check_report(suite, check_tests[at].name, status); /* it ended in that test */
            next = at + 1;
        }
    }
    munmap(shared, sizeof(*shared));
    return failures;
}

static inline int check_main_args(int argc, char **argv)
{
    const char *suite = check_suite_name(argc > 0 ? argv[0] : NULL);
    const char *only = argc > 1 ? argv[1] : NULL;
    int nofork = getenv("CHECK_NOFORK") != NULL;
    int failures = 0;
    if (!nofork && check_before_forks) check_before_forks();
    if (!nofork && check_batch && !getenv("CHECK_FORK_EACH")) {
        failures = check_run_batches(suite, only);
        if (failures >= 0) return failures ? 1 : 0;
        failures = 0; /* no shared memory: a child per test */
    }
    for (int i = 0; i < check_test_count; i++) {
        const struct check_entry *t = &check_tests[i];
        if (!check_selected(only, i)) continue;
        fflush(stdout);
        int status = 0;
        if (nofork) {
            status = check_run_one(t);
        } else {
            pid_t pid = fork();
            if (pid == 0) {
                int rc = check_run_one(t);
                fflush(stdout);
                _exit(rc);
            }
            status = check_wait(pid);
        }
        failures += check_report(suite, t->name, status);
    }
    return failures ? 1 : 0;
}

static inline int check_main(void) { return check_main_args(0, NULL); }

#endif
