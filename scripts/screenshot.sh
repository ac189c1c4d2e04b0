#!/usr/bin/env bash
# Screenshot of the Oscilab window on a recording, taken headless under Xvfb.
#
#   scripts/screenshot.sh [REC] [OUT.png] [oscilab options...]
#
#   REC       recording to open (default: samples/stepped_positive.flac)
#   OUT.png   where to save the picture (default: docs/screenshots/record-view.png)
#   options   passed on to oscilab, e.g. --cursor 12.5 (readout cursor at 12.5 s) or
#             --window 100:101 (time window shown), --size 1600x900 (default 1280x800)
#
# The app is ./build/app/oscilab unless OSCILAB_BIN names another. It runs on the real X11
# platform inside xvfb-run (packages xvfb, xauth), lays the window out, grabs it with
# QWidget::grab and exits; the exit status is oscilab's (1 when REC cannot be read).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
rec=${1:-$root/samples/stepped_positive.flac}
out=${2:-$root/docs/screenshots/record-view.png}
shift $(($# < 2 ? $# : 2))
bin=${OSCILAB_BIN:-$root/build/app/oscilab}

if [ ! -x "$bin" ]; then
  echo "screenshot: $bin not found; build it first (cmake --build build --target oscilab)" >&2
  exit 2
fi
mkdir -p "$(dirname "$out")"
# -a: a free display number; 24-bit screen larger than the window so nothing is cut
# (OSCILAB_SCREEN: another size, e.g. 2560x1600x24 for a 2560x1440 window).
xvfb-run -a -s "-screen 0 ${OSCILAB_SCREEN:-1920x1200x24}" "$bin" --screenshot "$out" "$@" "$rec"
echo "screenshot: $out"
