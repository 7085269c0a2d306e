#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# yocto-check.sh [--set-srcrev REV]
#
# Checks contrib/yocto/meta-as9888 without bitbake (CI has no OE-core
# build; see docs/DECISIONS.md for the one-off parse):
#  1. oelint-adv (PyPI, pinned with its dependencies in
#     scripts/oelint-requirements.txt, installed into a venv under
#     $AS9888_CACHE/oelint) on every recipe, once for each release that
#     conf/layer.conf's LAYERSERIES_COMPAT names (--release): any finding
#     fails. Three rules are off, for the reasons given at "suppress" below.
#  2. The pinned tree: SRCREV (include/as9888-source.inc) must be a commit
#     of this repository; every -D option the daemon's recipe passes
#     (EXTRA_OEMESON and both sides of each PACKAGECONFIG) must be an
#     option of that tree's meson_options.txt; and that tree, exported with
#     git archive, must configure (meson setup) with the recipe's flags,
#     BitBake's variables given their OE-core defaults, for a systemd and a
#     sysvinit distro, with and without PACKAGECONFIG gpiod.
#  3. The kernel fragment (recipes-kernel/linux/files/as9888.cfg): merged
#     into x86_64 defconfig of the cached 6.1 and 7.2 trees
#     (scripts/kernel-trees.sh; missing trees fail the check) with the
#     kernel's merge_config.sh, every option comes out as asked.
#  4. contrib/buildroot's packages: the same commit as SRCREV, and their
#     .hash files hold COPYING's sha256 as of it and a tarball hash for it
#     (computed once with Buildroot's download helper: docs/DECISIONS.md).
# --set-srcrev REV: first resolve REV (a tag such as v0.1.0, or a commit)
# and run check 2 on it; when it passes, write it into SRCREV. That is how
# a release moves the pin (the recipe never pins a commit that has not
# been checked to configure with its flags); check 4 then fails until the
# Buildroot packages follow.
# Prints "yocto: N passed, N failed".
set -uo pipefail

# shellcheck source=scripts/kernel-common.sh
. "$(dirname "$0")/kernel-common.sh"
top=$AS9888_REPO
layer=$top/contrib/yocto/meta-as9888
inc=$layer/include/as9888-source.inc
recipe=$layer/recipes-sensors/as9888-calibd/as9888-calibd_git.bb
cfg=$layer/recipes-kernel/linux/files/as9888.cfg
reqs=$top/scripts/oelint-requirements.txt
venv=$AS9888_CACHE/oelint/venv
work=${AS9888_BUILD:-$top/build}/yocto
mkdir -p "$work"

passed=0
failed=0
result() { # WHAT STATUS
	if [ "$2" -eq 0 ]; then
		echo "ok - $1"
		passed=$((passed + 1))
	else
		echo "not ok - $1"
		failed=$((failed + 1))
	fi
}

# --- the pinned tree configures with the recipe's flags --------------------------
# recipe_flags SYSTEMD SYSVINIT GPIOD: the recipe's meson flags with
# BitBake's variables expanded as OE-core's defaults would
recipe_flags() {
	python3 - "$recipe" "$1" "$2" "$3" <<'PY'
import re, sys
text, systemd, sysvinit, gpiod = open(sys.argv[1]).read(), *sys.argv[2:]
text = text.replace("\\\n", " ")
vals = []
for m in re.finditer(r'^EXTRA_OEMESON \+?= "([^"]*)"', text, re.M):
    vals.append(m.group(1))
flags = " ".join(vals)
pc = {n: (on, off) for n, on, off in
      re.findall(r'^PACKAGECONFIG\[(\w+)\] = "([^,]*),([^,]*),', text, re.M)}
flags += " " + (pc["gpiod"][0] if gpiod == "true" else pc["gpiod"][1])
def contains(m):
    return {"systemd": systemd, "sysvinit": sysvinit}[m.group(1)]
flags = re.sub(r"\$\{@bb\.utils\.contains\('DISTRO_FEATURES', '(\w+)', 'true', 'false', d\)\}",
               contains, flags)
statedir = re.search(r'^AS9888_STATEDIR \?\?= "([^"]*)"', text, re.M).group(1)
flags = flags.replace("${AS9888_STATEDIR}", statedir)
for var, val in {"systemd_system_unitdir": "/usr/lib/systemd/system",
                 "nonarch_base_libdir": "/usr/lib", "nonarch_libdir": "/usr/lib",
                 "localstatedir": "/var"}.items():
    flags = flags.replace("${%s}" % var, val)
left = re.findall(r"\$\{[^}]*\}", flags)
if left:
    sys.exit("unexpanded in the recipe's flags: %s" % " ".join(left))
print(" ".join(flags.split()))
PY
}

