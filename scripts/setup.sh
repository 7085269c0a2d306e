#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# Install the Debian 12 packages the userspace build, the tests and the demo
# need, if any is missing. Needs root (or sudo) only when something is
# missing. The kernel scripts install their own extra packages.
set -euo pipefail

packages=(
	build-essential pkg-config meson ninja-build
	libcmocka-dev
	libgpiod-dev gpiod
	clang-14 libclang-rt-14-dev
	strace python3 python3-jsonschema libxml2-utils
	systemd man-db
	busybox-static
)

missing=()
for p in "${packages[@]}"; do
	dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" ||
		missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "setup: installing ${missing[*]}"
sudo=""
[ "$(id -u)" -eq 0 ] || sudo=sudo
$sudo apt-get update -q
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
