#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# upstream-stages.sh trees OUTDIR
# upstream-stages.sh carry DIFF FIRST-STAGE TREESDIR
# upstream-stages.sh pack TREESDIR
# upstream-stages.sh update REV
#
# The stages of the upstream series (upstream/stages/NN-name/, one per
# patch after the binding) and the trees they stand for. The repository's
# own files are the tree of the LAST stage; each stage directory holds
#   message        the commit message: subject, blank line, body (no
#                  sign-off; upstream-series.sh adds it)
#   files          the repository paths the patch adds, one a line
#   changes.patch  (optional) what the patch changes in files that an
#                  earlier stage added: a unified diff, a/ b/ prefixes,
#                  from the tree of the stage before to this stage's
# The tree of stage k-1 is the tree of stage k without the files of stage
# k and with stage k's changes.patch applied in reverse (git apply -R, no
# fuzz). So a change to the repository flows into every stage whose code
# it touches, and a change inside a hunk of some changes.patch stops the
# series with the name of that stage, never a silent drift.
#
#   trees OUTDIR   writes the tree of every stage to OUTDIR/NN-name/
#                  (repository paths). Fails naming the stage whose
#                  changes.patch no longer applies, and when a file of
#                  the driver directory is in no stage.
#   carry DIFF FIRST-STAGE TREESDIR
#                  applies DIFF (a unified diff of repository paths, such
#                  as git diff A B -- drivers/iio/imu/as9888 Documentation)
#                  to the trees of FIRST-STAGE and every later stage in
#                  TREESDIR; in each tree, the hunks of files it does not
#                  have yet are left out (they reach the stage that adds
#                  the file), and so are hunks that do not apply: the code
#                  they change comes with a later stage. Each left-out
#                  hunk is listed, to be checked by the developer; one
#                  left out of the last tree fails (pack would refuse it).
#   pack TREESDIR  the inverse of trees: writes every stage's files and
#                  changes.patch from TREESDIR/NN-name/ (a stage directory
#                  needs its message first). The last tree must equal the
#                  repository's files.
#   update REV     after a change to the driver that stops `trees`: makes
#                  the stage trees of REV (a commit where the series
#                  passed, with the same stages), carries the change from
#                  REV to the working tree into them from the first stage
#                  on (each hunk lands in the first stage where it
#                  applies), and packs. Then run upstream-series.sh: a hunk
#                  that landed too early (it applied there, but uses what a
#                  later stage brings) fails that stage's build; move it
#                  by hand in the trees, which update leaves in
#                  $AS9888_CACHE/stages-update/.
#
# How to add a feature patch or fix a stage: docs/DECISIONS.md, "The
# upstream series is a stack of stages".
# Exit status: 0 done, 1 a stage does not apply or the trees are wrong,
# 2 usage.
set -euo pipefail

# shellcheck source-path=SCRIPTDIR source=kernel-common.sh
. "$(dirname "$0")/kernel-common.sh"

REPO="$AS9888_REPO"
STAGES="$REPO/upstream/stages"
# Repository files of the driver directory that are not sent: the
# out-of-tree build (Kbuild, compat/)
NOT_SENT_RE="^$AS9888_DRIVER_REL/(Kbuild|compat/.*)\$"

usage() {
	echo "usage: $0 trees OUTDIR | carry DIFF FIRST-STAGE TREESDIR | pack TREESDIR | update REV" >&2
	exit 2
}

# The stage names, in order
stage_names() {
	find "$STAGES" -mindepth 1 -maxdepth 1 -type d -printf '%f\n' | LC_ALL=C sort
}

# stage_files NAME: the files the stage adds (comments and blank lines out)
stage_files() {
	[ -f "$STAGES/$1/files" ] || return 0
	sed -e 's/#.*//' -e 's/[[:space:]]*$//' -e '/^$/d' "$STAGES/$1/files"
}

# Every repository file some stage adds, sorted
all_files() {
	local s
	for s in $(stage_names); do
		stage_files "$s"
	done | LC_ALL=C sort
}

# copy_tree FROM TO: a plain copy of a tree of repository paths
copy_tree() {
	rm -rf "$2"
	mkdir -p "$2"
	(cd "$1" && find . -type f -print0 | cpio -0pdm --quiet "$2")
}

