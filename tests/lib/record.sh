# SPDX-License-Identifier: GPL-2.0
# Shared by the shell test scripts, the host's (bash) and the VM guest's
# (busybox sh, where scripts/vm-run.sh ships it as /tests/record.sh), so
# POSIX sh: calibration records edited on purpose.

# record_crc32 FILE: the CRC-32 of FILE's bytes as 8 hex digits, zlib's, as
# the daemon computes it: python3's zlib where there is python3 (the
# host), else busybox crc32 (the guest, which has no python3)
record_crc32() {
	if command -v python3 >/dev/null 2>&1; then
		python3 -c 'import sys, zlib
print("%08x" % zlib.crc32(open(sys.argv[1], "rb").read()))' "$1"
	else
		crc32 <"$1"
	fi
}

# record_reseal FILE: seal FILE again after an edit: every "crc32 = " line
# is taken out and one with the CRC-32 of everything left is appended, so
# the record passes its checksum and a test sees what the daemon makes of
# the edited content itself. FILE is rewritten in place (same inode).
record_reseal() {
	_rr_body=$(mktemp) || return
	_rr_crc=$(sed '/^crc32 = /d' "$1" >"$_rr_body" && record_crc32 "$_rr_body") &&
		{ cat "$_rr_body" && echo "crc32 = $_rr_crc"; } >"$1"
	_rr_rc=$?
	rm -f "$_rr_body"
	return $_rr_rc
}

# record_add_magn RECORD [KEY=VALUE...]: a format 1 record given a
# magnetometer section, format 2 (as the builds before the section moved
# to <record>.magn wrote it), re-sealed. The section's keys default to a
# plausible calibration; KEY=VALUE replaces the line of KEY (one the
# record has, else it fails), for a test that needs a value the daemon
# must refuse or show.
record_add_magn() {
	_ram_rec=$1
	shift
	sed -i -e 's/^format = as9888-calibration 1$/format = as9888-calibration 2/' \
		-e '/^crc32 = /d' "$_ram_rec" || return
	{
		echo "magn_hard_iron = 30.000 -45.500 100.250"
		echo "magn_soft_iron = 1.020000 0.012000 -0.031000" \
			"0.012000 0.985000 0.004000 -0.031000 0.004000 1.003000"
		echo "magn_field = 48.512"
		echo "magn_residual = 0.321"
		echo "magn_coverage = 0.875"
		echo "magn_samples = 300"
		echo "magn_learned = 2026-11-23T00:00:00Z"
	} >>"$_ram_rec" || return
	for _ram_kv in "$@"; do
		_ram_k=${_ram_kv%%=*}
		if ! grep -q "^$_ram_k = " "$_ram_rec"; then
			echo "record_add_magn: $_ram_rec has no $_ram_k line to replace" >&2
			return 1
		fi
		# (the value as sed's replacement: \, | and & taken literally)
		_ram_v=$(printf '%s\n' "${_ram_kv#*=}" | sed 's/[\\|&]/\\&/g')
		sed -i "s|^$_ram_k = .*|$_ram_k = $_ram_v|" "$_ram_rec" || return
	done
	record_reseal "$_ram_rec"
}