# pinned_tree_ok REV: check 2 on REV; says what is wrong
pinned_tree_ok() {
	local rev=$1 opts flags o name src bld variant rc=0
	git -C "$top" cat-file -e "$rev^{commit}" 2>/dev/null || {
		echo "  SRCREV $rev is not a commit of this repository"
		return 1
	}
	opts=$(git -C "$top" show "$rev:meson_options.txt" | sed -n "s/^option('\([^']*\)'.*/\1/p")
	for variant in "true false false" "false true false" "true false true"; do
		# shellcheck disable=SC2086
		flags=$(recipe_flags $variant) || return 1
		for o in $flags; do
			name=${o#-D}
			name=${name%%=*}
			echo "$opts" | grep -qx "$name" || {
				echo "  the recipe passes -D$name, which $rev's meson_options.txt lacks"
				rc=1
			}
		done
	done
	[ "$rc" -eq 0 ] || return 1
	src=$work/pinned-src
	rm -rf "$src"
	mkdir -p "$src"
	git -C "$top" archive "$rev" | tar -x -C "$src"
	for variant in "true false false" "false true false" "true false true"; do
		# shellcheck disable=SC2086
		flags=$(recipe_flags $variant)
		bld=$work/pinned-build
		rm -rf "$bld"
		# shellcheck disable=SC2086
		if ! meson setup "$bld" "$src" --prefix=/usr $flags >"$work/pinned-setup.log" 2>&1; then
			echo "  $rev does not configure with: $flags"
			tail -n 5 "$work/pinned-setup.log" | sed 's/^/    /'
			rc=1
		else
			echo "  $rev configures with: $flags"
		fi
	done
	rm -rf "$src" "$bld"
	return "$rc"
}

if [ "${1:-}" = --set-srcrev ]; then
	[ $# -eq 2 ] || die "usage: scripts/yocto-check.sh [--set-srcrev REV]"
	rev=$(git -C "$top" rev-parse --verify "$2^{commit}") || die "$2: not a commit"
	pinned_tree_ok "$rev" || die "$2 ($rev) does not take the recipe's flags: SRCREV unchanged"
	sed -i "s/^SRCREV = \"[0-9a-f]*\"$/SRCREV = \"$rev\"/" "$inc"
	grep -q "^SRCREV = \"$rev\"$" "$inc" || die "could not write SRCREV into $inc"
	log "SRCREV = $rev ($2) in $inc"
	exit 0
elif [ $# -gt 0 ]; then
	die "usage: scripts/yocto-check.sh [--set-srcrev REV]"
fi

# --- 1. oelint-adv for each release ------------------------------------------------
if ! [ -x "$venv/bin/oelint-adv" ] || ! cmp -s "$reqs" "$venv/as9888-requirements.txt"; then
	log "installing oelint-adv (pinned in $reqs) into $venv"
	ensure_pkgs python3-venv
	rm -rf "$venv"
	/usr/bin/python3 -m venv "$venv" || die "python3 -m venv $venv failed"
	"$venv/bin/pip" install -q --no-deps -r "$reqs" || die "pip install of the pinned oelint-adv failed"
	cp "$reqs" "$venv/as9888-requirements.txt"
fi
releases=$(sed -n 's/^LAYERSERIES_COMPAT_as9888 = "\([^"]*\)"$/\1/p' "$layer/conf/layer.conf")
[ -n "$releases" ] || die "no LAYERSERIES_COMPAT_as9888 in $layer/conf/layer.conf"
mapfile -t files < <(find "$layer" -name '*.bb' -o -name '*.bbappend' | sort)
# suppress: oelint.var.bbclassextend - target-only recipes (a board's
# daemon and kernel modules have no native or nativesdk use);
# oelint.var.suggestedvar.BUGTRACKER - the project has no public tracker;
# oelint.vars.homepageping - it fetches HOMEPAGE over the network, which
# CI cannot rely on (and the project's host is not public yet).
for r in $releases; do
	"$venv/bin/oelint-adv" --release "$r" --quiet \
		--suppress oelint.var.bbclassextend \
		--suppress oelint.var.suggestedvar.BUGTRACKER \
		--suppress oelint.vars.homepageping \
		"${files[@]}" >"$work/oelint-$r.log" 2>&1
	rc=$?
	[ -s "$work/oelint-$r.log" ] && { sed 's/^/  /' "$work/oelint-$r.log"; rc=1; }
	result "oelint-adv $("$venv/bin/oelint-adv" --version | awk '{ print $2 }') --release $r: ${#files[@]} recipes clean" "$rc"
done

# --- 2. SRCREV ----------------------------------------------------------------------
srcrev=$(sed -n 's/^SRCREV = "\([0-9a-f]*\)"$/\1/p' "$inc")
pinned_tree_ok "${srcrev:-none}"
result "SRCREV ${srcrev:-none}: a commit of this repository that configures with the recipe's flags" $?

# --- 3. the kernel fragment -----------------------------------------------------------
fragment_ok() { # K
	local k=$1 src obj opt want got rc=0
	src=$(ksrc "$k")
	[ -f "$src/scripts/kconfig/merge_config.sh" ] || {
		echo "  no kernel tree $src (scripts/kernel-trees.sh $k)"
		return 1
	}
	obj=$work/kconfig-$k
	rm -rf "$obj"
	mkdir -p "$obj"
	{ make -s -C "$src" O="$obj" ARCH=x86_64 defconfig &&
		(cd "$src" && ARCH=x86_64 KCONFIG_CONFIG="$obj/.config" \
			scripts/kconfig/merge_config.sh -m -O "$obj" "$obj/.config" "$cfg") &&
		make -s -C "$src" O="$obj" ARCH=x86_64 olddefconfig; } >"$work/kconfig-$k.log" 2>&1 || {
		echo "  merging the fragment into $k's defconfig failed (log $work/kconfig-$k.log)"
		return 1
	}
	while IFS= read -r opt; do
		want=${opt#*=}
		got=$(sed -n "s/^${opt%%=*}=//p" "$obj/.config")
		[ "$got" = "$want" ] || { echo "  $k: ${opt%%=*} is ${got:-not set}, the fragment asks $want"; rc=1; }
	done < <(grep '^CONFIG_' "$cfg")
	rm -rf "$obj"
	return "$rc"
}
for k in 6.1 7.2; do
	fragment_ok "$k"
	result "as9888.cfg merged into $k's x86_64 defconfig: every option as asked" $?
done

# --- 4. Buildroot's packages pin the same tree ----------------------------------------
# (their tarball hashes were computed with Buildroot's own download helper,
# a one-off recorded in docs/DECISIONS.md; COPYING's hash is checked here)
br_pins_ok() {
	local mk hash v rc=0 want
	want=$(git -C "$top" show "$srcrev:COPYING" 2>/dev/null | sha256sum | cut -d' ' -f1)
	for mk in "$top"/contrib/buildroot/package/*/*.mk; do
		v=$(sed -n 's/^[A-Z0-9_]*_VERSION = \([0-9a-f]*\)$/\1/p' "$mk")
		[ "$v" = "$srcrev" ] || { echo "  ${mk#"$top"/}: version ${v:-none}, Yocto's SRCREV $srcrev"; rc=1; }
		hash=${mk%.mk}.hash
		grep -q "^sha256  $want  COPYING$" "$hash" ||
			{ echo "  ${hash#"$top"/}: no sha256 of COPYING as of $srcrev ($want)"; rc=1; }
		grep -q "^sha256  [0-9a-f]\{64\}  $(basename "${mk%.mk}")-$srcrev-git4.tar.gz$" "$hash" ||
			{ echo "  ${hash#"$top"/}: no tarball hash for version $srcrev"; rc=1; }
	done
	return "$rc"
}
br_pins_ok
result "Buildroot packages: the same commit as SRCREV, COPYING's hash as of it" $?

echo "yocto: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
