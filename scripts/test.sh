#!/usr/bin/env bash
# Runs every TriChart test: first checks the installed package from outside the source tree,
# then the whole CTest suite (core GoogleTest, VTK image tests, Python, pvpython plugin and
# app tests) under a virtual X server, then the core tests and every bad-input case again in a
# second build under AddressSanitizer and UndefinedBehaviorSanitizer (scripts/test-sanitize.sh;
# TRICHART_SKIP_SANITIZE=1 skips it). Run scripts/setup.sh first. Arguments go to the first ctest.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${TRICHART_BUILD_DIR:-$here/build}"

echo "test: the installed package, from another folder"
(cd / && /usr/bin/python3 -c "import trichart; print('import trichart', trichart.__version__)")
(cd / && trichart info)
if command -v pvpython >/dev/null; then
  (cd / && pvpython -c "
import trichart
from paraview.simple import LoadPlugin
LoadPlugin(trichart.plugin_path(), remote=False, ns=globals())
assert 'TriChartCurvature' in globals(), 'the installed plugin has no TriChart filters'
print('pvpython loads', trichart.plugin_path())")
fi

echo "test: ctest"
cd "$build"
status=0
# -noreset: Xvfb otherwise resets itself whenever its last client leaves, and a render window
# that connects during the reset fails ("bad X server connection"), most often on a busy machine.
xvfb-run -a -s '-screen 0 1280x1024x24 -noreset' ctest --output-on-failure -j 2 "$@" || status=$?

# The sanitizer build lives here, not in scripts/setup.sh: it is for testing only, installs
# nothing, and a user who sets up to use TriChart does not wait for it. It runs even when the
# first suite failed, so that one run reports both.
if [ "${TRICHART_SKIP_SANITIZE:-0}" != 1 ]; then
  bash "$here/scripts/test-sanitize.sh" || status=$?
fi
exit $status
