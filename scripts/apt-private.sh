# shellcheck shell=bash disable=SC2034
# A private apt configuration for a Debian suite that the host does not run
# (scripts/libgpiod2-check.sh: trixie's sources; scripts/vm-run.sh: trixie's
# binary packages for the guest). Sourced, never executed; the caller
# defines die and log. Nothing is ever installed into the system from it:
# its own sources.list, lists and package cache under the directory given,
# no sources.list.d, and an empty dpkg status (no installed package counts).

# apt_mirror: the archive URI the system's apt uses for the running release
# (e.g. http://deb.debian.org/debian/), whatever the format of its sources
# files
apt_mirror() {
	local codename
	# shellcheck disable=SC1091
	codename=$(. /etc/os-release && printf '%s' "${VERSION_CODENAME:-}")
	[ -n "$codename" ] || die "no VERSION_CODENAME in /etc/os-release"
	# shellcheck disable=SC2016 # $(REPO_URI) is apt's format, not the shell's
	apt-get indextargets --format '$(REPO_URI)' \
		"Release: $codename" "Target-Of: deb" 2>/dev/null | awk 'NF' | head -n1
}

# apt_private DIR SUITE TYPES [WHO]: DIR/sources.list with a line "TYPE
# [signed-by=<Debian keyring>] <mirror> SUITE main" for each of TYPES
# ("deb-src"; "deb": amd64 binary packages), DIR/lists and DIR/cache; sets
# APT_OPTS (the options that make apt-get and apt-cache use them) and
# MIRROR. WHO names the user in the list's comment. The caller runs
# apt-get update.
APT_OPTS=()
apt_private() {
	local dir="$1" suite="$2" types="$3" who="${4:-$0}" mirror type opts
	local kr=/usr/share/keyrings/debian-archive-keyring.gpg
	mirror=$(apt_mirror) || true
	[ -n "$mirror" ] ||
		die "could not find the Debian mirror of this release in /etc/apt/sources.list(.d)"
	mirror=${mirror%/}
	[ -r "$kr" ] || die "missing $kr (package debian-archive-keyring)"
	mkdir -p "$dir/lists/partial" "$dir/cache/archives/partial"
	echo "# Private list used by $who only (never by the system's apt)." >"$dir/sources.list.new"
	for type in $types; do
		opts="signed-by=$kr"
		[ "$type" != deb ] || opts="arch=amd64 $opts"
		echo "$type [$opts] $mirror $suite main" >>"$dir/sources.list.new"
	done
	mv "$dir/sources.list.new" "$dir/sources.list"
	APT_OPTS=(-q
		-o "Dir::Etc::SourceList=$dir/sources.list"
		-o Dir::Etc::SourceParts=/dev/null
		-o "Dir::State::Lists=$dir/lists"
		-o "Dir::Cache=$dir/cache"
		-o Dir::State::status=/dev/null
		-o APT::Sandbox::User=root
		-o Acquire::Languages=none
		-o Acquire::IndexTargets::deb::DEP-11::DefaultEnabled=false
		-o Acquire::IndexTargets::deb::DEP-11-icons::DefaultEnabled=false
		-o Acquire::IndexTargets::deb::DEP-11-icons-small::DefaultEnabled=false
		-o Acquire::IndexTargets::deb::DEP-11-icons-hidpi::DefaultEnabled=false)
	MIRROR=$mirror
}
