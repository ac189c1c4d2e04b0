#!/usr/bin/env bash
# oscilab-cli and its modules (analysis/common/module_loader.h): the executable does not link
# libhdf5, matio or cairo, and a command that reads no HDF5 or MAT-file and draws no PNG never
# loads them; a command that does loads the module and works; a missing module is one clear error.
#   modules_cli_test.sh OSCILAB_CLI SOURCE_DIR
source "$(dirname "$0")/cli_checks.sh"
pos=$src/samples/stepped_positive.flac
unset OSCILAB_MODULE_DIR
heavy='libhdf5|libmatio|libcairo'

# Neither the executable (its ELF DT_NEEDED entries) nor anything it links needs them.
needed=$(readelf -d "$cli" | grep NEEDED)
if [ -n "$needed" ] && ! grep -Eq "$heavy" <<< "$needed"; then
  pass "DT_NEEDED names none of libhdf5, matio, cairo ($(wc -l <<< "$needed") entries)"
else
  fail "DT_NEEDED: $needed"
fi
linked=$(ldd "$cli")
if ! grep -Eq "$heavy" <<< "$linked"; then
  pass "ldd lists none of them ($(wc -l <<< "$linked") libraries)"
else
  fail "ldd: $(grep -E "$heavy" <<< "$linked")"
fi

# A FLAC analysis does not load a module: the dynamic loader reports every object it opens.
LD_DEBUG=files "$cli" analyze "$pos" --edc "$work/edc.csv" > /dev/null 2> "$work/flac.debug"
if [ -s "$work/edc.csv" ]; then
  if grep -Eq "oscilab_(hdf5|png)_module|$heavy" "$work/flac.debug"; then
    fail "analyze of a FLAC loaded: $(grep -Eo "file=[^ ]*($heavy|_module)[^ ]*" "$work/flac.debug" | sort -u)"
  else
    pass "analyze of a FLAC loads no module"
  fi
else
  fail "analyze of a FLAC wrote no EDC table"
fi

# Through the module: a MAT-file written, then read back and analysed like the FLAC. It holds the
# channels in SI, so its sidecar is the FLAC's with scale 1.
/usr/bin/python3 - "$src/samples/stepped_positive.json" "$work/pos.json" << 'PY'
import json, sys
sidecar = json.load(open(sys.argv[1]))
for channel in sidecar["channels"]:
    channel["scale"], channel["offset"] = 1.0, 0.0
json.dump(sidecar, open(sys.argv[2], "w"))
PY
if "$cli" export "$pos" --mat "$work/pos.mat" > "$work/export.log" 2>&1 &&
  "$cli" analyze "$work/pos.mat" --edc "$work/edc_mat.csv" > "$work/mat.log" 2>&1; then
  sed -i 's/stepped_positive\.flac/REC/; s/pos\.mat/REC/' "$work/edc.csv" "$work/edc_mat.csv"
  cmp -s "$work/edc.csv" "$work/edc_mat.csv" && pass "MAT-file written and read back: same EDC table" ||
    fail "EDC table of the MAT-file differs: $(diff "$work/edc.csv" "$work/edc_mat.csv" | head -4)"
else
  fail "MAT-file: $(cat "$work/export.log" "$work/mat.log")"
fi
LD_DEBUG=files "$cli" info "$work/pos.mat" > "$work/info.log" 2> "$work/mat.debug"
grep -q "oscilab_hdf5_module.so" "$work/mat.debug" && grep -q "MATLAB 5.0 MAT-file" "$work/info.log" &&
  pass "info on a MAT-file loads oscilab_hdf5_module" || fail "info on a MAT-file: $(cat "$work/info.log")"

# An HDF5 file (h5py, a Debian package like the readers' tests use).
if /usr/bin/python3 - "$work/run.h5" << 'PY'
import sys, h5py, numpy as np
with h5py.File(sys.argv[1], "w") as f:
    d = f.create_dataset("signals/force", data=np.sin(np.arange(512) / 10.0))
    d.attrs["sample_rate_hz"] = 512.0
    d.attrs["unit"] = "N"
PY
then
  "$cli" info "$work/run.h5" > "$work/h5.log" 2>&1
  grep -q "/signals/force: 512 samples" "$work/h5.log" && grep -q "512 Hz" "$work/h5.log" &&
    pass "info on an HDF5 file" || fail "info on an HDF5 file: $(cat "$work/h5.log")"
else
  fail "h5py could not write the HDF5 file"
fi

# A PNG figure through oscilab_png_module.
if "$cli" hbm --model paper --freq 9 --f0 0.1:1.0 --well positive --harmonics 3 --no-stability \
  --out "$work/branch.csv" --png "$work/fig" > "$work/hbm.log" 2>&1 &&
  [ "$(head -c 8 "$work/fig-branch.png" | od -An -tx1 | tr -d ' ')" = "89504e470d0a1a0a" ]; then
  pass "hbm --png writes a PNG"
else
  fail "hbm --png: $(cat "$work/hbm.log")"
fi

# A missing module: one line naming the module and where it was looked for; nothing written.
mkdir "$work/empty"
expect_error() {
  local what=$1 pattern=$2
  shift 2
  local message status
  message=$("$@" 2>&1 >/dev/null)
  status=$?
  if [ $status -eq 2 ] && grep -q -- "$pattern" <<< "$message" && [ "$(wc -l <<< "$message")" -eq 1 ]; then
    pass "$what: $message"
  else
    fail "$what: status $status, message: $message"
  fi
}
export OSCILAB_MODULE_DIR=$work/empty
expect_error "reading a MAT-file without the module" \
  "reading $work/pos.mat needs oscilab_hdf5_module.so: not found in $work/empty" \
  "$cli" info "$work/pos.mat"
expect_error "exporting a MAT-file without the module" \
  "writing $work/new.mat needs oscilab_hdf5_module.so: not found in $work/empty" \
  "$cli" export "$pos" --mat "$work/new.mat"
expect_error "drawing a PNG without the module" \
  "writing $work/nofig-branch.png needs oscilab_png_module.so: not found in $work/empty" \
  "$cli" hbm --model paper --freq 9 --f0 0.1:1.0 --well positive --harmonics 3 --no-stability \
  --out "$work/nofig.csv" --png "$work/nofig"
leftover=$(cd "$work" && ls new.mat* nofig-branch.png 2> /dev/null)
[ -z "$leftover" ] && pass "nothing half-written" || fail "left behind: $leftover"
"$cli" analyze "$pos" --edc "$work/edc_without.csv" > /dev/null 2>&1 && pass "a FLAC needs no module" ||
  fail "analyze of a FLAC without the modules"
unset OSCILAB_MODULE_DIR

[ $failures -eq 0 ] || { echo "$failures failure(s)" >&2; exit 1; }
echo "all passed"
