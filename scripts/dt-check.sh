#!/bin/bash
# shellcheck disable=SC2016 # sed/awk programs, not shell expansions
# SPDX-License-Identifier: GPL-2.0
#
# dt-check.sh [7.2|6.1]
#
# Validates the devicetree binding(s) in dt-bindings/ the way the kernel's
# "make dt_binding_check" does, without a kernel build:
#
#   - a work tree in $AS9888_CACHE/dt-check/ gets the base schemas our
#     binding refers to (vendor-prefixes.yaml, spi/*-peripheral-props.yaml and
#     whatever they $ref) and the dt-bindings headers the examples #include,
#     all copied from the kernel tree prepared by kernel-trees.sh (default
#     7.2); our vendor-prefixes patch is applied to the copied
#     vendor-prefixes.yaml;
#   - yamllint with the kernel's .yamllint rules;
#   - dt-doc-validate on our binding(s) and the patched vendor-prefixes.yaml;
#   - dt-mk-schema -> processed-schema.json;
#   - per binding: dt-extract-example, cpp, dtc (the kernel's flags for
#     binding examples), dt-validate -m against processed-schema.json.
#
# The dt-schema tools exit 0 even when they print errors, so ANY output of
# any step counts as a failure. Tools: Debian's dt-schema, device-tree-compiler
# and yamllint; if Debian's dt-schema cannot process the tree's base schemas,
# PyPI's dtschema is installed into a venv in the cache and used instead.
#
# Exit status: 0 clean, 1 errors/warnings, 2 usage.
#
# Timings (2 cores, shared): warm 4-7 s; cold 33 s (apt-get install of
# dt-schema, device-tree-compiler, yamllint), plus kernel-trees.sh if no tree
# is prepared. PyPI path: 28 s the first time (venv + pip), then about 13 s.
# Environment: AS9888_CACHE; AS9888_DT_DIR (default: the repository's
# dt-bindings/, handy for checking a deliberately broken copy);
# AS9888_DT_PYPI=1 uses PyPI's dtschema even when Debian's works.
set -euo pipefail

# shellcheck source-path=SCRIPTDIR source=kernel-common.sh
. "$(dirname "$0")/kernel-common.sh"

K="${1:-7.2}"
case "$K" in
6.1 | 7.2) ;;
*)
	echo "usage: $0 [7.2|6.1]" >&2
	exit 2
	;;
esac

T_START=$(now)
cache_lock dt-check
DT_DIR="$(cd "${AS9888_DT_DIR:-$AS9888_REPO/dt-bindings}" && pwd)"
KSRC=$(ksrc "$K")
WORK="$AS9888_CACHE/dt-check"
mkdir -p "$LOG_DIR"

ensure_pkgs dt-schema device-tree-compiler yamllint cpp patch python3-venv

if [ ! -f "$KSRC/Documentation/devicetree/bindings/vendor-prefixes.yaml" ]; then
	log "kernel tree $K not prepared yet: running kernel-trees.sh $K"
	"$(dirname "$0")/kernel-trees.sh" "$K" >"$LOG_DIR/dt-check-trees.log" 2>&1 ||
		die "kernel-trees.sh $K failed, see $LOG_DIR/dt-check-trees.log"
fi
KB="$KSRC/Documentation/devicetree/bindings"

# Our schema files (relative to $DT_DIR) and the vendor-prefixes patch.
mapfile -t OURS < <(cd "$DT_DIR" && find . -name '*.yaml' ! -name 'vendor-prefixes*.yaml' | sed 's|^\./||' | sort)
mapfile -t PATCHES < <(find "$DT_DIR" -maxdepth 1 -name '*vendor-prefixes*.patch' | sort)
[ "${#OURS[@]}" -gt 0 ] || die "no binding (*.yaml) under $DT_DIR"

ERRORS=0
report() {
	# report STEP FILE: print FILE's content as errors of STEP, count lines
	local step="$1" f="$2" n
	n=$(grep -c . "$f" || true)
	if [ "$n" -gt 0 ]; then
		printf '[%s] %s: %d line(s) of errors/warnings:\n' "$SCRIPT_NAME" "$step" "$n" >&2
		sed -e "s|$BIND/|$DT_DIR/|g" -e 's/^/    /' "$f" >&2
		ERRORS=$((ERRORS + n))
	else
		log "$step: clean"
	fi
}

# --- work tree ---------------------------------------------------------------
rm -rf "$WORK"
TREE="$WORK/tree"
BIND="$TREE/Documentation/devicetree/bindings"
INC="$WORK/include"
OUT="$WORK/out"
mkdir -p "$BIND" "$INC" "$OUT"

