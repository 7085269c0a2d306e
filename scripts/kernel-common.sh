# shellcheck shell=bash disable=SC2034
# Helpers shared by the AS9888 kernel-side scripts (kernel-trees.sh,
# kernel-build.sh, dt-check.sh, dkms-check.sh). Sourced, never executed.
#
# Cache layout (everything outside the repository):
#   $AS9888_CACHE/src/linux-<k>/      pristine, unpacked kernel source (k = 6.1, 7.2)
#   $AS9888_CACHE/build/linux-<k>/    O= build dir: .config, vmlinux, bzImage, Module.symvers
#   $AS9888_CACHE/bin/sparse          sparse built from Debian unstable's source
#   $AS9888_CACHE/apt-unstable/       private apt sources list + lists + package cache
#   $AS9888_CACHE/stamps/             stamp files that make warm runs take seconds
#   $AS9888_CACHE/logs/               logs of the last runs
#   $AS9888_CACHE/kernels.env         paths above as shell variables, for other scripts

AS9888_CACHE="${AS9888_CACHE:-$HOME/.cache/as9888}"
AS9888_REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
AS9888_KERNELS=(6.1 7.2)
AS9888_DRIVER_REL="drivers/iio/imu/as9888"
SPARSE_BIN="$AS9888_CACHE/bin/sparse"
STAMP_DIR="$AS9888_CACHE/stamps"
LOG_DIR="$AS9888_CACHE/logs"
JOBS="${AS9888_JOBS:-2}"

SCRIPT_NAME="$(basename "$0" .sh)"

log() { printf '[%s] %s\n' "$SCRIPT_NAME" "$*"; }
warn() { printf '[%s] WARNING: %s\n' "$SCRIPT_NAME" "$*" >&2; }
die() {
	printf '[%s] ERROR: %s\n' "$SCRIPT_NAME" "$*" >&2
	exit 1
}

ksrc() { printf '%s/src/linux-%s\n' "$AS9888_CACHE" "$1"; }
kobj() { printf '%s/build/linux-%s\n' "$AS9888_CACHE" "$1"; }

# Seconds since the epoch with fractions, and a pretty "elapsed since" helper.
now() { date +%s.%N; }
since() { awk -v a="$1" -v b="$(now)" 'BEGIN { printf "%.1f s", b - a }'; }

# Run a command as root (directly, or through sudo when not root).
as_root() {
	if [ "$(id -u)" -eq 0 ]; then
		"$@"
	elif command -v sudo >/dev/null 2>&1; then
		sudo "$@"
	else
		die "need root (or sudo) to run: $*"
	fi
}

pkg_installed() {
	dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q 'install ok installed'
}

# ensure_pkgs PKG...: apt-get install the packages that are not installed yet
# (from the system's normal, stable sources). Retries once after apt-get update.
ensure_pkgs() {
	local missing=() p
	for p in "$@"; do
		pkg_installed "$p" || missing+=("$p")
	done
	[ "${#missing[@]}" -eq 0 ] && return 0
	log "apt-get install ${missing[*]}"
	local apt=(env DEBIAN_FRONTEND=noninteractive apt-get -q -o DPkg::Lock::Timeout=900)
	if ! as_root "${apt[@]}" install -y --no-install-recommends "${missing[@]}"; then
		log "install failed; running apt-get update and retrying"
		as_root "${apt[@]}" update
		as_root "${apt[@]}" install -y --no-install-recommends "${missing[@]}"
	fi
}

# Driver sources (.c) present in a source root? (prints them, one per line)
driver_c_files() {
	local root="$1"
	find "$root/$AS9888_DRIVER_REL" -maxdepth 1 -type f -name '*.c' 2>/dev/null | sort
}

# Sources (.c, relative to the driver dir) that the driver Makefile needs but
# that do not exist: objects of multi-object modules, and single-object
# modules. Prints one name per line.
driver_missing_sources() {
	local dir="$1/$AS9888_DRIVER_REL"
	[ -f "$dir/Makefile" ] || return 0
	sed -e ':a' -e '/\\$/{N;s/\\\n/ /;ba' -e '}' "$dir/Makefile" | awk '
		/^[[:space:]]*#/ { next }
		$1 ~ /^obj-/ { for (i = 3; i <= NF; i++) if ($i ~ /\.o$/) mods[$i] = 1; next }
		$1 ~ /-(y|objs|\$\(CONFIG_[A-Za-z0-9_]+\))$/ && ($2 == ":=" || $2 == "+=" || $2 == "=") {
			m = $1; sub(/-(y|objs|\$\(CONFIG_[A-Za-z0-9_]+\))$/, "", m); comp[m ".o"] = 1
			for (i = 3; i <= NF; i++) if ($i ~ /\.o$/) parts[$i] = 1
		}
		END {
			for (m in mods) if (!(m in comp)) need[m] = 1
			for (p in parts) need[p] = 1
			for (n in need) { sub(/\.o$/, ".c", n); print n }
		}' | sort | while IFS= read -r c; do
		[ -f "$dir/$c" ] || printf '%s\n' "$c"
	done
}

# cache_lock NAME: serialise runs of one script that share a cache dir (the
# lock is held until the script exits). Uses file descriptor 8.
cache_lock() {
	mkdir -p "$AS9888_CACHE"
	exec 8>"$AS9888_CACHE/.$1.lock"
	if ! flock -n 8; then
		log "another $1 run holds $AS9888_CACHE/.$1.lock; waiting"
		flock 8
	fi
}

# select_kernels [6.1|7.2|all]: the kernels a script works on, into WANT;
# a usage message and exit status 2 for anything else
select_kernels() {
	case "${1:-all}" in
	6.1 | 7.2) WANT=("$1") ;;
	all) WANT=("${AS9888_KERNELS[@]}") ;;
	*)
		echo "usage: $0 [6.1|7.2|all]" >&2
		exit 2
		;;
	esac
}
