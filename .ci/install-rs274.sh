#!/usr/bin/env bash
# Install LinuxCNC's standalone G-code interpreter `rs274` for lmdc's tests,
# without LinuxCNC's GUI dependencies, and a wrapper `rs274-run` around it.
#
# Usage:  bash .ci/install-rs274.sh [PREFIX]
#   PREFIX defaults to ${XDG_CACHE_HOME:-$HOME/.cache}/lmdc-rs274, the place
#   tests/support/rs274.rs looks when LMDC_RS274 is not set.
#   Prints the absolute path of PREFIX/bin/rs274-run on stdout (nothing else
#   goes to stdout); progress goes to stderr. Idempotent: a second run only
#   self-tests the install (~30 ms) and prints the path again.
#
#   CI:  export LMDC_RS274="$(bash .ci/install-rs274.sh)"
#
# How: Debian 12 ships rs274 in linuxcnc-uspace, whose package depends on Tk,
# GTK, Mesa, ... We only `apt-get download` that .deb (and
# libboost-python1.74.0) and extract the interpreter and its seven private
# libraries (~3 MB) into PREFIX; the few system libraries it links against
# (libpython3.11, libedit2, libtirpc3) are apt-get installed only when ldd
# says they are missing. Needs root (or passwordless sudo) only for apt-get
# update/install.
#
# Wrapper usage:  rs274-run [extra rs274 options, e.g. -i machine.ini] FILE.ngc
#                 rs274-run --selftest
#   Runs `rs274 -g -t PREFIX/share/tool.tbl ... FILE.ngc` with stdin closed,
#   a private HOME per run (rs274 mmaps $HOME/.tool.mmap; runs sharing it
#   crash with SIGBUS), and a timeout of ${RS274_TIMEOUT:-120} seconds.
#   Canonical calls go to stdout; stderr gets "executing" and, on an error,
#   the message and the offending line; exit status 1 on an interpreter error.
set -euo pipefail

PREFIX="${1:-${XDG_CACHE_HOME:-$HOME/.cache}/lmdc-rs274}"
STAMP_VERSION="lmdc-rs274 install v1"

log() { printf 'install-rs274: %s\n' "$*" >&2; }
die() {
	log "error: $*"
	exit 1
}

mkdir -p "$PREFIX"
PREFIX="$(cd "$PREFIX" && pwd)"
WRAPPER="$PREFIX/bin/rs274-run"
STAMP="$PREFIX/.installed"

installed_ok() {
	[[ -x $WRAPPER && -f $STAMP ]] &&
		[[ "$(head -n 1 "$STAMP")" == "$STAMP_VERSION" ]] &&
		"$WRAPPER" --selftest >/dev/null 2>&1
}

if installed_ok; then
	echo "$WRAPPER"
	exit 0
fi

# One installer at a time per prefix.
exec 9>"$PREFIX/.lock"
flock 9
if installed_ok; then
	echo "$WRAPPER"
	exit 0
fi

SUDO=()
if [[ $(id -u) -ne 0 ]]; then
	if command -v sudo >/dev/null 2>&1; then
		SUDO=(sudo -n env DEBIAN_FRONTEND=noninteractive)
	fi
fi
export DEBIAN_FRONTEND=noninteractive

APT_UPDATED=0
apt_update() {
	if [[ $APT_UPDATED -eq 0 ]]; then
		log "apt-get update"
		"${SUDO[@]}" apt-get update -qq >&2 || die "apt-get update failed"
		APT_UPDATED=1
	fi
}

# As root, apt-get download would try to drop to the _apt user, which cannot
# write into our private temporary directory (harmless warning); say root.
APT_DL_OPTS=(-qq)
if [[ $(id -u) -eq 0 ]]; then
	APT_DL_OPTS+=(-o APT::Sandbox::User=root)
fi

WORK="$(mktemp -d "${TMPDIR:-/tmp}/lmdc-rs274.XXXXXX")"
STAGE="$PREFIX.new.$$"
cleanup() { rm -rf "$WORK" "$STAGE"; }
trap cleanup EXIT

