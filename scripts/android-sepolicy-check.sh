#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# Compile contrib/android/sepolicy/ with AOSP's platform policy, as Soong's
# se_policy_conf and se_policy_cil do: m4 over the files in checkpolicy's
# order (system/sepolicy's Android.bp se_build_files: each name in public/,
# private/, vendor/ (the default HALs' domains, hal_sensors_default among
# them, which a full build puts in the vendor policy), then the fragment),
# then checkpolicy -M -c 30, which also checks every neverallow of the
# platform against the fragment's rules. The platform alone is compiled
# first, so a failure is the fragment's. Then each context in the
# fragment's file_contexts and genfs_contexts must name a type the
# compiled policy has. Last, contrib/android/sepolicy-persist/ (for trees
# that label the persist root persist_file) is compiled on top, with
# persist_file declared as such trees declare it.
#
# Needs a checkout of AOSP's system/sepolicy (not part of this tree; no CI
# stage runs this):
#   scripts/android-sepolicy-check.sh /path/to/aosp/system/sepolicy
# Needs m4 and checkpolicy (installed when missing).
set -euo pipefail

# shellcheck source=scripts/kernel-common.sh
. "$(dirname "$0")/kernel-common.sh"
sp=$(realpath "${1:?usage: android-sepolicy-check.sh AOSP-SYSTEM-SEPOLICY-DIR}")
ours=$AS9888_REPO/contrib/android/sepolicy
[ -f "$sp/public/te_macros" ] && [ -f "$sp/private/security_classes" ] ||
	die "$sp is not AOSP's system/sepolicy (no public/te_macros, private/security_classes)"
ensure_pkgs m4 checkpolicy
work=$(mktemp -d /tmp/as9888-sepolicy-XXXXXX)
trap 'rm -rf "$work"' EXIT

# the file names in the order of system/sepolicy's se_build_files (each
# name globbed in each directory in turn), which is checkpolicy's order
order=(security_classes initial_sids access_vectors global_macros neverallow_macros
	mls_macros mls_decl mls policy_capabilities te_macros attributes ioctl_defines
	ioctl_macros '*.te' roles_decl roles users initial_sid_contexts fs_use
	genfs_contexts port_contexts)
# conf OUT DIR...: the policy.conf of the files in DIR...
conf() {
	local out=$1 d p f
	shift
	# the build-flag macros (is_flag_enabled) of newer trees: every flag off
	: >"$out.files"
	[ ! -f "$sp/flagging/te_macros" ] || echo "$sp/flagging/te_macros" >"$out.files"
	for p in "${order[@]}"; do
		for d in "$@"; do
			for f in "$d"/$p; do
				[ -f "$f" ] && echo "$f"
			done
		done
	done >>"$out.files"
	# the defines of a user build of a full-Treble device
	xargs -d '\n' m4 --fatal-warnings -s -D mls_num_sens=1 -D mls_num_cats=1024 \
		-D target_arch=arm64 -D target_with_asan=false -D target_with_dexpreopt=false \
		-D target_with_native_coverage=false -D target_build_variant=user \
		-D target_full_treble=true -D target_compatible_property=true \
		-D target_treble_sysprop_neverallow=true -D target_enforce_sysprop_owner=true \
		-D target_exclude_build_test=false \
		-D target_requires_insecure_execmem_for_swiftshader=false \
		-D target_enforce_debugfs_restriction=true -D target_recovery=false \
		<"$out.files" >"$out"
}

status=0
conf "$work/platform.conf" "$sp/public" "$sp/private" "$sp/vendor"
if checkpolicy -M -c 30 -o "$work/platform.bin" "$work/platform.conf" >"$work/platform.log" 2>&1; then
	log "AOSP's platform policy alone compiles ($(grep -c . "$work/platform.conf.files") files, checkpolicy $(checkpolicy -V | awk '{ print $1 }'))"
else
	tail -5 "$work/platform.log"
	die "AOSP's platform policy alone does not compile with this checkpolicy: the check cannot run"
fi
conf "$work/with.conf" "$sp/public" "$sp/private" "$sp/vendor" "$ours"
if checkpolicy -M -c 30 -o "$work/with.bin" "$work/with.conf" >"$work/with.log" 2>&1; then
	echo "android-sepolicy: as9888_calibd.te, hal_sensors_default.te and genfs_contexts compile with the platform policy, its neverallows hold: ok"
else
	cat "$work/with.log"
	echo "android-sepolicy: the fragment does not compile with the platform policy: FAIL"
	status=1
fi
# a QCOM/Pixel-style tree: its persist_file, and our rules on it
mkdir "$work/persist"
echo 'type persist_file, file_type;' >"$work/persist/device_persist.te"
conf "$work/persist.conf" "$sp/public" "$sp/private" "$sp/vendor" "$ours" "$work/persist" \
	"$AS9888_REPO/contrib/android/sepolicy-persist"
if checkpolicy -M -c 30 -o "$work/persist.bin" "$work/persist.conf" >"$work/persist.log" 2>&1; then
	echo "android-sepolicy: sepolicy-persist/ compiles on a tree with persist_file: ok"
else
	cat "$work/persist.log"
	echo "android-sepolicy: sepolicy-persist/ does not compile on a tree with persist_file: FAIL"
	status=1
fi

# the contexts name types the policy declares (what checkfc would refuse)
for t in $(sed -n 's/.*u:object_r:\([a-z0-9_]*\):s0.*/\1/p' "$ours/file_contexts" "$ours/genfs_contexts" | sort -u); do
	if grep -Eq "^type $t[,;]" "$work/with.conf"; then
		echo "android-sepolicy: context type $t declared: ok"
	else
		echo "android-sepolicy: context type $t is not declared: FAIL"
		status=1
	fi
done
# every type an allow rule names is declared, by the platform or by us:
# none that only a device tree defines (persist_file and the like)
for t in $(sed -n 's/^allow \([a-z0-9_]*\) \([a-z0-9_]*\):.*/\1 \2/p' "$ours"/*.te |
		tr ' ' '\n' | grep -vx self | sort -u); do
	if grep -Eq "^(type|attribute) $t[,;]" "$work/platform.conf"; then
		echo "android-sepolicy: $t: the platform's: ok"
	elif grep -Eq "^type $t[,;]" "$ours"/*.te; then
		echo "android-sepolicy: $t: ours: ok"
	else
		echo "android-sepolicy: $t is neither the platform's nor ours: FAIL"
		status=1
	fi
done
[ $status -ne 0 ] || echo "android-sepolicy: all ok (AOSP system/sepolicy at $sp)"
exit $status