copy_schema() { # path relative to the bindings dir
	local rel="$1"
	[ -f "$BIND/$rel" ] && return 0
	[ -f "$KB/$rel" ] || return 0 # provided by dt-schema itself
	mkdir -p "$(dirname "$BIND/$rel")"
	cp "$KB/$rel" "$BIND/$rel"
	# Follow the schema's own references: relative ones and /schemas/... ones
	# that live in the kernel tree rather than in dt-schema.
	local ref dir
	dir=$(dirname "$rel")
	while IFS= read -r ref; do
		ref=${ref%%#*}
		[ -n "$ref" ] || continue
		case "$ref" in
		http*) continue ;;
		/schemas/*) copy_schema "${ref#/schemas/}" ;;
		/*) continue ;;
		*) copy_schema "$(realpath -m --relative-to="$KB" "$KB/$dir/$ref")" ;;
		esac
	done < <(sed -n 's/^[[:space:]-]*\$ref:[[:space:]]*["'\'']\{0,1\}\([^"'\''[:space:]]*\).*/\1/p' "$KB/$rel")
}

# Base schemas: the vendor prefix list, the SPI peripheral properties our
# binding references (and the controller-specific ones it references), and
# spi-controller.yaml, which gives spi-cpha/spi-cpol their types.
copy_schema vendor-prefixes.yaml
copy_schema spi/spi-controller.yaml
for f in "$KB"/spi/*peripheral-props.yaml; do
	copy_schema "${f#"$KB/"}"
done
log "kernel $K: copied $(find "$BIND" -name '*.yaml' | wc -l) base schema files into $BIND"

# The vendor prefix patch, applied like a maintainer would (patch -p1 at the
# top of the kernel tree).
for p in "${PATCHES[@]}"; do
	if ! patch -p1 -d "$TREE" --forward --no-backup-if-mismatch -r - <"$p" >"$OUT/patch.log" 2>&1; then
		cat "$OUT/patch.log" >&2
		die "$(basename "$p") does not apply to the $K tree's vendor-prefixes.yaml"
	fi
	log "applied $(basename "$p") ($(grep -Eo 'with fuzz [0-9]+|offset -?[0-9]+ lines?' "$OUT/patch.log" | head -n1 || echo exact))"
done
if [ "${#PATCHES[@]}" -eq 0 ]; then
	warn "no *vendor-prefixes*.patch in $DT_DIR"
	ERRORS=$((ERRORS + 1))
fi

# --- tools ----------------------------------------------------------------------
DT_BIN=/usr/bin
dt_tools_ok() { # can this dt-schema process the tree's base schemas (ours not copied yet)?
	"$DT_BIN/dt-mk-schema" -j "$BIND" >"$OUT/probe.json" 2>"$OUT/probe.err" &&
		[ -s "$OUT/probe.json" ] && [ ! -s "$OUT/probe.err" ]
}
if [ "${AS9888_DT_PYPI:-0}" = 1 ]; then
	log "AS9888_DT_PYPI=1: using PyPI's dtschema instead of Debian's dt-schema"
	DT_USE_PYPI=1
elif ! dt_tools_ok; then
	warn "Debian's dt-schema ($("$DT_BIN/dt-doc-validate" --version 2>/dev/null || echo '?')) cannot process the $K base schemas:"
	sed 's/^/    /' "$OUT/probe.err" >&2
	DT_USE_PYPI=1
fi
if [ "${DT_USE_PYPI:-0}" = 1 ]; then
	VENV="$AS9888_CACHE/dtschema-venv"
	dtschema_venv "$VENV"
	DT_BIN="$VENV/bin"
	dt_tools_ok || {
		sed 's/^/    /' "$OUT/probe.err" >&2
		die "PyPI dtschema cannot process the $K base schemas either"
	}
fi
log "dt-schema $("$DT_BIN/dt-doc-validate" --version) from $DT_BIN, $(dtc --version)"

# --- checks ---------------------------------------------------------------------
# Our binding(s), and whatever kernel schemas they reference.
for f in "${OURS[@]}"; do
	mkdir -p "$(dirname "$BIND/$f")"
	cp "$DT_DIR/$f" "$BIND/$f"
	while IFS= read -r ref; do
		ref=${ref%%#*}
		case "$ref" in /schemas/*) copy_schema "${ref#/schemas/}" ;; esac
	done < <(sed -n 's/^[[:space:]-]*\$ref:[[:space:]]*\([^[:space:]]*\).*/\1/p' "$DT_DIR/$f")
done

