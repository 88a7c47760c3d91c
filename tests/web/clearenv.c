/* clearenv(3) for the GL suites in the browser (make test-web-suites): tests/check.h calls it to
 * give each test of a batch the environment the batch began with, and emscripten 3.1.6's libc
 * leaves it out. glibc's meaning: no variable left, environ NULL. (The browser runs the suites
 * with CHECK_NOFORK, one test after another, where check.h does not call it.) */
#define _GNU_SOURCE
#include <stdlib.h>
#include <unistd.h>

int clearenv(void)
{
    environ = NULL;
    return 0;
}