cmd_trees() {
	local out="$1" cur names s i f dup
	[ -d "$STAGES" ] || die "no stages in $STAGES"
	mapfile -t names < <(stage_names)
	[ "${#names[@]}" -gt 0 ] || die "no stages in $STAGES"
	for s in "${names[@]}"; do
		[ -s "$STAGES/$s/message" ] || die "stage $s has no message"
	done
	dup=$(all_files | uniq -d)
	[ -z "$dup" ] || die "added by more than one stage: $dup"

	# Every file of the driver directory is sent, or is known not to be
	local missing=""
	while IFS= read -r f; do
		[[ "$f" =~ $NOT_SENT_RE ]] && continue
		all_files | grep -qxF "$f" || missing="$missing $f"
	done < <(cd "$REPO" && git ls-files "$AS9888_DRIVER_REL" 2>/dev/null ||
		find "$AS9888_DRIVER_REL" -type f)
	[ -z "$missing" ] || die "in no stage (add them to a stage's files):$missing"

	mkdir -p "$out"
	out="$(cd "$out" && pwd)"
	cur="$out/.work"
	rm -rf "$cur"
	mkdir -p "$cur"
	while IFS= read -r f; do
		[ -f "$REPO/$f" ] || die "stage file $f is not in the repository"
		mkdir -p "$(dirname "$cur/$f")"
		cp -p "$REPO/$f" "$cur/$f"
	done < <(all_files)

	for ((i = ${#names[@]} - 1; i >= 0; i--)); do
		s="${names[$i]}"
		copy_tree "$cur" "$out/$s"
		while IFS= read -r f; do
			rm -f "$cur/$f"
		done < <(stage_files "$s")
		if [ -f "$STAGES/$s/changes.patch" ]; then
			[ "$i" -gt 0 ] || die "stage $s is the first: it has nothing to change"
			# not in any git repository: git apply works on plain files
			if ! (cd "$cur" && GIT_CEILING_DIRECTORIES="$out" \
				git apply -R --whitespace=nowarn "$STAGES/$s/changes.patch") \
				>"$out/.apply.log" 2>&1; then
				sed 's/^/    /' "$out/.apply.log" >&2
				die "stage $s: its changes.patch no longer applies to the tree (reversed): the tree changed inside one of its hunks. Fix the stage trees and pack them again (docs/DECISIONS.md, \"The upstream series is a stack of stages\")"
			fi
		fi
	done
	f=$(cd "$cur" && find . -type f | head -n 5)
	[ -z "$f" ] || die "files left before the first stage (no stage adds them): $f"
	rm -rf "$cur" "$out/.apply.log"
}

cmd_carry() {
	local diff in first s f ex left="" started=0
	diff="$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"
	first="$2"
	in="$(cd "$3" && pwd)"
	[ -d "$in/$first" ] || die "no stage tree $in/$first"
	for s in $(find "$in" -mindepth 1 -maxdepth 1 -type d ! -name '.*' -printf '%f\n' | LC_ALL=C sort); do
		[ "$s" = "$first" ] && started=1
		[ "$started" = 1 ] || continue
		ex=()
		while IFS= read -r f; do
			[ -f "$in/$s/$f" ] || ex+=("--exclude=$f")
		done < <(sed -n 's|^+++ b/||p' "$diff" | sed 's/[[:space:]]*$//' | sort -u)
		(cd "$in/$s" && GIT_CEILING_DIRECTORIES="$in" \
			git apply -v --reject --whitespace=nowarn "${ex[@]}" "$diff") \
			>"$in/.carry.log" 2>&1 || true
		# "Applying patch F with N rejects...", then "Rejected hunk #K."
		left=$(grep -E '^(Applying patch|Rejected hunk)' "$in/.carry.log" |
			awk '/^Applying/ { f = $3; next }
			     { h = $3; sub(/\.$/, "", h); print f " hunk " h }' || true)
		find "$in/$s" -name '*.rej' -delete
		if [ -n "$left" ]; then
			log "$s: carried but for these hunks (code a later stage brings? check):"
			printf '%s\n' "$left" | sed 's/^/    /'
		else
			log "$s: carried"
		fi
	done
	[ -z "$left" ] || die "the last stage, $s, must take the whole diff"
	rm -f "$in/.carry.log"
}

cmd_pack() {
	local in="$1" names s prev="" f a b added
	in="$(cd "$in" && pwd)"
	mapfile -t names < <(find "$in" -mindepth 1 -maxdepth 1 -type d ! -name '.*' -printf '%f\n' | LC_ALL=C sort)
	[ "${#names[@]}" -gt 0 ] || die "no stage trees in $in"
	for s in "${names[@]}"; do
		[ -s "$STAGES/$s/message" ] ||
			die "stage $s has no $STAGES/$s/message: write it first"
	done
	# the last tree is the repository
	s="${names[${#names[@]} - 1]}"
	while IFS= read -r f; do
		cmp -s "$in/$s/$f" "$REPO/$f" ||
			die "the last stage's $f differs from the repository's"
	done < <(cd "$in/$s" && find . -type f | sed 's|^\./||' | LC_ALL=C sort)

	for s in "${names[@]}"; do
		added=""
		: >"$STAGES/$s/changes.patch.new"
		while IFS= read -r f; do
			if [ -z "$prev" ] || [ ! -f "$in/$prev/$f" ]; then
				added="$added$f"$'\n'
			elif ! cmp -s "$in/$prev/$f" "$in/$s/$f"; then
				diff -u --label "a/$f" --label "b/$f" "$in/$prev/$f" "$in/$s/$f" \
					>>"$STAGES/$s/changes.patch.new" || true
			fi
		done < <(cd "$in/$s" && find . -type f | sed 's|^\./||' | LC_ALL=C sort)
		if [ -n "$prev" ]; then
			while IFS= read -r f; do
				[ -f "$in/$s/$f" ] || die "stage $s removes $f: stages only add files"
			done < <(cd "$in/$prev" && find . -type f | sed 's|^\./||')
		fi
		printf '%s' "$added" >"$STAGES/$s/files"
		if [ -s "$STAGES/$s/changes.patch.new" ]; then
			mv "$STAGES/$s/changes.patch.new" "$STAGES/$s/changes.patch"
		else
			rm -f "$STAGES/$s/changes.patch.new" "$STAGES/$s/changes.patch"
		fi
		log "$s: $(grep -c . "$STAGES/$s/files" || true) files added, $(grep -c '^@@' "$STAGES/$s/changes.patch" 2>/dev/null || echo 0) hunks changed"
		prev="$s"
	done
}

cmd_update() {
	local rev="$1" tmp="$AS9888_CACHE/stages-update" names first
	git -C "$REPO" rev-parse -q --verify "$rev^{commit}" >/dev/null ||
		die "$rev is not a commit"
	rm -rf "$tmp"
	mkdir -p "$tmp/before"
	git -C "$REPO" archive "$rev" | tar -x -C "$tmp/before"
	# this script, whatever REV's was
	cp "$0" "$tmp/before/scripts/upstream-stages.sh"
	cp "$(dirname "$0")/kernel-common.sh" "$tmp/before/scripts/kernel-common.sh"
	"$tmp/before/scripts/upstream-stages.sh" trees "$tmp/trees" ||
		die "the stage trees of $rev cannot be made either"
	git -C "$REPO" diff "$rev" -- "$AS9888_DRIVER_REL" Documentation >"$tmp/change.diff"
	mapfile -t names < <(stage_names)
	first="${names[0]}"
	if [ -s "$tmp/change.diff" ]; then
		cmd_carry "$tmp/change.diff" "$first" "$tmp/trees"
	else
		log "no change to the driver or Documentation since $rev"
	fi
	cmd_pack "$tmp/trees"
	log "trees in $tmp/trees; now run scripts/upstream-series.sh"
}

case "${1:-}" in
trees) [ $# -eq 2 ] || usage; cmd_trees "$2" ;;
carry) [ $# -eq 4 ] || usage; cmd_carry "$2" "$3" "$4" ;;
pack) [ $# -eq 2 ] || usage; cmd_pack "$2" ;;
update) [ $# -eq 2 ] || usage; cmd_update "$2" ;;
*) usage ;;
esac
