# SPDX-License-Identifier: GPL-2.0
# Shared by the shell test scripts: calibration records edited on purpose.

# record_reseal FILE: seal FILE again after an edit: every "crc32 = " line
# is taken out and one with the CRC-32 (zlib's, as the daemon computes it)
# of everything left is appended, so the record passes its checksum and a
# test sees what the daemon makes of the edited content itself
record_reseal() {
	python3 - "$1" <<'PY'
import re, sys, zlib
path = sys.argv[1]
with open(path) as f:
    body = re.sub(r"(?m)^crc32 = .*(\n|$)", "", f.read())
with open(path, "w") as f:
    f.write(body + "crc32 = %08x\n" % zlib.crc32(body.encode()))
PY
}
