#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0
"""Check factory-test JSON reports against daemon/report.schema.json.

Usage: report_check.py SCHEMA [--complete] REPORT...

Each report must validate against the schema (Debian's python3-jsonschema,
Draft 7), have unique judgment IDs, and be consistent: a judgment with a
value passes exactly when the value lies within low..high, and the first
failed judgment is failed_step/failed_id. With --complete (a passing run
with every pin monitored) every judgment of the application note must be
there under its own ID. One line per report; exit status 1 if any fails.
"""
import json
import sys

import jsonschema

# Every judgment of the application note in a passing run on the register
# backend with RSTN, INT1 and INT2 monitored (see docs/DECISIONS.md)
APP_NOTE_IDS = (
    ["1-2.rstn", "1-4", "1-27", "1-39",
     "2-4.int1", "2-4.int2", "2-5", "2-6", "2-7", "2-9", "2-11", "2-13",
     "2-16", "2-17", "2-19", "2-21", "2-23",
     "3-23.posture", "3-23.dacopt", "3-26"]
    + ["3-%d" % s for s in [4, 5, 6] + list(range(7, 23))]
    + ["3-5.stable", "3-30.stable"]
    + ["3-%d" % s for s in [29, 30, 31] + list(range(32, 48))])


def problems(report, schema, complete):
    out = [e.message for e in
           jsonschema.Draft7Validator(schema).iter_errors(report)][:3]
    if out:
        return out
    steps = report["steps"]
    ids = [s["id"] for s in steps]
    dup = sorted({i for i in ids if ids.count(i) > 1})
    if dup:
        out.append("IDs not unique: %s" % ", ".join(dup))
    for s in steps:
        if not s["id"].startswith(s["step"]):
            out.append("%s: ID does not start with its step" % s["id"])
        if s["value"] is None or s["result"] == "skip":
            continue
        inside = ((s["low"] is None or s["value"] >= s["low"]) and
                  (s["high"] is None or s["value"] <= s["high"]))
        if inside != (s["result"] == "pass"):
            out.append("%s: value %s within %s..%s but result %s" %
                       (s["id"], s["value"], s["low"], s["high"], s["result"]))
    failed = [s for s in steps if s["result"] == "fail"]
    first = failed[0] if failed else None
    if report["result"] != ("fail" if failed else "pass"):
        out.append("result %s with %d failed judgments" %
                   (report["result"], len(failed)))
    if report["failed_id"] != (first and first["id"]) or \
       report["failed_step"] != (first and first["step"]):
        out.append("failed_step/failed_id do not name the first failure")
    if report["result"] == "pass" and report["calibration"] is None:
        out.append("a pass without a calibration")
    if report["record"] is not None and report["result"] != "pass":
        out.append("a record written by a failing run")
    if complete:
        missing = [i for i in APP_NOTE_IDS if i not in ids]
        if missing:
            out.append("judgments missing: %s" % ", ".join(missing))
        if report["result"] != "pass":
            out.append("--complete wants a passing run")
    return out


def main(argv):
    schema = json.load(open(argv[1]))
    jsonschema.Draft7Validator.check_schema(schema)
    complete = "--complete" in argv
    files = [a for a in argv[2:] if a != "--complete"]
    bad = 0
    for name in files:
        try:
            report = json.load(open(name))
        except ValueError as e:
            out = ["not JSON: %s" % e]
        else:
            out = problems(report, schema, complete)
        print("%s %s%s" % ("bad" if out else "ok", name,
                           ": " + "; ".join(out) if out else ""))
        bad += bool(out)
    return 1 if bad or not files else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
