#!/usr/bin/env bash
# Renders every view of the desktop app shown in the README into docs/screenshots/, headless
# under Xvfb (scripts/screenshot.sh does one picture). Look at each one after rendering.
#
#   scripts/screenshots.sh            all views, from ./build/app/oscilab (OSCILAB_BIN: another)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
shot() { "$root/scripts/screenshot.sh" "$@"; }
pos=$root/samples/stepped_positive.flac
neg=$root/samples/stepped_negative.flac
out=$root/docs/screenshots

shot "$pos" "$out/record-view.png" --hide-panel --tab levels
shot "$pos" "$out/record-view-zoom.png" --hide-panel --window 100:101 --cursor 100.5
shot "$neg" "$out/review-levels.png" --size 1400x900 --hide-panel --tab levels --level 0:11,1:11 \
  --mark 116.2:"check bolt" --cursor 116.2 "$pos"
shot "$neg" "$out/review-rfs.png" --size 1400x900 --hide-panel --tab rfs "$pos"
shot "$neg" "$out/fit-panel.png" --size 1700x1000 --run fit "$pos"
shot "$root/samples/presliding_negative.flac" "$out/diagnosis-panel.png" --size 1700x1000 \
  --run diagnose "$root/samples/presliding_positive.flac"
shot "$neg" "$out/fit-hbm.png" --size 1000x820 --run fit --dialog hbm "$pos"
shot "$neg" "$out/fit-map.png" --size 1000x1180 --run fit --dialog map "$pos"
shot "$pos" "$out/live-monitor.png" --size 1600x1000 --hide-panel --live rig
# A 2560x1440 desktop screen: review, live, fit and diagnosis.
big() { OSCILAB_SCREEN=2560x1600x24 shot "$@" --size 2560x1440; }
big "$neg" "$out/desktop-review-2560x1440.png" --tab levels --level 0:11,1:11 "$pos"
big "$neg" "$out/desktop-review-dark-2560x1440.png" --tab levels --level 0:11,1:11 --theme dark "$pos"
big "$pos" "$out/desktop-live-2560x1440.png" --live rig
big "$neg" "$out/desktop-fit-2560x1440.png" --run fit "$pos"
big "$root/samples/presliding_negative.flac" "$out/desktop-diagnosis-2560x1440.png" \
  --run diagnose "$root/samples/presliding_positive.flac"
