#!/bin/sh
# The browser tier (make test-web; make test runs its first case, --quick): the authoring page
# of build/web/ in headless Chromium, driven over its DevTools pipe by node (tests/web/cdp.js,
# test_page.js), then (not --quick) the same frames as sbfx-play's on Mesa (tests/web/same_picture.sh).
# Usage: tests/web/run.sh WEB_DIR [--quick]; prints "ok - x" / "not ok - x: reason" lines.
set -u
here=$(cd "$(dirname "$0")" && pwd)
web=${1:?usage: tests/web/run.sh WEB_DIR [--quick]}
[ -f "$web/sbfx.js" ] || { echo "not ok - web: $web/sbfx.js is missing (make web)"; exit 1; }
command -v node >/dev/null || { echo "not ok - web: no node (tools/deps.sh web installs emscripten, which brings it)"; exit 1; }
[ -x "${CHROMIUM:-/usr/bin/chromium}" ] || { echo "not ok - web: no ${CHROMIUM:-/usr/bin/chromium} (tools/deps.sh web)"; exit 1; }
rc=0
# shellcheck disable=SC2086 # no second argument: none passed on
node "$here/test_page.js" "$web" ${2:-} || rc=1
[ "${2:-}" = --quick ] && exit $rc
player=$(dirname "$web")/sbfx-play
[ -x "$player" ] || { echo "not ok - same_picture: $player is missing (make test-web builds it)"; exit 1; }
node "$here/same_picture.js" "$web" "$player" "$web/../web-same-picture" || rc=1
exit $rc