DEBS=(linuxcnc-uspace libboost-python1.74.0)
log "downloading ${DEBS[*]}"
if ! (cd "$WORK" && apt-get download "${APT_DL_OPTS[@]}" "${DEBS[@]}" >/dev/null 2>&1); then
	# No or stale package lists (e.g. a fresh machine): refresh and retry.
	apt_update
	(cd "$WORK" && apt-get download "${APT_DL_OPTS[@]}" "${DEBS[@]}" >&2) ||
		die "apt-get download ${DEBS[*]} failed"
fi

LCNC_DEB="$(echo "$WORK"/linuxcnc-uspace_*.deb)"
BOOST_DEB="$(echo "$WORK"/libboost-python1.74.0_*.deb)"
[[ -f $LCNC_DEB && -f $BOOST_DEB ]] || die "downloaded .deb files not found in $WORK"

log "extracting rs274 from $(basename "$LCNC_DEB")"
mkdir -p "$WORK/x" "$STAGE/bin" "$STAGE/libexec" "$STAGE/lib" "$STAGE/share"
dpkg-deb --fsys-tarfile "$LCNC_DEB" |
	tar -x -C "$WORK/x" --wildcards \
		'./usr/bin/rs274' './usr/lib/lib*.so*' './usr/share/doc/linuxcnc-uspace/copyright'
dpkg-deb --fsys-tarfile "$BOOST_DEB" |
	tar -x -C "$WORK/x" --wildcards './usr/lib/x86_64-linux-gnu/libboost_python*.so*'
cp -a "$WORK/x/usr/bin/rs274" "$STAGE/libexec/rs274"
cp -a "$WORK"/x/usr/lib/lib*.so* "$WORK"/x/usr/lib/x86_64-linux-gnu/libboost_python*.so* "$STAGE/lib/"
cp -a "$WORK/x/usr/share/doc/linuxcnc-uspace/copyright" "$STAGE/share/linuxcnc-copyright"

