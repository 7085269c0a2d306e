#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# Verify the systemd units with systemd-analyze against a staged root that
# holds the built as9888-calibd (a missing ExecStart binary is an error).
# Fails on any message, since verify also prints warnings with status 0.
# Usage: check-units.sh PATH-TO-as9888-calibd
set -euo pipefail

top=$(cd "$(dirname "$0")/.." && pwd)
calibd=${1:?usage: check-units.sh PATH-TO-as9888-calibd}
root=$(mktemp -d /tmp/as9888-units-XXXXXX)
trap 'rm -rf "$root"' EXIT

install -D -m 0755 "$calibd" "$root/usr/sbin/as9888-calibd"
install -D -m 0644 "$top/daemon/as9888-calibd.8" "$root/usr/share/man/man8/as9888-calibd.8"
for unit in "$top"/daemon/systemd/*.service "$top"/daemon/systemd/*.socket; do
	install -D -m 0644 "$unit" "$root/usr/lib/systemd/system/$(basename "$unit")"
done
# the targets and slices the default dependencies name
for unit in /usr/lib/systemd/system/*.target /usr/lib/systemd/system/*.slice; do
	cp -P "$unit" "$root/usr/lib/systemd/system/"
done
status=0
for unit in "$top"/daemon/systemd/*.service "$top"/daemon/systemd/*.socket; do
	if ! out=$(MANPATH="$root/usr/share/man" systemd-analyze verify --root="$root" \
			"$root/usr/lib/systemd/system/$(basename "$unit")" 2>&1) ||
	   [ -n "$out" ]; then
		echo "$out"
		echo "check-units: $(basename "$unit"): FAIL"
		status=1
	else
		echo "check-units: $(basename "$unit"): ok"
	fi
done
exit $status