# Every vendor prefix our compatibles use must be in vendor-prefixes.yaml,
# in its alphabetical place.
: >"$OUT/prefix.err"
sed -n 's/^  "\^\([^"]*\),\.\*":$/\1/p' "$BIND/vendor-prefixes.yaml" >"$OUT/prefixes"
while IFS= read -r vendor; do
	if ! grep -qxF "$vendor" "$OUT/prefixes"; then
		echo "vendor prefix '$vendor' is not in vendor-prefixes.yaml" >>"$OUT/prefix.err"
		continue
	fi
	LC_ALL=C awk -v v="$vendor" '
		$0 == v { if (NR > 1 && prev >= v) bad = prev; getline next_; if (next_ != "" && next_ <= v) bad = next_; exit }
		{ prev = $0 }
		END { if (bad != "") printf "vendor prefix %s is out of alphabetical order (next to %s)\n", v, bad }
	' "$OUT/prefixes" >>"$OUT/prefix.err"
done < <(cd "$BIND" && grep -ho 'const: *[a-z0-9-]*,' "${OURS[@]}" | sed 's/const: *//; s/,$//' | sort -u)
report "vendor-prefixes" "$OUT/prefix.err"

YL_CONF="$KB/.yamllint"
(cd "$BIND" && yamllint -f parsable ${YL_CONF:+-c "$YL_CONF"} "${OURS[@]}" vendor-prefixes.yaml) >"$OUT/yamllint.out" 2>&1 || true
report "yamllint" "$OUT/yamllint.out"

(cd "$BIND" && "$DT_BIN/dt-doc-validate" -u "$BIND" "${OURS[@]}" vendor-prefixes.yaml) >"$OUT/doc-validate.out" 2>&1 || true
report "dt-doc-validate" "$OUT/doc-validate.out"

"$DT_BIN/dt-mk-schema" -j "$BIND" >"$OUT/processed-schema.json" 2>"$OUT/mk-schema.out" || true
report "dt-mk-schema" "$OUT/mk-schema.out"

# Headers an example includes, copied (recursively) from the kernel tree.
copy_headers() {
	local file="$1" h
	while IFS= read -r h; do
		[ -f "$INC/$h" ] && continue
		[ -f "$KSRC/include/$h" ] || {
			echo "$file: included header $h not found in $KSRC/include" >>"$OUT/headers.err"
			continue
		}
		mkdir -p "$(dirname "$INC/$h")"
		cp "$KSRC/include/$h" "$INC/$h"
		copy_headers "$INC/$h"
	done < <(sed -n 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*<\(dt-bindings\/[^>]*\)>.*/\1/p' "$file")
}

DTC_FLAGS=(-Wno-avoid_unnecessary_addr_size -Wno-graph_child_address
	-Wno-interrupt_provider -Wno-unique_unit_address
	-Wunique_unit_address_if_enabled)
: >"$OUT/headers.err"
for f in "${OURS[@]}"; do
	base="$OUT/${f%.yaml}"
	mkdir -p "$(dirname "$base")"
	step="example $f"
	"$DT_BIN/dt-extract-example" "$BIND/$f" >"$base.example.dts" 2>"$base.err" || true
	if ! grep -q 'example-0' "$base.example.dts"; then
		echo "no example found" >>"$base.err"
		report "$step" "$base.err"
		continue
	fi
	copy_headers "$base.example.dts"
	gcc -E -nostdinc -I"$INC" -undef -D__DTS__ -x assembler-with-cpp \
		-o "$base.example.pp.dts" "$base.example.dts" 2>>"$base.err" || true
	dtc -I dts -O dtb -b 0 "${DTC_FLAGS[@]}" -o "$base.example.dtb" \
		"$base.example.pp.dts" 2>>"$base.err" || echo "dtc failed" >>"$base.err"
	if [ -s "$base.example.dtb" ]; then
		"$DT_BIN/dt-validate" -m -u "$BIND" -p "$OUT/processed-schema.json" \
			"$base.example.dtb" >>"$base.err" 2>&1 || true
		log "$f: $(grep -c 'example-[0-9]* {' "$base.example.dts") examples compiled and validated"
	fi
	awk '!seen[$0]++' "$base.err" >"$base.err.u" && mv "$base.err.u" "$base.err"
	report "$step" "$base.err"
done
report "example headers" "$OUT/headers.err"

if [ "$ERRORS" -gt 0 ]; then
	log "dt-check $K: $ERRORS errors/warnings (work dir $WORK) in $(since "$T_START")"
	exit 1
fi
log "dt-check $K: 0 errors/warnings, ${#OURS[@]} binding(s) clean in $(since "$T_START")"
