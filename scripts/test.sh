#!/usr/bin/env bash
# Runs every TriChart test: first checks the installed package from outside the source tree,
# then the whole CTest suite (core GoogleTest, VTK image tests, Python, pvpython plugin and
# app tests) under a virtual X server. Run scripts/setup.sh first.
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
xvfb-run -a -s '-screen 0 1280x1024x24' ctest --output-on-failure -j 2 "$@"
