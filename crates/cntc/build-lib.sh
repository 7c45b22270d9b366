#!/usr/bin/env bash
# build-lib.sh [DEST] - builds railcontact's CONTACT-compatible library and
# puts it in DEST (default: target/cntc) under the name CONTACT's loaders
# open, contact_addon_linux64.so, with the C header beside it.
#
#   crates/cntc/build-lib.sh                     # -> target/cntc/contact_addon_linux64.so
#   crates/cntc/build-lib.sh /opt/contact/bin    # where CONTACT's python_intfc looks (../bin)
#
# Environment: PROFILE (default release; "dev" for a debug build).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
DEST=${1:-$ROOT/target/cntc}
PROFILE=${PROFILE:-release}
cd "$ROOT"
cargo build --profile "$PROFILE" -p railcontact-cntc
DIR=$(cargo metadata --format-version 1 --no-deps | sed -n 's/.*"target_directory":"\([^"]*\)".*/\1/p')
case "$PROFILE" in dev) SUB=debug ;; *) SUB=$PROFILE ;; esac
mkdir -p "$DEST"
cp "$DIR/$SUB/libcontact_addon.so" "$DEST/contact_addon_linux64.so"
cp "$ROOT/crates/cntc/include/contact_addon.h" "$DEST/"
echo "built $DEST/contact_addon_linux64.so ($PROFILE) and $DEST/contact_addon.h"
