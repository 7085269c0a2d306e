#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0
"""Give a format 1 record a magnetometer section (format 2), re-sealed.

magn_inject.py RECORD [KEY=VALUE...]: the section's keys default to a
plausible calibration; KEY=VALUE replaces one (as the tests need a value
the daemon must refuse or show).
"""
import sys
import zlib

DEFAULT = {
    "magn_hard_iron": "30.000 -45.500 100.250",
    "magn_soft_iron": "1.020000 0.012000 -0.031000 0.012000 0.985000 0.004000 "
                      "-0.031000 0.004000 1.003000",
    "magn_field": "48.512",
    "magn_residual": "0.321",
    "magn_coverage": "0.875",
    "magn_samples": "300",
    "magn_learned": "2026-11-23T00:00:00Z",
}


def main():
    path = sys.argv[1]
    keys = dict(DEFAULT)
    for arg in sys.argv[2:]:
        k, v = arg.split("=", 1)
        keys[k] = v
    text = open(path).read()
    body = text[:text.index("crc32 = ")]
    body = body.replace("format = as9888-calibration 1\n",
                        "format = as9888-calibration 2\n")
    body += "".join(f"{k} = {v}\n" for k, v in keys.items())
    with open(path, "w") as f:
        f.write(body + "crc32 = %08x\n" % zlib.crc32(body.encode()))


main()