# System libraries rs274 links against that this machine lacks.
missing_libs() {
	LD_LIBRARY_PATH="$STAGE/lib" ldd "$STAGE/libexec/rs274" |
		awk '/=> not found/ {print $1}' | sort -u
}
pkg_for() {
	case "$1" in
	libpython3.11.so*) echo libpython3.11 ;;
	libedit.so*) echo libedit2 ;;
	libtirpc.so*) echo libtirpc3 ;;
	libstdc++.so*) echo libstdc++6 ;;
	libgcc_s.so*) echo libgcc-s1 ;;
	libz.so*) echo zlib1g ;;
	libexpat.so*) echo libexpat1 ;;
	libbsd.so*) echo libbsd0 ;;
	libtinfo.so*) echo libtinfo6 ;;
	libgssapi_krb5.so*) echo libgssapi-krb5-2 ;;
	libboost_python*) echo libboost-python1.74.0 ;;
	*) return 1 ;;
	esac
}
mapfile -t MISSING < <(missing_libs)
if [[ ${#MISSING[@]} -gt 0 ]]; then
	PKGS=()
	for lib in "${MISSING[@]}"; do
		pkg="$(pkg_for "$lib")" || die "no known Debian package for missing library $lib"
		PKGS+=("$pkg")
	done
	mapfile -t PKGS < <(printf '%s\n' "${PKGS[@]}" | sort -u)
	if [[ $(id -u) -ne 0 && ${#SUDO[@]} -eq 0 ]]; then
		die "missing system packages ${PKGS[*]} and not root (no sudo): apt-get install ${PKGS[*]}"
	fi
	log "apt-get install ${PKGS[*]} (missing: ${MISSING[*]})"
	apt_install() {
		"${SUDO[@]}" apt-get install -y -qq --no-install-recommends "${PKGS[@]}" \
			>"$WORK/apt-install.log" 2>&1
	}
	if ! apt_install; then
		apt_update
		apt_install || {
			cat "$WORK/apt-install.log" >&2
			die "apt-get install ${PKGS[*]} failed"
		}
	fi
	mapfile -t MISSING < <(missing_libs)
	[[ ${#MISSING[@]} -eq 0 ]] || die "still missing after install: ${MISSING[*]}"
fi

# A tool table is mandatory (without -t, rs274 exits 1 printing nothing).
# T1 is the deposition head with zero offsets, so `T1 M6` / `G43 H1` work.
cat >"$STAGE/share/tool.tbl" <<'EOF'
T1 P1 X0 Y0 Z0 D0 ;lmdc deposition head (zero offsets)
EOF

cat >"$STAGE/bin/rs274-run" <<'WRAPPER_EOF'
#!/usr/bin/env bash
# rs274-run: run LinuxCNC's standalone interpreter rs274 on a G-code file and
# print its canonical machining calls (installed by lmdc's .ci/install-rs274.sh).
# usage: rs274-run [extra rs274 options, e.g. -i machine.ini] FILE.ngc
#        rs274-run --selftest
# Don't pass -g (it is a toggle and is already on). Exit status: rs274's
# (0 ok, 1 interpreter error, message on stderr), 124 on timeout
# (RS274_TIMEOUT seconds, default 120), 2 on usage errors.
set -uo pipefail
root="$(cd -- "$(dirname -- "$(readlink -f -- "${BASH_SOURCE[0]}")")/.." && pwd)"
if [[ $# -lt 1 || $1 == -h || $1 == --help ]]; then
	sed -n '2,8p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//' >&2
	exit 2
fi
tmp="$(mktemp -d "${TMPDIR:-/tmp}/rs274-run.XXXXXX")" || exit 2
trap 'rm -rf "$tmp"' EXIT
if [[ $1 == --selftest ]]; then
	printf 'G21 G90 G94\nG0 X1 Y2 Z3 A4 C5\nG1 X6 F100\nM2\n' >"$tmp/selftest.ngc"
	set -- "$tmp/selftest.ngc"
	selftest=1
else
	selftest=0
fi
# rs274 creates and mmaps $HOME/.tool.mmap (or /tmp/.tool.mmap without HOME);
# concurrent runs sharing that file die with SIGBUS, so each run gets its own.
mkdir "$tmp/home"
export HOME="$tmp/home"
export LD_LIBRARY_PATH="$root/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
unset PYTHONHOME PYTHONPATH PYTHONSTARTUP
timeout_s="${RS274_TIMEOUT:-120}"
if [[ $selftest -eq 1 ]]; then
	out="$(timeout -k 5 "$timeout_s" "$root/libexec/rs274" -g -t "$root/share/tool.tbl" "$@" \
		</dev/null 2>"$tmp/stderr")"
	rc=$?
	if [[ $rc -eq 0 && $out == *"STRAIGHT_FEED(6.0000, 2.0000, 3.0000, 4.0000, 0.0000, 5.0000)"* ]]; then
		echo "rs274-run: selftest ok"
		exit 0
	fi
	printf '%s\n' "$out"
	cat "$tmp/stderr" >&2
	echo "rs274-run: selftest FAILED (rs274 exit $rc)" >&2
	exit 1
fi
timeout -k 5 "$timeout_s" "$root/libexec/rs274" -g -t "$root/share/tool.tbl" "$@" </dev/null
rc=$?
if [[ $rc -eq 124 ]]; then
	echo "rs274-run: rs274 timed out after ${timeout_s}s" >&2
fi
exit $rc
WRAPPER_EOF
chmod 755 "$STAGE/bin/rs274-run"

"$STAGE/bin/rs274-run" --selftest >&2 || die "self-test of the fresh install failed"

{
	echo "$STAMP_VERSION"
	echo "deb: $(basename "$LCNC_DEB")"
	echo "deb: $(basename "$BOOST_DEB")"
} >"$STAGE/.installed"

# Swap the new tree in (keep the lock file, drop everything else).
find "$PREFIX" -mindepth 1 -maxdepth 1 ! -name .lock -exec rm -rf {} +
mv "$STAGE"/bin "$STAGE"/libexec "$STAGE"/lib "$STAGE"/share "$STAGE"/.installed "$PREFIX"/
log "installed rs274 into $PREFIX"
echo "$WRAPPER"
