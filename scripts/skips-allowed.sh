#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# skips-allowed.sh LIST COUNT LOG...: whether the COUNT skipped checks of a
# full run (scripts/test.sh) are all environment facts of LIST.
#
# LIST holds one entry a line, "NAME<TAB>PATTERN": PATTERN an extended
# regular expression matched against a skip line of the logs, NAME the
# fact it stands for; "#" starts a comment. A skip line is a TAP
# "# SKIP" (VM bench, boot test), a KUnit "[SKIPPED]" or a Meson "SKIP"
# result line (musl suite). Prints every skip line with the entry it
# matched, or "NOT ALLOWED", then the entries that applied. Exit 0 only
# when every skip line found matches an entry and at least COUNT were found
# (a skip that was counted but is in no log cannot be judged); 1 otherwise,
# 2 on a usage error or an unreadable LIST.
set -uo pipefail

[ $# -ge 2 ] || { echo "usage: skips-allowed.sh LIST COUNT LOG..." >&2; exit 2; }
list=$1 count=$2
shift 2
[ -r "$list" ] || { echo "skips-allowed: cannot read the list $list" >&2; exit 2; }
case $count in '' | *[!0-9]*) echo "skips-allowed: COUNT '$count' is not a number" >&2; exit 2 ;; esac

names=() patterns=()
while IFS=$'\t' read -r name pattern; do
	case $name in '' | '#'*) continue ;; esac
	if [ -z "$pattern" ]; then
		echo "skips-allowed: $list: entry '$name' has no pattern (NAME<TAB>PATTERN)" >&2
		exit 2
	fi
	names+=("$name")
	patterns+=("$pattern")
done <"$list"

found=0 bad=0
declare -A applied=()
while IFS= read -r line; do
	found=$((found + 1))
	hit=""
	for i in "${!patterns[@]}"; do
		if grep -qE -- "${patterns[$i]}" <<<"$line"; then
			hit=${names[$i]}
			break
		fi
	done
	if [ -n "$hit" ]; then
		applied[$hit]=1
		echo "skip: $line  [allowed: $hit]"
	else
		bad=$((bad + 1))
		echo "skip: $line  [NOT ALLOWED: no entry of $list]"
	fi
done < <(cat -- "$@" 2>/dev/null | grep -E '# SKIP|\[SKIPPED\]|[[:space:]]SKIP[[:space:]]')

facts=""
for name in "${!applied[@]}"; do facts="$facts $name"; done
echo "skips allowed as environment facts that applied:${facts:- none}"
if [ "$found" -lt "$count" ]; then
	echo "skips-allowed: $count skips counted, $found found in the logs: the rest cannot be judged"
	exit 1
fi
[ "$bad" -eq 0 ]
